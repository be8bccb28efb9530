// The PETSc options of the command line (the words with one dash that the
// commands do not take): PETSc started with them, those it cannot take
// refused before any run, and those nothing read reported after it.
#pragma once

#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace pushout::driver
{
/// The names of the PETSc options on the command line ("-snes_monitor"):
/// the words that start with a dash and a letter (a negative number is a
/// value).
std::set<std::string> option_names(const std::vector<std::string>& words);

/// Starts PETSc (and MPI) with `options`; false after saying why.
bool start_petsc(char* program, std::vector<std::string>& options);

/// The user's PETSc options as the default solver's objects read them (a
/// SNES, its KSP and PC): PETSc's message where one cannot take its value
/// (-ksp_type bogus, -snes_max_it abc), else "". Found before the run, it
/// is a usage error (exit 2), not a run that fails in its first solve. The
/// same on every process (each reads the same options).
std::string petsc_option_error();

/// The exit code after the user's PETSc options (`given`) were checked: a
/// PETSc option nothing read is most likely a typo of one (-snes_monitr):
/// an error (exit 2) after a run that succeeded, unless `allow_unused`; a
/// warning otherwise. `summary` (a run's summary.json; empty for sweep and
/// fit) then lists them too. Collective.
int check_petsc_options(const std::set<std::string>& given, bool allow_unused, int rc,
                        const std::filesystem::path& summary);
} // namespace pushout::driver

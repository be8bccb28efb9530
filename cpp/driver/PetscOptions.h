// The PETSc options of the command line (the words with one dash that the
// commands do not take): PETSc started with them, those it cannot take
// refused before any run, and those nothing read reported after it.
#pragma once

#include <filesystem>
#include <mpi.h>
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
/// SNES, its KSP and PC; a fit's TAO, of type TAOBNLS): PETSc's message
/// where one cannot take its value (-ksp_type bogus, -snes_max_it abc,
/// -tao_ls_type mt), or a solver type other than pushout's (-snes_type
/// ksponly, -tao_type lmvm), else "". Found before any command runs, it is a usage
/// error (exit 2), not a run that fails in its first solve, nor a fit
/// refused after its runs. The same on every process (each reads the same
/// options).
std::string petsc_option_error();

/// The user's PETSc options (`given`, from the command line) that nothing
/// read so far, alike on every process of `comm`: an option read on any of
/// them counts as read. The default solver path's options (SNES, KSP, PC,
/// MUMPS, TAO and this program's own) count as read even where no solver
/// of that kind was made: petsc_option_error() read the first four and
/// TAO's before the command ran. Defaults the program sets itself
/// (solver/NewtonSolver.cpp) are not the user's: a run with -pc_type gamg
/// never reads its -pc_factor_mat_solver_type. Collective on `comm`.
std::vector<std::string> unused_petsc_options(const std::set<std::string>& given, MPI_Comm comm);

/// After the first runs of a sweep or a fit (`first_runs` names them): a
/// warning, said where `say`, of the user's PETSc options (`given`) that
/// their solvers did not read on `comm`'s processes, most likely typos
/// (-ksp_rtoll): a long `command` need not run to its end, where
/// check_petsc_options finds them, to learn of them. Nothing unless
/// `allow_unused` is false. Collective on `comm`.
void warn_unread_options(const std::set<std::string>& given, bool allow_unused, MPI_Comm comm,
                         bool say, const std::string& first_runs, const std::string& command);

/// The exit code after the user's PETSc options (`given`) were checked: a
/// PETSc option nothing read is most likely a typo of one (-snes_monitr):
/// an error (exit 2) after a run that succeeded, unless `allow_unused`; a
/// warning otherwise. `summary` (a run's summary.json; empty for sweep and
/// fit) then lists them too. Collective.
int check_petsc_options(const std::set<std::string>& given, bool allow_unused, int rc,
                        const std::filesystem::path& summary);
} // namespace pushout::driver

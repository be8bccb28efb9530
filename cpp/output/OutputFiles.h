// How every output reaches the disk, and the folder's ownership by a run.
//
// A whole file (summary.json, scene.toml, sweep.csv, fit.json, fit.csv) is
// written to a temporary name in its folder, checked after it is closed and
// then renamed over the old one, so it is either whole or absent: a full
// disk is an error ("cannot write FILE (disk full?)"), never a cut file.
//
// The output folder (--out) belongs to one run at a time: claim() takes a
// lock held until the process ends (`DIR/.pushout.lock`, flock(2)), then
// removes what an earlier run of pushout left there (the files of the
// Outputs table, by name: a file of another name is never touched, nor any
// file of a folder no run of pushout used), so that no output of an earlier
// run can be read as this run's.
#pragma once

#include <cerrno>
#include <filesystem>
#include <mpi.h>
#include <stdexcept>
#include <string>
#include <vector>

namespace pushout::output
{
/// The output folder cannot be used: another run holds it, or an input
/// would be overwritten. A usage error (exit code 2).
class FolderError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// The message of an output that could not be written, for the errno of
/// the call that failed: a full disk (ENOSPC, EDQUOT: "disk full?", also
/// where the cause is not known) or the cause's own name.
std::string cannot_write(const std::filesystem::path& file, int error = ENOSPC);

/// Writes `text` as the whole of `file` (through a temporary file in the
/// same folder, renamed when complete); throws std::runtime_error
/// (cannot_write) if it could not be written whole.
void write_file(const std::filesystem::path& file, const std::string& text);

/// Takes the output folder `dir` for this process (one process of a run:
/// rank 0): creates it, refuses it if one of `inputs` is a file pushout
/// writes there, takes its lock (held until the process ends) and, if a run
/// of pushout used it before (its lock file is there), removes that run's
/// outputs. Throws FolderError (in use, cannot be created or written, an
/// input among the outputs).
void claim(const std::filesystem::path& dir, const std::vector<std::filesystem::path>& inputs);

/// Removes the outputs of a run of pushout from `dir`, and `dir` if nothing
/// else is left in it.
void remove_outputs(const std::filesystem::path& dir);

/// The command's run id (random, hex): in summary.json, tells one run's
/// outputs from another's.
const std::string& run_id();

/// Gives every process of `comm` rank 0's run id (collective; once, at the
/// start, so that every summary of a sweep or fit carries the same one).
void share_run_id(MPI_Comm comm);
} // namespace pushout::output

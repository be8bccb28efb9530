// What the commands that make many runs (pushout sweep, fit) share: their
// options and the process groups that run their cases side by side.
#pragma once

#include "../scene/Scene.h"
#include <filesystem>
#include <functional>
#include <mpi.h>
#include <set>
#include <string>
#include <vector>

namespace pushout::study
{
/// What the commands that make many runs (pushout sweep, fit) share.
struct ManyRunsOptions
{
  std::filesystem::path scene_file;
  /// The scene file's text, read once at the command's start
  /// (read_scene_text): every run runs the scene its plan checked, however
  /// the file is edited meanwhile.
  std::string scene_text;
  std::vector<std::string> sets; ///< --set overrides of every run
  std::filesystem::path out;     ///< the command's folder
  std::filesystem::path mesh_cache;
  int ranks_per_case = 1; ///< processes per run (--ranks-per-case)
  bool quiet = false;
  bool force = false;
  std::set<std::string> petsc_options; ///< the PETSc options given (their names)
  bool allow_unused = false;           ///< --allow-unused-petsc-options
};

/// The text `read` returns on the first process of MPI_COMM_WORLD, on all
/// of them (one text, even where its file is saved between their reads).
/// Throws SceneError, agreed. Collective on MPI_COMM_WORLD.
std::string read_on_first(const std::function<std::string()>& read);

/// Reads opt.scene_file into opt.scene_text (read_on_first).
void read_scene_text(ManyRunsOptions& opt);

/// The scene of a run of many: opt.scene_text with the overrides `sets`.
/// Throws SceneError.
Scene scene_of(const ManyRunsOptions& opt, const std::vector<std::string>& sets);

/// The processes of MPI_COMM_WORLD in groups of ranks_per_case
/// (MPI_Comm_split), each running its runs on its own communicator, which
/// the error agreements use (mpi::set_run_processes) until close().
/// Collective on MPI_COMM_WORLD.
class ProcessGroups
{
public:
  /// Throws SceneError unless `ranks_per_case` divides the processes.
  static void check(int ranks_per_case);
  /// A new communicator of this process's group (ranks_per_case processes of
  /// MPI_COMM_WORLD in rank order), for the caller to free; no agreement
  /// moves to it. Collective on MPI_COMM_WORLD.
  static MPI_Comm split(int ranks_per_case);
  /// Processes on this machine of the other groups that run cases beside
  /// `group`'s, when at most `runs_at_once` cases run at a time (a sweep's
  /// cases; a fit's batch, the base point and one per free value): a group
  /// with none to run is idle. Collective on
  /// MPI_COMM_WORLD.
  static int others_here(MPI_Comm group, int runs_at_once);
  explicit ProcessGroups(int ranks_per_case);
  ~ProcessGroups() { close(); }
  ProcessGroups(const ProcessGroups&) = delete;
  ProcessGroups& operator=(const ProcessGroups&) = delete;

  MPI_Comm comm() const { return _comm; }
  int count() const { return _count; }
  int index() const { return _index; }
  /// others_here(comm(), runs_at_once), from the counts made with the groups.
  int others_here(int runs_at_once) const;
  /// Whether this process is its group's first.
  bool leader() const { return _leader; }
  /// Agreements on MPI_COMM_WORLD again; the groups' communicator freed.
  void close();

private:
  MPI_Comm _comm = MPI_COMM_NULL;
  int _count = 1, _index = 0;
  int _here = 1, _group_here = 1; ///< this machine's processes: all, this group's
  bool _leader = true;
};

} // namespace pushout::study

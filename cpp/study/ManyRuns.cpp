#include "ManyRuns.h"
#include "../common/mpi_errors.h"
#include "../common/mpi_gather.h"
#include "../record/ResourceGuard.h"
#include "../scene/SceneError.h"
#include <algorithm>

namespace pushout::study
{
std::string read_on_first(const std::function<std::string()>& read)
{
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  std::string text;
  mpi::collectively<SceneError>(MPI_COMM_WORLD,
                                [&]
                                {
                                  if (rank == 0)
                                    text = read();
                                });
  return mpi::broadcast_from_first(std::move(text), MPI_COMM_WORLD);
}

void read_scene_text(ManyRunsOptions& opt)
{
  opt.scene_text = read_on_first([&] { return Scene::read(opt.scene_file); });
}

Scene scene_of(const ManyRunsOptions& opt, const std::vector<std::string>& sets)
{
  return Scene::parse(opt.scene_text, parse_overrides(sets), opt.scene_file.string());
}

void ProcessGroups::check(int ranks_per_case)
{
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (ranks_per_case < 1 || size % ranks_per_case != 0)
    throw SceneError("--ranks-per-case " + std::to_string(ranks_per_case) + " must divide the " +
                     std::to_string(size) + " processes");
}

MPI_Comm ProcessGroups::split(int ranks_per_case)
{
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm comm = MPI_COMM_NULL;
  MPI_Comm_split(MPI_COMM_WORLD, rank / ranks_per_case, rank, &comm);
  return comm;
}

namespace
{
/// Of `here` processes on this machine, `group_here` in the group: the others
/// that run, at most runs_at_once - 1 groups of as many.
int others_running(int here, int group_here, int runs_at_once)
{
  return std::min(here - group_here, std::max(0, runs_at_once - 1) * group_here);
}
} // namespace

int ProcessGroups::others_here(MPI_Comm group, int runs_at_once)
{
  const int here = record::processes_on_this_machine(MPI_COMM_WORLD);
  return others_running(here, record::processes_on_this_machine(group), runs_at_once);
}

int ProcessGroups::others_here(int runs_at_once) const
{
  return others_running(_here, _group_here, runs_at_once);
}

ProcessGroups::ProcessGroups(int ranks_per_case)
{
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  _count = size / ranks_per_case;
  _index = rank / ranks_per_case;
  _comm = split(ranks_per_case);
  int group_rank = 0;
  MPI_Comm_rank(_comm, &group_rank);
  _leader = group_rank == 0;
  _here = record::processes_on_this_machine(MPI_COMM_WORLD);
  _group_here = record::processes_on_this_machine(_comm);
  mpi::set_run_processes(_comm);
}

void ProcessGroups::close()
{
  if (_comm == MPI_COMM_NULL)
    return;
  mpi::set_run_processes(MPI_COMM_WORLD);
  MPI_Comm_free(&_comm);
}
} // namespace pushout::study

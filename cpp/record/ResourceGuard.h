// The size guard: before meshing, the run's size and peak memory are
// estimated from the mesh keys, and a run that cannot fit in the memory of
// this machine is refused with what to change (--force runs it anyway).
//
// Peak resident memory of one process [MB], measured on this stack and
// fitted (bench/memory_estimate.py keeps the table of estimate against
// measurement; docs/performance.md says how the law was found):
//
//   solve   = base + mesh arrays + s c_p n sqrt(F) / P^0.6        (whole model, LU)
//           = base + mesh arrays + 1.3 c_p n sqrt(F) + 32 n_I^2 B   (condensed)
//           = base + mesh arrays + 4.2 kB n / P^0.5     (iterative: -pc_type gamg ...)
//             + 3 kB per cracking point / P             (cracks anywhere, [cracking])
//   meshing = base + 0.35 kB per generated hexahedron (gmsh, rank 0)
//
// n the dofs, F the dofs of the largest cut through the specimen (the
// nested-dissection separator: the radial-by-thickness section, twice for
// the closed ring of the full model), P the processes, n_I the interface
// dofs; MUMPS's LU fill grows like n sqrt(F) on these slices. c_1 = 4.2e-4
// MB, c_2 = 5.5e-4 MB (triquadratic: denser rows); base 110 MB; s = 0.6 for
// the LU in single precision under GMRES (solver.precision = "mixed",
// LoadStepSolver::single_precision_lu), 1 in double. The cracking points are
// 8 per concrete hexahedron (every one: an upper bound where
// cracking.radius keeps some linear); with them the bulk is never
// condensed.
#pragma once

#include "../mesh/size.h"
#include "../scene/Scene.h"
#include <mpi.h>
#include <stdexcept>
#include <string>

namespace pushout::record
{
struct ResourceEstimate
{
  mesh::MeshSize size;
  bool condensed = false; ///< Newton on the condensed interface system
  bool direct = true;     ///< the Newton systems are factored (LU)
  int processes = 1;      ///< processes of the run
  int processes_here = 1; ///< of them, on one machine (the most on any)
  /// Processes of the same command's other groups on this machine (pushout
  /// sweep and fit run cases at once), each counted at this run's solving peak (solve_mb).
  int others_here = 0;
  double meshing_mb = 0;   ///< rank 0's peak while gmsh meshes [MB]
  double solve_mb = 0;     ///< one process's peak while solving [MB]
  double machine_mb = 0;   ///< all processes on one machine, at their peak (the most on any) [MB]
  double available_mb = 0; ///< memory available on one machine (the least on any) [MB]
  /// The least address space a process may still map (ulimit -v) [MB]; -1:
  /// no limit. Each process's peak must fit in it.
  double address_space_mb = -1;

  /// The larger of the meshing and solving peaks of one process [MB]
  /// (summary.json: estimated_memory_mb).
  double peak_mb() const;
  /// Dofs, joint elements and the solver path, in words.
  std::string describe() const;
  /// The memory this machine needs, in words ("about 1.20 GB of memory").
  std::string memory() const;
};

/// The estimate for the mesh `in` describes, solved as `solver` asks, on
/// `comm`'s processes, beside `others_here` processes of other cases on this
/// machine (ResourceEstimate::others_here). Collective.
ResourceEstimate estimate_resources(const mesh::MeshInput& in, const SolverPart& solver,
                                    const CrackingPart& cracking, MPI_Comm comm,
                                    int others_here = 0);

/// A run refused by the size guard (exit 2, like a bad scene).
class TooLarge : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// Throws TooLarge, on every process, unless the run fits in the memory
/// available here (or `force`).
void check_fits(const ResourceEstimate& estimate, const mesh::MeshInput& in, bool force);

/// The processes of `comm` on this machine (MPI_COMM_TYPE_SHARED).
/// Collective on `comm`.
int processes_on_this_machine(MPI_Comm comm);

/// Memory available to new allocations on this machine [MB]: MemAvailable
/// of /proc/meminfo, or less under a cgroup memory limit.
double available_memory_mb();

/// What a limit of this process's address space (RLIMIT_AS, ulimit -v)
/// leaves beyond what it maps already [MB]; -1: no limit. A process's
/// estimated peak must fit in it (ResourceEstimate::address_space_mb).
double address_space_left_mb();
} // namespace pushout::record

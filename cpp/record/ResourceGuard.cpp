#include "ResourceGuard.h"
#include "../solver/Condensation.h"
#include "../solver/LoadStepSolver.h"
#include "../solver/NewtonSolver.h"
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <sys/resource.h>

namespace pushout::record
{
namespace
{
// The fitted law of ResourceGuard.h [MB].
constexpr double base_mb = 110;                    // libraries, MPI, PETSc
constexpr double lu_mb_degree1 = 4.2e-4;           // c_1: per dof and sqrt(separator dof)
constexpr double lu_mb_degree2 = 5.5e-4;           // c_2
constexpr double condensed_lu_factor = 1.3;        // the interface ordered last
constexpr double dense_bytes_per_entry = 32;       // Schur complement, its LU, Z and C
constexpr double gmsh_mb_per_cell = 0.35e-3;       // gmsh's mesh and its reading
constexpr double mesh_arrays_mb_per_cell = 0.1e-3; // MeshData on every process
constexpr double lu_parallel_exponent = 0.6;       // MUMPS's share per process: P^-0.6
constexpr double iterative_mb_per_dof = 4.2e-3;    // matrices, Krylov basis, AMG levels
constexpr double iterative_parallel_exponent = 0.5;
constexpr double single_lu_share = 0.6;          // s: the LU in single precision
constexpr double cracking_mb_per_point = 3.0e-3; // a cracking point's state, maps and matrices
constexpr double cracking_points_per_cell = 8;   // forms/cracking.py: 2 x 2 x 2

/// Dofs of the largest cut through the specimen (ResourceGuard.h: F).
double separator_dofs(const mesh::MeshInput& in, const mesh::MeshSize& size)
{
  if (!in.pushout)
    return 1;
  const mesh::SliceDivisions d = mesh::slice_divisions(in);
  const std::int64_t p = in.mesh.degree;
  const double section =
      3.0 * double(p * (d.steel + d.ring + d.graded) + 2) * double(p * d.thickness + 1);
  return size.symmetry.copies() > 1 ? section : 2 * section; // an arc, or a ring cut twice
}

std::string gigabytes(double mb)
{
  std::ostringstream s;
  s << std::fixed << std::setprecision(mb < 10240 ? 2 : 1) << mb / 1024 << " GB";
  return s.str();
}

/// The value [kB] of the line "`key` value kB" of a /proc file such as
/// /proc/meminfo; -1 where there is none.
double proc_kb(const char* file, const std::string& key)
{
  std::ifstream in(file);
  for (std::string name; in >> name;)
  {
    if (name == key)
    {
      double kb = -1;
      in >> kb;
      return kb;
    }
    in.ignore(256, '\n');
  }
  return -1;
}
} // namespace

int processes_on_this_machine(MPI_Comm comm)
{
  MPI_Comm local;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &local);
  int size = 1;
  MPI_Comm_size(local, &size);
  MPI_Comm_free(&local);
  return size;
}

double available_memory_mb()
{
  const double kb = proc_kb("/proc/meminfo", "MemAvailable:");
  double available = kb < 0 ? -1 : kb / 1024;
  // A cgroup (v2) limit, as in containers and batch jobs.
  std::ifstream max_file("/sys/fs/cgroup/memory.max"),
      current_file("/sys/fs/cgroup/memory.current");
  std::string max;
  double current = 0;
  if (max_file >> max && max != "max" && current_file >> current)
  {
    const double left = (std::stod(max) - current) / (1024.0 * 1024.0);
    if (available < 0 || left < available)
      available = left;
  }
  return available;
}

double address_space_left_mb()
{
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY)
    return -1;
  // What this process maps already (libraries, MPI's and PETSc's regions)
  // counts against the limit.
  const double vm_kb = std::max(0.0, proc_kb("/proc/self/status", "VmSize:"));
  return std::max(0.0, double(limit.rlim_cur) / (1024.0 * 1024.0) - vm_kb / 1024);
}

double ResourceEstimate::peak_mb() const
{
  return std::max(meshing_mb, solve_mb);
}

std::string ResourceEstimate::describe() const
{
  std::ostringstream s;
  s << size.dofs << " dofs, " << size.joint_elements << " joint elements"
    << (size.symmetry.copies() > 1 ? " of a " + size.symmetry.name() + " model" : std::string())
    << ", Newton on " << (condensed ? "the condensed interface" : "the whole model")
    << (condensed || direct ? "" : " (iterative)");
  return s.str();
}

std::string ResourceEstimate::memory() const
{
  std::string s = "about " + gigabytes(machine_mb) + " of memory";
  if (processes_here + others_here > 1)
    s += " (" + std::to_string(processes_here + others_here) + " processes" +
         (others_here > 0 ? ", " + std::to_string(others_here) + " of them running other cases"
                          : std::string()) +
         ")";
  return s;
}

ResourceEstimate estimate_resources(const mesh::MeshInput& in, const SolverPart& solver,
                                    const CrackingPart& cracking, MPI_Comm comm, int others_here)
{
  ResourceEstimate e;
  e.others_here = others_here;
  e.size = mesh::predict_size(in);
  MPI_Comm_size(comm, &e.processes);
  e.processes_here = processes_on_this_machine(comm);

  using Concrete = solver::NewtonSolver::Concrete;
  const Concrete concrete = solver::LoadStepSolver::concrete(cracking.embedded, cracking.implex);
  std::string why;
  e.condensed = solver::Condensation::chosen(solver.condensation, e.processes,
                                             e.size.interface_dofs, cracking.embedded, why);
  e.direct = solver::NewtonSolver::direct_factorization();
  const double n = double(e.size.dofs), P = double(e.processes);
  const double c = in.mesh.degree == 2 ? lu_mb_degree2 : lu_mb_degree1;
  const double lu = c * n * std::sqrt(separator_dofs(in, e.size));
  const double n_i = double(e.size.interface_dofs);
  double solver_mb = iterative_mb_per_dof * n / std::pow(P, iterative_parallel_exponent);
  if (e.condensed)
    solver_mb = condensed_lu_factor * lu + dense_bytes_per_entry * n_i * n_i / 1e6;
  else if (e.direct)
    solver_mb =
        (solver::LoadStepSolver::single_precision_lu(solver, concrete) ? single_lu_share : 1.0) *
        lu / std::pow(P, lu_parallel_exponent);
  // Every concrete point's crack band, an upper bound where cracking.radius
  // keeps some of them linear; shared out over the processes.
  if (concrete != Concrete::linear)
    solver_mb +=
        cracking_mb_per_point * cracking_points_per_cell * double(e.size.concrete_cells) / P;
  e.solve_mb = base_mb + mesh_arrays_mb_per_cell * double(e.size.cells_generated) + solver_mb;
  e.meshing_mb = base_mb + gmsh_mb_per_cell * double(e.size.cells_generated);
  // Rank 0 meshes while the others wait; then every process solves. The
  // other cases' processes here as large as this run's, whatever they do.
  const int here = e.processes_here + e.others_here;
  e.machine_mb =
      std::max(e.meshing_mb + base_mb * (e.processes_here - 1) + e.solve_mb * e.others_here,
               e.solve_mb * here);
  // Each machine judges by its own memory and processes; the tightest
  // decides, the same on every process (so check_fits' verdict is), also
  // where a run's processes sit unevenly on several machines.
  MPI_Allreduce(MPI_IN_PLACE, &e.machine_mb, 1, MPI_DOUBLE, MPI_MAX, comm);
  MPI_Allreduce(MPI_IN_PLACE, &e.processes_here, 1, MPI_INT, MPI_MAX, comm);
  e.available_mb = available_memory_mb();
  MPI_Allreduce(MPI_IN_PLACE, &e.available_mb, 1, MPI_DOUBLE, MPI_MIN, comm);
  // A limit of each process's address space (ulimit -v; a batch system's
  // per-process memory): the tightest process's.
  const double left = address_space_left_mb();
  double least = left < 0 ? std::numeric_limits<double>::infinity() : left;
  MPI_Allreduce(MPI_IN_PLACE, &least, 1, MPI_DOUBLE, MPI_MIN, comm);
  e.address_space_mb = std::isfinite(least) ? least : -1;
  return e;
}

void check_fits(const ResourceEstimate& e, const mesh::MeshInput& in, bool force)
{
  const bool machine = e.available_mb >= 0 && e.machine_mb > e.available_mb;
  const bool process = e.address_space_mb >= 0 && e.peak_mb() > e.address_space_mb;
  if (force || !(machine || process))
    return;
  std::ostringstream m;
  if (machine)
    m << "this run needs " << e.memory() << ", more than the " << gigabytes(e.available_mb)
      << " available here (" << e.describe() << ")";
  else
    m << "a process of this run needs about " << gigabytes(e.peak_mb()) << ", more than the "
      << gigabytes(e.address_space_mb) << " its address space limit (ulimit -v) leaves ("
      << e.describe() << ")";
  if (in.pushout)
    m << "; lower mesh.elements_per_quarter (" << in.mesh.elements_per_quarter
      << "), mesh.elements_through_thickness (" << in.mesh.elements_through_thickness
      << ") or mesh.steel_layers (" << in.mesh.steel_layers << ")"
      << (in.mesh.degree == 2 ? ", or use mesh.degree = 1" : std::string());
  if (machine && e.others_here > 0)
    m << "; or run fewer cases at once (a larger --ranks-per-case, or fewer processes)";
  m << "; --force runs it anyway";
  throw TooLarge(m.str());
}
} // namespace pushout::record

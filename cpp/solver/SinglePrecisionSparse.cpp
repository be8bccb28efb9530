#include "SinglePrecisionSparse.h"
#include "../common/petsc_check.h"
#include "ShellPreconditioner.h"
#include "SingleColumnBlas.h"
#include <cmath>
#include <petscmat.h>
#include <smumps_c.h>
#include <string>
#include <utility>
#include <vector>

namespace pushout::solver
{
using petsc::check;

namespace
{
// MUMPS's job codes and the entries of its control and information arrays
// used here (MUMPS 5 users' guide: ICNTL(k) is icntl[k - 1]).
constexpr MUMPS_INT job_init = -1, job_end = -2, job_analyse = 1, job_factor = 2, job_solve = 3;
constexpr int icntl_error_stream = 0, icntl_diagnostic_stream = 1, icntl_global_stream = 2,
              icntl_print_level = 3, icntl_column_permutation = 5, icntl_ordering = 6,
              icntl_workspace_percent = 13, icntl_distributed_matrix = 17;
/// ICNTL(7): the ordering given in PERM_IN; MUMPS's automatic choice.
constexpr MUMPS_INT ordering_given = 1, ordering_automatic = 7;
/// INFOG(1) of a numerically and of a structurally singular matrix.
constexpr MUMPS_INT error_singular = -10, error_structurally_singular = -6;
/// INFOG(1) of the workspace errors that a larger ICNTL(14) cures.
constexpr MUMPS_INT workspace_errors[] = {-8, -9, -11, -12, -14, -15, -17, -20};
/// How often a factorisation short of workspace is tried again, each with
/// twice the extra workspace (ICNTL(14), MUMPS's default 20 %).
constexpr int workspace_retries = 4;

struct Factors
{
  SMUMPS_STRUC_C id{};
  bool initialised = false;
  bool factored = false;
  bool distributed = false; ///< more than one process (ICNTL(18) = 3)
  /// The analysed matrix (its id and nonzero state); -1: none
  PetscInt64 matrix = -1;
  PetscObjectState pattern = -1;
  MUMPS_INT workspace_percent = 0; ///< ICNTL(14) as MUMPS set it
  /// This process's rows of the matrix: 1-based global coordinates, in
  /// the matrix's row order, and values
  std::vector<MUMPS_INT> rows, cols;
  std::vector<float> values;
  std::vector<float> rhs; ///< the whole right-hand side on the host; empty elsewhere
  /// Several processes: this process's rows' positions in a numbering that
  /// no partition changes (use_single_precision_sparse_lu), or empty; and
  /// the host's order of the rows made in it for MUMPS (PERM_IN, 1-based).
  std::vector<std::int64_t> numbering;
  std::vector<MUMPS_INT> order;
  /// More than one process: the right-hand side gathered on the first
  /// (MUMPS's host), where MUMPS takes it and leaves the solution.
  VecScatter to_host = nullptr;
  Vec on_host = nullptr;

  ~Factors()
  {
    if (initialised)
    {
      id.job = job_end;
      smumps_c(&id);
    }
    // Not checked: a destructor does not throw.
    VecScatterDestroy(&to_host);
    VecDestroy(&on_host);
  }
};

/// MUMPS's quiet settings (Factors::id, and the ordering's own analysis).
void quiet(SMUMPS_STRUC_C& id)
{
  id.icntl[icntl_error_stream] = -1;
  id.icntl[icntl_diagnostic_stream] = -1;
  id.icntl[icntl_global_stream] = -1;
  id.icntl[icntl_print_level] = 0;
}

void initialise(Factors& f, MPI_Comm comm)
{
  int processes = 1;
  MPI_Comm_size(comm, &processes);
  f.id.comm_fortran = MUMPS_INT(MPI_Comm_c2f(comm));
  f.id.par = 1; // the host (the first process) works too
  f.id.sym = 0; // unsymmetric: friction makes the Jacobian so
  f.id.job = job_init;
  smumps_c(&f.id);
  if (f.id.infog[0] < 0)
    throw std::runtime_error("MUMPS (single precision) could not start: INFOG(1) = " +
                             std::to_string(f.id.infog[0]));
  f.initialised = true;
  // Quiet: a failure is reported through the preconditioner's failed reason.
  quiet(f.id);
  f.workspace_percent = f.id.icntl[icntl_workspace_percent];
  // More than one process: each gives its own rows (ICNTL(18) = 3, the
  // distributed assembled matrix); the right-hand side and the solution
  // stay whole on the host (ICNTL(20) = ICNTL(21) = 0, MUMPS's defaults).
  f.distributed = processes > 1;
  if (f.distributed)
    f.id.icntl[icntl_distributed_matrix] = 3;
}

/// This process's rows of P for MUMPS: their values in single precision,
/// and for a new pattern their coordinates (1-based, global, in P's row
/// order). A sequential AIJ matrix is read through its row structure, a
/// parallel one row by row.
void read_rows(Factors& f, Mat P, bool new_pattern)
{
  if (!f.distributed)
  {
    PetscInt n;
    const PetscInt *ia, *ja;
    PetscBool done;
    check(MatGetRowIJ(P, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done), "MatGetRowIJ");
    if (!done)
      throw std::runtime_error("single-precision LU: the preconditioning matrix has no row "
                               "structure (a sequential AIJ matrix is needed)");
    const std::size_t nnz = std::size_t(ia[n]);
    if (new_pattern)
    {
      f.rows.resize(nnz);
      f.cols.resize(nnz);
      for (PetscInt i = 0; i < n; ++i)
        for (PetscInt k = ia[i]; k < ia[i + 1]; ++k)
        {
          f.rows[std::size_t(k)] = MUMPS_INT(i + 1);
          f.cols[std::size_t(k)] = MUMPS_INT(ja[k] + 1);
        }
    }
    check(MatRestoreRowIJ(P, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done), "MatRestoreRowIJ");
    const PetscScalar* a;
    check(MatSeqAIJGetArrayRead(P, &a), "MatSeqAIJGetArrayRead");
    f.values.resize(nnz);
    for (std::size_t k = 0; k < nnz; ++k)
      f.values[k] = float(a[k]);
    check(MatSeqAIJRestoreArrayRead(P, &a), "MatSeqAIJRestoreArrayRead");
    return;
  }
  PetscInt first, end;
  check(MatGetOwnershipRange(P, &first, &end), "MatGetOwnershipRange");
  if (new_pattern)
  {
    f.rows.clear();
    f.cols.clear();
  }
  f.values.clear();
  for (PetscInt i = first; i < end; ++i)
  {
    PetscInt count;
    const PetscInt* cols;
    const PetscScalar* a;
    check(MatGetRow(P, i, &count, &cols, &a), "MatGetRow");
    for (PetscInt k = 0; k < count; ++k)
    {
      if (new_pattern)
      {
        f.rows.push_back(MUMPS_INT(i + 1));
        f.cols.push_back(MUMPS_INT(cols[k] + 1));
      }
      f.values.push_back(float(a[k]));
    }
    check(MatRestoreRow(P, i, &count, &cols, &a), "MatRestoreRow");
  }
}

/// Several processes: the order of the rows (PERM_IN) that MUMPS would pick
/// on one process, made on the host from every process's pattern
/// renumbered by f.numbering (collective). Empty where there is no
/// numbering, where it is not a permutation of the rows, or where that
/// analysis fails: MUMPS then orders the rows itself.
std::vector<MUMPS_INT> partition_free_order(Factors& f, MPI_Comm comm, PetscInt n)
{
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  // Each process's rows are a contiguous range, in rank order: the host
  // gathers the positions of all rows, and the pattern's coordinates.
  const auto gather = [&](const auto* mine, int count, MPI_Datatype type, auto& all)
  {
    const std::size_t processes = static_cast<std::size_t>(size);
    std::vector<int> counts(processes), displs(processes + 1, 0);
    MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
    for (int p = 0; p < size; ++p)
      displs[std::size_t(p) + 1] = displs[std::size_t(p)] + counts[std::size_t(p)];
    all.resize(rank == 0 ? std::size_t(displs[processes]) : 0);
    MPI_Gatherv(mine, count, type, all.data(), counts.data(), displs.data(), type, 0, comm);
  };
  std::vector<std::int64_t> position;
  std::vector<MUMPS_INT> rows, cols;
  gather(f.numbering.data(), int(f.numbering.size()), MPI_INT64_T, position);
  gather(f.rows.data(), int(f.rows.size()), MPI_INT, rows);
  gather(f.cols.data(), int(f.cols.size()), MPI_INT, cols);
  if (rank != 0)
    return {};
  // A permutation of the rows, or nothing (an empty numbering included).
  std::vector<MUMPS_INT> row_at(std::size_t(n), 0); // 1-based row at each position
  if (position.size() != std::size_t(n))
    return {};
  for (std::size_t r = 0; r < position.size(); ++r)
  {
    const std::int64_t p = position[r];
    if (p < 0 || p >= n || row_at[std::size_t(p)] != 0)
      return {};
    row_at[std::size_t(p)] = MUMPS_INT(r + 1);
  }
  // The pattern in that numbering, ordered by MUMPS on this process alone
  // (its automatic choice, as with one process; the values are not needed
  // for a symmetric ordering, so no column permutation by them).
  for (std::size_t k = 0; k < rows.size(); ++k)
  {
    rows[k] = MUMPS_INT(position[std::size_t(rows[k] - 1)] + 1);
    cols[k] = MUMPS_INT(position[std::size_t(cols[k] - 1)] + 1);
  }
  std::vector<float> ones(rows.size(), 1.0f);
  SMUMPS_STRUC_C alone{};
  alone.comm_fortran = MUMPS_INT(MPI_Comm_c2f(MPI_COMM_SELF));
  alone.par = 1;
  alone.sym = 0;
  alone.job = job_init;
  smumps_c(&alone);
  if (alone.infog[0] < 0)
    return {};
  quiet(alone);
  alone.icntl[icntl_column_permutation] = 0;
  alone.n = MUMPS_INT(n);
  alone.nnz = MUMPS_INT8(rows.size());
  alone.irn = rows.data();
  alone.jcn = cols.data();
  alone.a = ones.data();
  alone.job = job_analyse;
  smumps_c(&alone);
  std::vector<MUMPS_INT> order;
  if (alone.infog[0] >= 0)
  {
    // SYM_PERM(p): the pivot at which position p is eliminated.
    order.resize(std::size_t(n));
    for (std::size_t p = 0; p < std::size_t(n); ++p)
      order[std::size_t(row_at[p] - 1)] = alone.sym_perm[p];
  }
  alone.job = job_end;
  smumps_c(&alone);
  return order;
}

/// P's values, and the analysis of its pattern (ordering, symbolic
/// factorisation) once per matrix and nonzero pattern, agreed on by every
/// process (the analysis is collective). Whether the analysis of P's
/// pattern is at hand.
bool load(Factors& f, Mat P)
{
  PetscObjectState state;
  check(MatGetNonzeroState(P, &state), "MatGetNonzeroState");
  PetscObjectId id;
  check(PetscObjectGetId(reinterpret_cast<PetscObject>(P), &id), "PetscObjectGetId");
  int new_pattern = state != f.pattern || PetscInt64(id) != f.matrix;
  MPI_Allreduce(MPI_IN_PLACE, &new_pattern, 1, MPI_INT, MPI_LOR,
                PetscObjectComm(reinterpret_cast<PetscObject>(P)));
  read_rows(f, P, new_pattern);
  PetscInt rows;
  check(MatGetSize(P, &rows, nullptr), "MatGetSize");
  f.id.n = MUMPS_INT(rows);
  if (f.distributed)
  {
    f.id.nnz_loc = MUMPS_INT8(f.values.size());
    f.id.irn_loc = f.rows.data();
    f.id.jcn_loc = f.cols.data();
    f.id.a_loc = f.values.data();
  }
  else
  {
    f.id.nnz = MUMPS_INT8(f.values.size());
    f.id.irn = f.rows.data();
    f.id.jcn = f.cols.data();
    f.id.a = f.values.data();
  }
  if (new_pattern)
  {
    // Another matrix may have another layout: the gather is made anew.
    check(VecScatterDestroy(&f.to_host), "VecScatterDestroy");
    check(VecDestroy(&f.on_host), "VecDestroy");
    if (f.distributed)
    {
      // The order one process would make, if the host could make it; the
      // host's choice, sent to all, as the analysis is collective.
      const MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(P));
      f.order = partition_free_order(f, comm, rows);
      int given = f.order.empty() ? 0 : 1;
      MPI_Bcast(&given, 1, MPI_INT, 0, comm);
      f.id.icntl[icntl_ordering] = given ? ordering_given : ordering_automatic;
      f.id.perm_in = f.order.empty() ? nullptr : f.order.data();
    }
    f.id.job = job_analyse;
    smumps_c(&f.id);
    const bool analysed = f.id.infog[0] >= 0; // INFOG: the same on every process
    f.pattern = analysed ? state : -1;
    f.matrix = analysed ? PetscInt64(id) : -1;
    return analysed;
  }
  return true;
}

bool workspace_error(MUMPS_INT info)
{
  for (MUMPS_INT e : workspace_errors)
    if (info == e)
      return true;
  return false;
}

/// MUMPS's INFOG(1) as PETSc's failed reason of a factorisation.
PCFailedReason failed_reason(MUMPS_INT info)
{
  if (info >= 0)
    return PC_NOERROR;
  if (info == error_singular)
    return PC_FACTOR_NUMERIC_ZEROPIVOT;
  if (info == error_structurally_singular)
    return PC_FACTOR_STRUCT_ZEROPIVOT;
  // -13: an allocation failed (the machine's memory; the step loop ends the
  // run). A workspace still short after its retries is the pivoting's, which
  // a smaller step may not need: another failure, cut as such.
  if (info == mumps_allocation_failed)
    return PC_FACTOR_OUTMEMORY;
  return PC_FACTOR_OTHER;
}

PetscErrorCode set_up(PC pc)
{
  return petsc::callback(
      [&]
      {
        Factors* f;
        check(PCShellGetContext(pc, &f), "PCShellGetContext");
        if (!f->initialised)
          initialise(*f, PetscObjectComm(reinterpret_cast<PetscObject>(pc)));
        Mat P;
        check(PCGetOperators(pc, nullptr, &P), "PCGetOperators");
        f->factored = false;
        // An earlier failure (its INFOG(1) still there) does not stop this
        // factorisation: only the analysis of this pattern must be at hand.
        if (load(*f, P))
        {
          f->id.icntl[icntl_workspace_percent] = f->workspace_percent;
          f->id.job = job_factor;
          smumps_c(&f->id);
          for (int retry = 0; retry < workspace_retries && workspace_error(f->id.infog[0]); ++retry)
          {
            f->id.icntl[icntl_workspace_percent] *= 2;
            smumps_c(&f->id);
          }
        }
        f->factored = f->id.infog[0] >= 0;
        // A failure of an earlier factorisation is over when this one works.
        check(PCSetFailedReason(pc, failed_reason(f->id.infog[0])), "PCSetFailedReason");
      });
}

/// Solves with the factors in place (collective): the host's `rhs` becomes
/// the solution. Whether MUMPS solved.
bool solve(Factors& f)
{
  f.id.rhs = f.rhs.data();
  f.id.nrhs = 1;
  f.id.lrhs = MUMPS_INT(f.rhs.size());
  f.id.job = job_solve;
  smumps_c(&f.id);
  return f.id.infog[0] >= 0; // INFOG: the same on every process
}

/// x's entries on this process in single precision.
void to_single(const Vec x, std::vector<float>& out)
{
  PetscInt n;
  check(VecGetLocalSize(x, &n), "VecGetLocalSize");
  out.resize(std::size_t(n));
  const double* xa;
  check(VecGetArrayRead(x, &xa), "VecGetArrayRead");
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = float(xa[i]);
  check(VecRestoreArrayRead(x, &xa), "VecRestoreArrayRead");
}

/// y's entries on this process from single precision.
void from_single(const std::vector<float>& in, Vec y)
{
  double* ya;
  check(VecGetArray(y, &ya), "VecGetArray");
  for (std::size_t i = 0; i < in.size(); ++i)
    ya[i] = double(in[i]);
  check(VecRestoreArray(y, &ya), "VecRestoreArray");
}

PetscErrorCode apply(PC pc, Vec x, Vec y)
{
  return petsc::callback(
      [&]
      {
        Factors* f;
        check(PCShellGetContext(pc, &f), "PCShellGetContext");
        if (!f->factored)
        {
          check(VecSetInf(y), "VecSetInf");
          return;
        }
        if (!f->distributed)
        {
          to_single(x, f->rhs);
          if (solve(*f))
            from_single(f->rhs, y);
          else
            check(VecSetInf(y), "VecSetInf");
          return;
        }
        if (!f->to_host)
          check(VecScatterCreateToZero(x, &f->to_host, &f->on_host), "VecScatterCreateToZero");
        check(VecScatterBegin(f->to_host, x, f->on_host, INSERT_VALUES, SCATTER_FORWARD),
              "VecScatterBegin");
        check(VecScatterEnd(f->to_host, x, f->on_host, INSERT_VALUES, SCATTER_FORWARD),
              "VecScatterEnd");
        to_single(f->on_host, f->rhs); // empty but on the host
        if (!solve(*f))
        {
          check(VecSetInf(y), "VecSetInf");
          return;
        }
        from_single(f->rhs, f->on_host);
        check(VecScatterBegin(f->to_host, f->on_host, y, INSERT_VALUES, SCATTER_REVERSE),
              "VecScatterBegin");
        check(VecScatterEnd(f->to_host, f->on_host, y, INSERT_VALUES, SCATTER_REVERSE),
              "VecScatterEnd");
      });
}
} // namespace

/// The start of the preconditioner's name (-ksp_view).
constexpr const char* lu_name = "sparse LU in single precision";

void use_single_precision_sparse_lu(PC pc, std::vector<std::int64_t> numbering)
{
  const std::string name =
      lu_name + std::string(single_column_blas_bound()
                                ? " (MUMPS, pushout; its one-column BLAS calls by sgemv/strsv)"
                                : " (MUMPS, pushout)");
  make_shell_preconditioner<Factors>(pc, set_up, apply, name.c_str());
  Factors* f;
  check(PCShellGetContext(pc, &f), "PCShellGetContext");
  f->numbering = std::move(numbering);
}

SparseFactors single_precision_lu_factors(PC pc)
{
  PetscBool shell = PETSC_FALSE;
  check(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCSHELL, &shell),
        "PetscObjectTypeCompare");
  if (!shell)
    return {};
  const char* name = nullptr;
  check(PCShellGetName(pc, &name), "PCShellGetName");
  if (!name || std::string(name).rfind(lu_name, 0) != 0)
    return {};
  Factors* f;
  check(PCShellGetContext(pc, &f), "PCShellGetContext");
  if (!f->factored)
    return {};
  // INFOG(29); negative: in millions (MUMPS 5 users' guide).
  const MUMPS_INT entries = f->id.infog[28];
  return {entries >= 0 ? std::int64_t(entries) : -std::int64_t(entries) * 1000000,
          int(f->id.infog[6])};
}
} // namespace pushout::solver

#include "SinglePrecisionSparse.h"
#include "../common/mpi_gather.h"
#include "../common/petsc_check.h"
#include "NestedDissection.h"
#include "ShellPreconditioner.h"
#include "SingleColumnBlas.h"
#include <cmath>
#include <iterator>
#include <limits>
#include <petscmat.h>
#include <smumps_c.h>
#include <stdexcept>
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
/// ICNTL(28): the analysis sequential; MUMPS's automatic choice.
constexpr int icntl_analysis = 27;
constexpr MUMPS_INT analysis_sequential = 1, analysis_automatic = 0;
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
  int block_size = 1; ///< consecutive places of `numbering` that are one node's
  std::vector<MUMPS_INT> order;
  /// The host's estimates of the factorisation's flops in MUMPS's own order
  /// (PORD) and in SCOTCH's, and whether `order` is SCOTCH's
  double own_flops = 0, scotch_flops = 0;
  bool scotch = false;
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
    petsc::check_nothrow(VecScatterDestroy(&to_host), "VecScatterDestroy");
    petsc::check_nothrow(VecDestroy(&on_host), "VecDestroy");
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
  {
    // Ended even though its start failed, as PETSc's own MUMPS interface
    // ends an instance whose start it called; `initialised` stays false.
    const MUMPS_INT error = f.id.infog[0];
    f.id.job = job_end;
    smumps_c(&f.id);
    throw std::runtime_error("MUMPS (single precision) could not start: INFOG(1) = " +
                             std::to_string(error));
  }
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

/// The order of the rows (PERM_IN, 1-based) made on the host, and the
/// flops MUMPS's analysis estimates for the factorisation in each order
/// tried (RINFOG(1); 0: not made).
struct HostOrder
{
  std::vector<MUMPS_INT> order;
  double own_flops = 0;    ///< MUMPS's own choice of order in the numbering
  int own_ordering = 0;    ///< which it chose (INFOG(7): 4 PORD, 2 AMF, 6 QAMD, ...)
  double scotch_flops = 0; ///< SCOTCH's nested dissection (NestedDissection.h)
  bool scotch = false;     ///< the order is SCOTCH's
};

/// The name of an ordering by MUMPS's code (INFOG(7)).
const char* ordering_name(int code)
{
  constexpr const char* names[] = {"AMD", "the given", "AMF", "SCOTCH", "PORD", "METIS", "QAMD"};
  return code >= 0 && code < int(std::size(names)) ? names[code] : "another";
}

/// The cheaper of two orders of the rows (PERM_IN, 1-based) for the
/// pattern `rows`, `cols` (1-based, n rows) renumbered by `position` (each
/// row's place, 0-based; `block_size` consecutive places one node's):
/// MUMPS's own on this process alone in that numbering, as one process
/// would order it (its automatic choice: PORD on the slices' meshes; no
/// column permutation, as the values are not given), and SCOTCH's nested dissection of the
/// pattern's node graph, by MUMPS's estimate of the factorisation's flops
/// at each analysis (which is the cheaper depends on the mesh:
/// use_single_precision_sparse_lu). An empty order if `position` is not a
/// permutation of the rows, or if MUMPS fails; MUMPS's own where SCOTCH
/// fails.
HostOrder order_in_numbering(PetscInt n, const std::vector<std::int64_t>& position, int block_size,
                             std::vector<MUMPS_INT> rows, std::vector<MUMPS_INT> cols)
{
  std::vector<MUMPS_INT> row_at(std::size_t(n), 0); // 1-based row at each position
  HostOrder host;
  if (position.size() != std::size_t(n))
    return host;
  for (std::size_t r = 0; r < position.size(); ++r)
  {
    const std::int64_t p = position[r];
    if (p < 0 || p >= n || row_at[std::size_t(p)] != 0)
      return host;
    row_at[std::size_t(p)] = MUMPS_INT(r + 1);
  }
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
  {
    alone.job = job_end; // as ~Factors does after a failed start
    smumps_c(&alone);
    return host;
  }
  // Ended on every way out, an exception's included; PERM_IN may point
  // into a vector gone by then.
  struct Ending
  {
    SMUMPS_STRUC_C& id;
    ~Ending()
    {
      id.perm_in = nullptr;
      id.job = job_end;
      smumps_c(&id);
    }
  } ending{alone};
  quiet(alone);
  alone.icntl[icntl_column_permutation] = 0;
  alone.n = MUMPS_INT(n);
  alone.nnz = MUMPS_INT8(rows.size());
  alone.irn = rows.data();
  alone.jcn = cols.data();
  alone.a = ones.data();
  // SYM_PERM(p): the step at which the variable in position p is
  // eliminated; PERM_IN(row) likewise, for the row in that position.
  const auto order_of_rows = [&]
  {
    std::vector<MUMPS_INT> order(static_cast<std::size_t>(n));
    for (std::size_t p = 0; p < std::size_t(n); ++p)
      order[std::size_t(row_at[p] - 1)] = alone.sym_perm[p];
    return order;
  };
  alone.job = job_analyse;
  smumps_c(&alone);
  if (alone.infog[0] >= 0)
  {
    host.order = order_of_rows();
    host.own_flops = double(alone.rinfog[0]);
    host.own_ordering = int(alone.infog[6]);
    const std::vector<std::int64_t> step = nested_dissection(n, block_size, rows, cols);
    std::vector<MUMPS_INT> scotch(step.size());
    for (std::size_t p = 0; p < step.size(); ++p)
      scotch[p] = MUMPS_INT(step[p] + 1);
    if (!scotch.empty())
    {
      alone.icntl[icntl_ordering] = ordering_given;
      alone.perm_in = scotch.data();
      smumps_c(&alone);
      if (alone.infog[0] >= 0)
      {
        host.scotch_flops = double(alone.rinfog[0]);
        if (host.scotch_flops < host.own_flops)
        {
          host.order = order_of_rows();
          host.scotch = true;
        }
      }
    }
  }
  return host;
}

/// Several processes: the order of the rows (PERM_IN) that the host makes
/// in f.numbering (order_in_numbering) from every process's pattern
/// (collective; the host's answer, the others' empty). Its order empty, so
/// that MUMPS orders the rows itself, where a process has no numbering of
/// its `local_rows` rows (P2, or another layout), where the pattern is too
/// large to gather in MPI's int counts, or where the host cannot make it.
HostOrder partition_free_order(Factors& f, MPI_Comm comm, PetscInt n, PetscInt local_rows)
{
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  // Agreed by all: whether every process numbers its rows, and whether the
  // pattern fits in int counts and displacements.
  std::int64_t sums[2] = {f.numbering.size() == std::size_t(local_rows) ? 0 : 1,
                          std::int64_t(f.rows.size())};
  MPI_Allreduce(MPI_IN_PLACE, sums, 2, MPI_INT64_T, MPI_SUM, comm);
  if (sums[0] > 0 || sums[1] > std::numeric_limits<int>::max())
  {
    if (rank == 0)
      petsc::check_nothrow(
          PetscInfo(nullptr, "single-precision LU: MUMPS orders the rows itself (%s)\n",
                    sums[0] > 0 ? "no numbering of every row" : "pattern too large to gather"),
          "PetscInfo");
    return {};
  }
  // Each process's rows are a contiguous range, in rank order: the host
  // gathers the positions of all rows, and the pattern's coordinates.
  const std::vector<std::int64_t> position =
      mpi::gather_to_first(comm, f.numbering.data(), int(f.numbering.size()), MPI_INT64_T);
  std::vector<MUMPS_INT> rows =
      mpi::gather_to_first(comm, f.rows.data(), int(f.rows.size()), MPI_INT);
  std::vector<MUMPS_INT> cols =
      mpi::gather_to_first(comm, f.cols.data(), int(f.cols.size()), MPI_INT);
  if (rank != 0)
    return {};
  HostOrder host;
  try // nothing thrown past here: the others wait for the host's answer
  {
    host = order_in_numbering(n, position, f.block_size, std::move(rows), std::move(cols));
  }
  catch (const std::exception&)
  {
    host = {};
  }
  if (host.order.empty())
    petsc::check_nothrow(PetscInfo(nullptr, "single-precision LU: MUMPS orders the rows itself "
                                            "(the numbering is no permutation of the rows, or its "
                                            "analysis failed)\n"),
                         "PetscInfo");
  else
    petsc::check_nothrow(PetscInfo(nullptr,
                                   "single-precision LU: the rows in %s's order (the "
                                   "factorisation's flops estimated: MUMPS's own choice, %s, "
                                   "%g; SCOTCH's %g, 0: not made)\n",
                                   host.scotch ? "SCOTCH" : ordering_name(host.own_ordering),
                                   ordering_name(host.own_ordering), host.own_flops,
                                   host.scotch_flops),
                         "PetscInfo");
  return host;
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
      // The order the host makes in the numbering given, if it can; its
      // answer sent to all, as the analysis is collective. A given order
      // needs the sequential analysis (ICNTL(28) = 1), whatever parallel
      // ordering tools MUMPS was built with.
      const MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(P));
      PetscInt local_rows;
      check(MatGetLocalSize(P, &local_rows, nullptr), "MatGetLocalSize");
      HostOrder host = partition_free_order(f, comm, rows, local_rows);
      f.order = std::move(host.order);
      // Agreed by all: whether the order is given, and the host's estimates.
      double agreed[4] = {f.order.empty() ? 0.0 : 1.0, host.scotch ? 1.0 : 0.0, host.own_flops,
                          host.scotch_flops};
      MPI_Bcast(agreed, 4, MPI_DOUBLE, 0, comm);
      const bool given = agreed[0] > 0;
      f.scotch = agreed[1] > 0;
      f.own_flops = agreed[2];
      f.scotch_flops = agreed[3];
      f.id.icntl[icntl_ordering] = given ? ordering_given : ordering_automatic;
      f.id.icntl[icntl_analysis] = given ? analysis_sequential : analysis_automatic;
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

void use_single_precision_sparse_lu(PC pc, std::vector<std::int64_t> numbering, int block_size)
{
  const std::string name =
      lu_name + std::string(single_column_blas_bound()
                                ? " (MUMPS, pushout; its one-column BLAS calls by sgemv/strsv)"
                                : " (MUMPS, pushout)");
  make_shell_preconditioner<Factors>(pc, set_up, apply, name.c_str());
  Factors* f;
  check(PCShellGetContext(pc, &f), "PCShellGetContext");
  f->numbering = std::move(numbering);
  f->block_size = block_size;
}

SparseFactors single_precision_lu_factors(PC pc)
{
  const Factors* f = shell_context<Factors>(pc);
  if (!f || !f->factored)
    return {};
  // INFOG(29); negative: in millions (MUMPS 5 users' guide).
  const MUMPS_INT entries = f->id.infog[28];
  return {entries >= 0 ? std::int64_t(entries) : -std::int64_t(entries) * 1000000,
          int(f->id.infog[6]), f->own_flops, f->scotch_flops, f->scotch};
}
} // namespace pushout::solver

#include "SinglePrecisionSparse.h"
#include "../common/petsc_check.h"
#include "ShellPreconditioner.h"
#include "SingleColumnBlas.h"
#include <cmath>
#include <petscmat.h>
#include <smumps_c.h>
#include <string>
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
              icntl_print_level = 3, icntl_workspace_percent = 13;
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
  /// The analysed matrix (its id and nonzero state); -1: none
  PetscInt64 matrix = -1;
  PetscObjectState pattern = -1;
  MUMPS_INT workspace_percent = 0;   ///< ICNTL(14) as MUMPS set it
  std::vector<MUMPS_INT> rows, cols; ///< 1-based coordinates, in the matrix's CSR order
  std::vector<float> values, rhs;

  ~Factors()
  {
    if (initialised)
    {
      id.job = job_end;
      smumps_c(&id);
    }
  }
};

void initialise(Factors& f)
{
  f.id.comm_fortran = MUMPS_INT(MPI_Comm_c2f(PETSC_COMM_SELF));
  f.id.par = 1; // the host works too (one process)
  f.id.sym = 0; // unsymmetric: friction makes the Jacobian so
  f.id.job = job_init;
  smumps_c(&f.id);
  if (f.id.infog[0] < 0)
    throw std::runtime_error("MUMPS (single precision) could not start: INFOG(1) = " +
                             std::to_string(f.id.infog[0]));
  f.initialised = true;
  // Quiet: a failure is reported through the preconditioner's failed reason.
  f.id.icntl[icntl_error_stream] = -1;
  f.id.icntl[icntl_diagnostic_stream] = -1;
  f.id.icntl[icntl_global_stream] = -1;
  f.id.icntl[icntl_print_level] = 0;
  f.workspace_percent = f.id.icntl[icntl_workspace_percent];
}

/// The pattern of P as MUMPS's coordinates, and its analysis (ordering,
/// symbolic factorisation) once per matrix and nonzero pattern; then its
/// values. Whether the analysis of P's pattern is at hand.
bool load(Factors& f, Mat P)
{
  PetscObjectState state;
  check(MatGetNonzeroState(P, &state), "MatGetNonzeroState");
  PetscObjectId id;
  check(PetscObjectGetId(reinterpret_cast<PetscObject>(P), &id), "PetscObjectGetId");
  PetscInt n;
  const PetscInt *ia, *ja;
  PetscBool done;
  check(MatGetRowIJ(P, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done), "MatGetRowIJ");
  if (!done)
    throw std::runtime_error("single-precision LU: the preconditioning matrix has no row "
                             "structure (a sequential AIJ matrix is needed)");
  const PetscInt rows = n; // MatRestoreRowIJ clears n
  const std::size_t nnz = std::size_t(ia[n]);
  const bool new_pattern = state != f.pattern || PetscInt64(id) != f.matrix;
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
  f.id.n = MUMPS_INT(rows);
  f.id.nnz = MUMPS_INT8(nnz);
  f.id.irn = f.rows.data();
  f.id.jcn = f.cols.data();
  f.id.a = f.values.data();
  f.rhs.resize(std::size_t(rows));
  if (new_pattern)
  {
    f.id.job = job_analyse;
    smumps_c(&f.id);
    const bool analysed = f.id.infog[0] >= 0;
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
  if (workspace_error(info) || info == -13) // -13: an allocation failed
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
          initialise(*f);
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
        const std::size_t n = f->rhs.size();
        const double* xa;
        check(VecGetArrayRead(x, &xa), "VecGetArrayRead");
        for (std::size_t i = 0; i < n; ++i)
          f->rhs[i] = float(xa[i]);
        check(VecRestoreArrayRead(x, &xa), "VecRestoreArrayRead");
        f->id.rhs = f->rhs.data();
        f->id.nrhs = 1;
        f->id.lrhs = MUMPS_INT(n);
        f->id.job = job_solve;
        smumps_c(&f->id);
        if (f->id.infog[0] < 0)
        {
          check(VecSetInf(y), "VecSetInf");
          return;
        }
        double* ya;
        check(VecGetArray(y, &ya), "VecGetArray");
        for (std::size_t i = 0; i < n; ++i)
          ya[i] = double(f->rhs[i]);
        check(VecRestoreArray(y, &ya), "VecRestoreArray");
      });
}
} // namespace

void use_single_precision_sparse_lu(PC pc)
{
  make_shell_preconditioner<Factors>(
      pc, set_up, apply,
      single_column_blas_bound()
          ? "sparse LU in single precision (MUMPS, pushout; its one-column BLAS calls by "
            "sgemv/strsv)"
          : "sparse LU in single precision (MUMPS, pushout)");
}
} // namespace pushout::solver

#include "SinglePrecision.h"
#include "../common/petsc_check.h"
#include "../common/vector_clones.h"
#include "ShellPreconditioner.h"
#include <algorithm>
#include <petscblaslapack.h>
#include <petscmat.h>
#include <utility>
#include <vector>

namespace pushout::solver
{
using petsc::check;

namespace
{
/// b = (L U)^-1 b: L (unit diagonal) forwards, then U backwards, column by
/// column (the factors are column-major, n x n).
PUSHOUT_VECTOR_CLONES
void lu_solve_kernel(const float* __restrict lu, std::size_t n, float* __restrict b)
{
  for (std::size_t j = 0; j < n; ++j)
  {
    const float bj = b[j];
    const float* __restrict col = lu + j * n;
    for (std::size_t i = j + 1; i < n; ++i)
      b[i] -= col[i] * bj;
  }
  for (std::size_t j = n; j-- > 0;)
  {
    const float* __restrict col = lu + j * n;
    b[j] /= col[j];
    const float bj = b[j];
    for (std::size_t i = 0; i < j; ++i)
      b[i] -= col[i] * bj;
  }
}

/// The entries of a square sequential dense matrix, column-major without
/// padding (n x n, lda = n); returns n.
std::size_t copy_dense(Mat A, std::vector<double>& out)
{
  PetscInt rows, cols, lda;
  check(MatGetSize(A, &rows, &cols), "MatGetSize");
  check(MatDenseGetLDA(A, &lda), "MatDenseGetLDA");
  const std::size_t n = std::size_t(rows);
  out.resize(n * n);
  const double* a;
  check(MatDenseGetArrayRead(A, &a), "MatDenseGetArrayRead");
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i)
      out[i + j * n] = a[i + j * std::size_t(lda)];
  check(MatDenseRestoreArrayRead(A, &a), "MatDenseRestoreArrayRead");
  return n;
}

struct Factors
{
  PetscBLASInt n = 0;
  std::vector<float> lu;            ///< L (unit diagonal) and U, column-major, n x n
  std::vector<PetscBLASInt> pivots; ///< getrf's: row i was swapped with row pivots[i] - 1
  std::vector<float> b;             ///< the right-hand side, then the solution
  std::vector<double> work;         ///< the double-precision factorisation
};

PetscErrorCode set_up(PC pc)
{
  return petsc::callback(
      [&]
      {
        Factors* f;
        check(PCShellGetContext(pc, &f), "PCShellGetContext");
        Mat P;
        check(PCGetOperators(pc, nullptr, &P), "PCGetOperators");
        const std::size_t n = copy_dense(P, f->work);
        f->n = PetscBLASInt(n);
        f->pivots.resize(n);
        PetscBLASInt info = 0;
        LAPACKgetrf_(&f->n, &f->n, f->work.data(), &f->n, f->pivots.data(), &info);
        if (info != 0)
        {
          // A zero pivot (info > 0): reported as PETSc's factorisations do.
          check(PCSetFailedReason(pc, PC_FACTOR_NUMERIC_ZEROPIVOT), "PCSetFailedReason");
          f->lu.clear();
          return;
        }
        f->lu.assign(f->work.begin(), f->work.end());
        f->work = std::vector<double>(); // only the single-precision factors stay
        f->b.resize(n);
        // A zero pivot of an earlier factorisation is over.
        check(PCSetFailedReason(pc, PC_NOERROR), "PCSetFailedReason");
      });
}

PetscErrorCode apply(PC pc, Vec x, Vec y)
{
  return petsc::callback(
      [&]
      {
        Factors* f;
        check(PCShellGetContext(pc, &f), "PCShellGetContext");
        const std::size_t n = std::size_t(f->n);
        if (f->lu.size() != n * n) // the factorisation failed
        {
          check(VecSetInf(y), "VecSetInf");
          return;
        }
        float* b = f->b.data();
        const float* lu = f->lu.data();
        const double* xa;
        check(VecGetArrayRead(x, &xa), "VecGetArrayRead");
        for (std::size_t i = 0; i < n; ++i)
          b[i] = float(xa[i]);
        check(VecRestoreArrayRead(x, &xa), "VecRestoreArrayRead");
        // P = Pi L U: the row swaps, then the triangular solves.
        for (std::size_t i = 0; i < n; ++i)
          std::swap(b[i], b[std::size_t(f->pivots[i] - 1)]);
        lu_solve_kernel(lu, n, b);
        double* ya;
        check(VecGetArray(y, &ya), "VecGetArray");
        for (std::size_t i = 0; i < n; ++i)
          ya[i] = double(b[i]);
        check(VecRestoreArray(y, &ya), "VecRestoreArray");
      });
}
} // namespace

void use_single_precision_lu(PC pc)
{
  make_shell_preconditioner<Factors>(
      pc, set_up, apply, "LU factored in double, applied in single precision (pushout)");
}
} // namespace pushout::solver

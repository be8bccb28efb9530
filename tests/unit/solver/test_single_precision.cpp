// The single-precision LU preconditioner of the condensed systems
// (solver/SinglePrecision.h): flexible GMRES preconditioned by it converges
// to 1e-11 on a double-precision operator, and a singular matrix is a
// failed preconditioner (zero pivot), not an error.
#include "common/petsc_check.h"
#include "solver/SinglePrecision.h"
#include "zero_pivot.h"
#include <cmath>
#include <gtest/gtest.h>
#include <petscksp.h>
#include <random>

using namespace pushout;
using petsc::check;

namespace
{
/// A random, diagonally weighted, non-symmetric n x n dense matrix.
Mat random_matrix(PetscInt n, unsigned seed)
{
  Mat A;
  check(MatCreateSeqDense(PETSC_COMM_SELF, n, n, nullptr, &A), "MatCreateSeqDense");
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> U(-1, 1);
  for (PetscInt i = 0; i < n; ++i)
    for (PetscInt j = 0; j < n; ++j)
      check(MatSetValue(A, i, j, U(gen) + (i == j ? 0.5 * double(n) : 0.0), INSERT_VALUES),
            "MatSetValue");
  check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  return A;
}
} // namespace

TEST(SinglePrecision, PreconditionedGmresConvergesInDouble)
{
  const PetscInt n = 64;
  Mat A = random_matrix(n, 2);
  KSP ksp;
  check(KSPCreate(PETSC_COMM_SELF, &ksp), "KSPCreate");
  check(KSPSetType(ksp, KSPFGMRES), "KSPSetType"); // right preconditioning, as Condensation
  check(KSPSetOperators(ksp, A, A), "KSPSetOperators");
  check(KSPSetTolerances(ksp, 1e-12, 1e-30, PETSC_DEFAULT, 50), "KSPSetTolerances");
  PC pc;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  solver::use_single_precision_lu(pc);
  Vec b, x, r;
  check(MatCreateVecs(A, &x, &b), "MatCreateVecs");
  check(VecDuplicate(b, &r), "VecDuplicate");
  check(VecSetRandom(b, nullptr), "VecSetRandom");
  check(KSPSolve(ksp, b, x), "KSPSolve");
  KSPConvergedReason reason;
  PetscInt its;
  check(KSPGetConvergedReason(ksp, &reason), "KSPGetConvergedReason");
  check(KSPGetIterationNumber(ksp, &its), "KSPGetIterationNumber");
  EXPECT_GT(reason, 0);
  EXPECT_LE(its, 4); // each iteration gains the ~7 digits of single precision
  // The true residual, in double: GMRES converged on the double operator.
  check(MatMult(A, x, r), "MatMult");
  check(VecAXPY(r, -1.0, b), "VecAXPY");
  double rn, bn;
  check(VecNorm(r, NORM_2, &rn), "VecNorm");
  check(VecNorm(b, NORM_2, &bn), "VecNorm");
  EXPECT_LT(rn, 1e-11 * bn);
  for (Vec* v : {&b, &x, &r})
    check(VecDestroy(v), "VecDestroy");
  check(KSPDestroy(&ksp), "KSPDestroy");
  check(MatDestroy(&A), "MatDestroy");
}

TEST(SinglePrecision, ZeroPivotIsAFailedPreconditioner)
{
  Mat A;
  check(MatCreateSeqDense(PETSC_COMM_SELF, 2, 2, nullptr, &A), "MatCreateSeqDense");
  for (PetscInt i = 0; i < 2; ++i)
    for (PetscInt j = 0; j < 2; ++j)
      check(MatSetValue(A, i, j, 1.0, INSERT_VALUES), "MatSetValue"); // rank 1
  check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  KSP ksp;
  check(KSPCreate(PETSC_COMM_SELF, &ksp), "KSPCreate");
  check(KSPSetType(ksp, KSPGMRES), "KSPSetType");
  check(KSPSetOperators(ksp, A, A), "KSPSetOperators");
  PC pc;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  solver::use_single_precision_lu(pc);
  unit::expect_zero_pivot_failure(ksp, A);
}

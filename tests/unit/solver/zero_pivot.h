// What a preconditioner whose factorisation meets a zero pivot must do, for
// the single-precision LU preconditioners' unit tests: fail the Krylov
// solve as PETSc's own factorisations do, without raising an error.
#pragma once

#include "common/petsc_check.h"
#include <gtest/gtest.h>
#include <petscksp.h>

namespace pushout::unit
{
/// Solves A x = 1 with `ksp` (its operators A, its PC the one under test):
/// no error raised, the solve diverged with a failed preconditioner, the PC
/// failed on a zero pivot. Destroys ksp and A.
inline void expect_zero_pivot_failure(KSP ksp, Mat A)
{
  using petsc::check;
  Vec b, x;
  check(MatCreateVecs(A, &x, &b), "MatCreateVecs");
  check(VecSet(b, 1.0), "VecSet");
  check(KSPSolve(ksp, b, x), "KSPSolve"); // no error raised
  KSPConvergedReason reason;
  check(KSPGetConvergedReason(ksp, &reason), "KSPGetConvergedReason");
  EXPECT_EQ(reason, KSP_DIVERGED_PC_FAILED);
  PC pc;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  PCFailedReason failed;
  check(PCGetFailedReasonRank(pc, &failed), "PCGetFailedReasonRank");
  EXPECT_EQ(failed, PC_FACTOR_NUMERIC_ZEROPIVOT);
  for (Vec* v : {&b, &x})
    check(VecDestroy(v), "VecDestroy");
  check(KSPDestroy(&ksp), "KSPDestroy");
  check(MatDestroy(&A), "MatDestroy");
}
} // namespace pushout::unit

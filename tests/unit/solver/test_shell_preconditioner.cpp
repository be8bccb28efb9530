// The shells of solver/ShellPreconditioner.h own their context and know it
// by the tag make_shell_preconditioner composes, not by their name: another
// context type, a shell of the same name, and a shell whose type was changed
// since are not taken for it; a shell made again deletes its old context.
#include "common/petsc_check.h"
#include "solver/ShellPreconditioner.h"
#include "solver/SinglePrecision.h"
#include "solver/SinglePrecisionSparse.h"
#include <gtest/gtest.h>
#include <petscpc.h>

using namespace pushout;
using petsc::check;

namespace
{
/// Counts its live objects.
struct First
{
  inline static int live = 0;
  int value = 1;
  First() { ++live; }
  ~First() { --live; }
};
struct Second
{
  int value = 2;
};

PetscErrorCode set_up(PC)
{
  return 0;
}
PetscErrorCode apply(PC, Vec x, Vec y)
{
  return VecCopy(x, y);
}

PC new_pc()
{
  PC pc;
  check(PCCreate(PETSC_COMM_SELF, &pc), "PCCreate");
  return pc;
}
} // namespace

TEST(ShellPreconditioner, ContextKnownByItsTagNotByItsName)
{
  PC pc = new_pc();
  solver::make_shell_preconditioner<First>(pc, set_up, apply, "first");
  ASSERT_NE(solver::shell_context<First>(pc), nullptr);
  EXPECT_EQ(solver::shell_context<First>(pc)->value, 1);
  EXPECT_EQ(solver::shell_context<Second>(pc), nullptr) << "another context type";

  // Made again with the same context type: a new context, the old deleted.
  ASSERT_EQ(First::live, 1);
  First* first = solver::shell_context<First>(pc);
  first->value = 7;
  solver::make_shell_preconditioner<First>(pc, set_up, apply, "first again");
  EXPECT_EQ(First::live, 1);
  ASSERT_NE(solver::shell_context<First>(pc), nullptr);
  EXPECT_EQ(solver::shell_context<First>(pc)->value, 1);
  // Made again with another context: the old one is deleted, and the tag
  // follows the new one.
  solver::make_shell_preconditioner<Second>(pc, set_up, apply, "second");
  EXPECT_EQ(First::live, 0);
  EXPECT_EQ(solver::shell_context<First>(pc), nullptr);
  ASSERT_NE(solver::shell_context<Second>(pc), nullptr);
  EXPECT_EQ(solver::shell_context<Second>(pc)->value, 2);

  // Another type: the shell's context is gone, and so is its tag; a shell
  // made by hand after it is none of make_shell_preconditioner's.
  check(PCSetType(pc, PCJACOBI), "PCSetType");
  EXPECT_EQ(solver::shell_context<Second>(pc), nullptr);
  First by_hand;
  check(PCSetType(pc, PCSHELL), "PCSetType");
  check(PCShellSetContext(pc, &by_hand), "PCShellSetContext");
  EXPECT_EQ(solver::shell_context<Second>(pc), nullptr);
  EXPECT_EQ(solver::shell_context<First>(pc), nullptr);
  check(PCDestroy(&pc), "PCDestroy");
}

TEST(ShellPreconditioner, TheSparseLuIsNotTakenFromAShellOfItsName)
{
  // A shell of pushout's own kind, named as the single-precision LU is: its
  // context is not the LU's, so there are no factors to report.
  PC pc = new_pc();
  solver::make_shell_preconditioner<First>(pc, set_up, apply,
                                           "sparse LU in single precision (MUMPS, pushout)");
  EXPECT_EQ(solver::single_precision_lu_factors(pc).entries, -1);
  // Nor from the dense single-precision LU's.
  solver::use_single_precision_lu(pc);
  EXPECT_EQ(solver::single_precision_lu_factors(pc).entries, -1);
  check(PCDestroy(&pc), "PCDestroy");
}

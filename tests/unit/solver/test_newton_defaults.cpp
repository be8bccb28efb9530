// The PETSc defaults of Newton (NewtonSolver::set_default_options) follow
// the run they are set for: the cases of a sweep share one process, and a
// case with cracking concrete (line search l2) must not leave its line
// search to the next case without (bt), nor the other way round.
#include "common/petsc_check.h"
#include "solver/NewtonSolver.h"
#include <gtest/gtest.h>
#include <string>

using pushout::petsc::check;
using pushout::solver::NewtonSolver;

namespace
{
std::string line_search()
{
  char value[64] = "";
  PetscBool set = PETSC_FALSE;
  check(
      PetscOptionsGetString(nullptr, nullptr, "-snes_linesearch_type", value, sizeof(value), &set),
      "PetscOptionsGetString");
  return set ? value : "";
}
} // namespace

TEST(NewtonDefaults, EachRunGetsItsOwnLineSearch)
{
  const auto pc = NewtonSolver::Preconditioner::jacobian;
  NewtonSolver::set_default_options(pc, true);
  EXPECT_EQ(line_search(), "l2");
  NewtonSolver::set_default_options(pc, false);
  EXPECT_EQ(line_search(), "bt");
  NewtonSolver::set_default_options(pc, true);
  EXPECT_EQ(line_search(), "l2");
  NewtonSolver::set_default_options(pc, false); // as the other tests expect
  EXPECT_EQ(line_search(), "bt");
}

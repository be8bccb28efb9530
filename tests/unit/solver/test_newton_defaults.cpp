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
/// The value of a PETSc option, "" if it is not set.
std::string option(const char* name)
{
  char value[64] = "";
  PetscBool set = PETSC_FALSE;
  check(PetscOptionsGetString(nullptr, nullptr, name, value, sizeof(value), &set),
        "PetscOptionsGetString");
  return set ? value : "";
}

std::string line_search()
{
  return option("-snes_linesearch_type");
}
} // namespace

TEST(NewtonDefaults, EachRunGetsItsOwnLineSearch)
{
  const auto pc = NewtonSolver::Preconditioner::jacobian;
  NewtonSolver::set_default_options(pc, NewtonSolver::Concrete::cracks);
  EXPECT_EQ(line_search(), "l2");
  NewtonSolver::set_default_options(pc, NewtonSolver::Concrete::linear);
  EXPECT_EQ(line_search(), "bt");
  NewtonSolver::set_default_options(pc, NewtonSolver::Concrete::cracks);
  EXPECT_EQ(line_search(), "l2");
  NewtonSolver::set_default_options(pc,
                                    NewtonSolver::Concrete::linear); // as the other tests expect
  EXPECT_EQ(line_search(), "bt");
}

// A failed solve is tried again with the other line search where the
// concrete cracks: each fallback differs from the first line search.
TEST(NewtonDefaults, CrackingConcreteFallsBackOnTheOtherLineSearch)
{
  const auto pc = NewtonSolver::Preconditioner::lagged;
  for (const auto concrete :
       {NewtonSolver::Concrete::cracks, NewtonSolver::Concrete::implex_cracks})
  {
    NewtonSolver::set_default_options(pc, concrete);
    const std::string fallback = NewtonSolver::fallback_line_search(concrete);
    EXPECT_FALSE(fallback.empty());
    EXPECT_NE(fallback, line_search());
  }
  EXPECT_EQ(std::string(NewtonSolver::fallback_line_search(NewtonSolver::Concrete::implex_cracks)),
            "l2");
  EXPECT_EQ(std::string(NewtonSolver::fallback_line_search(NewtonSolver::Concrete::linear)), "");
  NewtonSolver::set_default_options(NewtonSolver::Preconditioner::jacobian,
                                    NewtonSolver::Concrete::linear); // as the other tests expect
}

// IMPL-EX cracks stop Newton and GMRES at NewtonSolver::implex_rtol, and the
// next run without them is back at 1e-10 (a sweep's cases share a process);
// a run whose LU is the solver keeps no GMRES default of an earlier one.
TEST(NewtonDefaults, ImplexCracksGetTheirOwnTolerances)
{
  const auto pc = NewtonSolver::Preconditioner::lagged;
  NewtonSolver::set_default_options(pc, NewtonSolver::Concrete::implex_cracks);
  EXPECT_EQ(option("-snes_rtol"), NewtonSolver::implex_rtol);
  EXPECT_EQ(option("-ksp_rtol"), NewtonSolver::implex_rtol);
  EXPECT_EQ(option("-snes_linesearch_type"), "bt");
  NewtonSolver::set_default_options(pc, NewtonSolver::Concrete::cracks);
  EXPECT_EQ(option("-snes_rtol"), "1e-10");
  EXPECT_EQ(option("-ksp_rtol"), "1e-10");
  // The LU of every Jacobian: under GMRES only where it is single precision;
  // otherwise the LU is the solver, and no GMRES default of an earlier run
  // stays behind.
  const auto jacobian = NewtonSolver::Preconditioner::jacobian;
  NewtonSolver::set_default_options(jacobian, NewtonSolver::Concrete::cracks, true);
  EXPECT_EQ(option("-ksp_type"), "gmres");
  EXPECT_EQ(option("-ksp_rtol"), "1e-10");
  NewtonSolver::set_default_options(jacobian, NewtonSolver::Concrete::cracks, false);
  EXPECT_EQ(option("-ksp_type"), "preonly");
  EXPECT_EQ(option("-ksp_rtol"), "");
  NewtonSolver::set_default_options(pc, NewtonSolver::Concrete::implex_cracks);
  NewtonSolver::set_default_options(jacobian,
                                    NewtonSolver::Concrete::linear); // as the others expect
  EXPECT_EQ(option("-snes_rtol"), "1e-10");
  EXPECT_EQ(option("-ksp_type"), "preonly");
  EXPECT_EQ(option("-ksp_rtol"), "");
}

// solver.inexact_newton's tolerance of a linear solve (NewtonSolver::
// inexact_rtol): half of what Newton's test still needs relative to the
// residual at hand, never below -ksp_rtol nor above 0.1 (or -ksp_rtol).
TEST(NewtonDefaults, InexactToleranceIsWhatNewtonStillNeeds)
{
  // Newton asks for 1e-4 N (-snes_rtol 1e-6 of 100 N).
  const double needed = NewtonSolver::newton_tolerance(1e-10, 1e-6, 100.0); // [N]
  EXPECT_DOUBLE_EQ(needed, 1e-4);
  // The push's second iteration: ||F|| at 5e-2 N.
  EXPECT_DOUBLE_EQ(NewtonSolver::inexact_rtol(needed, 5e-2, 1e-6), 1e-3);
  // At the first residual: no looser than -ksp_rtol.
  EXPECT_DOUBLE_EQ(NewtonSolver::inexact_rtol(needed, 100.0, 1e-6), 1e-6);
  // Close to the test: at most 0.1.
  EXPECT_DOUBLE_EQ(NewtonSolver::inexact_rtol(needed, 2e-4, 1e-6), 0.1);
  // The absolute tolerance where it is the larger.
  EXPECT_DOUBLE_EQ(
      NewtonSolver::inexact_rtol(NewtonSolver::newton_tolerance(1e-3, 1e-6, 100.0), 1e-1, 1e-10),
      5e-3);
  // A -ksp_rtol above 0.1 is kept; a zero residual asks for -ksp_rtol.
  EXPECT_DOUBLE_EQ(NewtonSolver::inexact_rtol(needed, 1e-5, 0.5), 0.5);
  EXPECT_DOUBLE_EQ(NewtonSolver::inexact_rtol(needed, 0.0, 1e-6), 1e-6);
}

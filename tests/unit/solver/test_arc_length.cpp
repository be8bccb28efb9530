// Path following with a load factor that enters the equations nonlinearly
// (ArcLengthSolver::set_load_difference, the corrosion stage's x): a system
// of two unknowns whose equilibrium path is known in closed form,
//   F1 = x1 - lambda^2,   F2 = x2 - x1 - lambda^3,
// controlled by c(x) = x2 = lambda^2 + lambda^3.
#include "common/petsc_check.h"
#include "solver/ArcLengthSolver.h"
#include "two_unknowns.h"
#include <cmath>
#include <gtest/gtest.h>
#include <limits>

using namespace pushout;
using petsc::check;

namespace
{
class CubicPath : public unit::TwoUnknowns
{
public:
  double lambda = 0;          ///< set by the path follower's set_load
  double jacobian_scale = 1;  ///< the Jacobian given, times the true one
  double first_row_scale = 1; ///< and its first row (dF1/dx) times this

  std::array<double, 2> F(const std::array<double, 2>& x) override
  {
    return {x[0] - lambda * lambda, x[1] - x[0] - lambda * lambda * lambda};
  }
  std::array<double, 4> J(const std::array<double, 2>&) override
  {
    return {first_row_scale * jacobian_scale, 0, -jacobian_scale, jacobian_scale};
  }
};

/// One step of control increment d_eta from the equilibrium at lambda0 with
/// e by differences of step h (0: as if F were affine in lambda), the
/// Jacobian times jacobian_scale, its first row times first_row_scale; a
/// stall nearly in equilibrium ends the step if `loose`. `end`: the step's
/// last x.
solver::SolveReport step(double lambda0, double d_eta, double h, double& lambda,
                         double jacobian_scale = 1, double first_row_scale = 1, bool loose = false,
                         std::array<double, 2>* end = nullptr)
{
  CubicPath problem;
  problem.jacobian_scale = jacobian_scale;
  problem.first_row_scale = first_row_scale;
  Vec a = problem.create_vector(), x = problem.create_vector();
  check(VecSetValue(a, 1, 1.0, INSERT_VALUES), "VecSetValue");
  check(VecSetValue(x, 0, lambda0 * lambda0, INSERT_VALUES), "VecSetValue");
  check(VecSetValue(x, 1, lambda0 * lambda0 * (1 + lambda0), INSERT_VALUES), "VecSetValue");
  solver::SolveReport rep;
  {
    solver::LinearConstraint control(a);
    solver::ArcLengthSolver arc(problem, control, solver::NewtonSolver::Preconditioner::jacobian,
                                1);
    arc.set_load_difference(h);
    lambda = lambda0;
    rep = arc.step(
        x, lambda, d_eta, [&](double l) { problem.lambda = l; }, 0, loose);
  }
  if (end)
  {
    const PetscScalar* v = nullptr;
    check(VecGetArrayRead(x, &v), "VecGetArrayRead");
    *end = {v[0], v[1]};
    check(VecRestoreArrayRead(x, &v), "VecRestoreArrayRead");
  }
  check(VecDestroy(&a), "VecDestroy");
  check(VecDestroy(&x), "VecDestroy");
  return rep;
}
} // namespace

TEST(ArcLength, NonlinearLoadFactorByDifferences)
{
  // From lambda = 1 (x2 = 2) to x2 = 3: lambda^3 + lambda^2 = 3.
  double lambda = 0;
  const solver::SolveReport rep = step(1.0, 1.0, 1e-7, lambda);
  ASSERT_TRUE(rep.converged) << rep.reason;
  EXPECT_NEAR(lambda * lambda * (1 + lambda), 3.0, 1e-9);
  EXPECT_NEAR(lambda, 1.174559410903, 1e-9);
  // Newton on the bordered system with e to 1e-7: quadratic, up to the
  // difference's error (measured: 4 iterations).
  EXPECT_LE(rep.iterations, 5);
}

TEST(ArcLength, AffineDirectionIsSlowForANonlinearLoadFactor)
{
  // The same step with e = F(lambda) - F(lambda + 1) (the affine rule): the
  // secant over a unit of lambda, not the tangent. It still lands on the
  // path (F and the constraint are what converge) but linearly (measured:
  // 23 iterations): the differences are what make the first test fast.
  double lambda = 0;
  const solver::SolveReport rep = step(1.0, 1.0, 0.0, lambda);
  ASSERT_TRUE(rep.converged) << rep.reason;
  EXPECT_NEAR(lambda * lambda * (1 + lambda), 3.0, 1e-9);
  EXPECT_GT(rep.iterations, 10);
}

TEST(ArcLength, NoProgressIsCutEarly)
{
  // Half the Jacobian: each Newton step goes twice as far as it should and
  // the iterates swing across the path without getting closer. The step
  // fails once 10 iterations have not halved the smallest |F| so far, not
  // after all of -snes_max_it (50).
  double lambda = 0;
  const solver::SolveReport rep = step(1.0, 1.0, 1e-7, lambda, 0.5);
  EXPECT_FALSE(rep.converged);
  EXPECT_EQ(rep.reason.rfind("DIVERGED_NO_PROGRESS", 0), 0u) << rep.reason;
  EXPECT_LE(rep.iterations, 15); // measured: 12
}

TEST(ArcLength, AStalledStepNearEquilibriumEndsAtItsBestIterate)
{
  // dF1/dx1 given as 0.18 of the true one: the control row is exact, and
  // |F| falls by only 0.97 per iteration (measured in a model of the
  // iteration), so the step stalls. From lambda = 1 by x2 += 1e-7 (the
  // reactions' norm is 1 here) its iterates are within 1e-7 of
  // equilibrium: with `loose` (as dissipation control asks) the step ends
  // at the best of them, within 1e-5 of the
  // reactions (ArcLengthSolver::loose_rtol), the control within 1 % of the
  // step. On the path, lambda^2 (1 + lambda) = 2 + 1e-7.
  double lambda = 0;
  std::array<double, 2> x{};
  const solver::SolveReport rep = step(1.0, 1e-7, 1e-7, lambda, 1, 0.18, true, &x);
  ASSERT_TRUE(rep.converged) << rep.reason;
  EXPECT_TRUE(rep.loose);
  EXPECT_EQ(rep.reason.rfind("CONVERGED_AT_STALL", 0), 0u) << rep.reason;
  EXPECT_LE(rep.iterations, 15);
  // The step moved: the control x2 within 1 % of the step from 2 + 1e-7
  // (the loose rule's promise; it starts 1e-7 away, at 2), and the iterate
  // within 1e-5 of equilibrium (loose_rtol times the reactions' norm, 1).
  EXPECT_NEAR(x[1], 2.0 + 1e-7, 1e-9);
  EXPECT_LE(std::hypot(x[0] - lambda * lambda, x[1] - x[0] - lambda * lambda * lambda), 1e-5);
  // The path's lambda, 1 + 2e-8, to the |F| of the iterate (below 1e-7;
  // d lambda / d F is about 1 here), not to Newton's tolerance.
  EXPECT_NEAR(lambda, 1.0 + 2e-8, 1e-7);
  // Not unless the caller allows it,
  const solver::SolveReport strict = step(1.0, 1e-7, 1e-7, lambda, 1, 0.18);
  EXPECT_FALSE(strict.converged);
  EXPECT_EQ(strict.reason.rfind("DIVERGED_NO_PROGRESS", 0), 0u) << strict.reason;
  // and not a whole unit of x2 away, far from equilibrium.
  const solver::SolveReport far = step(1.0, 1.0, 1e-7, lambda, 1, 0.18, true);
  EXPECT_FALSE(far.converged);
  EXPECT_FALSE(far.loose);
  EXPECT_EQ(far.reason.rfind("DIVERGED_NO_PROGRESS", 0), 0u) << far.reason;
}

TEST(ArcLength, LooseConvergenceNeedsBothEquilibriumAndControl)
{
  using solver::ArcLengthSolver;
  // The corroded study's stalled step (tube centred, beta 2, seed 4,
  // x = 25 um, push step 4, -arc_monitor): its best iterate has |F| 3.6e-5 N
  // against reactions of 299 N (1.2e-7) and its control off by 6.6e-7 N mm
  // of a 7.8e-3 N mm step (8.5e-5).
  EXPECT_EQ(ArcLengthSolver::loose_convergence(3.609e-5, 299.4, 6.642e-7, 7.8125e-3)
                .rfind("CONVERGED_AT_STALL", 0),
            0u);
  // At the bounds, and just beyond each.
  EXPECT_NE(ArcLengthSolver::loose_convergence(1e-5, 1.0, 0.01, 1.0), "");
  EXPECT_EQ(ArcLengthSolver::loose_convergence(1.01e-5, 1.0, 0.0, 1.0), "");
  EXPECT_EQ(ArcLengthSolver::loose_convergence(0.0, 1.0, 0.0101, 1.0), "");
  EXPECT_EQ(ArcLengthSolver::loose_convergence(0.0, 1.0, -0.0101, 1.0), "");
  // Not a number is never near.
  EXPECT_EQ(ArcLengthSolver::loose_convergence(NAN, 1.0, 0.0, 1.0), "");
}

TEST(ArcLength, TheControlTestHasARoundOffFloor)
{
  using solver::ArcLengthSolver;
  // A step converges with its control within 1e-8 of its increment,
  EXPECT_DOUBLE_EQ(ArcLengthSolver::control_tolerance(1e-3, 0.05), 1e-11);
  // but not below c's round-off: the brittle slice with cracks at
  // implex_tolerance 0.003 (docs/cracking.md, "Under arc length"), whose
  // slip increments had fallen to 1.25e-13 mm while the IMPL-EX cracks
  // relaxed through a snap, ran into -snes_max_it at |F| 1e-6 of its
  // tolerance with its control off by 1e-18 to 3e-18 mm (-arc_monitor),
  // the round-off of the mean slip's terms (sum |a_i x_i| some 0.02 mm
  // there). The floor is 1000 machine epsilons of those terms.
  const double floor = ArcLengthSolver::control_tolerance(1.25e-13, 0.02);
  EXPECT_GT(floor, 3e-18);
  EXPECT_DOUBLE_EQ(floor, 1e3 * std::numeric_limits<double>::epsilon() * 0.02);
  // It stays below 1 % of the least slip increment path following gives a
  // step (1e-6 of its length, stepping/PathFollowing.cpp: 2e-12 mm there
  // at the smallest length), so the control still ends where it is told.
  EXPECT_LT(floor, 0.01 * 1e-6 * 0.002 / 1024);
}

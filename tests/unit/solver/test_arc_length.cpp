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

using namespace pushout;
using petsc::check;

namespace
{
class CubicPath : public unit::TwoUnknowns
{
public:
  double lambda = 0;         ///< set by the path follower's set_load
  double jacobian_scale = 1; ///< the Jacobian given, times the true one

  std::array<double, 2> F(const std::array<double, 2>& x) override
  {
    return {x[0] - lambda * lambda, x[1] - x[0] - lambda * lambda * lambda};
  }
  std::array<double, 4> J(const std::array<double, 2>&) override
  {
    return {jacobian_scale, 0, -jacobian_scale, jacobian_scale};
  }
};

/// One step of control increment d_eta from the equilibrium at lambda0 with
/// e by differences of step h (0: as if F were affine in lambda), the
/// Jacobian times jacobian_scale.
solver::SolveReport step(double lambda0, double d_eta, double h, double& lambda,
                         double jacobian_scale = 1)
{
  CubicPath problem;
  problem.jacobian_scale = jacobian_scale;
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
    rep = arc.step(x, lambda, d_eta, [&](double l) { problem.lambda = l; });
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

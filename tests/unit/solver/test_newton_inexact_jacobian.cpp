// Newton with an inexact Jacobian, as cracking concrete gives it (a new
// crack's normal follows the strain and its tangent does not):
//   F_i = x_i + x_i^3 / 10 - b_i,   J given = s dF/dx.
// - s = 1.25: each step covers 1/1.25 of the error, a linear tail near 0.2;
//   once two iterations in a row have cut ||F|| by 0.3 or better, the later
//   ones keep the factorisation at hand (NewtonSolver::set_tail_reuse): the
//   same solution to Newton's tolerance, fewer factorisations.
// - s = 0.5 with full steps, F linear (no cube): each step lands as far on
//   the other side and the iterates swing without getting closer; with set_stop_when_stalled the
//   solve fails after about ten iterations (DIVERGED_NO_PROGRESS), not at
//   -snes_max_it (50).
// - A predicted start (NewtonSolver::solve's reference): Newton's relative
//   test is of the step's own residual, not of the prediction's.
// - A lagged LU that has gone stale (F = A x - b with A changed between
//   solves): GMRES stopped short on it fails the Newton solve, which is
//   tried again on a fresh LU before the step loop would cut it.
// - A Jacobian that fails (a law at a point) fails the solve, with PETSc's
//   DIVERGED_JACOBIAN_DOMAIN, however good the matrix it left.
#include "common/petsc_check.h"
#include "solver/NewtonHistory.h"
#include "solver/NewtonSolver.h"
#include "two_unknowns.h"
#include <array>
#include <cmath>
#include <gtest/gtest.h>

using namespace pushout;
using petsc::check;

namespace
{
constexpr std::array<double, 2> b = {1.0, 3.0};

class InexactJacobian : public unit::TwoUnknowns
{
public:
  double scale = 1;  ///< the Jacobian given, times the true one
  double cube = 0.1; ///< the coefficient of x_i^3 in F
  int jacobians = 0; ///< Jacobian evaluations

  std::array<double, 2> F(const std::array<double, 2>& x) override
  {
    return {x[0] + cube * x[0] * x[0] * x[0] - b[0], x[1] + cube * x[1] * x[1] * x[1] - b[1]};
  }
  std::array<double, 4> J(const std::array<double, 2>& x) override
  {
    ++jacobians;
    return {scale * (1 + 3 * cube * x[0] * x[0]), 0, 0, scale * (1 + 3 * cube * x[1] * x[1])};
  }
};

struct Solve
{
  solver::SolveReport report;
  int factorizations = 0;
  int jacobians = 0;
  std::array<double, 2> x{};
};

/// One Newton solve from x = 0 with the Jacobian times `scale`, keeping the
/// factorisation in tails below `ratio` (0: never), failing when stalled if
/// `stop_stalled`; F's cube times `cube`; PETSc's line search `line_search`
/// instead of the default (bt), and `fallback` for a second attempt
/// (NewtonSolver::set_fallback_line_search; none by default).
Solve solve(double ratio, double scale = 1.25, bool stop_stalled = false, double cube = 0.1,
            const char* line_search = nullptr, const char* fallback = nullptr)
{
  solver::NewtonSolver::set_default_options(solver::NewtonSolver::Preconditioner::jacobian);
  if (line_search)
    check(PetscOptionsSetValue(nullptr, "-snes_linesearch_type", line_search),
          "PetscOptionsSetValue");
  InexactJacobian problem;
  problem.scale = scale;
  problem.cube = cube;
  Vec x = problem.create_vector();
  check(VecSet(x, 0.0), "VecSet");
  Solve s;
  {
    solver::NewtonSolver newton(problem, solver::NewtonSolver::Preconditioner::jacobian);
    newton.set_tail_reuse(ratio);
    newton.set_stop_when_stalled(stop_stalled);
    if (fallback)
      newton.set_fallback_line_search(fallback);
    s.report = newton.solve(x);
    s.factorizations = newton.factorizations();
  }
  s.jacobians = problem.jacobians;
  s.x = InexactJacobian::values(x);
  check(VecDestroy(&x), "VecDestroy");
  return s;
}
} // namespace

TEST(TailReuse, SameSolutionFewerFactorisations)
{
  const Solve every = solve(0.0), tail = solve(0.3);
  ASSERT_TRUE(every.report.converged) << every.report.reason;
  ASSERT_TRUE(tail.report.converged) << tail.report.reason;
  // Both stop at ||F|| <= 1e-10 ||F(0)|| = 1e-10 |b| (-snes_rtol, above
  // -snes_atol here), and dF/dx >= 1: each x within that of the root, so
  // the two within twice it.
  const double tolerance = 1e-10 * std::hypot(b[0], b[1]);
  for (int i = 0; i < 2; ++i)
  {
    EXPECT_NEAR(tail.x[i] + std::pow(tail.x[i], 3) / 10, b[i], tolerance);
    EXPECT_NEAR(tail.x[i], every.x[i], 2 * tolerance);
  }
  // Without reuse, a factorisation per iteration; with it, the first two
  // iterations' and those where the tail slowed past 0.3 (measured: 15
  // iterations either way, 15 and 4 factorisations).
  EXPECT_EQ(every.factorizations, every.report.iterations);
  EXPECT_LT(tail.factorizations, every.factorizations / 2);
  EXPECT_EQ(tail.jacobians, tail.factorizations);
}

TEST(TailReuse, ARatioNoTailReachesChangesNothing)
{
  // A ratio no tail reaches: a new Jacobian in every iteration.
  const Solve every = solve(0.0), never = solve(1e-30);
  EXPECT_EQ(never.report.iterations, every.report.iterations);
  EXPECT_EQ(never.factorizations, every.factorizations);
}

TEST(StallStop, SwingingIteratesStopEarly)
{
  // Full steps (no line search) on half the Jacobian of a linear F.
  const Solve stopped = solve(0.0, 0.5, true, 0.0, "basic"),
              not_stopped = solve(0.0, 0.5, false, 0.0, "basic");
  // bt again, as the other tests expect (set_default_options replaces the
  // option it set).
  solver::NewtonSolver::set_default_options(solver::NewtonSolver::Preconditioner::jacobian);
  EXPECT_FALSE(stopped.report.converged);
  EXPECT_EQ(stopped.report.reason.rfind("DIVERGED_NO_PROGRESS", 0), 0u) << stopped.report.reason;
  // Iteration 0, the first (which may raise |F|), then ten that do not halve
  // the smallest since.
  EXPECT_LE(stopped.report.iterations, solver::stall_iterations + 2);
  EXPECT_TRUE(stopped.report.stalled);
  EXPECT_FALSE(not_stopped.report.converged);
  EXPECT_EQ(not_stopped.report.iterations, 50) << not_stopped.report.reason; // -snes_max_it
  EXPECT_FALSE(not_stopped.report.stalled);
}

TEST(StallStop, AStalledSolveIsNotTriedAgain)
{
  // As above, with a fallback line search: a solve that runs to -snes_max_it
  // is tried again with it, a stalled one is not (the step loop cuts it).
  const Solve stopped = solve(0.0, 0.5, true, 0.0, "basic", "basic"),
              not_stopped = solve(0.0, 0.5, false, 0.0, "basic", "basic");
  solver::NewtonSolver::set_default_options(solver::NewtonSolver::Preconditioner::jacobian);
  EXPECT_TRUE(stopped.report.stalled);
  EXPECT_LE(stopped.report.iterations, solver::stall_iterations + 2);
  EXPECT_FALSE(not_stopped.report.converged);
  EXPECT_EQ(not_stopped.report.iterations, 2 * 50) << not_stopped.report.reason;
}

TEST(StallStop, ASteadyTailIsLeftAlone)
{
  // The linear tail of the first test (rate near 0.2) converges as before.
  const Solve stopping = solve(0.0, 1.25, true), not_stopping = solve(0.0, 1.25, false);
  ASSERT_TRUE(stopping.report.converged) << stopping.report.reason;
  EXPECT_EQ(stopping.report.iterations, not_stopping.report.iterations);
}

namespace
{
struct Predicted
{
  solver::SolveReport report;
  double F_start = 0; ///< ||F|| at the start [N]
  double F_end = 0;   ///< ||F|| at the solution [N]
};

/// x = b (1 + `error`): a prediction of the root b of the linear F (no
/// cube), a new vector of `problem`'s.
Vec prediction(const InexactJacobian& problem, double error)
{
  Vec x = problem.create_vector();
  PetscScalar* xa;
  check(VecGetArray(x, &xa), "VecGetArray");
  for (int i = 0; i < 2; ++i)
    xa[i] = b[i] * (1 + error);
  check(VecRestoreArray(x, &xa), "VecRestoreArray");
  return x;
}

/// One solve of the linear F (no cube; its root is b) with 1.25 times its
/// Jacobian, so that each iteration cuts ||F|| to 0.2 of itself, from the
/// prediction x = b (1 + `error`), with NewtonSolver::solve's `reference`.
Predicted solve_predicted(double error, double reference)
{
  solver::NewtonSolver::set_default_options(solver::NewtonSolver::Preconditioner::jacobian);
  // Only the relative test: -snes_atol (1e-10 by default) out of the way,
  // for this solve only.
  check(PetscOptionsSetValue(nullptr, "-snes_atol", "1e-30"), "PetscOptionsSetValue");
  InexactJacobian problem;
  problem.scale = 1.25;
  problem.cube = 0.0;
  Vec x = prediction(problem, error);
  const auto norm = [&](Vec v)
  {
    const std::array<double, 2> f = problem.F(InexactJacobian::values(v));
    return std::hypot(f[0], f[1]);
  };
  Predicted p;
  p.F_start = norm(x);
  {
    solver::NewtonSolver newton(problem, solver::NewtonSolver::Preconditioner::jacobian);
    p.report = newton.solve(x, reference);
  }
  p.F_end = norm(x);
  check(VecDestroy(&x), "VecDestroy");
  check(PetscOptionsClearValue(nullptr, "-snes_atol"), "PetscOptionsClearValue");
  return p;
}
} // namespace

TEST(PredictedStart, TheTestIsRelativeToTheStepsOwnResidual)
{
  // The step's own residual, at x = 0 without the prediction: |b|. The
  // prediction's is 1e-3 of it. -snes_rtol is 1e-10.
  const double step = std::hypot(b[0], b[1]);
  const Predicted alone = solve_predicted(1e-3, 0.0), referred = solve_predicted(1e-3, step);
  ASSERT_TRUE(alone.report.converged) << alone.report.reason;
  ASSERT_TRUE(referred.report.converged) << referred.report.reason;
  EXPECT_NEAR(alone.F_start, 1e-3 * step, 1e-9 * step);
  // Without the reference: 1e-10 of the prediction's residual, about 15
  // iterations at 0.2 each; with it, 1e-10 of the step's, about 10.
  EXPECT_LE(alone.F_end, 1e-10 * alone.F_start);
  EXPECT_LE(referred.F_end, 1e-10 * step);
  EXPECT_GT(referred.F_end, 1e-10 * alone.F_start); // it did stop earlier
  EXPECT_LE(referred.report.iterations + 3, alone.report.iterations);
  // A reference below the prediction's residual changes nothing.
  const Predicted below = solve_predicted(1e-3, 1e-4 * step);
  EXPECT_EQ(below.report.iterations, alone.report.iterations);
  EXPECT_EQ(below.F_end, alone.F_end);
  // A prediction already within the step's tolerance takes no iteration.
  const Predicted within = solve_predicted(5e-11, step);
  ASSERT_TRUE(within.report.converged) << within.report.reason;
  EXPECT_EQ(within.report.iterations, 0);
}

namespace
{
/// The linear F with its own Jacobian on a lagged LU under flexible GMRES
/// (whose norm is the true residual's, as with the single-precision LU),
/// keeping its KSP to read the tolerance of the last linear solve.
class FlexibleLagged : public InexactJacobian
{
public:
  mutable KSP ksp = nullptr;
  void configure(KSP k) const override
  {
    ksp = k;
    PC pc;
    check(KSPSetType(k, KSPFGMRES), "KSPSetType");
    check(KSPGetPC(k, &pc), "KSPGetPC");
    check(PCSetType(pc, PCLU), "PCSetType");
  }
};

/// The relative tolerance of the first (and only) linear solve of an
/// inexact Newton solve from the prediction x = b (1 + 1e-3), with
/// NewtonSolver::solve's `reference`.
double first_linear_rtol(double reference)
{
  solver::NewtonSolver::set_default_options(solver::NewtonSolver::Preconditioner::lagged);
  check(PetscOptionsSetValue(nullptr, "-snes_atol", "1e-30"), "PetscOptionsSetValue");
  FlexibleLagged problem;
  problem.scale = 1.0;
  problem.cube = 0.0;
  Vec x = prediction(problem, 1e-3);
  PetscReal rtol = 0;
  {
    solver::NewtonSolver newton(problem, solver::NewtonSolver::Preconditioner::lagged);
    newton.set_inexact(true);
    const solver::SolveReport r = newton.solve(x, reference);
    EXPECT_TRUE(r.converged) << r.reason;
    EXPECT_EQ(r.iterations, 1); // F linear, its own Jacobian
    check(KSPGetTolerances(problem.ksp, &rtol, nullptr, nullptr, nullptr), "KSPGetTolerances");
  }
  check(VecDestroy(&x), "VecDestroy");
  check(PetscOptionsClearValue(nullptr, "-snes_atol"), "PetscOptionsClearValue");
  solver::NewtonSolver::set_default_options(solver::NewtonSolver::Preconditioner::jacobian);
  return rtol;
}
} // namespace

TEST(PredictedStart, TheFirstLinearSolveStopsAtWhatTheStepsTestNeeds)
{
  // -ksp_rtol 1e-10 and -snes_rtol 1e-10. Without a reference the first
  // solve goes to -ksp_rtol (a linear step converges in one); with the
  // step's own residual |b|, 1e3 times the prediction's, Newton asks for
  // 1e-10 |b| and GMRES stops at half of it: 0.5 x 1e-10 |b| / (1e-3 |b|).
  EXPECT_DOUBLE_EQ(first_linear_rtol(0.0), 1e-10);
  EXPECT_NEAR(first_linear_rtol(std::hypot(b[0], b[1])), 5e-8, 1e-12);
}

namespace
{
/// F = A x - b, J = A: linear, with A set between solves (a step loop's
/// new tangent).
class Linear : public unit::TwoUnknowns
{
public:
  std::array<double, 4> A = {2, 0, 0, 1};
  std::array<double, 2> F(const std::array<double, 2>& x) override
  {
    return {A[0] * x[0] + A[1] * x[1] - b[0], A[2] * x[0] + A[3] * x[1] - b[1]};
  }
  std::array<double, 4> J(const std::array<double, 2>&) override { return A; }
  /// GMRES of one iteration on the LU (right-preconditioned, as the lagged
  /// default): exact on the LU of the Jacobian itself, short on the LU of
  /// another where P^-1 J has two eigenvalues and the right-hand side is
  /// not an eigenvector.
  void configure(KSP ksp) const override
  {
    check(KSPSetType(ksp, KSPGMRES), "KSPSetType");
    check(KSPSetPCSide(ksp, PC_RIGHT), "KSPSetPCSide");
    PC pc;
    check(KSPGetPC(ksp, &pc), "KSPGetPC");
    check(PCSetType(pc, PCLU), "PCSetType");
    PetscReal rtol, abstol, dtol;
    PetscInt max_it;
    check(KSPGetTolerances(ksp, &rtol, &abstol, &dtol, &max_it), "KSPGetTolerances");
    check(KSPSetTolerances(ksp, rtol, abstol, dtol, 1), "KSPSetTolerances");
  }
};
} // namespace

TEST(StaleLu, AFailedLinearSolveOnAStaleLuIsTriedOnAFreshOne)
{
  solver::NewtonSolver::set_default_options(solver::NewtonSolver::Preconditioner::lagged);
  Linear problem;
  Vec x = problem.create_vector();
  check(VecSet(x, 0.0), "VecSet");
  {
    solver::NewtonSolver newton(problem, solver::NewtonSolver::Preconditioner::lagged);
    newton.set_first_tangent(false); // each solve's first iteration on its own tangent
    // The first solve: the lagged LU is A's (the Jacobian at x = 0).
    const solver::SolveReport first = newton.solve(x);
    EXPECT_TRUE(first.converged) << first.reason;
    EXPECT_EQ(newton.factorizations(), 1);
    // A new A: the lagged LU is stale (P^-1 J = diag(2, 3), F = (1, 6)),
    // its GMRES iteration falls short, and the solve is tried again on the
    // LU of the new A, which solves it.
    problem.A = {4, 0, 0, 3};
    const solver::SolveReport second = newton.solve(x);
    EXPECT_TRUE(second.converged) << second.reason;
    EXPECT_EQ(newton.factorizations(), 2);
    const std::array<double, 2> at = Linear::values(x);
    EXPECT_NEAR(at[0], b[0] / 4, 1e-10 * b[0]); // Newton's -snes_rtol on |F(x)|, dF/dx >= 1
    EXPECT_NEAR(at[1], b[1] / 3, 1e-10 * b[1]);
  }
  check(VecDestroy(&x), "VecDestroy");
  solver::NewtonSolver::set_default_options(solver::NewtonSolver::Preconditioner::jacobian);
}

namespace
{
/// The cubic F of InexactJacobian whose Jacobian evaluations fail from the
/// `fail_from`-th on (as a law at a point would), leaving the true matrix.
class FailingJacobian : public InexactJacobian
{
public:
  int fail_from = 2;
  bool jacobian(Vec x, Mat J_out) override
  {
    InexactJacobian::jacobian(x, J_out);
    return jacobians < fail_from;
  }
};
} // namespace

TEST(JacobianDomainError, AFailedJacobianFailsTheSolve)
{
  solver::NewtonSolver::set_default_options(solver::NewtonSolver::Preconditioner::jacobian);
  FailingJacobian problem;
  Vec x = problem.create_vector();
  check(VecSet(x, 0.0), "VecSet");
  solver::SolveReport report;
  {
    solver::NewtonSolver newton(problem, solver::NewtonSolver::Preconditioner::jacobian);
    report = newton.solve(x);
  }
  check(VecDestroy(&x), "VecDestroy");
  // The matrix is the true Jacobian, so Newton would converge on it (about
  // six iterations, TailReuse above): only the failure can stop it.
  EXPECT_FALSE(report.converged);
  EXPECT_EQ(report.reason.rfind("DIVERGED_JACOBIAN_DOMAIN", 0), 0u) << report.reason;
  EXPECT_LE(report.iterations, 2) << report.reason;
}

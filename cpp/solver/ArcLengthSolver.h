// Path following through limit points of the prescribed displacement
// (the snap-back after the adhesion peak, paper §2.2): indirect
// displacement control on the interface jump, a form of arc length.
//
// Unknowns: the displacement x and a load factor lambda that moves the
// prescribed dofs, u_c = g(lambda), affine in lambda (push-out: lambda is
// the push delta [mm], dg/dlambda = -1 at the tube's top z dofs), so that
// F is affine in lambda with e = -dF/dlambda (on the whole model: e = dg/
// dlambda at the constrained rows, 0 elsewhere; on the condensed interface
// system the bulk carries the load to every row). Equations:
//   F(x, lambda) = 0        equilibrium (constrained rows: x_c - g(lambda))
//   a . x = eta             control: a . x is the mean axial slip s [mm]
// Newton on the bordered system
//   [ J    -e ] [ dx      ]     [ F         ]
//   [ a^T   0 ] [ dlambda ] = - [ a . x - eta ]
// by block elimination, two solves with the same J:
//   J v1 = -F,   J v2 = e,
//   dlambda = -(a . x - eta + a . v1) / (a . v2),   dx = v1 + dlambda v2.
// The caller chooses the control increment of each step (driver/StepLoop.cpp:
// from the previous step, scaled to a path length in the (lambda, s) plane).
// The slip of a push-out only grows (damage and friction never pull the
// tube back), so a positive increment fixes the direction through a limit
// point in lambda, without the sign tests of the classical arc-length
// methods (Crisfield).
//
// Limits: the control must increase monotonically (no unloading); J is
// singular exactly at a limit point in lambda, where the elimination fails
// (the step is then cut and usually lands past it); the mean slip hides a
// localised event whose slip is small compared with the whole interface.
#pragma once

#include "NewtonSolver.h"
#include "NonlinearProblem.h"
#include <functional>
#include <petscksp.h>
#include <string>

namespace pushout::solver
{
class ArcLengthSolver
{
public:
  /// `control`: the coefficients a of the control functional (owned dofs).
  /// Tolerances and the iteration limit are SNES's (-snes_rtol, -snes_atol,
  /// -snes_stol, -snes_max_it; -arc_monitor prints each iteration); the linear solver is configured
  /// like SNES's KSP (-ksp_type, -pc_type, ...), with the same preconditioner policy as
  /// NewtonSolver.
  ArcLengthSolver(NonlinearProblem& problem, Vec control, NewtonSolver::Preconditioner pc,
                  int refactor_iterations);
  ~ArcLengthSolver();
  ArcLengthSolver(const ArcLengthSolver&) = delete;
  ArcLengthSolver& operator=(const ArcLengthSolver&) = delete;

  /// One step from the equilibrium (x, lambda) to the equilibrium with
  /// control value a . x + d_eta [mm]. On success
  /// x and lambda hold the next equilibrium; on failure x is left at the
  /// last iterate (the caller restores it) and lambda is unchanged.
  /// `set_load(lambda)` puts the constraints of load factor lambda into the
  /// problem; they must be affine in lambda.
  SolveReport step(Vec x, double& lambda, double d_eta,
                   const std::function<void(double)>& set_load);

  /// The control value a . x [mm].
  double control(Vec x) const;

  /// Numeric factorisations so far (for the summary).
  int factorizations() const { return _policy.factorizations(); }

private:
  /// F(x) into _F on every process's say; the norm of the reactions into
  /// `reactions`.
  bool residual(Vec x, double& reactions);
  /// Jacobian at x into the operators of the KSP (refreshing P by policy).
  bool setup_operators(Vec x);
  /// Solves J y = b; "" or why the linear solve failed even after
  /// refreshing P.
  std::string solve(Vec b, Vec y);

  NonlinearProblem& _problem;
  PreconditionerPolicy _policy;
  KSP _ksp = nullptr;
  Mat _J = nullptr, _P = nullptr;
  Vec _a = nullptr, _e = nullptr, _F = nullptr, _v1 = nullptr, _v2 = nullptr;
  double _rtol = 1e-10, _atol = 1e-10, _stol = 1e-14;
  PetscInt _max_it = 50;
  PetscBool _monitor = PETSC_FALSE; ///< -arc_monitor: print each iteration
};
} // namespace pushout::solver

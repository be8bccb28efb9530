// Path following through limit points of the prescribed displacement
// (the snap-back after the adhesion peak, paper §2.2): indirect control by
// a function c(x) of the unknowns (PathConstraint below), a form of arc
// length: the mean axial slip of the interface (linear, a . x) or the energy
// the joints release in the step (NonlinearProblem::energy_release:
// dissipation control, Gutierrez 2004; Verhoosel, Remmers & Gutierrez 2009).
//
// Unknowns: the displacement x and a load factor lambda that moves the
// prescribed dofs, u_c = g(lambda), affine in lambda (push-out: lambda is
// the push delta [mm], dg/dlambda = -1 at the tube's top z dofs), so that
// F is affine in lambda with e = -dF/dlambda (on the whole model: e = dg/
// dlambda at the constrained rows, 0 elsewhere; on the condensed interface
// system the bulk carries the load to every row). A load factor that enters
// the laws instead (the corrosion depth x of the oxide's expansion,
// specimen/Corrosion.h) makes F nonlinear in lambda: e is then the forward
// difference -(F(x, lambda + h) - F(x, lambda)) / h at every iterate
// (set_load_difference). Equations:
//   F(x, lambda) = 0        equilibrium (constrained rows: x_c - g(lambda))
//   c(x) = eta              control, a = dc/dx at the iterate
// Newton on the bordered system
//   [ J    -e ] [ dx      ]     [ F        ]
//   [ a^T   0 ] [ dlambda ] = - [ c(x) - eta ]
// by block elimination, two solves with the same J:
//   J v1 = -F,   J v2 = e,
//   dlambda = -(c(x) - eta + a . v1) / (a . v2),   dx = v1 + dlambda v2.
// The caller chooses the control increment of each step (stepping/StepLoop.cpp:
// from the previous step, scaled to a path length in the (lambda, s) plane).
// The slip of a push-out only grows (damage and friction never pull the
// tube back), and so does the energy released, so a positive increment fixes
// the direction through a limit point in lambda, without the sign tests of
// the classical arc-length methods (Crisfield).
//
// Limits: the control must increase monotonically (no unloading); J is
// singular exactly at a limit point in lambda, where the elimination fails
// (the step is then cut and usually lands past it); the mean slip hides a
// localised event whose slip is small compared with the whole interface
// (the energy released does not); the energy released is zero where the
// step is elastic, where a . v2 = 0 and the step cannot be controlled by it.
#pragma once

#include "NewtonSolver.h"
#include "NonlinearProblem.h"
#include <functional>
#include <optional>
#include <petscksp.h>
#include <string>
#include <vector>

namespace pushout::solver
{
/// The control function c(x) of path following.
class PathConstraint
{
public:
  virtual ~PathConstraint() = default;
  /// c(x) and dc/dx into `gradient` (the problem's space); false if an
  /// interface law failed. Collective.
  virtual bool evaluate(Vec x, double& value, Vec gradient) = 0;
};

/// c(x) = a . x, a constant functional (the mean axial slip [mm]).
class LinearConstraint : public PathConstraint
{
public:
  /// Keeps a copy of `a`.
  explicit LinearConstraint(Vec a);
  ~LinearConstraint();
  LinearConstraint(const LinearConstraint&) = delete;
  LinearConstraint& operator=(const LinearConstraint&) = delete;
  bool evaluate(Vec x, double& value, Vec gradient) override;
  /// a . x
  double value(Vec x) const;
  /// Adds beta a to y.
  void add_to(Vec y, double beta) const;

private:
  Vec _a = nullptr;
};

/// c(x) = G(x) + beta a . x: the energy the joints release from the
/// committed state [N mm] (NonlinearProblem::energy_release) plus beta
/// times a linear functional, the mean axial slip [mm] with beta [N]. Where
/// nothing dissipates yet (elastic loading before a peak) G and its
/// gradient vanish and the slip term keeps the step controllable; where the
/// joints soften G dominates.
class EnergyReleaseConstraint : public PathConstraint
{
public:
  /// Keeps a copy of `slip`.
  EnergyReleaseConstraint(NonlinearProblem& problem, Vec slip) : _problem(problem), _slip(slip) {}
  bool evaluate(Vec x, double& value, Vec gradient) override;
  /// beta [N].
  void set_slip_weight(double beta) { _beta = beta; }

private:
  NonlinearProblem& _problem;
  LinearConstraint _slip;
  double _beta = 0;
};

class ArcLengthSolver
{
public:
  /// `control`: the control function c, a vector `like` of the problem's
  /// space to copy the layout from. Tolerances and the iteration limit are SNES's (-snes_rtol,
  /// -snes_atol, -snes_stol, -snes_max_it; a step also fails when 10 iterations have not halved
  /// the smallest |F| so far; -arc_monitor prints each iteration); the linear solver is configured
  /// like SNES's KSP (-ksp_type, -pc_type, ...), with the same preconditioner policy as
  /// NewtonSolver.
  ArcLengthSolver(NonlinearProblem& problem, PathConstraint& control,
                  NewtonSolver::Preconditioner pc, int refactor_iterations);
  ~ArcLengthSolver();
  ArcLengthSolver(const ArcLengthSolver&) = delete;
  ArcLengthSolver& operator=(const ArcLengthSolver&) = delete;

  /// One step from the equilibrium (x, lambda) to the equilibrium with
  /// control value c(x) + d_eta. On success
  /// x and lambda hold the next equilibrium; on failure x is left at the
  /// last iterate (the caller restores it) and lambda is unchanged.
  /// `set_load(lambda)` puts the constraints of load factor lambda into the
  /// problem; they must be affine in lambda. `max_dlambda` (> 0) bounds the
  /// change of lambda of each Newton iteration (a trust region for a control
  /// whose linearisation at the start sees few of the points that will
  /// dissipate; 0: none).
  ///
  /// With `loose`, a step whose iterations stall (NewtonHistory.h) ends at
  /// its best iterate if that is nearly in equilibrium: |F| at most `loose_rtol` of
  /// the reactions, the control within `loose_control` of the step's
  /// increment (SolveReport::loose; loose_convergence). That happens where
  /// cracks sit on the kink between their loading and their secant
  /// unloading (docs/cracking.md, "Still to come" 3): a piecewise smooth
  /// system whose Newton iterates take the kinks' sides in turn, in cycles
  /// of 2 to 8 iterates whose |F| halves with the step, so no cut passes.
  ///
  /// `eta_from`: where (x, lambda) is a prediction of the step's end, not
  /// the equilibrium it starts from, the control value of that equilibrium
  /// (the target is eta_from + d_eta); by default c(x). `max_dlambda` then
  /// bounds the first correction from the prediction.
  SolveReport step(Vec x, double& lambda, double d_eta, const std::function<void(double)>& set_load,
                   double max_dlambda = 0, bool loose = false,
                   std::optional<double> eta_from = std::nullopt);

  /// |F| over the norm of the reactions at which a stalled step's best
  /// iterate ends it (step): 1e-5, 1e5 times -snes_rtol, and a millionth
  /// of the push force on the study's meshes (the reactions' 2-norm is
  /// about a tenth of it), far below the discretisation's error (~1 %).
  static constexpr double loose_rtol = 1e-5;
  /// |c(x) - eta| over the step's control increment at which it does: 1 %.
  /// The control only picks where along the equilibrium path the step
  /// ends, and the next step measures its control from there.
  static constexpr double loose_control = 1e-2;
  /// |c(x) - eta| over the step's control increment at which a step
  /// converges (with |F| at its tolerance).
  static constexpr double control_rtol = 1e-8;
  /// The round-off floor of that test, in machine epsilons of the terms
  /// that c sums (control_tolerance): a step of a control increment
  /// within round-off of c can converge (through a snap-back the slip
  /// increments may fall to 1e-10 of the slip, where control_rtol of them
  /// is below c's round-off).
  static constexpr double control_round_off = 1e3;
  /// The tolerance of |c(x) - eta| for a step of control increment `d_eta`
  /// whose control sums terms of size `terms` (control_terms): control_rtol
  /// of d_eta, or control_round_off epsilons of the terms.
  static double control_tolerance(double d_eta, double terms);
  /// Why an iterate of |F| `fnorm` [N], with reactions of norm `reactions`
  /// [N] and its control off by `control_error` from a step's increment
  /// `d_eta`, ends a stalled step ("CONVERGED_AT_STALL ..."), or "" if it
  /// does not.
  static std::string loose_convergence(double fnorm, double reactions, double control_error,
                                       double d_eta);

  /// The load factor enters F nonlinearly (through the laws, not only the
  /// constraints): e by a forward difference of step `h` (> 0, in lambda's
  /// units) at every iterate, one more evaluation of F each. 0: affine (e
  /// once per step, exact).
  void set_load_difference(double h) { _fd_step = h; }

  /// The control value c(x) (evaluates the laws at x if c does); throws if
  /// a law failed.
  double control(Vec x);

  /// Numeric factorisations so far (for the summary).
  int factorizations() const { return _policy.factorizations(); }
  /// Krylov iterations of its linear solves so far (for the summary).
  std::int64_t linear_iterations() const { return _linear_iterations; }

private:
  /// F(x) into _F on every process's say; the norm of the reactions into
  /// `reactions`.
  bool residual(Vec x, double& reactions);
  /// Jacobian at x into the operators of the KSP (refreshing P by policy).
  bool setup_operators(Vec x);
  /// Solves J y = b; "" or why the linear solve failed even after
  /// refreshing P.
  std::string solve(Vec b, Vec y);

  /// The bordered Newton correction at x, whose residual is in _F, tangent
  /// e in _e and control gradient in _a, with the control c - eta =
  /// `c_minus_eta`: dx into _v1 and d lambda into `dlambda` (at most
  /// `max_dlambda` in size if positive); "" or why it failed.
  std::string correction(Vec x, double c_minus_eta, double max_dlambda, double& dlambda);
  /// sum |a_i x_i| at the iterate x, whose control gradient a is in _a:
  /// the size of the terms that c sums (its linearisation's, if c is not
  /// linear) [c's unit].
  double control_terms(Vec x);
  /// c(x) into `value`, dc/dx into _a, agreed on by every process.
  bool constraint(Vec x, double& value);
  /// e = -dF/dlambda at (x, lambda) into _e, and F(x, lambda) into _F, with
  /// the load of lambda set; false if a law failed.
  bool load_direction(Vec x, double lambda, const std::function<void(double)>& set_load,
                      double& reactions);
  /// An iterate (x, lam): F into _F (e into _e where it moves with the
  /// iterate), the load of lam set, |F| into `fnorm`, the control into `c`
  /// and its gradient into _a; "" or why it failed.
  std::string iterate(Vec x, double lam, const std::function<void(double)>& set_load,
                      double& reactions, double& fnorm, double& c);

  void set_up(NonlinearProblem& problem); ///< the constructor's work
  void release() noexcept;                ///< destroys what set_up made

  NonlinearProblem& _problem;
  PathConstraint& _control;
  PreconditionerPolicy _policy;
  std::int64_t _linear_iterations = 0; ///< linear_iterations()
  KSP _ksp = nullptr;
  Mat _J = nullptr, _P = nullptr;
  Vec _a = nullptr, _e = nullptr, _F = nullptr, _v1 = nullptr, _v2 = nullptr;
  Vec _w = nullptr;    ///< scratch (control_tolerance)
  double _fd_step = 0; ///< set_load_difference [lambda's unit]
  double _rtol = 1e-10, _atol = 1e-10, _stol = 1e-14;
  PetscInt _max_it = 50;
  PetscBool _monitor = PETSC_FALSE; ///< -arc_monitor: print each iteration
};
} // namespace pushout::solver

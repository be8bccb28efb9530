// Path following (loading.control = "arc_length"): indirect displacement
// control of the push by the mean axial slip of the interface (de Borst
// 1987), through a snap-back where the push delta must decrease
// (solver/PathFollower.h; docs/numerics.md, "Path following").
#include "StepLoop.h"
#include "StepLoopShared.h"
#include "TestHooks.h"
#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>

namespace pushout::stepping
{
using namespace detail;

solver::SolveReport StepLoop::load_factor_step(double lambda_from, double lambda_to,
                                               double extrapolation)
{
  _scenario.apply_load_factor(lambda_to, _equilibrium);
  set_crack_extrapolation(extrapolation);
  set_time_increment(lambda_to - lambda_from);
  _equilibrium.apply_constraints(_x);
  return _solver.solve(_x);
}

namespace
{
/// The least slip increment of a step, as a share of its length: where the
/// path turns vertical (delta falls at a nearly constant slip, as while
/// IMPL-EX cracks relax step by step through a snap), the scaled slip
/// increment would shrink by the same ratio every step, down to the
/// slip's round-off.
constexpr double min_slip_share = 1e-6;
} // namespace

/// The steps of path following, one member function per part of a step
/// (as DissipationSteps).
class StepLoop::PathSteps
{
public:
  PathSteps(StepLoop& loop, const LoadFactorPath& p, const solver::Vector& slip_functional);
  /// All steps; false if one failed or a signal stopped the run (the
  /// summary's message says which).
  bool run();

private:
  /// One try of a step from the committed state at _lambda.
  struct Try
  {
    solver::SolveReport rep;
    double lambda_new;     ///< the push it reached [mm]
    double increment;      ///< of the try's control (check_step_error) [mm]
    bool replaced = false; ///< a converged step past lambda_final replaced by a step to it
  };
  /// Step k: a step of delta (the first, or steps of delta to
  /// lambda_final), else a step of the slip; one past lambda_final is
  /// replaced by a step of delta to it.
  Try try_step(int k);
  /// Records and commits converged step k; false (reverted, with the
  /// summary's message) if the mean slip did not grow.
  bool accept(int k, const Try& t, const StepErrorCheck& checked);
  /// After a failed try of step k: reverted and cut; false if it cannot be
  /// cut again.
  bool failed(int k, const Try& t, const StepErrorCheck& checked);
  /// A step of delta for the stepper's increment `increment` (the first
  /// step, or steps of delta to lambda_final) [mm].
  double next_delta_step(double increment) const
  {
    return std::min({increment * _h_nominal, _delta_cap, _lambda_final - _lambda});
  }

  StepLoop& _loop;
  const LoadFactorPath& _p;
  const double _lambda_final, _h_nominal; ///< [mm]
  solver::PathFollower _path;
  const SolverCounts _count{_loop._summary, _path};
  Stepper _stepper;
  double _lambda = 0.0, _slip;                                 ///< of the committed state [mm]
  double _d_lambda_prev = 0.0, _d_slip_prev = 0.0;             ///< the last converged step [mm]
  bool _last_predicts = false;                                 ///< the last step predicts the next
  bool _by_delta = false;                                      ///< steps of delta to lambda_final
  double _delta_cap = std::numeric_limits<double>::infinity(); ///< of a step of delta [mm]
  int _cuts = 0;                                               ///< of the step being tried
};

StepLoop::PathSteps::PathSteps(StepLoop& loop, const LoadFactorPath& p,
                               const solver::Vector& slip_functional)
    : _loop(loop), _p(p), _lambda_final(p.lambda_final), _h_nominal(p.h_nominal),
      _path(loop._solver, slip_functional),
      _stepper(loop._max_cuts, easy_tries(loop._equilibrium.model(), true)),
      _slip(_path.control(loop._x))
{
}

bool StepLoop::PathSteps::run()
{
  for (int k = 1; _lambda < _lambda_final;)
  {
    if (_loop.stop_requested() || !_loop.within_step_limit(_p, k, _lambda, "path following"))
      return false;
    Try t = try_step(k);
    _loop.test_fail_implicit_try(t.rep);
    if (t.rep.converged && t.lambda_new == _lambda_final && test_fail_step_to_final())
    {
      t.rep.converged = false;
      t.rep.reason = "failed by a test hook (PUSHOUT_TEST_FAIL_TO_FINAL)";
    }
    _loop._summary.newton_iterations += t.rep.iterations;
    const StepErrorCheck checked =
        t.rep.converged ? _loop.check_step_error(t.rep, t.increment, _stepper) : StepErrorCheck{};
    if (t.rep.converged)
    {
      if (!accept(k, t, checked))
        return false;
      ++k;
      continue;
    }
    if (!failed(k, t, checked))
      return false;
  }
  return true;
}

StepLoop::PathSteps::Try StepLoop::PathSteps::try_step(int k)
{
  const double h = _stepper.increment() * _h_nominal; // [mm]
  Try t{{}, _lambda, h, false};
  if (k == 1 || _by_delta)
  {
    t.increment = next_delta_step(_stepper.increment());
    t.lambda_new = t.increment == _lambda_final - _lambda ? _lambda_final : _lambda + t.increment;
    t.rep = _loop.load_factor_step(_lambda, t.lambda_new,
                                   _last_predicts ? extrapolation_ratio(t.increment, _d_lambda_prev)
                                                  : 0.0);
    return t;
  }
  const double d_slip = std::max(_d_slip_prev * h / std::hypot(_d_lambda_prev, _d_slip_prev),
                                 min_slip_share * h); // [mm]
  const double r = d_slip / _d_slip_prev;
  _loop.set_time_increment(h);
  _loop.set_crack_extrapolation(_last_predicts ? extrapolation_ratio(d_slip, _d_slip_prev) : 0.0);
  if (_last_predicts && !test_no_step_prediction() && _loop.extrapolate(r))
    t.lambda_new = _lambda + r * _d_lambda_prev; // the secant prediction
  const auto set_load = [&](double lambda)
  { _loop._scenario.apply_load_factor(lambda, _loop._equilibrium); };
  t.rep = _path.step(_loop._x, t.lambda_new, d_slip, set_load, 0, false, _slip);
  if (t.rep.converged && t.lambda_new > _lambda_final)
  {
    // The fraction f of the try that reaches lambda_final grows the
    // cracks by about f of the try's extrapolation.
    const double f = (_lambda_final - _lambda) / (t.lambda_new - _lambda);
    _loop._summary.newton_iterations += t.rep.iterations;
    _loop.revert();
    t.lambda_new = _lambda_final;
    t.increment = _lambda_final - _lambda;
    t.replaced = true;
    t.rep = _loop.load_factor_step(_lambda, t.lambda_new,
                                   _last_predicts ? extrapolation_ratio(f * d_slip, _d_slip_prev)
                                                  : 0.0);
  }
  return t;
}

bool StepLoop::PathSteps::accept(int k, const Try& t, const StepErrorCheck& checked)
{
  const double slip_new = _path.control(_loop._x);
  if (!(slip_new > _slip))
  {
    _loop.revert();
    _loop._summary.message = "path following: the mean slip did not grow in step " +
                             std::to_string(k) + "; the push cannot be followed by slip control";
    return false;
  }
  _loop._recorder.record(_loop._x, t.rep.iterations, _cuts, k,
                         0); // before the commit: StepRecorder.h
  ++_loop._summary.steps;
  _loop.count_step_error(checked, "path-following step " + std::to_string(k));
  _loop.commit();
  _d_lambda_prev = t.lambda_new - _lambda;
  _d_slip_prev = slip_new - _slip;
  _lambda = t.lambda_new;
  _slip = slip_new;
  _last_predicts = !checked.jump;
  _delta_cap = std::numeric_limits<double>::infinity();
  _stepper.converged(t.rep.iterations, checked.may_grow());
  _cuts = 0;
  return true;
}

bool StepLoop::PathSteps::failed(int k, const Try& t, const StepErrorCheck& checked)
{
  _loop.revert();
  if (t.replaced || _by_delta)
  {
    // A retry of the step to lambda_final would be the same step: steps
    // of delta from here, the next cut as this one failed.
    if (!_by_delta && _loop._report.talk())
      std::cout << "path-following step " << k << ": the step to delta = " << _lambda_final * 1e3
                << " um failed; steps of delta to it" << std::endl;
    _by_delta = true;
    _delta_cap = checked.cut_factor() * t.increment;
  }
  // The size cut_back names: a length, or a step of delta (the next try's
  // after a cut; the failed try's where the stepper cannot cut further
  // and its increment stays as it was).
  const double tried = _stepper.increment();
  const Words length = sized("a length of", _h_nominal, "mm");
  const Words step_of_delta = [&](double s)
  { return sized("a step of delta of", 1.0, "mm")(s < tried ? next_delta_step(s) : t.increment); };
  return _loop.cut_back(_stepper, _cuts, "path-following step " + std::to_string(k), t.rep.reason,
                        _by_delta ? step_of_delta : length, checked.cut_factor()) != Retry::stop;
}

/// Path following (solver/PathFollower.h) in steps of length
/// h = lambda_final / steps in the plane (lambda, s) of the push delta and
/// the mean slip [mm]. The first step is displacement-controlled (delta =
/// h); each later one prescribes the slip increment of the previous step
/// scaled to length h,  ds = ds_prev h / |(dlambda_prev, ds_prev)|  (at
/// least min_slip_share h), which depends only on converged states (not on
/// the tangent at a kink of the laws). Each starts from a secant
/// prediction: the last step's increment of x and lambda scaled to its
/// length (on the control's target, which is linear in x); the iterates
/// converge in one or two where the step is smooth. Failed steps are
/// halved, easy ones grow back (Stepper.h). The step that would pass
/// lambda_final is replaced by a displacement-controlled step to exactly
/// lambda_final; if that fails, steps of delta, cut as it failed, go on to
/// lambda_final. IMPL-EX cracks (docs/cracking.md) extrapolate the last
/// committed step's growth by the ratio of the step's slip increment to
/// that step's (of delta for a step of delta), at most max_extrapolation,
/// and are checked and cut as under displacement control (check_step_error).
/// Nothing is predicted into the first step (the corrosion stage's growth
/// is not the push's) nor after a jump (its increment is the snap's).
bool StepLoop::path_following()
{
  LoadFactorPath p;
  if (!begin_load_factor_path("path following", p))
    return false;
  forget_step_error_misses();
  const solver::Vector slip(_equilibrium.model().mean_axial_slip_functional());
  return PathSteps(*this, p, slip).run();
}
} // namespace pushout::stepping

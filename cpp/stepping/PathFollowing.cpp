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
/// and are checked and cut as under displacement control (check_implex).
/// Nothing is predicted into the first step (the corrosion stage's growth
/// is not the push's) nor after a jump (its increment is the snap's).
bool StepLoop::path_following()
{
  LoadFactorPath p;
  if (!begin_load_factor_path("path following", p))
    return false;
  forget_implex_misses();
  const solver::Vector a(_equilibrium.model().mean_axial_slip_functional());
  solver::PathFollower path(_solver, a);
  const SolverCounts count{_summary, path};
  const double lambda_final = p.lambda_final, h_nominal = p.h_nominal; // [mm]
  const auto set_load = [&](double lambda) { _scenario.apply_load_factor(lambda, _equilibrium); };
  const auto length = sized("a length of", h_nominal, "mm");
  Stepper stepper(_max_cuts, easy_tries(_equilibrium.model(), true));
  double lambda = 0.0, slip = path.control(_x);               // of the committed state [mm]
  double d_lambda_prev = 0.0, d_slip_prev = 0.0;              // the last converged step [mm]
  bool last_predicts = false;                                 // the last step predicts the next
  bool by_delta = false;                                      // steps of delta to lambda_final
  double delta_cap = std::numeric_limits<double>::infinity(); // of a step of delta [mm]
  int cuts = 0;
  // A step of delta for the stepper's increment (the first step, or steps
  // of delta to lambda_final) [mm].
  const auto next_delta_step = [&](double increment) {
    return std::min({increment * h_nominal, delta_cap, lambda_final - lambda});
  };
  for (int k = 1; lambda < lambda_final;)
  {
    if (stop_requested() || !within_step_limit(p, k, lambda, "path following"))
      return false;
    const double h = stepper.increment() * h_nominal; // [mm]
    double lambda_new = lambda;
    double increment = h; // of the try's control (check_implex) [mm]
    bool replaced = false;
    solver::SolveReport rep;
    if (k == 1 || by_delta)
    {
      increment = next_delta_step(stepper.increment());
      lambda_new = increment == lambda_final - lambda ? lambda_final : lambda + increment;
      rep = load_factor_step(lambda, lambda_new,
                             last_predicts ? extrapolation_ratio(increment, d_lambda_prev) : 0.0);
    }
    else
    {
      const double d_slip = std::max(d_slip_prev * h / std::hypot(d_lambda_prev, d_slip_prev),
                                     min_slip_share * h); // [mm]
      const double r = d_slip / d_slip_prev;
      set_time_increment(h);
      set_crack_extrapolation(last_predicts ? extrapolation_ratio(d_slip, d_slip_prev) : 0.0);
      if (last_predicts && !test_no_step_prediction() && extrapolate(r))
        lambda_new = lambda + r * d_lambda_prev; // the secant prediction
      rep = path.step(_x, lambda_new, d_slip, set_load, 0, false, slip);
      if (rep.converged && lambda_new > lambda_final)
      {
        // The fraction f of the try that reaches lambda_final grows the
        // cracks by about f of the try's extrapolation.
        const double f = (lambda_final - lambda) / (lambda_new - lambda);
        _summary.newton_iterations += rep.iterations;
        revert();
        lambda_new = lambda_final;
        increment = lambda_final - lambda;
        replaced = true;
        rep = load_factor_step(lambda, lambda_new,
                               last_predicts ? extrapolation_ratio(f * d_slip, d_slip_prev) : 0.0);
      }
    }
    if (rep.converged && lambda_new == lambda_final && test_fail_step_to_final())
    {
      rep.converged = false;
      rep.reason = "failed by a test hook (PUSHOUT_TEST_FAIL_TO_FINAL)";
    }
    _summary.newton_iterations += rep.iterations;
    const ImplexCheck implex =
        rep.converged ? check_implex(rep, increment, stepper) : ImplexCheck{};
    if (rep.converged)
    {
      const double slip_new = path.control(_x);
      if (!(slip_new > slip))
      {
        revert();
        _summary.message = "path following: the mean slip did not grow in step " +
                           std::to_string(k) + "; the push cannot be followed by slip control";
        return false;
      }
      _recorder.record(_x, rep.iterations, cuts, k, 0); // before the commit: StepRecorder.h
      ++_summary.steps;
      count_implex(implex);
      commit();
      d_lambda_prev = lambda_new - lambda;
      d_slip_prev = slip_new - slip;
      lambda = lambda_new;
      slip = slip_new;
      last_predicts = !implex.jump;
      delta_cap = std::numeric_limits<double>::infinity();
      stepper.converged(rep.iterations, implex.may_grow());
      cuts = 0;
      ++k;
      continue;
    }
    revert();
    if (replaced || by_delta)
    {
      // A retry of the step to lambda_final would be the same step: steps
      // of delta from here, the next cut as this one failed.
      if (!by_delta && _report.talk())
        std::cout << "path-following step " << k << ": the step to delta = " << lambda_final * 1e3
                  << " um failed; steps of delta to it" << std::endl;
      by_delta = true;
      delta_cap = implex.cut_factor() * increment;
    }
    // The size cut_back names: a length, or a step of delta (the next try's
    // after a cut; the failed try's where the stepper cannot cut further
    // and its increment stays as it was).
    const double tried = stepper.increment();
    const Words step_of_delta = [&](double s)
    { return sized("a step of delta of", 1.0, "mm")(s < tried ? next_delta_step(s) : increment); };
    if (!cut_back(stepper, cuts, "path-following step " + std::to_string(k), rep.reason,
                  by_delta ? step_of_delta : Words(length), implex.cut_factor()))
      return false;
  }
  return true;
}
} // namespace pushout::stepping

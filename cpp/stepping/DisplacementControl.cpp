// Displacement control (loading.control = "displacement"): nominal steps of
// the load parameter, each tried whole and, when Newton fails, retried from
// the committed state in halves, grown back after easy steps (Stepper.h;
// docs/numerics.md, "Adaptive stepping"). Step 0 and the corrosion stage
// run the same steps. An unloading segment of the push that ends where the
// force falls to zero (docs/results.md, "Unload and reload") ends at the
// load parameter ZeroForceSearch.h finds; its tries are solved here.
#include "../common/petsc_check.h"
#include "StepLoop.h"
#include "StepLoopShared.h"
#include "TestHooks.h"
#include "ZeroForceSearch.h"
#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>
#include <sstream>

namespace pushout::stepping
{
using namespace detail;

namespace
{
/// Unloading at zero force (loading.unload_to): the force's zero is found
/// to this fraction of the largest push force so far (ZeroForceSearch.h).
constexpr double zero_force_tolerance = 1e-6;
/// The cracks' step error (IMPL-EX's, or the implicit cracks' held to
/// theirs): a cut whose error stays above this fraction of the error before
/// it (a first-order error halves) finds a jump of the state
/// (StepLoop::check_step_error).
constexpr double jump_error_fall = 0.75;
/// The implicit cracks' step error (cracking.implicit_tolerance) cuts a
/// step down to this fraction of a nominal one [nominal steps] (or to the
/// smallest loading.max_cuts allows, if larger), and takes it there: its
/// predictor misses where thousands of cracks turn between loading and
/// unloading whatever the step (as IMPL-EX's error has a floor there), and
/// steps held at the smallest size leave Newton no cut when it cycles on a
/// kink (the centred tube, beta 3, seed 5, at 0.0025: down to 2^-10 of a
/// step by x = 9 um, then stopped there). A smaller try that did not cut
/// the error by a quarter is taken too, as IMPL-EX's jump is.
constexpr double implicit_error_smallest_step = 1.0 / 64;
} // namespace

/// Displacement control of the push.
bool StepLoop::push_by_displacement()
{
  const int steps = _scenario.steps();
  return nominal_steps(
      {"load step", steps, [&](double s) { _scenario.apply_load(s, _equilibrium); },
       [&](double s0, double s1) { return _scenario.time_at(s1) - _scenario.time_at(s0); },
       [&](int iterations, int cuts, int k, double)
       {
         _recorder.record(_x, iterations, cuts, k, steps);
         ++_summary.steps;
       },
       true, extrapolation([&](double s) { return _scenario.prescribed_at(s); })});
}

/// Each nominal step is tried whole and cut in halves (from the committed
/// state) when Newton fails; increments grow back after easy convergence
/// (Stepper.h).
bool StepLoop::nominal_steps(const Stage& stage)
{
  const int steps = stage.steps;
  Stepper stepper(_max_cuts, easy_tries(_equilibrium.model()));
  forget_step_error_misses(); // another stage, another parameter
  const auto step_name = [&](int k)
  { return steps == 1 ? stage.step_name : stage.step_name + " " + std::to_string(k); };
  const Words fraction = [](double increment)
  {
    std::ostringstream s;
    s << increment << " of a step";
    return s.str();
  };
  // The load force of the committed state and its largest magnitude so far
  // [N], for unloading that ends at zero force.
  const model::Model& model = _equilibrium.model();
  double P = stage.zero_force_ends ? _scenario.load_force(model) : 0.0, P_peak = std::abs(P);
  double s = 0.0;
  // Stage::extrapolate_by: the last converged step's increment of the load
  // (0: none to extrapolate).
  double d_load_last = 0;
  for (int k = 1; k <= steps; ++k)
  {
    int cuts = 0;
    while (s < double(k) - step_tolerance)
    {
      if (stop_requested())
        return false;
      const double s_try = stepper.next(s, double(k));
      stage.apply(s_try);
      set_time_increment(stage.duration(s, s_try));
      const double ratio =
          d_load_last != 0 ? (stage.extrapolate_by(s_try) - stage.extrapolate_by(s)) / d_load_last
                           : 0.0;
      set_crack_extrapolation(ratio);
      solver::SolveReport rep = solve_predicted(ratio);
      _summary.newton_iterations += rep.iterations;
      // The cracks' step error is first order in the step: a step that missed its
      // tolerance is cut at once to one that should meet it (0.8 of the
      // ratio), and one whose error would not stay under it at twice the
      // increment does not grow, unless it jumped (smaller steps do not
      // help there).
      const StepErrorCheck checked =
          rep.converged ? check_step_error(rep, s_try - s, stepper) : StepErrorCheck{};
      if (rep.converged && stage.zero_force_ends)
      {
        const double P_try = _scenario.load_force(model);
        // (a force within the search's tolerance of zero is zero: an
        // unloading that reaches it at its vertex, as a secant one to the
        // origin, ends there whatever the round-off's sign)
        const double tol = zero_force_tolerance * std::max(P_peak, 1e-300); // [N]
        if (_scenario.ends_at_zero_force(k) && P >= -tol && P_try < -tol)
        {
          // The device cannot pull: the unloading ends where P = 0, and
          // the next segment starts there.
          revert();
          double s_zero;
          if (!zero_force_step(stage, k, cuts, s, P, s_try, P_try, tol, s_zero))
            return false;
          const double delta = _scenario.prescribed_at(s_zero);
          _summary.permanent_displacements_mm.push_back(delta);
          if (_report.talk())
            std::cout << "step " << k << ": the push force fell to zero at delta = " << delta * 1e3
                      << " um (permanent displacement); the unloading ends there" << std::endl;
          s = _scenario.end_segment_at(k, s_zero);
          d_load_last = 0; // a new segment: nothing to extrapolate
          k = int(std::lround(s));
          P = _scenario.load_force(model);
          break;
        }
        P = P_try;
        P_peak = std::max(P_peak, std::abs(P));
      }
      if (rep.converged)
      {
        stage.record(rep.iterations, cuts, k, s_try); // before the commit: StepRecorder.h
        // After a jump the last increment predicts nothing (its cracks'
        // growth is the snap's).
        if (stage.extrapolate_by)
          d_load_last = checked.jump ? 0.0 : stage.extrapolate_by(s_try) - stage.extrapolate_by(s);
        count_step_error(checked, step_name(k));
        commit();
        s = s_try;
        stepper.converged(rep.iterations, checked.may_grow());
        continue;
      }
      revert();
      if (cut_back(stepper, cuts, step_name(k), rep.reason, fraction, checked.cut_factor(),
                   s_try - s) == Retry::stop)
        return false;
    }
  }
  return true;
}

/// The search (find_zero_force) chooses the load parameters; each try here
/// is one step from the committed state at s0 (a path-dependent law sees
/// one increment, as in the try that overshot), reverted before the next.
bool StepLoop::zero_force_step(const Stage& stage, int k, int cuts, double s0, double P0, double s1,
                               double P1, double tol, double& s)
{
  const double s_committed = s0;
  solver::SolveReport rep; // of the last try
  bool stopped = false;    // a signal stopped the run before a try
  bool tried = false;      // the state holds the last try's converged step
  const auto try_at = [&](double s_try) -> std::optional<double>
  {
    if (tried)
      revert();
    tried = false;
    if (stop_requested())
    {
      stopped = true;
      return std::nullopt;
    }
    stage.apply(s_try);
    set_time_increment(stage.duration(s_committed, s_try));
    set_crack_extrapolation(0); // the push turned back: nothing to extrapolate
    _equilibrium.apply_constraints(_x);
    rep = _solver.solve(_x);
    _summary.newton_iterations += rep.iterations;
    if (!rep.converged || !crack_band_updated(rep))
    {
      revert();
      // A signal fails the solve (NewtonSolver: a domain error at the next
      // residual): the run stops for it, not for a failed try.
      stopped = stop_requested();
      return std::nullopt;
    }
    tried = true;
    return _scenario.load_force(_equilibrium.model());
  };
  const ZeroForceResult zero = find_zero_force(s0, P0, s1, P1, tol, try_at);
  s = zero.s;
  switch (zero.outcome)
  {
  case ZeroForceResult::Outcome::found:
    stage.record(rep.iterations, cuts, k, s); // before the commit: StepRecorder.h
    commit();
    forget_step_error_misses(); // a step found by its force, not by its error
    return true;
  case ZeroForceResult::Outcome::try_failed:
    if (!stopped) // else the summary says so
      _summary.message = "load step " + std::to_string(k) +
                         ": a try at the zero force of the unloading failed (" + rep.reason +
                         "); stopped";
    return false;
  default:
    revert();
    _summary.message = "load step " + std::to_string(k) + ": the zero force of the unloading was " +
                       "not found in " + std::to_string(zero.tries) + " tries; stopped";
    return false;
  }
}

std::function<double(double)> StepLoop::extrapolation(std::function<double(double)> load) const
{
  if (!_equilibrium.model().bulk_cracking())
    return {};
  return load;
}

namespace
{
/// What a crack band update that failed at `points` points says.
std::string update_failed_at(std::int64_t points)
{
  return "the crack band's update failed at " + std::to_string(points) +
         (points == 1 ? " point" : " points");
}
} // namespace

std::int64_t StepLoop::band_update_failures(double error, std::int64_t failed_points)
{
  if (_equilibrium.model().bulk_cracking()->implex_rescue())
    _rescue_error = error; // its reading, counted when it is committed (commit())
  return failed_points + (test_fail_crack_band_update() ? 1 : 0);
}

bool StepLoop::crack_band_updated(solver::SolveReport& rep)
{
  model::BulkCracking* bulk = _equilibrium.model().bulk_cracking();
  if (!bulk || !bulk->implex())
    return true;
  std::int64_t failed_points = 0;
  const double error = bulk->implex_error(failed_points); // the update commit() then keeps
  failed_points = band_update_failures(error, failed_points);
  if (failed_points == 0)
    return true;
  rep.converged = false;
  rep.reason = "IMPL-EX: " + update_failed_at(failed_points);
  return false;
}

StepLoop::StepErrorCheck StepLoop::check_step_error(solver::SolveReport& rep, double increment,
                                                    const Stepper& stepper, const char* why_taken)
{
  model::BulkCracking* bulk = _equilibrium.model().bulk_cracking();
  if (!bulk)
    return {};
  const bool rescue = bulk->implex_rescue();
  // (never in a rescue's step: BulkCracking::step_error_measured_only)
  const bool measured_only = bulk->step_error_measured_only();
  if (!(rescue || measured_only || bulk->step_tolerance() > 0))
    return {};
  std::int64_t failed_points = 0;
  const double error = bulk->step_error(failed_points);
  if (measured_only) // read, never cut for (count_step_error keeps the largest)
    return {.ratio = 0, .jump = false, .error = error, .said = {}, .measured_only = true};
  if (rescue)
  {
    // An IMPL-EX step in place of one that no cut passed (cut_back): at the
    // smallest step its error is measured and reported, not held (as
    // IMPL-EX's is taken there); a larger one (a try of another kind, a
    // step of lambda after an energy step that overshot) is held as
    // IMPL-EX's. The crack band's own update at its strain must hold at
    // every point.
    failed_points = band_update_failures(error, failed_points);
    if (failed_points == 0 &&
        (stepper.increment() <= jump_smallest_step || !(bulk->step_tolerance() > 0)))
      return {};
  }
  const std::string error_name = bulk->implex() ? "IMPL-EX error" : "the cracks' step error";
  StepErrorCheck c{error / bulk->step_tolerance(), false, error, {}};
  std::ostringstream why;
  if (failed_points > 0)
  {
    // The crack band's own update failed there: cut the step (as the
    // implicit cracks would), never take it.
    why << "IMPL-EX: " << update_failed_at(failed_points);
    c.ratio = 2;
  }
  else
  {
    // The error is first order in the step, but where the cracks snap back
    // under this control no step is small enough: the state jumps, and the
    // step is taken as a jump (summary.json implex_jumps or implicit_jumps)
    // once a smaller try than the last that missed did not cut the error by
    // a quarter, or at the smallest step loading.max_cuts allows where that
    // is small (jump_smallest_step) or right after a jump (the snap goes
    // on). A
    // larger smallest step that misses fails, as a Newton solve would: only
    // max_cuts stopped its cuts (taken, max_cuts = 0 put p 12 % off).
    const bool smaller = _error_missed > 0 && increment < 0.99 * _error_missed_increment;
    const bool snaps = smaller && error > jump_error_fall * _error_missed;
    const bool falling = smaller && !snaps; // a smaller try lowered the error
    const bool smallest = stepper.smallest() && (stepper.increment() <= jump_smallest_step ||
                                                 (_error_jumped && !falling));
    const bool implicit_floor =
        !bulk->implex() &&
        (stepper.increment() <= implicit_error_smallest_step || stepper.smallest());
    c.jump = c.ratio > 1 && (snaps || smallest || implicit_floor);
    if (c.jump && !bulk->implex())
      why_taken = snaps ? "a smaller step does not lower it"
                        : "the implicit cracks' steps are cut for their error down to 2^-6 of "
                          "a step";
    if (c.ratio <= 1 || c.jump)
    {
      if (c.jump) // said when the step is committed (count_step_error)
      {
        std::ostringstream said;
        said << error_name << " " << error;
        if (smaller)
          said << " (" << _error_missed << " before the last cut)";
        said << ": " << (why_taken ? why_taken : "the cracks snap back under this control")
             << "; the step is taken";
        c.said = said.str();
      }
      _error_missed = 0;
      return c;
    }
    _error_missed = error;
    _error_missed_increment = increment;
    why << error_name << " " << error << " > " << bulk->step_tolerance_key() << " "
        << bulk->step_tolerance();
    if (stepper.smallest()) // no smaller step to try: the run stops on this
      why << "; loading.max_cuts = " << _max_cuts << " stops the cuts at 2^-" << _max_cuts
          << " of a step before a smaller one showed that the error stops falling with the "
             "step, as where the cracks snap back: raise max_cuts (default 10) or "
          << bulk->step_tolerance_key();
  }
  rep.converged = false;
  rep.reason = why.str();
  return c;
}

void StepLoop::count_step_error(const StepErrorCheck& c, const std::string& step)
{
  _error_jumped = c.jump; // a committed step's: jumped or not
  if (!(c.ratio > 0) && !c.measured_only)
    return;
  // A rescue's IMPL-EX error is its own reading (commit()), not the
  // implicit cracks' step error.
  const model::BulkCracking* bulk = _equilibrium.model().bulk_cracking();
  if (!bulk->implex_rescue())
  {
    _summary.step_error_jumps += c.jump ? 1 : 0;
    _summary.step_error_max = std::max(_summary.step_error_max, c.error);
  }
  if (c.measured_only)
  {
    ++_unheld_steps;
    _unheld_steps_above += c.error > bulk->implex_tolerance() ? 1 : 0;
  }
  if (!c.said.empty() && _report.talk())
    std::cout << step << ": " << c.said << std::endl;
}

void StepLoop::note_unheld_step_error()
{
  if (_unheld_steps_above == 0) // (none without the implicit cracks read so)
    return;
  const model::BulkCracking* bulk = _equilibrium.model().bulk_cracking();
  std::ostringstream note;
  note << "the implicit cracks' steps were not held to their error (cracking.implicit_tolerance "
          "= 0): its estimate reached "
       << _summary.step_error_max << " (summary.json implicit_error_max), above IMPL-EX's "
       << "cracking.implex_tolerance = " << bulk->implex_tolerance() << " on "
       << _unheld_steps_above << " of " << _unheld_steps
       << " steps; cracking.implicit_tolerance = " << bulk->implex_tolerance()
       << " holds them to it, as IMPL-EX's are (docs/cracking.md, \"The implicit cracks' step "
          "error\")";
  _summary.notes.push_back(note.str());
  if (_report.talk())
    std::cout << "pushout: note: " << note.str() << std::endl;
}

void StepLoop::forget_step_error_misses()
{
  _error_missed = 0;
  _error_jumped = false;
}

void StepLoop::set_crack_extrapolation(double ratio)
{
  if (model::BulkCracking* bulk = _equilibrium.model().bulk_cracking())
    bulk->set_extrapolation(ratio);
}

bool StepLoop::extrapolate(double ratio)
{
  // Only forwards: where the load turns back (an unloading segment) the
  // last increment predicts nothing.
  if (!(ratio > 0) || !std::isfinite(ratio))
    return false;
  // x = x_c + r (x_c - x_before)
  _x.copy_from(_x_committed);
  petsc::check(VecAXPBY(_x, -ratio, 1 + ratio, _x_before), "VecAXPBY");
  return true;
}

solver::SolveReport StepLoop::solve_predicted(double ratio)
{
  // Newton's relative test of the step's own residual where the start is a
  // prediction (LoadStepSolver::solve).
  const bool predicted = extrapolate(ratio) && !test_no_prediction_reference();
  _equilibrium.apply_constraints(_x);
  if (predicted)
  {
    _x_unpredicted.copy_from(_x_committed);
    _equilibrium.apply_constraints(_x_unpredicted);
  }
  solver::SolveReport rep = _solver.solve(_x, predicted ? Vec(_x_unpredicted) : nullptr);
  test_fail_implicit_try(rep);
  return rep;
}

void StepLoop::test_fail_implicit_try(solver::SolveReport& rep) const
{
  const model::BulkCracking* bulk = _equilibrium.model().bulk_cracking();
  if (rep.converged && bulk && !bulk->implex() &&
      test_fail_implicit_row(_summary.corrosion_steps + _summary.steps))
  {
    rep.converged = false;
    rep.reason = "DIVERGED (PUSHOUT_TEST_FAIL_IMPLICIT_ROW)";
  }
}
} // namespace pushout::stepping

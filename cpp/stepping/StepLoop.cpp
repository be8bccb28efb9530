// The step loop (StepLoop.h): run() in the order of the algorithm, step 0,
// and what the controls share: commit and revert of the trial state, the
// cut of a failed step (Stepper.h; docs/numerics.md, "Adaptive
// stepping"), the agreement on a signal between tries, and the push by its
// load factor (path following and dissipation control). The controls are
// in files of their own (StepLoop.h lists them).
#include "StepLoop.h"
#include "../common/Interrupt.h"
#include "../common/mpi_errors.h"
#include "../record/NonFinite.h"
#include "StepLoopShared.h"
#include <array>
#include <iostream>
#include <optional>
#include <string_view>

namespace pushout::stepping
{
using namespace detail;

StepLoop::StepLoop(specimen::Scenario& scenario, specimen::Corrosion& corrosion,
                   solver::Equilibrium& equilibrium, solver::LoadStepSolver& solver,
                   StepRecorder& recorder, record::RunReport& report, int max_cuts,
                   int dissipation_steps)
    : _scenario(scenario), _corrosion(corrosion), _equilibrium(equilibrium), _solver(solver),
      _recorder(recorder), _report(report), _summary(report.summary()), _max_cuts(max_cuts),
      _dissipation_steps(dissipation_steps), _comm(equilibrium.model().comm()),
      _x(equilibrium.model().create_vector())
{
  _x.set(0.0);
  _x_committed = _x.duplicate();
  _x_committed.copy_from(_x);
  _x_before = _x.duplicate();
  _x_before.copy_from(_x);
  _x_unpredicted = _x.duplicate();
}

void StepLoop::time_linear_solve()
{
  _scenario.apply_load(1.0, _equilibrium);
  _equilibrium.apply_constraints(_x);
  _summary.linear_solve_s = _solver.time_linear_solve(_x);
  // Back to the start, and the model's last evaluation made there: the
  // timing's, at the first step's load, was what step 0's row read (and
  // committed) where no thermal step solves (loading.temperature_change 0).
  _scenario.apply_load(0.0, _equilibrium);
  _x.set(0.0);
  _equilibrium.apply_constraints(_x);
  const solver::Vector F(_equilibrium.model().create_vector());
  const bool evaluated = _equilibrium.residual(_x, F);
  _equilibrium.forget_trial_state();
  mpi::throw_if_any(_comm, !evaluated,
                    "solver.time_linear_solve: a law failed at the unloaded start");
  if (_report.talk())
    std::cout << "one linear solve: " << _summary.linear_solve_s << " s" << std::endl;
}

bool StepLoop::run(Control control)
{
  const bool done = run_stages(control);
  end_implex_rescue(); // one a stop left on (a signal, a stage that stopped)
  if (done)
    note_unheld_step_error();
  return done;
}

bool StepLoop::run_stages(Control control)
{
  try
  {
    // Step 0 and the corrosion stage end with the push's start recorded
    // (curve.csv row 0) before their last commit. Each stage names itself
    // where a signal stops it (the watcher's phase, and stop_requested()).
    std::optional<interrupt::Phase> phase;
    const auto enter = [&](const char* stage)
    {
      _stage = stage;
      phase.emplace(stage, interrupt::stop_grace_s); // the last one's ended first
    };
    _may_snap_back = control == Control::displacement && _scenario.has_load_factor() && softens();
    enter("step 0");
    if (!initial_step())
      return false;
    enter("corrosion steps");
    if (_corrosion.active() &&
        !(control == Control::dissipation ? corrode_by_dissipation() : corrode()))
    {
      // Stopped in the stage (a signal, a step that did not converge): the
      // cracks of its last committed step, as the push's start would have
      // had them (summary.json cracks, crack_pattern.csv).
      end_implex_rescue();
      revert();
      _corrosion.describe_cracks(_equilibrium, _x, _summary);
      return false;
    }
    enter("load steps");
    switch (control)
    {
    case Control::arc_length:
      return path_following();
    case Control::dissipation:
      return push_by_dissipation();
    default:
      return push_by_displacement();
    }
  }
  catch (const record::NonFiniteResult& e) // thrown on every process alike
  {
    _summary.message = std::string(e.what()) + "; stopped (not written)";
    // The state of the last committed step, as a stop in the stage leaves
    // it: in the corrosion stage its cracks too (summary.json cracks,
    // crack_pattern.csv), as the stage's own stop says them.
    end_implex_rescue();
    revert();
    if (std::string_view(_stage) == "corrosion steps")
      _corrosion.describe_cracks(_equilibrium, _x, _summary);
    return false;
  }
}

/// Step 0: the thermal step or preload, if the scenario has one, in parts
/// (its load scaled, cut in halves like a load step) when it does not
/// converge whole. It takes the pseudo-time of the push's first load step
/// (time_at(1) - time_at(0): with loading.step_growth the first, smallest,
/// step), so that a viscous damage layer damages in it as it would in that
/// step of the push (with dt = 0 its damage would freeze). With a corrosion stage, the
/// push starts after it.
bool StepLoop::initial_step()
{
  _scenario.apply_load(0.0, _equilibrium);
  // Step 0 is one row whatever its parts (their iterations summed; its
  // cuts, as a load step's row has them).
  const auto started = [&](int iterations, int cuts)
  {
    if (_corrosion.active())
      _corrosion.record(0.0, _equilibrium, _x, iterations, cuts, 0, true,
                        [&](int row) { _recorder.record_corrosion(row); });
    else
      start_push(iterations, cuts);
  };
  if (!_scenario.initial_solve())
  {
    started(0, 0);
    commit();
    return true;
  }
  const double step_time = _scenario.time_at(1.0) - _scenario.time_at(0.0);
  int iterations = 0; // of all its parts
  // Its parts (after a cut) start from the tangent at their start (the
  // committed state, or with cracking concrete its extrapolation, below):
  // where the thermal load starts a brittle layer softening, the last
  // part's converged tangent is its softening branch, a poor predictor of
  // the next (c = 2000 1/mm, f_t = 6 MPa, k = 1e5 N/mm^3 on the demo: step
  // 0 failed; with cracks too it converges, in fewer cuts and iterations
  // with the extrapolation than without: docs/numerics.md).
  const StartTangent start_tangent{_solver};
  // From the unloaded slice the first Newton step of the thermal load cracks
  // thousands of points the solution does not (cracking concrete): Newton
  // wandered at |F| ~ 1e4 N (43 iterations on the coarse corroded demo; 93
  // and two cuts on the paper's mesh). Solved first with no new cracks,
  // then with them.
  const CrackFreePredictor predictor{_solver};
  // Its load is linear in the fraction, so with cracking concrete a part
  // after a cut extrapolates the last part's increment, as a load step
  // does: the start, and IMPL-EX's prediction of the cracks that the
  // retraction opens (the cracking demo's step 0: 4 Newton iterations in
  // 4 tries, against 30 in 12 without; docs/cracking.md).
  return nominal_steps({"step 0 (initial/thermal step)", 1,
                        [&](double fraction)
                        { _scenario.apply_initial_load(fraction, _equilibrium); },
                        [&](double s0, double s1) { return (s1 - s0) * step_time; },
                        [&](int its, int cuts, int, double fraction)
                        {
                          iterations += its;
                          if (fraction >= 1.0 - step_tolerance)
                            started(iterations, cuts);
                        },
                        false, extrapolation([](double fraction) { return fraction; })});
}

void StepLoop::start_push(int iterations, int cuts)
{
  _recorder.end_corrosion(); // the corrosion stage's fields whole, their memory back
  _corrosion.describe_cracks(_equilibrium, _x, _summary);
  // The damage the thermal step and the corrosion stage left.
  const interface::Interface& itf = _equilibrium.model().interface();
  _summary.initial_damage.clear();
  for (std::size_t l = 0; l < itf.num_layers(); ++l)
    if (itf.softens(l))
    {
      std::array<double, 2> sum = {itf.damage_of(l)[0], itf.area()};
      double largest = itf.damage_of(l)[1];
      MPI_Allreduce(MPI_IN_PLACE, sum.data(), 2, MPI_DOUBLE, MPI_SUM, _comm);
      MPI_Allreduce(MPI_IN_PLACE, &largest, 1, MPI_DOUBLE, MPI_MAX, _comm);
      _summary.initial_damage.push_back({int(l), sum[0] / sum[1], largest});
    }
  _solver.set_bulk_needed(_recorder.bulk_needed());
  {
    const solver::ReadView x(_x);
    _scenario.start_loading(x.span());
  }
  _recorder.record(_x, iterations, cuts, 0, _scenario.steps()); // before the commit
}

void StepLoop::set_time_increment(double dt)
{
  for (interface::Interface* joints : _equilibrium.model().joints())
    joints->set_time_increment(dt);
  if (model::BulkCracking* cracking = _equilibrium.model().bulk_cracking())
    cracking->set_time_increment(dt);
}

void StepLoop::commit()
{
  for (interface::Interface* joints : _equilibrium.model().joints())
    joints->commit();
  if (model::BulkCracking* cracking = _equilibrium.model().bulk_cracking())
  {
    cracking->commit();
    if (cracking->implex_rescue()) // one IMPL-EX step stood in (cut_back)
    {
      ++_summary.implex_rescues;
      _summary.implex_rescue_error_max = std::max(_summary.implex_rescue_error_max, _rescue_error);
      cracking->set_implex_rescue(false);
      _solver.forget_tangent(); // the next implicit step starts from its own
      if (_report.talk())
        std::cout << "the IMPL-EX step's error " << _rescue_error
                  << " (cracking.implex_rescue); implicit cracks again" << std::endl;
    }
  }
  _x_before.copy_from(_x_committed);
  _x_committed.copy_from(_x);
  _report.publish();
}

void StepLoop::revert()
{
  for (interface::Interface* joints : _equilibrium.model().joints())
    joints->state().revert();
  if (model::BulkCracking* cracking = _equilibrium.model().bulk_cracking())
    cracking->revert();
  _x.copy_from(_x_committed);
  _solver.forget_tangent(); // it was the reverted state's
}

StepLoop::Retry StepLoop::cut_back(Stepper& stepper, int& cuts, const std::string& what,
                                   const std::string& reason, const Words& size, double factor,
                                   double tried)
{
  if (stop_requested())
    return Retry::stop;
  model::BulkCracking* cracking = _equilibrium.model().bulk_cracking();
  const bool rescuing = cracking && cracking->implex_rescue();
  if (stepper.failed(factor, tried)) // a rescue's try too, cut as IMPL-EX's
  {
    ++cuts;
    ++_summary.cuts;
    if (_report.talk())
    {
      // A push step ("load step 3") is said "step 3", as its progress line; a
      // stage of one step by its name ("load step", "corrosion step"), and
      // so is a corrosion step ("corrosion step 3": its progress line says
      // "corrosion 3/25").
      const std::size_t at =
          what.rfind("corrosion ", 0) == 0 ? std::string::npos : what.rfind("step ");
      std::cout << (at == std::string::npos ? what : what.substr(at)) << ": " << reason
                << "; retrying with " << size(stepper.increment()) << std::endl;
    }
    return Retry::cut;
  }
  // Newton failed (diverged, a singular bordered system, a law that failed
  // at an iterate), not IMPL-EX's own check: the last resort before a stop
  // is worth one step (a rescue that fails stops the run all the same).
  const bool newton_failed = reason.rfind("IMPL-EX", 0) != 0;
  if (!rescuing && newton_failed && cracking && cracking->may_rescue() &&
      stepper.increment() <= jump_smallest_step)
  {
    // The implicit cracks' Newton cycles on a kink that no cut passes
    // (cracks that turn between loading and unloading): the smallest step
    // once more as an IMPL-EX step, linear but for closure, and implicit
    // steps again after it (commit()). docs/cracking.md, "The IMPL-EX
    // rescue".
    cracking->set_implex_rescue(true);
    forget_step_error_misses(); // the implicit cracks' misses, not IMPL-EX's
    if (_report.talk())
      std::cout << what << ": " << reason << "; the step of " << size(stepper.increment())
                << " as one IMPL-EX step (cracking.implex_rescue)" << std::endl;
    return Retry::implex_rescue;
  }
  end_implex_rescue();
  _summary.message = what + " did not converge with " + std::to_string(cuts) +
                     (cuts == 1 ? " cut" : " cuts") + ", down to " + size(stepper.increment()) +
                     (rescuing ? ", nor as one IMPL-EX step" : "") + " (" + reason + "); stopped";
  if (newton_failed || rescuing)
  {
    using Cracks = FailureCase::Cracks;
    using Rescue = FailureCase::Rescue;
    FailureCase failure{.may_snap_back = _may_snap_back, .monotonic = _scenario.monotonic()};
    if (cracking && cracking->implicit_run())
    {
      failure.cracks = cracking->viscous()              ? Cracks::implicit_viscous
                       : cracking->step_tolerance() > 0 ? Cracks::implicit_held
                                                        : Cracks::implicit;
      // (the rescue was off, or the smallest step too large)
      if (!cracking->viscous())
        failure.rescue = rescuing ? Rescue::failed : Rescue::not_tried;
    }
    _summary.message += failure_hint(failure);
  }
  return Retry::stop;
}

void StepLoop::end_implex_rescue()
{
  model::BulkCracking* cracking = _equilibrium.model().bulk_cracking();
  if (cracking && cracking->implex_rescue())
    cracking->set_implex_rescue(false);
}

bool StepLoop::stop_requested()
{
  test_hooks_before_agreement(_summary.steps, _comm);
  mpi::checkpoint(_comm);
  test_hooks_after_agreement(_summary.steps, _comm);
  int local = interrupt::received(), global = 0;
  MPI_Allreduce(&local, &global, 1, MPI_INT, MPI_MAX, _comm);
  if (global == 0)
    return false;
  interrupt::acknowledge(); // every process stops here, by itself
  _summary.interrupted = true;
  _summary.signal = global;
  _summary.stopped_in = _stage;
  _summary.message = "interrupted by " + interrupt::signal_name(global) + " " +
                     record::stage_progress(_stage, _summary);
  _report.save_stop();
  return true;
}

bool StepLoop::begin_load_factor_path(const std::string& control, LoadFactorPath& p)
{
  p.lambda_final = _scenario.final_load_factor();
  if (!(p.lambda_final > 0))
  {
    _summary.message = control + " needs a positive final push displacement";
    return false;
  }
  // The constraints of the push (their dofs stay; only values move) before
  // a PathFollower takes the solver's problem.
  _scenario.apply_load_factor(0.0, _equilibrium);
  p.h_nominal = p.lambda_final / _scenario.steps();
  p.max_steps = stage_step_limit(_scenario.steps());
  return true;
}

int StepLoop::stage_step_limit(int nominal_steps) const
{
  const model::BulkCracking* bulk = _equilibrium.model().bulk_cracking();
  return detail::path_step_limit(nominal_steps, bulk ? bulk->step_tolerance() : 0.0);
}

bool StepLoop::within_step_limit(const LoadFactorPath& p, int k, double lambda,
                                 const std::string& control)
{
  if (k <= p.max_steps)
    return true;
  _summary.message = control + " did not reach the end of the " + p.target + " in " +
                     std::to_string(p.max_steps) + " steps (" + p.symbol + " = " +
                     std::to_string(lambda) + " mm); stopped";
  return false;
}
} // namespace pushout::stepping

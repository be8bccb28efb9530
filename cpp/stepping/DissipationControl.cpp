// Dissipation control (loading.control = "dissipation" or "auto"; Gutierrez
// 2004; Verhoosel, Remmers & Gutierrez 2009; docs/numerics.md,
// "Dissipation control"): steps of the load factor lambda while the joints
// dissipate little, steps of the energy they release through a brittle
// event (solver/PathFollower.h). For the push here, for the corrosion
// stage in CorrosionStage.cpp; the switching between the two kinds of
// step in StepLoop::DissipationSteps, one member function per part of a
// step. The energies are summed over the processes here, the one control
// that needs them.
#include "../common/petsc_check.h"
#include "EnergyEvent.h"
#include "StepLoop.h"
#include "StepLoopShared.h"
#include "TestHooks.h"
#include <algorithm>
#include <array>
#include <iostream>
#include <optional>
#include <sstream>

namespace pushout::stepping
{
using namespace detail;

namespace
{
/// Dissipation control: a step of delta that dissipates too much is halved
/// down to this fraction of a step before energy steps take over.
constexpr double min_probe_increment = 1.0 / 16;

/// The energy released by the joints to full softening, summed over the
/// processes [N mm].
double joints_fracture_energy(model::Model& model)
{
  double local = 0, total = 0;
  for (const interface::Interface* joints : model.joints())
    local += joints->fracture_energy();
  MPI_Allreduce(&local, &total, 1, MPI_DOUBLE, MPI_SUM, model.comm());
  return total;
}

/// The joints' fracture energy plus that of a crack through the cover if
/// the concrete cracks (model::BulkCracking::nominal_fracture_energy) [N mm].
double fracture_energy(model::Model& model)
{
  const model::BulkCracking* cracking = model.bulk_cracking();
  return joints_fracture_energy(model) + (cracking ? cracking->nominal_fracture_energy() : 0.0);
}

/// Whether a step (of lambda, or of energy after one) may start from the
/// last step's increment extrapolated: where nothing that softens is
/// solved for implicitly in it.
/// IMPL-EX cracks hold their history through a step (its bulk is linear but
/// for closure), so its equilibrium does not depend on Newton's start; a
/// joint layer that softens has branches, and a start beyond a peak could
/// carry Newton onto the one after it without a dissipation the loop would
/// see (the snap-back slice of e2e_dissipation_control_passes_snap_back:
/// the peak sampled at 2.167 against 2.257 MPa), where the loop, not
/// Newton, must pass the event.
bool predicts_steps(model::Model& model)
{
  const model::BulkCracking* cracking = model.bulk_cracking();
  return cracking && cracking->implex() && !(joints_fracture_energy(model) > 0);
}

/// The energy the joints and the concrete's cracks dissipated from the
/// committed state to the last evaluation, summed over the processes
/// [N mm]: all layers, softening layers (the cracks soften).
std::array<double, 2> dissipation(model::Model& model)
{
  std::array<double, 2> local = {0, 0}, total;
  for (const interface::Interface* joints : model.joints())
  {
    local[0] += joints->dissipation();
    local[1] += joints->dissipation(true);
  }
  if (model::BulkCracking* cracking = model.bulk_cracking())
  {
    const double cracks = cracking->dissipation();
    local[0] += cracks;
    local[1] += cracks;
  }
  MPI_Allreduce(local.data(), total.data(), 2, MPI_DOUBLE, MPI_SUM, model.comm());
  return total;
}
} // namespace

/// The steps of a stage under dissipation control from lambda = 0 to its
/// end (StepLoop::by_dissipation says which step is taken when): the state
/// the loop keeps between steps, and one member function per part of a
/// step.
class StepLoop::DissipationSteps
{
public:
  /// dG_nominal: the energy increment of a whole energy step [N mm].
  DissipationSteps(StepLoop& loop, const DissipationStage& stage, double dG_nominal);
  /// All steps; false if one failed or a signal stopped the run (the
  /// summary's message says which).
  bool run();

private:
  /// One try of a step from the committed state at _lambda.
  struct Try
  {
    solver::SolveReport rep;
    double lambda_new;            ///< the load factor it reached [mm]
    bool energy_step;             ///< a step of energy (else of lambda)
    double dG_step;               ///< the increment of an energy step [N mm]
    bool too_dissipative = false; ///< a converged step of lambda reverted: it dissipated too much
    /// a converged step of lambda reverted: the cracks' step error took it as a jump
    bool snaps = false;
    StepLoop::StepErrorCheck checked; ///< the converged try's crack step error (check_step_error)
  };
  /// An energy step if the last steps chose one (a step of lambda instead
  /// if it would move lambda too far), else a step of lambda.
  Try try_step(const std::string& name);
  /// A step of energy dG_step [N mm] from the committed state; lambda_new:
  /// the load factor it reached.
  solver::SolveReport energy_step(double& lambda_new, double dG_step);
  /// A step of lambda from lambda_from to lambda_to.
  solver::SolveReport lambda_step(double lambda_from, double lambda_to);
  /// After a converged step of lambda to lambda_new: whether it dissipated
  /// more than dG_nominal beyond its work (then reverted, and the next try
  /// a shorter step of lambda or an energy step).
  bool too_dissipative(const std::string& name, double lambda_new);
  /// After a converged step of lambda that the cracks' step error would
  /// take as a jump (its error does not fall with the step: the cracks snap
  /// back): whether it is reverted and handed to energy steps, which trace
  /// the snap-back.
  /// Not when the last hand-over has no energy step since (one that cannot
  /// step, as where nothing softens along the path, hands back: the jump is
  /// then taken, and the stage goes on).
  bool snaps(const std::string& name, const Try& t);
  /// After a failed try: reverted and cut; false if it cannot be cut again
  /// or a signal stops the run. Chooses the kind of the next try.
  bool failed(const std::string& name, const Try& t);
  /// Records and commits converged step k, and chooses the kind of the
  /// next.
  void accept(int k, const std::string& name, const Try& t);
  /// The stage's mean jump at the state in _x [mm].
  double mean_jump();
  /// IMPL-EX cracks, or the implicit cracks held to their error: the
  /// converged try `t`'s step error against the tolerance
  /// (StepLoop::check_step_error; a try that misses it fails, to be cut); the
  /// error of a step of one kind is not compared with the other's.
  void check_step_error(Try& t);
  void say(const std::string& what);

  StepLoop& _loop;
  const DissipationStage& _stage;
  const double _lambda_final, _h_nominal; ///< the stage's final lambda, a nominal step [mm]
  const double _dG_nominal;               ///< [N mm]
  /// Controls the energy released + beta times the mean jump.
  solver::PathFollower _path;
  const SolverCounts _count{_loop._summary, _path};
  const Words _step_words, _energy_words;
  Stepper _by_lambda, _energy;
  bool _by_energy = false; ///< the kind of the next step
  double _lambda = 0.0;    ///< of the committed state [mm]
  double _P = 0;           ///< the force on lambda at the committed state [N]
  double _jump = 0;        ///< the mean jump at the committed state [mm]
  double _jump_rate = 0;   ///< d jump / d lambda of the last step
  int _cuts = 0;           ///< of the step being tried
  /// IMPL-EX cracks extrapolate the last committed step's growth of their
  /// history (BulkCracking::set_extrapolation) by the ratio of the try's
  /// increment to that step's: of lambda in a step of lambda after one
  /// (_d_lambda_last [mm]), of the energy released in an energy step
  /// (_released_last [N mm], by the softening layers and the cracks). 0:
  /// nothing to extrapolate (the stage's first step, a step of the other
  /// kind for lambda, a jump).
  double _d_lambda_last = 0, _released_last = 0;
  /// An energy step after one (not a jump) starts, where
  /// predicts_steps(), from the last step's increment of x and
  /// lambda scaled by the ratio of the energy increments asked for: that
  /// step's increment [N mm] (0: none to predict from) and of lambda [mm].
  double _dG_last = 0, _d_lambda_energy_last = 0;
  bool _checked_energy_step = false; ///< the kind of the last try StepLoop::check_step_error saw
  /// A step of lambda that the step error would have taken as a jump was
  /// handed to energy steps, and no energy step has been committed since
  /// (snaps()).
  bool _snap_handed_over = false;
  /// The steps of lambda since the last commit replace an energy step that
  /// overshot (try_step): if they fail back to energy steps, the same
  /// energy step would overshoot again, for ever; it is cut instead.
  bool _overshot = false;
  /// The energy steps since the last hand-over to them.
  EnergyEvent _event;
  /// A step of lambda after one starts from the last step's increment
  /// scaled by the same ratio (StepLoop::solve_predicted), as under
  /// displacement control, where predicts_steps().
  const bool _predict = predicts_steps(_loop._equilibrium.model());
};

/// Dissipation control of the push: the push delta is the load factor, the
/// mean axial slip keeps an elastic energy step controllable, P works on it.
bool StepLoop::push_by_dissipation()
{
  LoadFactorPath p;
  if (!begin_load_factor_path("dissipation control", p))
    return false;
  const solver::Vector slip(_equilibrium.model().mean_axial_slip_functional());
  return by_dissipation({"load step", "a push of", p,
                         [&](double lambda) { _scenario.apply_load_factor(lambda, _equilibrium); },
                         0.0, 1.0, slip, [&] { return _scenario.load_force(_equilibrium.model()); },
                         [&](int iterations, int cuts, int k, double)
                         {
                           _recorder.record(_x, iterations, cuts, k, 0);
                           ++_summary.steps;
                         },
                         [&] { return push_by_displacement(); }});
}

bool StepLoop::softens()
{
  return fracture_energy(_equilibrium.model()) > 0;
}

/// Dissipation control of a stage (Verhoosel, Remmers & Gutierrez 2009):
/// steps of the load factor lambda as under displacement control while the
/// joints dissipate little; steps of the energy they release (path
/// following, solver/PathFollower.h: the softening layers'
/// Interface::energy_release plus beta times the stage's mean jump, beta
/// set so that where nothing softens an energy step moves lambda by about a
/// step of lambda) through a brittle event. A step of lambda hands over to
/// energy steps when it fails, or when it dissipates D (the laws' own
/// account, Interface::dissipation) more than the dissipation increment
/// dG = fracture energy / dissipation_steps and more than dG beyond the
/// work W = 1/2 (P0 + P1) d lambda of the force P on lambda: a brittle
/// event that fed on the elastic energy stored, where displacement control
/// jumps (snap-through) or stalls. Such a step is first halved, down to
/// min_probe_increment: before a peak a shorter step dissipates less,
/// through a snap-back it does not. With IMPL-EX cracks (or the implicit
/// cracks held to their step error) a step of lambda also hands over where
/// the step error would take it as a jump (snaps()).
/// Energy steps hand back to steps of lambda once the event is over
/// (EnergyEvent::End: it released little, lambda is back past where the
/// snap-back began, or a step past a failure it took over from), or when
/// one would move lambda by more than a step of lambda. Failed steps
/// are halved (each kind its own Stepper.h). Without softening layers
/// (dG = 0) the stage runs as without dissipation control.
bool StepLoop::by_dissipation(const DissipationStage& stage)
{
  const double dG_nominal = fracture_energy(_equilibrium.model()) / _dissipation_steps; // [N mm]
  if (!(dG_nominal > 0))
  {
    if (_report.talk())
      std::cout << "dissipation control: no joint layer softens (no fracture energy); the "
                << stage.path.target << " runs under displacement control" << std::endl;
    return stage.without_softening();
  }
  // Steps of lambda here must stay on the branch of the committed state:
  // the loop, not Newton, passes the brittle events. They start from the
  // committed state's tangent whatever solver.first_tangent says (the last
  // converged tangent may carry Newton to another branch).
  const StartTangent start_tangent{_solver};
  DissipationSteps steps(*this, stage, dG_nominal);
  return steps.run();
}

StepLoop::DissipationSteps::DissipationSteps(StepLoop& loop, const DissipationStage& stage,
                                             double dG_nominal)
    : _loop(loop), _stage(stage), _lambda_final(stage.path.lambda_final),
      _h_nominal(stage.path.h_nominal), _dG_nominal(dG_nominal),
      _path(solver::PathFollower::by_energy(loop._solver, stage.control)),
      _step_words(sized(stage.increment_words, _h_nominal, "mm")),
      _energy_words(sized("a release of", dG_nominal, "N mm")),
      _by_lambda(loop._max_cuts, easy_tries(loop._equilibrium.model())),
      _energy(loop._max_cuts, easy_tries(loop._equilibrium.model(), true))
{
  _path.set_load_difference(stage.load_difference);
  _loop.forget_step_error_misses(); // another stage, another parameter
  _jump = mean_jump();
  _P = stage.force();
}

bool StepLoop::DissipationSteps::run()
{
  for (int k = 1; _lambda < _lambda_final - step_tolerance * _lambda_final;)
  {
    if (_loop.stop_requested() ||
        !_loop.within_step_limit(_stage.path, k, _lambda, "dissipation control"))
      return false;
    const std::string name = _stage.step_name + " " + std::to_string(k);
    const Try t = try_step(name);
    if (t.too_dissipative || t.snaps)
      continue;
    if (!t.rep.converged)
    {
      if (!failed(name, t))
        return false;
      continue;
    }
    accept(k, name, t);
    ++k;
  }
  return true;
}

StepLoop::DissipationSteps::Try StepLoop::DissipationSteps::try_step(const std::string& name)
{
  Try t{{}, _lambda, _by_energy, _energy.increment() * _dG_nominal, false, false, {}};
  bool overshot = false;
  if (_by_energy)
  {
    t.rep = energy_step(t.lambda_new, t.dG_step);
    // IMPL-EX's check first: an energy try whose extrapolated cracks
    // release too little moves lambda far and misses the tolerance, and is
    // cut (a smaller release); replaced by a step of lambda it would be
    // jumped, found too dissipative and tried by energy again, for ever.
    check_step_error(t);
    if (t.rep.converged && t.lambda_new < 0)
    {
      // Behind the stage's start (a push turned into a pull of the tube, a
      // negative corrosion depth): an equilibrium of the model, not a state
      // of the test. The step of energy is cut.
      std::ostringstream why;
      why << "a step of energy took " << _stage.path.symbol << " to " << t.lambda_new * 1e3
          << " um, behind the start of the " << _stage.path.target;
      t.rep.converged = false;
      t.rep.reason = why.str();
    }
    if (t.rep.converged && (t.lambda_new > _lambda + _h_nominal || t.lambda_new > _lambda_final ||
                            test_energy_overshoots()))
    {
      // Past a nominal step of lambda (the joints have little left to
      // release) or its final value: a step of lambda instead, taken
      // whatever it dissipates, and steps of lambda again.
      _loop.revert();
      t.energy_step = _by_energy = false;
      t.checked = {}; // the energy try's, reverted
      overshot = _overshot = true;
      _by_lambda = Stepper(_loop._max_cuts, easy_tries(_loop._equilibrium.model())); // a whole step
      const std::string& lambda = _stage.path.symbol;
      say(name + ": a step of energy would move " + lambda + " by more than a step of " + lambda +
          "; displacement control");
    }
  }
  if (!t.energy_step)
  {
    t.lambda_new = _lambda + _by_lambda.increment() * _h_nominal;
    if (t.lambda_new > _lambda_final * (1 - step_tolerance))
      t.lambda_new = _lambda_final;
    t.rep = lambda_step(_lambda, t.lambda_new);
    if (_overshot && test_energy_overshoots())
      t.rep = {.converged = false, .reason = "PUSHOUT_TEST_ENERGY_OVERSHOOTS"};
    _loop._summary.newton_iterations += t.rep.iterations;
    check_step_error(t); // before too_dissipative: IMPL-EX's cracks dissipate in its update
    t.snaps = t.rep.converged && !overshot && snaps(name, t);
    t.too_dissipative =
        t.rep.converged && !overshot && !t.snaps && too_dissipative(name, t.lambda_new);
  }
  return t;
}

solver::SolveReport StepLoop::DissipationSteps::energy_step(double& lambda_new, double dG_step)
{
  // beta such that an elastic energy step (G = 0) moves lambda by about a
  // nominal step: dG_nominal = beta jump_rate h_nominal. No Newton
  // iteration moves lambda by more than the shortest probe of a step of
  // lambda: at the start of an event the control's linearisation sees few
  // of the points that will soften, and would overshoot.
  _path.set_slip_weight(_jump_rate > 0 ? _dG_nominal / (_jump_rate * _h_nominal) : 0.0);
  _loop.set_time_increment(_h_nominal * _stage.time_per_lambda);
  _loop.set_crack_extrapolation(extrapolation_ratio(dG_step, _released_last));
  // A stall nearly in equilibrium ends the step (ArcLengthSolver::step,
  // loose): cuts do not pass it (its |F| shrinks with the step), and a step
  // of the smallest size stuck there took every later step down with it
  // (the corroded study's centred tube, beta 2, seed 4, x = 25 um: 17 such
  // steps, then one that was not near equilibrium, against 3 and a whole
  // curve when any step may end so).
  std::optional<double> control_from; // of the committed state, if predicted
  if (_predict && _dG_last > 0 && !test_no_step_prediction())
  {
    const double r = extrapolation_ratio(dG_step, _dG_last);
    const double committed = _path.control(_loop._x);
    if (_loop.extrapolate(r))
    {
      control_from = committed;
      lambda_new = _lambda + r * _d_lambda_energy_last;
    }
  }
  solver::SolveReport rep = _path.step(_loop._x, lambda_new, dG_step, _stage.set_load,
                                       min_probe_increment * _h_nominal, true, control_from);
  _loop._summary.newton_iterations += rep.iterations;
  _loop.test_fail_implicit_try(rep);
  return rep;
}

solver::SolveReport StepLoop::DissipationSteps::lambda_step(double lambda_from, double lambda_to)
{
  _stage.set_load(lambda_to);
  _loop.set_time_increment((lambda_to - lambda_from) * _stage.time_per_lambda);
  const double ratio = extrapolation_ratio(lambda_to - lambda_from, _d_lambda_last);
  _loop.set_crack_extrapolation(ratio);
  return _loop.solve_predicted(_predict && !test_no_step_prediction() ? ratio : 0.0);
}

bool StepLoop::DissipationSteps::too_dissipative(const std::string& name, double lambda_new)
{
  const auto [D, D_softening] = dissipation(_loop._equilibrium.model());
  const double P_new = _stage.force();
  const double work = 0.5 * (_P + P_new) * (lambda_new - _lambda);
  if (!(D_softening > _dG_nominal && D > work + _dG_nominal))
    return false;
  // Shorter steps first: before a peak the dissipation shrinks with the
  // step; through a snap-back it does not.
  _loop.revert();
  std::ostringstream s;
  s << name << ": " << _stage.increment_words << " " << lambda_new - _lambda << " mm dissipated "
    << D << " N mm, " << D - work << " N mm more than its work; ";
  _by_energy = _by_lambda.increment() <= min_probe_increment || !_by_lambda.failed();
  _event.handed_over_by_event(); // a dissipation
  s << (_by_energy ? "dissipation control" : "a shorter step");
  say(s.str());
  return true;
}

bool StepLoop::DissipationSteps::snaps(const std::string& name, const Try& t)
{
  // Under displacement control IMPL-EX passes a snap-back in jumps at the
  // smallest step, relaxing the cracks at a nearly constant load: on the
  // corroded study's centred tube (beta 2, seed 4, 12 / 4, x = 50 um) some
  // 70 of them, each dissipating less than dG_nominal, so too_dissipative
  // handed over only once the pressure had fallen from 11.1 to 7.9 MPa,
  // and the run ended in the jumped state (165 N mm dissipated, the
  // implicit cracks tracing the snap-back 145 N mm). Handed over at the
  // first jump, the energy steps trace it as they do the implicit cracks'
  // (150 N mm, the residual bond 0.865 MPa as theirs at 320 corrosion
  // steps; docs/cracking.md, "Under dissipation control").
  if (!t.checked.jump || _snap_handed_over)
    return false;
  _loop.revert();
  _snap_handed_over = true;
  _by_energy = true;
  _event.handed_over_by_event(); // a snap
  std::ostringstream s;
  if (_loop._equilibrium.model().bulk_cracking()->implex())
    s << name << ": IMPL-EX error " << t.checked.error
      << " does not fall with the step (the cracks snap back); dissipation control";
  else // taken where its prediction misses (StepLoop::check_step_error)
    s << name << ": the cracks' step error " << t.checked.error
      << " is not met by a smaller step; dissipation control";
  say(s.str());
  return true;
}

bool StepLoop::DissipationSteps::failed(const std::string& name, const Try& t)
{
  _loop.revert();
  Stepper& stepper = t.energy_step ? _energy : _by_lambda;
  // The last step of lambda, clipped to lambda_final, is cut from its own size.
  const double tried = t.energy_step ? stepper.increment() : (t.lambda_new - _lambda) / _h_nominal;
  const Retry retry = _loop.cut_back(
      stepper, _cuts, (t.energy_step ? "dissipation-controlled " : "") + name, t.rep.reason,
      t.energy_step ? _energy_words : _step_words, t.checked.cut_factor(), tried);
  if (retry == Retry::stop)
    return false;
  // The same step as one IMPL-EX step (StepLoop::cut_back): of the same
  // kind, unless nothing along the path dissipated (a singular control:
  // then a step of lambda, as below, held to IMPL-EX's tolerance where it is
  // not the smallest, StepLoop::check_step_error).
  const bool singular = t.rep.reason.find("singular") != std::string::npos;
  if (retry == Retry::implex_rescue && !singular)
    return true;
  // A step of lambda that failed short (below min_probe_increment) is
  // retried under dissipation control; a step of energy that nothing along
  // the path dissipates (singular control) under displacement control.
  if (t.energy_step)
    _by_energy = !singular;
  else if (_by_lambda.increment() < min_probe_increment && !(t.checked.ratio > 1))
  {
    // (An IMPL-EX error is no sign of an event: its step is cut as under
    // displacement control, down to where it would jump, which snaps()
    // hands to energy steps.)
    _by_energy = true;
    _event.handed_over_by_failure();
    if (_overshot && !_energy.failed())
    {
      _loop._summary.message = name + ": steps of " + _stage.path.symbol +
                               " failed where the smallest step of energy would move it by "
                               "more than a step (" +
                               t.rep.reason + "); stopped";
      return false;
    }
    if (_overshot)
      say(name + ": dissipation control, with " + _energy_words(_energy.increment()) +
          " (the last overshot)");
    else
      say(name + ": dissipation control");
  }
  return true;
}

void StepLoop::DissipationSteps::accept(int k, const std::string& name, const Try& t)
{
  _stage.record(t.rep.iterations, _cuts, k, t.lambda_new); // before the commit: StepRecorder.h
  if (t.energy_step)
  {
    ++_loop._summary.dissipation_steps;
    _snap_handed_over = false;
  }
  if (t.rep.loose)
  {
    ++_loop._summary.loose_steps;
    say(name + ": " + t.rep.reason);
  }
  _loop.count_step_error(t.checked, name);
  _loop.commit();
  (t.energy_step ? _energy : _by_lambda).converged(t.rep.iterations, t.checked.may_grow());
  _overshot = false;
  // After a jump of the load the last step's growth predicts nothing; an
  // energy step taken at the floor of IMPL-EX's error released what it was
  // asked for, and its growth is extrapolated as any other's (on the coarse
  // centred case as many jumps as when it was not, p within 2 %).
  const double released = dissipation(_loop._equilibrium.model())[1];
  _released_last = t.checked.jump && !t.energy_step ? 0.0 : released;
  _d_lambda_last = t.energy_step || t.checked.jump ? 0.0 : t.lambda_new - _lambda;
  _dG_last = t.energy_step && !t.checked.jump ? t.dG_step : 0.0;
  _d_lambda_energy_last = t.lambda_new - _lambda;
  // The event is over once its softening layers release little, or once
  // lambda, having fallen, is back past where the event began: the
  // snap-back is traced, and the branch rises with lambda again (an event
  // further on hands over again). Without the second, a corrosion stage
  // that softens all the way on (the centred tube after its cover crack)
  // stayed in energy steps to its end: with IMPL-EX cracks, whose energy
  // steps sit at the floor of their error, 768 of them, 118 s and the
  // residual bond 0.399 MPa (beta 3, seed 1, 50 um), against 249, 64 s
  // and 0.457 MPa (the implicit cracks 0.518; 0.524 without the rule and
  // 0.523 with it at implex_tolerance 0.0004, in 428 and 179 s).
  // Energy steps that took over from a failed step of lambda end too once
  // they have carried lambda a whole nominal step past it without it ever
  // falling: they trace a branch that rises with lambda, and what failed is
  // passed. Without that, the implicit cracks held to their step error (the
  // corroded study's centred tube, beta 3, seed 2, 12 / 4) stayed in
  // energy steps from x = 12.6 to 47.9 um, 266 of them with x rising all
  // the way and each release large, until Newton cycled at the smallest
  // release and the run stopped.
  if (!t.energy_step)
    _event.load_step();
  else if (const EnergyEvent::End end = _event.energy_step(_lambda, t.lambda_new, released,
                                                           t.dG_step, _dG_nominal, _h_nominal);
           end != EnergyEvent::End::none)
  {
    // Whole steps of lambda again (cut if they fail).
    _by_energy = false;
    _by_lambda = Stepper(_loop._max_cuts, easy_tries(_loop._equilibrium.model()));
    const std::string& lambda = _stage.path.symbol;
    std::ostringstream s;
    s << name << ": ";
    if (end == EnergyEvent::End::traced)
      s << lambda << " is back past " << _event.start() * 1e3 << " um, where the snap-back began";
    else if (end == EnergyEvent::End::passed)
      s << lambda << " is a step past " << _event.start() * 1e3 << " um, where a step of " << lambda
        << " failed, and has not fallen";
    else
      s << "the softening layers released little in the step";
    say(s.str() + "; displacement control");
  }
  _P = _stage.force();
  const double jump_new = mean_jump();
  if (t.lambda_new > _lambda && jump_new > _jump)
    _jump_rate = (jump_new - _jump) / (t.lambda_new - _lambda);
  _jump = jump_new;
  _lambda = t.lambda_new;
  _cuts = 0;
}

void StepLoop::DissipationSteps::check_step_error(Try& t)
{
  if (!t.rep.converged)
    return;
  if (t.energy_step != _checked_energy_step)
    _loop.forget_step_error_misses(); // steps of energy and of the load: other parameters
  _checked_energy_step = t.energy_step;
  Stepper& stepper = t.energy_step ? _energy : _by_lambda;
  // An energy step's error that a smaller release does not lower is the
  // floor of IMPL-EX's error where thousands of cracks switch between
  // loading and unloading (docs/cracking-speed.md), not a snap.
  t.checked =
      _loop.check_step_error(t.rep, t.energy_step ? t.dG_step : t.lambda_new - _lambda, stepper,
                             t.energy_step ? "a smaller release does not lower it" : nullptr);
}

double StepLoop::DissipationSteps::mean_jump()
{
  double s;
  petsc::check(VecDot(_stage.control, _loop._x, &s), "VecDot");
  return s;
}

void StepLoop::DissipationSteps::say(const std::string& what)
{
  if (_loop._report.talk())
    std::cout << what << std::endl;
}
} // namespace pushout::stepping

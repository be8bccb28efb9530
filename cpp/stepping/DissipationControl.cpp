// Dissipation control (loading.control = "dissipation" or "auto"; Gutierrez
// 2004; Verhoosel, Remmers & Gutierrez 2009; docs/numerics.md,
// "Dissipation control"): steps of the load factor lambda while the joints
// dissipate little, steps of the energy they release through a brittle
// event (solver/PathFollower.h). For the push here, for the corrosion
// stage in CorrosionStage.cpp; the switching between the two kinds of
// step in by_dissipation. The energies are summed over the processes here,
// the one control that needs them.
#include "../common/petsc_check.h"
#include "StepLoop.h"
#include "StepLoopShared.h"
#include <array>
#include <iostream>
#include <sstream>

namespace pushout::stepping
{
using namespace detail;

namespace
{
/// Dissipation control: a step of delta that dissipates too much is halved
/// down to this fraction of a step before energy steps take over.
constexpr double min_probe_increment = 1.0 / 16;
/// Dissipation control: steps of delta again after an energy step in which
/// the softening layers released less than this fraction of its increment
/// (the slip term of the control did the rest), once the energy steps have
/// released more than one increment (the event is over, not beginning).
constexpr double released_to_return = 0.25;

/// The energy released by the joints to full softening, summed over the
/// processes [N mm].
double fracture_energy(model::Model& model)
{
  double local = 0, total = 0;
  for (const interface::Interface* joints : model.joints())
    local += joints->fracture_energy();
  MPI_Allreduce(&local, &total, 1, MPI_DOUBLE, MPI_SUM, model.comm());
  return total;
}

/// The energy the joints dissipated from the committed state to the last
/// evaluation, summed over the processes [N mm]: all layers, softening
/// layers.
std::array<double, 2> dissipation(model::Model& model)
{
  std::array<double, 2> local = {0, 0}, total;
  for (const interface::Interface* joints : model.joints())
  {
    local[0] += joints->dissipation();
    local[1] += joints->dissipation(true);
  }
  MPI_Allreduce(local.data(), total.data(), 2, MPI_DOUBLE, MPI_SUM, model.comm());
  return total;
}
} // namespace

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
/// through a snap-back it does not. Energy steps hand back to steps of
/// lambda once the event is over (released_to_return), or when one would
/// move lambda by more than a step of lambda. Failed steps are halved (each
/// kind its own Stepper.h). Without softening layers (dG = 0) the stage
/// runs as without dissipation control.
bool StepLoop::by_dissipation(const DissipationStage& stage)
{
  const LoadFactorPath& p = stage.path;
  const double dG_nominal = fracture_energy(_equilibrium.model()) / _dissipation_steps; // [N mm]
  if (!(dG_nominal > 0))
  {
    if (_report.talk())
      std::cout << "dissipation control: no joint layer softens (no fracture energy); the "
                << p.target << " runs under displacement control" << std::endl;
    return stage.without_softening();
  }
  // Steps of lambda here must stay on the branch of the committed state:
  // the loop, not Newton, passes the brittle events. They start from the
  // committed state's tangent whatever solver.first_tangent says (the last
  // converged tangent may carry Newton to another branch).
  const StartTangent start_tangent{_solver};
  // control: the energy released + beta times the mean jump
  solver::PathFollower path = solver::PathFollower::by_energy(_solver, stage.control);
  path.set_load_difference(stage.load_difference);
  const FactorizationCount count{_summary, path};
  const auto mean_jump = [&]
  {
    double s;
    petsc::check(VecDot(stage.control, _x, &s), "VecDot");
    return s;
  };
  double jump = mean_jump(), jump_rate = 0; // [mm], d jump / d lambda of the last step
  const double lambda_final = p.lambda_final, h_nominal = p.h_nominal; // [mm]
  const auto step_words = sized(stage.increment_words, h_nominal, "mm");
  const auto energy_words = sized("a release of", dG_nominal, "N mm");
  const auto say = [&](const std::string& what)
  {
    if (_report.talk())
      std::cout << what << std::endl;
  };
  const auto lambda_step = [&](double lambda_from, double lambda_to)
  {
    stage.set_load(lambda_to);
    set_time_increment((lambda_to - lambda_from) * stage.time_per_lambda);
    _equilibrium.apply_constraints(_x);
    return _solver.solve(_x);
  };
  Stepper by_lambda(_max_cuts, easy_iterations), energy(_max_cuts, easy_bordered_iterations);
  bool by_energy = false;       // the kind of the next step
  double released_in_event = 0; // by the softening layers in the energy steps so far [N mm]
  double lambda = 0.0, P = stage.force();
  int cuts = 0;
  for (int k = 1; lambda < lambda_final - step_tolerance * lambda_final;)
  {
    if (stop_requested() || !within_step_limit(p, k, lambda, "dissipation control"))
      return false;
    const std::string name = stage.step_name + " " + std::to_string(k);
    double lambda_new = lambda;
    solver::SolveReport rep;
    bool energy_step = by_energy, overshot = false;
    const double dG_step = energy.increment() * dG_nominal; // if energy_step [N mm]
    if (by_energy)
    {
      // beta such that an elastic energy step (G = 0) moves lambda by about
      // a nominal step: dG_nominal = beta jump_rate h_nominal. No Newton
      // iteration moves lambda by more than the shortest probe of a step of
      // lambda: at the start of an event the control's linearisation sees
      // few of the points that will soften, and would overshoot.
      path.set_slip_weight(jump_rate > 0 ? dG_nominal / (jump_rate * h_nominal) : 0.0);
      set_time_increment(h_nominal * stage.time_per_lambda);
      rep = path.step(_x, lambda_new, dG_step, stage.set_load, min_probe_increment * h_nominal);
      _summary.newton_iterations += rep.iterations;
      if (rep.converged && (lambda_new > lambda + h_nominal || lambda_new > lambda_final))
      {
        // Past a nominal step of lambda (the joints have little left to
        // release) or its final value: a step of lambda instead, taken
        // whatever it dissipates, and steps of lambda again.
        revert();
        energy_step = by_energy = false;
        overshot = true;
        by_lambda = Stepper(_max_cuts, easy_iterations); // a whole step
        say(name + ": a step of energy would move " + p.symbol + " by more than a step of " +
            p.symbol + "; displacement control");
      }
    }
    if (!energy_step)
    {
      lambda_new = lambda + by_lambda.increment() * h_nominal;
      if (lambda_new > lambda_final * (1 - step_tolerance))
        lambda_new = lambda_final;
      rep = lambda_step(lambda, lambda_new);
      _summary.newton_iterations += rep.iterations;
      if (rep.converged && !overshot)
      {
        const auto [D, D_softening] = dissipation(_equilibrium.model());
        const double P_new = stage.force();
        const double work = 0.5 * (P + P_new) * (lambda_new - lambda);
        if (D_softening > dG_nominal && D > work + dG_nominal)
        {
          // Shorter steps first: before a peak the dissipation shrinks with
          // the step; through a snap-back it does not.
          revert();
          std::ostringstream s;
          s << name << ": " << stage.increment_words << " " << lambda_new - lambda
            << " mm dissipated " << D << " N mm, " << D - work << " N mm more than its work; ";
          by_energy = by_lambda.increment() <= min_probe_increment || !by_lambda.failed();
          s << (by_energy ? "dissipation control" : "a shorter step");
          say(s.str());
          continue;
        }
      }
    }
    if (!rep.converged)
    {
      revert();
      Stepper& stepper = energy_step ? energy : by_lambda;
      if (!cut_back(stepper, cuts, (energy_step ? "dissipation-controlled " : "") + name,
                    rep.reason, energy_step ? energy_words : step_words))
        return false;
      // A step of lambda that failed short (below min_probe_increment) is
      // retried under dissipation control; a step of energy that nothing
      // along the path dissipates (singular control) under displacement
      // control.
      if (energy_step)
        by_energy = rep.reason.find("singular") == std::string::npos;
      else if (by_lambda.increment() < min_probe_increment)
      {
        by_energy = true;
        say(name + ": dissipation control");
      }
      continue;
    }
    stage.record(rep.iterations, cuts, k, lambda_new); // before the commit: StepRecorder.h
    if (energy_step)
      ++_summary.dissipation_steps;
    commit();
    (energy_step ? energy : by_lambda).converged(rep.iterations);
    if (energy_step)
    {
      const double released = dissipation(_equilibrium.model())[1];
      released_in_event += released;
      if (released_in_event > dG_nominal && released < released_to_return * dG_step)
      {
        // The event is over: whole steps of lambda again (cut if they fail).
        by_energy = false;
        by_lambda = Stepper(_max_cuts, easy_iterations);
        say(name + ": the softening layers released little in the step; displacement control");
      }
    }
    else
      released_in_event = 0;
    P = stage.force();
    const double jump_new = mean_jump();
    if (lambda_new > lambda && jump_new > jump)
      jump_rate = (jump_new - jump) / (lambda_new - lambda);
    jump = jump_new;
    lambda = lambda_new;
    cuts = 0;
    ++k;
  }
  return true;
}
} // namespace pushout::stepping

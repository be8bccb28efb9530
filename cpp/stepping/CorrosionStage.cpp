// The corrosion stage (corrosion.*, specimen/Corrosion.h; docs/corrosion.md):
// between step 0 and the push, the oxide grows to the corrosion depth x in
// steps, under the constraints and temperature of step 0. By displacement
// control (nominal steps of x, DisplacementControl.cpp) or, with
// loading.control = "dissipation", by dissipation control with x as the
// load factor (DissipationControl.cpp; docs/numerics.md, "The corrosion
// stage").
#include "StepLoop.h"
#include "StepLoopShared.h"

namespace pushout::stepping
{
using namespace detail;

namespace
{
/// Dissipation control of the corrosion stage: the step of the numerical
/// derivative of the residual by x, as a fraction of a step of x (a
/// relative perturbation near the square root of the round-off: the
/// derivative to about 1e-7).
constexpr double load_difference_fraction = 1e-7;
} // namespace

/// The corrosion stage: the constraints and temperature of step 0, the
/// interface's oxide inputs of depth x(s); each step takes the pseudo-time
/// of the push's first step (as step 0 does), for viscous laws.
bool StepLoop::corrode()
{
  const double step_time = _scenario.time_at(1.0) - _scenario.time_at(0.0);
  interface::Interface& itf = _equilibrium.model().interface();
  return nominal_steps({"corrosion step", _corrosion.steps(),
                        [&](double s)
                        {
                          _scenario.apply_load(0.0, _equilibrium);
                          _corrosion.apply(s, itf);
                        },
                        [&](double s0, double s1) { return (s1 - s0) * step_time; },
                        [&](int iterations, int cuts, int k, double s)
                        { record_corrosion(iterations, cuts, k, s, true); },
                        false, extrapolation([](double s) { return s; })});
}

void StepLoop::record_corrosion(int iterations, int cuts, int k, double s, bool numbered)
{
  _corrosion.record(s, _equilibrium, _x, iterations, cuts, k, numbered,
                    [&](int row) { _recorder.record_corrosion(row); });
  ++_summary.corrosion_steps;
  _summary.penetration_mm = _corrosion.penetration_at(s);
  // The stage's end by the test its loops end on (relative: dissipation
  // control's loop ends within step_tolerance of x_final, an energy step
  // possibly short of it by more than step_tolerance nominal steps).
  if (s >= _corrosion.steps() * (1 - step_tolerance))
    start_push(0);
}

/// Dissipation control of the corrosion stage: the corrosion depth x [mm]
/// is the load factor. It enters the oxide's law (its free opening and
/// compliance), not the constraints, so the solver differentiates the
/// residual by x numerically (ArcLengthSolver::set_load_difference). The
/// mean normal opening of the interface grows with x while nothing softens
/// (the oxide pushes the concrete out) and keeps an elastic energy step
/// controllable; the oxide's expansion force (Corrosion::expansion_force)
/// works on x.
bool StepLoop::corrode_by_dissipation()
{
  const int steps = _corrosion.steps();
  const double h = _corrosion.penetration_at(1.0); // a nominal step of x [mm]
  LoadFactorPath p{_corrosion.penetration_at(steps), h, stage_step_limit(steps), "corrosion stage",
                   "x"};
  _scenario.apply_load(0.0, _equilibrium); // the constraints and loads of step 0
  interface::Interface& itf = _equilibrium.model().interface();
  const solver::Vector opening(
      _equilibrium.model().mean_jump_functional(model::Model::Jump::normal_opening));
  const double step_time = _scenario.time_at(1.0) - _scenario.time_at(0.0);
  double s = 0; // the stage parameter of the last set_load
  return by_dissipation({"corrosion step", "corrosion of", p,
                         [&](double x)
                         {
                           s = x / h;
                           _corrosion.apply(s, itf);
                         },
                         load_difference_fraction * h, step_time / h, opening,
                         [&] { return _corrosion.expansion_force(itf, s); },
                         [&](int iterations, int cuts, int k, double x)
                         { record_corrosion(iterations, cuts, k, x / h, false); },
                         [&] { return corrode(); }});
}
} // namespace pushout::stepping

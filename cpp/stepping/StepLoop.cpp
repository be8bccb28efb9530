#include "StepLoop.h"
#include "../common/Interrupt.h"
#include "../common/mpi_errors.h"
#include "../common/petsc_check.h"
#include "../record/NonFinite.h"
#include "../solver/PathFollower.h"
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <thread>

namespace pushout::stepping
{
namespace
{
/// A try that converged in at most this many Newton iterations is easy;
/// two easy tries in a row double the increment again (Stepper.h).
constexpr int easy_iterations = 4;
/// The same for the steps of the bordered system (arc length, and the energy
/// steps of dissipation control): their Newton iterations close the control
/// equation too (and energy steps start from the committed state's tangent,
/// StartTangent), so an easy one takes a few more (arc length on brittle
/// adhesion: 5 per step). With 4, a step cut once never grew back.
constexpr int easy_bordered_iterations = 6;
/// The load parameter reaches a nominal step within this tolerance.
constexpr double step_tolerance = 1e-12;
/// Path following: snap-back makes the path longer than the final push, so
/// a run whose path never reaches it stops after path_steps_per_step x the
/// nominal steps + path_steps_extra.
constexpr int path_steps_per_step = 20;
constexpr int path_steps_extra = 100;
/// Dissipation control: a step of delta that dissipates too much is halved
/// down to this fraction of a step before energy steps take over.
constexpr double min_probe_increment = 1.0 / 16;
/// Dissipation control: steps of delta again after an energy step in which
/// the softening layers released less than this fraction of its increment
/// (the slip term of the control did the rest), once the energy steps have
/// released more than one increment (the event is over, not beginning).
constexpr double released_to_return = 0.25;
/// Unloading at zero force (loading.unload_to): the force's zero is found
/// to this fraction of the largest push force so far, in at most this many
/// tries.
constexpr double zero_force_tolerance = 1e-6;
constexpr int zero_force_max_tries = 50;
constexpr double zero_force_bracket = 1e-12; ///< of the load parameter
/// Dissipation control of the corrosion stage: the step of the numerical
/// derivative of the residual by x, as a fraction of a step of x (a
/// relative perturbation near the square root of the round-off: the
/// derivative to about 1e-7).
constexpr double load_difference_fraction = 1e-7;

/// Test hook, not a scene key (tests/e2e/test_error_on_one_process_ends_all.py): with the
/// environment variables PUSHOUT_TEST_FAIL_RANK=r and PUSHOUT_TEST_FAIL_AT=
/// `at`, process r alone throws here, as an error found on one process
/// only would: "setup" at the end of the set-up (driver/Run.cpp), "step"
/// after two load steps, "collective" there too but where the others next
/// wait in a collective that is no agreement (common/mpi_errors.h: the run
/// ends with MPI_Abort after abandon_after_s).
/// Words for an increment of a step in `scale` units (cut_back's messages):
/// "a push of 0.025 mm".
std::function<std::string(double)> sized(std::string what, double scale, std::string unit)
{
  return [=](double increment)
  {
    std::ostringstream s;
    s << what << " " << increment * scale << " " << unit;
    return s.str();
  };
}

/// Adds a path follower's factorisations to the summary on every way out of
/// a loop that uses it.
struct FactorizationCount
{
  output::Summary& summary;
  const solver::PathFollower& path;
  ~FactorizationCount() { summary.factorizations += path.factorizations(); }
};

/// A test hook: from the third load step on, each step spends
/// PUSHOUT_TEST_SLOW_STEP_S seconds without looking at signals, as a long
/// factorisation does (the tests of a stop that cannot wait for the step).
void test_slow_step(int steps)
{
  static const char* slow_s = std::getenv("PUSHOUT_TEST_SLOW_STEP_S");
  if (slow_s && steps >= 2)
    std::this_thread::sleep_for(std::chrono::duration<double>(std::atof(slow_s)));
}

void test_failure(const char* at, MPI_Comm comm)
{
  static const char* fail_rank = std::getenv("PUSHOUT_TEST_FAIL_RANK");
  static const char* fail_at = std::getenv("PUSHOUT_TEST_FAIL_AT");
  if (!fail_rank || !fail_at || std::string(fail_at) != at)
    return;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == std::atoi(fail_rank))
    throw std::runtime_error(std::string("test failure on process ") + fail_rank + " at " + at +
                             " (PUSHOUT_TEST_FAIL_AT)");
}
} // namespace

void test_failure_at_setup(MPI_Comm comm)
{
  test_failure("setup", comm);
}

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
}

void StepLoop::time_linear_solve()
{
  _scenario.apply_load(1.0, _equilibrium);
  _equilibrium.apply_constraints(_x);
  _summary.linear_solve_s = _solver.time_linear_solve(_x);
  _x.set(0.0);
  if (_report.talk())
    std::cout << "one linear solve: " << _summary.linear_solve_s << " s" << std::endl;
}

bool StepLoop::run(Control control)
{
  try
  {
    // Step 0 and the corrosion stage end with the push's start recorded
    // (curve.csv row 0) before their last commit.
    if (!initial_step())
      return false;
    if (_corrosion.active() &&
        !(control == Control::dissipation ? corrode_by_dissipation() : corrode()))
      return false;
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
    return false;
  }
}

bool StepLoop::stop_requested()
{
  test_slow_step(_summary.steps);
  if (_summary.steps == 2)
    test_failure("step", _comm);
  mpi::checkpoint(_comm);
  if (_summary.steps == 2)
    test_failure("collective", _comm);
  int local = interrupt::received(), global = 0;
  MPI_Allreduce(&local, &global, 1, MPI_INT, MPI_MAX, _comm);
  if (global == 0)
    return false;
  interrupt::acknowledge(); // every process stops here, by itself
  _summary.interrupted = true;
  _summary.signal = global;
  _summary.stopped_in = "load steps";
  _summary.message = "interrupted by " + interrupt::signal_name(global) + " after " +
                     std::to_string(_summary.steps) + " load steps";
  _report.save_stop();
  return true;
}

void StepLoop::commit()
{
  for (interface::Interface* joints : _equilibrium.model().joints())
    joints->commit();
  _x_committed.copy_from(_x);
  _report.publish();
}

void StepLoop::revert()
{
  for (interface::Interface* joints : _equilibrium.model().joints())
    joints->state().revert();
  _x.copy_from(_x_committed);
  _solver.forget_tangent(); // it was the reverted state's
}

template <class Words>
bool StepLoop::cut_back(Stepper& stepper, int& cuts, const std::string& what,
                        const std::string& reason, Words size)
{
  if (stop_requested())
    return false;
  if (!stepper.failed())
  {
    _summary.message = what + " did not converge with " + std::to_string(cuts) + " cuts, down to " +
                       size(stepper.increment()) + " (" + reason + "); stopped";
    return false;
  }
  ++cuts;
  ++_summary.cuts;
  if (_report.talk())
  {
    // "load step 3" is said "step 3", as its progress line; a stage of one
    // step ("corrosion step") by its name.
    const std::size_t at = what.rfind("step ");
    std::cout << (at == std::string::npos ? what : what.substr(at)) << ": " << reason
              << "; retrying with " << size(stepper.increment()) << std::endl;
  }
  return true;
}

void StepLoop::set_time_increment(double dt)
{
  for (interface::Interface* joints : _equilibrium.model().joints())
    joints->set_time_increment(dt);
}

namespace
{
/// While it lives, each Newton solve starts from the tangent at its initial
/// guess (solver.first_tangent = "current").
struct StartTangent
{
  solver::LoadStepSolver& solver;
  const bool converged = solver.first_tangent_converged();
  explicit StartTangent(solver::LoadStepSolver& s) : solver(s) { solver.set_first_tangent(false); }
  ~StartTangent() { solver.set_first_tangent(converged); }
  StartTangent(const StartTangent&) = delete;
  StartTangent& operator=(const StartTangent&) = delete;
};
} // namespace

/// Step 0: the thermal step or preload, if the scenario has one, in parts
/// (its load scaled, cut in halves like a load step) when it does not
/// converge whole. It takes the pseudo-time of one nominal load step, so
/// that a viscous damage layer damages in it as it would in one step of the
/// push (with dt = 0 its damage would freeze). With a corrosion stage, the
/// push starts after it.
bool StepLoop::initial_step()
{
  _scenario.apply_load(0.0, _equilibrium);
  const auto started = [&](int iterations)
  {
    if (_corrosion.active())
      _corrosion.record(0.0, _equilibrium, _x, iterations, 0, 0);
    else
      start_push(iterations);
  };
  if (!_scenario.initial_solve())
  {
    started(0);
    commit();
    return true;
  }
  const double step_time = _scenario.time_at(1.0) - _scenario.time_at(0.0);
  int iterations = 0; // of all its parts
  // Its parts (after a cut) start from the committed state's tangent: where
  // the thermal load starts a brittle layer softening, the last part's
  // converged tangent is its softening branch, a poor predictor of the next
  // (c = 2000 1/mm, f_t = 6 MPa, k = 1e5 N/mm^3 on the demo: step 0 failed).
  const StartTangent start_tangent{_solver};
  return nominal_steps({"step 0 (initial/thermal step)", 1,
                        [&](double fraction)
                        { _scenario.apply_initial_load(fraction, _equilibrium); },
                        [&](double s0, double s1) { return (s1 - s0) * step_time; },
                        [&](int its, int, int, double fraction)
                        {
                          iterations += its;
                          if (fraction >= 1.0 - step_tolerance)
                            started(iterations);
                        }});
}

void StepLoop::start_push(int iterations)
{
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
  _recorder.record(_x, iterations, 0, 0, _scenario.steps()); // before the commit
}

/// The corrosion stage: the constraints and temperature of step 0, the
/// interface's oxide inputs of depth x(s); each step takes the pseudo-time
/// of one nominal push step (as step 0 does), for viscous laws.
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
                        { record_corrosion(iterations, cuts, k, s, true); }});
}

void StepLoop::record_corrosion(int iterations, int cuts, int k, double s, bool numbered)
{
  _corrosion.record(s, _equilibrium, _x, iterations, cuts, k, numbered);
  ++_summary.corrosion_steps;
  _summary.penetration_mm = _corrosion.penetration_at(s);
  if (s >= _corrosion.steps() - step_tolerance)
    start_push(0);
}

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
       true});
}

/// Each nominal step is tried whole and cut in halves (from the committed
/// state) when Newton fails; increments grow back after easy convergence
/// (Stepper.h).
bool StepLoop::nominal_steps(const Stage& stage)
{
  const int steps = stage.steps;
  Stepper stepper(_max_cuts, easy_iterations);
  const auto fraction = [](double increment)
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
      _equilibrium.apply_constraints(_x);
      const solver::SolveReport rep = _solver.solve(_x);
      _summary.newton_iterations += rep.iterations;
      if (rep.converged && stage.zero_force_ends)
      {
        const double P_try = _scenario.load_force(model);
        if (_scenario.ends_at_zero_force(k) && P >= 0 && P_try < 0)
        {
          // The device cannot pull: the unloading ends where P = 0, and
          // the next segment starts there.
          revert();
          double s_zero;
          if (!zero_force_step(stage, k, cuts, s, P, s_try, P_try,
                               zero_force_tolerance * std::max(P_peak, 1e-300), s_zero))
            return false;
          const double delta = _scenario.prescribed_at(s_zero);
          _summary.permanent_displacements_mm.push_back(delta);
          if (_report.talk())
            std::cout << "step " << k << ": the push force fell to zero at delta = " << delta * 1e3
                      << " um (permanent displacement); the unloading ends there" << std::endl;
          s = _scenario.end_segment_at(k, s_zero);
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
        commit();
        s = s_try;
        stepper.converged(rep.iterations);
        continue;
      }
      revert();
      const std::string what =
          steps == 1 ? stage.step_name : stage.step_name + " " + std::to_string(k);
      if (!cut_back(stepper, cuts, what, rep.reason, fraction))
        return false;
    }
  }
  return true;
}

bool StepLoop::zero_force_step(const Stage& stage, int k, int cuts, double s0, double P0, double s1,
                               double P1, double tol, double& s)
{
  // Illinois false position on [s0, s1], P0 >= 0 > P1; every try one step
  // from the committed state at s0 (a path-dependent law sees one
  // increment, as in the try that overshot).
  const double s_committed = s0;
  int replaced = 0; // the end the last try replaced: -1 (s0) or +1 (s1)
  for (int tries = 0; tries < zero_force_max_tries; ++tries)
  {
    if (stop_requested())
      return false;
    s = s1 - P1 * (s1 - s0) / (P1 - P0);
    stage.apply(s);
    set_time_increment(stage.duration(s_committed, s));
    _equilibrium.apply_constraints(_x);
    const solver::SolveReport rep = _solver.solve(_x);
    _summary.newton_iterations += rep.iterations;
    if (!rep.converged)
    {
      revert();
      _summary.message = "load step " + std::to_string(k) +
                         ": a try at the zero force of the unloading did not converge (" +
                         rep.reason + "); stopped";
      return false;
    }
    const double P = _scenario.load_force(_equilibrium.model());
    // Found, or the bracket is down to round-off of the load parameter
    // (the force's own noise above tol).
    if (std::abs(P) <= tol || std::abs(s1 - s0) <= zero_force_bracket * std::max(1.0, s))
    {
      stage.record(rep.iterations, cuts, k, s); // before the commit: StepRecorder.h
      commit();
      return true;
    }
    revert();
    if (P < 0)
    {
      s1 = s;
      P1 = P;
      if (replaced == +1) // s0 kept twice: halve its weight
        P0 /= 2;
      replaced = +1;
    }
    else
    {
      s0 = s;
      P0 = P;
      if (replaced == -1)
        P1 /= 2;
      replaced = -1;
    }
  }
  _summary.message = "load step " + std::to_string(k) + ": the zero force of the unloading was " +
                     "not found in " + std::to_string(zero_force_max_tries) + " tries; stopped";
  return false;
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
  p.max_steps = path_steps_per_step * _scenario.steps() + path_steps_extra;
  return true;
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

solver::SolveReport StepLoop::load_factor_step(double lambda_from, double lambda_to)
{
  _scenario.apply_load_factor(lambda_to, _equilibrium);
  set_time_increment(lambda_to - lambda_from);
  _equilibrium.apply_constraints(_x);
  return _solver.solve(_x);
}

/// Path following (solver/PathFollower.h) in steps of length
/// h = lambda_final / steps in the plane (lambda, s) of the push delta and
/// the mean slip [mm]. The first step is displacement-controlled (delta =
/// h); each later one prescribes the slip increment of the previous step
/// scaled to length h,  ds = ds_prev h / |(dlambda_prev, ds_prev)|,  which
/// depends only on converged states (not on the tangent at a kink of the
/// laws). Failed steps are halved, easy ones grow back (Stepper.h). The step
/// that would pass lambda_final is replaced by a displacement-controlled step
/// to exactly lambda_final.
bool StepLoop::path_following()
{
  LoadFactorPath p;
  if (!begin_load_factor_path("path following", p))
    return false;
  const solver::Vector a(_equilibrium.model().mean_axial_slip_functional());
  solver::PathFollower path(_solver, a);
  const FactorizationCount count{_summary, path};
  const double lambda_final = p.lambda_final, h_nominal = p.h_nominal; // [mm]
  const auto set_load = [&](double lambda) { _scenario.apply_load_factor(lambda, _equilibrium); };
  const auto length = sized("a length of", h_nominal, "mm");
  Stepper stepper(_max_cuts, easy_bordered_iterations);
  double lambda = 0.0, slip = path.control(_x);
  double d_lambda_prev = 0.0, d_slip_prev = 0.0; // the last converged step
  int cuts = 0;
  for (int k = 1; lambda < lambda_final;)
  {
    if (stop_requested() || !within_step_limit(p, k, lambda, "path following"))
      return false;
    const double h = stepper.increment() * h_nominal;
    double lambda_new = lambda;
    solver::SolveReport rep;
    if (k == 1)
    {
      lambda_new = std::min(h, lambda_final);
      rep = load_factor_step(lambda, lambda_new);
    }
    else
    {
      const double d_slip = d_slip_prev * h / std::hypot(d_lambda_prev, d_slip_prev);
      set_time_increment(h);
      rep = path.step(_x, lambda_new, d_slip, set_load);
      if (rep.converged && lambda_new > lambda_final)
      {
        _summary.newton_iterations += rep.iterations;
        revert();
        lambda_new = lambda_final;
        rep = load_factor_step(lambda, lambda_new);
      }
    }
    _summary.newton_iterations += rep.iterations;
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
      commit();
      d_lambda_prev = lambda_new - lambda;
      d_slip_prev = slip_new - slip;
      lambda = lambda_new;
      slip = slip_new;
      stepper.converged(rep.iterations);
      cuts = 0;
      ++k;
      continue;
    }
    revert();
    if (!cut_back(stepper, cuts, "path-following step " + std::to_string(k), rep.reason, length))
      return false;
  }
  return true;
}

std::array<double, 2> StepLoop::dissipation()
{
  std::array<double, 2> local = {0, 0}, total;
  for (const interface::Interface* joints : _equilibrium.model().joints())
  {
    local[0] += joints->dissipation();
    local[1] += joints->dissipation(true);
  }
  MPI_Allreduce(local.data(), total.data(), 2, MPI_DOUBLE, MPI_SUM, _comm);
  return total;
}

double StepLoop::fracture_energy()
{
  double local = 0, total = 0;
  for (const interface::Interface* joints : _equilibrium.model().joints())
    local += joints->fracture_energy();
  MPI_Allreduce(&local, &total, 1, MPI_DOUBLE, MPI_SUM, _comm);
  return total;
}

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
  LoadFactorPath p{_corrosion.penetration_at(steps), h,
                   path_steps_per_step * steps + path_steps_extra, "corrosion stage", "x"};
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
  const double dG_nominal = fracture_energy() / _dissipation_steps; // [N mm]
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
        const auto [D, D_softening] = dissipation();
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
      const double released = dissipation()[1];
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

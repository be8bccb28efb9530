#include "Run.h"
#include "../common/Interrupt.h"
#include "../common/mpi_errors.h"
#include "../common/petsc_check.h"
#include "../mesh/generate.h"
#include "../mesh/symmetry.h"
#include "../model/Model.h"
#include "../output/CurveWriter.h"
#include "../output/FieldWriter.h"
#include "../output/plot.h"
#include "../scene/SceneError.h"
#include "../solver/ArcLengthSolver.h"
#include "../solver/LoadStepSolver.h"
#include "PushOut.h"
#include "ResourceGuard.h"
#include "SingleJoint.h"
#include "Stepper.h"
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/la/petsc.h>
#include <fstream>
#include <functional>
#include <iostream>
#include <mutex>
#include <optional>
#include <sstream>
#include <sys/resource.h>

namespace pushout::driver
{
using petsc::check;

namespace
{
using Clock = std::chrono::steady_clock;

/// How long a signal may wait for a load step to stop by itself (between
/// Newton iterations) before the process is ended where it is, e.g. inside a
/// long factorisation [s].
constexpr double stop_grace_s = 5;
double seconds_since(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Peak resident memory of this process so far [MB].
double peak_memory_here_mb()
{
  rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;
}

/// Test hook, not a scene key (tests/e2e/test_mpi_errors.py): with the
/// environment variables PUSHOUT_TEST_FAIL_RANK=r and PUSHOUT_TEST_FAIL_AT=
/// `at`, process r alone throws here, as an error found on one process
/// only would: "setup" at the end of the set-up, "step" after two load
/// steps, "collective" there too but where the others next wait in a
/// collective that is no agreement (common/mpi_errors.h: the run ends
/// with MPI_Abort after abandon_after_s).
void test_failure(const char* at)
{
  static const char* fail_rank = std::getenv("PUSHOUT_TEST_FAIL_RANK");
  static const char* fail_at = std::getenv("PUSHOUT_TEST_FAIL_AT");
  if (!fail_rank || !fail_at || std::string(fail_at) != at)
    return;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == std::atoi(fail_rank))
    throw std::runtime_error(std::string("test failure on process ") + fail_rank + " at " + at +
                             " (PUSHOUT_TEST_FAIL_AT)");
}

/// Whether a signal asked to stop (agreed on by all processes); records it.
/// First, an error of any process since the last agreement is thrown here
/// on all (common/mpi_errors.h).
bool stop_requested(output::Summary& summary)
{
  if (summary.steps == 2)
    test_failure("step");
  mpi::checkpoint(MPI_COMM_WORLD);
  if (summary.steps == 2)
    test_failure("collective");
  int local = interrupt::received(), global = 0;
  MPI_Allreduce(&local, &global, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  if (global == 0)
    return false;
  summary.interrupted = true;
  summary.signal = global;
  summary.stopped_in = "load steps";
  summary.message = "interrupted by " + interrupt::signal_name(global) + " after " +
                    std::to_string(summary.steps) + " load steps";
  return true;
}

/// What the step loops share: the model, the solvers, the committed state
/// and the outputs.
struct StepLoop
{
  Scenario& scenario;
  model::Model& model;
  solver::Equilibrium& equilibrium;
  solver::LoadStepSolver& solver;
  Vec x, x_committed;
  output::Summary& summary;
  std::function<void(int iterations, int cuts, int step, int steps)> record;
  bool talk;
  int max_cuts;

  std::function<void()> publish; ///< the summary for a forced stop

  void commit()
  {
    model.interface->state().commit();
    check(VecCopy(x, x_committed), "VecCopy");
    ++summary.steps;
    publish();
  }
  void revert()
  {
    model.interface->state().revert();
    check(VecCopy(x_committed, x), "VecCopy");
  }
};

/// Displacement control: each nominal step is tried whole and cut in halves
/// (from the committed state) when Newton fails; increments grow back after
/// easy convergence (Stepper.h). A signal stops the loop between tries.
bool step_displacement(StepLoop& L)
{
  Stepper stepper(L.max_cuts, 4);
  double s = 0.0;
  for (int k = 1; k <= L.scenario.steps(); ++k)
  {
    int cuts = 0;
    while (s < double(k) - 1e-12)
    {
      if (stop_requested(L.summary))
        return false;
      const double s_try = stepper.next(s, double(k));
      L.scenario.apply_load(s_try, L.equilibrium);
      L.model.interface->set_time_increment(L.scenario.time_at(s_try) - L.scenario.time_at(s));
      L.equilibrium.apply_constraints(L.x);
      const solver::SolveReport rep = L.solver.solve(L.x);
      L.summary.newton_iterations += rep.iterations;
      if (rep.converged)
      {
        L.record(rep.iterations, cuts, k, L.scenario.steps()); // before the commit: see record
        L.commit();
        s = s_try;
        stepper.converged(rep.iterations);
        continue;
      }
      L.revert();
      if (stop_requested(L.summary))
        return false;
      if (!stepper.failed())
      {
        L.summary.message = "load step " + std::to_string(k) + " did not converge with " +
                            std::to_string(cuts) + " cuts, down to " +
                            std::to_string(stepper.increment()) + " of a step (" + rep.reason +
                            "); stopped";
        return false;
      }
      ++cuts;
      ++L.summary.cuts;
      if (L.talk)
        std::cout << "step " << k << ": " << rep.reason << "; retrying with " << stepper.increment()
                  << " of a step" << std::endl;
    }
  }
  return true;
}

/// Path following (solver/ArcLengthSolver.h) in steps of length
/// h = lambda_final / steps in the plane (lambda, s) of the push delta and
/// the mean slip [mm]. The first step is displacement-controlled (delta =
/// h); each later one prescribes the slip increment of the previous step
/// scaled to length h,  ds = ds_prev h / |(dlambda_prev, ds_prev)|,  which
/// depends only on converged states (not on the tangent at a kink of the
/// laws). Failed steps are halved, easy ones grow back (Stepper.h). The step
/// that would pass lambda_final is replaced by a displacement-controlled step
/// to exactly lambda_final.
bool follow_path(StepLoop& L, solver::NewtonSolver::Preconditioner pc, int refactor_iterations)
{
  const double lambda_final = L.scenario.final_load_factor();
  if (!(lambda_final > 0))
  {
    L.summary.message = "path following needs a positive final push displacement";
    return false;
  }
  // The constraints of the push (their dofs stay; only values move) before
  // the solver's problem is taken.
  L.scenario.apply_load_factor(0.0, L.equilibrium);
  Vec a_whole = L.model.mean_axial_slip_functional();
  Vec a = L.solver.functional(a_whole);
  solver::ArcLengthSolver arc(L.solver.problem(), a, pc, refactor_iterations);
  check(VecDestroy(&a), "VecDestroy");
  check(VecDestroy(&a_whole), "VecDestroy");
  // Counts the arc solver's factorisations on every way out.
  struct Count
  {
    output::Summary& s;
    const solver::ArcLengthSolver& arc;
    ~Count() { s.factorizations += arc.factorizations(); }
  } count{L.summary, arc};
  const double h_nominal = lambda_final / L.scenario.steps(); // [mm]
  // Snap-back makes the path longer than lambda_final; this bounds a run
  // whose path never reaches it.
  const int max_steps = 20 * L.scenario.steps() + 100;
  const auto set_load = [&](double lambda) { L.scenario.apply_load_factor(lambda, L.equilibrium); };
  // Displacement-controlled step to lambda (first and last steps).
  const auto displacement_step = [&](double lambda_from, double lambda_to)
  {
    set_load(lambda_to);
    L.model.interface->set_time_increment(lambda_to - lambda_from);
    L.equilibrium.apply_constraints(L.x);
    return L.solver.solve(L.x);
  };
  Stepper stepper(L.max_cuts, 4);
  const auto slip_of = [&] { return arc.control(L.solver.to_problem(L.x)); };
  double lambda = 0.0, slip = slip_of();
  double d_lambda_prev = 0.0, d_slip_prev = 0.0; // the last converged step
  int cuts = 0;
  for (int k = 1; lambda < lambda_final;)
  {
    if (stop_requested(L.summary))
      return false;
    if (k > max_steps)
    {
      L.summary.message = "path following did not reach the final push displacement in " +
                          std::to_string(max_steps) + " steps (delta = " + std::to_string(lambda) +
                          " mm); stopped";
      return false;
    }
    const double h = stepper.increment() * h_nominal;
    double lambda_new = lambda;
    solver::SolveReport rep;
    if (k == 1)
    {
      lambda_new = std::min(h, lambda_final);
      rep = displacement_step(lambda, lambda_new);
    }
    else
    {
      const double d_slip = d_slip_prev * h / std::hypot(d_lambda_prev, d_slip_prev);
      L.model.interface->set_time_increment(h);
      rep = arc.step(L.solver.to_problem(L.x), lambda_new, d_slip, set_load);
      if (rep.converged)
        L.solver.from_problem(L.x);
      if (rep.converged && lambda_new > lambda_final)
      {
        L.summary.newton_iterations += rep.iterations;
        L.revert();
        lambda_new = lambda_final;
        rep = displacement_step(lambda, lambda_new);
      }
    }
    L.summary.newton_iterations += rep.iterations;
    if (rep.converged)
    {
      const double slip_new = slip_of();
      if (!(slip_new > slip))
      {
        L.revert();
        L.summary.message = "path following: the mean slip did not grow in step " +
                            std::to_string(k) + "; the push cannot be followed by slip control";
        return false;
      }
      L.record(rep.iterations, cuts, k, 0); // before the commit: see record
      L.commit();
      d_lambda_prev = lambda_new - lambda;
      d_slip_prev = slip_new - slip;
      lambda = lambda_new;
      slip = slip_new;
      stepper.converged(rep.iterations);
      cuts = 0;
      ++k;
      continue;
    }
    L.revert();
    if (stop_requested(L.summary))
      return false;
    if (!stepper.failed())
    {
      std::ostringstream m;
      m << "path-following step " << k << " did not converge with " << cuts
        << " cuts, down to a length of " << stepper.increment() * h_nominal << " mm (" << rep.reason
        << "); stopped";
      L.summary.message = m.str();
      return false;
    }
    ++cuts;
    ++L.summary.cuts;
    if (L.talk)
      std::cout << "step " << k << ": " << rep.reason << "; retrying with length "
                << stepper.increment() * h_nominal << " mm" << std::endl;
  }
  return true;
}

/// Whether Newton runs on the condensed interface system (solver/
/// Condensation.h); if not, `why` gets " (reason)" unless it was asked for.
bool use_condensation(const Scene& scene, const solver::Equilibrium& eq, std::string& why)
{
  const std::string mode = scene.string("solver.condensation");
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  std::string reason;
  const bool can = solver::Condensation::chosen(
      mode, size, solver::Condensation::interface_dofs(eq.model()), reason);
  if (!can && mode == "on")
    throw SceneError("solver.condensation = \"on\" is not possible here: " + reason);
  if (!can && !reason.empty())
    why = " (not condensed: " + reason + ")";
  return can;
}

/// Why a push-out runs on the full model, for the progress line ("" if it
/// does not or is not a push-out).
std::string full_model_why(const Scene& scene)
{
  std::string why;
  if (mesh::use_quarter_model(scene, why) || why.empty())
    return "";
  return " (full model: " + why + ")";
}

std::unique_ptr<Scenario> make_scenario(const Scene& scene, const mesh::MeshData& m,
                                        const model::Model& model)
{
  if (scene.string("model.type") == "single_joint")
    return std::make_unique<SingleJoint>(scene, m, model);
  return std::make_unique<PushOut>(scene, m, model);
}
} // namespace

output::Summary run(const Scene& scene, const RunOptions& opt)
{
  const auto t_start = Clock::now();
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const bool talk = rank == 0 && !opt.quiet;

  output::Summary summary;
  summary.model_type = scene.string("model.type");
  summary.processes = size;
  if (rank == 0)
  {
    std::ofstream(opt.out / "scene.toml") << scene.to_toml();
  }

  // What a stop forced by a signal reports (common/Interrupt.h): the state
  // last published by the run, and where it was.
  std::mutex published_mutex;
  output::Summary published = summary;
  const auto publish = [&]
  {
    std::lock_guard lock(published_mutex);
    published = summary;
  };
  const interrupt::ReportOnStop on_stop(
      [&, rank](int sig, const std::string& phase)
      {
        std::lock_guard lock(published_mutex);
        output::Summary s = published;
        s.interrupted = true;
        s.converged = false;
        s.signal = sig;
        s.stopped_in = phase;
        s.message = "interrupted by " + interrupt::signal_name(sig) + " during " + phase +
                    " after " + std::to_string(s.steps) + " load steps";
        s.wall_s = seconds_since(t_start);
        s.peak_memory_mb = peak_memory_here_mb();
        if (rank != 0)
          return;
        s.write(opt.out / "summary.json");
        std::cerr << "pushout: " << s.message << "; " << (opt.out / "summary.json").string()
                  << " says so" << std::endl;
      });
  std::optional<interrupt::Phase> phase;

  // The size guard, before meshing.
  const ResourceEstimate estimate = estimate_resources(scene, MPI_COMM_WORLD);
  check_fits(estimate, scene, opt.force);
  summary.estimate = {estimate.size.dofs, estimate.size.cells, estimate.size.joint_elements,
                      estimate.peak_mb()};
  summary.symmetry = estimate.size.quarter ? "quarter" : "full";
  publish();
  if (talk)
    std::cout << "pushout: meshing " << estimate.size.cells << " cells (" << estimate.memory()
              << " at the peak)" << std::endl;

  // Mesh.
  phase.emplace("meshing", 0);
  auto t0 = Clock::now();
  const mesh::MeshData data = mesh::generate(scene, opt.mesh_cache, summary.mesh_reused);
  summary.mesh_s = seconds_since(t0);

  // Model: spaces, bulk stiffness, interface.
  phase.emplace("set-up", 0);
  t0 = Clock::now();
  model::Model model(MPI_COMM_WORLD, data, scene);
  const std::unique_ptr<Scenario> scenario = make_scenario(scene, data, model);
  const auto pc = scene.string("solver.preconditioner") == "lagged"
                      ? solver::NewtonSolver::Preconditioner::lagged
                      : solver::NewtonSolver::Preconditioner::jacobian;
  solver::NewtonSolver::set_default_options(pc);
  solver::Equilibrium equilibrium(model);
  std::string whole_why;
  const bool condense = use_condensation(scene, equilibrium, whole_why);
  solver::LoadStepSolver step_solver(equilibrium, condense, pc,
                                     int(scene.integer("solver.refactor_iterations")));
  summary.dofs = model.num_dofs();
  summary.cells = std::int64_t(data.num_cells());
  summary.symmetry = data.copies == 4 ? "quarter" : "full";
  const std::int64_t local_pairs = std::int64_t(model.interface->num_pairs());
  MPI_Allreduce(&local_pairs, &summary.interface_pairs, 1, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD);
  if (talk) // before the condensation, which takes a while on a large interface
    std::cout << "pushout: " << summary.model_type << ", " << summary.cells << " cells, "
              << summary.dofs << " dofs, " << summary.interface_pairs << " joint elements"
              << (data.copies == 4 ? " (quarter model by symmetry)" : full_model_why(scene))
              << (summary.mesh_reused ? " (mesh from cache)" : "") << "; Newton on "
              << (condense
                      ? "the " + std::to_string(solver::Condensation::interface_dofs(model) / 2) +
                            " interface jumps (bulk condensed)"
                      : "the whole model" + whole_why)
              << std::endl;
  scenario->apply_load(0.0, equilibrium); // the constraints of step 0
  step_solver.problem();                  // the condensation, if any
  summary.condensed_dofs = step_solver.condensed_size();
  summary.setup_s = seconds_since(t0);
  test_failure("setup");
  mpi::checkpoint(MPI_COMM_WORLD); // an error of the set-up on any process

  const auto& map = *model.V->dofmap()->index_map;
  const int bs = model.V->dofmap()->index_map_bs();
  Vec x = dolfinx::la::petsc::create_vector(map, bs);
  Vec x_committed, reactions;
  check(VecSet(x, 0.0), "VecSet");
  check(VecDuplicate(x, &x_committed), "VecDuplicate");
  check(VecDuplicate(x, &reactions), "VecDuplicate");
  check(VecCopy(x, x_committed), "VecCopy");

  // curve.csv: rank 0 writes it; every process learns whether it could.
  std::optional<output::CurveWriter> curve;
  mpi::collectively(MPI_COMM_WORLD,
                    [&]
                    {
                      if (rank != 0)
                        return;
                      auto c = scenario->columns();
                      c.insert(c.end(), {"newton_iterations", "cuts", "wall_s"});
                      curve.emplace(opt.out / "curve.csv", c);
                    });
  std::unique_ptr<output::FieldWriter> fields;
  if (scene.boolean("output.xdmf"))
    fields = std::make_unique<output::FieldWriter>(model, opt.out);

  // A condensed solver recovers the bulk after each load step only if an
  // output reads it (step 0 always: start_loading reads the whole x).
  const bool bulk_needed = scenario->uses_bulk() || fields != nullptr;

  // Records the converged state of a step as a curve row, before it is
  // committed: evaluating the laws again (the reactions) from the committed
  // state would advance a viscous law a second time.
  int row_index = 0;
  const auto record = [&](int iterations, int cuts, int step, int steps)
  {
    const interrupt::Phase writing("writing step outputs", -1);
    const auto t_out = Clock::now();
    if (bulk_needed)
      equilibrium.internal_forces(x, reactions);
    else
      equilibrium.update_displacement(x); // the interface reads model.u
    const double* r;
    const double* xa;
    check(VecGetArrayRead(reactions, &r), "VecGetArrayRead");
    check(VecGetArrayRead(x, &xa), "VecGetArrayRead");
    PetscInt n;
    check(VecGetLocalSize(x, &n), "VecGetLocalSize");
    std::vector<double> values =
        scenario->row(std::span<const double>(r, n), std::span<const double>(xa, n), model);
    check(VecRestoreArrayRead(reactions, &r), "VecRestoreArrayRead");
    check(VecRestoreArrayRead(x, &xa), "VecRestoreArrayRead");
    const std::string line = scenario->progress(values);
    values.insert(values.end(), {double(iterations), double(cuts), seconds_since(t_start)});
    mpi::collectively(MPI_COMM_WORLD,
                      [&]
                      {
                        if (rank == 0)
                          curve->row(row_index, values);
                      });
    if (fields)
      fields->write(double(row_index));
    ++row_index;
    summary.output_s += seconds_since(t_out);
    if (talk)
    {
      std::cout << "step " << step;
      if (steps > 0) // path following does not know its number of steps
        std::cout << "/" << steps;
      std::cout << "  " << line << "  (newton " << iterations
                << (cuts ? ", cuts " + std::to_string(cuts) : "") << ", " << std::fixed
                << std::setprecision(2) << seconds_since(t_start) << " s)" << std::defaultfloat
                << std::endl;
    }
  };

  // The floor: one linear solve of the first load step (the thermal load
  // included), from the unloaded state.
  if (scene.boolean("solver.time_linear_solve"))
  {
    scenario->apply_load(1.0, equilibrium);
    equilibrium.apply_constraints(x);
    summary.linear_solve_s = step_solver.time_linear_solve(x);
    check(VecSet(x, 0.0), "VecSet");
    if (talk)
      std::cout << "one linear solve: " << summary.linear_solve_s << " s" << std::endl;
  }

  // Step 0: the thermal step or preload (if the scenario has one).
  publish();
  phase.emplace("load steps", stop_grace_s);
  t0 = Clock::now();
  scenario->apply_load(0.0, equilibrium);
  int its0 = 0;
  bool ok = true;
  if (scenario->initial_solve() && stop_requested(summary))
    ok = false;
  else if (scenario->initial_solve())
  {
    // The thermal step (or preload) takes the pseudo-time of one nominal
    // load step, so that a viscous damage layer damages in it as it would in
    // one step of the push (without it, dt = 0 would freeze its damage).
    model.interface->set_time_increment(scenario->time_at(1.0) - scenario->time_at(0.0));
    equilibrium.apply_constraints(x);
    const solver::SolveReport rep =
        mpi::collectively(MPI_COMM_WORLD, [&] { return step_solver.solve(x); });
    its0 = rep.iterations;
    summary.newton_iterations += rep.iterations;
    ok = rep.converged;
    if (!ok && !stop_requested(summary))
      summary.message = "step 0 (initial/thermal step) did not converge: " + rep.reason;
  }
  step_solver.set_bulk_needed(bulk_needed);
  if (ok)
  {
    const double* xa;
    PetscInt n;
    check(VecGetLocalSize(x, &n), "VecGetLocalSize");
    check(VecGetArrayRead(x, &xa), "VecGetArrayRead");
    scenario->start_loading(std::span<const double>(xa, n));
    check(VecRestoreArrayRead(x, &xa), "VecRestoreArrayRead");
    record(its0, 0, 0, scenario->steps()); // before the commit: see record
    model.interface->state().commit();
    check(VecCopy(x, x_committed), "VecCopy");
  }

  // Load steps.
  StepLoop loop{
      *scenario,   model,   equilibrium, step_solver, x,
      x_committed, summary, record,      talk,        int(scene.integer("loading.max_cuts")),
      publish};
  // An error on one process is agreed on here, where the solvers still
  // live: destroying a MUMPS factor is collective, so a process must not
  // leave with it while the others go on (common/mpi_errors.h).
  if (ok)
    ok = mpi::collectively(
        MPI_COMM_WORLD,
        [&]
        {
          return scenario->has_load_factor() && scene.string("loading.control") == "arc_length"
                     ? follow_path(loop, pc, int(scene.integer("solver.refactor_iterations")))
                     : step_displacement(loop);
        });
  phase.emplace("writing outputs", -1);
  summary.solve_s = seconds_since(t0) - summary.output_s;
  summary.converged = ok;
  summary.factorizations += step_solver.factorizations();
  check(VecDestroy(&x), "VecDestroy");
  check(VecDestroy(&x_committed), "VecDestroy");
  check(VecDestroy(&reactions), "VecDestroy");
  fields.reset();

  if (rank == 0 && scene.boolean("output.plot"))
  {
    std::string why;
    if (!output::plot_curve(opt.out / "curve.csv", opt.out / "curve.png", summary.model_type, why))
      std::cerr << "pushout: warning: no curve.png: " << why << std::endl;
  }
  summary.wall_s = seconds_since(t_start);
  // Peak resident memory, the largest over the processes [MB].
  double peak_mb = peak_memory_here_mb();
  MPI_Allreduce(MPI_IN_PLACE, &peak_mb, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  summary.peak_memory_mb = peak_mb;
  if (rank == 0)
    summary.write(opt.out / "summary.json");
  return summary;
}
} // namespace pushout::driver

#include "Run.h"
#include "../common/Interrupt.h"
#include "../common/exit_codes.h"
#include "../common/mpi_errors.h"
#include "../mesh/generate.h"
#include "../mesh/symmetry.h"
#include "../model/Model.h"
#include "../record/ResourceGuard.h"
#include "../record/RunReport.h"
#include "../scene/SceneError.h"
#include "../solver/LoadStepSolver.h"
#include "../specimen/Corrosion.h"
#include "../specimen/Scenario.h"
#include "../stepping/StepLoop.h"
#include "../stepping/StepRecorder.h"
#include <chrono>
#include <functional>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>

namespace pushout::driver
{
namespace
{
/// Before the run's first line: what the scene sets that nothing reads
/// (Scene::unread_keys: a key of a switched-off part is most likely a
/// slip, but not an error), and values that are valid but may not run well
/// (specimen::scene_notes); summary.json keeps them (a --quiet run's too).
void note_scene(const Scene& scene, record::RunReport& report)
{
  std::vector<std::string>& notes = report.summary().notes;
  notes = scene.unread_keys();
  for (const std::string& note : specimen::scene_notes(scene))
    notes.push_back(note);
  if (report.talk())
    for (const std::string& note : notes)
      std::cout << "pushout: note: " << note << std::endl;
}

/// Whether the first progress line may say that the mesh comes from the
/// cache (generate() still says so if the file proves unreadable, and
/// reports an error of the .geo file or of the cache's bound itself).
bool mesh_cached(const mesh::MeshInput& shape, const std::filesystem::path& cache_dir)
{
  try
  {
    return mesh::in_cache(shape, cache_dir);
  }
  catch (const std::exception&)
  {
    return false;
  }
}

/// Before meshing: the size guard (throws TooLarge unless the run fits or
/// --force), its estimate into the summary and the first progress line.
void guard_size(const mesh::MeshInput& shape, const Scene& scene, const RunOptions& opt,
                record::RunReport& report)
{
  const record::ResourceEstimate estimate = record::estimate_resources(
      shape, scene.solver(), scene.cracking(), opt.comm, opt.others_here);
  record::check_fits(estimate, shape, opt.force);
  output::Summary& s = report.summary();
  s.estimate = {estimate.size.dofs, estimate.size.cells, estimate.size.joint_elements,
                estimate.peak_mb()};
  s.symmetry = estimate.size.symmetry.name();
  report.publish();
  if (report.talk())
    std::cout << "pushout: "
              << (mesh_cached(shape, opt.mesh_cache) ? "the cached mesh, " : "meshing ")
              << estimate.size.cells << " cells, " << estimate.size.dofs << " dofs, "
              << estimate.size.joint_elements << " joint elements (" << estimate.memory()
              << " at the peak)" << std::endl;
}

/// The model's size into the summary, and the progress line that says what
/// was built and what Newton runs on (before the condensation, which takes
/// a while on a large interface).
void describe_model(const mesh::MeshInput& shape, const mesh::MeshData& data,
                    const model::Model& model, const solver::LoadStepSolver& solver,
                    record::RunReport& report)
{
  output::Summary& s = report.summary();
  s.dofs = model.num_dofs();
  s.cells = std::int64_t(data.num_cells());
  const mesh::Symmetry symmetry = mesh::symmetry_of(data);
  s.symmetry = symmetry.name();
  std::int64_t local_pairs = 0; // joint elements: interface and crack planes
  for (const interface::Interface* joints : model.joints())
    local_pairs += std::int64_t(joints->num_pairs());
  MPI_Allreduce(&local_pairs, &s.interface_pairs, 1, MPI_INT64_T, MPI_SUM, model.comm());
  report.publish(); // a signal during the rest of the set-up reports the model's size
  if (!report.talk())
    return;
  std::string cut;
  std::string why;
  mesh::model_symmetry(shape, why);
  if (symmetry.copies() == 4)
    cut = " (quarter model by symmetry)";
  else if (symmetry.copies() == 2)
  {
    std::ostringstream plane;
    plane << (symmetry.x_plane ? "x = " : "y = ") << data.symmetry_center[symmetry.x_plane ? 0 : 1]
          << " mm";
    cut = " (half model by symmetry about " + plane.str() + "; " + why + ")";
  }
  else if (s.model_type == "pushout" && !why.empty())
    cut = " (full model: " + why + ")";
  if (symmetry.copies() > 1 && shape.bulk_cracking) // docs/cracking.md, "Reading the cracks"
    cut += " (the surface cracks read are the modelled part's, one on a symmetry plane whole "
           "with its mirror image)";
  std::cout << "pushout: " << s.model_type << ", " << s.cells << " cells, " << s.dofs << " dofs, "
            << s.interface_pairs << " joint elements" << cut
            << (s.mesh_reused ? " (mesh from cache)" : "") << "; Newton on " << solver.description()
            << std::endl;
}
} // namespace

Simulation::Simulation(const Scene& scene, const RunOptions& opt, record::RunReport& report)
    : _fingerprint(set_up_fingerprint(scene))
{
  output::Summary& summary = report.summary();
  const mesh::MeshInput shape = mesh::MeshInput::of(scene);
  guard_size(shape, scene, opt, report);

  // Mesh.
  std::optional<interrupt::Phase> phase(std::in_place, "meshing", 0);
  double t0 = report.seconds();
  _data = mesh::generate(shape, opt.mesh_cache, summary.mesh_reused, opt.comm);
  summary.mesh_s = report.seconds() - t0;

  // Model and the solver of a load step.
  phase.emplace("set-up", 0);
  t0 = report.seconds();
  _model = std::make_unique<model::Model>(opt.comm, _data, model::ModelInput::of(scene));
  stepping::test_failure_in_setup(opt.comm);
  _equilibrium = std::make_unique<solver::Equilibrium>(*_model);
  _solver = solver::LoadStepSolver::make(*_equilibrium, scene.solver());
  _solver->set_talk(report.talk());
  describe_model(shape, _data, *_model, *_solver, report);
  specimen::make_scenario(scene, _data, *_model)
      ->apply_load(0.0, *_equilibrium); // step 0's constraints
  _solver->prepare();                   // the condensation, if any
  summary.condensed_dofs = _solver->condensed_size();
  summary.condensation_asymmetry = _solver->condensation_asymmetry();
  summary.setup_s = report.seconds() - t0;
  _set_up = summary;
  stepping::test_failure_at_setup(opt.comm);
  mpi::checkpoint(opt.comm); // an error of the set-up on any process
}

Simulation::~Simulation() = default;

std::string Simulation::set_up_fingerprint(const Scene& scene)
{
  std::ostringstream s;
  s << std::setprecision(17);
  for (const KeyDef& k : scene_keys())
    for (const char* prefix :
         {"model.", "geometry.", "mesh.", "concrete.", "steel.", "cracking.", "solver."})
      if (const Value* v = scene.find(k.path); v && k.path.starts_with(prefix))
        s << k.path << "=" << to_toml(*v) << "\n";
  if (scene.model().pushout())
    s << "loading.thermal_tube_top=" << (scene.loading().tube_top_free ? "free" : "held") << "\n";
  // Fields take the whole slice under model.symmetry = "auto" (mesh/symmetry.h).
  s << "output.xdmf=" << scene.output().xdmf << "\n";
  for (const CrackSpec& c : scene.cracks())
    s << "crack.angle=" << (c.angle_deg ? std::to_string(*c.angle_deg) : "nearest_face") << "\n";
  return s.str();
}

namespace
{
/// While it lives, what the run publishes has the solver's counts so far
/// (RunReport::set_counters); add_to_summary() adds them to the summary
/// once, at the steps' end, or its destructor does where an error leaves
/// them (the summary.json of the error then has them).
class PublishedSolverCounts
{
public:
  using Counts = std::function<void(output::Summary&)>;
  PublishedSolverCounts(record::RunReport& report, Counts counts)
      : _report(report), _counts(std::move(counts))
  {
    _report.set_counters(_counts);
  }
  PublishedSolverCounts(const PublishedSolverCounts&) = delete;
  PublishedSolverCounts& operator=(const PublishedSolverCounts&) = delete;
  void add_to_summary()
  {
    if (_added)
      return;
    _added = true;
    _report.set_counters({});
    _counts(_report.summary());
  }
  ~PublishedSolverCounts() { add_to_summary(); }

private:
  record::RunReport& _report;
  Counts _counts;
  bool _added = false;
};
} // namespace

void Simulation::load_steps(const Scene& scene, const RunOptions& opt, record::RunReport& report)
{
  output::Summary& summary = report.summary();
  if (_runs++ > 0)
  {
    // The set-up of an earlier scene: its sizes, no time.
    summary.estimate = _set_up.estimate;
    summary.symmetry = _set_up.symmetry;
    summary.mesh_reused = true;
    summary.dofs = _set_up.dofs;
    summary.cells = _set_up.cells;
    summary.interface_pairs = _set_up.interface_pairs;
    summary.condensed_dofs = _set_up.condensed_dofs;
    summary.condensation_asymmetry = _set_up.condensation_asymmetry;
    summary.setup_reused = true;
    _model->set_laws(model::JointLaws::of(scene));
    _equilibrium->restart();
    _solver->restart();
  }
  const std::unique_ptr<specimen::Scenario> scenario =
      specimen::make_scenario(scene, _data, *_model);
  scenario->apply_load(0.0, *_equilibrium);
  const int factorizations_before = _solver->factorizations();
  const std::int64_t linear_before = _solver->linear_iterations();

  // Outputs and load steps.
  specimen::Corrosion corrosion(scene.corrosion(), scene.crack_directions(),
                                scene.cracking().embedded, opt.out, report, opt.comm,
                                mesh::symmetry_of(_data), scene.geometry());
  stepping::StepRecorder recorder(scene.output(), opt.out, *scenario, *_equilibrium, report,
                                  corrosion.active());
  const Loading& loading = scene.loading();
  stepping::StepLoop loop(*scenario, corrosion, *_equilibrium, *_solver, recorder, report,
                          int(loading.max_cuts),
                          scenario->has_load_factor() ? int(loading.dissipation_steps) : 1);
  if (scene.solver().time_linear_solve)
    loop.time_linear_solve();
  report.publish();
  std::optional<interrupt::Phase> phase(std::in_place, "load steps", interrupt::stop_grace_s);
  const double t0 = report.seconds();
  // The solver's time and counts so far: in what each step publishes (a
  // forced stop's summary.json), and in the summary at the steps' end, or
  // where an error leaves them (its summary.json).
  PublishedSolverCounts counts(report,
                               [&report, t0, solver = _solver.get(), factorizations_before,
                                linear_before](output::Summary& s)
                               {
                                 s.solve_s = report.seconds() - t0 - s.output_s;
                                 s.factorizations +=
                                     solver->factorizations() - factorizations_before;
                                 s.linear_iterations += solver->linear_iterations() - linear_before;
                               });
  const auto control = [&]
  {
    if (!scenario->has_load_factor())
      return stepping::StepLoop::Control::displacement;
    switch (loading.control)
    {
    case Loading::Control::displacement:
      return stepping::StepLoop::Control::displacement;
    case Loading::Control::arc_length:
      return stepping::StepLoop::Control::arc_length;
    default:
      return stepping::StepLoop::Control::dissipation; // "dissipation" or "auto"
    }
  }();
  // An error on one process is agreed on here, where the solvers still
  // live: destroying a MUMPS factor is collective, so a process must not
  // leave with it while the others go on (common/mpi_errors.h).
  summary.converged = mpi::collectively(opt.comm, [&] { return loop.run(control); });
  if (const model::BulkCracking* cracking = _model->bulk_cracking())
    corrosion.note_edge_cracks(cracking->edge_cracks());

  phase.emplace("writing outputs", -1);
  counts.add_to_summary();
  recorder.close();
}

namespace
{
/// Runs `f` (the run's steps and its end) on the run's processes `comm`;
/// an error other than a bad scene or size (which write nothing) is in
/// summary.json too, where it fits. Agreed on here, while the report lives:
/// a process whose error the others do not come to agree on (they wait in
/// a collective it skipped) then ends the run with its abandon report
/// (RunReport::abandoned), so that summary.json says that error.
template <class F> output::Summary reporting_errors(record::RunReport& report, MPI_Comm comm, F&& f)
{
  try
  {
    return mpi::collectively<OptionError, SceneError, record::TooLarge>(comm, f);
  }
  catch (const SceneError&)
  {
    throw;
  }
  catch (const record::TooLarge&)
  {
    throw;
  }
  catch (const std::exception& e)
  {
    report.fail(e.what());
    throw;
  }
  catch (const std::string& e) // gmsh reports errors this way
  {
    report.fail(e);
    throw;
  }
}
} // namespace

void check_solver_options(const Scene& scene, int processes)
{
  const CrackingPart& cracking = scene.cracking();
  solver::LoadStepSolver::check_options(
      scene.solver(), solver::LoadStepSolver::concrete(cracking.embedded, cracking.implex),
      processes);
}

void check_before_run(const Scene& scene, const RunOptions& opt)
{
  specimen::check_scene(scene);
  int processes = 1;
  MPI_Comm_size(opt.comm, &processes);
  check_solver_options(scene, processes);
  const mesh::MeshInput shape = mesh::MeshInput::of(scene);
  record::check_fits(record::estimate_resources(shape, scene.solver(), scene.cracking(), opt.comm,
                                                opt.others_here),
                     shape, opt.force);
  (void)mesh::cache_limit_mb(); // throws on a $PUSHOUT_CACHE_MAX_MB that is no size
}

output::Summary run(const Scene& scene, const RunOptions& opt)
{
  record::RunReport report(scene, opt.out, opt.quiet, opt.comm, opt.plot);
  note_scene(scene, report);
  return reporting_errors(report, opt.comm,
                          [&]
                          {
                            auto simulation = std::make_unique<Simulation>(scene, opt, report);
                            // What the steps' phases return to: never forced
                            // (the step loop looks at a signal that comes
                            // before it starts).
                            const interrupt::Phase writing("writing outputs", -1);
                            simulation->load_steps(scene, opt, report);
                            // The steps are done: a signal that the loop
                            // did not see stops nothing (the outputs are
                            // whole and the run ends as it would have; a
                            // second signal still ends the process at
                            // once). Without this, one after the writing
                            // was forced in the phase that returned, exit
                            // 128 + signal beside a summary that said
                            // converged.
                            interrupt::acknowledge();
                            const output::Summary s = report.finish();
                            simulation.reset();
                            return s;
                          });
}

RunOutcome run_case(const std::string& scene_text, const std::filesystem::path& scene_file,
                    const std::vector<std::string>& sets, const RunOptions& opt,
                    std::unique_ptr<Simulation>& simulation)
{
  RunOutcome r;
  const auto t0 = std::chrono::steady_clock::now();
  try
  {
    const output::Summary s = mpi::collectively<OptionError, SceneError, record::TooLarge>(
        opt.comm,
        [&]
        {
          // A run that fails before its outputs, its scene's values
          // included, must not leave an earlier run's in the folder (a fit
          // reads curve.csv back).
          int rank = 0;
          MPI_Comm_rank(opt.comm, &rank);
          if (rank == 0)
          {
            std::filesystem::create_directories(opt.out);
            for (const char* f : {"curve.csv", "summary.json", "corrosion.csv"})
              std::filesystem::remove(opt.out / f);
          }
          const Scene scene = Scene::parse(scene_text, parse_overrides(sets), scene_file.string());
          specimen::check_scene(scene);
          record::RunReport report(scene, opt.out, opt.quiet, opt.comm, opt.plot);
          note_scene(scene, report);
          return reporting_errors(report, opt.comm,
                                  [&]
                                  {
                                    if (!simulation || !simulation->fits(scene))
                                    {
                                      simulation.reset(); // its memory first
                                      simulation = std::make_unique<Simulation>(scene, opt, report);
                                    }
                                    simulation->load_steps(scene, opt, report);
                                    const interrupt::Phase writing("writing outputs",
                                                                   -1); // never forced
                                    return report.finish();
                                  });
        });
    r.exit_code = s.interrupted ? exit_code::signal(s.signal)
                  : s.converged ? exit_code::done
                                : exit_code::not_converged;
    r.message = s.message;
  }
  catch (const SceneError& e)
  {
    r.exit_code = exit_code::bad_input;
    r.message = std::string(RunOutcome::scene_label) + e.what();
    r.refused = RunOutcome::Refusal::scene;
  }
  catch (const record::TooLarge& e)
  {
    r.exit_code = exit_code::bad_input;
    r.message = e.what();
    r.refused = RunOutcome::Refusal::size;
  }
  catch (const std::exception& e)
  {
    r.exit_code = exit_code::failure;
    r.message = e.what();
  }
  catch (const std::string& e) // gmsh reports errors this way
  {
    r.exit_code = exit_code::failure;
    r.message = e;
  }
  if (r.exit_code == exit_code::failure || r.exit_code == exit_code::bad_input)
    simulation.reset(); // an error may have left it half built: not reused
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

} // namespace pushout::driver

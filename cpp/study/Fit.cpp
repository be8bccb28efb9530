// `pushout fit` (Fit.h): its set-up (the measured curve, the free values and
// their bounds, the checks of the scene) and its steps: TAO on the runs, the
// statistics at the optimum, the fitted run in DIR/best, the files written.
#include "Fit.h"
#include "../common/Interrupt.h"
#include "../common/exit_codes.h"
#include "../common/mpi_errors.h"
#include "../common/mpi_gather.h"
#include "../driver/MeshChecks.h"
#include "../driver/exit_on_error.h"
#include "../laws/LawRegistry.h"
#include "../output/OutputFiles.h"
#include "../record/ResourceGuard.h"
#include "../scene/Scene.h"
#include "../scene/SceneError.h"
#include "../specimen/Scenario.h"
#include "FitEvaluator.h"
#include "FitReport.h"
#include "FitStatistics.h"
#include "FreeValue.h"
#include "TaoFit.h"
#include "text.h"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <mpi.h>
#include <optional>
#include <sstream>

namespace pushout::study
{
namespace
{
/// The value of `key` in `scene`, with the bounds of its range in `f` (a
/// law's parameter's, or a scene key's); throws SceneError if the key is
/// not a number of the scene, or not read by it.
double value_of(const Scene& scene, const std::string& key, Free& f)
{
  const std::vector<std::string> parts = split(key, '.');
  if (parts.size() == 3 && (parts[0] == "interface" || parts[0] == "crack") && !parts[1].empty() &&
      std::all_of(parts[1].begin(), parts[1].end(), ::isdigit))
  {
    const std::size_t i = std::stoul(parts[1]);
    const bool itf = parts[0] == "interface";
    if (i >= (itf ? scene.layers().size() : scene.cracks().size()))
      throw SceneError("--free '" + key + "': the scene has no " + parts[0] + " " + parts[1]);
    const LayerSpec& layer = itf ? scene.layers()[i] : scene.cracks()[i].layer;
    const laws::LawInfo* law = laws::find_law(layer.law);
    const auto def = std::find_if(law->params.begin(), law->params.end(),
                                  [&](const laws::ParamDef& p) { return p.name == parts[2]; });
    if (def == law->params.end())
    {
      std::string names;
      for (const auto& p : law->params)
        names += (names.empty() ? "" : ", ") + p.name;
      throw SceneError("--free '" + key + "': law '" + layer.law + "' has no parameter '" +
                       parts[2] + "' (it has " + names + ")");
    }
    const auto it = layer.params.find(parts[2]);
    if (it == layer.params.end())
      throw SceneError("--free '" + key + "' has no value in the scene (an optional parameter): " +
                       "give it a start with --set " + key + "=...");
    f.lo = def->min;
    f.lo_exclusive = def->min_exclusive;
    f.hi = def->max;
    return it->second;
  }
  const Value* v = scene.find(key);
  if (!v)
    throw SceneError("--free '" + key + "': no such key (pushout keys lists them)");
  const double* d = std::get_if<double>(v);
  if (!d)
    throw SceneError("--free '" + key + "': " +
                     (std::holds_alternative<std::int64_t>(*v)
                          ? "an integer key (" + to_toml(*v) + "), which a fit cannot vary smoothly"
                          : "not a number key (" + to_toml(*v) + ")"));
  if (const KeyDef* def = find_key(key))
  {
    if (def->outputs_only)
      throw SceneError("--free '" + key +
                       "': it changes how the outputs read the run, not the curve: the fit "
                       "could not move it");
    f.lo = def->min;
    f.hi = def->max;
    f.lo_exclusive = f.hi_exclusive = def->open;
  }
  return *d;
}

/// A value within `f`'s bounds away from 0 (the middle of finite bounds).
double off_zero(const Free& f)
{
  const bool lo = std::isfinite(f.lo), hi = std::isfinite(f.hi);
  const double mid = lo && hi ? (f.lo + f.hi) / 2 : lo ? f.lo + 1 : hi ? f.hi - 1 : 1;
  return mid != 0 ? mid : hi ? f.hi : 1;
}

/// Throws SceneError for a free scene key that the scene reads at none of
/// the values the fit may give: it would leave the curve unchanged, and the
/// fit could not move it. Whether a key is read may hang on another key's
/// being 0 (cracking.correlation_length on cracking.strength_cov,
/// corrosion.beta on corrosion.penetration): a free key that starts at 0
/// is tried away from it, within its bounds, so that two keys freed
/// together are both read when the fit can make them so.
void check_read(const Scene& scene, const std::vector<Free>& free, const FitOptions& opt)
{
  auto scene_key = [](const Free& f) { return find_key(f.key) != nullptr; };
  std::vector<std::string> sets = opt.sets;
  for (const Free& f : free)
    if (scene_key(f) && f.start == 0)
      sets.push_back(f.key + "=" + number_text(off_zero(f)));
  std::optional<Scene> moved;
  if (sets.size() > opt.sets.size())
  {
    try
    {
      moved = scene_of(opt, sets);
    }
    catch (const SceneError&)
    {
      // Not a valid scene away from 0: the start's reading stands.
    }
  }
  for (const Free& f : free)
    if (const std::string note =
            scene_key(f) ? (moved ? *moved : scene).unread_note(f.key) : std::string();
        !note.empty())
      throw SceneError("--free '" + f.key + "': the scene does not read it (" + note + ")");
}

/// The free values with their starts and bounds; throws SceneError.
std::vector<Free> free_values(const Scene& scene, const FitOptions& opt)
{
  if (opt.free.empty())
    throw SceneError("pushout fit needs at least one --free key");
  std::vector<Free> free;
  for (const std::string& key : opt.free)
  {
    if (std::any_of(free.begin(), free.end(), [&](const Free& f) { return f.key == key; }))
      throw SceneError("--free '" + key + "' is given twice");
    Free f{key};
    f.start = value_of(scene, key, f);
    f.scale = f.start != 0 ? std::abs(f.start) : 1.0;
    free.push_back(f);
  }
  std::vector<std::string> bounded; // the keys given --bounds so far
  for (const std::string& b : opt.bounds)
  {
    const auto eq = b.find('='), colon = b.find(':', eq == std::string::npos ? 0 : eq);
    if (eq == std::string::npos || colon == std::string::npos)
      throw SceneError("--bounds '" + b + "': expected key=lo:hi (either may be empty)");
    const std::string key = b.substr(0, eq);
    if (std::find(bounded.begin(), bounded.end(), key) != bounded.end())
      throw SceneError("--bounds '" + key + "' is given twice: give one lo:hi");
    bounded.push_back(key);
    const auto f =
        std::find_if(free.begin(), free.end(), [&](const Free& x) { return x.key == key; });
    if (f == free.end())
      throw SceneError("--bounds '" + b + "': '" + key + "' is not a --free key");
    const std::string lo = b.substr(eq + 1, colon - eq - 1), hi = b.substr(colon + 1);
    double lo_value = -HUGE_VAL, hi_value = HUGE_VAL;
    if ((!lo.empty() && !finite_number(lo, lo_value)) ||
        (!hi.empty() && !finite_number(hi, hi_value)))
      throw SceneError("--bounds '" + b + "': the bounds must be finite numbers (or empty)");
    if (lo_value > f->lo)
    {
      f->lo = lo_value;
      f->lo_exclusive = false;
    }
    if (hi_value < f->hi)
    {
      f->hi = hi_value;
      f->hi_exclusive = false;
    }
  }
  for (const Free& f : free)
  {
    std::ostringstream b; // as [lo, hi], a bound that is excluded in ( )
    b << std::setprecision(15) << (f.lo_exclusive ? '(' : '[') << f.lo << ", " << f.hi
      << (f.hi_exclusive ? ')' : ']');
    const std::string bounds = b.str();
    if (!(f.lo < f.hi))
      throw SceneError("the bounds of '" + f.key + "' " + bounds +
                       " leave no value: lo is not below hi");
    if (!(f.tao_lo() <= f.start && f.start <= f.tao_hi()))
    {
      std::ostringstream start;
      start << std::setprecision(15) << f.start;
      throw SceneError("the bounds of '" + f.key + "' " + bounds + " exclude its start " +
                       start.str());
    }
  }
  check_read(scene, free, opt);
  return free;
}

/// How finely a fit resolves `scene`'s curve (docs/fitting.md, "Method").
/// A curve of the joints and crack planes is smooth in its keys to Newton's
/// tolerance: forward differences of 1e-4 (truncation error near 1e-4,
/// noise near 1e-10), and Bates and Watts' offset of 1e-3. With cracks
/// anywhere in the concrete IMPL-EX's error control chooses the steps, and
/// the curve jumps as they change with the keys (measured on the coarse
/// cracking demo: tau by 7e-5 to 1.1e-4 MPa at a 1e-4 change of f_t, 15 %
/// of the difference itself). A step of 1e-2 makes those jumps 100 times
/// smaller against the difference; the offset still cannot fall below the
/// jumps against the data's scatter (0.028 on that demo with 0.5 % noise),
/// so 0.05 ends the fit: 5 % of the confidence region's radius. With less
/// scatter the floor is higher, and where it lies depends on the point: an
/// offset below 1 that fell by less than a fifth in two iterations running
/// ends the fit there. TAO's line search then backtracks on the objective
/// alone (More and Thuente's asked for n + 1 runs at each point it tried,
/// and thrashed on the jumps: 120 runs in one iteration).
Resolution resolution_of(const Scene& scene)
{
  if (scene.cracking().embedded)
    return {1e-2, 0.05, 0.8, TAOLINESEARCHARMIJO};
  return {1e-4, 1e-3, 0.0, TAOLINESEARCHMT};
}

/// The fitted run at x (scaled values), with its outputs, in DIR/best
/// (group 0; rank 0 leads it); its exit code into `exit_code_best`, and on
/// rank 0 how it failed into `best_failure` ("did not converge: ...";
/// "" if it converged). Then
/// the runs' set-ups and the groups are freed. Returns the signal that
/// stopped it, or any run, on any process (0: none): a stopped fitted run
/// leaves no best/ (it would hold a part of the curve), and the fit no
/// fit.json. Collective.
int run_fitted(const FitOptions& opt, Evaluator& evaluator, ProcessGroups& groups,
               const std::vector<double>& x, int& exit_code_best, std::string& best_failure)
{
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (groups.index() == 0)
    evaluator.run(x, opt.out / "best", true, Evaluator::Counts::never);
  const driver::RunOutcome& o = evaluator.last();
  exit_code_best = o.exit_code;
  // Its refusal by the scene is write_fit's to say (no scene.toml).
  using Refusal = driver::RunOutcome::Refusal;
  best_failure = o.exit_code == exit_code::done            ? ""
                 : o.exit_code == exit_code::not_converged ? "did not converge: " + o.message
                 : o.refused == Refusal::size              ? "was refused: " + o.message
                 : o.refused == Refusal::scene             ? ""
                                                           : "ended with an error: " + o.message;
  evaluator.release();
  groups.close();
  const int signal = evaluator.signal_anywhere();
  if (signal != 0)
  {
    interrupt::acknowledge();
    if (rank == 0)
    {
      output::remove_outputs(opt.out / "best");
      std::cerr << "pushout: interrupted by " << interrupt::signal_name(signal)
                << " during the fitted run after " << evaluator.evaluations()
                << " runs; no fit written" << std::endl;
    }
  }
  return signal;
}

/// The fit's inputs, read and checked before its folder is touched: the
/// measured curve into `data`, the free values into `free`; the start a
/// valid scene with the push to the data's end that fits a group's
/// processes, and whose mesh suits its cracks anywhere; the folder
/// claimed. exit_code::done, or the refusal's code (said once).
int prepare(FitOptions& opt, MeasuredCurve& data, std::vector<Free>& free, Resolution& resolution)
{
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return driver::exit_code_of(
      "pushout fit", "error",
      [&]
      {
        read_scene_text(opt);
        const std::string data_text = read_on_first([&] { return read_measured_text(opt.data); });
        mpi::collectively<SceneError>(
            MPI_COMM_WORLD,
            [&]
            {
              ProcessGroups::check(opt.ranks_per_case);
              data = parse_measured(data_text, opt.data);
              const Scene scene = scene_of(opt, opt.sets);
              if (!scene.model().pushout())
                throw SceneError("pushout fit fits push-out curves (model.type = \"pushout\")");
              if (!scene.loading().push_path.empty())
                throw SceneError(
                    "pushout fit runs a monotonic push: leave 'loading.push_path' empty");
              free = free_values(scene, opt);
              resolution = resolution_of(scene);
              if (data.delta.size() <= free.size())
                throw SceneError("--data '" + opt.data.string() + "' has " +
                                 std::to_string(data.delta.size()) + " rows: more than the " +
                                 std::to_string(free.size()) + " free values are needed");
            });
        // The start must be a valid scene with the push to the data's end,
        // that fits a group's processes (the size guard, as each run's, on a
        // group of --ranks-per-case processes as the runs' will be), before
        // the folder is touched: a refused fit leaves an earlier one's
        // outputs there.
        struct Group
        {
          MPI_Comm comm;
          ~Group() { MPI_Comm_free(&comm); }
        } group{ProcessGroups::split(opt.ranks_per_case)};
        const int others_here = ProcessGroups::others_here(group.comm, int(free.size()) + 1);
        std::vector<std::string> sets = opt.sets;
        sets.push_back("loading.push_displacement=" + number_text(data.delta.back()));
        const Scene start =
            mpi::collectively<SceneError>(MPI_COMM_WORLD, [&] { return scene_of(opt, sets); });
        mpi::collectively<SceneError, record::TooLarge>(
            MPI_COMM_WORLD,
            [&]
            {
              try
              {
                driver::check_before_run(start, driver::RunOptions{opt.out, opt.mesh_cache,
                                                                   opt.quiet, opt.force, group.comm,
                                                                   true, others_here});
              }
              catch (const SceneError& e)
              {
                // The push is the data's: say so (delta_mm in um, 10 for 0.01 mm, lands here).
                if (std::string(e.what()).rfind("'loading.push_displacement'", 0) != 0)
                  throw;
                throw SceneError("--data '" + opt.data.string() + "': the fit pushes to its last " +
                                 "delta_mm, " + number_text(data.delta.back()) +
                                 " mm (delta_mm is in mm), and " + e.what());
              }
            });
        // With cracks anywhere, the crack band against the start's elements
        // (collective on MPI_COMM_WORLD, so once every group passed its guard).
        mpi::collectively<SceneError>(MPI_COMM_WORLD,
                                      [&] {
                                        driver::MeshChecks{opt.mesh_cache, opt.force}(start);
                                      });
        // The folder is this fit's alone, without an earlier run's outputs
        // (output/OutputFiles.h); neither the scene nor the data may be
        // among them.
        mpi::collectively<output::FolderError>(
            MPI_COMM_WORLD,
            [&]
            {
              if (rank == 0)
                output::claim(opt.out, {opt.scene_file, opt.data});
            });
        return exit_code::done;
      });
}
} // namespace

int fit(const FitOptions& given)
{
  FitOptions opt = given; // with its scene's text, read once (prepare)
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const bool talk = rank == 0 && !opt.quiet;
  const auto t0 = std::chrono::steady_clock::now();
  MeasuredCurve data;
  std::vector<Free> free;
  Resolution resolution{};
  if (const int set_up = prepare(opt, data, free, resolution); set_up != exit_code::done)
    return set_up;

  ProcessGroups groups(opt.ranks_per_case);
  Evaluator evaluator(opt, free, data, groups.comm(), groups.count(), groups.index(),
                      groups.others_here(int(free.size()) + 1));
  Problem problem(evaluator, free, resolution, talk, t0);
  if (talk)
    std::cout << "pushout fit: " << free.size() << " values to " << data.delta.size()
              << " points of " << opt.data.string() << "; " << groups.count()
              << (groups.count() == 1 ? " group" : " groups") << " of " << opt.ranks_per_case
              << (opt.ranks_per_case == 1 ? " process" : " processes") << std::endl;

  // TAO on each process alike (PETSC_COMM_SELF), on the scaled values.
  TaoFit solver(free, PetscInt(data.delta.size()), problem);
  FitOutcome outcome;
  try
  {
    outcome.x = solver.solve();
  }
  catch (const Interrupted& e)
  {
    evaluator.release();
    groups.close();
    if (rank == 0)
      std::cerr << "pushout: " << e.what() << " after " << evaluator.evaluations()
                << " runs; no fit written" << std::endl;
    return exit_code::signal(e.signal);
  }
  const std::vector<double>& x = outcome.x;
  outcome.r = problem.r_last;
  outcome.statistics = statistics(solver.J, outcome.r, free, x, problem.difference_failed);

  int best_exit_code = exit_code::done;
  if (const int signal =
          run_fitted(opt, evaluator, groups, x, best_exit_code, outcome.best_failure);
      signal != 0)
    return exit_code::signal(signal);
  outcome.converged =
      solver.converged() && evaluator.failed() == 0 && best_exit_code == exit_code::done;
  outcome.reason = solver.reason();
  // Why a run failed, from any process (the failure may have been another
  // group's).
  outcome.failure = mpi::first_message(evaluator.last_failure(), MPI_COMM_WORLD);
  outcome.refusal = mpi::first_message(evaluator.last_refusal(), MPI_COMM_WORLD);
  if (outcome.refusal.empty()) // none by the scene: by the size guard, if any
  {
    outcome.refusal = mpi::first_message(evaluator.last_size_refusal(), MPI_COMM_WORLD);
    outcome.refusal_by_size = !outcome.refusal.empty();
  }
  outcome.sets = evaluator.sets_at(x);
  outcome.evaluations = evaluator.evaluations();
  outcome.failed_runs = evaluator.failed();
  outcome.refused_runs = evaluator.refused();
  outcome.iterations = solver.iterations();
  outcome.relative_offset = solver.offset();
  // Data the model meets to its own precision (an rms misfit below
  // Newton's relative tolerance, 1e-6, of the largest |tau| measured; a
  // measurement scatters far more) leave the offset undefined: its two
  // parts are round-off then (a run's own curve fitted back read 199).
  if (std::sqrt(outcome.statistics.rss / double(data.tau.size())) <= 1e-6 * data.largest_tau())
    outcome.relative_offset = NAN;
  if (problem.at_resolution)
  {
    std::ostringstream w;
    w << std::setprecision(2) << "the relative offset settled at " << outcome.relative_offset
      << ", above " << resolution.offset_tolerance
      << ": the curve's own jumps (IMPL-EX's steps) are not small against the data's scatter, "
         "so each value lies within "
      << outcome.relative_offset * std::sqrt(double(free.size()))
      << " standard errors of where a further step would take it";
    outcome.statistics.warnings.push_back(w.str());
  }
  int code = outcome.converged ? exit_code::done : exit_code::not_converged;
  if (rank == 0)
  {
    outcome.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    code = write_fit(opt, data, free, outcome, talk);
  }
  MPI_Bcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return code;
}
} // namespace pushout::study

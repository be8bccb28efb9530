// `pushout sweep` (Sweep.h): its plan (every case's scene read before any
// runs), the cases run by the process groups, and its outputs: the tables
// (SweepTables.h), sweep.png and the closing line.
#include "Sweep.h"
#include "../common/Interrupt.h"
#include "../common/exit_codes.h"
#include "../common/mpi_errors.h"
#include "../common/mpi_gather.h"
#include "../driver/MeshChecks.h"
#include "../driver/PetscOptions.h"
#include "../driver/Run.h"
#include "../driver/exit_on_error.h"
#include "../mesh/generate.h"
#include "../output/OutputFiles.h"
#include "../output/plot.h"
#include "../scene/SceneError.h"
#include "../specimen/Scenario.h"
#include "SweepTables.h"
#include "text.h"
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <numeric>
#include <sstream>

namespace pushout::study
{
using driver::run_case;
using driver::RunOptions;
using driver::RunOutcome;
using driver::Simulation;
namespace
{
/// Whether the CSV file at `path` exists and has a row after its header.
bool has_rows(const std::filesystem::path& path)
{
  std::ifstream in(path);
  std::string line;
  int lines = 0;
  while (lines < 2 && std::getline(in, line))
    lines += !line.empty();
  return lines == 2;
}

/// The results of every process's cases on rank 0 (others: empty).
std::vector<CaseResult> gather(const std::vector<CaseResult>& mine)
{
  nlohmann::json j = nlohmann::json::array();
  for (const CaseResult& r : mine)
    j.push_back({{"index", r.index},
                 {"exit_code", r.exit_code},
                 {"wall_s", r.wall_s},
                 {"message", r.message}});
  // (a message that is not UTF-8 is replaced, not thrown on one process)
  const std::string text = j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  std::vector<int> offsets;
  const std::vector<char> gathered =
      mpi::gather_to_first(MPI_COMM_WORLD, text.data(), int(text.size()), MPI_CHAR, &offsets);
  std::vector<CaseResult> results;
  if (rank != 0)
    return results;
  const std::string all(gathered.begin(), gathered.end());
  for (int p = 0; p < size; ++p)
    for (const auto& e : nlohmann::json::parse(
             all.substr(std::size_t(offsets[std::size_t(p)]),
                        std::size_t(offsets[std::size_t(p) + 1] - offsets[std::size_t(p)]))))
    {
      CaseResult r;
      r.index = e["index"].get<int>();
      r.exit_code = e["exit_code"].get<int>();
      r.wall_s = e["wall_s"].get<double>();
      r.message = e["message"].get<std::string>();
      results.push_back(r);
    }
  std::sort(results.begin(), results.end(),
            [](const CaseResult& a, const CaseResult& b) { return a.index < b.index; });
  return results;
}

/// A value `v` gives twice, as its text, as a number or as an array of
/// numbers ("" if none).
std::string repeated_value(const Variation& v)
{
  // The numbers of a value: one, or an array's ("[50, 50.0]"); false if
  // it is neither.
  auto numbers = [](const std::string& text, std::vector<double>& x)
  {
    x.clear();
    const bool array = text.size() >= 2 && text.front() == '[' && text.back() == ']';
    for (const std::string& part :
         array ? split(text.substr(1, text.size() - 2), ',') : std::vector<std::string>{text})
      if (double d = 0; finite_number(part, d))
        x.push_back(d);
      else
        return false;
    return !x.empty();
  };
  for (std::size_t i = 0; i < v.values.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
    {
      std::vector<double> a, b;
      if (v.values[i] == v.values[j] ||
          (numbers(v.values[i], a) && numbers(v.values[j], b) && a == b))
        return v.values[i];
    }
  return "";
}

} // namespace

Variation parse_variation(const std::string& text)
{
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw SceneError("--vary '" + text + "': expected key=value,value,...");
  Variation v{text.substr(0, eq), {}};
  std::string value;
  int depth = 0;
  char quote = 0; // inside a TOML string: its quote (" or ')
  bool escaped = false;
  for (char c : text.substr(eq + 1))
  {
    if (quote != 0)
    {
      value += c;
      if (quote == '"' && c == '\\' && !escaped)
        escaped = true;
      else
      {
        if (c == quote && !escaped)
          quote = 0;
        escaped = false;
      }
      continue;
    }
    if (c == '"' || c == '\'')
      quote = c;
    depth += c == '[' ? 1 : c == ']' ? -1 : 0;
    if (c == ',' && depth == 0)
    {
      v.values.push_back(value);
      value.clear();
    }
    else
      value += c;
  }
  v.values.push_back(value);
  // One spelling of a value in sweep.csv and its tables (and the repeated
  // values found as numbers).
  std::transform(v.values.begin(), v.values.end(), v.values.begin(), integer_in_decimal);
  if (depth != 0 || quote != 0 ||
      std::any_of(v.values.begin(), v.values.end(), [](const std::string& s) { return s.empty(); }))
    throw SceneError("--vary '" + text + "': an empty value, unbalanced [ ] or an unclosed quote");
  return v;
}

std::vector<std::vector<std::string>> cartesian_cases(const std::vector<Variation>& vary)
{
  std::vector<std::vector<std::string>> cases = {{}};
  for (const Variation& v : vary)
  {
    std::vector<std::vector<std::string>> next;
    for (const auto& c : cases)
      for (const std::string& value : v.values)
      {
        next.push_back(c);
        next.back().push_back(v.key + "=" + value);
      }
    cases = std::move(next);
  }
  return cases;
}

std::vector<std::size_t> set_up_order(const std::vector<std::string>& set_ups)
{
  std::map<std::string, std::size_t> first; // each set-up's first case
  for (std::size_t i = 0; i < set_ups.size(); ++i)
    first.emplace(set_ups[i], i);
  std::vector<std::size_t> order(set_ups.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b)
                   { return first.at(set_ups[a]) < first.at(set_ups[b]); });
  return order;
}

/// What a sweep runs: its variations, its cases (each a list of key=value)
/// and the order it takes them in, the model type and whether it plots.
struct SweepPlan
{
  std::vector<Variation> vary;
  std::vector<std::vector<std::string>> cases;
  std::vector<std::size_t> order; ///< the cases in the order they are taken
  std::string model_type;
  bool plot = false;
  /// With the seed varied: the cases that do not read it (a uniform
  /// strength beside another case's field), said before they run, as their
  /// sweep_seeds.csv rows are one specimen run once per seed ("": none).
  std::string seed_note;
};

/// Reads every case's scene, so that a bad value stops the sweep before any
/// case runs; throws SceneError.
SweepPlan plan_sweep(const SweepOptions& opt)
{
  SweepPlan plan;
  if (opt.vary.empty())
    throw SceneError("pushout sweep needs at least one --vary key=value,value,...");
  ProcessGroups::check(opt.ranks_per_case);
  (void)mesh::cache_limit_mb(); // a $PUSHOUT_CACHE_MAX_MB that is no size: before any case
  for (const std::string& v : opt.vary)
  {
    plan.vary.push_back(parse_variation(v));
    const Variation& last = plan.vary.back();
    for (std::size_t i = 0; i + 1 < plan.vary.size(); ++i)
      if (plan.vary[i].key == last.key)
        throw SceneError("'" + last.key +
                         "' is given in two --vary options: give its values in one");
    if (const std::string twice = repeated_value(last); !twice.empty())
      throw SceneError(
          "--vary '" + v + "' gives the value " + twice + " twice: each case would run again" +
          (last.key == "cracking.seed" ? " (and the seed would count twice in sweep_seeds.csv)"
                                       : ""));
  }
  // The count before the cases are made (it may not fit in memory).
  double count = 1;
  for (const Variation& v : plan.vary)
    count *= double(v.values.size());
  if (count > double(opt.max_cases))
  {
    std::ostringstream s;
    s << std::setprecision(15) << "the --vary options make " << count << " cases, more than "
      << opt.max_cases;
    if (count <= double(SweepOptions::largest_max_cases))
      s << ": --max-cases " << std::size_t(count) << " runs them";
    else
      s << ", and more than the " << SweepOptions::largest_max_cases
        << " one sweep runs: split the --vary values over several sweeps";
    throw SceneError(s.str());
  }
  plan.cases = cartesian_cases(plan.vary);
  // The model type and the plot of the sweep: the scene's with the
  // --set values (a case may not change them).
  const Scene base = scene_of(opt, opt.sets);
  plan.model_type = base.model().name();
  plan.plot = base.output().plot;
  std::vector<std::string> set_ups(plan.cases.size());
  // Each varied key's note from a case that does not read it; erased where
  // one case does (a key another varied key switches off in some cases,
  // such as the seed beside strength_cov = 0, is read in the others).
  std::map<std::string, std::string> unread;
  for (const Variation& v : plan.vary)
    unread[v.key] = "";
  driver::MeshChecks check_mesh(opt.mesh_cache, opt.force);
  std::string seed_unread; // the cases that do not read a varied seed
  for (std::size_t i = 0; i < plan.cases.size(); ++i)
  {
    std::vector<std::string> sets = opt.sets;
    sets.insert(sets.end(), plan.cases[i].begin(), plan.cases[i].end());
    try
    {
      const Scene scene = scene_of(opt, sets);
      if (scene.model().name() != plan.model_type)
        throw SceneError("a sweep runs one model type: vary other keys");
      specimen::check_scene(scene); // the relations between keys, as a run checks them
      driver::check_solver_options(scene, opt.ranks_per_case);
      check_mesh(scene);
      if (varies_seed(plan.vary) && !scene.unread_note(seed_key).empty())
        seed_unread += (seed_unread.empty() ? "" : ", ") + case_name(i);
      for (auto it = unread.begin(); it != unread.end();)
      {
        const std::string note = scene.unread_note(it->first);
        if (note.empty())
          it = unread.erase(it);
        else
          (it++)->second = note;
      }
      set_ups[i] = Simulation::set_up_fingerprint(scene);
    }
    catch (const SceneError& e)
    {
      std::string what;
      for (const std::string& s : plan.cases[i])
        what += (what.empty() ? "" : " ") + s;
      throw SceneError(case_name(i) + " (" + what + "): " + e.what());
    }
  }
  std::string names, notes; // of the varied keys no case reads, in --vary's order
  for (const Variation& v : plan.vary)
    if (const auto it = unread.find(v.key); it != unread.end())
    {
      names += (names.empty() ? "" : ", ") + v.key;
      notes += (notes.empty() ? "" : "; ") + it->second;
    }
  if (!names.empty())
    throw SceneError("--vary: no case reads " + names +
                     ", so each of its values would run the same cases again (" + notes + ")");
  if (!seed_unread.empty())
    plan.seed_note = std::string(seed_key) + " is not read in " + seed_unread +
                     " (a uniform strength): their rows of sweep_seeds.csv are one specimen run "
                     "once per seed, with no spread";
  plan.order = set_up_order(set_ups);
  return plan;
}

namespace
{
/// The cases the process groups ran: this group's outcomes (on its first
/// process; none on the others) and the signal that stopped the sweep (0:
/// none; the same on every process).
struct CasesRun
{
  std::vector<CaseResult> mine;
  int stop_signal = 0;
};

/// The number of the next case this process's group takes (its first
/// process takes it from the counter in `window`, the others hear it): at
/// least the number of cases when none is left.
int next_case(MPI_Win window, bool leader, MPI_Comm group)
{
  int index = 0;
  if (leader)
  {
    const int one = 1;
    MPI_Win_lock(MPI_LOCK_SHARED, 0, 0, window);
    MPI_Fetch_and_op(&one, &index, MPI_INT, 0, 0, MPI_SUM, window);
    MPI_Win_unlock(0, window);
  }
  MPI_Bcast(&index, 1, MPI_INT, 0, group);
  return index;
}

/// The progress line of a case that ran, `sets` its values (its group's
/// first process, `rank`).
void say_case(const std::vector<std::string>& sets, const CaseResult& r, int rank)
{
  std::string what;
  for (const std::string& s : sets)
    what += (what.empty() ? "" : " ") + s;
  std::ostringstream line;
  line << "sweep: " << case_name(std::size_t(r.index)) << " (" << what
       << "): " << (r.exit_code == 0 ? "done" : "failed (exit " + std::to_string(r.exit_code) + ")")
       << " in " << std::fixed << std::setprecision(2) << r.wall_s << " s"
       << (r.message.empty() ? "" : ": " + r.message) << " [process " << rank << "]\n";
  std::cout << line.str() << std::flush;
}

/// Runs the cases of `plan` in its order, each group taking the next one from
/// a counter that every process shares (an MPI window on rank 0), until none
/// is left or a signal stops the sweep; then closes `groups`. Collective on
/// MPI_COMM_WORLD.
CasesRun run_cases(const SweepOptions& opt, const SweepPlan& plan, ProcessGroups& groups)
{
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const std::vector<std::vector<std::string>>& cases = plan.cases;
  const MPI_Comm group = groups.comm();
  const bool leader = groups.leader();
  // The shared counter of the next case (rank 0's window).
  int* next = nullptr;
  MPI_Win window;
  MPI_Win_allocate(rank == 0 ? MPI_Aint(sizeof(int)) : 0, sizeof(int), MPI_INFO_NULL,
                   MPI_COMM_WORLD, &next, &window);
  if (rank == 0)
  {
    MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 0, 0, window);
    *next = 0;
    MPI_Win_unlock(0, window);
  }
  MPI_Barrier(MPI_COMM_WORLD);

  // Between cases a signal waits for the loop to see it (at most a case's
  // set-up: the run's own phases apply inside a case), then the table of
  // what ran is written.
  const interrupt::Phase phase("sweep", interrupt::stop_grace_s);
  CasesRun run;
  std::unique_ptr<Simulation> simulation; // the group's last set-up
  bool first_case = true;
  for (;;)
  {
    int index = next_case(window, leader, group);
    int signal = interrupt::received();
    MPI_Allreduce(MPI_IN_PLACE, &signal, 1, MPI_INT, MPI_MAX, group);
    if (signal != 0)
    {
      run.stop_signal = signal;
      interrupt::acknowledge(); // the sweep stops here, on every process
      // The other groups take no new case (a signal to this group's
      // processes alone): each stops after the case it runs.
      if (leader)
      {
        // (By the same operation as next_case: the window's accumulates
        // are atomic only among one operation. The counter only grows.)
        const int past_the_last = int(cases.size());
        int taken = 0;
        MPI_Win_lock(MPI_LOCK_SHARED, 0, 0, window);
        MPI_Fetch_and_op(&past_the_last, &taken, MPI_INT, 0, 0, MPI_SUM, window);
        MPI_Win_unlock(0, window);
      }
    }
    if (index >= int(cases.size()) || run.stop_signal != 0)
      break;
    index = int(plan.order[std::size_t(index)]);
    std::vector<std::string> sets = opt.sets;
    sets.insert(sets.end(), cases[std::size_t(index)].begin(), cases[std::size_t(index)].end());
    // Quiet, and no curve.png per case: sweep.png overlays them.
    CaseResult r;
    static_cast<RunOutcome&>(r) =
        run_case(opt.scene_text, opt.scene_file, sets,
                 {opt.out / case_name(std::size_t(index)), opt.mesh_cache, true, opt.force, group,
                  false, groups.others_here(int(cases.size()))},
                 simulation);
    r.index = index;
    if (r.exit_code > 128)
      run.stop_signal = r.exit_code - 128;
    if (first_case) // collective on the group; said once, by the first process
      driver::warn_unread_options(opt.petsc_options, opt.allow_unused, group, rank == 0,
                                  case_name(std::size_t(index)), "sweep");
    first_case = false;
    if (!leader)
      continue;
    run.mine.push_back(r);
    if (!opt.quiet)
      say_case(cases[std::size_t(index)], r, rank);
  }
  simulation.reset(); // on the group, before it goes
  MPI_Win_free(&window);
  groups.close();
  MPI_Allreduce(MPI_IN_PLACE, &run.stop_signal, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return run;
}

/// sweep.csv, sweep.png (unless a signal stopped the sweep) and the closing
/// line, on rank 0, from the `results` of every case that ran; returns the
/// exit code: 0 if every case converged, 3 if one did not, 128 + signal if
/// a signal stopped the sweep, 1 if sweep.csv could not be written.
int write_sweep(const SweepOptions& opt, const SweepPlan& plan,
                const std::vector<CaseResult>& results, int stop_signal,
                std::chrono::steady_clock::time_point t0)
{
  const std::vector<std::vector<std::string>>& cases = plan.cases;
  int code = exit_code::done;
  try
  {
    write_tables(opt.out, plan.model_type, plan.vary, cases, results);
  }
  catch (const std::exception& e)
  {
    std::cerr << "pushout: error: " << e.what() << std::endl;
    code = exit_code::failure;
  }
  // A stopped sweep draws no sweep.png: plotting every curve takes
  // longer than a stop may (sweep.csv has the table).
  // Nor does one whose cases all failed before a curve's first row
  // (refused, say, or failed in the corrosion stage: a curve.csv of its
  // header alone).
  const bool any_curve =
      std::any_of(results.begin(), results.end(),
                  [&](const CaseResult& r)
                  { return has_rows(opt.out / case_name(std::size_t(r.index)) / "curve.csv"); });
  const bool plot = plan.plot && stop_signal == 0 && any_curve;
  std::string why;
  if (plan.plot && stop_signal == 0 && !any_curve)
    std::cerr << "pushout: warning: no sweep.png: no case wrote a curve" << std::endl;
  if (plot && !output::plot_sweep(opt.out, opt.out / "sweep.png", why))
    std::cerr << "pushout: warning: no sweep.png: " << why << std::endl;
  const auto converged = std::count_if(results.begin(), results.end(),
                                       [](const CaseResult& r) { return r.exit_code == 0; });
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!opt.quiet || converged < std::ptrdiff_t(cases.size()))
    (converged < std::ptrdiff_t(cases.size()) ? std::cerr : std::cout)
        << "pushout sweep: " << converged << " of " << cases.size() << " cases converged"
        << (results.size() < cases.size()
                ? " (" + std::to_string(cases.size() - results.size()) + " not run)"
                : "")
        << " in " << std::fixed << std::setprecision(2) << wall
        << " s; table: " << (opt.out / "sweep.csv").string()
        << (varies_seed(plan.vary) ? ", " + (opt.out / "sweep_seeds.csv").string() : "")
        << (plot ? ", plot: " + (opt.out / "sweep.png").string() : "") << std::endl;
  if (code == exit_code::done && stop_signal != 0)
    code = exit_code::signal(stop_signal);
  else if (code == exit_code::done && converged < std::ptrdiff_t(cases.size()))
    code = exit_code::not_converged;
  return code;
}
} // namespace

int sweep(const SweepOptions& given)
{
  SweepOptions opt = given; // with its scene's text, read once below
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const auto t0 = std::chrono::steady_clock::now();
  SweepPlan plan;
  const int set_up = driver::exit_code_of(
      "pushout sweep", "error",
      [&]
      {
        read_scene_text(opt);
        // The same on every process.
        plan = mpi::collectively<SceneError>(MPI_COMM_WORLD, [&] { return plan_sweep(opt); });
        // The folder is this sweep's alone, without an earlier
        // run's outputs (output/OutputFiles.h: its case folders,
        // sweep.csv, ...).
        mpi::collectively<output::FolderError>(MPI_COMM_WORLD,
                                               [&]
                                               {
                                                 if (rank == 0)
                                                   output::claim(opt.out, {opt.scene_file});
                                               });
        return exit_code::done;
      });
  if (set_up != exit_code::done)
    return set_up;
  ProcessGroups groups(opt.ranks_per_case);
  if (rank == 0 && !opt.quiet)
    std::cout << "pushout sweep: " << plan.cases.size() << " cases, " << groups.count()
              << (groups.count() == 1 ? " group" : " groups") << " of " << opt.ranks_per_case
              << (opt.ranks_per_case == 1 ? " process" : " processes") << std::endl;
  if (rank == 0 && !plan.seed_note.empty())
    std::cout << "pushout sweep: note: " << plan.seed_note << std::endl;
  const CasesRun run = run_cases(opt, plan, groups);

  const interrupt::Phase phase("writing outputs", -1);
  const std::vector<CaseResult> results = gather(run.mine);
  int code = exit_code::done;
  if (rank == 0)
    code = write_sweep(opt, plan, results, run.stop_signal, t0);
  MPI_Bcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return code;
}
} // namespace pushout::study

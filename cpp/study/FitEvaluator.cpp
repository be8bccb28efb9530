// The model runs of a fit (FitEvaluator.h): a batch of points over the
// process groups, each run read back from its curve.csv as residuals at the
// measured points.
#include "FitEvaluator.h"
#include "../driver/PetscOptions.h"
#include "text.h"
#include <algorithm>
#include <cstdlib>
#include <fstream>

namespace pushout::study
{
using driver::run_case;
using driver::RunOutcome;

Evaluator::Evaluator(const FitOptions& opt, const std::vector<Free>& free,
                     const MeasuredCurve& data, MPI_Comm group, int groups, int group_index,
                     int others_here)
    : _opt(opt), _free(free), _data(data), _group(group), _groups(groups),
      _group_index(group_index), _others_here(others_here)
{
  int rank = 0;
  MPI_Comm_rank(group, &rank);
  _leader = rank == 0;
}

std::vector<std::vector<double>>
Evaluator::residuals(const std::vector<std::vector<double>>& points, std::vector<bool>* failed,
                     std::size_t counted)
{
  // Per point its m residuals, then 1 if its run failed outright.
  const std::size_t m = _data.delta.size(), stride = m + 1;
  std::vector<double> all(points.size() * stride, 0.0);
  for (std::size_t k = 0; k < points.size(); ++k)
    if (int(k % std::size_t(_groups)) == _group_index)
    {
      const std::vector<double> r =
          run(points[k], _opt.out / ".runs" / ("group_" + std::to_string(_group_index)), false,
              k < counted ? Counts::now : Counts::when_used);
      if (_leader)
      {
        std::copy(r.begin(), r.end(), all.begin() + std::ptrdiff_t(k * stride));
        all[k * stride + m] = _failed_outright ? 1 : 0;
      }
    }
  MPI_Allreduce(MPI_IN_PLACE, all.data(), int(all.size()), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  int signal = std::max(interrupt::received(), _signal);
  MPI_Allreduce(MPI_IN_PLACE, &signal, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  if (signal != 0) // on every process alike: TaoSolve ends with it
  {
    interrupt::acknowledge();
    throw Interrupted(signal);
  }
  sum_counts();
  if (_evaluations == 0) // every process is here (the sums above)
  {
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    driver::warn_unread_options(_opt.petsc_options, _opt.allow_unused, MPI_COMM_WORLD, rank == 0,
                                "the fit's first runs", "fit");
  }
  _evaluations += int(points.size());
  std::vector<std::vector<double>> out;
  if (failed)
    failed->assign(points.size(), false);
  for (std::size_t k = 0; k < points.size(); ++k)
  {
    out.emplace_back(all.begin() + std::ptrdiff_t(k * stride),
                     all.begin() + std::ptrdiff_t(k * stride + m));
    if (failed)
      (*failed)[k] = all[k * stride + m] != 0;
  }
  return out;
}

double Evaluator::failed_residual() const
{
  return failed_run_factor * _data.largest_tau();
}

std::vector<std::string> Evaluator::sets_at(const std::vector<double>& x) const
{
  std::vector<std::string> sets = _opt.sets;
  sets.push_back("loading.push_displacement=" + number_text(_data.delta.back()));
  for (std::size_t j = 0; j < _free.size(); ++j)
    sets.push_back(_free[j].key + "=" + number_text(x[j] * _free[j].scale));
  return sets;
}

void Evaluator::tally(const RunOutcome& o)
{
  // Values the scene (or the size guard) refuses are the fit's to avoid (a
  // misfit), not a run that failed.
  if (o.refused != RunOutcome::Refusal::none)
  {
    ++_refused;
    // The run's words, less what the fit says ("error in scene: ").
    (o.refused == RunOutcome::Refusal::size ? _last_size_refusal : _last_refusal) = o.reason();
  }
  else if (o.exit_code != 0)
  {
    ++_failed;
    _last_failure = o.message;
  }
}

void Evaluator::count(const std::vector<double>& x)
{
  if (const auto it = _pending.find(x); it != _pending.end())
  {
    tally(it->second);
    _pending.erase(it);
  }
  sum_counts();
}

void Evaluator::sum_counts()
{
  int here[2] = {_failed, _refused}, total[2] = {0, 0};
  MPI_Allreduce(here, total, 2, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  _failed_total = total[0];
  _refused_total = total[1];
}

std::vector<double> Evaluator::run(const std::vector<double>& x, const std::filesystem::path& out,
                                   bool plot, Counts counts)
{
  const RunOutcome o =
      run_case(_opt.scene_text, _opt.scene_file, sets_at(x),
               {out, _opt.mesh_cache, true, _opt.force, _group, plot, _others_here}, _simulation);
  std::vector<double> r(_data.delta.size(), 0.0);
  _last = o;
  if (o.exit_code > exit_code::signal(0))
    _signal = o.exit_code - exit_code::signal(0);
  // Once per group: the counts are summed over processes. A run ahead
  // counts once the fit uses it (count()).
  if (_leader && counts == Counts::now)
    tally(o);
  else if (_leader && counts == Counts::when_used && o.exit_code != 0)
    _pending[x] = o;
  // A run that failed outright (a bad value, an error) counts as
  // failed_residual() everywhere; one that stopped (no convergence, a
  // signal) by what it reached.
  _failed_outright = o.exit_code == exit_code::bad_input || o.exit_code == exit_code::failure;
  if (!_leader || _failed_outright)
  {
    if (_leader)
      std::fill(r.begin(), r.end(), failed_residual());
    return r;
  }
  std::vector<double> delta, tau;
  std::ifstream in(out / "curve.csv");
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split(line, ',');
  const auto column = [&](const std::string& name)
  { return std::size_t(std::find(header.begin(), header.end(), name) - header.begin()); };
  const std::size_t cd = column("delta_mm"), ct = column("tau_MPa");
  while (std::getline(in, line)) // our own file: a row that does not parse ends it
  {
    const std::vector<std::string> cells = split(line, ',');
    if (cd >= cells.size() || ct >= cells.size())
      break;
    char *end_d = nullptr, *end_t = nullptr;
    const double d = std::strtod(cells[cd].c_str(), &end_d);
    const double t = std::strtod(cells[ct].c_str(), &end_t);
    if (end_d == cells[cd].c_str() || end_t == cells[ct].c_str())
      break;
    delta.push_back(d);
    tau.push_back(t);
  }
  for (std::size_t i = 0; i < r.size(); ++i)
    r[i] = (delta.empty() ? 0.0 : interpolate(delta, tau, _data.delta[i])) - _data.tau[i];
  return r;
}

int Evaluator::signal_anywhere() const
{
  int signal = std::max(interrupt::received(), _signal);
  MPI_Allreduce(MPI_IN_PLACE, &signal, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return signal;
}
} // namespace pushout::study

// The model runs of a fit (Fit.h): each a run_case (driver/Run.h) at a point
// of the free values, on its process group's reused set-up, and its
// residuals against the measured curve; a batch of points spread over the
// groups. A signal stops the fit on every process at once (Interrupted).
#pragma once

#include "../common/Interrupt.h"
#include "../common/exit_codes.h"
#include "../driver/Run.h"
#include "Fit.h"
#include "FreeValue.h"
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mpi.h>
#include <stdexcept>
#include <string>
#include <vector>

namespace pushout::study
{
/// A signal stopped the fit (thrown on every process at once).
class Interrupted : public std::runtime_error
{
public:
  explicit Interrupted(int signal)
      : std::runtime_error("interrupted by " + interrupt::signal_name(signal)), signal(signal)
  {
  }
  int signal;
};

/// The model runs of the fit, spread over the groups of processes.
class Evaluator
{
public:
  Evaluator(const FitOptions& opt, const std::vector<Free>& free, const MeasuredCurve& data,
            MPI_Comm group, int groups, int group_index, int others_here);

  /// The residuals at each of `points` (scaled values); every process gets
  /// them all, and `failed` (if given) whether each point's run failed
  /// outright (its residuals then failed_residual()). The points from
  /// `counted` on are runs ahead: a failure or refusal of theirs counts
  /// only once count() is called with the point. Collective on
  /// MPI_COMM_WORLD.
  std::vector<std::vector<double>> residuals(const std::vector<std::vector<double>>& points,
                                             std::vector<bool>* failed = nullptr,
                                             std::size_t counted = SIZE_MAX);
  /// A run ahead at x is used: its failure or refusal counts now (nothing
  /// if it was neither). Collective on MPI_COMM_WORLD.
  void count(const std::vector<double>& x);

  /// The residual at every point of a run that failed outright (a value the
  /// scene refuses, such as f_fr > f_t, or an error) [MPa]:
  /// failed_run_factor times the largest |tau| measured, beyond any run's
  /// misfit, so that TAO's line search steps back from such values.
  double failed_residual() const;
  static constexpr double failed_run_factor = 1e3;

  /// The --set overrides of the scene at scaled values x.
  std::vector<std::string> sets_at(const std::vector<double>& x) const;

  /// Whether a run's failure or refusal counts among the fit's runs.
  enum class Counts
  {
    now,       ///< a run the fit asked for
    when_used, ///< a run ahead: once count() is called with its point
    never      ///< the fitted run (best/): its outcome is fit.json's converged
  };
  /// One run at scaled values x into `out` on this group; its residuals
  /// (leader), the curve held flat after its last row if it stopped short.
  std::vector<double> run(const std::vector<double>& x, const std::filesystem::path& out,
                          bool plot = false, Counts counts = Counts::now);

  int evaluations() const { return _evaluations; }
  /// The groups that share a batch of runs.
  int groups() const { return _groups; }
  /// How this group's last run ended.
  const driver::RunOutcome& last() const { return _last; }
  /// A signal that stopped a run of any process, or came here (collective
  /// on MPI_COMM_WORLD).
  int signal_anywhere() const;
  /// Runs that did not converge or ended with an error, on every process.
  int failed() const { return _failed_total; }
  /// Runs whose values the scene refused (failed_residual()).
  int refused() const { return _refused_total; }
  const std::string& last_failure() const { return _last_failure; }
  /// Why the scene refused this group's last run it refused ("" if none).
  const std::string& last_refusal() const { return _last_refusal; }
  /// Why the size guard refused this group's last run it refused ("" if
  /// none): the machine's memory, which other work may take during a fit.
  const std::string& last_size_refusal() const { return _last_size_refusal; }
  void release() { _simulation.reset(); }

private:
  const FitOptions& _opt;
  const std::vector<Free>& _free;
  const MeasuredCurve& _data;
  MPI_Comm _group;
  int _groups, _group_index;
  int _others_here; ///< driver::RunOptions::others_here
  bool _leader = false;
  std::unique_ptr<driver::Simulation> _simulation; ///< the group's set-up, reused
  int _evaluations = 0, _failed = 0, _failed_total = 0, _refused = 0, _refused_total = 0;
  int _signal = 0; ///< a run stopped by this signal
  driver::RunOutcome _last{exit_code::done, 0, "", driver::RunOutcome::Refusal::none};
  bool _failed_outright = false; ///< this group's last run
  std::string _last_failure, _last_refusal, _last_size_refusal;
  /// This group's runs ahead that failed or were refused, not yet counted:
  /// their outcomes (leader).
  std::map<std::vector<double>, driver::RunOutcome> _pending;

  /// Counts a run's outcome (leader).
  void tally(const driver::RunOutcome& o);
  /// The totals over the processes. Collective on MPI_COMM_WORLD.
  void sum_counts();
};
} // namespace pushout::study

// What a run reports while it runs and when it ends: the summary as it
// grows, the state a forced stop reports (common/Interrupt.h: the watcher
// thread writes summary.json from the last published state), the progress
// lines, and at the end curve.png, the wall time, the peak memory and
// summary.json.
#pragma once

#include "../common/Interrupt.h"
#include "../common/mpi_errors.h"
#include "../output/Summary.h"
#include "../output/plot.h"
#include "../scene/Scene.h"
#include <array>
#include <chrono>
#include <filesystem>
#include <functional>
#include <mpi.h>
#include <mutex>
#include <optional>
#include <string>

namespace pushout::record
{
/// How far the steps of `stage` had gone when a signal stopped it: "in step
/// 0", "after 5 corrosion steps", empty before the steps (meshing, set-up),
/// or (the push, or a later phase: writing outputs, ...) "after 3 load
/// steps" (summary.json's message; `stage` as its stopped_in).
std::string stage_progress(const std::string& stage, const output::Summary& s);

class RunReport
{
public:
  /// Writes the resolved scene (scene.toml) into `out` (rank 0 of the
  /// run's processes `comm`) and sets the stop report; starts the plotting
  /// process if the run draws its curve (output.plot and `plot`). `quiet`:
  /// no progress lines.
  RunReport(const Scene& scene, const std::filesystem::path& out, bool quiet, MPI_Comm comm,
            bool plot = true);
  RunReport(const RunReport&) = delete;
  RunReport& operator=(const RunReport&) = delete;

  output::Summary& summary() { return _summary; }
  /// Makes the summary as it is now the one a forced stop reports.
  void publish();
  /// What publish() adds to the summary it publishes, not to summary()
  /// (the solver's counts so far, which the run adds at its end); {}: none.
  void set_counters(std::function<void(output::Summary&)> counters)
  {
    _counters = std::move(counters);
  }

  /// Whether this process prints progress lines (rank 0, not quiet).
  bool talk() const { return _talk; }
  /// Seconds since the run started.
  double seconds() const;

  /// Asks finish() to draw `stem`.png from `stem`.csv of the output folder
  /// too, as plot `kind` of scripts/plot_curve.py (if the run draws plots).
  void plot_also(const std::string& stem, const std::string& kind);

  /// The end of the run: curve.png (and corrosion.png, and those of
  /// plot_also) if it draws them,
  /// the wall time and the largest peak memory of the processes,
  /// summary.json (rank 0; throws if it cannot be written). An interrupted
  /// run draws no plot. Collective. Returns the summary.
  output::Summary finish();

  /// The run stops (a signal; the summary says so): summary.json now, as it
  /// is (rank 0), before the outputs are finished, which under mpirun may
  /// be cut short by its SIGKILL. Not collective.
  void save_stop() noexcept;

  /// The end of a run that failed with `message` (an error, already agreed
  /// on): summary.json says so (rank 0), if it can be written. Not
  /// collective.
  void fail(const std::string& message) noexcept;

private:
  /// On the process that ends the run with an error the others did not
  /// come to agree on (mpi::abandon), before it does: summary.json says
  /// the error (rank 0), or (another process) the error is left in the
  /// output folder for rank 0's stop report, as mpirun's SIGTERM to it
  /// follows.
  void abandoned(const std::string& message) noexcept;
  /// Rank 0's stop report: `s` is the error another process left
  /// (abandoned) if it did, not the signal that followed it.
  bool take_process_error(output::Summary& s) const noexcept;
  /// The run's wall time and this process's peak memory so far into `s`
  /// (a summary written before finish()).
  void stamp(output::Summary& s) const;
  using Clock = std::chrono::steady_clock;
  Clock::time_point _start = Clock::now();
  std::filesystem::path _out;
  MPI_Comm _comm;
  int _rank = 0;
  bool _talk = false;
  output::Summary _summary;
  std::mutex _published_mutex;
  output::Summary _published;                      ///< guarded by _published_mutex
  std::function<void(output::Summary&)> _counters; ///< set_counters
  interrupt::ReportOnStop _on_stop;
  mpi::ReportOnAbandon _on_abandon;
  std::optional<output::CurvePlotter> _plotter;        ///< rank 0, if the run draws its curve
  std::vector<std::array<std::string, 2>> _more_plots; ///< plot_also's [stem, kind]
};

/// Peak resident memory of this process so far [MB].
double peak_memory_here_mb();
} // namespace pushout::record

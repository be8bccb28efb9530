// SIGINT/SIGTERM handling, at any time of a run.
//
// The handler only records the signal. Between load steps (and inside
// Newton, by failing the current solve) the step loop looks at it and stops
// cleanly: every finished step stays in curve.csv and summary.json says so.
// A phase that cannot look (gmsh meshing, the model's set-up, a long
// factorisation) is covered by a watcher thread: when a signal has waited
// longer than the current phase's grace, the watcher reports where the run
// stopped (the driver's stop report: summary.json and one line on stderr)
// and ends the process with exit code 128 + signal. A second signal ends it
// at once, whatever the phase.
#pragma once

#include <functional>
#include <string>

namespace pushout::interrupt
{
/// Installs the handlers for SIGINT and SIGTERM (after PetscInitialize,
/// whose handlers they replace), the default action for SIGPIPE, and
/// starts the watcher.
void install();

/// The signal received (0: none). Local to this process.
int received();

/// The name of a signal ("SIGTERM").
std::string signal_name(int signal);

/// Marks a phase of the run for the watcher, until destroyed (the previous
/// phase then returns). `grace_s`: how long a signal may wait for the code
/// to stop by itself before the watcher ends the process; 0 for phases that
/// never look at it; a negative grace: never forced (writing the outputs).
class Phase
{
public:
  Phase(std::string name, double grace_s);
  ~Phase();
  Phase(const Phase&) = delete;
  Phase& operator=(const Phase&) = delete;

private:
  std::string _previous_name;
  double _previous_grace;
};

/// What the watcher calls before it ends the process: `phase` is where the
/// run was. Called on the watcher's thread while the main thread is still
/// running, so it must read only what it owns or what is guarded.
using StopReport = std::function<void(int signal, const std::string& phase)>;

/// Sets the stop report until destroyed (then none: the watcher only says
/// where it stopped on stderr).
class ReportOnStop
{
public:
  explicit ReportOnStop(StopReport report);
  ~ReportOnStop();
  ReportOnStop(const ReportOnStop&) = delete;
  ReportOnStop& operator=(const ReportOnStop&) = delete;
};
} // namespace pushout::interrupt

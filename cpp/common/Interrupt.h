// SIGINT/SIGTERM/SIGHUP handling, at any time of a run.
//
// The handler only records the signal. Between load steps (and inside
// Newton, by failing the current solve) the step loop looks at it and stops
// cleanly: every finished step stays in curve.csv and summary.json says so.
// A phase that cannot look (gmsh meshing, the model's set-up, a long
// factorisation) is covered by a watcher thread: when a signal has waited
// longer than the current phase's grace, the watcher reports where the run
// stopped (the driver's stop report: summary.json and one line on stderr)
// and ends the process with exit code 128 + signal. A second signal ends it
// at once, whatever the phase. The signal reported is the first one.
//
// Under mpirun every process has its own handler and watcher; the step
// loop stops where all processes agree (an MPI_Allreduce of the signal at
// each step). mpirun follows its SIGTERM to the processes with a SIGKILL
// odls_base_sigkill_timeout later (1 s unless set): there the graces are
// shortened to end before it (by 0.5 s or a fifth of it), so that
// summary.json is written before the SIGKILL.
#pragma once

#include <functional>
#include <string>

namespace pushout::interrupt
{
/// Installs the handlers for SIGINT, SIGTERM and SIGHUP (after
/// PetscInitialize, whose handlers they replace; SIGHUP stays ignored if
/// it was when the process started: nohup), ignores SIGPIPE (a write to a
/// closed pipe fails instead), and starts the watcher.
void install();

/// The first signal received (0: none). Local to this process.
int received();

/// The code has seen the signal and is stopping by itself: the watcher no
/// longer ends the process for it (only for a second signal).
void acknowledge();

/// The name of a signal ("SIGTERM").
std::string signal_name(int signal);

/// The grace of the phases that look at the signal themselves (a run's load
/// steps, a fit's or a sweep's time between runs) [s]: how long a signal may
/// wait for the code to stop cleanly (between Newton iterations, steps or
/// runs) before the watcher ends the process where it is, e.g. inside a long
/// factorisation.
constexpr double stop_grace_s = 5;

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

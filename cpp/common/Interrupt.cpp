#include "Interrupt.h"
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <mutex>
#include <thread>

namespace pushout::interrupt
{
namespace
{
volatile std::sig_atomic_t signal_received = 0;
volatile std::sig_atomic_t signal_count = 0;

extern "C" void on_signal(int sig)
{
  signal_received = sig;
  signal_count = signal_count + 1;
}

/// What the watcher reads, guarded by `mutex`. Never destroyed, so the
/// detached watcher never sees it go away at exit.
struct Watched
{
  std::mutex mutex;
  std::string phase = "start-up";
  double grace_s = 0;
  StopReport report;
};
Watched& watched()
{
  static Watched* w = new Watched;
  return *w;
}

/// Polls for a signal that the code has not acted on within the grace of
/// its phase; then reports and ends the process.
void watch()
{
  using Clock = std::chrono::steady_clock;
  constexpr auto poll = std::chrono::milliseconds(50);
  Clock::time_point since{};
  for (;;)
  {
    std::this_thread::sleep_for(poll);
    const int sig = signal_received;
    if (sig == 0)
      continue;
    if (since == Clock::time_point{})
      since = Clock::now();
    Watched& w = watched();
    std::lock_guard lock(w.mutex);
    const double waited = std::chrono::duration<double>(Clock::now() - since).count();
    const bool again = signal_count > 1;
    if (!again && (w.grace_s < 0 || waited < w.grace_s))
      continue;
    if (w.report)
      w.report(sig, w.phase);
    else
      std::cerr << "pushout: interrupted by " << signal_name(sig) << " during " << w.phase
                << std::endl;
    std::fflush(nullptr);
    std::_Exit(128 + sig);
  }
}
} // namespace

void install()
{
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  // A closed pipe (`pushout run ... | head`) ends the run quietly, as for
  // any command, instead of through PETSc's error handler.
  std::signal(SIGPIPE, SIG_DFL);
  std::thread(watch).detach();
}

int received()
{
  return signal_received;
}

std::string signal_name(int signal)
{
  switch (signal)
  {
  case SIGINT:
    return "SIGINT";
  case SIGTERM:
    return "SIGTERM";
  default:
    return "signal " + std::to_string(signal);
  }
}

Phase::Phase(std::string name, double grace_s)
{
  Watched& w = watched();
  std::lock_guard lock(w.mutex);
  _previous_name = std::move(w.phase);
  _previous_grace = w.grace_s;
  w.phase = std::move(name);
  w.grace_s = grace_s;
}

Phase::~Phase()
{
  Watched& w = watched();
  std::lock_guard lock(w.mutex);
  w.phase = std::move(_previous_name);
  w.grace_s = _previous_grace;
}

ReportOnStop::ReportOnStop(StopReport report)
{
  Watched& w = watched();
  std::lock_guard lock(w.mutex);
  w.report = std::move(report);
}

ReportOnStop::~ReportOnStop()
{
  Watched& w = watched();
  std::lock_guard lock(w.mutex);
  w.report = nullptr;
}
} // namespace pushout::interrupt

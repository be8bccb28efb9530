#include "Interrupt.h"
#include "exit_codes.h"
#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <mutex>
#include <thread>

namespace pushout::interrupt
{
namespace
{
// Written by the handler and the main thread, read by the watcher thread:
// atomics, lock-free so that the handler may touch them.
static_assert(std::atomic<int>::is_always_lock_free);
std::atomic<int> signal_received = 0; ///< the first signal
std::atomic<int> signal_count = 0;
std::atomic<int> signal_acknowledged = 0;

extern "C" void on_signal(int sig)
{
  int none = 0;
  signal_received.compare_exchange_strong(none, sig);
  ++signal_count;
}

/// Whether SIGHUP was ignored when the process started (`nohup`): read
/// before main(), since PetscInitialize installs its own handler.
const bool hangup_ignored = []
{
  struct sigaction action;
  return sigaction(SIGHUP, nullptr, &action) == 0 && action.sa_handler == SIG_IGN;
}();

/// The longest grace of any phase [s] (infinite: none): under mpirun, whose
/// SIGTERM to the processes is followed by a SIGKILL
/// odls_base_sigkill_timeout later (default 1 s), a phase that has not
/// stopped by itself well before that is ended by the watcher, which still
/// has time to write summary.json.
double grace_limit_s()
{
  if (!std::getenv("OMPI_COMM_WORLD_SIZE")) // not started by mpirun
    return std::numeric_limits<double>::infinity();
  double timeout_s = 1; // Open MPI's default
  if (const char* t = std::getenv("OMPI_MCA_odls_base_sigkill_timeout"))
    timeout_s = std::max(std::atof(t), 0.0);
  return std::max(0.1, timeout_s - std::max(0.5, 0.2 * timeout_s));
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
  const double limit_s = grace_limit_s();
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
    const double grace_s = w.grace_s < 0 ? w.grace_s : std::min(w.grace_s, limit_s);
    if (!again && (signal_acknowledged || grace_s < 0 || waited < grace_s))
      continue;
    if (w.report)
      w.report(sig, w.phase);
    else
      std::cerr << "pushout: interrupted by " << signal_name(sig) << " during " << w.phase
                << std::endl;
    std::fflush(nullptr);
    std::_Exit(exit_code::signal(sig));
  }
}
} // namespace

void install()
{
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  // A closed terminal or ssh session: a clean stop, unless started to
  // outlive it (nohup).
  std::signal(SIGHUP, hangup_ignored ? SIG_IGN : on_signal);
  // A closed pipe (`pushout run ... | head`) does not end the run: writes to
  // it fail (progress lines are no longer printed), the files are written.
  std::signal(SIGPIPE, SIG_IGN);
  std::thread(watch).detach();
}

int received()
{
  return signal_received;
}

void acknowledge()
{
  signal_acknowledged = 1;
}

std::string signal_name(int signal)
{
  switch (signal)
  {
  case SIGINT:
    return "SIGINT";
  case SIGTERM:
    return "SIGTERM";
  case SIGHUP:
    return "SIGHUP";
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

#include "Interrupt.h"
#include <csignal>

namespace pushout::interrupt
{
namespace
{
volatile std::sig_atomic_t signal_received = 0;

extern "C" void on_signal(int sig)
{
  signal_received = sig;
}
} // namespace

void install()
{
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  // A closed pipe (`pushout run ... | head`) ends the run quietly, as for
  // any command, instead of through PETSc's error handler.
  std::signal(SIGPIPE, SIG_DFL);
}

int received()
{
  return signal_received;
}
} // namespace pushout::interrupt

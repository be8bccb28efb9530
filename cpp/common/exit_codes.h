// The exit codes of every pushout command (run, sweep, fit, keys, laws):
// one table, used everywhere a process decides how it ends.
#pragma once

namespace pushout::exit_code
{
constexpr int done = 0;          ///< the command did what it was asked
constexpr int failure = 1;       ///< anything else: an I/O error, an internal error
constexpr int bad_input = 2;     ///< a bad scene, option or command line
constexpr int not_converged = 3; ///< a step that cannot converge (or a non-finite result)
/// A signal stopped the command: 128 + its number (SIGINT 130, SIGTERM 143).
constexpr int signal(int number)
{
  return 128 + number;
}
} // namespace pushout::exit_code

#include "plot.h"
#include <csignal>
#include <cstdlib>
#include <string>
#include <sys/wait.h>
#include <utility>
#include <vector>

#ifndef PUSHOUT_PYTHON
#error "PUSHOUT_PYTHON must name the python interpreter with matplotlib"
#endif
#ifndef PUSHOUT_SCRIPTS_DIR
#error "PUSHOUT_SCRIPTS_DIR must point to scripts/"
#endif

namespace pushout::output
{
namespace
{
/// Ignores SIGPIPE while it lives: a plotting process that died (python or
/// matplotlib missing, a signal) makes a write fail, not end the run.
class NoSigpipe
{
public:
  NoSigpipe() : _previous(std::signal(SIGPIPE, SIG_IGN)) {}
  ~NoSigpipe() { std::signal(SIGPIPE, _previous); }
  NoSigpipe(const NoSigpipe&) = delete;
  NoSigpipe& operator=(const NoSigpipe&) = delete;

private:
  void (*_previous)(int);
};

std::string quote(const std::string& s)
{
  std::string q = "'";
  for (char c : s)
    q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// How a child ended, from its wait status (std::system, pclose): "exit
/// 1", "signal 9".
std::string ended(int status)
{
  if (WIFEXITED(status))
    return "exit " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status))
    return "signal " + std::to_string(WTERMSIG(status));
  return "status " + std::to_string(status);
}

std::string script_path(const char* script)
{
  return (std::filesystem::path(PUSHOUT_SCRIPTS_DIR) / script).string();
}

/// The shell command that runs the python interpreter with the signals
/// that stop a run ignored: a Ctrl-C reaches the whole foreground process
/// group, the plotting child too, and the run decides (a signal once the
/// last step is done stops nothing, and the plot is drawn; docs/running.md,
/// "Stopping a run"). Python keeps SIGINT ignored when it starts so (no
/// KeyboardInterrupt); a child whose run died ends at its pipe's end.
std::string python_command()
{
  return "trap '' INT TERM HUP; exec " + quote(PUSHOUT_PYTHON);
}

/// Runs the python interpreter with `args` (a script of scripts/ and its
/// arguments, each shell-quoted); false with `why` if it failed.
bool run_script(const std::vector<std::string>& args, std::string& why)
{
  std::string cmd = python_command();
  for (const std::string& a : args)
    (cmd += ' ') += quote(a);
  cmd += " 2>&1";
  const int rc = std::system(cmd.c_str());
  if (rc != 0)
  {
    why =
        "plot script failed (" + (rc == -1 ? std::string("not started") : ended(rc)) + "): " + cmd;
    return false;
  }
  return true;
}
} // namespace

CurvePlotter::CurvePlotter()
{
  // The child's output goes to the run's stderr; it ends at the pipe's end.
  std::string cmd = python_command();
  (cmd += ' ') += quote(script_path("plot_curve.py"));
  cmd += " --serve 1>&2";
  _pipe = popen(cmd.c_str(), "w");
}

CurvePlotter::~CurvePlotter()
{
  if (_pipe)
  {
    const NoSigpipe guard;
    pclose(_pipe);
  }
}

void CurvePlotter::draw(const std::filesystem::path& csv, const std::filesystem::path& png,
                        const std::string& kind)
{
  if (!_pipe)
    return;
  const NoSigpipe guard;
  // One JSON list per line: ["csv", "png", "kind"].
  const auto json = [](const std::string& s)
  {
    std::string q = "\"";
    for (char c : s)
    {
      if (c == '"' || c == '\\')
        q += '\\';
      q += c;
    }
    q += '"';
    return q;
  };
  std::string line = "[";
  line += json(csv.string());
  line += ',';
  line += json(png.string());
  line += ',';
  line += json(kind);
  line += "]\n";
  if (std::fputs(line.c_str(), _pipe) < 0 || std::fflush(_pipe) != 0)
    _failed = true;
}

bool CurvePlotter::finish(std::string& why)
{
  if (!_pipe)
  {
    why = "could not start " + std::string(PUSHOUT_PYTHON);
    return false;
  }
  const NoSigpipe guard;
  const int rc = pclose(std::exchange(_pipe, nullptr));
  if (rc != 0 || _failed)
  {
    why = "plot script failed (" + (rc == -1 ? std::string("not waited for") : ended(rc)) + ")";
    return false;
  }
  return true;
}

bool plot_fit(const std::filesystem::path& folder, const std::filesystem::path& png,
              std::string& why)
{
  return run_script({script_path("plot_fit.py"), folder.string(), png.string()}, why);
}

bool plot_sweep(const std::filesystem::path& folder, const std::filesystem::path& png,
                std::string& why)
{
  return run_script({script_path("plot_sweep.py"), folder.string(), png.string()}, why);
}
} // namespace pushout::output

#include "plot.h"
#include <cstdlib>
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
std::string quote(const std::string& s)
{
  std::string q = "'";
  for (char c : s)
    q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string script_path(const char* script)
{
  return (std::filesystem::path(PUSHOUT_SCRIPTS_DIR) / script).string();
}

/// Runs the python interpreter with `args` (a script of scripts/ and its
/// arguments, each shell-quoted); false with `why` if it failed.
bool run_script(const std::vector<std::string>& args, std::string& why)
{
  std::string cmd = quote(PUSHOUT_PYTHON);
  for (const std::string& a : args)
    (cmd += ' ') += quote(a);
  cmd += " 2>&1";
  const int rc = std::system(cmd.c_str());
  if (rc != 0)
  {
    why = "plot script failed (exit " + std::to_string(rc) + "): " + cmd;
    return false;
  }
  return true;
}
} // namespace

CurvePlotter::CurvePlotter()
{
  // The child's output goes to the run's stderr; it ends at the pipe's end.
  std::string cmd = quote(PUSHOUT_PYTHON);
  (cmd += ' ') += quote(script_path("plot_curve.py"));
  cmd += " --serve 1>&2";
  _pipe = popen(cmd.c_str(), "w");
}

CurvePlotter::~CurvePlotter()
{
  if (_pipe)
    pclose(_pipe);
}

void CurvePlotter::draw(const std::filesystem::path& csv, const std::filesystem::path& png,
                        const std::string& kind)
{
  if (!_pipe)
    return;
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
  std::fputs(line.c_str(), _pipe);
}

bool CurvePlotter::finish(std::string& why)
{
  if (!_pipe)
  {
    why = "could not start " + std::string(PUSHOUT_PYTHON);
    return false;
  }
  const int rc = pclose(std::exchange(_pipe, nullptr));
  if (rc != 0)
  {
    why = "plot script failed (exit " + std::to_string(rc) + ")";
    return false;
  }
  return true;
}

bool plot_curve(const std::filesystem::path& csv, const std::filesystem::path& png,
                const std::string& kind, std::string& why)
{
  return run_script({script_path("plot_curve.py"), csv.string(), png.string(), "--kind", kind},
                    why);
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

#include "plot.h"
#include <cstdlib>

#ifndef PUSHOUT_PYTHON
#error "PUSHOUT_PYTHON must name the python interpreter with matplotlib"
#endif
#ifndef PUSHOUT_SCRIPTS_DIR
#error "PUSHOUT_SCRIPTS_DIR must point to scripts/"
#endif

namespace pushout::output
{
bool plot_curve(const std::filesystem::path& csv, const std::filesystem::path& png,
                const std::string& kind, std::string& why)
{
  const std::filesystem::path script = std::filesystem::path(PUSHOUT_SCRIPTS_DIR) / "plot_curve.py";
  const auto quote = [](const std::string& s)
  {
    std::string q = "'";
    for (char c : s)
      q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  };
  const std::string cmd = quote(PUSHOUT_PYTHON) + " " + quote(script.string()) + " " +
                          quote(csv.string()) + " " + quote(png.string()) + " --kind " +
                          quote(kind) + " 2>&1";
  const int rc = std::system(cmd.c_str());
  if (rc != 0)
  {
    why = "plot script failed (exit " + std::to_string(rc) + "): " + cmd;
    return false;
  }
  return true;
}
} // namespace pushout::output

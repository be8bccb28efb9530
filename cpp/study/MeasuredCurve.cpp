// The measured curve of a fit (MeasuredCurve.h): its reading, with an error
// that says what is wrong with the file, and its interpolation.
#include "MeasuredCurve.h"
#include "../scene/InputFile.h"
#include "../scene/SceneError.h"
#include "text.h"
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace pushout::study
{
std::string read_measured_text(const std::filesystem::path& file)
{
  // A measured curve is some thousands of rows: 64 MiB is not one.
  return read_input_file(file, "--data '" + file.string() + "'", std::uintmax_t(64) << 20,
                         "a measured curve");
}

MeasuredCurve parse_measured(const std::string& text, const std::filesystem::path& file)
{
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line))
    throw SceneError("--data '" + file.string() + "' is empty");
  if (!line.empty() && line.back() == '\r')
    line.pop_back();
  // A UTF-8 byte order mark (spreadsheets write one) is not the header's.
  const std::string bom = "\xEF\xBB\xBF";
  if (line.rfind(bom, 0) == 0)
    line.erase(0, bom.size());
  const std::vector<std::string> header = split(line, ',');
  const auto find = [&](const std::string& name)
  {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end())
      throw SceneError("--data '" + file.string() + "': no column '" + name + "' in its header '" +
                       line + "' (delta_mm and tau_MPa are needed)");
    return std::size_t(it - header.begin());
  };
  const std::size_t cd = find("delta_mm"), ct = find("tau_MPa");
  MeasuredCurve c;
  for (int row = 2; std::getline(in, line); ++row)
  {
    if (!line.empty() && line.back() == '\r')
      line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos)
      continue;
    const std::vector<std::string> cells = split(line, ',');
    double v[2];
    for (int k = 0; k < 2; ++k)
    {
      const std::size_t col = k == 0 ? cd : ct;
      if (col >= cells.size() || !finite_number(cells[col], v[k]))
        throw SceneError("--data '" + file.string() + "' line " + std::to_string(row) + ": " +
                         header[col] + " '" + (col < cells.size() ? cells[col] : "") +
                         "' is not a number");
    }
    if (v[0] < 0)
      throw SceneError("--data '" + file.string() + "' line " + std::to_string(row) +
                       ": delta_mm " + cells[cd] +
                       " is negative: the push displaces the tube forward from delta = 0");
    if (!c.delta.empty() && !(v[0] > c.delta.back()))
      throw SceneError("--data '" + file.string() + "' line " + std::to_string(row) +
                       ": delta_mm must increase (a monotonic push; unload and reload "
                       "branches are not fitted)");
    c.delta.push_back(v[0]);
    c.tau.push_back(v[1]);
  }
  if (c.delta.empty())
    throw SceneError("--data '" + file.string() + "' has no rows");
  if (std::none_of(c.tau.begin(), c.tau.end(), [](double t) { return t > 0; }))
    throw SceneError("--data '" + file.string() +
                     "': no tau_MPa above 0: a push-out's bond stress is positive (the push "
                     "force resists the push); a curve of the opposite sign needs its sign "
                     "changed");
  if (!(c.delta.back() > 0))
    throw SceneError("--data '" + file.string() + "': the largest delta_mm must be > 0");
  return c;
}

double interpolate(const std::vector<double>& delta, const std::vector<double>& tau, double d)
{
  if (d <= delta.front())
    return tau.front();
  for (std::size_t i = 1; i < delta.size(); ++i)
    if (d <= delta[i])
    {
      const double t = (d - delta[i - 1]) / (delta[i] - delta[i - 1]);
      return tau[i - 1] + t * (tau[i] - tau[i - 1]);
    }
  return tau.back();
}
} // namespace pushout::study

// Text helpers of the fit: a line split at a separator, a number read from
// text, and a number as text that reads back as the same double.
#pragma once

#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace pushout::study
{
/// The parts of `s` between the separators `by`.
inline std::vector<std::string> split(const std::string& s, char by)
{
  std::vector<std::string> parts;
  std::stringstream in(s);
  for (std::string part; std::getline(in, part, by);)
    parts.push_back(part);
  return parts;
}

/// Whether `s` is one finite number, spaces and tabs around it allowed (not
/// "0.5x", "nan", "inf" or ""); the number into `v`.
inline bool finite_number(const std::string& s, double& v)
{
  std::size_t used = 0;
  try
  {
    v = std::stod(s, &used);
  }
  catch (const std::exception&)
  {
    return false;
  }
  return s.find_first_not_of(" \t", used) == std::string::npos && std::isfinite(v);
}

/// `v` with 17 significant digits: reads back as the same double.
inline std::string number_text(double v)
{
  std::ostringstream s;
  s << std::setprecision(17) << v;
  return s.str();
}
} // namespace pushout::study

// Text helpers of the fit: a line split at a separator, and a number as text
// that reads back as the same double.
#pragma once

#include <iomanip>
#include <sstream>
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

/// `v` with 17 significant digits: reads back as the same double.
inline std::string number_text(double v)
{
  std::ostringstream s;
  s << std::setprecision(17) << v;
  return s.str();
}
} // namespace pushout::study

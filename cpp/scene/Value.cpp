#include "Value.h"
#include <cstdlib>
#include <iomanip>
#include <sstream>

namespace pushout
{
const char* type_name(KeyType type)
{
  switch (type)
  {
  case KeyType::number:
    return "a number";
  case KeyType::integer:
    return "an integer";
  case KeyType::boolean:
    return "true or false";
  case KeyType::string:
    return "a string";
  case KeyType::number_array:
    return "an array of numbers";
  }
  return "?";
}

namespace
{
/// Shortest decimal form that reads back to exactly x.
std::string format_number(double x)
{
  std::string out;
  for (int digits = 15; digits <= 17; ++digits)
  {
    std::ostringstream s;
    s << std::setprecision(digits) << x;
    out = s.str();
    // strtod, not stod: stod throws on a subnormal x (out of range).
    if (std::strtod(out.c_str(), nullptr) == x)
      break;
  }
  if (out.find_first_of(".eEn") == std::string::npos)
    out += ".0";
  return out;
}
} // namespace

std::string to_toml(const Value& value)
{
  if (const auto* d = std::get_if<double>(&value))
    return format_number(*d);
  if (const auto* i = std::get_if<std::int64_t>(&value))
    return std::to_string(*i);
  if (const auto* b = std::get_if<bool>(&value))
    return *b ? "true" : "false";
  if (const auto* s = std::get_if<std::string>(&value))
    return "\"" + *s + "\"";
  const auto& a = std::get<std::vector<double>>(value);
  std::string out = "[";
  for (std::size_t i = 0; i < a.size(); ++i)
    out += (i ? ", " : "") + format_number(a[i]);
  return out + "]";
}
} // namespace pushout

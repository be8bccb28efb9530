// A scene value: the types a scene key can have.
#pragma once

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

namespace pushout
{
enum class KeyType
{
  number,      ///< floating point (integers accepted)
  integer,     ///< whole number
  boolean,     ///< true | false
  string,      ///< free text or one of `choices`
  number_array ///< array of numbers
};

using Value = std::variant<double, std::int64_t, bool, std::string, std::vector<double>>;

/// Human-readable name of a key type, for error messages.
const char* type_name(KeyType type);

/// Format a value as TOML.
std::string to_toml(const Value& value);
} // namespace pushout

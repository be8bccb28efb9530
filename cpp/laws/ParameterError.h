// The error a law throws when its parameters cannot go together (a
// combination its per-parameter ranges cannot express). The message names
// the keys with the prefix the caller gave; the scene turns it into a
// SceneError, so laws/ needs nothing from the rest of the project.
#pragma once

#include <stdexcept>

namespace pushout::laws
{
class ParameterError : public std::invalid_argument
{
public:
  using std::invalid_argument::invalid_argument;
};
} // namespace pushout::laws

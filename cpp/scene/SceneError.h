// Error in the user's scene or command line: always names the offending key.
#pragma once

#include <stdexcept>
#include <string>

namespace pushout
{
/// A scene (or `--set`) problem the user can fix. The message names the key.
class SceneError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};
} // namespace pushout

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

/// A command-line option or environment variable the user can fix (a PETSc
/// option, $PUSHOUT_CACHE_MAX_MB): refused as a scene's error is (exit 2),
/// but not called an error in the scene. The message names the option.
class OptionError : public SceneError
{
public:
  using SceneError::SceneError;
};
} // namespace pushout

// Where the mesh cache lives (mesh::default_cache_dir): the environment's
// choice, in order; a relative XDG_CACHE_HOME is none (the XDG base
// directory spec).
#include "mesh/generate.h"
#include <cstdlib>
#include <gtest/gtest.h>
#include <optional>
#include <string>

namespace
{
/// Sets (or unsets, nullopt) an environment variable for the scope.
class Env
{
public:
  Env(const char* name, std::optional<std::string> value) : _name(name)
  {
    if (const char* v = std::getenv(name))
      _old = v;
    if (value)
      setenv(name, value->c_str(), 1);
    else
      unsetenv(name);
  }
  ~Env()
  {
    if (_old)
      setenv(_name, _old->c_str(), 1);
    else
      unsetenv(_name);
  }

private:
  const char* _name;
  std::optional<std::string> _old;
};
} // namespace

TEST(CacheDir, TheEnvironmentsChoiceInOrder)
{
  using pushout::mesh::default_cache_dir;
  const Env home("HOME", "/home/u");
  {
    const Env dir("PUSHOUT_CACHE_DIR", "/c"), xdg("XDG_CACHE_HOME", "/x");
    EXPECT_EQ(default_cache_dir(), "/c");
  }
  const Env dir("PUSHOUT_CACHE_DIR", std::nullopt);
  {
    const Env xdg("XDG_CACHE_HOME", "/x");
    EXPECT_EQ(default_cache_dir(), "/x/pushout");
  }
  {
    const Env xdg("XDG_CACHE_HOME", "relative/cache");
    EXPECT_EQ(default_cache_dir(), "/home/u/.cache/pushout");
  }
  const Env xdg("XDG_CACHE_HOME", std::nullopt);
  EXPECT_EQ(default_cache_dir(), "/home/u/.cache/pushout");
}

// A constructor that throws runs no destructor, so what it got (PETSc
// objects, borrowed arrays) before the error must be given back by hand:
// build_or_release runs the constructor's work and, if that throws, the
// release, then lets the error go on (a sweep's refused case goes on to the
// next one without a leak).
#pragma once

#include <utility>

namespace pushout
{
/// Runs `build()`; if it throws, runs `release()` (which must accept a
/// partial build and not throw) and rethrows the error.
template <class Build, class Release> void build_or_release(Build&& build, Release&& release)
{
  try
  {
    std::forward<Build>(build)();
  }
  catch (...)
  {
    std::forward<Release>(release)();
    throw;
  }
}
} // namespace pushout

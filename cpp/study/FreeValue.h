// A free value of a fit (Fit.h): the scene key it sets, its start, its
// bounds and the scale TAO divides it by.
#pragma once

#include <cmath>
#include <string>

namespace pushout::study
{
/// A free value: its key, start, bounds and the scale TAO divides it by.
struct Free
{
  std::string key;
  double start = 0, lo = -INFINITY, hi = INFINITY, scale = 1;
  bool lo_exclusive = false; ///< lo itself is not allowed (a law's positive parameter)
  /// The lower bound given to TAO: lo, or the next number above it.
  double tao_lo() const { return lo_exclusive ? std::nextafter(lo, INFINITY) : lo; }
};
} // namespace pushout::study

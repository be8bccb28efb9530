// A free value of a fit (Fit.h): the scene key it sets, its start, its
// bounds and the scale TAO divides it by.
#pragma once

#include <algorithm>
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
  bool hi_exclusive = false; ///< hi itself is not allowed (a key's open range)
  /// The lower bound given to TAO: lo, or just above it where lo itself is
  /// not allowed: by 1e-9 of the value's scale, so that the bound divided
  /// by the scale (TAO's variable) and multiplied back stays above lo (the
  /// next number above 0 became 0 there, and the model was run at f_t = 0),
  /// and within the 1e-6 of the scale that says a value sits on its bound.
  double tao_lo() const
  {
    return lo_exclusive ? std::max(lo + 1e-9 * scale, std::nextafter(lo, INFINITY)) : lo;
  }
  /// The upper bound given to TAO: hi, or just below it (as tao_lo).
  double tao_hi() const
  {
    return hi_exclusive ? std::min(hi - 1e-9 * scale, std::nextafter(hi, -INFINITY)) : hi;
  }
  /// Whether the scaled value x sits on its lower (upper) bound: within 1e-6
  /// of the scale, which tao_lo's and tao_hi's 1e-9 lie within.
  bool on_lo(double x) const
  {
    return std::isfinite(lo) && std::abs(x * scale - lo) <= 1e-6 * scale;
  }
  bool on_hi(double x) const
  {
    return std::isfinite(hi) && std::abs(x * scale - hi) <= 1e-6 * scale;
  }
};
} // namespace pushout::study

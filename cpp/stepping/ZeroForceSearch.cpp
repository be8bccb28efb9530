// Illinois false position for the zero force of an unloading segment
// (ZeroForceSearch.h).
#include "ZeroForceSearch.h"
#include <algorithm>
#include <cmath>

namespace pushout::stepping
{
ZeroForceResult find_zero_force(double s0, double P0, double s1, double P1, double tol,
                                const ZeroForceTry& try_at, int max_tries, double bracket)
{
  using Outcome = ZeroForceResult::Outcome;
  double s = s0;
  int replaced = 0; // the end the last try replaced: -1 (s0) or +1 (s1)
  for (int tries = 1; tries <= max_tries; ++tries)
  {
    s = s1 - P1 * (s1 - s0) / (P1 - P0);
    const std::optional<double> P = try_at(s);
    if (!P)
      return {Outcome::try_failed, s, tries};
    // Found, or the bracket is down to round-off of the load parameter
    // (the force's own noise above tol).
    if (std::abs(*P) <= tol || std::abs(s1 - s0) <= bracket * std::max(1.0, s))
      return {Outcome::found, s, tries};
    if (*P < 0)
    {
      s1 = s;
      P1 = *P;
      if (replaced == +1) // s0 kept twice: halve its weight
        P0 /= 2;
      replaced = +1;
    }
    else
    {
      s0 = s;
      P0 = *P;
      if (replaced == -1)
        P1 /= 2;
      replaced = -1;
    }
  }
  return {Outcome::not_found, s, std::max(max_tries, 0)};
}
} // namespace pushout::stepping

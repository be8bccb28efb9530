// The zero of the push force on an unloading segment that ends where the
// force falls to zero (loading.unload_to = "zero_force": a push-out device
// cannot pull; docs/results.md, "Unload and reload"): Illinois false
// position on the load parameter s. The caller tries a load parameter (one
// step from its committed state, DisplacementControl.cpp) and reports the
// force; the search only chooses where to try, so it is a pure function of
// the forces it is given.
#pragma once

#include <functional>
#include <optional>

namespace pushout::stepping
{
/// Tries at most this many load parameters.
constexpr int zero_force_max_tries = 50;
/// Ends once the bracket is this small, relative to max(1, s): round-off
/// of the load parameter, where the force's own noise is above tol.
constexpr double zero_force_bracket = 1e-12;

/// How a zero-force search ended.
struct ZeroForceResult
{
  enum class Outcome
  {
    found,      ///< |P(s)| <= tol, or the bracket down to round-off
    try_failed, ///< the try at s did not converge
    not_found   ///< max_tries tries, none of them found
  };
  Outcome outcome;
  double s;  ///< the load parameter of the last try (s0 if none)
  int tries; ///< tries made, the last one included
};

/// The try at load parameter s: the force P(s) [N], or nullopt if the try
/// did not converge (the search ends there).
using ZeroForceTry = std::function<std::optional<double>(double s)>;

/// The load parameter s in (s0, s1] where the force is zero within `tol`
/// [N], from a bracket with force P0 >= 0 at s0 and P1 < 0 at s1 [N]. Each
/// try is at the secant's zero of the bracket, s = s1 - P1 (s1 - s0) / (P1
/// - P0); the try replaces the end of its sign, and the end kept twice in a
/// row has its force halved (Illinois). Ends at the first try with |P| <=
/// tol or with the bracket it was chosen in down to `bracket` max(1, s).
ZeroForceResult find_zero_force(double s0, double P0, double s1, double P1, double tol,
                                const ZeroForceTry& try_at, int max_tries = zero_force_max_tries,
                                double bracket = zero_force_bracket);
} // namespace pushout::stepping

// Softening envelopes sigma(kappa) of the cohesive laws (paper §2.3, Fig. 5):
// the traction reached on monotonic loading at equivalent jump kappa >= w0,
// w0 = f_t / k the jump at the peak (elastic branch before it).
//
//   linear:               f_t (1 - (kappa - w0) / w_c2), zero beyond w0 + w_c2
//   linear with residual: the linear branch until it reaches f_fr, then f_fr
//   exponential:          f_fr + (f_t - f_fr) exp(-c (kappa - w0))
//
// Units: f_t, f_fr [MPa]; w_c2, kappa [mm]; c [1/mm].
#pragma once

#include <algorithm>
#include <cmath>

namespace pushout::laws
{
struct Envelope
{
  enum class Kind
  {
    linear,
    linear_residual,
    exponential
  };
  Kind kind;
  double f_t;      ///< tensile strength (peak) [MPa]
  double w_c2 = 0; ///< linear: softening length from the peak to zero [mm]
  double f_fr = 0; ///< residual (asymptote) [MPa]
  double c = 0;    ///< exponential decay [1/mm]

  struct Value
  {
    double sigma;  ///< traction on the envelope [MPa]
    double dsigma; ///< d sigma / d kappa [N/mm^3]
  };

  /// sigma(kappa) and its slope, for kappa >= w0.
  Value evaluate(double kappa, double w0) const
  {
    const double x = kappa - w0;
    if (kind == Kind::exponential)
    {
      const double e = std::exp(-c * x);
      return {f_fr + (f_t - f_fr) * e, -c * (f_t - f_fr) * e};
    }
    const double floor = kind == Kind::linear ? 0.0 : f_fr;
    const double sigma = f_t * (1 - x / w_c2);
    if (sigma <= floor)
      return {floor, 0.0};
    return {sigma, -f_t / w_c2};
  }

  /// The area under the envelope from w0 to kappa [N/mm]: int sigma.
  double work(double kappa, double w0) const
  {
    const double x = std::max(kappa - w0, 0.0);
    if (kind == Kind::exponential)
      return f_fr * x - (f_t - f_fr) * std::expm1(-c * x) / c; // exact where c x is tiny
    const double floor = kind == Kind::linear ? 0.0 : f_fr;
    const double x_floor = w_c2 * (1 - floor / f_t); // where the line meets the floor
    const double xl = std::min(x, x_floor);
    return f_t * (xl - xl * xl / (2 * w_c2)) + floor * (x - xl);
  }

  /// The area between the envelope and its residual f_fr beyond the peak
  /// [N/mm]: the energy the softening releases (the residual's part is the
  /// plateau's, not brittle). Exponential (f_t - f_fr) / c; linear
  /// f_t w_c2 / 2; linear with residual (f_t - f_fr)^2 w_c2 / (2 f_t).
  double softening_energy() const
  {
    if (kind == Kind::exponential)
      return (f_t - f_fr) / c;
    if (kind == Kind::linear)
      return 0.5 * f_t * w_c2;
    return 0.5 * (f_t - f_fr) * (f_t - f_fr) * w_c2 / f_t;
  }
};
} // namespace pushout::laws

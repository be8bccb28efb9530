// A random tensile-strength field for concrete that cracks (docs/cracking.md):
// seeded, spatially correlated, and a pure function of position, so that
// every process (any partition), every run and every machine sees the same
// field for the same seed.
//
// The strength at x is f_t s(x), with s lognormal of mean 1 and coefficient
// of variation `cov`:
//
//   s(x) = exp(sigma g(x) - sigma^2 / 2),   sigma^2 = ln(1 + cov^2),
//
// g a standard Gaussian field with correlation exp(-(r / l)^2), l the
// correlation length [mm], approximated by random Fourier modes (Rahimi &
// Recht's random features; Shinozuka's spectral representation):
//
//   g(x) = sqrt(2 / M) sum_m cos(k_m . x + phi_m),
//   k_m ~ N(0, (2 / l^2) I),  phi_m ~ U(0, 2 pi),
//
// whose mean is 0, variance 1 and correlation E cos(k . r) = exp(-(r/l)^2);
// with M = 512 modes g is Gaussian to the central limit. A lognormal s is
// positive, as a strength must be.
//
// The modes come from std::mt19937_64 (fully specified by the C++ standard)
// through this file's own Box-Muller transform (std::normal_distribution's
// algorithm is the library's choice), so a seed gives the same field with
// any standard library.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

namespace pushout::bulk
{
class StrengthField
{
public:
  static constexpr int modes = 512;

  /// `cov` [-] (0: uniform, s = 1), `correlation_length` [mm] (> 0),
  /// `seed`.
  StrengthField(double cov, double correlation_length, std::uint64_t seed)
      : _sigma(std::sqrt(std::log1p(cov * cov)))
  {
    if (cov <= 0)
      return;
    std::mt19937_64 engine(seed);
    // A uniform in (0, 1) from the engine's 64 bits (53 of them).
    const auto uniform = [&engine]()
    { return (double(engine() >> 11) + 0.5) * (1.0 / 9007199254740992.0); };
    const double k_scale = std::sqrt(2.0) / correlation_length; // std of each k component [1/mm]
    _k.resize(modes);
    _phase.resize(modes);
    for (int m = 0; m < modes; ++m)
    {
      for (int d = 0; d < 3; d += 2) // Box-Muller: two normals per pair of uniforms
      {
        const double r = std::sqrt(-2 * std::log(uniform())), t = 2 * std::numbers::pi * uniform();
        _k[m][d] = k_scale * r * std::cos(t);
        if (d + 1 < 3)
          _k[m][d + 1] = k_scale * r * std::sin(t);
      }
      _phase[m] = 2 * std::numbers::pi * uniform();
    }
  }

  /// The standard Gaussian field g at x [mm] (0 for a uniform field).
  double gaussian(const std::array<double, 3>& x) const
  {
    if (_k.empty())
      return 0;
    double sum = 0;
    for (int m = 0; m < modes; ++m)
      sum += std::cos(_k[m][0] * x[0] + _k[m][1] * x[1] + _k[m][2] * x[2] + _phase[m]);
    return std::sqrt(2.0 / modes) * sum;
  }

  /// The strength factor s(x) = f_t(x) / f_t: lognormal, mean 1.
  double factor(const std::array<double, 3>& x) const
  {
    if (_k.empty())
      return 1;
    return std::exp(_sigma * gaussian(x) - 0.5 * _sigma * _sigma);
  }

private:
  double _sigma; ///< std of ln s
  std::vector<std::array<double, 3>> _k;
  std::vector<double> _phase;
};
} // namespace pushout::bulk

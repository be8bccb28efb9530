// Quadrature on the joint element's reference square [0,1]^2.
//
// gauss: 2x2 Gauss-Legendre, exact for the bilinear x bilinear products of
//        the joint stiffness. nodal: Newton-Cotes (trapezoidal) at the 4
//        node pairs, which decouples the node pairs and avoids the traction
//        oscillations of Gauss integration at high penalty stiffness
//        (Schellekens & de Borst 1993).
#pragma once

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace pushout::interface
{
struct Quadrature
{
  std::vector<std::array<double, 2>> points; ///< (xi, eta) in [0,1]^2
  std::vector<double> weights;               ///< sum to 1 (reference area)
};

inline Quadrature make_quadrature(const std::string& kind)
{
  if (kind == "gauss")
  {
    const double a = 0.5 - 0.5 / std::sqrt(3.0), b = 0.5 + 0.5 / std::sqrt(3.0);
    return {{{a, a}, {b, a}, {a, b}, {b, b}}, {0.25, 0.25, 0.25, 0.25}};
  }
  if (kind == "nodal")
    return {{{0, 0}, {1, 0}, {0, 1}, {1, 1}}, {0.25, 0.25, 0.25, 0.25}};
  throw std::invalid_argument("unknown interface quadrature '" + kind + "'");
}

/// Bilinear shape functions at (xi, eta), tensor node order.
inline std::array<double, 4> shape(const std::array<double, 2>& p)
{
  const auto [x, y] = p;
  return {(1 - x) * (1 - y), x * (1 - y), (1 - x) * y, x * y};
}
} // namespace pushout::interface

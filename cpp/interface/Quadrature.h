// Shape functions and quadrature on the joint element's reference square
// [0,1]^2, for facets of a trilinear bulk (4 node pairs) or a triquadratic
// one (mesh.degree = 2: 9 node pairs).
//
// Node order: the corners (0,0), (1,0), (0,1), (1,1) first (tensor order),
// then for 9 nodes the edge midpoints (1/2,0), (0,1/2), (1,1/2), (1/2,1)
// and the centre (1/2,1/2).
//
// gauss: Gauss-Legendre, 2x2 (4 nodes) or 3x3 (9 nodes), exact for the
//        products of shape functions in the joint stiffness. nodal:
//        Newton-Cotes at the node pairs (trapezoidal, or Simpson for 9
//        nodes), which decouples the node pairs and avoids the traction
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

/// Reference coordinates of the nodes (4 or 9), in node order.
inline std::vector<std::array<double, 2>> reference_nodes(int nodes)
{
  std::vector<std::array<double, 2>> r = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  if (nodes == 9)
    r.insert(r.end(), {{0.5, 0}, {0, 0.5}, {1, 0.5}, {0.5, 1}, {0.5, 0.5}});
  else if (nodes != 4)
    throw std::invalid_argument("joint elements have 4 or 9 node pairs");
  return r;
}

inline Quadrature make_quadrature(const std::string& kind, int nodes = 4)
{
  // 1D rule on [0, 1], then its tensor product.
  std::vector<double> x, w;
  if (kind == "gauss" && nodes == 4)
  {
    x = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
    w = {0.5, 0.5};
  }
  else if (kind == "gauss" && nodes == 9)
  {
    const double d = 0.5 * std::sqrt(0.6);
    x = {0.5 - d, 0.5, 0.5 + d};
    w = {5.0 / 18, 8.0 / 18, 5.0 / 18};
  }
  else if (kind == "nodal")
  {
    // At the nodes themselves, in node order.
    Quadrature q;
    const std::array<double, 3> w1 = nodes == 9 ? std::array<double, 3>{1.0 / 6, 4.0 / 6, 1.0 / 6}
                                                : std::array<double, 3>{0.5, 0.0, 0.5};
    const auto weight_1d = [&](double t) { return t == 0.0 ? w1[0] : t == 1.0 ? w1[2] : w1[1]; };
    for (const auto& p : reference_nodes(nodes))
    {
      q.points.push_back(p);
      q.weights.push_back(weight_1d(p[0]) * weight_1d(p[1]));
    }
    return q;
  }
  else
    throw std::invalid_argument("unknown interface quadrature '" + kind + "'");
  Quadrature q;
  for (std::size_t j = 0; j < x.size(); ++j)
    for (std::size_t i = 0; i < x.size(); ++i)
    {
      q.points.push_back({x[i], x[j]});
      q.weights.push_back(w[i] * w[j]);
    }
  return q;
}

/// Shape function values at (xi, eta), node order (4 or 9 nodes).
inline std::vector<double> shape(const std::array<double, 2>& p, int nodes = 4)
{
  const auto [x, y] = p;
  if (nodes == 4)
    return {(1 - x) * (1 - y), x * (1 - y), (1 - x) * y, x * y};
  // Quadratic Lagrange on {0, 1/2, 1}: at 0, at 1/2, at 1.
  const auto L = [](double t) -> std::array<double, 3> {
    return {2 * (t - 0.5) * (t - 1), -4 * t * (t - 1), 2 * t * (t - 0.5)};
  };
  const auto lx = L(x), ly = L(y);
  return {lx[0] * ly[0], lx[2] * ly[0], lx[0] * ly[2], lx[2] * ly[2], lx[1] * ly[0],
          lx[0] * ly[1], lx[2] * ly[1], lx[1] * ly[2], lx[1] * ly[1]};
}
} // namespace pushout::interface

#include "cracks.h"
#include "../scene/CrackPlanes.h"
#include "../scene/SceneError.h"
#include "symmetry.h"
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace pushout::mesh
{
namespace
{
constexpr double pi = std::numbers::pi;

double degrees(double a)
{
  return a * 180 / pi;
}
} // namespace

std::int64_t SliceSectors::around() const
{
  std::int64_t n = 0;
  for (std::int64_t e : elements)
    n += e;
  return n;
}

SliceSectors slice_sectors(const MeshInput& in)
{
  const Geometry& g = in.geometry;
  const std::array<double, 4> corners = corner_angles(g);
  std::vector<std::pair<double, bool>> b; // (angle, is a corner)
  for (double a : corners)
    b.push_back({a, true});
  // The cracks, and a boundary on each symmetry plane (mesh/symmetry.h), so
  // that a half or a quarter of this mesh is a model of its own.
  std::vector<double> rays = in.cracks.angles;
  const Symmetry symmetry = geometric_symmetry(in);
  if (symmetry.x_plane)
    rays.insert(rays.end(), {pi / 2, 3 * pi / 2});
  if (symmetry.y_plane)
    rays.insert(rays.end(), {0.0, pi});
  for (double a : rays)
    if (std::none_of(b.begin(), b.end(),
                     [&](const auto& boundary) { return angle_between(a, boundary.first) < 1e-9; }))
      b.push_back({a, false});
  std::sort(b.begin(), b.end());
  SliceSectors sec;
  for (std::size_t i = 0; i < b.size(); ++i)
  {
    const auto [a, corner] = b[i];
    sec.angles.push_back(a);
    if (corner && !g.circle) // exactly the corner, not a ray's round-off near it
      sec.outer.push_back(block_corners(
          g)[std::size_t(std::find(corners.begin(), corners.end(), a) - corners.begin())]);
    else
      sec.outer.push_back(boundary_point(g, a));
    const double next = i + 1 < b.size() ? b[i + 1].first : b[0].first + 2 * pi;
    const double share = (next - a) / (pi / 2); // of a quarter circumference
    sec.elements.push_back(
        std::max<std::int64_t>(std::llround(double(in.mesh.elements_per_quarter) * share), 1));
  }
  return sec;
}

void insert_cracks(MeshData& mesh, std::array<double, 2> centre, double R,
                   const std::vector<double>& angles)
{
  const double tol = 1e-7 * R; // nodes lie on the rays to round-off [mm]
  for (double angle : angles)
  {
    const double dx = std::cos(angle), dy = std::sin(angle);
    const double nx = -dy, ny = dx; // normal: from minus to plus
    const auto along = [&](std::int64_t i)
    { return (mesh.x[3 * i] - centre[0]) * dx + (mesh.x[3 * i + 1] - centre[1]) * dy; };
    const auto across = [&](std::int64_t i)
    { return (mesh.x[3 * i] - centre[0]) * nx + (mesh.x[3 * i + 1] - centre[1]) * ny; };

    // The concrete nodes on the plane, and the side of each concrete cell.
    const std::size_t n_nodes = mesh.num_nodes();
    std::vector<bool> in_concrete(n_nodes, false);
    for (std::size_t c = 0; c < mesh.num_cells(); ++c)
      if (mesh.material[c] == concrete)
        for (int i = 0; i < 8; ++i)
          in_concrete[mesh.cells[8 * c + i]] = true;
    std::vector<std::int64_t> copy(n_nodes, -1);
    double r_mouth = 0;
    for (std::size_t i = 0; i < n_nodes; ++i)
      if (in_concrete[i] && std::abs(across(i)) < tol && along(i) > R - tol)
      {
        copy[i] = std::int64_t(mesh.num_nodes());
        for (int d = 0; d < 3; ++d)
          mesh.x.push_back(mesh.x[3 * i + d]);
        r_mouth = std::max(r_mouth, along(i));
      }
    const auto on_plane = [&](const std::array<std::int64_t, 4>& f)
    { return std::all_of(f.begin(), f.end(), [&](std::int64_t n) { return copy[n] >= 0; }); };

    // Facets of the plane on the minus side (original nodes), and the plus
    // side cells that take the copies.
    std::map<std::array<std::int64_t, 4>, std::int64_t> minus_facet; // sorted nodes -> cell
    std::vector<std::size_t> plus_cells;
    for (std::size_t c = 0; c < mesh.num_cells(); ++c)
    {
      if (mesh.material[c] != concrete)
        continue;
      const std::int64_t* cell = mesh.cells.data() + 8 * c;
      if (std::none_of(cell, cell + 8, [&](std::int64_t n) { return copy[n] >= 0; }))
        continue;
      const std::array<double, 3> x = centroid(mesh, c);
      const bool plus = (x[0] - centre[0]) * nx + (x[1] - centre[1]) * ny > 0;
      if (plus)
      {
        plus_cells.push_back(c);
        continue;
      }
      for (const auto& f : hex_facets)
      {
        std::array<std::int64_t, 4> key = {cell[f[0]], cell[f[1]], cell[f[2]], cell[f[3]]};
        if (!on_plane(key))
          continue;
        std::sort(key.begin(), key.end());
        minus_facet[key] = std::int64_t(c);
      }
    }

    CrackPlane plane;
    plane.angle = angle;
    for (std::size_t c : plus_cells)
    {
      std::int64_t* cell = mesh.cells.data() + 8 * c;
      for (const auto& f : hex_facets)
      {
        const std::array<std::int64_t, 4> nodes = {cell[f[0]], cell[f[1]], cell[f[2]], cell[f[3]]};
        if (!on_plane(nodes))
          continue;
        std::array<std::int64_t, 4> key = nodes;
        std::sort(key.begin(), key.end());
        const auto partner = minus_facet.find(key);
        if (partner == minus_facet.end())
          throw std::runtime_error("crack plane facet without a partner on the other side");
        InterfacePair pair;
        pair.minus = nodes;
        for (int i = 0; i < 4; ++i)
          pair.plus[i] = copy[nodes[i]];
        pair.minus_cell = partner->second;
        pair.plus_cell = std::int64_t(c);
        orient(pair, mesh, centroid(mesh, std::size_t(partner->second)));
        plane.pairs.push_back(pair);
      }
    }
    // The plus side takes the copies: its cells, and the steel-concrete
    // pairs whose concrete facet is on it.
    std::vector<bool> is_plus(mesh.num_cells(), false);
    for (std::size_t c : plus_cells)
    {
      is_plus[c] = true;
      for (int i = 0; i < 8; ++i)
      {
        std::int64_t& n = mesh.cells[8 * c + i];
        if (copy[n] >= 0)
          n = copy[n];
      }
    }
    for (InterfacePair& p : mesh.pairs)
      if (is_plus[std::size_t(p.plus_cell)])
        for (std::int64_t& n : p.plus)
          if (copy[n] >= 0)
            n = copy[n];
    for (std::size_t i = 0; i < n_nodes; ++i)
      if (copy[i] >= 0 && along(std::int64_t(i)) > r_mouth - tol)
        plane.mouth.push_back({std::int64_t(i), copy[i]});
    if (plane.pairs.empty() || plane.mouth.empty())
      throw std::runtime_error("crack plane at " + std::to_string(degrees(angle)) +
                               " deg: no mesh facets lie on it");
    mesh.cracks.push_back(std::move(plane));
  }
}
} // namespace pushout::mesh

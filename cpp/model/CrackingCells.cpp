#include "CrackingCells.h"
#include "../mesh/MeshData.h"
#include <algorithm>
#include <cmath>
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/la/Vector.h>
#include <dolfinx/mesh/Topology.h>
#include <functional>
#include <sstream>

namespace pushout::model
{
namespace
{
/// Calls f(cell, distance [mm] of its centre from the tube `axis`) for each
/// owned concrete cell.
template <typename F>
void for_concrete_cells(const dolfinx::mesh::Mesh& mesh, const std::vector<std::int32_t>& material,
                        std::array<double, 2> axis, F f)
{
  const auto& original = mesh.topology().original_cell_index;
  const std::int32_t n_owned = mesh.topology().index_map(3)->size_local();
  const auto& x_dofmap = mesh.geometry().dofmap();
  const std::span<const double> x = mesh.geometry().x();
  for (std::int32_t c = 0; c < n_owned; ++c)
  {
    if (material[original[c]] != mesh::concrete)
      continue;
    double centre[2] = {0, 0};
    auto nodes = x_dofmap.links(c);
    for (std::int32_t node : nodes)
      for (int d = 0; d < 2; ++d)
        centre[d] += x[3 * node + d] / double(nodes.size());
    f(c, std::hypot(centre[0] - axis[0], centre[1] - axis[1]));
  }
}
} // namespace

std::vector<std::int32_t> cracking_cells(const dolfinx::mesh::Mesh& mesh,
                                         const std::vector<std::int32_t>& material, double radius,
                                         std::array<double, 2> axis)
{
  std::vector<std::int32_t> cells;
  for_concrete_cells(mesh, material, axis,
                     [&](std::int32_t c, double r)
                     {
                       if (may_crack(r, radius))
                         cells.push_back(c);
                     });
  return cells;
}

std::vector<std::size_t> region_edge(const dolfinx::mesh::Mesh& mesh,
                                     const std::vector<std::int32_t>& material,
                                     const std::vector<std::int32_t>& cells)
{
  // The vertices of the concrete that may not crack, marked on every
  // process that holds them (summed onto the owner, then sent back).
  const auto& topology = mesh.topology();
  const auto& cell_vertices = *topology.connectivity(3, 0);
  dolfinx::la::Vector<double> linear(topology.index_map(0), 1);
  std::span<double> mark = linear.mutable_array();
  const std::int32_t n_owned = topology.index_map(3)->size_local();
  for (std::int32_t c = 0; c < n_owned; ++c)
    if (material[topology.original_cell_index[c]] == pushout::mesh::concrete &&
        !std::binary_search(cells.begin(), cells.end(), c))
      for (std::int32_t v : cell_vertices.links(c))
        mark[v] = 1;
  linear.scatter_rev(std::plus<double>());
  linear.scatter_fwd();
  std::vector<std::size_t> edge;
  for (std::size_t k = 0; k < cells.size(); ++k)
  {
    const auto vertices = cell_vertices.links(cells[k]);
    if (std::any_of(vertices.begin(), vertices.end(), [&](std::int32_t v) { return mark[v] > 0; }))
      edge.push_back(k);
  }
  return edge;
}

std::string takes_no_concrete(double radius, double nearest)
{
  std::ostringstream why;
  why << "'cracking.radius' = " << radius << " mm takes in no concrete element: the "
      << "nearest element centre is " << nearest << " mm from the tube axis; raise it, or 0 "
      << "for all the concrete";
  return why.str();
}

double nearest_concrete_centre(const dolfinx::mesh::Mesh& mesh,
                               const std::vector<std::int32_t>& material,
                               std::array<double, 2> axis)
{
  double nearest = INFINITY;
  for_concrete_cells(mesh, material, axis,
                     [&](std::int32_t, double r) { nearest = std::min(nearest, r); });
  return nearest;
}
} // namespace pushout::model

// The cracking region's edge (model/CrackingCells.h, region_edge): the
// cracking cells that share a vertex with concrete that may not crack,
// against a count made on the generated mesh's own node numbers (before
// dolfinx renumbers and distributes it): the same cells, by their original
// index; none where every concrete cell may crack.
#include "mesh/MeshData.h"
#include "mesh/generate.h"
#include "model/CrackingCells.h"
#include "model/Model.h"
#include "scene/Scene.h"
#include <cmath>
#include <gtest/gtest.h>
#include <set>

namespace
{
using pushout::Scene;

/// The concrete cells of `data` (original indices) whose centre lies within
/// `radius` of `axis` and that share a node with a concrete cell whose
/// centre does not.
std::set<std::int64_t> edge_by_nodes(const pushout::mesh::MeshData& data, double radius,
                                     std::array<double, 2> axis)
{
  const auto inside = [&](std::size_t c)
  {
    const std::array<double, 3> m = pushout::mesh::centroid(data, c);
    return std::hypot(m[0] - axis[0], m[1] - axis[1]) <= radius;
  };
  std::set<std::int64_t> linear_nodes;
  for (std::size_t c = 0; c < data.num_cells(); ++c)
    if (data.material[c] == pushout::mesh::concrete && !inside(c))
      linear_nodes.insert(data.cells.begin() + 8 * c, data.cells.begin() + 8 * c + 8);
  std::set<std::int64_t> edge;
  for (std::size_t c = 0; c < data.num_cells(); ++c)
    if (data.material[c] == pushout::mesh::concrete && inside(c))
      for (int k = 0; k < 8; ++k)
        if (linear_nodes.contains(data.cells[8 * c + k]))
        {
          edge.insert(std::int64_t(c));
          break;
        }
  return edge;
}
} // namespace

TEST(CrackingCells, RegionEdgeIsTheCellsTouchingConcreteThatStaysLinear)
{
  const Scene scene =
      Scene::parse("[mesh]\nelements_per_quarter = 8\nelements_through_thickness = 2\n", {});
  bool reused = false;
  const pushout::mesh::MeshData data = pushout::mesh::generate(
      pushout::mesh::MeshInput::of(scene), pushout::mesh::default_cache_dir(), reused);
  const pushout::model::Model model(MPI_COMM_WORLD, data, pushout::model::ModelInput::of(scene));
  const dolfinx::mesh::Mesh& slice = *model.mesh();
  const std::array<double, 2> axis = scene.geometry().tube_center;
  for (double radius : {18.0, 25.0, 40.0})
  {
    const std::vector<std::int32_t> cells =
        pushout::model::cracking_cells(slice, data.material, radius, axis);
    std::set<std::int64_t> found;
    for (std::size_t k : pushout::model::region_edge(slice, data.material, cells))
      found.insert(slice.topology().original_cell_index[cells[k]]);
    const std::set<std::int64_t> expected = edge_by_nodes(data, radius, axis);
    EXPECT_FALSE(expected.empty()) << "radius " << radius;
    EXPECT_EQ(found, expected) << "radius " << radius;
  }
  const std::vector<std::int32_t> all =
      pushout::model::cracking_cells(slice, data.material, 0, axis);
  EXPECT_TRUE(pushout::model::region_edge(slice, data.material, all).empty());
}

// mesh.graded_lines = "radial" (meshes/slice.geo, scene/CrackPlanes.h
// radial_line_ends): the graded concrete's lines run along rays from the
// tube axis, the square's corners kept, so that a radial crack runs along a
// row of cells whose faces it is parallel to (docs/cracking.md, "Radial
// graded lines"). Checked on the lines' ends and on gmsh's mesh itself.
#include "mesh/generate.h"
#include "scene/CrackPlanes.h"
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <string>

using pushout::Geometry;
using pushout::Scene;
using pushout::mesh::MeshData;
using pushout::mesh::MeshInput;

namespace
{
constexpr double pi = std::numbers::pi;
constexpr double W = 100; // the default square's side [mm]
/// The slice's concrete area at 8 elements per quarter [mm^2]: the square
/// less the tube's polygon of 32 chords on R = 10 mm.
const double concrete_area_8 = W * W - 16 * 100.0 * std::sin(2 * pi / 32);

/// The default slice with the tube at (50, 25) (the corroded study's 15 mm
/// cover), `per_quarter` elements, one layer, the graded lines `lines`.
Scene off_centre(int per_quarter, const std::string& lines)
{
  return Scene::parse("[geometry]\ntube_center = [50.0, 25.0]\n[mesh]\nelements_per_quarter = " +
                          std::to_string(per_quarter) +
                          "\nelements_through_thickness = 1\ngraded_lines = \"" + lines + "\"\n",
                      {});
}

/// Distance of point p from the segment a-b [mm] (in the slice's plane).
double from_segment(const std::array<double, 2>& p, const std::array<double, 2>& a,
                    const std::array<double, 2>& b)
{
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const double t =
      std::clamp(((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
  return std::hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy);
}

/// The largest distance of a concrete node beyond the support circle from
/// the nearest of the radial lines (support circle node j to radial end j)
/// [mm].
double farthest_from_radial_lines(const MeshData& m, const Geometry& g, int per_quarter)
{
  const auto ends = pushout::radial_line_ends(g, per_quarter);
  const double Rs = g.support_inner_diameter / 2;
  const auto& c = g.tube_center;
  std::vector<std::array<double, 2>> starts;
  for (std::size_t j = 0; j < ends.size(); ++j)
  {
    const double a = pi / 4 + double(j) * pi / 2 / per_quarter;
    starts.push_back({c[0] + Rs * std::cos(a), c[1] + Rs * std::sin(a)});
  }
  std::vector<bool> concrete(m.num_nodes(), false);
  for (std::size_t cell = 0; cell < m.num_cells(); ++cell)
    if (m.material[cell] == pushout::mesh::concrete)
      for (int v = 0; v < 8; ++v)
        concrete[std::size_t(m.cells[8 * cell + std::size_t(v)])] = true;
  double farthest = 0;
  for (std::size_t i = 0; i < m.num_nodes(); ++i)
  {
    const std::array<double, 2> p = {m.x[3 * i], m.x[3 * i + 1]};
    if (!concrete[i] || std::hypot(p[0] - c[0], p[1] - c[1]) < Rs + 1e-6)
      continue;
    double nearest = INFINITY;
    for (std::size_t j = 0; j < ends.size(); ++j)
      nearest = std::min(nearest, from_segment(p, starts[j], ends[j]));
    farthest = std::max(farthest, nearest);
  }
  return farthest;
}

/// The concrete's area in the slice's plane [mm^2]: the bottom faces of its
/// hexahedra (vertices 0, 1, 3, 2 in DOLFINx's order), by the shoelace rule.
double concrete_area(const MeshData& m)
{
  double area = 0;
  for (std::size_t cell = 0; cell < m.num_cells(); ++cell)
  {
    if (m.material[cell] != pushout::mesh::concrete)
      continue;
    const std::array<int, 4> loop = {0, 1, 3, 2};
    double twice = 0;
    for (std::size_t k = 0; k < 4; ++k)
    {
      const std::size_t a = std::size_t(m.cells[8 * cell + std::size_t(loop[k])]);
      const std::size_t b = std::size_t(m.cells[8 * cell + std::size_t(loop[(k + 1) % 4])]);
      twice += m.x[3 * a] * m.x[3 * b + 1] - m.x[3 * b] * m.x[3 * a + 1];
    }
    area += std::abs(twice) / 2;
  }
  return area;
}
} // namespace

TEST(RadialLines, EndOnTheirRaysButTheCornersAreKept)
{
  const Geometry g = off_centre(16, "radial").geometry();
  const auto ends = pushout::radial_line_ends(g, 16);
  ASSERT_EQ(ends.size(), 64u);
  const std::array<std::array<double, 2>, 4> corners{{{W, W}, {0, W}, {0, 0}, {W, 0}}};
  int at_corners = 0;
  for (std::size_t j = 0; j < ends.size(); ++j)
  {
    const auto& e = ends[j];
    SCOPED_TRACE("line " + std::to_string(j));
    // On the boundary.
    EXPECT_NEAR(std::min({e[0], W - e[0], e[1], W - e[1]}), 0.0, 1e-12);
    if (std::find(corners.begin(), corners.end(), e) != corners.end())
    {
      ++at_corners;
      continue;
    }
    // On its ray: the angle from the tube axis is the line's.
    const double a = pi / 4 + double(j) * pi / 32;
    const double dx = e[0] - 50, dy = e[1] - 25;
    EXPECT_NEAR(dx * std::sin(a) - dy * std::cos(a), 0.0, 1e-9);
    EXPECT_GT(dx * std::cos(a) + dy * std::sin(a), 0.0);
  }
  EXPECT_EQ(at_corners, 4);
  // The +x+y corner (56.3 degrees from the tube axis) ends line 2 (56.25).
  EXPECT_EQ(ends[2], (std::array<double, 2>{W, W}));
  // A centred tube: the corners end the lines at 45 + 90 k degrees.
  const Geometry centred = Scene::parse("[mesh]\ngraded_lines = \"radial\"\n", {}).geometry();
  const auto centred_ends = pushout::radial_line_ends(centred, 8);
  for (std::size_t k = 0; k < 4; ++k)
    EXPECT_EQ(centred_ends[8 * k], corners[k]);
}

TEST(RadialLines, ASymmetricSliceHasSymmetricEnds)
{
  // The tube on x = 50 mm, its +y corners midway between two rays (56.25
  // and 123.75 degrees, 4 per quarter): line j's mirror image in x = 50 is
  // line 4 - j (mod 16), the corners' lines too.
  const double y = W - 50 * std::tan(56.25 * pi / 180);
  const Geometry g =
      Scene::parse("[geometry]\ntube_center = [50.0, " + std::to_string(y) + "]\n", {}).geometry();
  const auto ends = pushout::radial_line_ends(g, 4);
  for (std::size_t j = 0; j < 16; ++j)
  {
    SCOPED_TRACE("line " + std::to_string(j));
    const auto& image = ends[(20 - j) % 16];
    EXPECT_NEAR(ends[j][0], W - image[0], 1e-9);
    EXPECT_NEAR(ends[j][1], image[1], 1e-9);
  }
  EXPECT_EQ(std::count(ends.begin(), ends.end(), std::array<double, 2>{W, W}), 1);
  EXPECT_EQ(std::count(ends.begin(), ends.end(), std::array<double, 2>{0, W}), 1);
}

TEST(RadialLines, TheMeshFillsTheSliceAlongTheRays)
{
  for (const std::string lines : {"radial", "blocks"})
  {
    SCOPED_TRACE(lines);
    const Scene scene = off_centre(8, lines);
    bool reused = false;
    const MeshData m =
        pushout::mesh::generate(MeshInput::of(scene), pushout::mesh::default_cache_dir(), reused);
    // The whole slice but the tube: no corner cut off. (The mesh is the
    // half x >= 50 mm, the tube's place being symmetric about that plane:
    // m.copies 2.)
    EXPECT_NEAR(m.copies * concrete_area(m), concrete_area_8, 1e-9 * W * W);
    const double off = farthest_from_radial_lines(m, scene.geometry(), 8);
    if (lines == "radial")
      // gmsh's transfinite block places line j's nodes at the same fractions
      // of the segment from its start to its end, as its two corner lines are
      // graded alike: on the rays up to gmsh's arithmetic of those fractions
      // (4e-8 mm measured), far below a cell (about 1 mm).
      EXPECT_LT(off, 1e-6 * W);
    else
      EXPECT_GT(off, 1.0); // (the check can fail: the blocks' lines are not rays)
  }
  // A centred tube: cut to a quarter model (mesh/symmetry.h), which needs
  // the mesh's mirror images, and still the whole slice four times.
  bool reused = false;
  const MeshData quarter = pushout::mesh::generate(
      MeshInput::of(
          Scene::parse("[mesh]\nelements_per_quarter = 8\nelements_through_thickness = 1\n"
                       "graded_lines = \"radial\"\n",
                       {})),
      pushout::mesh::default_cache_dir(), reused);
  EXPECT_EQ(quarter.copies, 4);
  EXPECT_NEAR(4 * concrete_area(quarter), concrete_area_8, 1e-9 * W * W);
}

TEST(RadialLines, AKeyOfTheScene)
{
  EXPECT_TRUE(Scene::parse("[mesh]\ngraded_lines = \"radial\"\n", {}).mesh().radial_lines);
  EXPECT_FALSE(Scene::parse("", {}).mesh().radial_lines); // blocks, as before
}

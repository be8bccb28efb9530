// The graded block of meshes/slice.geo and slice_cracked.geo (mesh/size.h,
// slice_divisions): along every line from the support circle to the
// boundary the elements start at most graded_growth_max times the interface
// size h (a gentle step from the ring's elements) and grow by
// graded_growth_max at most, whatever the tube's place and
// mesh.graded_refinement, from scenes alone
// (no meshing; the e2e test test_resource_estimate_within_factor_2 compares
// the counts with gmsh's meshes).
#include "mesh/size.h"
#include <algorithm>
#include <array>
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <sstream>
#include <string>

using pushout::Scene;
using pushout::mesh::graded_growth_max;
using pushout::mesh::MeshInput;
using pushout::mesh::slice_divisions;
using pushout::mesh::SliceDivisions;

namespace
{
constexpr double pi = std::numbers::pi;

/// The default 100 mm square, R = 10 mm, support circle Rs = 15 mm, the
/// tube at `centre` [mm]; `extra`: more TOML.
MeshInput scene(const std::string& centre, int per_quarter, const std::string& extra = "")
{
  return MeshInput::of(Scene::parse(
      "[geometry]\ntube_center = " + centre +
      "\n[mesh]\nelements_per_quarter = " + std::to_string(per_quarter) + "\n" + extra));
}

/// slice.geo's graded lines: from the support circle at 45 + 90 k degrees
/// to the square's corner k [mm].
std::array<double, 4> corner_lines(double cx, double cy)
{
  const std::array<std::array<double, 2>, 4> corners{{{100, 100}, {0, 100}, {0, 0}, {100, 0}}};
  std::array<double, 4> L{};
  for (int k = 0; k < 4; ++k)
  {
    const double a = pi / 4 + k * pi / 2;
    L[k] = std::hypot(corners[k][0] - cx - 15 * std::cos(a), corners[k][1] - cy - 15 * std::sin(a));
  }
  return L;
}

/// The first element of n that fill L with growth q [mm].
double first_element(double L, std::int64_t n, double q)
{
  return q > 1 ? L * (q - 1) / (std::pow(q, double(n)) - 1) : L / double(n);
}
} // namespace

TEST(SliceDivisions, GradedElementsStartAndGrowGently)
{
  // Centred, the corroded demo's 15 mm cover, 6 mm and 1 mm of concrete
  // beyond the support circle (a tube 16 mm from a side: before, one
  // element across the other 70 mm of concrete), and a corner.
  for (const auto& [cx, cy] :
       std::array<std::array<double, 2>, 5>{{{50, 50}, {50, 25}, {50, 21}, {16, 50}, {20, 22}}})
    for (int nq : {4, 5, 6, 8, 12, 16, 24, 32})
      for (const std::string refinement : {"near_tube", "whole"})
      {
        std::ostringstream centre;
        centre << "[" << cx << ", " << cy << "]";
        const SliceDivisions d = slice_divisions(
            scene(centre.str(), nq, "graded_refinement = \"" + refinement + "\"\n"));
        const double h = pi / 2 * 10.0 / nq; // interface element [mm]
        std::ostringstream where;
        where << "centre " << centre.str() << ", " << nq << " per quarter, " << refinement << ": "
              << d.graded << " graded";
        SCOPED_TRACE(where.str());
        ASSERT_GE(d.graded, 1);
        EXPECT_GE(d.growth, 1.0);
        EXPECT_LE(d.growth, graded_growth_max + 1e-9); // 1e-9: the bisection
        for (double L : corner_lines(cx, cy))
          EXPECT_LE(first_element(L, d.graded, d.growth), graded_growth_max * h * (1 + 1e-6));
      }
}

TEST(SliceDivisions, VerifiedMeshesKeepTheirGrading)
{
  // The paper's centred mesh, where one growth for every line already starts
  // gently: 9 graded elements from h to 10 h (growth 10^(1/8)) on all four.
  const SliceDivisions centred = slice_divisions(scene("[50.0, 50.0]", 16));
  EXPECT_EQ(centred.graded, 9);
  EXPECT_NEAR(centred.growth, std::pow(10.0, 1.0 / 8), 1e-12);
  // A circle: all its lines have the shortest way's length.
  const SliceDivisions circle = slice_divisions(MeshInput::of(
      Scene::parse("[geometry]\nouter_shape = \"circle\"\n[mesh]\nelements_per_quarter = 16\n")));
  EXPECT_EQ(circle.graded, 9);
}

TEST(SliceDivisions, OffCentreTubeStartsItsFarLinesGently)
{
  // The corroded demo (15 mm cover): 5 elements growing by 1.50 fill its
  // 10 mm way out, and would start its lines to the far corners, 7.5 times
  // as long, at 5.8 h; 8 growing by at most 1.6 start them at 1.6 h.
  const SliceDivisions d = slice_divisions(scene("[50.0, 25.0]", 16));
  EXPECT_EQ(d.graded, 8);
  EXPECT_GT(d.growth, 1.45);
  EXPECT_LE(d.growth, graded_growth_max);
  // The paper's centred mesh at 24 per quarter: its corner lines started
  // just above 1.6 h (1.62 h); the same 13 elements, their growth 1.21 as
  // before to within 0.01.
  const SliceDivisions centred24 = slice_divisions(scene("[50.0, 50.0]", 24));
  EXPECT_EQ(centred24.graded, 13);
  EXPECT_NEAR(centred24.growth, std::pow(10.0, 1.0 / 12), 0.01);
}

TEST(SliceDivisions, CoarserAskedCoarserGiven)
{
  // A larger outer_size_ratio never gives more elements (before, a ratio
  // whose size was beyond the way out gave the uniform mesh of h, the
  // finest: 384 cells at 18 against 192 at 17, 8 per quarter).
  for (const char* centre : {"[50.0, 50.0]", "[50.0, 25.0]", "[16.0, 50.0]"})
    for (int nq : {8, 16})
      for (const char* refinement : {"near_tube", "whole"})
      {
        std::int64_t last = -1;
        for (double ratio : {1.0, 1.5, 2.0, 5.0, 10.0, 17.0, 18.0, 20.0, 50.0, 1000.0})
        {
          const std::int64_t n =
              slice_divisions(scene(centre, nq,
                                    "outer_size_ratio = " + std::to_string(ratio) +
                                        "\ngraded_refinement = \"" + refinement + "\"\n"))
                  .graded;
          if (last >= 0)
          {
            EXPECT_LE(n, last) << centre << ", " << nq << " per quarter, ratio " << ratio << ", "
                               << refinement;
          }
          last = n;
        }
      }
}

TEST(SliceDivisions, WholeRefinementKeepsTheGradedCellsShape)
{
  // The corroded demo's 15 mm cover, whose far corners' lines take the
  // stretched count on every mesh. near_tube: 7 to 10 graded elements from
  // 12 to 48 per quarter, so the far lines' last element stays some 26 mm
  // long; whole: every line's last element outer_size_ratio (10) times its
  // first, which starts the longest line at 1.6 h or just below, so that
  // both halve with h.
  const std::array<double, 4> lines = corner_lines(50, 25);
  const double longest = *std::max_element(lines.begin(), lines.end());
  const auto divisions = [](int nq, const char* refinement)
  {
    return slice_divisions(
        scene("[50.0, 25.0]", nq, std::string("graded_refinement = \"") + refinement + "\"\n"));
  };
  const auto last_element = [&](const SliceDivisions& d)
  { return first_element(longest, d.graded, d.growth) * std::pow(d.growth, double(d.graded - 1)); };
  for (int nq : {12, 16, 24})
  {
    SCOPED_TRACE(std::to_string(nq) + " per quarter");
    const double h = pi / 2 * 10.0 / nq; // interface element [mm]
    const SliceDivisions coarse = divisions(nq, "whole"), fine = divisions(2 * nq, "whole");
    for (const SliceDivisions& d : {coarse, fine})
    {
      EXPECT_LE(d.growth, graded_growth_max);
      EXPECT_NEAR(std::pow(d.growth, double(d.graded - 1)), 10.0, 1e-9); // last / first
    }
    // The fewest elements that start the longest line at 1.6 h at most: so
    // it starts between 1.6 h / q and 1.6 h.
    const double start = first_element(longest, coarse.graded, coarse.growth);
    EXPECT_LE(start, graded_growth_max * h * (1 + 1e-9));
    EXPECT_GT(start, graded_growth_max * h / coarse.growth);
    // So the last element on twice the count per quarter is half the
    // coarse one's, within those bounds on both meshes' starts.
    const double halved = last_element(fine) / last_element(coarse);
    EXPECT_GE(halved, 0.5 / fine.growth);
    EXPECT_LE(halved, 0.5 * coarse.growth);
    // near_tube keeps it (within 20 %), with fewer elements.
    const SliceDivisions near_coarse = divisions(nq, "near_tube");
    const SliceDivisions near_fine = divisions(2 * nq, "near_tube");
    EXPECT_GT(last_element(near_fine) / last_element(near_coarse), 0.8);
    EXPECT_GE(coarse.graded, near_coarse.graded);
  }
}

TEST(SliceDivisions, CrackPlanesSectorLinesStartGently)
{
  // slice_cracked.geo: a radial line on each sector boundary (towards the
  // four corners, the crack plane's towards the nearest face of the corroded
  // demo, and the symmetry plane's opposite it), the corners' the longest:
  // from the support circle (15 mm) to the corner.
  const SliceDivisions d = slice_divisions(
      scene("[50.0, 25.0]", 16,
            "[[crack]]\nangle = \"nearest_face\"\nlaw = \"exponential_softening\"\n"));
  const double h = pi / 2 * 10.0 / 16;
  EXPECT_GE(d.growth, 1.0);
  EXPECT_LE(d.growth, graded_growth_max + 1e-9);
  for (const auto& [x, y] :
       std::array<std::array<double, 2>, 4>{{{100, 100}, {0, 100}, {0, 0}, {100, 0}}})
    EXPECT_LE(first_element(std::hypot(x - 50, y - 25) - 15, d.graded, d.growth),
              graded_growth_max * h * (1 + 1e-6));
}

TEST(SliceDivisions, RoundedCountsKeepTheGrowthBound)
{
  // Towards ratio h the count is rounded: down, it made the growth 1.8 (a
  // circle 50 mm wide, 5 per quarter, ratio 1.8) and 1.64 (a 150 mm square,
  // 8 per quarter, ratio 11.95); one element more where it did.
  const SliceDivisions circle = slice_divisions(
      MeshInput::of(Scene::parse("[geometry]\nouter_shape = \"circle\"\nwidth = 50.0\n"
                                 "[mesh]\nelements_per_quarter = 5\nouter_size_ratio = 1.8\n")));
  EXPECT_LE(circle.growth, graded_growth_max);
  const SliceDivisions square = slice_divisions(
      MeshInput::of(Scene::parse("[geometry]\nwidth = 150.0\ntube_center = [75.0, 75.0]\n"
                                 "[mesh]\nelements_per_quarter = 8\nouter_size_ratio = 11.95\n")));
  EXPECT_LE(square.growth, graded_growth_max);
}

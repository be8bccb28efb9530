// Crack-plane directions and the sectors of meshes/slice_cracked.geo
// (scene/CrackPlanes.h, mesh/cracks.h), from scenes alone (no meshing).
#include "mesh/cracks.h"
#include "scene/SceneError.h"
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

using pushout::Scene;
using pushout::SceneError;
using pushout::mesh::MeshInput;

namespace
{
constexpr double pi = std::numbers::pi;
double deg(double a)
{
  return a * 180 / pi;
}
/// The crack directions the scene resolved as it was parsed (scene/CrackPlanes.h).
pushout::CrackDirections crack_directions(const Scene& s)
{
  return s.crack_directions();
}
pushout::mesh::SliceSectors slice_sectors(const Scene& s)
{
  return pushout::mesh::slice_sectors(MeshInput::of(s));
}
} // namespace

TEST(CrackDirections, NearestFaceIsTheCoverSide)
{
  const std::string crack = "[[crack]]\nangle = \"nearest_face\"\n";
  // Cover 15 mm to y = 0, to x = 100 mm, to y = 100 mm.
  EXPECT_NEAR(deg(crack_directions(Scene::parse("[geometry]\ntube_center = [50.0, 25.0]\n" + crack))
                      .angles[0]),
              270, 1e-12);
  EXPECT_NEAR(deg(crack_directions(Scene::parse("[geometry]\ntube_center = [75.0, 50.0]\n" + crack))
                      .angles[0]),
              0, 1e-12);
  EXPECT_NEAR(deg(crack_directions(Scene::parse("[geometry]\ntube_center = [50.0, 75.0]\n" + crack))
                      .angles[0]),
              90, 1e-12);
  // A centred tube: all faces alike, -y first.
  EXPECT_NEAR(deg(crack_directions(Scene::parse(crack)).angles[0]), 270, 1e-12);
  EXPECT_THROW(crack_directions(Scene::parse("[geometry]\nouter_shape = \"circle\"\n" + crack)),
               SceneError);
}

TEST(CrackDirections, NearACornerTheCrackMovesOntoIt)
{
  // 16 elements per quarter: an element spans 5.625 deg; the corner of a
  // centred tube is at 45 deg.
  const auto d =
      crack_directions(Scene::parse("[[crack]]\nangle = 47.0\n[[crack]]\nangle = -30.0\n"));
  EXPECT_TRUE(d.snapped[0]);
  EXPECT_NEAR(deg(d.angles[0]), 45, 1e-12);
  EXPECT_NEAR(deg(d.asked[0]), 47, 1e-12);
  EXPECT_FALSE(d.snapped[1]);
  EXPECT_NEAR(deg(d.angles[1]), 330, 1e-12); // within one turn
  EXPECT_THROW(crack_directions(Scene::parse("[[crack]]\nangle = 10.0\n[[crack]]\nangle = 13.0\n")),
               SceneError);
}

TEST(SliceSectors, CornersAndCracksCutTheCircumference)
{
  // Off-centre tube: the corners point at the square's corners, every ray
  // between two of them meets the side between their outer points.
  const Scene s = Scene::parse("[geometry]\ntube_center = [50.0, 25.0]\n"
                               "[[crack]]\nangle = 270.0\n[[crack]]\nangle = 90.0\n");
  const auto sec = slice_sectors(s);
  ASSERT_EQ(sec.angles.size(), 6u);
  for (std::size_t i = 1; i < sec.angles.size(); ++i)
    EXPECT_LT(sec.angles[i - 1], sec.angles[i]);
  EXPECT_NEAR(deg(sec.angles[0]), deg(std::atan2(75.0, 50.0)), 1e-12); // towards (100, 100)
  // The crack at 270 deg meets y = 0 below the tube centre; at 90 deg, y = 100.
  int rays = 0;
  for (std::size_t i = 0; i < sec.angles.size(); ++i)
    for (const auto& [angle, y] : {std::pair{270.0, 0.0}, std::pair{90.0, 100.0}})
      if (std::abs(deg(sec.angles[i]) - angle) < 1e-9)
      {
        EXPECT_NEAR(sec.outer[i][0], 50.0, 1e-12);
        EXPECT_NEAR(sec.outer[i][1], y, 1e-12);
        ++rays;
      }
  EXPECT_EQ(rays, 2);
  // Elements in proportion to the sectors' angles, about 4 x 16 around.
  EXPECT_NEAR(double(sec.around()), 64.0, 3.0);
  for (std::int64_t n : sec.elements)
    EXPECT_GE(n, 1);
}

// Reading the concrete's cracks at the slice's outer faces
// (model/SurfaceCracks.h), on hand-made columns of a 100 mm square slice
// with 2 mm cells and the tube (R = 10 mm) 15 mm from the face y = 0.
#include "model/SurfaceCracks.h"
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

using namespace pushout::model;

namespace
{
constexpr std::array<double, 2> axis = {50, 25}; // [mm]
constexpr double R = 10, cell = 2, resolution = 0.005;

/// The bottom face's columns (y = 1), gauge `gauge(x)`.
template <typename Gauge> std::vector<FaceColumn> bottom_face(Gauge gauge)
{
  std::vector<FaceColumn> faces;
  for (double x = 1; x < 100; x += cell)
    faces.push_back({std::atan2(1 - axis[1], x - axis[0]), x, 1, gauge(x), {x, 0}});
  return faces;
}

/// The concrete's columns, cracked (0.02 mm) on the line x = 49..51 from
/// the face up to y = `reach`.
std::vector<CrackColumn> concrete(double reach)
{
  std::vector<CrackColumn> columns;
  for (double x = 1; x < 100; x += cell)
    for (double y = 1; y < 100; y += cell)
      if (std::hypot(x - axis[0], y - axis[1]) > R)
        columns.push_back({x, y, (std::abs(x - 50) <= 1 && y <= reach) ? 0.02 : 0.0, cell});
  return columns;
}
} // namespace

TEST(SurfaceCracks, ACrackOverTwoBandsReadsWhole)
{
  // Two bands of 0.03 mm at x = 49 and 51; a third column below the
  // gauge's resolution at x = 81 is no crack.
  const auto faces =
      bottom_face([](double x) { return std::abs(x - 50) <= 1 ? 0.03 : (x == 81 ? 0.004 : 0.0); });
  const std::vector<SurfaceCrack> cracks =
      surface_cracks(faces, concrete(100), axis, R, resolution);
  ASSERT_EQ(cracks.size(), 1u);
  EXPECT_NEAR(cracks[0].width_mm, 0.06, 1e-15);
  // Its widest column is at x = 49 or 51, y = 1: about 270 degrees.
  EXPECT_NEAR(cracks[0].angle_deg, 270, std::atan(1.0 / 24) * 180 / std::numbers::pi + 1e-12);
  // Cracked from the face to the tube: at x = 49 from y = 0 to the tube's
  // surface at y = 25 - sqrt(R^2 - 1), measured from the mouth (49, 0) to
  // the tube's surface nearest the last column's centre (49, 15), 5e-4 mm
  // off that line.
  EXPECT_NEAR(cracks[0].length_mm, 25 - std::sqrt(R * R - 1), 1e-3);
}

TEST(SurfaceCracks, ALargerVisibleWidthReadsTheSameWidths)
{
  // The gauge resolves a tenth of the visible width, at most 5 um: a crack
  // that counts only from 1 mm still reads a crack smeared over four bands
  // of 0.02 mm (each below a tenth of 1 mm) whole.
  EXPECT_DOUBLE_EQ(gauge_resolution(0.05), 0.005);
  EXPECT_DOUBLE_EQ(gauge_resolution(0.02), 0.002);
  EXPECT_DOUBLE_EQ(gauge_resolution(1.0), 0.005);
  const auto faces = bottom_face([](double x) { return std::abs(x - 50) <= 3 ? 0.02 : 0.0; });
  const std::vector<SurfaceCrack> cracks =
      surface_cracks(faces, concrete(100), axis, R, gauge_resolution(1.0));
  ASSERT_EQ(cracks.size(), 1u);
  EXPECT_NEAR(cracks[0].width_mm, 0.08, 1e-15);
}

TEST(SurfaceCracks, LengthStopsWhereTheConcreteIsWhole)
{
  const auto faces = bottom_face([](double x) { return x == 49 ? 0.05 : 0.0; });
  for (double reach : {3.0, 7.0, 11.0})
  {
    const std::vector<SurfaceCrack> cracks =
        surface_cracks(faces, concrete(reach), axis, R, resolution);
    ASSERT_EQ(cracks.size(), 1u);
    // The last cracked column's centre is at y = reach, its cell ends at
    // reach + 1: the tip is within that cell.
    EXPECT_GE(cracks[0].length_mm, reach - 1 - 1e-12);
    EXPECT_LE(cracks[0].length_mm, reach + 1 + 1e-12);
  }
}

TEST(SurfaceCracks, LengthIsStraightFromTheMouthToTheTube)
{
  // A crack that steps sideways on its way in: cracked columns at x = 61
  // from the face to y = 7, then at x = 59 on to the tube (whose surface
  // the column at (59, 21) is within a column of). Its path through the
  // column centres is longer than the crack: the length is the straight
  // line from its mouth (61, 0) to the tube's surface nearest the last
  // column's centre.
  std::vector<CrackColumn> columns;
  for (double x = 1; x < 100; x += cell)
    for (double y = 1; y < 100; y += cell)
      if (std::hypot(x - axis[0], y - axis[1]) > R)
        columns.push_back(
            {x, y, ((x == 61 && y <= 7) || (x == 59 && y >= 7 && y <= 25)) ? 0.02 : 0.0, cell});
  const auto faces = bottom_face([](double x) { return x == 61 ? 0.05 : 0.0; });
  const std::vector<SurfaceCrack> cracks = surface_cracks(faces, columns, axis, R, resolution);
  ASSERT_EQ(cracks.size(), 1u);
  // The last column on the way in is the one nearest the axis at x = 59:
  // (59, 19) or (59, 21), both within a column of the tube.
  double nearest = INFINITY;
  for (double y : {19.0, 21.0})
  {
    const double r = std::hypot(59 - axis[0], y - axis[1]);
    const double tip_x = axis[0] + R * (59 - axis[0]) / r, tip_y = axis[1] + R * (y - axis[1]) / r;
    nearest = std::min(nearest, std::abs(cracks[0].length_mm - std::hypot(61 - tip_x, tip_y)));
  }
  EXPECT_LT(nearest, 1e-12);
  // Shorter than the path through the centres: 1 + 6 + 2 * sqrt(2) + ... mm.
  EXPECT_LT(cracks[0].length_mm, 1 + 6 + std::hypot(2, 2) + 10);
}

TEST(SurfaceCracks, ACrackOnASymmetryPlaneIsMeasuredAlongIt)
{
  // A half model about x = 50 (x >= 50) with 2 mm cells: the crack on the
  // plane at 270 degrees opens the band beside it (x = 51), whose columns
  // run from the face (mouth (51, 0)) to the tube. Measured along the
  // plane it is the cover, 25 - R = 15 mm, whatever the band's offset.
  std::vector<CrackColumn> columns;
  for (double x = 51; x < 100; x += cell)
    for (double y = 1; y < 100; y += cell)
      if (std::hypot(x - axis[0], y - axis[1]) > R)
        columns.push_back({x, y, x == 51 && y < 25 ? 0.02 : 0.0, cell});
  std::vector<FaceColumn> faces;
  for (double x = 51; x < 100; x += cell)
    faces.push_back({std::atan2(1 - axis[1], x - axis[0]), x, 1, x == 51 ? 0.03 : 0.0, {x, 0}});
  for (double y = 1; y < 100; y += cell) // the face x = 100, so the cut is the widest gap
    faces.push_back({std::atan2(y - axis[1], 99 - axis[0]), 99, y, 0.0, {100, y}});
  std::vector<SurfaceCrack> cracks = surface_cracks(faces, columns, axis, R, resolution, 2);
  ASSERT_EQ(cracks.size(), 1u);
  EXPECT_DOUBLE_EQ(cracks[0].angle_deg, 270);
  EXPECT_NEAR(cracks[0].width_mm, 0.06, 1e-15);
  EXPECT_NEAR(cracks[0].length_mm, 25 - R, 1e-12);
  // Stopped short of the tube (cracked to y = 9: its last centre 16 mm
  // from the axis along the plane), it measures from the face to there.
  for (CrackColumn& c : columns)
    c.opening = c.x == 51 && c.y <= 9 ? 0.02 : 0.0;
  cracks = surface_cracks(faces, columns, axis, R, resolution, 2);
  ASSERT_EQ(cracks.size(), 1u);
  EXPECT_NEAR(cracks[0].length_mm, 9, 1e-12);
}

TEST(SurfaceCracks, SeparateCracksWidestFirst)
{
  const auto faces = bottom_face(
      [](double x) { return x == 21 ? 0.01 : (x == 49 ? 0.08 : (x == 79 ? 0.02 : 0.0)); });
  const std::vector<SurfaceCrack> cracks =
      surface_cracks(faces, concrete(100), axis, R, resolution);
  ASSERT_EQ(cracks.size(), 3u);
  EXPECT_EQ(cracks[0].width_mm, 0.08);
  EXPECT_EQ(cracks[1].width_mm, 0.02);
  EXPECT_EQ(cracks[2].width_mm, 0.01);
  // Only the one at x = 49 meets cracked concrete inside.
  EXPECT_GT(cracks[0].length_mm, 10);
  EXPECT_LT(cracks[1].length_mm, 1e-12);
}

TEST(SurfaceCracks, ARunAcrossTheAnglesWrapIsOneCrack)
{
  // Columns all round a circle of radius 40 about the axis, 5 degrees
  // apart; a crack on the three columns at -5, 0 and +5 degrees.
  std::vector<FaceColumn> faces;
  for (int k = 0; k < 72; ++k)
  {
    const double a = (k * 5 - 180) * std::numbers::pi / 180; // [-pi, pi)
    const bool cracked = k == 35 || k == 36 || k == 37;
    faces.push_back({a,
                     axis[0] + 40 * std::cos(a),
                     axis[1] + 40 * std::sin(a),
                     cracked ? (k == 36 ? 0.05 : 0.01) : 0.0,
                     {axis[0] + 41 * std::cos(a), axis[1] + 41 * std::sin(a)}});
  }
  std::vector<SurfaceCrack> cracks = surface_cracks(faces, {}, axis, R, resolution);
  ASSERT_EQ(cracks.size(), 1u);
  EXPECT_NEAR(cracks[0].width_mm, 0.07, 1e-15);
  EXPECT_NEAR(cracks[0].angle_deg, 0, 1e-9);
  // The same crack where the angles wrap (at +-180 degrees).
  for (FaceColumn& f : faces)
  {
    f.angle = f.angle + std::numbers::pi;
    f.angle -= f.angle >= std::numbers::pi ? 2 * std::numbers::pi : 0;
    f.x = 2 * axis[0] - f.x;
    f.y = 2 * axis[1] - f.y;
    f.mouth = {2 * axis[0] - f.mouth[0], 2 * axis[1] - f.mouth[1]};
  }
  cracks = surface_cracks(faces, {}, axis, R, resolution);
  ASSERT_EQ(cracks.size(), 1u);
  EXPECT_NEAR(cracks[0].width_mm, 0.07, 1e-15);
  EXPECT_NEAR(cracks[0].angle_deg, 180, 1e-9);
}

TEST(SurfaceCracks, ACutModelReadsItsPlanesCracksWhole)
{
  // A half model about x = 50 (x >= 50): columns 40 mm from the axis every
  // 5 degrees from -87.5 to 87.5. A crack on the plane at 90 degrees (two
  // columns of 0.02 mm), one on the plane at 270 (a column of 0.03 mm) and
  // one inside at 0 (0.05 mm).
  std::vector<FaceColumn> faces;
  for (double deg = -87.5; deg < 90; deg += 5)
  {
    const double a = deg * std::numbers::pi / 180;
    const double gauge = deg > 80 ? 0.02 : deg < -85 ? 0.03 : std::abs(deg - 2.5) < 1 ? 0.05 : 0;
    faces.push_back({a,
                     axis[0] + 40 * std::cos(a),
                     axis[1] + 40 * std::sin(a),
                     gauge,
                     {axis[0] + 41 * std::cos(a), axis[1] + 41 * std::sin(a)}});
  }
  // Cut: the planes' cracks read whole (their mirror images), along the
  // planes; the one inside as it is.
  const std::vector<SurfaceCrack> cut = surface_cracks(faces, {}, axis, R, resolution, 2);
  ASSERT_EQ(cut.size(), 3u);
  EXPECT_NEAR(cut[0].width_mm, 0.08, 1e-15);
  EXPECT_DOUBLE_EQ(cut[0].angle_deg, 90);
  EXPECT_NEAR(cut[1].width_mm, 0.06, 1e-15);
  EXPECT_DOUBLE_EQ(cut[1].angle_deg, 270);
  EXPECT_NEAR(cut[2].width_mm, 0.05, 1e-15);
  EXPECT_NEAR(cut[2].angle_deg, 2.5, 1e-9);
  // Read as a closed perimeter the two planes' cracks would be one, across
  // the 185 degrees that the cut takes away.
  const std::vector<SurfaceCrack> closed = surface_cracks(faces, {}, axis, R, resolution);
  ASSERT_EQ(closed.size(), 2u);
  EXPECT_NEAR(closed[0].width_mm, 0.07, 1e-15);
}

TEST(SurfaceCracks, NoneOrAllRound)
{
  EXPECT_TRUE(
      surface_cracks(bottom_face([](double) { return 0.001; }), {}, axis, R, resolution).empty());
  EXPECT_TRUE(surface_cracks({}, {}, axis, R, resolution).empty());
  const std::vector<SurfaceCrack> all =
      surface_cracks(bottom_face([](double) { return 0.01; }), {}, axis, R, resolution);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_NEAR(all[0].width_mm, 0.01 * 50, 1e-12);
}

TEST(SurfaceCracks, ACutModelCrackedFromPlaneToPlaneIsCrackedAllRound)
{
  // A ring cracked evenly all round (0.01 mm a column, a column every 5
  // degrees on a circle 40 mm from the axis), as a quarter model (0 to 90
  // degrees) and a half one (-90 to 90): one crack all round, the whole
  // slice's 72 columns summed, as the whole model reads it (it was read as
  // a crack on each plane, half as wide, and mirrored into two).
  const auto ring = [](double from_deg, double to_deg)
  {
    std::vector<FaceColumn> faces;
    for (double deg = from_deg + 2.5; deg < to_deg; deg += 5)
    {
      const double a = deg * std::numbers::pi / 180;
      faces.push_back({a,
                       axis[0] + 40 * std::cos(a),
                       axis[1] + 40 * std::sin(a),
                       0.01,
                       {axis[0] + 41 * std::cos(a), axis[1] + 41 * std::sin(a)}});
    }
    return faces;
  };
  for (const auto& [faces, copies] :
       {std::pair{ring(0, 90), 4}, std::pair{ring(-90, 90), 2}, std::pair{ring(-180, 180), 1}})
  {
    const std::vector<SurfaceCrack> cracks = surface_cracks(faces, {}, axis, R, resolution, copies);
    ASSERT_EQ(cracks.size(), 1u) << copies;
    EXPECT_NEAR(cracks[0].width_mm, 72 * 0.01, 1e-12) << copies;
    EXPECT_TRUE(cracks[0].all_round) << copies;
  }
  // A run that reaches one plane only is still half of a crack there.
  std::vector<FaceColumn> quarter = ring(0, 90);
  quarter.back().gauge = 0;
  const std::vector<SurfaceCrack> cracks = surface_cracks(quarter, {}, axis, R, resolution, 4);
  ASSERT_EQ(cracks.size(), 1u);
  EXPECT_NEAR(cracks[0].width_mm, 2 * 17 * 0.01, 1e-12);
  EXPECT_FALSE(cracks[0].all_round);
  EXPECT_DOUBLE_EQ(cracks[0].angle_deg, 0);
}

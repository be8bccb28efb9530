// The crack band's width of a hexahedral cell along a normal
// (model/CellWidth.h): the projected extent and the width of the thinnest
// row of cells, against their closed forms on box, sheared and rotated cells.
#include "model/CellWidth.h"
#include <cmath>
#include <gtest/gtest.h>

using namespace pushout;
using model::CellVertices;

namespace
{
/// The parallelepiped origin + a e0 + b e1 + c e2 (a, b, c in {0, 1}), in
/// DOLFINx's vertex order.
CellVertices parallelepiped(const bulk::Vec3& origin, const bulk::Vec3& e0, const bulk::Vec3& e1,
                            const bulk::Vec3& e2)
{
  CellVertices x;
  for (int v = 0; v < 8; ++v)
    for (int a = 0; a < 3; ++a)
      x[std::size_t(v)][std::size_t(a)] = origin[std::size_t(a)] + (v & 1) * e0[std::size_t(a)] +
                                          ((v >> 1) & 1) * e1[std::size_t(a)] +
                                          ((v >> 2) & 1) * e2[std::size_t(a)];
  return x;
}

bulk::Vec3 unit(double x, double y, double z)
{
  const double r = std::sqrt(x * x + y * y + z * z);
  return {x / r, y / r, z / r};
}
} // namespace

TEST(CellWidth, AlongAnEdgeOfABoxBothAreTheEdge)
{
  const CellVertices box = parallelepiped({1, 2, 3}, {4, 0, 0}, {0, 10, 0}, {0, 0, 2.5});
  for (const bulk::Vec3& n : {bulk::Vec3{1, 0, 0}, bulk::Vec3{0, -1, 0}, bulk::Vec3{0, 0, 1}})
  {
    const double edge = std::abs(n[0]) * 4 + std::abs(n[1]) * 10 + std::abs(n[2]) * 2.5;
    EXPECT_NEAR(model::projected_width(box, n), edge, 1e-12);
    EXPECT_NEAR(model::row_width(box, n), edge, 1e-12);
  }
}

TEST(CellWidth, OnAShearedCellTheRowIsTheSpacingAndTheExtentIsWider)
{
  // A cell 20 mm along x, 10 mm in y, its x faces sheared by 0.3 (x moves
  // 0.3 mm per mm of y): a crack of normal x running along the row of such
  // cells opens it over 20 mm; the vertices' extent along x is 23 mm.
  const CellVertices sheared = parallelepiped({0, 0, 0}, {20, 0, 0}, {3, 10, 0}, {0, 0, 10});
  EXPECT_NEAR(model::row_width(sheared, {1, 0, 0}), 20.0, 1e-12);
  EXPECT_NEAR(model::projected_width(sheared, {1, 0, 0}), 23.0, 1e-12);
  // Along the shear's own face normal the row is the faces' distance.
  const bulk::Vec3 m = unit(10, -3, 0);
  EXPECT_NEAR(model::row_width(sheared, m), 20 * 10 / std::sqrt(109.0), 1e-12);
}

TEST(CellWidth, ANormalTiltedFromAnEdgeWidensTheRowByOneOverItsCosine)
{
  // A box 4 x 10 x 2.5 mm, a normal at theta from x in the x-y plane: the row
  // between the x faces is 4 / cos(theta) wide along it, the extent
  // 4 cos(theta) + 10 sin(theta); past the angle where the y faces' row is
  // thinner (tan(theta) = 10 / 4), that one.
  const CellVertices box = parallelepiped({0, 0, 0}, {4, 0, 0}, {0, 10, 0}, {0, 0, 2.5});
  for (double deg : {1.0, 10.0, 30.0, 45.0, 60.0, 80.0})
  {
    const double t = deg * M_PI / 180;
    const bulk::Vec3 n = {std::cos(t), std::sin(t), 0};
    const double projected = 4 * std::cos(t) + 10 * std::sin(t);
    EXPECT_NEAR(model::projected_width(box, n), projected, 1e-12) << deg << " deg";
    EXPECT_NEAR(model::row_width(box, n), std::min(4 / std::cos(t), 10 / std::sin(t)), 1e-12)
        << deg << " deg";
    EXPECT_LE(model::row_width(box, n), projected * (1 + 1e-15)) << deg << " deg";
  }
  // Along a diagonal of a cube both are its projected extent.
  const CellVertices cube = parallelepiped({0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2});
  EXPECT_NEAR(model::row_width(cube, unit(1, 1, 0)), 2 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(model::projected_width(cube, unit(1, 1, 0)), 2 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(model::row_width(cube, unit(1, 1, 1)), 2 * std::sqrt(3.0), 1e-12);
}

TEST(CellWidth, TheRowTurnsWithTheCell)
{
  // The sheared cell rotated by 40 deg about z, the normal with it: the same
  // widths (the rule is the cell's, not the axes').
  const double t = 40 * M_PI / 180, c = std::cos(t), s = std::sin(t);
  auto turn = [&](const bulk::Vec3& v) {
    return bulk::Vec3{c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]};
  };
  const CellVertices sheared =
      parallelepiped({5, -1, 2}, turn({20, 0, 0}), turn({3, 10, 0}), turn({0, 0, 10}));
  EXPECT_NEAR(model::row_width(sheared, turn({1, 0, 0})), 20.0, 1e-12);
  EXPECT_NEAR(model::projected_width(sheared, turn({1, 0, 0})), 23.0, 1e-12);
}

TEST(CellWidth, ATrapezoidalCellTakesItsCentresRow)
{
  // A cell whose far x face leans (a taper, as the push-out's cells round
  // the tube): its centre's row along x is the mean spacing.
  CellVertices x = parallelepiped({0, 0, 0}, {6, 0, 0}, {0, 4, 0}, {0, 0, 2});
  for (int v : {3, 7}) // the vertices at x = 6, y = 4: the face leans in
    x[std::size_t(v)][0] = 4;
  EXPECT_NEAR(model::row_width(x, {1, 0, 0}), 5.0, 1e-12);
  EXPECT_NEAR(model::projected_width(x, {1, 0, 0}), 6.0, 1e-12);
}

TEST(CellWidth, AFlatCellTakesItsExtent)
{
  // No volume, so no rows: the extent, not a width of zero; also where
  // round-off leaves it a volume (its third edge in the plane of the
  // others, the plane turned about an oblique axis).
  auto turn = [](const bulk::Vec3& v)
  {
    const bulk::Vec3 a = unit(1, 2, 3); // Rodrigues' rotation by 1 rad about a
    const double c = std::cos(1.0), s = std::sin(1.0);
    const double d = a[0] * v[0] + a[1] * v[1] + a[2] * v[2];
    const bulk::Vec3 axv = {a[1] * v[2] - a[2] * v[1], a[2] * v[0] - a[0] * v[2],
                            a[0] * v[1] - a[1] * v[0]};
    bulk::Vec3 r;
    for (std::size_t k = 0; k < 3; ++k)
      r[k] = v[k] * c + axv[k] * s + a[k] * d * (1 - c);
    return r;
  };
  const bulk::Vec3 e0 = turn({4, 0, 0}), e1 = turn({0, 10, 0});
  const bulk::Vec3 e2 = {0.3 * e0[0] + 0.1 * e1[0], 0.3 * e0[1] + 0.1 * e1[1],
                         0.3 * e0[2] + 0.1 * e1[2]};
  for (const CellVertices& flat : {parallelepiped({0, 0, 0}, {4, 0, 0}, {0, 10, 0}, {0, 0, 0}),
                                   parallelepiped({1, 2, 3}, e0, e1, e2)})
  {
    const bulk::Vec3 n = unit(1, 0.3, 1);
    EXPECT_NEAR(model::row_width(flat, n), model::projected_width(flat, n), 1e-12);
    EXPECT_GT(model::row_width(flat, n), 1.0);
  }
}

// The graded block of meshes/slice.geo (mesh/size.h, slice_divisions): its
// elements start at about the interface size h and grow by
// graded_growth_max at most, whatever the way to the boundary, from scenes
// alone (no meshing; the e2e test test_resource_estimate_within_factor_2
// compares the counts with gmsh's meshes).
#include "mesh/size.h"
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <string>

using pushout::Scene;
using pushout::mesh::graded_growth_max;
using pushout::mesh::MeshInput;
using pushout::mesh::slice_divisions;

namespace
{
/// The tube centre of the default 100 mm square with R = 10 mm and a
/// support circle of 15 mm: the graded block's shortest way, from the
/// support circle to the nearest face, is Lr = 35 mm centred and 10 mm with
/// the corroded demo's 15 mm cover.
struct Case
{
  const char* centre;
  double Lr; ///< mm
};
constexpr Case centred{"[50.0, 50.0]", 35.0}, cover15{"[50.0, 25.0]", 10.0};

pushout::mesh::SliceDivisions divisions(const Case& where, int per_quarter)
{
  return slice_divisions(MeshInput::of(
      Scene::parse(std::string("[geometry]\ntube_center = ") + where.centre +
                   "\n[mesh]\nelements_per_quarter = " + std::to_string(per_quarter) + "\n")));
}

/// The growth q of n elements that start at h and fill L:
/// h (q^n - 1) / (q - 1) = L (q > 1; bisection).
double growth_to_fill(double h, int n, double L)
{
  double lo = 1 + 1e-12, hi = 100;
  for (int i = 0; i < 200; ++i)
  {
    const double q = (lo + hi) / 2;
    (h * (std::pow(q, n) - 1) / (q - 1) < L ? lo : hi) = q;
  }
  return (lo + hi) / 2;
}
} // namespace

TEST(SliceDivisions, GradedElementsGrowGently)
{
  for (const Case& where : {centred, cover15})
    for (int nq : {4, 5, 6, 8, 12, 16, 24, 32})
    {
      const auto d = divisions(where, nq);
      const double h = std::numbers::pi / 2 * 10.0 / nq; // interface element [mm]
      SCOPED_TRACE("Lr = " + std::to_string(where.Lr) + " mm, " + std::to_string(nq) +
                   " per quarter: " + std::to_string(d.graded) + " graded elements");
      ASSERT_GE(d.graded, 1);
      if (double(d.graded) * h >= where.Lr)
        continue; // uniform, at most h
      // The growth the .geo gives its progression: from h to the outer size
      // ratio h (ratio 10) where that fills Lr gently, else the growth that
      // fills Lr from h. Either way at most q_max (1e-9: the bisection above).
      const double he = 10 * h, q0 = (where.Lr - h) / (where.Lr - he);
      const double q = he < where.Lr && q0 <= graded_growth_max
                           ? std::pow(10.0, 1.0 / double(d.graded - 1))
                           : growth_to_fill(h, int(d.graded), where.Lr);
      EXPECT_LE(q, graded_growth_max + 1e-9);
    }
}

TEST(SliceDivisions, ThinCoverKeepsSeveralElements)
{
  // Before the growth was bounded, 16 per quarter (the paper's mesh) gave the
  // 15 mm cover 2 graded elements of 1 and 9 mm (24 per quarter: 3) while 12
  // per quarter gave it 8 of 1.25 mm: the outer slice was 2 elements deep
  // and the corroded slice's bending after its cover cracked doubled its
  // pressure (docs/corrosion.md).
  EXPECT_EQ(divisions(cover15, 12).graded, 8); // uniform: 10 mm / 1.31 mm
  EXPECT_EQ(divisions(cover15, 16).graded, 5);
  EXPECT_EQ(divisions(cover15, 24).graded, 5);
  EXPECT_EQ(divisions(cover15, 32).graded, 6);
  // Where the grading was gentle nothing changed: the paper's centred mesh.
  EXPECT_EQ(divisions(centred, 16).graded, 9);
  EXPECT_EQ(divisions(centred, 12).graded, 6);
}

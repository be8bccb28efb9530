// A mirror set (a crack plane on a symmetry plane, interface/Interface.h):
// one face meshed, its minus side the plus side's mirror image. Against the
// two-sided joint with the minus nodes moved as the mirror images of the
// plus nodes: the same jumps and states, and forces on the plus nodes of half
// the two-sided ones, folded back through the mirror (the model holds half
// the plane). Its tangent against central finite differences.
#include "common/petsc_check.h"
#include "interface/Interface.h"
#include "laws/LawRegistry.h"
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <petscmat.h>
#include <random>

using namespace pushout;

namespace
{
// The facet x = 0, 0 <= y, z <= 1 (tensor order), normal +x: the minus side
// in x < 0, the plus side (the model's) in x > 0.
const std::vector<double> facet = {0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1};
constexpr std::array<double, 3> m = {1, 0, 0};

std::vector<std::unique_ptr<laws::InterfaceLaw>> crack_law()
{
  std::vector<std::unique_ptr<laws::InterfaceLaw>> layers;
  layers.push_back(
      laws::find_law("exponential_softening")
          ->make({{"k", 1000.0}, {"f_t", 3.0}, {"c", 30.0}, {"f_fr", 0.0}, {"eta", 0.0}}, ""));
  return layers;
}

/// The two-sided pair (minus nodes 0-3, plus nodes 4-7) and the mirror pair
/// on the plus nodes (blocks 4-7 both sides).
interface::Interface two_sided()
{
  return interface::Interface({0, 1, 2, 3, 4, 5, 6, 7}, facet, interface::make_quadrature("gauss"),
                              crack_law());
}
interface::Interface mirror()
{
  return interface::Interface({4, 5, 6, 7, 4, 5, 6, 7}, facet, interface::make_quadrature("gauss"),
                              crack_law(), m);
}

/// u of the 8 nodes: plus nodes given, minus nodes their mirror images.
std::vector<double> with_images(const std::vector<double>& u_plus)
{
  std::vector<double> u(24, 0.0);
  for (int a = 0; a < 4; ++a)
  {
    for (int d = 0; d < 3; ++d)
      u[12 + 3 * a + d] = u_plus[3 * a + d];
    u[3 * a] = -u_plus[3 * a]; // M = diag(-1, 1, 1)
    u[3 * a + 1] = u_plus[3 * a + 1];
    u[3 * a + 2] = u_plus[3 * a + 2];
  }
  return u;
}

Mat tangent_matrix()
{
  Mat A;
  pushout::petsc::check(MatCreateSeqBAIJ(PETSC_COMM_SELF, 3, 24, 24, 8, nullptr, &A),
                        "MatCreateSeqBAIJ");
  ISLocalToGlobalMapping l2g;
  std::vector<PetscInt> blocks = {0, 1, 2, 3, 4, 5, 6, 7};
  pushout::petsc::check(
      ISLocalToGlobalMappingCreate(PETSC_COMM_SELF, 3, 8, blocks.data(), PETSC_COPY_VALUES, &l2g),
      "ISLocalToGlobalMappingCreate");
  pushout::petsc::check(MatSetLocalToGlobalMapping(A, l2g, l2g), "MatSetLocalToGlobalMapping");
  pushout::petsc::check(ISLocalToGlobalMappingDestroy(&l2g), "ISLocalToGlobalMappingDestroy");
  return A;
}
} // namespace

TEST(MirrorJoint, HalfTheTwoSidedJointFoldedThroughTheMirror)
{
  interface::Interface two = two_sided(), half = mirror();
  ASSERT_TRUE(half.mirrored());
  EXPECT_NEAR(half.area(), 0.5 * two.area(), 1e-14);
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> U(-1, 1);
  for (int step = 0; step < 12; ++step) // the crack opens past f_t and softens
  {
    std::vector<double> u_plus(12);
    for (int i = 0; i < 12; ++i)
      u_plus[i] = (i % 3 == 0 ? 0.004 * step : 0.0) + 1e-3 * U(gen);
    const std::vector<double> u = with_images(u_plus);
    std::vector<double> f_two(24, 0.0), f_half(24, 0.0);
    ASSERT_TRUE(two.assemble(u, f_two, nullptr));
    ASSERT_TRUE(half.assemble(u, f_half, nullptr)); // reads the plus nodes only
    for (std::size_t p = 0; p < two.num_points(); ++p)
      EXPECT_TRUE(std::ranges::equal(two.state().trial(p, 0), half.state().trial(p, 0)));
    double scale = 0;
    for (double f : f_two)
      scale = std::max(scale, std::abs(f));
    for (int a = 0; a < 4; ++a)
    {
      // f_plus + M f_minus, halved: the normal (x) components add, the
      // tangential ones cancel (the mirror opening has no slip).
      const double* fp = &f_two[12 + 3 * a];
      const double* fm = &f_two[3 * a];
      const std::array<double, 3> folded = {0.5 * (fp[0] - fm[0]), 0.5 * (fp[1] + fm[1]),
                                            0.5 * (fp[2] + fm[2])};
      for (int d = 0; d < 3; ++d)
      {
        EXPECT_NEAR(f_half[12 + 3 * a + d], folded[d], 1e-13 * scale);
        EXPECT_EQ(f_half[3 * a + d], 0.0); // nothing on the absent minus nodes
      }
      EXPECT_NEAR(f_half[12 + 3 * a + 1], 0.0, 1e-13 * scale);
    }
    EXPECT_NEAR(half.dissipation(), 0.5 * two.dissipation(), 1e-13 * (1 + two.dissipation()));
    two.commit();
    half.commit();
  }
}

TEST(MirrorJoint, TangentMatchesFiniteDifferences)
{
  interface::Interface half = mirror();
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> U(-1, 1);
  std::vector<double> u(24, 0.0);
  for (int step = 0; step < 6; ++step)
  {
    for (int i = 12; i < 24; ++i)
      u[i] = (i % 3 == 0 ? 0.003 * step : 0.0) + 2e-4 * U(gen);
    Mat A = tangent_matrix();
    std::vector<double> f(24, 0.0);
    ASSERT_TRUE(half.assemble(u, f, A));
    pushout::petsc::check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    pushout::petsc::check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    const double h = 1e-7; // [mm]
    double worst = 0, scale = 0;
    for (int j = 12; j < 24; ++j)
    {
      std::vector<double> up = u, um = u, fp(24, 0.0), fm(24, 0.0);
      up[j] += h;
      um[j] -= h;
      ASSERT_TRUE(half.assemble(up, fp, nullptr));
      ASSERT_TRUE(half.assemble(um, fm, nullptr));
      for (int i = 12; i < 24; ++i)
      {
        double a = 0;
        pushout::petsc::check(MatGetValues(A, 1, &i, 1, &j, &a), "MatGetValues");
        const double fd = (fp[i] - fm[i]) / (2 * h);
        worst = std::max(worst, std::abs(a - fd));
        scale = std::max(scale, std::abs(a));
      }
    }
    EXPECT_LT(worst, 1e-5 * scale) << "step " << step;
    half.assemble(u, f, nullptr); // the trial state back at u
    half.commit();
    pushout::petsc::check(MatDestroy(&A), "MatDestroy");
  }
}

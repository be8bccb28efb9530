// Friction on the pressure of the corrosion oxide (laws/OxideFriction.h) and
// the oxide inputs of a corrosion depth (laws/Oxide.h): closed forms of a
// single joint, the limit without corrosion, and the consistent tangent.
#include "law_testing.h"
#include "laws/Friction.h"
#include "laws/Oxide.h"
#include "laws/OxideFriction.h"
#include <gtest/gtest.h>
#include <iostream>
#include <random>

using pushout::laws::Friction;
using pushout::laws::oxide_inputs;
using pushout::laws::OxideFriction;
using pushout::laws::OxideLayer;
using pushout::laws::StepInputs;
using pushout::laws::Vec3;

TEST(Oxide, OpeningAndComplianceFromTheDepth)
{
  // x = 20 um of steel, beta 2: the oxide is 40 um thick and opens 20 um.
  const auto a = oxide_inputs(OxideLayer{2.0, 0.0, 2000.0}, 0.02);
  EXPECT_DOUBLE_EQ(a.gap, 0.02);
  EXPECT_DOUBLE_EQ(a.compliance, 0.04 / 2000.0);
  // beta 3 with a 12.5 um porous zone: 40 - 12.5 um.
  const auto b = oxide_inputs(OxideLayer{3.0, 0.0125, 2000.0}, 0.02);
  EXPECT_NEAR(b.gap, 0.0275, 1e-15);
  // The porous zone takes the whole expansion: no opening yet.
  EXPECT_DOUBLE_EQ(oxide_inputs(OxideLayer{2.0, 0.03, 2000.0}, 0.02).gap, 0.0);
}

TEST(OxideFriction, FreeNormalOpensByTheGapAndCarriesNothing)
{
  const OxideFriction law(1000.0, 0.4);
  const StepInputs in{0, 0.002, 1e-3};
  std::vector<double> s0(OxideFriction::state_size), s1(s0.size());
  // A free joint settles where t_n = 0: w_n = g0, p = 0, so no shear either.
  const auto r = law.update(s0, {0.002, 0.001, 0}, s1, in);
  EXPECT_DOUBLE_EQ(r.t[0], 0.0);
  EXPECT_DOUBLE_EQ(r.t[1], 0.0);
  EXPECT_DOUBLE_EQ(law.slip(s1)[0], 0.001);
}

TEST(OxideFriction, HeldNormalPressesWithTheSeriesStiffness)
{
  // k 1000 and c_ox 1e-3 in series: 500 N/mm^3; g0 2 um -> p = 1 MPa.
  const OxideFriction law(1000.0, 0.4);
  const StepInputs in{0, 0.002, 1e-3};
  std::vector<double> s0(OxideFriction::state_size), s1(s0.size());
  const auto r = law.update(s0, {0, 0, 0}, s1, in);
  EXPECT_NEAR(r.t[0], -1.0, 1e-14);
  EXPECT_NEAR(r.D[0], 500.0, 1e-10);
  // Shear along s1 at w_n = 0: stick at k u, then slide at mu p = 0.4 MPa.
  std::vector<double> state(s0), trial(s0.size());
  std::vector<double> t;
  for (double u : {0.0002, 0.0004, 0.001, 0.003})
  {
    t.push_back(law.update(state, {0, u, 0}, trial, in).t[1]);
    state = trial;
  }
  EXPECT_NEAR(t[0], 0.2, 1e-14);
  EXPECT_NEAR(t[1], 0.4, 1e-14);
  EXPECT_NEAR(t[2], 0.4, 1e-14);
  EXPECT_NEAR(t[3], 0.4, 1e-14);
  EXPECT_NEAR(law.slip(state)[0], 0.003 - 0.4 / 1000, 1e-15);
  // The pressure grows with the gap and the limit with it (x grows, tube held).
  const auto r2 = law.update(state, {0, 0.004, 0}, trial, {0, 0.004, 1e-3});
  EXPECT_NEAR(r2.t[0], -2.0, 1e-13);
  EXPECT_NEAR(r2.t[1], 0.8, 1e-13);
}

TEST(OxideFriction, OpeningBeyondTheOxidePullsNothing)
{
  // The oxide cannot glue the concrete: beyond g0 no traction, no stiffness
  // (Friction would pull with k (w_n - g0) = 1 MPa here).
  const OxideFriction law(1000.0, 0.4);
  std::vector<double> s0(OxideFriction::state_size), s1(s0.size());
  const auto r = law.update(s0, {0.003, 0.001, 0}, s1, {0, 0.002, 1e-3});
  EXPECT_EQ(r.t[0], 0.0);
  EXPECT_EQ(r.t[1], 0.0);
  EXPECT_EQ(r.D[0], 0.0);
  EXPECT_EQ(r.D[3], 0.0); // the shear does not see w_n either
  // Without corrosion too: an open joint carries nothing.
  EXPECT_EQ(law.update(s0, {1e-4, 0, 0}, s1).t[0], 0.0);
  // At the gap exactly it keeps the penalty (a joint at rest is not singular).
  EXPECT_EQ(law.update(s0, {0.002, 0, 0}, s1, {0, 0.002, 1e-3}).D[0], 1000.0);
}

TEST(OxideFriction, WithoutCorrosionInContactItIsFriction)
{
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> U(-1, 1);
  const OxideFriction oxide(2000.0, 0.35);
  const Friction friction(2000.0, 0.35);
  for (int i = 0; i < 200; ++i)
  {
    const Vec3 w = {-1e-3 * (U(gen) + 1) / 2, 1e-3 * U(gen), 1e-3 * U(gen)}; // w_n <= 0
    const std::vector<double> s0 = {1e-3 * U(gen), 1e-3 * U(gen)};
    std::vector<double> a(2), b(2);
    const auto ra = oxide.update(s0, w, a), rb = friction.update(s0, w, b);
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(ra.t[c], rb.t[c]);
    for (int c = 0; c < 9; ++c)
      EXPECT_EQ(ra.D[c], rb.D[c]);
    EXPECT_EQ(a, b);
  }
}

TEST(OxideFriction, TangentMatchesFiniteDifferencesAtRandomStates)
{
  const auto states = pushout::testing::check_friction_tangent(
      11, [](double k, double mu) { return OxideFriction(k, mu); },
      [](std::mt19937& gen)
      {
        std::uniform_real_distribution<double> U(-1, 1);
        return StepInputs{0, 1e-3 * (U(gen) + 1) / 2, 1e-4 * (U(gen) + 1)};
      });
  std::cout << "oxide_friction: max FD tangent error " << states.worst << " over 300 states\n";
  EXPECT_GT(states.sliding, 50);
  EXPECT_GT(states.sticking, 20);
  EXPECT_GT(states.open, 30);
}

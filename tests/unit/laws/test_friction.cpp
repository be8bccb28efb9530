// Friction with inelastic slip (paper §3): analytic paths, vector slip,
// opening, and the consistent tangent against finite differences.
#include "law_testing.h"
#include "laws/Friction.h"
#include <gtest/gtest.h>
#include <iostream>
#include <random>

using pushout::laws::Friction;
using pushout::laws::PlasticSlip;
using pushout::laws::Vec3;

namespace
{
/// A state with plastic slip (s1, s2) [mm], written through its named view.
std::vector<double> with_slip(double s1, double s2)
{
  std::vector<double> state(Friction::state_size);
  const PlasticSlip<double> slip(state);
  slip.s1() = s1;
  slip.s2() = s2;
  return state;
}

/// Runs a shear path along s1 at fixed w_n, committing every step.
std::vector<double> shear_path(const Friction& law, double wn, const std::vector<double>& us)
{
  std::vector<double> state(Friction::state_size), trial(state.size()), t;
  for (double u : us)
  {
    const auto r = law.update(state, {wn, u, 0}, trial);
    t.push_back(r.t[1]);
    state = trial;
  }
  return t;
}
} // namespace

TEST(Friction, StickThenSlideThenReverse)
{
  // k 100, mu 0.4, w_n = -0.004 -> p = 0.4 MPa, limit 0.16 MPa (Fig. 6).
  const Friction law(100.0, 0.4);
  const auto t = shear_path(law, -0.004, {0.001, 0.0016, 0.01, 0.02, 0.019, 0.0168, 0.01, 0.012});
  EXPECT_NEAR(t[0], 0.1, 1e-14);  // stick: k u
  EXPECT_NEAR(t[1], 0.16, 1e-14); // just at the limit
  EXPECT_NEAR(t[2], 0.16, 1e-14); // sliding
  EXPECT_NEAR(t[3], 0.16, 1e-14);
  EXPECT_NEAR(t[4], 0.06, 1e-14);  // elastic unloading: 0.16 - 100 * 0.001
  EXPECT_NEAR(t[5], -0.16, 1e-14); // reverse limit reached at 0.0168
  EXPECT_NEAR(t[6], -0.16, 1e-14); // reverse sliding
  EXPECT_NEAR(t[7], 0.04, 1e-14);  // reloading: -0.16 + 100 * 0.002
}

TEST(Friction, SlipIsAVectorAlongTheTrialTraction)
{
  const Friction law(1000.0, 0.5);
  const std::vector<double> s0 = with_slip(0.001, -0.002);
  std::vector<double> s1(s0.size());
  const Vec3 w = {-0.01, 0.02, 0.01}; // p = 10 MPa, limit 5 MPa
  const auto r = law.update(s0, w, s1);
  const auto p0 = law.slip(s0), p1 = law.slip(s1); // (s1, s2) [mm]
  const double t1 = 1000 * (w[1] - p0[0]), t2 = 1000 * (w[2] - p0[1]);
  const double norm = std::hypot(t1, t2);
  EXPECT_NEAR(std::hypot(r.t[1], r.t[2]), 5.0, 1e-12);
  EXPECT_NEAR(r.t[1] * t2 - r.t[2] * t1, 0.0, 1e-9); // parallel to the trial
  EXPECT_NEAR(p1[0] - p0[0], (norm - 5.0) / 1000 * t1 / norm, 1e-15);
  EXPECT_NEAR(p1[1] - p0[1], (norm - 5.0) / 1000 * t2 / norm, 1e-15);
  EXPECT_DOUBLE_EQ(r.t[0], -10.0);
}

TEST(Friction, OpeningCarriesNoShearAndKeepsNormalStiffness)
{
  const Friction law(1000.0, 0.4);
  std::vector<double> s1(Friction::state_size);
  const auto r = law.update(std::vector<double>(s1.size()), {0.001, 0.003, -0.002}, s1);
  EXPECT_DOUBLE_EQ(r.t[0], 1.0);
  EXPECT_DOUBLE_EQ(r.t[1], 0.0);
  EXPECT_DOUBLE_EQ(r.t[2], 0.0);
  EXPECT_DOUBLE_EQ(r.D[0], 1000.0);
  EXPECT_DOUBLE_EQ(law.slip(s1)[0], 0.003); // the whole shear jump became slip
  EXPECT_DOUBLE_EQ(law.slip(s1)[1], -0.002);
}

TEST(Friction, ZeroFrictionSlidesFreely)
{
  const Friction law(1000.0, 0.0);
  const auto t = shear_path(law, -0.01, {0.001, -0.003});
  EXPECT_DOUBLE_EQ(t[0], 0.0);
  EXPECT_DOUBLE_EQ(t[1], 0.0);
}

TEST(Friction, TangentMatchesFiniteDifferencesAtRandomStates)
{
  const auto states = pushout::testing::check_friction_tangent(
      42, [](double k, double mu) { return Friction(k, mu); },
      [](std::mt19937&) { return pushout::laws::StepInputs{}; });
  std::cout << "friction: max FD tangent error " << states.worst << " over 300 states\n";
  EXPECT_GT(states.sliding, 50);
  EXPECT_GT(states.sticking, 20);
  EXPECT_GT(states.open, 50);
}

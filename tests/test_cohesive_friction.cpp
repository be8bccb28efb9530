// The coupled cohesive-friction law (Alfano & Sacco 2006): its two limits,
// its place between the single mechanisms, FD tangents.
#include "law_testing.h"
#include "laws/CohesiveFriction.h"
#include "laws/Elastic.h"
#include "laws/Friction.h"
#include "laws/LinearSoftening.h"
#include <gtest/gtest.h>
#include <iostream>
#include <random>

using namespace pushout::laws;

namespace
{
const double k = 100, mu = 0.4, f_t = 1, w_c2 = 0.3;
const CohesiveFriction coupled(k, mu, Envelope{Envelope::Kind::linear, f_t, w_c2});
} // namespace

TEST(CohesiveFriction, UndamagedIsElastic)
{
  const Elastic elastic(k, k);
  const Vec3 w = {-0.002, 0.004, -0.003}; // delta = 0.005 < w0 = 0.01
  std::vector<double> s0 = {0, 0, 0, 0}, s1(4);
  const auto a = coupled.update(s0, w, s1);
  const auto b = elastic.update({}, w, {});
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(a.t[i], b.t[i], 1e-15);
  for (int i = 0; i < 9; ++i)
    EXPECT_NEAR(a.D[i], b.D[i], 1e-12);
}

TEST(CohesiveFriction, FullyDamagedIsFrictionInContact)
{
  const Friction friction(k, mu);
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> U(-1, 1);
  for (int i = 0; i < 50; ++i)
  {
    const Vec3 w = {-0.01 * std::abs(U(gen)) - 1e-4, 0.02 * U(gen), 0.02 * U(gen)};
    const std::vector<double> slip = {0.01 * U(gen), 0.01 * U(gen)};
    std::vector<double> s0 = {1.0, 0.0, slip[0], slip[1]}, s1(4), f1(2); // beyond w0 + w_c2
    const auto a = coupled.update(s0, w, s1);
    const auto b = friction.update(slip, w, f1);
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(a.t[j], b.t[j], 1e-13);
    for (int j = 0; j < 9; ++j)
      EXPECT_NEAR(a.D[j], b.D[j], 1e-10);
    EXPECT_NEAR(s1[1], 1.0, 1e-15); // fully damaged
    EXPECT_NEAR(s1[2], f1[0], 1e-15);
    EXPECT_NEAR(s1[3], f1[1], 1e-15);
  }
}

TEST(CohesiveFriction, LiesBetweenCohesionAloneAndTheSuperposition)
{
  // Shear path under compression (p = 0.4 MPa), as in the paper's Fig. 9.
  const Friction friction(k, mu);
  const LinearSoftening cohesive(Params{{"k", k}, {"f_t", f_t}, {"w_c2", w_c2}, {"eta", 0}}, "");
  std::vector<double> sc = {0, 0, 0, 0}, sf = {0, 0}, sd = {0, 0};
  std::vector<double> nc(4), nf(2), nd(2);
  for (int i = 1; i <= 400; ++i)
  {
    const double u = 0.4 * i / 400;
    const Vec3 w = {-0.004, u, 0};
    const double tc = coupled.update(sc, w, nc).t[1];
    const double tf = friction.update(sf, w, nf).t[1];
    const double td = cohesive.update(sd, w, nd).t[1];
    EXPECT_GE(tc, td - 1e-12) << u;
    EXPECT_LE(tc, td + tf + 1e-12) << u;
    sc = nc;
    sf = nf;
    sd = nd;
  }
  // At the end the cohesion is gone and only friction remains.
  EXPECT_NEAR(coupled.update(sc, {-0.004, 0.4, 0}, nc).t[1], mu * 0.4, 1e-12);
}

TEST(CohesiveFriction, NeedsExactlyOneEnvelope)
{
  EXPECT_THROW(
      CohesiveFriction(Params{{"k", 1}, {"mu", 0.4}, {"f_t", 1}, {"eta", 0}}, "interface.0."),
      pushout::laws::ParameterError);
  EXPECT_THROW(
      CohesiveFriction(Params{{"k", 1}, {"mu", 0.4}, {"f_t", 1}, {"c", 2}, {"w_c2", 1}, {"eta", 0}},
                       "interface.0."),
      pushout::laws::ParameterError);
}

TEST(CohesiveFriction, TangentMatchesFiniteDifferencesAtRandomStates)
{
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> U(-1, 1);
  const double h = 1e-9, margin = 1e3 * h, w0 = f_t / k;
  int tested = 0, loading = 0, sliding = 0;
  double worst = 0;
  const CohesiveFriction exp_law(1000, 0.3, Envelope{Envelope::Kind::exponential, 3, 0, 0, 25});
  for (const CohesiveFriction* law : {&coupled, &exp_law})
  {
    const double kk = law == &coupled ? k : 1000;
    const double mm = law == &coupled ? mu : 0.3;
    const double ww0 = law == &coupled ? w0 : 0.003;
    for (int n = 0; n < 150;)
    {
      const double scale = 5 * ww0 * std::abs(U(gen)) + 1e-4;
      const Vec3 w = {scale * U(gen), scale * U(gen), scale * U(gen)};
      const std::vector<double> s0 = {3 * ww0 * std::abs(U(gen)), 0.0, scale * U(gen),
                                      scale * U(gen)};
      const double delta = CamanhoDavila::equivalent(w);
      const double f = kk * std::hypot(w[1] - s0[1], w[2] - s0[2]) - mm * std::max(-kk * w[0], 0.0);
      if (std::abs(w[0]) < margin || std::abs(delta - s0[0]) < margin ||
          std::abs(delta - ww0) < margin || std::abs(f) < kk * margin ||
          std::abs(delta - ww0 - w_c2) < margin)
        continue;
      const double err = pushout::testing::tangent_error(*law, s0, w, h, kk);
      worst = std::max(worst, err);
      EXPECT_LT(err, 1e-6) << "kappa " << s0[0] << " w " << w[0] << " " << w[1] << " " << w[2];
      ++n;
      ++tested;
      loading += delta > s0[0] && delta > ww0;
      sliding += f > 0;
    }
  }
  std::cout << "cohesive_friction: max FD tangent error " << worst << " over 300 states\n";
  EXPECT_EQ(tested, 300);
  EXPECT_GT(loading, 50);
  EXPECT_GT(sliding, 50);
}

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

/// A state with the largest jump kappa [mm], the acting damage D_v and the
/// plastic slip (s1, s2) [mm], written through its named view.
std::vector<double> state(double kappa, double damage, double s1, double s2)
{
  std::vector<double> s(CohesiveFriction::state_size);
  const CohesiveFrictionState<double> v(s);
  v.damage_history().kappa() = kappa;
  v.damage_history().damage() = damage;
  v.plastic_slip().s1() = s1;
  v.plastic_slip().s2() = s2;
  return s;
}
} // namespace

TEST(CohesiveFriction, UndamagedIsElastic)
{
  const Elastic elastic(k, k);
  const Vec3 w = {-0.002, 0.004, -0.003}; // delta = 0.005 < w0 = 0.01
  std::vector<double> s0(CohesiveFriction::state_size), s1(s0.size());
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
    const double p1 = 0.01 * U(gen), p2 = 0.01 * U(gen);    // plastic slip [mm]
    const std::vector<double> s0 = state(1.0, 0.0, p1, p2); // beyond w0 + w_c2
    std::vector<double> s1(s0.size()), f0(Friction::state_size), f1(f0.size());
    PlasticSlip<double>(f0).s1() = p1;
    PlasticSlip<double>(f0).s2() = p2;
    const auto a = coupled.update(s0, w, s1);
    const auto b = friction.update(f0, w, f1);
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(a.t[j], b.t[j], 1e-13);
    for (int j = 0; j < 9; ++j)
      EXPECT_NEAR(a.D[j], b.D[j], 1e-10);
    EXPECT_NEAR(coupled.damage(s1), 1.0, 1e-15); // fully damaged
    EXPECT_NEAR(coupled.slip(s1)[0], friction.slip(f1)[0], 1e-15);
    EXPECT_NEAR(coupled.slip(s1)[1], friction.slip(f1)[1], 1e-15);
  }
}

TEST(CohesiveFriction, LiesBetweenCohesionAloneAndTheSuperposition)
{
  // Shear path under compression (p = 0.4 MPa), as in the paper's Fig. 9.
  const Friction friction(k, mu);
  const LinearSoftening cohesive(Params{{"k", k}, {"f_t", f_t}, {"w_c2", w_c2}, {"eta", 0}}, "");
  std::vector<double> sc(CohesiveFriction::state_size), sf(Friction::state_size),
      sd(LinearSoftening::state_size);
  std::vector<double> nc(sc.size()), nf(sf.size()), nd(sd.size());
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
      // Without viscosity the committed D_v does not enter the update.
      const double kappa = 3 * ww0 * std::abs(U(gen)), p1 = scale * U(gen), p2 = scale * U(gen);
      const std::vector<double> s0 = state(kappa, 0.0, p1, p2);
      const double delta = CamanhoDavila::equivalent(w);
      const double f = kk * std::hypot(w[1] - p1, w[2] - p2) - mm * std::max(-kk * w[0], 0.0);
      if (std::abs(w[0]) < margin || std::abs(delta - kappa) < margin ||
          std::abs(delta - ww0) < margin || std::abs(f) < kk * margin ||
          std::abs(delta - ww0 - w_c2) < margin)
        continue;
      const double err = pushout::testing::tangent_error(*law, s0, w, h, kk);
      worst = std::max(worst, err);
      EXPECT_LT(err, 1e-6) << "kappa " << kappa << " w " << w[0] << " " << w[1] << " " << w[2];
      ++n;
      ++tested;
      loading += delta > kappa && delta > ww0;
      sliding += f > 0;
    }
  }
  std::cout << "cohesive_friction: max FD tangent error " << worst << " over 300 states\n";
  EXPECT_EQ(tested, 300);
  EXPECT_GT(loading, 50);
  EXPECT_GT(sliding, 50);
}

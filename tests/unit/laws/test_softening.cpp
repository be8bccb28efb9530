// Cohesive softening laws (paper §2.3, Fig. 5a/b): analytic paths, secant
// unloading, compression, energy to full separation, FD tangents.
#include "law_testing.h"
#include "laws/Envelope.h"
#include "laws/ExponentialSoftening.h"
#include "laws/LinearSoftening.h"
#include "laws/LinearSofteningFriction.h"
#include <gtest/gtest.h>
#include <iostream>
#include <random>

using namespace pushout::laws;

namespace
{
Params params(std::initializer_list<std::pair<const std::string, double>> p)
{
  return Params(p);
}

const LinearSoftening linear(params({{"k", 100}, {"f_t", 1}, {"w_c2", 0.3}, {"eta", 0}}), "");
const LinearSofteningFriction
    linear_fr(params({{"k", 100}, {"f_t", 1}, {"w_c2", 0.3}, {"f_fr", 0.4}, {"eta", 0}}), "");
const ExponentialSoftening
    exponential(params({{"k", 1000}, {"f_t", 3}, {"c", 25}, {"f_fr", 0}, {"eta", 0}}), "");

/// A damage history with the largest jump kappa [mm] and the acting damage
/// D_v, written through its named view.
std::vector<double> history(double kappa, double damage)
{
  std::vector<double> s(CamanhoDavila::state_size);
  const DamageHistory<double> h(s);
  h.kappa() = kappa;
  h.damage() = damage;
  return s;
}

/// Traction along a path of jumps, committing every step.
template <typename L> std::vector<Vec3> path(const L& law, const std::vector<Vec3>& jumps)
{
  std::vector<double> s(L::state_size), s1(s.size());
  std::vector<Vec3> t;
  for (const Vec3& w : jumps)
  {
    t.push_back(law.update(s, w, s1).t);
    s = s1;
  }
  return t;
}

/// Work of the normal traction over a monotonic opening to w_end [N/mm].
template <typename L> double opening_work(const L& law, double w_end, int n)
{
  std::vector<double> s(L::state_size), s1(s.size());
  double work = 0, t_prev = 0;
  for (int i = 1; i <= n; ++i)
  {
    const double w = w_end * i / n;
    const double t = law.update(s, {w, 0, 0}, s1).t[0];
    work += 0.5 * (t + t_prev) * w_end / n;
    t_prev = t;
    s = s1;
  }
  return work;
}
} // namespace

TEST(LinearSoftening, PureShearPeakSofteningSecantUnloadingReloading)
{
  // w0 = f_t / k = 0.01 mm; sigma = 1 - (kappa - 0.01) / 0.3.
  const auto t = path(linear, {{0, 0.005, 0},
                               {0, 0.01, 0},
                               {0, 0.16, 0},
                               {0, 0.08, 0},
                               {0, 0.16, 0},
                               {0, 0.31, 0},
                               {0, 0.4, 0}});
  EXPECT_NEAR(t[0][1], 0.5, 1e-14);  // elastic
  EXPECT_NEAR(t[1][1], 1.0, 1e-14);  // peak
  EXPECT_NEAR(t[2][1], 0.5, 1e-14);  // halfway down
  EXPECT_NEAR(t[3][1], 0.25, 1e-14); // secant to the origin
  EXPECT_NEAR(t[4][1], 0.5, 1e-14);  // back on the envelope
  EXPECT_NEAR(t[5][1], 0.0, 1e-14);  // fully damaged
  EXPECT_NEAR(t[6][1], 0.0, 1e-14);
  std::vector<double> s(LinearSoftening::state_size), s1(s.size());
  linear.update(s, {0, 0.4, 0}, s1);
  EXPECT_NEAR(linear.damage(s1), 1.0, 1e-14);
}

TEST(LinearSoftening, PureOpeningAndMixedModeUseTheEuclideanJump)
{
  const auto t = path(linear, {{0.16, 0, 0}});
  EXPECT_NEAR(t[0][0], 0.5, 1e-14);
  // Mixed: |(0.096, 0.128)| = 0.16 -> secant 0.5 / 0.16 on both components.
  const auto m = path(linear, {{0.096, 0.128, 0}});
  EXPECT_NEAR(m[0][0], 0.5 / 0.16 * 0.096, 1e-14);
  EXPECT_NEAR(m[0][1], 0.5 / 0.16 * 0.128, 1e-14);
}

TEST(LinearSoftening, CompressionIsElasticAndDoesNotDamage)
{
  std::vector<double> s(LinearSoftening::state_size), s1(s.size());
  const auto r = linear.update(s, {-0.5, 0, 0}, s1);
  EXPECT_DOUBLE_EQ(r.t[0], -50.0);
  EXPECT_DOUBLE_EQ(DamageHistory<const double>(s1).kappa(), 0.0);
  EXPECT_DOUBLE_EQ(linear.damage(s1), 0.0);
  // Damaged, then compressed: still the full k in the normal direction.
  s = history(0.2, 0.5);
  EXPECT_DOUBLE_EQ(linear.update(s, {-0.01, 0, 0}, s1).t[0], -1.0);
}

TEST(LinearSofteningFriction, SoftensToTheResidual)
{
  const auto t =
      path(linear_fr, {{0, 0.01, 0}, {0, 0.1, 0}, {0, 0.2, 0}, {0, 1.0, 0}, {0, 0.5, 0}});
  EXPECT_NEAR(t[0][1], 1.0, 1e-14);
  EXPECT_NEAR(t[1][1], 0.7, 1e-14);
  EXPECT_NEAR(t[2][1], 0.4, 1e-14); // reached f_fr at kappa = 0.19
  EXPECT_NEAR(t[3][1], 0.4, 1e-14);
  EXPECT_NEAR(t[4][1], 0.2, 1e-14); // secant unloading from the residual
}

TEST(ExponentialSoftening, Envelope)
{
  // w0 = 0.003 mm; sigma = 3 exp(-25 (kappa - w0)).
  const auto t = path(exponential, {{0.003, 0, 0}, {0.043, 0, 0}, {0.0215, 0, 0}});
  EXPECT_NEAR(t[0][0], 3.0, 1e-13);
  EXPECT_NEAR(t[1][0], 3 * std::exp(-1.0), 1e-13);
  EXPECT_NEAR(t[2][0], 1.5 * std::exp(-1.0), 1e-13);
}

TEST(Softening, EnergyToFullSeparationIsTheAreaUnderTheEnvelope)
{
  // Linear: f_t (w0 + w_c2) / 2 = 1 x 0.31 / 2.
  const double e_lin = opening_work(linear, 0.4, 40000) / 0.155 - 1;
  // Exponential, f_fr = 0: f_t w0 / 2 + f_t / c = 0.0045 + 0.12.
  const double G = 3 * 0.003 / 2 + 3.0 / 25;
  const double e_exp = opening_work(exponential, 0.003 + 40.0 / 25, 200000) / G - 1;
  std::cout << "energy relative error: linear " << e_lin << ", exponential " << e_exp << "\n";
  EXPECT_NEAR(e_lin, 0, 1e-3);
  EXPECT_NEAR(e_exp, 0, 1e-3);
}

TEST(Softening, ParametersAreChecked)
{
  EXPECT_THROW(
      LinearSofteningFriction(
          params({{"k", 100}, {"f_t", 1}, {"w_c2", 0.3}, {"f_fr", 2}, {"eta", 0}}), "interface.0."),
      pushout::laws::ParameterError);
  EXPECT_THROW(ExponentialSoftening(
                   params({{"k", 100}, {"f_t", 1}, {"c", 3}, {"f_fr", 1.5}, {"eta", 0}}), "x."),
               pushout::laws::ParameterError);
}

namespace
{
/// FD tangent check at random states of a softening law, away from kinks.
template <typename L> void check_random_tangents(const L& law, double k, double w0, double kink2)
{
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> U(-1, 1);
  const double h = 1e-9;
  double worst = 0;
  int loading = 0, unloading = 0, compressed = 0, tested = 0;
  while (tested < 200)
  {
    const double scale = 4 * w0 * std::abs(U(gen)) + kink2 * std::abs(U(gen));
    const Vec3 w = {scale * U(gen), scale * U(gen), scale * U(gen)};
    // Without viscosity the committed D_v does not enter the update.
    const double kappa = std::abs(U(gen)) * (2 * w0 + kink2);
    const std::vector<double> s0 = history(kappa, 0.0);
    const double delta = CamanhoDavila::equivalent(w);
    const double margin = 1e3 * h;
    if (std::abs(w[0]) < margin || std::abs(delta - kappa) < margin ||
        std::abs(delta - w0) < margin || std::abs(delta - kink2) < margin || delta < margin)
      continue;
    const double err = pushout::testing::tangent_error(law, s0, w, h, k);
    worst = std::max(worst, err);
    EXPECT_LT(err, 1e-6) << "kappa " << kappa << " w " << w[0] << " " << w[1] << " " << w[2];
    ++tested;
    (delta > kappa && delta > w0 ? loading : unloading)++;
    compressed += w[0] < 0;
  }
  std::cout << L::name << ": max FD tangent error " << worst << " over 200 states\n";
  EXPECT_GT(loading, 40);
  EXPECT_GT(unloading, 40);
  EXPECT_GT(compressed, 40);
}
} // namespace

TEST(Softening, TangentsMatchFiniteDifferencesAtRandomStates)
{
  check_random_tangents(linear, 100, 0.01, 0.31);
  check_random_tangents(linear_fr, 100, 0.01, 0.19);
  check_random_tangents(exponential, 1000, 0.003, 0.2);
}

TEST(ViscousDamage, LagsTheRateIndependentDamageAndRecoversItAsEtaVanishes)
{
  // Linear softening, eta = 0.01 mm: one step from 0 to 0.16 mm (D = 0.84
  // rate independent) over dt = 0.01 mm: theta = 1/2, D_v = 0.42.
  Params p{{"k", 100}, {"f_t", 1}, {"w_c2", 0.3}, {"eta", 0.01}};
  const LinearSoftening viscous(p, "");
  std::vector<double> s(LinearSoftening::state_size), s1(s.size()), s0(s.size());
  const auto r = viscous.update(s, {0, 0.16, 0}, s1, {0.01});
  const double D = 1 - 0.5 / (100 * 0.16);
  EXPECT_NEAR(viscous.damage(s1), 0.5 * D, 1e-14);
  EXPECT_NEAR(r.t[1], (1 - 0.5 * D) * 100 * 0.16, 1e-12);
  EXPECT_GT(r.t[1], linear.update(s, {0, 0.16, 0}, s0).t[1]);
  // dt / eta -> infinity: the rate-independent answer.
  EXPECT_NEAR(viscous.update(s, {0, 0.16, 0}, s1, {1e9}).t[1], 0.5, 1e-8);
  // Holding the jump, D_v keeps relaxing towards D and never exceeds it.
  std::vector<double> a = s1;
  for (int i = 0; i < 50; ++i)
  {
    viscous.update(a, {0, 0.16, 0}, s1, {0.01});
    EXPECT_GE(viscous.damage(s1), viscous.damage(a));
    EXPECT_LE(viscous.damage(s1), D + 1e-15);
    a = s1;
  }
  EXPECT_NEAR(viscous.damage(a), D, 1e-12);
}

TEST(ViscousDamage, TangentMatchesFiniteDifferences)
{
  Params p{{"k", 1000}, {"f_t", 3}, {"c", 25}, {"f_fr", 0}, {"eta", 0.005}};
  const ExponentialSoftening law(p, "");
  // The same damage without viscosity, for D(kappa).
  const CamanhoDavila rate_free(1000, Envelope{Envelope::Kind::exponential, 3, 0, 0, 25});
  std::mt19937 gen(9);
  std::uniform_real_distribution<double> U(-1, 1);
  double worst = 0;
  for (int n = 0; n < 100;)
  {
    const Vec3 w = {0.02 * U(gen), 0.05 * U(gen), 0.05 * U(gen)};
    const double kappa = 0.05 * std::abs(U(gen));
    // The committed D_v lags D(kappa): anywhere in [0, D(kappa) / 2].
    const std::vector<double> s0 = history(kappa, 0.5 * std::abs(U(gen)) * rate_free.damage(kappa));
    const double delta = CamanhoDavila::equivalent(w);
    if (std::abs(w[0]) < 1e-6 || std::abs(delta - kappa) < 1e-6 || std::abs(delta - 0.003) < 1e-6)
      continue;
    ++n;
    std::vector<double> s1(s0.size());
    const double dt = 0.001 * std::abs(U(gen)) + 1e-5;
    // tangent_error uses dt = 0; check with dt by hand.
    const auto r = law.update(s0, w, s1, {dt});
    double err = 0;
    for (int j = 0; j < 3; ++j)
    {
      Vec3 wp = w, wm = w;
      wp[j] += 1e-9;
      wm[j] -= 1e-9;
      const Vec3 tp = law.update(s0, wp, s1, {dt}).t, tm = law.update(s0, wm, s1, {dt}).t;
      for (int i = 0; i < 3; ++i)
        err = std::max(err, std::abs((tp[i] - tm[i]) / 2e-9 - r.D[3 * i + j]) / 1000);
    }
    worst = std::max(worst, err);
  }
  std::cout << "viscous exponential_softening: max FD tangent error " << worst << "\n";
  EXPECT_LT(worst, 1e-6);
}

TEST(Envelope, WorkOfAnExponentialWithATinyDecayIsTheStrengthTimesTheOpening)
{
  // c x near or below the round-off of 1: (1 - exp(-c x)) / c would lose
  // every digit (0 from c x < 1e-16 on); the work is f_t x (1 - c x / 2).
  for (const double c : {1e-6, 1e-12, 1e-16, 1e-100})
  {
    const Envelope e{.kind = Envelope::Kind::exponential, .f_t = 3.0, .c = c};
    const double x = 0.2; // [mm]
    EXPECT_NEAR(e.work(0.001 + x, 0.001), 3.0 * x * (1 - c * x / 2), 1e-14) << "c = " << c;
  }
}

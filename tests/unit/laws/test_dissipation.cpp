// The dissipation each law reports from its update (LawResult::dissipation)
// against the energy identity: summed along a monotonic path to full
// separation it is the fracture energy G_F of the law, the area under its
// traction-separation curve; for friction it is mu p times the slip.
#include "laws/CohesiveFriction.h"
#include "laws/ExponentialSoftening.h"
#include "laws/Friction.h"
#include "laws/LawRegistry.h"
#include <cmath>
#include <gtest/gtest.h>
#include <iostream>

using namespace pushout::laws;

namespace
{
/// Sum of the dissipation along w(s) = s * dir, s from 0 to `end` in `n`
/// steps, committing every step.
double dissipated(const InterfaceLaw& law, const Vec3& dir, double end, int n)
{
  std::vector<double> state(law.state_size(), 0.0), trial(state.size());
  double total = 0;
  for (int i = 1; i <= n; ++i)
  {
    const double s = end * i / n;
    total += law.update(state, {s * dir[0], s * dir[1], s * dir[2]}, trial, {}).dissipation;
    state = trial;
  }
  return total;
}

std::unique_ptr<InterfaceLaw> make(const std::string& name, const Params& set)
{
  const LawInfo* info = find_law(name);
  Params p;
  for (const ParamDef& d : info->params)
    if (d.default_value)
      p[d.name] = *d.default_value;
  for (const auto& [k, v] : set)
    p[k] = v;
  return info->make(p, "interface.0.");
}
} // namespace

TEST(Dissipation, ExponentialSofteningReleasesItsFractureEnergy)
{
  // G_F = f_t^2 / (2 k) + f_t / c (f_fr = 0): 0.0045 + 0.12 N/mm.
  const auto law = make("exponential_softening", {{"k", 1000.0}, {"f_t", 3.0}, {"c", 25.0}});
  const double G_F = 3.0 * 3.0 / 2000 + 3.0 / 25;
  EXPECT_NEAR(law->fracture_energy(), G_F, 1e-15);
  for (const Vec3 dir : {Vec3{1, 0, 0}, Vec3{0, 0.6, 0.8}, Vec3{0.6, 0.8, 0}})
  {
    const double total = dissipated(*law, dir, 1.5, 20000); // exp(-25 * 1.5): separated
    std::cout << "exponential_softening along (" << dir[0] << ", " << dir[1] << ", " << dir[2]
              << "): dissipated / G_F = " << total / G_F << "\n";
    EXPECT_NEAR(total / G_F, 1.0, 1e-4) << "direction " << dir[0] << " " << dir[1];
  }
}

TEST(Dissipation, LinearSofteningReleasesItsFractureEnergy)
{
  // G_F = f_t^2 / (2 k) + f_t w_c2 / 2 = 0.005 + 0.15 N/mm.
  const auto law = make("linear_softening", {{"k", 100.0}, {"f_t", 1.0}, {"w_c2", 0.3}});
  const double G_F = 1.0 / 200 + 0.3 / 2;
  EXPECT_NEAR(law->fracture_energy(), G_F, 1e-15);
  const double ratio = dissipated(*law, {1, 0, 0}, 0.4, 20000) / G_F;
  std::cout << "linear_softening: dissipated / G_F = " << ratio << "\n";
  EXPECT_NEAR(ratio, 1.0, 1e-4);
}

TEST(Dissipation, NothingIsDissipatedElasticallyOrOnUnloading)
{
  const auto law = make("exponential_softening", {{"k", 1000.0}, {"f_t", 3.0}, {"c", 25.0}});
  EXPECT_DOUBLE_EQ(dissipated(*law, {1, 0, 0}, 0.002, 100), 0.0); // below w0 = 0.003
  std::vector<double> s0(law->state_size(), 0.0), s1(s0.size()), s2(s0.size());
  law->update(s0, {0.05, 0, 0}, s1, {});
  EXPECT_DOUBLE_EQ(law->update(s1, {0.02, 0, 0}, s2, {}).dissipation, 0.0); // secant unloading
}

TEST(Dissipation, ADamageLawsStepDissipatesExactlyWhateverItsSize)
{
  // Each step's dissipation is the softening's energy between its histories,
  // 1/2 f_t w0 + int_w0^kappa sigma - 1/2 sigma(kappa) kappa: in one step
  // or in two, to round-off (a trapezoid of kappa^2 over the step gave 2.7
  // times the first one below, and 65 times G_F for the linear law in one
  // step). Exponential: k 1000, f_t 3, c 25, w0 0.003 mm.
  const auto exponential =
      make("exponential_softening", {{"k", 1000.0}, {"f_t", 3.0}, {"c", 25.0}});
  const double w0 = 0.003;
  const auto softened = [&](double kappa)
  {
    const double x = kappa - w0, sigma = 3.0 * std::exp(-25 * x);
    return 0.5 * 3.0 * w0 + 3.0 * (1 - std::exp(-25 * x)) / 25 - 0.5 * sigma * kappa;
  };
  for (const Vec3 dir : {Vec3{1, 0, 0}, Vec3{0, 0.6, 0.8}})
  {
    std::vector<double> s0(exponential->state_size(), 0.0), s1(s0.size()), s2(s0.size());
    const double one =
        exponential->update(s0, {0.0155 * dir[0], 0.0155 * dir[1], 0.0155 * dir[2]}, s1, {})
            .dissipation;
    EXPECT_NEAR(one, softened(0.0155), 1e-12) << "0 -> 0.0155 mm in one step";
    const double two =
        exponential->update(s1, {0.03 * dir[0], 0.03 * dir[1], 0.03 * dir[2]}, s2, {}).dissipation;
    EXPECT_NEAR(two, softened(0.03) - softened(0.0155), 1e-12) << "0.0155 -> 0.03 mm";
  }
  // Linear (k 1000, f_t 3, w_c2 0.1: separated at 0.103 mm): G_F = 0.1545
  // N/mm in two steps, and in one step past separation.
  const auto linear = make("linear_softening", {{"k", 1000.0}, {"f_t", 3.0}, {"w_c2", 0.1}});
  const double G_F = 0.5 * 3.0 * w0 + 0.5 * 3.0 * 0.1;
  EXPECT_NEAR(dissipated(*linear, {1, 0, 0}, 0.106, 2), G_F, 1e-12) << "two steps";
  EXPECT_NEAR(dissipated(*linear, {1, 0, 0}, 0.2, 1), G_F, 1e-12) << "one step past separation";
}

TEST(Dissipation, FrictionDissipatesMuPTimesTheSlip)
{
  // k 1000, mu 0.4, w_n = -0.001: p = 1 MPa, sliding from u = 0.0004 mm on.
  const Friction law(1000.0, 0.4);
  std::vector<double> state(Friction::state_size, 0.0), trial(state.size());
  double total = 0;
  const int n = 1000;
  for (int i = 1; i <= n; ++i)
  {
    total += law.update(state, {-0.001, 0.01 * i / n, 0}, trial).dissipation;
    state = trial;
  }
  EXPECT_NEAR(total, 0.4 * 1.0 * (0.01 - 0.4 / 1000), 1e-12);
}

TEST(Dissipation, CohesiveFrictionInOpeningIsItsEnvelopesFractureEnergy)
{
  const auto law = make("cohesive_friction", {{"k", 1000.0}, {"f_t", 3.0}, {"c", 25.0}});
  const double G_F = 3.0 * 3.0 / 2000 + 3.0 / 25;
  EXPECT_NEAR(law->fracture_energy(), G_F, 1e-15);
  const double ratio = dissipated(*law, {1, 0, 0}, 1.5, 20000) / G_F;
  std::cout << "cohesive_friction: dissipated / G_F = " << ratio << "\n";
  EXPECT_NEAR(ratio, 1.0, 1e-4);
}

TEST(Dissipation, FractureEnergyOfAResidualLawCountsOnlyTheSofteningAndNonSofteningLawsHaveNone)
{
  // linear_softening_friction: f_t 2, f_fr 0.5, w_c2 0.4, k 100: the linear
  // branch meets f_fr at w0 + 0.3; released f_t^2/(2k) + (f_t - f_fr) 0.3 / 2.
  const auto law =
      make("linear_softening_friction", {{"k", 100.0}, {"f_t", 2.0}, {"f_fr", 0.5}, {"w_c2", 0.4}});
  EXPECT_NEAR(law->fracture_energy(), 4.0 / 200 + 1.5 * 0.3 / 2, 1e-15);
  // Opened to w_end on the plateau, the work int sigma dw = G + f_fr (w_end -
  // w0) is dissipated but for the free energy f_fr w_end / 2 the secant
  // stores: dissipated = G + f_fr (w_end / 2 - w0).
  const double w_end = 1.0, w0 = 0.02, f_fr = 0.5;
  const double plateau = f_fr * (w_end / 2 - w0);
  EXPECT_NEAR((dissipated(*law, {1, 0, 0}, w_end, 20000) - plateau) / law->fracture_energy(), 1.0,
              1e-4);
  for (const char* name : {"elastic", "friction"})
    EXPECT_EQ(make(name, {{"k_n", 1000.0}, {"k_s", 1000.0}})->fracture_energy(), 0.0) << name;
}

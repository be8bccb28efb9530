// The crack band of concrete at one point (bulk/CrackBand.h) along
// prescribed strain paths: onset at f_t, softening on the cohesive law's
// envelope, G_F per unit crack area whatever the band width, unloading and
// reclosure, rotated loadings, and the consistent tangent against finite
// differences.
#include "bulk/CrackBand.h"
#include <cmath>
#include <gtest/gtest.h>
#include <iostream>
#include <random>

using pushout::bulk::CrackBand;
using pushout::bulk::CrackBandResult;
using pushout::bulk::Mat3;
using pushout::bulk::SecantOperator;
using pushout::bulk::Vec3;
using pushout::bulk::Voigt;
using pushout::laws::Envelope;

namespace
{
// Concrete of the scenes (MPa) and the default cracking law: exponential
// softening f_t 3 MPa, c 30 1/mm (G_F = f_t / c = 0.1 N/mm).
constexpr double E = 30000, nu = 0.2, f_t = 3, c = 30;
const Envelope exponential = {Envelope::Kind::exponential, f_t, 0.0, 0.0, c};
const Envelope linear = {Envelope::Kind::linear, f_t, 0.1, 0.0, 0.0};
constexpr double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));

using State = std::vector<double>;

/// A path of strains from the committed state, committing every step.
struct Path
{
  const CrackBand& law;
  double h; // band width [mm]
  State state = State(CrackBand::state_size, 0.0);
  double dissipated = 0, work = 0; // per unit volume [N mm/mm^3]
  Voigt strain{}, stress{};

  CrackBandResult step(const Voigt& to)
  {
    State trial(state.size());
    const CrackBandResult r = law.update(state, to, trial, [&](const Vec3&) { return h; });
    EXPECT_EQ(r.status, CrackBandResult::Status::ok);
    for (int i = 0; i < 6; ++i)
      work += 0.5 * (stress[i] + r.stress[i]) * (to[i] - strain[i]);
    dissipated += r.dissipation;
    state = trial;
    strain = to;
    stress = r.stress;
    return r;
  }
};

/// Q diag-strain Q^T for a rotation Q (rows), in Voigt form.
Voigt rotated(const Mat3& Q, const Voigt& e)
{
  const Mat3 T = {e[0], e[5] / 2, e[4] / 2, e[5] / 2, e[1], e[3] / 2, e[4] / 2, e[3] / 2, e[2]};
  Mat3 out{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          out[3 * i + j] += Q[3 * a + i] * T[3 * a + b] * Q[3 * b + j];
  return {out[0], out[4], out[8], 2 * out[5], 2 * out[2], 2 * out[1]};
}

Mat3 random_rotation(std::mt19937& gen)
{
  std::normal_distribution<double> N;
  const double q0 = N(gen), q1 = N(gen), q2 = N(gen), q3 = N(gen);
  const double s = 1 / std::sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3);
  const double a = q0 * s, b = q1 * s, cq = q2 * s, d = q3 * s;
  return {a * a + b * b - cq * cq - d * d,
          2 * (b * cq - a * d),
          2 * (b * d + a * cq),
          2 * (b * cq + a * d),
          a * a - b * b + cq * cq - d * d,
          2 * (cq * d - a * b),
          2 * (b * d - a * cq),
          2 * (cq * d + a * b),
          a * a - b * b - cq * cq + d * d};
}
} // namespace

TEST(SymmetricEigen, ValuesDescendingVectorsOrthonormal)
{
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> U(-1, 1);
  for (int trial = 0; trial < 100; ++trial)
  {
    const Mat3 A = {U(gen), 0, 0, 0, U(gen), 0, 0, 0, U(gen)};
    Mat3 S = A;
    S[1] = S[3] = U(gen);
    S[2] = S[6] = U(gen);
    S[5] = S[7] = U(gen);
    Vec3 values;
    Mat3 V;
    pushout::bulk::symmetric_eigen(S, values, V);
    EXPECT_GE(values[0], values[1]);
    EXPECT_GE(values[1], values[2]);
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i)
      {
        double Sv = 0;
        for (int j = 0; j < 3; ++j)
          Sv += S[3 * i + j] * V[3 * k + j];
        EXPECT_NEAR(Sv, values[k] * V[3 * k + i], 1e-12);
      }
    const double det = V[0] * (V[4] * V[8] - V[5] * V[7]) - V[1] * (V[3] * V[8] - V[5] * V[6]) +
                       V[2] * (V[3] * V[7] - V[4] * V[6]);
    EXPECT_NEAR(det, 1.0, 1e-12);
  }
}

TEST(CrackBand, ElasticUntilTheLargestPrincipalStressReachesFt)
{
  const CrackBand law(E, nu, exponential);
  Path path{law, 2.0};
  // Uniaxial strain along x: sigma_xx = (lambda + 2 mu) eps is the largest
  // principal stress, f_t at eps_cr.
  const double eps_cr = f_t / (lambda + 2 * mu);
  path.step({0.999 * eps_cr, 0, 0, 0, 0, 0});
  EXPECT_EQ(path.state[0], 0.0) << "uncracked below f_t";
  EXPECT_NEAR(path.stress[0], 0.999 * f_t, 1e-12);
  EXPECT_NEAR(path.stress[1], lambda * 0.999 * eps_cr, 1e-12);
  const CrackBandResult r = path.step({1.01 * eps_cr, 0, 0, 0, 0, 0});
  EXPECT_EQ(path.state[0], 1.0) << "cracked past f_t";
  EXPECT_NEAR(std::abs(path.state[1]), 1.0, 1e-12) << "normal along x";
  EXPECT_EQ(path.state[7], 2.0) << "band width stored";
  // In the step that cracks it, the crack takes up the excess strain (the
  // elastic stress would be 1.01 f_t): sigma = f_t exp(-c (w - w0)) with
  // w <= (0.01 + c w) eps_cr h, so f_t >= sigma >= f_t (1 - c 0.011 eps_cr h).
  EXPECT_LE(r.stress[0], f_t * (1 + 1e-12));
  EXPECT_GE(r.stress[0], f_t * (1 - c * 0.011 * eps_cr * 2.0));
  EXPECT_GT(r.opening[0], 0.0);
}

TEST(CrackBand, SoftensOnTheEnvelopeAndDissipatesGfPerCrackAreaWhateverTheBand)
{
  for (const Envelope& env : {exponential, linear})
    for (double h : {0.5, 2.0, 8.0})
    {
      SCOPED_TRACE("h = " + std::to_string(h) +
                   (env.kind == Envelope::Kind::linear ? " linear" : " exponential"));
      const CrackBand law(E, nu, env);
      const pushout::laws::CamanhoDavila cohesive = law.cohesive_law(h);
      Path path{law, h};
      // To an opening of 0.6 mm (exp(-18) of f_t; the linear law ends at
      // 0.1 mm) in steps of 0.1 um of opening.
      const double eps_end = 0.6 / h;
      const int steps = 6000;
      double worst = 0;
      for (int i = 1; i <= steps; ++i)
      {
        const CrackBandResult r = path.step({eps_end * i / steps, 0, 0, 0, 0, 0});
        if (r.opening[0] > 10 * cohesive.w0())
        {
          // On the envelope: the traction across the crack is sigma(w).
          const double expected =
              env.kind == Envelope::Kind::exponential
                  ? f_t * std::exp(-c * (r.opening[0] - cohesive.w0()))
                  : std::max(f_t * (1 - (r.opening[0] - cohesive.w0()) / 0.1), 0.0);
          worst = std::max(worst, std::abs(r.stress[0] - expected));
        }
      }
      EXPECT_LT(worst, 1e-9 * f_t) << "sigma_xx on the envelope";
      // The energy per unit crack area: dissipation density times h.
      const double G_F = cohesive.fracture_energy();
      EXPECT_NEAR(path.dissipated * h, G_F, 0.01 * G_F);
      EXPECT_NEAR(path.work * h, G_F, 0.01 * G_F) << "the work done is all dissipated";
      std::cout << "h = " << h << " mm: G_F " << G_F << " N/mm, dissipated " << path.dissipated * h
                << ", work " << path.work * h << "\n";
    }
}

TEST(CrackBand, UnloadsSecantToTheOriginAndRecloses)
{
  const CrackBand law(E, nu, exponential);
  const double h = 2.0;
  Path path{law, h};
  const double eps = 0.02 / h; // an opening of about 0.02 mm: damage well past the peak
  const CrackBandResult peak = path.step({eps, 0, 0, 0, 0, 0});
  const double D = peak.damage;
  EXPECT_GT(D, 0.4);
  // Half the strain back: the crack closes along its secant, damage kept.
  const CrackBandResult half = path.step({eps / 2, 0, 0, 0, 0, 0});
  EXPECT_EQ(half.damage, D);
  EXPECT_GT(half.stress[0], 0);
  EXPECT_LT(half.stress[0], peak.stress[0]);
  EXPECT_NEAR(half.stress[0] / half.opening[0], peak.stress[0] / peak.opening[0],
              1e-9 * peak.stress[0] / peak.opening[0])
      << "secant stiffness of the crack unchanged";
  // Back to zero strain: no stress, the crack shut.
  const CrackBandResult zero = path.step({0, 0, 0, 0, 0, 0});
  EXPECT_NEAR(zero.stress[0], 0.0, 1e-12);
  EXPECT_NEAR(zero.opening[0], 0.0, 1e-15);
  // Compression: the closed crack carries it by its penalty (stiffness
  // within 1e-3 of the elastic).
  const CrackBandResult press = path.step({-1e-4, 0, 0, 0, 0, 0});
  EXPECT_NEAR(press.stress[0], -(lambda + 2 * mu) * 1e-4, 2e-3 * (lambda + 2 * mu) * 1e-4);
  // Reload to the old strain: back on the old point, no new dissipation.
  const double before = path.dissipated;
  const CrackBandResult again = path.step({eps, 0, 0, 0, 0, 0});
  EXPECT_NEAR(again.stress[0], peak.stress[0], 1e-9 * f_t);
  EXPECT_NEAR(path.dissipated, before, 1e-12);
}

TEST(CrackBand, RotatedLoadingsCrackAlongTheRotatedPrincipalDirection)
{
  const CrackBand law(E, nu, exponential);
  std::mt19937 gen(5);
  for (int trial = 0; trial < 20; ++trial)
  {
    const Mat3 Q = random_rotation(gen);
    Path plain{law, 2.0}, turned{law, 2.0};
    // Tension along x with some lateral contraction: x is the largest
    // principal direction.
    for (double e : {1e-4, 2e-4, 1e-3, 5e-3})
    {
      const Voigt strain = {e, -0.1 * e, -0.2 * e, 0, 0, 0};
      const CrackBandResult a = plain.step(strain);
      const CrackBandResult b = turned.step(rotated(Q, strain));
      EXPECT_NEAR(a.opening[0], b.opening[0], 1e-12);
      EXPECT_NEAR(a.damage, b.damage, 1e-12);
      // The stress turns with the strain.
      const Voigt expected = rotated(Q, {a.stress[0], a.stress[1], a.stress[2], 2 * a.stress[3],
                                         2 * a.stress[4], 2 * a.stress[5]});
      for (int i = 0; i < 6; ++i)
        EXPECT_NEAR(b.stress[i], i < 3 ? expected[i] : expected[i] / 2, 1e-9 * f_t);
    }
    // The crack normal is Q^T e_x (the image of x), either sign.
    const Vec3 n = {turned.state[1], turned.state[2], turned.state[3]};
    const double along = n[0] * Q[0] + n[1] * Q[1] + n[2] * Q[2];
    EXPECT_NEAR(std::abs(along), 1.0, 1e-12);
  }
}

// The principal axes turn after the crack opened (a fixed crack under a
// growing shear, as Willam's test): the normal stays that of the onset, the
// crack slides and softens further in mixed mode, and over the closed path
// back to zero strain the work done is what was dissipated (the trapezoid
// rule's error on 3000 steps: far below 1 %): G_F per unit crack area, less
// what is left of its envelope, once it has slid through it.
TEST(CrackBand, AFixedCrackUnderTurningAxesDissipatesGf)
{
  const CrackBand law(E, nu, exponential);
  const double h = 2.0;
  const pushout::laws::CamanhoDavila cohesive = law.cohesive_law(h);
  const double eps_cr = f_t / (lambda + 2 * mu);
  Path path{law, h};
  const int steps = 1000;
  const auto ramp = [&](const Voigt& from, const Voigt& to)
  {
    for (int i = 1; i <= steps; ++i)
    {
      Voigt e;
      for (int k = 0; k < 6; ++k)
        e[k] = from[k] + (to[k] - from[k]) * i / steps;
      path.step(e);
    }
  };
  const Voigt opened = {2 * eps_cr, 0, 0, 0, 0, 0};
  ramp({}, opened); // a crack normal to x, just past the peak
  const Vec3 n0 = {path.state[1], path.state[2], path.state[3]};
  ASSERT_NEAR(std::abs(n0[0]), 1.0, 1e-12);
  const double after_opening = path.dissipated;
  // Shear xy growing to 0.1 (a slide of 0.2 mm: past the envelope's end,
  // exp(-6)) with the normal strain held: the principal axes turn towards
  // 45 degrees.
  const Voigt sheared = {2 * eps_cr, 0, 0, 0, 0, 0.1};
  ramp(opened, sheared);
  EXPECT_EQ(path.state[1], n0[0]);
  EXPECT_EQ(path.state[2], n0[1]);
  EXPECT_EQ(path.state[3], n0[2]);
  EXPECT_GT(path.dissipated, 1.01 * after_opening) << "the crack slides and softens further";
  EXPECT_LT(std::abs(path.stress[5]), 0.01 * f_t) << "the crack slid through its envelope";
  // Back to zero strain: nothing stored, the work all dissipated.
  ramp(sheared, {});
  EXPECT_NEAR(path.stress[0], 0.0, 1e-9 * f_t);
  EXPECT_NEAR(path.work, path.dissipated, 0.01 * path.dissipated);
  // Slid through in mixed mode (the envelope is one in the equivalent jump
  // delta, here the slide 0.1 h, the opening 1e-3 of it): G_F less what is
  // left of the envelope past delta and the crack's secant energy at delta,
  // which the unloading gave back (1 % of G_F together). 1e-3 of G_F: the
  // opening left out, and the trapezoid rule.
  const double G_F = cohesive.fracture_energy(), delta = 0.1 * h;
  const double left = f_t * std::exp(-c * (delta - cohesive.w0())); // sigma(delta) [MPa]
  EXPECT_NEAR(path.dissipated * h, G_F - left / c - 0.5 * left * delta, 1e-3 * G_F);
  std::cout << "turning axes: dissipated " << after_opening * h << " N/mm opening, "
            << path.dissipated * h << " N/mm in all (G_F " << G_F << "), work " << path.work * h
            << " N/mm\n";
}

TEST(CrackBand, TangentMatchesFiniteDifferences)
{
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> U(-1, 1);
  const double h = 2.0;
  int cracked = 0, uncracked = 0, softened = 0;
  double worst = 0;
  // Near the onset, and far into the softening (a first tension up to 0.06:
  // openings to 0.12 mm, c w up to 3.6 on the exponential envelope, past
  // w_c on the linear one), on both envelopes.
  for (int trial = 0; trial < 600; ++trial)
  {
    const Envelope& env = trial % 2 ? linear : exponential;
    const double reach = trial % 4 < 2 ? 2e-4 : 3e-2;
    const CrackBand law(E, nu, env);
    // A committed state from a random tension past the onset (or not),
    // then a random strain from there: loading, unloading, closure, shear.
    Path path{law, h};
    const Voigt first = {reach * (U(gen) + 1), 1e-4 * U(gen), 1e-4 * U(gen),
                         1e-4 * U(gen),        1e-4 * U(gen), 1e-4 * U(gen)};
    path.step(first);
    Voigt strain;
    for (int i = 0; i < 6; ++i)
      strain[i] = first[i] + (path.state[0] != 0 ? 3e-4 : 3e-5) * U(gen);
    State trial_state(path.state.size());
    const auto width = [&](const Vec3&) { return h; };
    const CrackBandResult r = law.update(path.state, strain, trial_state, width);
    ASSERT_EQ(r.status, CrackBandResult::Status::ok);
    // The step that inserts a crack takes its normal from the trial strain,
    // and its tangent holds that normal fixed (a fixed crack): it is not
    // the derivative there, by design, and is left out.
    if (path.state[0] == 0 && trial_state[0] != 0)
      continue;
    (path.state[0] != 0 ? cracked : uncracked)++;
    softened += path.state[8] > 1 / c; // kappa: c w past 1 (the linear law: a third of w_c)
    // 5e-6 of the strains' scale: below it, the crack's local equilibrium
    // (solved to its tolerance) shows in the differences of the large strains.
    const double step = 5e-6 * reach;
    for (int j = 0; j < 6; ++j)
    {
      Voigt plus = strain, minus = strain;
      plus[j] += step;
      minus[j] -= step;
      const CrackBandResult rp = law.update(path.state, plus, trial_state, width);
      const CrackBandResult rm = law.update(path.state, minus, trial_state, width);
      for (int i = 0; i < 6; ++i)
      {
        const double fd = (rp.stress[i] - rm.stress[i]) / (2 * step);
        worst = std::max(worst, std::abs(fd - r.tangent[6 * i + j]) / (lambda + 2 * mu));
      }
    }
  }
  std::cout << "crack band: max FD tangent error " << worst << " of lambda + 2 mu over " << cracked
            << " cracked (" << softened << " far into the softening) and " << uncracked
            << " uncracked states\n";
  EXPECT_GT(cracked, 100);
  EXPECT_GT(softened, 50);
  EXPECT_GT(uncracked, 10);
  // Central differences of steps of 5e-6 of the strains: truncation and
  // round-off about 1e-6 of the stiffness, except where a step crosses a
  // kink of the law (onset, loading/unloading), which random states hit
  // with probability ~1e-5.
  EXPECT_LT(worst, 1e-5);
}

TEST(CrackBand, ABandWiderThanTheSizeConditionIsRefused)
{
  const CrackBand law(E, nu, exponential);
  // mu / (c f_t) = 12500 / 90 mm.
  EXPECT_NEAR(law.max_band_width(), mu / (c * f_t), 1e-9);
  std::vector<double> s(CrackBand::state_size, 0.0), t(s.size());
  const auto wide = [&](const Vec3&) { return 1.01 * mu / (c * f_t); };
  const CrackBandResult r = law.update(s, {1e-3, 0, 0, 0, 0, 0}, t, wide);
  EXPECT_EQ(r.status, CrackBandResult::Status::band_too_wide);
}

// IMPL-EX's response (CrackBand::secant_response): a crack holding the
// damage of a given history is a secant spring. At the committed history it
// is what update() gives wherever update() unloads or recloses; a longer
// history softens it; an uncracked point stays elastic; the stress is
// linear in the strain on either side of closure, and the tangent is its
// derivative and symmetric.
TEST(CrackBand, SecantResponseIsUpdatesUnloadingBranchWithTheHistoryHeld)
{
  const CrackBand law(E, nu, exponential);
  const double h = 2.0;
  const auto width = [&](const Vec3&) { return h; };
  Path path{law, h};
  const double onset = f_t / (lambda + 2 * mu); // uniaxial strain at f_t
  for (int k = 1; k <= 12; ++k)
    path.step({k * 0.5 * onset, 0, 0, 0, 0, 0});
  ASSERT_NE(path.state[0], 0.0);
  const double kappa = path.state[8];
  ASSERT_GT(kappa, 0.0);
  State trial(path.state.size());
  // Unloading, reclosure and shear from the committed state: update() runs
  // secant (no history grows), and so does secant_response at kappa.
  const std::vector<Voigt> strains = {{3 * onset, 0, 0, 0, 0, 0},
                                      {1.5 * onset, 0.2 * onset, 0, 0, 0.3 * onset, 0},
                                      {-2 * onset, 0, 0, 0, 0, 0},
                                      {-0.5 * onset, 0.1 * onset, 0, 0, 0, 0.2 * onset}};
  for (const Voigt& strain : strains)
  {
    const CrackBandResult implicit = law.update(path.state, strain, trial, width);
    ASSERT_EQ(implicit.status, CrackBandResult::Status::ok);
    ASSERT_NEAR(trial[8], kappa, 1e-15); // it did not load
    const CrackBandResult secant = law.secant_response(path.state, strain, kappa);
    ASSERT_EQ(secant.status, CrackBandResult::Status::ok);
    for (int i = 0; i < 6; ++i)
      EXPECT_NEAR(secant.stress[i], implicit.stress[i], 1e-9 * f_t);
    for (int i = 0; i < 36; ++i)
      EXPECT_NEAR(secant.tangent[i], implicit.tangent[i], 1e-9 * (lambda + 2 * mu));
    EXPECT_DOUBLE_EQ(secant.dissipation, 0.0);
  }
  // A longer history softens the crack: less tension at the same strain.
  const Voigt pulled = {3 * onset, 0, 0, 0, 0, 0};
  const double held = law.secant_response(path.state, pulled, kappa).stress[0];
  const double extrapolated = law.secant_response(path.state, pulled, 2 * kappa).stress[0];
  EXPECT_LT(extrapolated, held);
  EXPECT_GT(extrapolated, 0.0);
  // A history shorter than the committed one is the committed one.
  EXPECT_DOUBLE_EQ(law.secant_response(path.state, pulled, 0.5 * kappa).stress[0], held);
  // An uncracked point is elastic whatever its stress (onset comes after
  // the step, from update()).
  const State virgin(CrackBand::state_size, 0.0);
  const CrackBandResult elastic = law.secant_response(virgin, {10 * onset, 0, 0, 0, 0, 0}, 0.0);
  EXPECT_NEAR(elastic.stress[0], 10 * f_t, 1e-9 * f_t);
}

TEST(CrackBand, SecantResponseIsLinearEachSideOfClosureWithSymmetricTangent)
{
  const CrackBand law(E, nu, exponential);
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> U(-1, 1);
  const double h = 2.0;
  double worst_fd = 0, worst_symmetry = 0, worst_linear = 0;
  int tried = 0;
  for (int trial = 0; trial < 200; ++trial)
  {
    Path path{law, h};
    path.step({2e-4 * (U(gen) + 1.5), 1e-4 * U(gen), 1e-4 * U(gen), 1e-4 * U(gen), 1e-4 * U(gen),
               1e-4 * U(gen)});
    if (path.state[0] == 0)
      continue;
    ++tried;
    const double kappa = path.state[8] * (1 + U(gen) + 1); // extrapolated: 1 to 3 times
    Voigt strain;
    for (int i = 0; i < 6; ++i)
      strain[i] = 3e-4 * U(gen);
    const CrackBandResult r = law.secant_response(path.state, strain, kappa);
    ASSERT_EQ(r.status, CrackBandResult::Status::ok);
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
        worst_symmetry =
            std::max(worst_symmetry,
                     std::abs(r.tangent[6 * i + j] - r.tangent[6 * j + i]) / (lambda + 2 * mu));
    const double step = 1e-9;
    for (int j = 0; j < 6; ++j)
    {
      Voigt plus = strain, minus = strain;
      plus[j] += step;
      minus[j] -= step;
      const CrackBandResult rp = law.secant_response(path.state, plus, kappa);
      const CrackBandResult rm = law.secant_response(path.state, minus, kappa);
      for (int i = 0; i < 6; ++i)
        worst_fd = std::max(
            worst_fd, std::abs((rp.stress[i] - rm.stress[i]) / (2 * step) - r.tangent[6 * i + j]) /
                          (lambda + 2 * mu));
    }
    // Linear: the stress at a strain scaled by 2 (the same side of closure)
    // is twice the stress.
    Voigt doubled;
    for (int i = 0; i < 6; ++i)
      doubled[i] = 2 * strain[i];
    const CrackBandResult r2 = law.secant_response(path.state, doubled, kappa);
    for (int i = 0; i < 6; ++i)
      worst_linear = std::max(worst_linear, std::abs(r2.stress[i] - 2 * r.stress[i]) / f_t);
  }
  EXPECT_GT(tried, 100);
  // Central differences of a piecewise linear map: round-off only, except
  // at the closure kink (w . n = 0), which random strains hit with
  // probability ~1e-5.
  EXPECT_LT(worst_fd, 1e-6);
  // J and the tangent are symmetric up to the round-off of their sums.
  EXPECT_LT(worst_symmetry, 1e-12);
  EXPECT_LT(worst_linear, 1e-10);
}

// IMPL-EX's evaluations within a step (BulkCracking::evaluate): the secant
// response as linear maps computed once (CrackBand::secant_operator) and
// applied at each strain (secant_apply) is secant_response itself, on
// either side of closure, to the round-off of the different sums. One
// operator is written over and over, as BulkCracking keeps one per point:
// nothing of an earlier state may stay in it.
TEST(CrackBand, SecantOperatorAppliedIsTheSecantResponse)
{
  const CrackBand law(E, nu, exponential);
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> U(-1, 1);
  double worst_stress = 0, worst_tangent = 0;
  int tried = 0, closed = 0, open = 0;
  SecantOperator op;
  for (int trial = 0; trial < 200; ++trial)
  {
    Path path{law, 2.0};
    path.step({2e-4 * (U(gen) + 1.5), 1e-4 * U(gen), 1e-4 * U(gen), 1e-4 * U(gen), 1e-4 * U(gen),
               1e-4 * U(gen)});
    const double kappa = path.state[8] * (2 + U(gen));
    law.secant_operator(path.state, kappa, 1, op);
    EXPECT_EQ(op.cracked, path.state[0] != 0);
    ++tried;
    for (int k = 0; k < 5; ++k)
    {
      Voigt strain;
      for (int i = 0; i < 6; ++i)
        strain[i] = 3e-4 * U(gen);
      const CrackBandResult direct = law.secant_response(path.state, strain, kappa);
      const CrackBandResult applied = law.secant_apply(op, strain);
      ASSERT_EQ(applied.status, direct.status);
      // The side that BulkCracking::evaluate reads without the result.
      const int side = CrackBand::secant_side(op, strain);
      EXPECT_EQ(side == CrackBand::secant_failed, direct.status != CrackBandResult::Status::ok);
      EXPECT_EQ(side == CrackBand::secant_elastic, !op.cracked);
      EXPECT_EQ(side == CrackBand::secant_closed, direct.closed);
      EXPECT_EQ(applied.closed, direct.closed);
      (direct.closed ? closed : open) += op.cracked;
      EXPECT_DOUBLE_EQ(applied.damage, direct.damage);
      for (int i = 0; i < 6; ++i)
        worst_stress = std::max(worst_stress, std::abs(applied.stress[i] - direct.stress[i]) / f_t);
      for (int i = 0; i < 36; ++i)
        worst_tangent = std::max(worst_tangent, std::abs(applied.tangent[i] - direct.tangent[i]) /
                                                    (lambda + 2 * mu));
    }
  }
  EXPECT_EQ(tried, 200);
  EXPECT_GT(closed, 50); // both sides of closure were met
  EXPECT_GT(open, 50);
  EXPECT_LT(worst_stress, 1e-10);
  EXPECT_LT(worst_tangent, 1e-12);
}

// An undamaged crack (its history at most w0: the secant is the penalty)
// has one map on both sides of closure. secant_response() calls it open
// whatever the strain; the side BulkCracking::evaluate reads must too, or a
// sign change of its opening would count as a crack that opens or closes
// and its cells' tangent would be assembled again for nothing.
TEST(CrackBand, AnUndamagedCrackIsOpenOnBothSides)
{
  const CrackBand law(E, nu, exponential);
  Path path{law, 2.0};
  path.step({3e-4, 0, 0, 0, 0, 0}); // a crack normal to x
  ASSERT_NE(path.state[0], 0);
  State undamaged = path.state;
  undamaged[8] = 0; // its history kappa: none
  SecantOperator op;
  law.secant_operator(undamaged, 0, 1, op);
  ASSERT_EQ(op.damage, 0);
  for (const double e_xx : {1e-4, -1e-4}) // opening, then closing the crack
  {
    const Voigt strain = {e_xx, 0, 0, 0, 0, 0};
    const CrackBandResult direct = law.secant_response(undamaged, strain, 0);
    ASSERT_EQ(direct.status, CrackBandResult::Status::ok);
    EXPECT_FALSE(direct.closed) << e_xx;
    EXPECT_EQ(CrackBand::secant_side(op, strain), CrackBand::secant_open) << e_xx;
    EXPECT_FALSE(law.secant_apply(op, strain).closed) << e_xx;
    // The elastic response either way: no damage, the penalty both sides.
    EXPECT_NEAR(direct.stress[0], law.secant_apply(op, strain).stress[0], 1e-12 * E * 1e-4);
  }
}

// A point's operator is kept where it holds the maps of the same crack at
// the same history and strength (SecantOperator::made_of), and made again
// wherever one of them changed: over a sequence that returns to earlier
// inputs, the kept operator is always the one made afresh, to the bit.
TEST(CrackBand, SecantOperatorKeptOnlyForTheSameInputs)
{
  const CrackBand law(E, nu, exponential);
  Path a{law, 2.0}, b{law, 1.5};
  a.step({3e-4, 0, 0, 0, 0, 0});    // normal along x
  b.step({0, 3e-4, 0, 2e-5, 0, 0}); // normal near y, another band width
  ASSERT_TRUE(a.state[0] != 0 && b.state[0] != 0);
  const State uncracked(CrackBand::state_size, 0.0);
  const double ka = a.state[8], kb = b.state[8];
  // a's crack with one input changed at a time: the normal turned about s1,
  // s1 turned about the normal (the frame stays orthonormal; the maps do
  // not depend on s1, so they may be kept), the band width (state: flag, n
  // at 1-3, s1 at 4-6, h at 7).
  const auto turned = [](const State& s, int axis, int moved)
  {
    State t = s;
    const double c = std::cos(0.1), si = std::sin(0.1);
    Vec3 k{s[std::size_t(axis)], s[std::size_t(axis) + 1], s[std::size_t(axis) + 2]};
    for (int i = 0; i < 3; ++i)
    {
      const double v = s[std::size_t(moved + i)];
      // v turned about k (k . v = 0): v c + (k x v) sin
      const int j = (i + 1) % 3, l = (i + 2) % 3;
      const double kxv = k[std::size_t(j)] * s[std::size_t(moved + l)] -
                         k[std::size_t(l)] * s[std::size_t(moved + j)];
      t[std::size_t(moved + i)] = v * c + kxv * si;
    }
    return t;
  };
  const State n_turned = turned(a.state, 4, 1), s1_turned = turned(a.state, 1, 4);
  State wider = a.state;
  wider[7] *= 1.1;
  struct Input
  {
    const State* state;
    double kappa, strength;
  };
  const std::vector<Input> sequence = {
      {&a.state, ka, 1},         {&a.state, ka, 1},        {&a.state, 2 * ka, 1},
      {&a.state, 2 * ka, 1.2},   {&n_turned, 2 * ka, 1.2}, {&a.state, 2 * ka, 1.2},
      {&s1_turned, 2 * ka, 1.2}, // kept from a's: only s1 differs
      {&wider, 2 * ka, 1.2},     {&a.state, 2 * ka, 1.2},  {&b.state, 2 * ka, 1.2},
      {&uncracked, 0, 1},        {&a.state, ka, 1},        {&b.state, kb, 1}};
  SecantOperator kept;
  for (const Input& in : sequence)
  {
    law.secant_operator(*in.state, in.kappa, in.strength, kept);
    SecantOperator fresh;
    law.secant_operator(*in.state, in.kappa, in.strength, fresh);
    ASSERT_EQ(kept.cracked, fresh.cracked);
    if (!fresh.cracked)
      continue;
    EXPECT_EQ(kept.regular, fresh.regular);
    EXPECT_EQ(kept.damage, fresh.damage);
    EXPECT_EQ(kept.closing, fresh.closing);
    EXPECT_EQ(kept.tangent, fresh.tangent);
  }
}

// Onset is decided by the largest principal stress against the point's
// strength (the eigensolver's), whatever shortcut update() takes for points
// far below it: on states where the shortcut's bound is exact (equal normal
// stresses and one shear) and at strengths within an ulp of that principal
// stress, a crack appears exactly where the eigenvalue reaches the strength.
TEST(CrackBand, OnsetWhereTheLargestPrincipalStressReachesTheStrength)
{
  const CrackBand law(E, nu, exponential);
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> U(-1, 1);
  int cracked = 0, elastic = 0;
  for (int trial = 0; trial < 2000; ++trial)
  {
    const double a = 1e-4 * U(gen);
    const Voigt strain = {a, a, 1e-4 * U(gen), 0, 0, 2e-4 * U(gen)};
    Vec3 principal;
    Mat3 axes;
    pushout::bulk::symmetric_eigen(
        pushout::bulk::stress_tensor(pushout::bulk::multiply(law.stiffness(), strain)), principal,
        axes);
    if (!(principal[0] > 0))
      continue;
    const double at = principal[0] / f_t; // the strength that makes f_t equal it
    for (const double strength : {std::nextafter(at, 0.0), at, std::nextafter(at, 2 * at)})
    {
      State now(CrackBand::state_size);
      const State old(CrackBand::state_size, 0.0);
      law.update(
          old, strain, now, [](const Vec3&) { return 1.0; }, strength);
      const bool expected = principal[0] >= strength * f_t;
      EXPECT_EQ(now[0] != 0, expected) << "trial " << trial << ", strength " << strength;
      (expected ? cracked : elastic) += 1;
    }
  }
  EXPECT_GT(cracked, 100); // both sides were met
  EXPECT_GT(elastic, 100);
}

// A strain that is not finite (an iterate that blew up) is an error of every
// response, at an uncracked point too: before, an uncracked point answered
// it with a NaN stress and status ok, so only the residual's norm said so.
TEST(CrackBand, AStrainThatIsNotFiniteFailsEveryResponse)
{
  const CrackBand law(E, nu, exponential);
  Path path{law, 2.0};
  path.step({3e-4, 0, 0, 0, 0, 0}); // a crack normal to x
  const State uncracked(CrackBand::state_size, 0.0);
  SecantOperator cracked_op, uncracked_op;
  law.secant_operator(path.state, 0, 1, cracked_op);
  law.secant_operator(uncracked, 0, 1, uncracked_op);
  ASSERT_TRUE(cracked_op.cracked);
  ASSERT_FALSE(uncracked_op.cracked);
  const auto band = [](const Vec3&) { return 2.0; };
  for (const double bad : {std::nan(""), double(INFINITY), -double(INFINITY)})
  {
    const Voigt strain = {1e-5, 0, bad, 0, 0, 0};
    for (const State& old : {uncracked, path.state})
    {
      State trial(old.size());
      EXPECT_EQ(law.update(old, strain, trial, band).status, CrackBandResult::Status::not_finite);
      EXPECT_EQ(law.secant_response(old, strain, 0).status, CrackBandResult::Status::not_finite);
    }
    for (const SecantOperator* op : {&cracked_op, &uncracked_op})
    {
      EXPECT_EQ(CrackBand::secant_side(*op, strain), CrackBand::secant_failed);
      EXPECT_EQ(law.secant_apply(*op, strain).status, CrackBandResult::Status::not_finite);
    }
  }
}

// IMPL-EX's updates ask for no tangent (Tangent::skip): the same state,
// stress, opening, damage, dissipation and status as the update with it,
// and a zero tangent, on a path through onset, softening, unloading,
// closure and a band too wide to soften. Equal to the bit, not to a
// tolerance: both run the same operations in the same order (the crack's
// equilibrium and CrackBand's point_stress), only the tangent's are left out.
TEST(CrackBand, AnUpdateWithoutTheTangentIsTheUpdateWithIt)
{
  const CrackBand law(E, nu, exponential);
  std::mt19937 gen(7);
  const Mat3 Q = random_rotation(gen);
  for (const double h : {2.0, 10 * law.max_band_width()})
  {
    Path path{law, h};
    const auto band = [&](const Vec3&) { return h; };
    int compared = 0, damaged = 0;
    CrackBandResult::Status last = CrackBandResult::Status::ok;
    for (const double eps : {5e-5, 1.2e-4, 3e-4, 1e-3, 4e-4, 0.0, -2e-4, 1.5e-3})
    {
      const Voigt strain = rotated(Q, {eps, -0.2 * eps, 0.1 * eps, 0, 0, 0});
      State with(path.state.size()), without(path.state.size());
      const CrackBandResult a = law.update(path.state, strain, with, band);
      const CrackBandResult b =
          law.update(path.state, strain, without, band, 1, 0, pushout::bulk::Tangent::skip);
      EXPECT_EQ(a.status, b.status);
      EXPECT_EQ(with, without);
      EXPECT_EQ(a.stress, b.stress);
      EXPECT_EQ(a.opening, b.opening);
      EXPECT_EQ(a.damage, b.damage);
      EXPECT_EQ(a.dissipation, b.dissipation);
      for (double t : b.tangent)
        EXPECT_EQ(t, 0.0);
      ++compared;
      damaged += a.damage > 0;
      last = a.status;
      if (a.status != CrackBandResult::Status::ok)
        break; // the too-wide band: refused at onset
      path.state = with;
    }
    if (h == 2.0)
    {
      EXPECT_EQ(compared, 8);
      EXPECT_GE(damaged, 5); // softened, unloaded, closed, reloaded
    }
    else
      EXPECT_EQ(last, CrackBandResult::Status::band_too_wide);
  }
}

// Points that stopped a run of the corroded study's case (bench/cracking_mesh.py
// --lines radial --graded-refinement whole --beta 3 --seed 4, 24 / 8, push
// step 5; states and strains printed to the last bit): fully damaged cracks
// (their damage 1 to six digits) dragged along by the push, their strains
// shears of about 0.2, so that the trial traction s0 on the crack is some
// 3e4 MPa. Newton on the crack's balance converges there to 1.03e-14 |s0|
// and no closer: just above its tolerance of 1e-14 |s0|, so every cut of
// the step failed the same way. The balance is accepted at its round-off.
TEST(CrackBand, BalancesAtItsRoundOffWhereTheTrialTractionIsLarge)
{
  const CrackBand law(E, nu, exponential);
  struct Case
  {
    State old;       // committed state: cracked, n, s1, h [mm], the law's history
    Voigt strain;    // engineering shears
    double strength; // f_t of the point over the law's
  };
  const std::vector<Case> cases = {
      {{0x1p+0, -0x1.65eac1f902dcap-2, 0x1.dfa8d8d5fb587p-1, -0x1.ab3771534c86p-7,
        0x1.98d4819e1bb3fp-4, 0x1.a259ed4d5e762p-5, 0x1.fcc594896598fp-1, 0x1.74a3d9add33dp-1,
        0x1.830696eadf6d3p-3, 0x1.fffffff4e59bbp-1},
       {-0x1.5f11eb5246d8ep-4, 0x1.5218aa242cf4ep-4, 0x1.9968165720fb8p-14, 0x1.0abd81b6ac09fp-9,
        -0x1.07593707805c1p-8, 0x1.861afc51410a3p-3},
       0x1.14b11feabfd7fp+0},
      {{0x1p+0, -0x1.6913a8d525c7ap-2, 0x1.df1cbb18a0ed8p-1, 0x1.2a59eb081b341p-9,
        -0x1.5c1c8c945e554p-3, -0x1.10255b89770c9p-4, 0x1.f766be1af539bp-1, 0x1.66e5711a64bap-1,
        0x1.9293ed9f3f187p-3, 0x1.fffffff9a464fp-1},
       {-0x1.7856cf847054ep-4, 0x1.6eb9377958fedp-4, 0x1.6524e19c1d31cp-14, 0x1.c5f144a7a5471p-9,
        -0x1.19016453bed17p-11, 0x1.9b8e3c7be9251p-3},
       0x1.adcb678105e09p-1},
      {{0x1p+0, -0x1.6a357b07360fap-2, 0x1.dee5f6cdbf64bp-1, 0x1.43934dc2e4e6bp-9,
        -0x1.69e55e03c9542p-3, -0x1.1c54648202b01p-4, 0x1.f6b0244b8bdaap-1, 0x1.67245ade729cp-1,
        0x1.973f5bce72404p-3, 0x1.fffffffa0854p-1},
       {-0x1.7f2def8cded7ap-4, 0x1.74c01f14c063ep-4, 0x1.66295ad2461c1p-12, 0x1.116eb9abea97p-8,
        -0x1.7a298487b21bap-11, 0x1.9ff69e8cbf6e7p-3},
       0x1.b4ad42c71da0bp-1},
      {{0x1p+0, 0x1.a55289d19c57p-2, 0x1.d2a52cf5ee8a4p-1, -0x1.6c38919fcc207p-8,
        0x1.657d6201e1cc9p-3, -0x1.2a3e3f83769bp-4, 0x1.f6c2560e9cfbep-1, 0x1.6b176b0f5cd4p-1,
        0x1.0c219a357efa7p-3, 0x1.ffffffba724a1p-1},
       {-0x1.226554d624afp-4, 0x1.1b82a8ad864d1p-4, -0x1.72e95686a9ca2p-13, 0x1.1feee7eb4f46cp-15,
        0x1.465c24a39e0f5p-10, -0x1.eaa096923b41ap-4},
       0x1.afecaa822b664p-1},
  };
  for (const Case& c : cases)
  {
    State now(c.old.size());
    const CrackBandResult r = law.update(
        c.old, c.strain, now, [&](const Vec3&) { return c.old[7]; }, c.strength);
    ASSERT_EQ(r.status, CrackBandResult::Status::ok);
    // The crack is fully damaged and closed: the stress on its plane is
    // the closure's pressure, no tension.
    const Vec3 n = {c.old[1], c.old[2], c.old[3]};
    const Mat3 s = {r.stress[0], r.stress[5], r.stress[4], r.stress[5], r.stress[1],
                    r.stress[3], r.stress[4], r.stress[3], r.stress[2]};
    Vec3 t{};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        t[i] += s[3 * i + j] * n[j];
    const double t_n = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];
    EXPECT_LT(t_n, 0.0);
    EXPECT_GT(r.damage, 1 - 1e-6);
  }
}

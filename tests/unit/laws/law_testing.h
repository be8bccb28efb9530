// Shared helpers for the law tests: central finite differences of a law's
// traction against its consistent tangent.
#pragma once

#include "laws/InterfaceLaw.h"
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <random>
#include <vector>

namespace pushout::testing
{
/// Max over entries of |D - D_fd| / max(|D|_max, floor), D_fd by central
/// differences with step h [mm] from the committed state `s0`, with the
/// step's inputs `in`.
template <typename L>
double tangent_error(const L& law, const std::vector<double>& s0, const laws::Vec3& w, double h,
                     double floor, const laws::StepInputs& in = {})
{
  std::vector<double> s1(s0.size());
  const laws::LawResult r = law.update(s0, w, s1, in);
  double scale = floor, err = 0;
  for (double d : r.D)
    scale = std::max(scale, std::abs(d));
  for (int j = 0; j < 3; ++j)
  {
    laws::Vec3 wp = w, wm = w;
    wp[j] += h;
    wm[j] -= h;
    const laws::Vec3 tp = law.update(s0, wp, s1, in).t;
    const laws::Vec3 tm = law.update(s0, wm, s1, in).t;
    for (int i = 0; i < 3; ++i)
      err = std::max(err, std::abs((tp[i] - tm[i]) / (2 * h) - r.D[3 * i + j]));
  }
  return err / scale;
}

/// The states a frictional law met in check_friction_tangent, and the
/// largest relative tangent error.
struct FrictionStates
{
  int sliding = 0, sticking = 0, open = 0;
  double worst = 0;
};

/// The consistent tangent of a frictional law `make(k, mu)` (state: the
/// plastic slip s1, s2) against central differences at 300 random states
/// away from its kinks (the yield surface and the onset of contact): k in
/// 1e2 .. 1e6 N/mm^3, mu in 0.1 .. 0.6, jumps of 1e-3 mm, a third of them
/// starting near the slip so that they stick; `inputs(gen)` draws the
/// step's inputs (the contact opens at w_n = oxide_gap, with the oxide's
/// compliance in series). Each error must be below 1e-6.
template <class Make, class Inputs>
FrictionStates check_friction_tangent(unsigned seed, Make make, Inputs inputs)
{
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> U(-1, 1);
  const double h = 1e-9, scale = 1e-3; // FD step and jump scale [mm]
  FrictionStates states;
  while (states.sliding + states.sticking + states.open < 300)
  {
    const double k = std::pow(10.0, 2 + 2 * (U(gen) + 1)); // 1e2 .. 1e6 N/mm^3
    const double mu = 0.1 + 0.5 * (U(gen) + 1);
    const laws::StepInputs in = inputs(gen);
    const auto law = make(k, mu);
    const laws::Vec3 w = {scale * U(gen), scale * U(gen), scale * U(gen)};
    const bool near = U(gen) < -1.0 / 3;
    const std::vector<double> s0 = {near ? w[1] + 1e-2 * scale * U(gen) : scale * U(gen),
                                    near ? w[2] + 1e-2 * scale * U(gen) : scale * U(gen)};
    // Trial yield function (eq. 6) on the contact pressure.
    const double opening = w[0] - in.oxide_gap;
    const double p = std::max(-opening, 0.0) / (1 / k + in.oxide_compliance);
    const double f = k * std::hypot(w[1] - s0[0], w[2] - s0[1]) - mu * p;
    if (std::abs(opening) < 1e3 * h || std::abs(f) < 1e3 * k * h) // central differences
      continue;                                                   // would straddle a kink
    const double err = tangent_error(law, s0, w, h, k, in);
    states.worst = std::max(states.worst, err);
    EXPECT_LT(err, 1e-6) << "k " << k << " mu " << mu << " w " << w[0] << " " << w[1] << " " << w[2]
                         << " gap " << in.oxide_gap;
    (opening > 0 ? states.open : f > 0 ? states.sliding : states.sticking)++;
  }
  return states;
}
} // namespace pushout::testing

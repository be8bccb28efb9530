// Shared helpers for the law tests: central finite differences of a law's
// traction against its consistent tangent.
#pragma once

#include "laws/InterfaceLaw.h"
#include <algorithm>
#include <cmath>
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
} // namespace pushout::testing

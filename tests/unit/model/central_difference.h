// Checks of an exact derivative against central finite differences, for the
// model's unit tests (the assembled tangent, the energy release's gradient).
#pragma once

#include "solver/Equilibrium.h"
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <petscvec.h>
#include <random>

namespace pushout::unit
{
/// The largest relative difference over three random directions v (of
/// `space`; each entry `amplitude` times a uniform draw in (-1, 1) from
/// `gen`) between `exact(v, e)` (e of `result`'s layout) and the central
/// difference `difference(h, v, d)`, each direction its best of the
/// `steps` h. A central difference errs by its truncation (~h^2, large
/// where a step crosses a kink of a law: loading and unloading, stick and
/// slip) and by round-off (~eps |F| / h, whose size depends on the state's
/// cancellations, and so on the BLAS threads and the generated forms' last
/// digits); a wrong derivative is wrong at every step.
template <typename Exact, typename Difference>
double worst_relative_error(Vec space, Vec result, std::mt19937& gen, double amplitude,
                            std::initializer_list<double> steps, Exact&& exact,
                            Difference&& difference)
{
  std::uniform_real_distribution<double> U(-1, 1);
  Vec v, e, d;
  VecDuplicate(space, &v);
  VecDuplicate(result, &e);
  VecDuplicate(result, &d);
  PetscInt n;
  VecGetLocalSize(v, &n);
  double worst = 0;
  for (int trial = 0; trial < 3; ++trial)
  {
    double* a;
    VecGetArray(v, &a);
    for (PetscInt i = 0; i < n; ++i)
      a[i] = amplitude * U(gen);
    VecRestoreArray(v, &a);
    exact(v, e);
    double scale;
    VecNorm(e, NORM_INFINITY, &scale);
    double best = INFINITY;
    for (const double h : steps)
    {
      difference(h, v, d);
      VecAXPY(d, -1.0, e);
      double diff;
      VecNorm(d, NORM_INFINITY, &diff);
      best = std::min(best, diff / scale);
    }
    worst = std::max(worst, best);
  }
  for (Vec* w : {&v, &e, &d})
    VecDestroy(w);
  return worst;
}

/// worst_relative_error of the assembled tangent J at `at` against the
/// central differences of the assembled residual there; directions of
/// `amplitude` [mm] per dof drawn from `gen`.
inline double tangent_error(solver::Equilibrium& eq, Mat J, Vec at, std::mt19937 gen,
                            double amplitude, std::initializer_list<double> steps)
{
  Vec xp, xm, Fm;
  for (Vec* w : {&xp, &xm, &Fm})
    VecDuplicate(at, w);
  const double error = worst_relative_error(
      at, at, gen, amplitude, steps, [&](Vec v, Vec Jv) { MatMult(J, v, Jv); },
      [&](double h, Vec v, Vec d)
      {
        VecWAXPY(xp, h, v, at);
        VecWAXPY(xm, -h, v, at);
        eq.internal_forces(xp, d);
        eq.internal_forces(xm, Fm);
        VecAXPY(d, -1.0, Fm);
        VecScale(d, 1.0 / (2 * h));
      });
  for (Vec* w : {&xp, &xm, &Fm})
    VecDestroy(w);
  return error;
}
} // namespace pushout::unit

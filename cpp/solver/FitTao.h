// The solver of a fit (study/TaoFit.h) as PETSc reads its options: TAO's
// bounded Newton line search (TAOBNLS) taking the whole Gauss-Newton step
// each iteration (its KSP conjugate gradients), with a line search that the
// command line's -tao_ls_type may change. One set-up, so that the options a
// command is given are checked on the solver a fit will use
// (driver/PetscOptions.h).
#pragma once

#include "../common/petsc_check.h"
#include <petsctao.h>

namespace pushout::solver
{
/// Sets `tao` up as a fit's solver with `line_search`, then reads the
/// user's -tao_* options (TaoSetFromOptions). Throws petsc::Error.
inline void set_up_fit_tao(Tao tao, TaoLineSearchType line_search)
{
  using petsc::check;
  check(TaoSetType(tao, TAOBNLS), "TaoSetType");
  // The whole Gauss-Newton step each iteration: BNLS's default Krylov
  // solver (KSPSTCG) bounds it by a trust radius that a short step cuts to
  // a quarter of itself, and the next step with it.
  KSP ksp;
  check(TaoGetKSP(tao, &ksp), "TaoGetKSP");
  check(KSPSetType(ksp, KSPCG), "KSPSetType");
  TaoLineSearch search;
  check(TaoGetLineSearch(tao, &search), "TaoGetLineSearch");
  check(TaoLineSearchSetType(search, line_search), "TaoLineSearchSetType");
  // Converged when the gradient fell by 1e6 from the start (the
  // differences' noise floor is near 1e-10 of it) or below 1e-12 [MPa^2].
  check(TaoSetTolerances(tao, 1e-12, 0.0, 1e-6), "TaoSetTolerances");
  check(TaoSetMaximumIterations(tao, 50), "TaoSetMaximumIterations");
  check(TaoSetFromOptions(tao), "TaoSetFromOptions");
}

/// The line searches a fit may use (study/Fit.cpp resolution_of): More
/// and Thuente's on a smooth curve, Armijo's with cracks anywhere.
inline constexpr TaoLineSearchType fit_line_searches[] = {TAOLINESEARCHMT, TAOLINESEARCHARMIJO};
} // namespace pushout::solver

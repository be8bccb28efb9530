// The least-squares solver of a fit (Fit.h): PETSc TAO's bounded regularised
// Gauss-Newton (TAOBRGN) on the scaled values x = value / scale, the same
// on every process (PETSC_COMM_SELF), whose residual and forward-difference
// Jacobian callbacks are batches of the fit's runs (FitEvaluator.h).
#pragma once

#include "FitEvaluator.h"
#include "FreeValue.h"
#include <chrono>
#include <petsctao.h>
#include <string>
#include <vector>

namespace pushout::study
{
/// What TAO's callbacks share.
struct Problem
{
  Evaluator& evaluator;
  const std::vector<Free>& free;
  bool talk = false;
  std::vector<double> x_last, r_last; ///< the last base point and its residuals
  std::vector<double> x_jacobian;     ///< where the last Jacobian was formed
  std::vector<double> jacobian;       ///< its entries, column-major (m x n)
  int iterations = 0;
  std::chrono::steady_clock::time_point t0;
  bool last_failed = false; ///< whether x_last's run failed outright

  /// The scaled values in X.
  std::vector<double> values(Vec X) const;
  /// The root mean square of the last residuals [MPa].
  double rms() const;

  /// The stored Jacobian into J.
  void fill(Mat J) const;

  /// The residuals at x and, if `J`, the forward-difference Jacobian there
  /// (one batch of runs over the groups; a difference whose run fails
  /// outright is taken backwards, in a second batch).
  void evaluate(const std::vector<double>& x, Mat J);
};

/// The TAO solver of a fit (bounded regularised Gauss-Newton, TAOBRGN) on
/// the scaled values x = value / scale, with its vectors: the start and the
/// bounds of `free`, the m residuals and their Jacobian; freed when it goes.
struct TaoFit
{
  Tao tao = nullptr;
  Vec X = nullptr, F = nullptr, lo = nullptr, hi = nullptr;
  Mat J = nullptr;

  TaoFit(const std::vector<Free>& free, PetscInt m, Problem& problem);
  ~TaoFit();
  TaoFit(const TaoFit&) = delete;
  TaoFit& operator=(const TaoFit&) = delete;

  /// Runs TAO (the watcher's phase "fit"); returns the optimum (scaled
  /// values) with `problem`'s residuals and the Jacobian J evaluated there.
  /// Throws Interrupted when a signal stopped the runs.
  std::vector<double> solve(Problem& problem);
  /// Whether TAO converged (a positive reason).
  bool converged() const;
  /// Why TAO stopped, by PETSc's name.
  std::string reason() const;
};
} // namespace pushout::study

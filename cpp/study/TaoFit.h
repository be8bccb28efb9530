// The least-squares solver of a fit (Fit.h): Gauss-Newton on the scaled
// values x = value / scale, as PETSc TAO's bounded Newton line search
// (TAOBNLS) on f = |r|^2 / 2 with the gradient J^T r and the Hessian J^T J,
// the same on every process (PETSC_COMM_SELF). Its callbacks are batches of
// the fit's runs (FitEvaluator.h): the objective one run (and, with several
// groups, the points a backtracking line search would try next), the
// gradient the forward-difference Jacobian's n more (Resolution::line_search
// says what the line search asks for at the points it tries).
#pragma once

#include "FitEvaluator.h"
#include "FreeValue.h"
#include <chrono>
#include <cmath>
#include <petsctao.h>
#include <string>
#include <vector>

namespace pushout::study
{
/// How finely a fit can resolve its curve's dependence on the values
/// (docs/fitting.md, "Method").
struct Resolution
{
  /// The relative step of the Jacobian's forward differences (of the scaled
  /// values, which start at 1).
  double difference_step;
  /// A fit whose relative offset (FitStatistics.h) falls below this has
  /// converged: the Gauss-Newton step still to go is this fraction of the
  /// radius of the values' confidence region, however far the gradient is
  /// from TAO's test (which noise in the model's curve may hold up).
  double offset_tolerance;
  /// A curve that jumps with the values (cracks anywhere) puts a floor
  /// under the offset: where it stays above `stall_ratio` of the last
  /// iteration's, below 1, in two iterations running, the fit has reached
  /// the model's resolution (0: no such test, the curve being smooth).
  double stall_ratio = 0;
  /// TAO's line search: More and Thuente's (TAOLINESEARCHMT) asks for the
  /// gradient at each point it tries, n + 1 runs, and its curvature test
  /// thrashes on a curve that jumps; Armijo's backtracking
  /// (TAOLINESEARCHARMIJO) asks for the objective alone, one run.
  TaoLineSearchType line_search = TAOLINESEARCHMT;
};

/// Scaled values whose run is known, with its residuals [MPa] and whether
/// it failed outright.
struct KnownPoint
{
  std::vector<double> x, r;
  bool failed = false;
};

/// What TAO's callbacks share.
struct Problem
{
  Problem(Evaluator& evaluator, const std::vector<Free>& free, Resolution resolution, bool talk,
          std::chrono::steady_clock::time_point t0)
      : evaluator(evaluator), free(free), resolution(resolution), talk(talk), t0(t0)
  {
  }

  Evaluator& evaluator;
  const std::vector<Free>& free;
  Resolution resolution;
  bool talk;
  std::chrono::steady_clock::time_point t0;
  std::vector<double> x_last, r_last; ///< the last base point and its residuals
  std::vector<double> x_jacobian;     ///< where the last Jacobian was formed
  std::vector<double> jacobian;       ///< its entries, column-major (m x n)
  bool last_failed = false;           ///< whether x_last's run failed outright
  /// Per value: whether its column of the last Jacobian holds a failure
  /// (its difference's run failed, and the other way failed too or lay
  /// beyond its bound), so that the column is no derivative.
  std::vector<bool> difference_failed;
  /// x_jacobian's run first (where a line search that finds no step goes back
  /// to), and the points of its line search that other groups ran ahead.
  std::vector<KnownPoint> known_points;
  Tao tao = nullptr;            ///< the solver whose iterations these are
  PetscInt last_iteration = -1; ///< the iteration last tested
  double last_offset = NAN;     ///< the offset at that iteration
  int stalls = 0;               ///< iterations running that it stalled
  bool at_resolution = false;   ///< stopped by Resolution::stall_ratio or search_at_resolution
  /// Whether a point a line search tried since the last iteration failed
  /// outright (a value the scene refuses, or an error).
  bool failed_in_search = false;
  /// Iterations running whose line search met such a point and that did
  /// not halve the offset.
  int searches_failed = 0;
  /// With a curve that jumps (Resolution::stall_ratio > 0): the line search
  /// of this iteration met the model's resolution. Its whole step, from an
  /// iterate whose offset is below search_resolution_offset (the step well
  /// inside the confidence region), raised the misfit: what is left of the
  /// step is below the curve's jumps, and backtracking would only sample
  /// them (15 to 25 runs an iteration, measured). The points it tries after
  /// are not run: each is given x_jacobian's misfit, which no line search
  /// accepts, and the fit ends at x_jacobian (TaoFit::reason:
  /// CONVERGED_MODEL_RESOLUTION).
  bool search_at_resolution = false;
  /// The offset below which a line search's rise in the misfit means the
  /// model's resolution: four times Resolution::offset_tolerance.
  double search_resolution_offset() const { return 4 * resolution.offset_tolerance; }
  /// Line-search points run since the last Jacobian.
  int search_points = 0;
  /// Where that held in searches_failed_to_stop iterations running, the
  /// fit stops (TAO_DIVERGED_USER, DIVERGED_REFUSED_VALUES): the best fit
  /// lies beyond a relation between keys (f_fr <= f_t), where Armijo's
  /// backtracking (which asks for the objective alone at the points it
  /// tries) would creep towards the relation to TAO's iteration limit.
  static constexpr int searches_failed_to_stop = 3;

  /// The scaled values in X.
  std::vector<double> values(Vec X) const;
  /// The root mean square of the last residuals [MPa].
  double rms() const;
  /// The objective |r|^2 / 2 at the last base point [MPa^2].
  double objective() const { return half_square(r_last); }
  /// |r|^2 / 2 of residuals r [MPa^2].
  static double half_square(const std::vector<double>& r);
  /// The relative offset (FitStatistics.h) at x, from its residuals and
  /// Jacobian, over the values not held on a bound and with a derivative
  /// (difference_failed; 0 if none is left); NaN if the last Jacobian was
  /// formed elsewhere.
  double offset_at(const std::vector<double>& x) const;
  /// Whether at x, the last Jacobian's, no free value has a derivative
  /// (difference_failed, or a column of zeros: the curve the same on either
  /// side): where the fit stands then says nothing of where
  /// its optimum lies (an offset over no values, a gradient of none, are
  /// no test). With some derivative left the fit is judged by those values,
  /// the others held where they are (their standard errors null).
  bool nothing_to_judge(const std::vector<double>& x) const;
  /// The progress line of TAO's iteration `iteration` at x.
  void report(int iteration, const std::vector<double>& x, double offset) const;

  /// The stored Jacobian into J.
  void fill(Mat J) const;

  /// The residuals at x and, if `with_jacobian`, the forward-difference
  /// Jacobian there (one batch of runs over the groups; a difference whose
  /// run fails outright is taken backwards, in a second batch). Nothing is
  /// run again at a known point (the last, known_points). With several
  /// groups, a point that a line search tries alone comes with the next
  /// ones its backtracking would try, in the same batch.
  void evaluate(const std::vector<double>& x, bool with_jacobian);
};

/// The TAO solver of a fit (Gauss-Newton as TAOBNLS) on the scaled values
/// x = value / scale, with its vectors: the start and the bounds of `free`,
/// the Jacobian of the m residuals and the Hessian J^T J; freed when it
/// goes.
struct TaoFit
{
  Tao tao = nullptr;
  Vec X = nullptr, lo = nullptr, hi = nullptr;
  Mat J = nullptr, H = nullptr;

  TaoFit(const std::vector<Free>& free, PetscInt m, Problem& problem);
  ~TaoFit();

  TaoFit(const TaoFit&) = delete;
  TaoFit& operator=(const TaoFit&) = delete;

  /// Runs TAO (the watcher's phase "fit"); returns the optimum (scaled
  /// values) with the problem's residuals and the Jacobian J evaluated there.
  /// Throws Interrupted when a signal stopped the runs.
  std::vector<double> solve();
  /// Whether the fit converged: never where nothing is left to judge it by
  /// (Problem::nothing_to_judge: reason DIVERGED_NO_DERIVATIVE); else
  /// TAO's gradient test, or the relative offset
  /// below the problem's offset_tolerance (at the iteration limit too), or
  /// settled below 1 at the model's resolution (Resolution::stall_ratio),
  /// or a line search that met it (Problem::search_at_resolution).
  bool converged() const;
  /// Why TAO stopped, by PETSc's name (CONVERGED_RELATIVE_OFFSET for the
  /// offset's test, CONVERGED_MODEL_RESOLUTION for its floor,
  /// DIVERGED_NO_DERIVATIVE where nothing is left to judge the fit by).
  std::string reason() const;
  /// TAO's iterations.
  int iterations() const;
  /// The relative offset at the optimum (after solve()).
  double offset() const { return final_offset; }

private:
  /// TAO's `reason` is the end of a line search that met the model's
  /// resolution (Problem::search_at_resolution).
  bool at_resolution_by_search(TaoConvergedReason reason) const;
  Problem& _problem;
  double final_offset = INFINITY;
  bool no_derivative = false; ///< Problem::nothing_to_judge at the optimum
};
} // namespace pushout::study

// How well a fit determines its values (Fit.h): at the optimum
//   s^2 = |r|^2 / (m - n),  cov = s^2 (J^T J)^-1,
// the standard errors sqrt(cov_jj) and the correlations cov_jk / (se_j se_k)
// in the keys' units, and the warnings the user should read (values the
// data do not tell apart, a value on its bound).
#pragma once

#include "FreeValue.h"
#include <petscmat.h>
#include <string>
#include <vector>

namespace pushout::study
{
/// What the fit found beyond its values: their standard errors and
/// correlations, the residual sum of squares, and what the user should know.
struct FitStatistics
{
  std::vector<double> se;                ///< standard errors, the keys' units
  std::vector<std::vector<double>> corr; ///< correlations (NaN: undetermined)
  std::vector<std::string> warnings;
  double rss = 0; ///< |r|^2 [MPa^2]
};

/// The statistics at the optimum x (scaled values) from the Jacobian J (m x
/// n, dense, of the scaled values) and the residuals r [MPa]: s^2 = |r|^2 /
/// (m - n), cov = s^2 (J^T J)^-1 in the keys' units (docs/fitting.md).
/// A value whose column of J is no derivative (`no_derivative`: its
/// difference's runs failed, Problem::difference_failed) has no standard
/// error (infinite) and no correlations, and a warning says why; the
/// others' are those with it held where it is.
FitStatistics statistics(Mat J, const std::vector<double>& r, const std::vector<Free>& free,
                         const std::vector<double>& x, std::vector<bool> no_derivative);

/// J^T J of the column-major m x n `jacobian`, each column j divided by
/// scale[j] (none: 1).
std::vector<std::vector<double>> normal_matrix(const double* jacobian, std::size_t m, std::size_t n,
                                               const std::vector<double>& scale = {});

/// J^T r of the column-major r.size() x n `jacobian` (the gradient of
/// |r|^2 / 2 in the values J differentiates by).
std::vector<double> transpose_times(const std::vector<double>& jacobian,
                                    const std::vector<double>& r);

/// The relative offset of Bates and Watts (1981, Technometrics 23:179-183)
/// at residuals r [MPa] with Jacobian `jacobian` (column-major, r.size() x
/// n, of any scaling of the values): with P the projection onto J's columns,
///   sqrt(|P r|^2 / n) / sqrt(|r - P r|^2 / (m - n)),
/// the Gauss-Newton step still to go measured against the radius of the
/// values' confidence region. Infinite where J^T J is singular or the
/// residuals lie in J's columns (data the model meets exactly).
double relative_offset(const std::vector<double>& jacobian, const std::vector<double>& r);
} // namespace pushout::study

// The statistics of a fit at its optimum (FitStatistics.h).
#include "FitStatistics.h"
#include "../common/petsc_check.h"
#include "text.h"
#include <algorithm>
#include <cmath>
#include <cstdio>

namespace pushout::study
{
namespace
{
/// A correlation as the warning gives it: three decimals (-0.990).
std::string correlation_text(double c)
{
  char text[16];
  std::snprintf(text, sizeof text, "%.3f", c);
  return text;
}

using petsc::check;

/// Two values whose correlation exceeds this are not separately
/// identifiable from the data.
constexpr double identifiable_correlation = 0.95;

/// Solves the n x n system A y = b (A symmetric positive definite, small)
/// by Gauss-Jordan with partial pivoting; false if A is singular.
bool invert(std::vector<std::vector<double>> a, std::vector<std::vector<double>>& inverse)
{
  const std::size_t n = a.size();
  inverse.assign(n, std::vector<double>(n, 0.0));
  for (std::size_t i = 0; i < n; ++i)
    inverse[i][i] = 1;
  for (std::size_t c = 0; c < n; ++c)
  {
    std::size_t p = c;
    for (std::size_t r = c + 1; r < n; ++r)
      if (std::abs(a[r][c]) > std::abs(a[p][c]))
        p = r;
    if (!(std::abs(a[p][c]) > 1e-300))
      return false;
    std::swap(a[p], a[c]);
    std::swap(inverse[p], inverse[c]);
    const double d = a[c][c];
    for (std::size_t k = 0; k < n; ++k)
    {
      a[c][k] /= d;
      inverse[c][k] /= d;
    }
    for (std::size_t r = 0; r < n; ++r)
      if (r != c)
      {
        const double f = a[r][c];
        for (std::size_t k = 0; k < n; ++k)
        {
          a[r][k] -= f * a[c][k];
          inverse[r][k] -= f * inverse[c][k];
        }
      }
  }
  return true;
}
} // namespace

std::vector<std::vector<double>> normal_matrix(const double* jacobian, std::size_t m, std::size_t n,
                                               const std::vector<double>& scale)
{
  std::vector<std::vector<double>> JtJ(n, std::vector<double>(n, 0.0));
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t k = 0; k < n; ++k)
    {
      for (std::size_t i = 0; i < m; ++i)
        JtJ[j][k] += jacobian[j * m + i] * jacobian[k * m + i];
      if (!scale.empty())
        JtJ[j][k] /= scale[j] * scale[k];
    }
  return JtJ;
}

std::vector<double> transpose_times(const std::vector<double>& jacobian,
                                    const std::vector<double>& r)
{
  const std::size_t m = r.size(), n = m == 0 ? 0 : jacobian.size() / m;
  std::vector<double> Jtr(n, 0.0);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < m; ++i)
      Jtr[j] += jacobian[j * m + i] * r[i];
  return Jtr;
}

FitStatistics statistics(Mat J, const std::vector<double>& r, const std::vector<Free>& free,
                         const std::vector<double>& x, std::vector<bool> no_derivative)
{
  const std::size_t n = free.size(), m = r.size();
  no_derivative.resize(n, false); // none known: every column a derivative
  FitStatistics st;
  std::vector<double> scale(n);
  for (std::size_t j = 0; j < n; ++j)
    scale[j] = free[j].scale; // J is of the scaled values: J^T J in the keys' units
  const PetscScalar* a;
  check(MatDenseGetArrayRead(J, &a), "MatDenseGetArrayRead");
  const std::vector<std::vector<double>> all = normal_matrix(a, m, n, scale);
  check(MatDenseRestoreArrayRead(J, &a), "MatDenseRestoreArrayRead");
  // The values whose columns are derivatives; J^T J of those.
  std::vector<std::size_t> d;
  for (std::size_t j = 0; j < n; ++j)
    if (!no_derivative[j])
      d.push_back(j);
  std::vector<std::vector<double>> JtJ(d.size(), std::vector<double>(d.size()));
  for (std::size_t j = 0; j < d.size(); ++j)
    for (std::size_t k = 0; k < d.size(); ++k)
      JtJ[j][k] = all[d[j]][d[k]];
  for (double v : r)
    st.rss += v * v;
  const double s2 = st.rss / double(m > d.size() ? m - d.size() : 1); // the others held
  std::vector<std::vector<double>> cov;
  st.se.assign(n, INFINITY);
  st.corr.assign(n, std::vector<double>(n, NAN));
  if (invert(JtJ, cov))
  {
    for (std::size_t j = 0; j < d.size(); ++j)
      st.se[d[j]] = std::sqrt(std::max(s2 * cov[j][j], 0.0));
    for (std::size_t j = 0; j < d.size(); ++j)
      for (std::size_t k = 0; k < d.size(); ++k)
        st.corr[d[j]][d[k]] = s2 * cov[j][k] / (st.se[d[j]] * st.se[d[k]]);
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t k = j + 1; k < n; ++k)
        if (std::abs(st.corr[j][k]) > identifiable_correlation)
          st.warnings.push_back(free[j].key + " and " + free[k].key + " are correlated (" +
                                correlation_text(st.corr[j][k]) +
                                "): the data do not determine them separately");
  }
  else
    st.warnings.push_back("J^T J is singular at the optimum: some values do not change the curve");
  for (std::size_t k = 0; k < n; ++k)
    if (no_derivative[k])
      st.warnings.push_back(free[k].key + " = " + number_text(x[k] * free[k].scale) +
                            " has no standard error: the run beside it that its derivative "
                            "needs failed or was refused (fit.json refusal or failure), and "
                            "the other way failed too or lies beyond its bound, so the fit "
                            "cannot tell how the curve changes with it there");
  // A value the optimum pushes onto a bound is not a fit of it: the data
  // want it beyond (a different model, or data the model cannot make).
  for (std::size_t k = 0; k < n; ++k)
    if (!no_derivative[k] && (free[k].on_lo(x[k]) || free[k].on_hi(x[k])))
      st.warnings.push_back(free[k].key + " = " + number_text(x[k] * free[k].scale) +
                            " sits on its bound: the best fit would take it beyond, so the "
                            "model does not describe these data well there");
  return st;
}

double relative_offset(const std::vector<double>& jacobian, const std::vector<double>& r)
{
  const std::size_t m = r.size(), n = m == 0 ? 0 : jacobian.size() / m;
  if (n == 0 || m <= n)
    return INFINITY;
  std::vector<std::vector<double>> inverse;
  const std::vector<double> Jtr = transpose_times(jacobian, r);
  if (!invert(normal_matrix(jacobian.data(), m, n), inverse))
    return INFINITY;
  double projected = 0, rss = 0; // |P r|^2 = (J^T r)^T (J^T J)^-1 J^T r, |r|^2 [MPa^2]
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t k = 0; k < n; ++k)
      projected += Jtr[j] * inverse[j][k] * Jtr[k];
  for (double v : r)
    rss += v * v;
  const double rest = rss - projected;
  if (!(rest > 0))
    return INFINITY;
  return std::sqrt(std::max(projected, 0.0) / double(n)) / std::sqrt(rest / double(m - n));
}
} // namespace pushout::study

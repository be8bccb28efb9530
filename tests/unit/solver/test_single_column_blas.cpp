// The program's sgemm_ and strsm_ (solver/SingleColumnBlas.h): they are the
// ones the libraries see; a call with one column (sgemv / strsv) and a call
// with several (the BLAS library's own) both give the product and the
// triangular solve that the BLAS defines, for every transposition, side,
// triangle, unit diagonal and scaling, with a stride where the BLAS allows
// one, and beta = 0 does not read C; a call with one column is counted as
// done by sgemv / strsv (single_column_calls), one with several is not.
#include "solver/SingleColumnBlas.h"
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <gtest/gtest.h>
#include <limits>
#include <string>
#include <vector>

using fortran_length = std::size_t;
extern "C"
{
  void sgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
              const float* alpha, const float* a, const int* lda, const float* b, const int* ldb,
              const float* beta, float* c, const int* ldc, fortran_length, fortran_length);
  void strsm_(const char* side, const char* uplo, const char* transa, const char* diag,
              const int* m, const int* n, const float* alpha, const float* a, const int* lda,
              float* b, const int* ldb, fortran_length, fortran_length, fortran_length,
              fortran_length);
}

namespace
{
/// Sums of at most 40 products of numbers of order 1 in single precision:
/// each result is within 40 float epsilons (1.2e-7) of its value times the
/// size of the terms, so 1e-5 of the largest holds whatever the order of the
/// sums.
constexpr double tolerance = 1e-5;

/// Reproducible numbers in [-1, 1].
std::vector<float> numbers(std::size_t n, unsigned seed)
{
  std::vector<float> v(n);
  unsigned s = seed;
  for (float& x : v)
  {
    s = s * 1664525u + 1013904223u;
    x = float(s >> 8) / float(1u << 24) * 2.0f - 1.0f;
  }
  return v;
}

double largest(const std::vector<double>& v)
{
  double m = 0;
  for (double x : v)
    m = std::max(m, std::abs(x));
  return m;
}

bool transposed(char t)
{
  return t != 'N';
}

/// C = alpha op(A) op(B) + beta C in double, as the BLAS defines sgemm.
std::vector<double> gemm_reference(char ta, char tb, int m, int n, int k, float alpha,
                                   const std::vector<float>& a, int lda,
                                   const std::vector<float>& b, int ldb, float beta,
                                   const std::vector<float>& c, int ldc)
{
  std::vector<double> r(c.begin(), c.end());
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < m; ++i)
    {
      double s = 0;
      for (int l = 0; l < k; ++l)
        s += double(transposed(ta) ? a[l + i * lda] : a[i + l * lda]) *
             double(transposed(tb) ? b[j + l * ldb] : b[l + j * ldb]);
      r[i + j * ldc] = alpha * s + (beta == 0.0f ? 0.0 : beta * double(c[i + j * ldc]));
    }
  return r;
}

/// op(A) of strsm as a dense s x s matrix in double (row-major): the
/// triangle `uplo` of A, a unit diagonal for diag 'U', transposed for 'T'.
std::vector<double> triangle(char uplo, char trans, char diag, int s, const std::vector<float>& a,
                             int lda)
{
  std::vector<double> t(std::size_t(s * s), 0.0);
  for (int i = 0; i < s; ++i)
    for (int j = 0; j < s; ++j)
    {
      const bool stored = uplo == 'U' ? j >= i : j <= i;
      double v = stored ? double(a[i + j * lda]) : 0.0;
      if (i == j && diag == 'U')
        v = 1.0;
      (transposed(trans) ? t[j * s + i] : t[i * s + j]) = v;
    }
  return t;
}

/// x solving t x = y (t row-major s x s, regular), Gaussian elimination.
std::vector<double> solve(std::vector<double> t, std::vector<double> y)
{
  const int s = int(y.size());
  for (int p = 0; p < s; ++p)
  {
    int best = p;
    for (int i = p + 1; i < s; ++i)
      if (std::abs(t[i * s + p]) > std::abs(t[best * s + p]))
        best = i;
    for (int j = 0; j < s; ++j)
      std::swap(t[p * s + j], t[best * s + j]);
    std::swap(y[p], y[best]);
    for (int i = p + 1; i < s; ++i)
    {
      const double f = t[i * s + p] / t[p * s + p];
      for (int j = p; j < s; ++j)
        t[i * s + j] -= f * t[p * s + j];
      y[i] -= f * y[p];
    }
  }
  std::vector<double> x(std::size_t(s), 0.0);
  for (int i = s - 1; i >= 0; --i)
  {
    double r = y[i];
    for (int j = i + 1; j < s; ++j)
      r -= t[i * s + j] * x[j];
    x[i] = r / t[i * s + i];
  }
  return x;
}

/// B overwritten by X in double, as the BLAS defines strsm:
/// op(A) X = alpha B (side 'L') or X op(A) = alpha B (side 'R').
std::vector<double> trsm_reference(char side, char uplo, char trans, char diag, int m, int n,
                                   float alpha, const std::vector<float>& a, int lda,
                                   const std::vector<float>& b, int ldb)
{
  std::vector<double> r(b.begin(), b.end());
  // A left solve takes B's columns one at a time, a right one its rows
  // (X op(A) = alpha B: op(A)^T x = alpha b for each row).
  const bool left = side == 'L';
  const int s = left ? m : n, lines = left ? n : m;
  const std::vector<double> t =
      triangle(uplo, left == transposed(trans) ? 'T' : 'N', diag, s, a, lda);
  const auto at = [&](int line, int k) { return left ? k + line * ldb : line + k * ldb; };
  for (int line = 0; line < lines; ++line)
  {
    std::vector<double> y(static_cast<std::size_t>(s));
    for (int k = 0; k < s; ++k)
      y[k] = alpha * double(b[at(line, k)]);
    const std::vector<double> x = solve(t, y);
    for (int k = 0; k < s; ++k)
      r[at(line, k)] = x[k];
  }
  return r;
}

/// The largest difference of `computed` from `expected`, relative to the
/// largest entry of `expected` (at least 1).
double difference(const std::vector<float>& computed, const std::vector<double>& expected)
{
  double d = 0;
  for (std::size_t i = 0; i < computed.size(); ++i)
    d = std::max(d, std::abs(double(computed[i]) - expected[i]));
  return d / std::max(1.0, largest(expected));
}

/// A well-conditioned triangle: the diagonal of A shifted away from zero.
std::vector<float> regular(int s, int lda, unsigned seed)
{
  std::vector<float> a = numbers(std::size_t(lda * s), seed);
  for (int i = 0; i < s; ++i)
    a[i + i * lda] += a[i + i * lda] < 0 ? -4.0f : 4.0f;
  return a;
}
} // namespace

TEST(SingleColumnBlas, TheLibrariesSeeTheProgramsRoutines)
{
  EXPECT_TRUE(pushout::solver::single_column_blas_bound());
}

TEST(SingleColumnBlas, GemmIsTheBlasProductForOneColumnAndSeveral)
{
  const int m = 7, k = 9, lda = 12, ldc = 8;
  for (const int n : {1, 3})
    for (const char ta : {'N', 'T'})
      for (const char tb : {'N', 'T'})
        for (const float alpha : {1.0f, -0.5f})
          for (const float beta : {0.0f, 1.0f, 0.3f})
          {
            // B: k x n ('N') or n x k ('T'), in a leading dimension of 11.
            const int ldb = 11;
            const std::vector<float> a = numbers(std::size_t(lda * std::max(m, k)), 1);
            const std::vector<float> b = numbers(std::size_t(ldb * std::max(n, k)), 2);
            std::vector<float> c = numbers(std::size_t(ldc * n), 3);
            const std::vector<double> expected =
                gemm_reference(ta, tb, m, n, k, alpha, a, lda, b, ldb, beta, c, ldc);
            if (beta == 0.0f) // not to be read
              for (int j = 0; j < n; ++j)
                std::fill_n(c.begin() + j * ldc, m, std::numeric_limits<float>::quiet_NaN());
            const char tas[2] = {ta, 0}, tbs[2] = {tb, 0};
            const std::int64_t before = pushout::solver::single_column_calls();
            sgemm_(tas, tbs, &m, &n, &k, &alpha, a.data(), &lda, b.data(), &ldb, &beta, c.data(),
                   &ldc, 1, 1);
            // One column by sgemv, several by the library.
            EXPECT_EQ(pushout::solver::single_column_calls() - before, n == 1 ? 1 : 0);
            EXPECT_LT(difference(c, expected), tolerance)
                << "n " << n << " transa " << ta << " transb " << tb << " alpha " << alpha
                << " beta " << beta;
          }
}

TEST(SingleColumnBlas, TrsmIsTheBlasSolveForOneColumnOrRowAndSeveral)
{
  const int lda = 10, ldb = 6;
  for (const char side : {'L', 'R'})
    for (const int columns : {1, 2}) // of a left solve; rows of a right one
      for (const char uplo : {'U', 'L'})
        for (const char trans : {'N', 'T'})
          for (const char diag : {'N', 'U'})
            for (const float alpha : {1.0f, 2.5f, 0.0f})
            {
              // Left: B is 5 x columns; right: B is columns x 5, so that
              // one row of it has the stride ldb.
              const int m = side == 'L' ? 5 : columns, n = side == 'L' ? columns : 5;
              const int s = side == 'L' ? m : n;
              const std::vector<float> a = regular(s, lda, 4);
              std::vector<float> b = numbers(std::size_t(ldb * n), 5);
              const std::vector<double> expected =
                  trsm_reference(side, uplo, trans, diag, m, n, alpha, a, lda, b, ldb);
              const char sides[2] = {side, 0}, uplos[2] = {uplo, 0}, transes[2] = {trans, 0},
                         diags[2] = {diag, 0};
              const std::int64_t before = pushout::solver::single_column_calls();
              strsm_(sides, uplos, transes, diags, &m, &n, &alpha, a.data(), &lda, b.data(), &ldb,
                     1, 1, 1, 1);
              EXPECT_EQ(pushout::solver::single_column_calls() - before, columns == 1 ? 1 : 0);
              EXPECT_LT(difference(b, expected), tolerance)
                  << "side " << side << " columns " << columns << " uplo " << uplo << " trans "
                  << trans << " diag " << diag << " alpha " << alpha;
            }
}

TEST(SingleColumnBlas, LowerCaseConjugateEmptyAndZeroScaleAreTheBlas)
{
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const int m = 4, k = 3, one = 1, zero = 0, lda = 4, ldb = 5, ldc = 4;
  const std::vector<float> a = numbers(std::size_t(lda * 4), 6),
                           b = numbers(std::size_t(ldb * 4), 7);
  // Lower case, and 'C' (a real matrix's conjugate transpose is its
  // transpose).
  for (const char* ta : {"n", "t", "C", "c"})
    for (const char* tb : {"n", "t", "C"})
    {
      const float alpha = 0.7f, beta = 0.2f;
      std::vector<float> c = numbers(std::size_t(ldc), 8);
      const std::vector<double> expected =
          gemm_reference(ta[0] == 'n' ? 'N' : 'T', tb[0] == 'n' ? 'N' : 'T', m, 1, k, alpha, a, lda,
                         b, ldb, beta, c, ldc);
      sgemm_(ta, tb, &m, &one, &k, &alpha, a.data(), &lda, b.data(), &ldb, &beta, c.data(), &ldc, 1,
             1);
      EXPECT_LT(difference(c, expected), tolerance) << "transa " << ta << " transb " << tb;
    }
  // alpha = 0: A and B are not read (a NaN there stays out of C); C = beta C.
  {
    const std::vector<float> a_nan(std::size_t(lda * k), nan), b_nan(std::size_t(ldb), nan);
    const float alpha = 0.0f, beta = 0.5f;
    std::vector<float> c = {1.0f, 2.0f, 3.0f, 4.0f};
    sgemm_("N", "N", &m, &one, &k, &alpha, a_nan.data(), &lda, b_nan.data(), &ldb, &beta, c.data(),
           &ldc, 1, 1);
    EXPECT_EQ(c, (std::vector<float>{0.5f, 1.0f, 1.5f, 2.0f}));
  }
  // k = 0: C = beta C (the library's); m = 0: nothing.
  {
    const float alpha = 1.0f, beta = 2.0f;
    std::vector<float> c = {1.0f, 2.0f, 3.0f, 4.0f};
    sgemm_("N", "N", &m, &one, &zero, &alpha, a.data(), &lda, b.data(), &ldb, &beta, c.data(), &ldc,
           1, 1);
    EXPECT_EQ(c, (std::vector<float>{2.0f, 4.0f, 6.0f, 8.0f}));
    sgemm_("N", "N", &zero, &one, &k, &alpha, a.data(), &lda, b.data(), &ldb, &beta, c.data(), &ldc,
           1, 1);
    EXPECT_EQ(c, (std::vector<float>{2.0f, 4.0f, 6.0f, 8.0f}));
  }
  // strsm in lower case.
  {
    const int s = 4, lda_t = 6;
    const std::vector<float> t = regular(s, lda_t, 9);
    std::vector<float> x = numbers(std::size_t(s), 10);
    const float alpha = 1.5f;
    const std::vector<double> expected =
        trsm_reference('L', 'L', 'T', 'N', s, 1, alpha, t, lda_t, x, s);
    strsm_("l", "l", "t", "n", &s, &one, &alpha, t.data(), &lda_t, x.data(), &s, 1, 1, 1, 1);
    EXPECT_LT(difference(x, expected), tolerance);
  }
}

#include "SymmetricMatrix.h"
#include "../common/petsc_check.h"
#include "../common/vector_clones.h"
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <type_traits>
#include <utility>

namespace pushout::solver
{
using petsc::check;

namespace
{
/// y = A x, A symmetric n x n as its packed upper triangle. Each stored
/// entry of row i serves y_i (a dot product with x) and y_j (x_i times the
/// entry): one pass over the bytes. The dot product runs in `lanes`
/// independent sums, so that it vectorises without reassociating a sum.
template <class T>
[[gnu::always_inline]] inline void multiply_body(const T* __restrict a, std::size_t n,
                                                 const T* __restrict x, T* __restrict y)
{
  constexpr std::size_t lanes = 64 / sizeof(T); // two AVX2 registers of sums
  std::fill(y, y + n, T(0));
  for (std::size_t i = 0; i < n; ++i)
  {
    const T xi = x[i];
    // The entries right of the diagonal: a_ij, j = i+1..n-1.
    const T* __restrict row = a + 1;
    const T* __restrict xr = x + i + 1;
    T* __restrict yr = y + i + 1;
    const std::size_t m = n - i - 1;
    T sums[lanes] = {};
    std::size_t j = 0;
    for (; j + lanes <= m; j += lanes)
      for (std::size_t l = 0; l < lanes; ++l)
      {
        sums[l] += row[j + l] * xr[j + l];
        yr[j + l] += row[j + l] * xi;
      }
    T s = a[0] * xi;
    for (std::size_t l = 0; l < lanes; ++l)
      s += sums[l];
    for (; j < m; ++j)
    {
      s += row[j] * xr[j];
      yr[j] += row[j] * xi;
    }
    y[i] += s;
    a += m + 1;
  }
}

PUSHOUT_VECTOR_CLONES
void multiply_kernel(const float* __restrict a, std::size_t n, const float* __restrict x,
                     float* __restrict y)
{
  multiply_body(a, n, x, y);
}

PUSHOUT_VECTOR_CLONES
void multiply_kernel(const double* __restrict a, std::size_t n, const double* __restrict x,
                     double* __restrict y)
{
  multiply_body(a, n, x, y);
}

/// The size and the column stride of a square sequential dense matrix.
std::pair<std::size_t, std::size_t> dense_shape(Mat A)
{
  PetscInt rows, cols, lda;
  check(MatGetSize(A, &rows, &cols), "MatGetSize");
  if (rows != cols)
    throw std::logic_error("a symmetric matrix must be square");
  check(MatDenseGetLDA(A, &lda), "MatDenseGetLDA");
  return {std::size_t(rows), std::size_t(lda)};
}
} // namespace

double relative_asymmetry(Mat A)
{
  const auto [n, lda] = dense_shape(A);
  const double* a;
  check(MatDenseGetArrayRead(A, &a), "MatDenseGetArrayRead");
  double largest = 0, asymmetry = 0;
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i)
    {
      largest = std::max(largest, std::abs(a[i + j * lda]));
      asymmetry = std::max(asymmetry, std::abs(a[i + j * lda] - a[j + i * lda]));
    }
  check(MatDenseRestoreArrayRead(A, &a), "MatDenseRestoreArrayRead");
  return largest > 0 ? asymmetry / largest : 0.0;
}

void symmetrize(Mat A)
{
  const auto [n, lda] = dense_shape(A);
  double* a;
  check(MatDenseGetArray(A, &a), "MatDenseGetArray");
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = j + 1; i < n; ++i)
      a[i + j * lda] = a[j + i * lda] = 0.5 * (a[i + j * lda] + a[j + i * lda]);
  check(MatDenseRestoreArray(A, &a), "MatDenseRestoreArray");
}

template <class T> SymmetricMatrix<T>::SymmetricMatrix(Mat A)
{
  const auto [n, lda] = dense_shape(A);
  _n = n;
  _a.reserve(n * (n + 1) / 2);
  const double* a;
  check(MatDenseGetArrayRead(A, &a), "MatDenseGetArrayRead");
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j)
      _a.push_back(T(a[i + j * lda]));
  check(MatDenseRestoreArrayRead(A, &a), "MatDenseRestoreArrayRead");
  if constexpr (!std::is_same_v<T, double>)
  {
    _x.resize(n);
    _y.resize(n);
  }
}

template <class T> void SymmetricMatrix<T>::multiply(const double* x, double* y) const
{
  if constexpr (std::is_same_v<T, double>)
    multiply_kernel(_a.data(), _n, x, y);
  else
  {
    std::copy(x, x + _n, _x.begin());
    multiply_kernel(_a.data(), _n, _x.data(), _y.data());
    std::copy(_y.begin(), _y.end(), y);
  }
}

template class SymmetricMatrix<float>;
template class SymmetricMatrix<double>;
} // namespace pushout::solver

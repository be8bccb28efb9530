// A dense symmetric matrix stored once: its upper triangle, row by row
// (packed), in float or double.
//
// Why: the condensed flexibility C (Condensation.h) is symmetric (the
// Schur complement of the linear elastic bulk, seen through the jumps), and
// its products are bound by memory traffic: the residual's in every Newton
// iteration (double) and the Jacobian's action in every GMRES iteration
// (float or double). The packed triangle streams half the bytes of the full
// matrix (on the paper's half model with one crack plane, 963 jumps: 3.7 MB
// instead of 7.4 MB in double), at the same arithmetic: each stored entry
// a_ij (i < j) serves y_i and y_j.
//
// The kernels are compiled for the machine's widest vectors (AVX2 and FMA
// where the CPU has them, chosen at run time; plain x86-64 elsewhere), as
// the single-precision LU's (SinglePrecision.h).
#pragma once

#include <cstddef>
#include <petscmat.h>
#include <vector>

namespace pushout::solver
{
/// Largest relative asymmetry max|A - A^T| / max|A| of a matrix taken as
/// symmetric that its products may carry: averaging the asymmetry away
/// moves them by at most half of it, relative. A flexibility C = G K^-1 G^T
/// computed through a factorisation carries round-off of about
/// n eps cond(K) (n: unknowns), which the asymmetry samples (the demos and
/// the full slice: 1e-11 to 5e-11; a circle slice with four cracks and
/// steel.E = 2e6 MPa: 1.5e-9); the shortcuts of the solver are held to 1e-6
/// of Newton on the whole model (docs/performance.md), so C is trusted up
/// to a decade below that.
constexpr double trusted_asymmetry = 1e-7;
/// max|A - A^T| / max|A| of a square sequential dense matrix (0 for A = 0).
double relative_asymmetry(Mat A);

/// Replaces the square sequential dense matrix A by (A + A^T) / 2.
void symmetrize(Mat A);

/// A dense symmetric n x n matrix, its upper triangle packed row by row, in
/// T (float or double).
template <class T> class SymmetricMatrix
{
public:
  SymmetricMatrix() = default;
  /// The upper triangle of the square sequential dense matrix A (taken as
  /// symmetric: the caller checks, relative_asymmetry).
  explicit SymmetricMatrix(Mat A);
  /// y = A x (x, y of size n, not overlapping), rounded to T on the way in
  /// and accumulated in T.
  void multiply(const double* x, double* y) const;
  std::size_t size() const { return _n; }

private:
  std::size_t _n = 0;
  std::vector<T> _a;             ///< rows i = 0..n-1 of the upper triangle: a_ii, ..., a_i(n-1)
  mutable std::vector<T> _x, _y; ///< x and y rounded to T (float only)
};

extern template class SymmetricMatrix<float>;
extern template class SymmetricMatrix<double>;
} // namespace pushout::solver

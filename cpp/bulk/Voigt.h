// Small dense algebra of the bulk laws at a quadrature point: Voigt vectors,
// the isotropic elastic stiffness, 3 x 3 solves and the eigenvectors of a
// symmetric 3 x 3 tensor.
//
// Voigt order: stress [xx, yy, zz, yz, xz, xy] (MPa); strain [xx, yy, zz,
// 2 yz, 2 xz, 2 xy] (engineering shears), so that sigma . epsilon is the
// energy density and the stiffness is a symmetric 6 x 6 (row-major).
#pragma once

#include "../laws/InterfaceLaw.h"
#include <array>
#include <cmath>

namespace pushout::bulk
{
using laws::Mat3; ///< 3 x 3, row-major
using laws::Vec3;
using Voigt = std::array<double, 6>;
using Voigt66 = std::array<double, 36>; ///< row-major

/// Lame's constants of E [MPa], nu [-]: {lambda, mu} [MPa].
inline std::array<double, 2> lame(double E, double nu)
{
  return {E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))};
}

/// The isotropic stiffness C (Voigt, engineering shears).
inline Voigt66 isotropic_stiffness(double E, double nu)
{
  const auto [lambda, mu] = lame(E, nu);
  Voigt66 C{};
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
      C[6 * i + j] = lambda;
    C[6 * i + i] = lambda + 2 * mu;
    C[6 * (i + 3) + (i + 3)] = mu;
  }
  return C;
}

inline Voigt multiply(const Voigt66& A, const Voigt& x)
{
  Voigt y{};
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      y[i] += A[6 * i + j] * x[j];
  return y;
}

/// The complementary energy density 1/2 s : C^-1 : s of a stress s in an
/// isotropic material (E [MPa], nu) [N mm/mm^3].
inline double complementary_energy(const Voigt& s, double E, double nu)
{
  const double trace = s[0] + s[1] + s[2];
  const double squares =
      s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + 2 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
  return 0.5 * ((1 + nu) * squares - nu * trace * trace) / E;
}

/// The symmetric tensor of a Voigt stress as a 3 x 3 matrix.
inline Mat3 stress_tensor(const Voigt& s)
{
  return {s[0], s[5], s[4], s[5], s[1], s[3], s[4], s[3], s[2]};
}

/// The traction of a Voigt stress on the plane of normal n: sigma n [MPa].
inline Vec3 traction(const Voigt& s, const Vec3& n)
{
  return {s[0] * n[0] + s[5] * n[1] + s[4] * n[2], s[5] * n[0] + s[1] * n[1] + s[3] * n[2],
          s[4] * n[0] + s[3] * n[1] + s[2] * n[2]};
}

/// The engineering strain sym(w (x) n) of an opening w over a unit band.
inline Voigt band_strain(const Vec3& w, const Vec3& n)
{
  return {w[0] * n[0],
          w[1] * n[1],
          w[2] * n[2],
          w[1] * n[2] + w[2] * n[1],
          w[0] * n[2] + w[2] * n[0],
          w[0] * n[1] + w[1] * n[0]};
}

/// The adjugate of a 3 x 3 A (A^-1 = adjugate / det) and its determinant;
/// false if A is singular to round-off (|det| <= 1e-14 max|a_ij|^3).
inline bool adjugate3(const Mat3& A, Mat3& adj, double& det)
{
  det = A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) +
        A[2] * (A[3] * A[7] - A[4] * A[6]);
  double scale = 0;
  for (double a : A)
    scale = std::max(scale, std::abs(a));
  if (!(std::abs(det) > 1e-14 * scale * scale * scale))
    return false;
  adj = {A[4] * A[8] - A[5] * A[7], A[2] * A[7] - A[1] * A[8], A[1] * A[5] - A[2] * A[4],
         A[5] * A[6] - A[3] * A[8], A[0] * A[8] - A[2] * A[6], A[2] * A[3] - A[0] * A[5],
         A[3] * A[7] - A[4] * A[6], A[1] * A[6] - A[0] * A[7], A[0] * A[4] - A[1] * A[3]};
  return true;
}

/// Solves A x = b for a 3 x 3 A; false if A is singular to round-off.
inline bool solve3(const Mat3& A, const Vec3& b, Vec3& x)
{
  Mat3 adj;
  double det;
  if (!adjugate3(A, adj, det))
    return false;
  for (int i = 0; i < 3; ++i)
    x[i] = (adj[3 * i] * b[0] + adj[3 * i + 1] * b[1] + adj[3 * i + 2] * b[2]) / det;
  return true;
}

/// Whether a 3 x 3 A is regular, as solve3() and invert3() decide it.
inline bool regular3(const Mat3& A)
{
  Mat3 adj;
  double det;
  return adjugate3(A, adj, det);
}

/// A^-1 of a 3 x 3 A (row-major), each entry as solve3() of a unit vector
/// gives it; false if A is singular to round-off (as solve3()).
inline bool invert3(const Mat3& A, Mat3& inverse)
{
  Mat3 adj;
  double det;
  if (!adjugate3(A, adj, det))
    return false;
  for (int k = 0; k < 9; ++k)
    inverse[k] = adj[k] / det;
  return true;
}

/// Eigenvalues (descending) and unit eigenvectors (rows of `vectors`, a
/// right-handed frame) of a symmetric 3 x 3 matrix, by Jacobi rotations.
inline void symmetric_eigen(Mat3 A, Vec3& values, Mat3& vectors)
{
  Mat3 V = {1, 0, 0, 0, 1, 0, 0, 0, 1}; // columns: eigenvectors
  for (int sweep = 0; sweep < 50; ++sweep)
  {
    const double off = A[1] * A[1] + A[2] * A[2] + A[5] * A[5];
    const double diag = A[0] * A[0] + A[4] * A[4] + A[8] * A[8];
    if (off <= 1e-30 * diag || off == 0)
      break;
    for (const auto [p, q] : {std::array<int, 2>{0, 1}, {0, 2}, {1, 2}})
    {
      const double apq = A[3 * p + q];
      if (apq == 0)
        continue;
      const double theta = (A[3 * q + q] - A[3 * p + p]) / (2 * apq);
      const double t = (theta >= 0 ? 1 : -1) / (std::abs(theta) + std::sqrt(theta * theta + 1));
      const double c = 1 / std::sqrt(t * t + 1), s = t * c;
      for (int k = 0; k < 3; ++k) // A <- A J (columns p, q)
      {
        const double akp = A[3 * k + p], akq = A[3 * k + q];
        A[3 * k + p] = c * akp - s * akq;
        A[3 * k + q] = s * akp + c * akq;
      }
      for (int k = 0; k < 3; ++k) // A <- J^T A (rows p, q)
      {
        const double apk = A[3 * p + k], aqk = A[3 * q + k];
        A[3 * p + k] = c * apk - s * aqk;
        A[3 * q + k] = s * apk + c * aqk;
      }
      for (int k = 0; k < 3; ++k)
      {
        const double vkp = V[3 * k + p], vkq = V[3 * k + q];
        V[3 * k + p] = c * vkp - s * vkq;
        V[3 * k + q] = s * vkp + c * vkq;
      }
    }
  }
  std::array<int, 3> order = {0, 1, 2};
  const Vec3 d = {A[0], A[4], A[8]};
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j)
      if (d[order[j]] > d[order[i]])
        std::swap(order[i], order[j]);
  for (int i = 0; i < 3; ++i)
  {
    values[i] = d[order[i]];
    for (int k = 0; k < 3; ++k)
      vectors[3 * i + k] = V[3 * k + order[i]];
  }
  // Right-handed: the third row is the cross product of the first two.
  vectors[6] = vectors[1] * vectors[5] - vectors[2] * vectors[4];
  vectors[7] = vectors[2] * vectors[3] - vectors[0] * vectors[5];
  vectors[8] = vectors[0] * vectors[4] - vectors[1] * vectors[3];
}
} // namespace pushout::bulk

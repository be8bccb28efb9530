// The width of a hexahedral cell along a crack's normal: the band over which
// the crack band smears a crack's opening (bulk/CrackBand.h, the h of
// epsilon = epsilon_e + sym(w (x) n) / h). Two rules, cracking.band_width
// (docs/cracking.md, "The band's width"):
//
// - projected: the extent of the cell's vertices along n. Exact for a
//   crack that runs along a row of cells whose faces it is parallel to,
//   and the mean volume per unit of crack area of the cells that a plane
//   of normal n cuts; too wide where the crack runs along a row of cells
//   whose faces it crosses obliquely (sheared cells, or a normal tilted
//   across elongated ones): a cell 20 mm along the crack's normal, 10 mm
//   across and sheared by 0.3 has an extent of 23 mm.
// - row: the width of the thinnest row of cells the crack can run along.
//   A crack that localises in the row between two opposite faces of the
//   cell, whose reference coordinate is xi_i, opens the row by a jump
//   w n whose normal strain is w |grad xi_i . n|, so the row's band is
//   1 / |grad xi_i . n| (Oliver 1989's width, for the step function of
//   that face pair); the rule takes the smallest of the three, at the
//   cell's centre, and never more than the projected extent. Exact for
//   the sheared cell above (20 mm), equal to the projected extent where n
//   runs along an edge or a diagonal of a box cell, and h / cos(theta)
//   (against the projected h cos(theta) + b sin(theta)) for a normal at
//   theta from an edge of length h in a box cell h x b, while tan(theta) <=
//   b / h (past it the other row's b / sin(theta)). Unlike Oliver's width
//   through the centre's plane, it is continuous in n and positive on any
//   cell with a volume.
//
// Vertices in DOLFINx's (basix's) order for a hexahedron: vertex v at the
// reference point (v & 1, (v >> 1) & 1, (v >> 2) & 1). Lengths in mm.
#pragma once

#include "../bulk/Voigt.h"
#include <algorithm>
#include <array>
#include <cmath>

namespace pushout::model
{
using CellVertices = std::array<bulk::Vec3, 8>; ///< a hexahedron's vertices [mm]

/// The extent of the cell's vertices along the unit normal n [mm].
inline double projected_width(const CellVertices& x, const bulk::Vec3& n)
{
  double lo = INFINITY, hi = -INFINITY;
  for (const bulk::Vec3& p : x)
  {
    const double s = p[0] * n[0] + p[1] * n[1] + p[2] * n[2];
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
  return hi - lo;
}

/// The width along the unit normal n of the thinnest row of cells the crack
/// can run along (the file's head) [mm]: min over the reference directions
/// i of 1 / |grad xi_i . n| at the centre, at most projected_width.
inline double row_width(const CellVertices& x, const bulk::Vec3& n)
{
  // The map's Jacobian at the centre, J[a][i] = d x_a / d xi_i: each edge
  // direction's mean over the cell's four edges along it.
  double J[3][3] = {};
  for (int v = 0; v < 8; ++v)
    for (int i = 0; i < 3; ++i)
    {
      const double sign = (v >> i) & 1 ? 0.25 : -0.25;
      for (int a = 0; a < 3; ++a)
        J[a][i] += sign * x[std::size_t(v)][std::size_t(a)];
    }
  // grad xi_i is row i of J^-1, (J^-1)[i][a] = cof[a][i] / det with
  // cof[a][i] the cofactor of J[a][i].
  double cof[3][3];
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < 3; ++i)
    {
      const int a1 = (a + 1) % 3, a2 = (a + 2) % 3, i1 = (i + 1) % 3, i2 = (i + 2) % 3;
      cof[a][i] = J[a1][i1] * J[a2][i2] - J[a1][i2] * J[a2][i1];
    }
  const double det = J[0][0] * cof[0][0] + J[0][1] * cof[0][1] + J[0][2] * cof[0][2];
  double width = projected_width(x, n);
  // A flat cell (its volume below round-off of its edges' product) has no
  // rows: its extent.
  double edges = 1;
  for (int i = 0; i < 3; ++i)
    edges *= std::sqrt(J[0][i] * J[0][i] + J[1][i] * J[1][i] + J[2][i] * J[2][i]);
  if (!(std::abs(det) > 1e-12 * edges))
    return width;
  for (int i = 0; i < 3; ++i)
  {
    // grad xi_i = row i of J^-1 = (cof[0][i], cof[1][i], cof[2][i]) / det
    const double g_n = (cof[0][i] * n[0] + cof[1][i] * n[1] + cof[2][i] * n[2]) / det;
    if (g_n != 0)
      width = std::min(width, 1 / std::abs(g_n));
  }
  return width;
}
} // namespace pushout::model

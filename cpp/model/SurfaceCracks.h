// The concrete's cracks as seen on the slice's outer faces: what a
// crack-width gauge there would read (docs/cracking.md, "Reading the
// cracks").
//
// The slice's mesh is extruded through its thickness, so its cells stand in
// columns that share their (x, y). Each column of the cracking concrete
// carries the thickness mean of its cells' widest normal crack opening; each
// column on an outer face carries a gauge increment: the crack strain along
// the face, t . eps_cr . t with t the face's horizontal tangent, integrated
// across the column along t, as the thickness mean. A crack band of
// opening w and normal n adds (w . t)(n . t) / h over a crossing of length
// h / |n . t|, that is w . t: a gauge across one cracked band reads the
// band's opening along the gauge, as across a discrete crack.
//
// Along the faces (the columns in order of their angle about the tube axis)
// a surface crack is a run of adjacent columns whose increments exceed the
// gauge's resolution; its width is the sum of the run's increments (a
// crack smeared over two or three bands reads whole), its direction the
// angle of the run's widest column about the tube axis, and its length how
// far it runs in: its path is followed from the face inwards through the
// cracked columns of the concrete (mean opening above the resolution), from
// each column to the widest cracked neighbour nearer the tube axis, to the
// crack's tip or the tube, and the length is the straight line from its
// mouth on the face to that end. On a model cut by symmetry no run crosses
// the cut, and a run that reaches a symmetry plane is completed by its
// mirror image and measured along the plane. A run all round the faces (on
// a cut model: from one plane to the other, all round once mirrored) is one
// crack, whose width sums every band's opening: on a slice cracked evenly
// all round (a uniform ring) that is the ring's whole opening, more than a
// gauge across any one of its bands reads.
//
// Pure functions of their inputs: rank 0 calls them on the gathered columns.
#pragma once

#include <algorithm>
#include <array>
#include <vector>

namespace pushout::model
{
/// A column of cracking cells through the thickness.
struct CrackColumn
{
  double x = 0, y = 0; ///< centre [mm]
  double opening = 0;  ///< thickness mean of the cells' widest normal opening [mm]
  double size = 0;     ///< horizontal extent of its cells [mm]
  /// Its outline seen along the axis: corners (x, y) counter-clockwise [mm].
  std::array<double, 8> outline{};
};

/// A column on an outer face.
struct FaceColumn
{
  double angle = 0;    ///< of its centre about the tube axis, from +x towards +y [rad]
  double x = 0, y = 0; ///< centre [mm]
  double gauge = 0;    ///< thickness mean of the crack opening across it along the face [mm]
  /// Where a crack through it meets the face: its centre moved out to the
  /// face along the face's normal (x, y) [mm].
  std::array<double, 2> mouth{};
};

struct SurfaceCrack
{
  double angle_deg = 0; ///< its widest column's direction from the tube axis, in [0, 360)
  double width_mm = 0;  ///< the gauge's reading across it
  /// How far it runs in from the face towards the tube axis: from its mouth
  /// to its tip (or the tube's surface), straight; along the plane for a
  /// crack on a symmetry plane.
  double length_mm = 0;
  /// One run all round the specimen's faces (its width the whole run's):
  /// no mirror images.
  bool all_round = false;
};

/// The finest the gauge resolves whatever the visible width [mm].
constexpr double max_gauge_resolution = 0.005;

/// The gauge's resolution [mm] when a crack counts as visible from
/// `visible_width` [mm] (cracking.visible_width): a tenth of it, at most
/// max_gauge_resolution. Raising the visible width counts fewer cracks; it
/// does not make the narrower ones vanish from the readings.
inline double gauge_resolution(double visible_width)
{
  return std::min(visible_width / 10, max_gauge_resolution);
}

/// The surface cracks of the `faces` columns (any order; their angles
/// close the perimeter cyclically), widest first. `resolution` the smallest
/// increment a gauge reads [mm]; `columns` the cracking concrete's columns,
/// through which lengths are followed towards `axis` (the tube axis) up to
/// the tube's surface at `tube_radius` [mm]. `copies`: the specimen's
/// copies of the part modelled; above 1 the model is cut by symmetry (its
/// planes through the axis, along x or y), so the columns do not close
/// round the slice: the widest angular gap between neighbours is the cut,
/// no run crosses it, and a run that reaches it is half of a crack that
/// its mirror image completes (its width doubled, its direction the
/// plane's); a run from one plane to the other is the specimen's crack all
/// round (its width `copies` times the run's). The cracks are those of the
/// part modelled, but for that one.
std::vector<SurfaceCrack> surface_cracks(std::vector<FaceColumn> faces,
                                         const std::vector<CrackColumn>& columns,
                                         std::array<double, 2> axis, double tube_radius,
                                         double resolution, int copies = 1);
} // namespace pushout::model

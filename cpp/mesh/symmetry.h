// Exact symmetry: a push-out slice whose tube is centred in x in a square
// (or any circle) is symmetric about the plane x = xc, and one whose tube is
// centred in y about y = yc; so is its solution (the laws are isotropic in
// the interface plane, the loads are symmetric) if the crack planes are: the
// set of crack directions must be its own mirror image. Then half of the
// mesh (or a quarter, about both planes) with symmetry conditions gives the
// whole specimen's curve at a half (a quarter) of the dofs.
//
// The part is cut from the full mesh: slice.geo's blocks are mirror images
// about both planes, and with an even number of elements per quarter the
// planes are mesh surfaces; slice_cracked.geo has a sector boundary on every
// symmetry plane (cracks.h: slice_sectors). So the part's nodes are exactly
// the full model's.
//
// A crack plane on a symmetry plane (the main crack of an off-centre tube,
// to its nearest face) keeps one face: a mirror crack (MeshData.h
// CrackPlane::mirror), whose opening is twice the face's normal displacement
// and whose energy the part holds half of (interface/Interface.h). A crack
// plane outside the kept part is the image of one inside it and is cut away.
//
// A cut forces the symmetric solution. Where two crack planes are mirror
// images of each other (four cracks at 90 degrees), the whole slice may
// open one of them more than its image (localisation, a branch the cut model
// cannot take), so model.symmetry = "auto" cuts only along planes that every
// crack plane lies on; "symmetric" cuts wherever the geometry allows.
#pragma once

#include "MeshData.h"
#include "MeshInput.h"
#include <array>
#include <string>
#include <vector>

namespace pushout::mesh
{
/// The mirror planes of a model: x = xc (kept: x >= xc) and y = yc (kept:
/// y >= yc).
struct Symmetry
{
  bool x_plane = false;
  bool y_plane = false;
  int copies() const { return (x_plane ? 2 : 1) * (y_plane ? 2 : 1); }
  /// "full", "half" or "quarter".
  std::string name() const;
};

/// Where a ray from the tube axis at `angle` [rad] lies with respect to the
/// part a symmetry keeps: inside it, on one of its symmetry planes, or
/// outside it (the image of a ray inside).
enum class Side
{
  inside,
  on_plane,
  outside
};
Side side_of(Symmetry s, double angle);

/// The planes `mesh` was cut along (MeshData::symmetry_planes).
inline Symmetry symmetry_of(const MeshData& mesh)
{
  return {mesh.symmetry_planes[0], mesh.symmetry_planes[1]};
}

/// The directions [rad] of a ray from the tube axis at `angle` and of its
/// mirror images in the whole specimen, `angle` first: copies() of them,
/// half as many for a ray on a symmetry plane (its own image about it).
std::vector<double> images_of(Symmetry s, double angle);

/// The planes the slice and its crack planes are symmetric about (geometry
/// only: the meshes of the full and of the cut model are the same).
Symmetry geometric_symmetry(const MeshInput& in);

/// The planes the run is cut along: those of geometric_symmetry() of a
/// push-out with model.symmetry = "symmetric" (its fields then the part's)
/// and an even mesh.elements_per_quarter (without cracks); with "auto" only
/// those that every crack plane lies on, and none with field output (fields
/// cover the whole specimen). `why` says why the model is not cut at all, or not about both
/// planes ("" if it is a quarter).
Symmetry model_symmetry(const MeshInput& in, std::string& why);

/// Keeps the cells in the part (x >= xc if s.x_plane, y >= yc if s.y_plane;
/// by centroid) and the joint elements between them, makes the crack planes
/// on a symmetry plane mirror cracks and cuts away the others' images,
/// renumbers nodes and cells, and records the symmetry. Throws logic_error
/// if a cell straddles a plane (not a mesh surface).
void keep_symmetric_part(MeshData& mesh, Symmetry s, std::array<double, 2> centre);
} // namespace pushout::mesh

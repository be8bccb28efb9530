// The size of the mesh a scene asks for, counted from the mesh keys before
// any meshing: meshes/slice.geo is a structured block mesh, so its element
// counts follow from its block divisions (computed here, for gmsh too). Used to refuse a run
// that cannot fit in memory before gmsh spends minutes on it
// (record/ResourceGuard.h).
#pragma once

#include "MeshInput.h"
#include "symmetry.h"
#include <cstdint>
#include <numbers>

namespace pushout::mesh
{
struct MeshSize
{
  std::int64_t cells = 0;           ///< hexahedra of the model (a part or the full slice)
  std::int64_t cells_generated = 0; ///< hexahedra gmsh generates (always the full slice)
  std::int64_t concrete_cells = 0;  ///< of the model's hexahedra, the concrete's
  std::int64_t nodes = 0;           ///< mesh nodes, interface nodes counted twice
  std::int64_t dofs = 0;            ///< displacement dofs (3 per node of the degree)
  std::int64_t joint_elements = 0;  ///< joint elements (interface and crack planes)
  std::int64_t interface_dofs = 0;  ///< 6 per node pair of the joints (both sides)
  Symmetry symmetry;                ///< the planes the model is cut along (symmetry.h)
};

/// The block divisions of meshes/slice.geo and meshes/slice_cracked.geo for
/// a push-out scene, computed here alone and passed to gmsh as constants
/// (mesh/generate.cpp); the mesh size estimate counts cells from them too.
///
/// The graded block runs from the support circle to the outer boundary
/// along one line per block corner (slice.geo) or sector boundary
/// (slice_cracked.geo), each with the same number of elements and growth
/// (gmsh's progression). They are sized on the shortest way out, Lr
/// (support circle to the nearest side): from about the interface size h
/// towards outer_size_ratio h, growing by graded_growth_max at most. The
/// other lines are longer (to the square's corners, or across an off-centre
/// tube), and the same divisions stretch their elements by their length
/// over Lr. Where that makes the longest line's first element more than
/// graded_growth_max h (a jump from the ring's elements of h), the lines get
/// enough elements to start it at graded_growth_max h (the shorter ways
/// then start with smaller elements: the corroded demo's 10 mm cover at
/// 0.21 h), and either (mesh.graded_refinement = "near_tube") grow by
/// graded_growth_max at most, with the growth that fills it so, where
/// outer_size_ratio no longer applies and the outer elements keep their
/// size as h falls, or ("whole") grow to outer_size_ratio times the first,
/// as many more as that takes, so that every graded element shrinks with h. A tube 6 mm
/// from a side had one element across the other 70 mm of concrete before,
/// and its curve moved by 1.7 % from 24 to 32 elements per quarter
/// (docs/corrosion.md, "The mesh").
struct SliceDivisions
{
  std::int64_t circumferential; ///< elements per quarter circumference (nq)
  std::int64_t steel;           ///< radial elements in the tube wall (ns)
  std::int64_t ring;            ///< radial elements from R to the support circle (nr1)
  std::int64_t graded;          ///< radial elements from there to the boundary (nr2)
  std::int64_t thickness;       ///< elements through the thickness (nz)
  /// The graded lines' growth, each element to the next (gmsh's
  /// progression, from the support circle out; 1: uniform).
  double growth = 1;
};
SliceDivisions slice_divisions(const MeshInput& in);

/// The size of an interface element along the tube's circumference [mm]:
/// a quarter of the circumference of radius `tube_radius` [mm] over
/// `per_quarter` elements (mesh.elements_per_quarter).
inline double interface_element_size(double tube_radius, std::int64_t per_quarter)
{
  return std::numbers::pi / 2 * tube_radius / double(per_quarter);
}

/// The most the graded block's elements grow from one to the next (and its
/// first ones from the ring's, of the interface size): where reaching
/// outer_size_ratio times the interface size would take more, they grow by
/// this much at most and stay smaller.
inline constexpr double graded_growth_max = 1.6;

/// The size of the scene's mesh and model (push-out or single joint).
MeshSize predict_size(const MeshInput& in);
} // namespace pushout::mesh

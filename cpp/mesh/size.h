// The size of the mesh a scene asks for, counted from the mesh keys before
// any meshing: meshes/slice.geo is a structured block mesh, so its element
// counts follow from its block divisions in closed form. Used to refuse a run
// that cannot fit in memory before gmsh spends minutes on it
// (record/ResourceGuard.h).
#pragma once

#include "MeshInput.h"
#include "symmetry.h"
#include <cstdint>

namespace pushout::mesh
{
struct MeshSize
{
  std::int64_t cells = 0;           ///< hexahedra of the model (a part or the full slice)
  std::int64_t cells_generated = 0; ///< hexahedra gmsh generates (always the full slice)
  std::int64_t nodes = 0;           ///< mesh nodes, interface nodes counted twice
  std::int64_t dofs = 0;            ///< displacement dofs (3 per node of the degree)
  std::int64_t joint_elements = 0;  ///< joint elements (interface and crack planes)
  std::int64_t interface_dofs = 0;  ///< 6 per node pair of the joints (both sides)
  Symmetry symmetry;                ///< the planes the model is cut along (symmetry.h)
};

/// The block divisions of meshes/slice.geo for a push-out scene. These
/// formulas mirror the .geo file: change both together (the e2e test
/// test_resource_estimate_within_factor_2 compares them with generated meshes).
struct SliceDivisions
{
  std::int64_t circumferential; ///< elements per quarter circumference (nq)
  std::int64_t steel;           ///< radial elements in the tube wall (ns)
  std::int64_t ring;            ///< radial elements from R to the support circle (nr1)
  std::int64_t graded;          ///< radial elements from there to the boundary (nr2)
  std::int64_t thickness;       ///< elements through the thickness (nz)
};
SliceDivisions slice_divisions(const MeshInput& in);

/// The most the graded block's elements grow from one to the next (q_max of
/// meshes/slice.geo): where reaching outer_size_ratio times the interface
/// size within the block would take more, they grow by this much at most
/// and stay smaller.
inline constexpr double graded_growth_max = 1.6;

/// The size of the scene's mesh and model (push-out or single joint).
MeshSize predict_size(const MeshInput& in);
} // namespace pushout::mesh

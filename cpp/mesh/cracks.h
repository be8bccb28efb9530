// Crack planes of a push-out slice (scene [[crack]] tables;
// docs/corrosion.md): planes through the whole thickness of the concrete,
// each along a ray from the tube axis at angle theta in the x-y plane, from
// the interface (r = R) to the slice's outer boundary.
//
// Meshing: with cracks the slice is meshed from meshes/slice_cracked.geo,
// whose circumference is cut into sectors at the block corners and at every
// crack direction (slice_sectors), so that each crack plane is a mesh
// surface; then insert_cracks duplicates the concrete nodes on each plane and
// pairs the facets on its two sides into joint elements, as insert_interface
// does for the steel-concrete surface. Without cracks nothing here applies
// and the mesh is slice.geo's, unchanged.
#pragma once

#include "MeshData.h"
#include "MeshInput.h"
#include <array>
#include <cstdint>
#include <vector>

namespace pushout::mesh
{
/// The sectors of meshes/slice_cracked.geo: boundaries at increasing angles
/// from the tube centre (the block corners, the cracks and the symmetry
/// planes of mesh/symmetry.h geometric_symmetry), each with its
/// outer point on the slice boundary; sector i runs from boundary i to
/// boundary i + 1 (cyclically) with elements[i] elements around.
struct SliceSectors
{
  std::vector<double> angles;               ///< [rad], increasing, within one turn
  std::vector<std::array<double, 2>> outer; ///< outer point of each boundary [mm]
  std::vector<std::int64_t> elements;       ///< elements around each sector
  std::int64_t around() const;              ///< elements around the whole circumference
};
SliceSectors slice_sectors(const MeshInput& in);

/// Splits the concrete along each crack plane (rays from `centre` at
/// `angles`, r >= R): the nodes on a plane get copies on its + side (the
/// side its normal (-sin, cos, 0) points to), the facets on the two sides
/// become the plane's joint elements (minus side first, normal from minus
/// to plus), the steel-concrete pairs on the + side take the copies, and
/// the nodes of the plane on the slice's outer boundary (largest r) are its
/// mouth. Call after insert_interface.
void insert_cracks(MeshData& mesh, std::array<double, 2> centre, double R,
                   const std::vector<double>& angles);
} // namespace pushout::mesh

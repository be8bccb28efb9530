// Plain mesh arrays: what the generator produces and the model consumes.
#pragma once

#include <array>
#include <cstdint>
#include <mpi.h>
#include <vector>

namespace pushout::mesh
{
/// Cell material tags (gmsh physical volumes in meshes/*.geo).
enum Material : std::int32_t
{
  steel = 1,
  concrete = 2
};

/// Local vertices of the 6 facets of a DOLFINx hexahedron, tensor order.
inline constexpr std::array<std::array<int, 4>, 6> hex_facets = {
    {{0, 1, 2, 3}, {0, 1, 4, 5}, {0, 2, 4, 6}, {1, 3, 5, 7}, {2, 3, 6, 7}, {4, 5, 6, 7}}};

/// A joint element: a facet on the minus side and its partner facet on the
/// plus side; the jump is w = u_plus - u_minus. On the steel-concrete
/// interface minus is steel and plus is concrete; on a crack plane they are
/// its two faces. Nodes are in tensor order (0:(0,0) 1:(1,0) 2:(0,1) 3:(1,1)
/// of the facet's (xi,eta)) and oriented so that dx/dxi x dx/deta points
/// from minus to plus. Node i of one side sits where node i of the other
/// sits.
struct InterfacePair
{
  std::array<std::int64_t, 4> minus;
  std::array<std::int64_t, 4> plus;
  std::int64_t minus_cell; ///< the cell of the minus facet
  std::int64_t plus_cell;  ///< the cell of the plus facet
};

/// A crack plane in the concrete (mesh/cracks.h): its joint elements and
/// the node pairs of its mouth on the slice's outer boundary.
///
/// On a model cut by symmetry (mesh/symmetry.h) a plane may lie on a
/// symmetry plane: then only one face is meshed, and each pair's minus
/// nodes are its plus nodes, standing for their mirror images (`mirror`,
/// the symmetry plane's unit normal into the kept part: the minus side is
/// x - 2 (x . mirror) mirror of the plus side). A plane outside the kept
/// part has no pairs; `image_of` is the plane that is its mirror image.
struct CrackPlane
{
  double angle = 0;                               ///< direction from the tube axis [rad]
  std::vector<InterfacePair> pairs;               ///< minus side: clockwise of the ray
  std::vector<std::array<std::int64_t, 2>> mouth; ///< (minus, plus) nodes at the outer face
  std::array<double, 3> mirror = {0, 0, 0};       ///< nonzero: a plane on a symmetry plane
  int image_of = -1;                              ///< >= 0: cut away, the image of that plane

  bool mirrored() const { return mirror != std::array<double, 3>{0, 0, 0}; }
};

/// Hexahedral mesh with duplicated nodes on the steel-concrete surface.
struct MeshData
{
  std::vector<double> x;              ///< [node][3] coordinates, mm
  std::vector<std::int64_t> cells;    ///< [cell][8] nodes, DOLFINx order
  std::vector<std::int32_t> material; ///< [cell] Material
  std::vector<InterfacePair> pairs;   ///< steel-concrete joint elements
  std::vector<CrackPlane> cracks;     ///< crack planes (push-out with [[crack]])
  /// The specimen is `copies` mirror images of this mesh: 1; 2 for a half
  /// model in x >= symmetry_center[0] (symmetry_planes[0]) or in y >=
  /// symmetry_center[1] (symmetry_planes[1]); 4 for a quarter model in both
  /// (mesh/symmetry.h).
  int copies = 1;
  std::array<double, 2> symmetry_center = {0, 0};
  std::array<bool, 2> symmetry_planes = {false, false}; ///< x = xc, y = yc

  std::size_t num_nodes() const { return x.size() / 3; }
  std::size_t num_cells() const { return material.size(); }
};

/// Orients a pair: if the bilinear normal at the facet centre points
/// towards `minus_centroid` (the minus cell's centroid), swaps xi and eta.
void orient(InterfacePair& pair, const MeshData& mesh, const std::array<double, 3>& minus_centroid);

/// Centroid of cell c [mm].
std::array<double, 3> centroid(const MeshData& mesh, std::size_t c);

/// Splits the nodes shared by steel and concrete cells: steel cells get new
/// copies of them, and every steel facet lying on them becomes a joint
/// element paired with the concrete facet at the same place.
void insert_interface(MeshData& mesh);

/// Copies rank `root`'s mesh to every process of `comm`.
void broadcast(MeshData& mesh, MPI_Comm comm, int root = 0);
} // namespace pushout::mesh

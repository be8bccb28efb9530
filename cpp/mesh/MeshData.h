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

/// A joint element: a steel facet and its concrete partner facet. Nodes are
/// in tensor order (0:(0,0) 1:(1,0) 2:(0,1) 3:(1,1) of the facet's (xi,eta))
/// and oriented so that dx/dxi x dx/deta points from steel to concrete.
/// Node i of the steel side sits where node i of the concrete side sits.
struct InterfacePair
{
  std::array<std::int64_t, 4> steel;
  std::array<std::int64_t, 4> concrete;
  std::int64_t steel_cell;    ///< the cell of the steel facet
  std::int64_t concrete_cell; ///< the cell of the concrete facet
};

/// Hexahedral mesh with duplicated nodes on the steel-concrete surface.
struct MeshData
{
  std::vector<double> x;              ///< [node][3] coordinates, mm
  std::vector<std::int64_t> cells;    ///< [cell][8] nodes, DOLFINx order
  std::vector<std::int32_t> material; ///< [cell] Material
  std::vector<InterfacePair> pairs;   ///< joint elements
  /// The specimen is `copies` mirror images of this mesh: 1, or 4 for a
  /// quarter model in x >= symmetry_center[0], y >= symmetry_center[1]
  /// (mesh/symmetry.h).
  int copies = 1;
  std::array<double, 2> symmetry_center = {0, 0};

  std::size_t num_nodes() const { return x.size() / 3; }
  std::size_t num_cells() const { return material.size(); }
};

/// Splits the nodes shared by steel and concrete cells: steel cells get new
/// copies of them, and every steel facet lying on them becomes a joint
/// element paired with the concrete facet at the same place.
void insert_interface(MeshData& mesh);

/// Copies rank `root`'s mesh to every process of `comm`.
void broadcast(MeshData& mesh, MPI_Comm comm, int root = 0);
} // namespace pushout::mesh

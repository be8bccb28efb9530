#include "MeshData.h"
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace pushout::mesh
{
namespace
{
std::array<double, 3> node(const MeshData& m, std::int64_t i)
{
  return {m.x[3 * i], m.x[3 * i + 1], m.x[3 * i + 2]};
}
} // namespace

std::array<double, 3> centroid(const MeshData& mesh, std::size_t c)
{
  std::array<double, 3> x{0, 0, 0};
  for (int i = 0; i < 8; ++i)
    for (int d = 0; d < 3; ++d)
      x[d] += mesh.x[3 * mesh.cells[8 * c + i] + d] / 8;
  return x;
}

void orient(InterfacePair& pair, const MeshData& mesh, const std::array<double, 3>& minus_centroid)
{
  const auto x0 = node(mesh, pair.plus[0]), x1 = node(mesh, pair.plus[1]),
             x2 = node(mesh, pair.plus[2]), x3 = node(mesh, pair.plus[3]);
  std::array<double, 3> dxi, deta, mid;
  for (int d = 0; d < 3; ++d)
  {
    dxi[d] = 0.5 * (x1[d] - x0[d] + x3[d] - x2[d]);
    deta[d] = 0.5 * (x2[d] - x0[d] + x3[d] - x1[d]);
    mid[d] = 0.25 * (x0[d] + x1[d] + x2[d] + x3[d]) - minus_centroid[d];
  }
  const std::array<double, 3> n = {dxi[1] * deta[2] - dxi[2] * deta[1],
                                   dxi[2] * deta[0] - dxi[0] * deta[2],
                                   dxi[0] * deta[1] - dxi[1] * deta[0]};
  if (n[0] * mid[0] + n[1] * mid[1] + n[2] * mid[2] < 0)
  {
    std::swap(pair.minus[1], pair.minus[2]);
    std::swap(pair.plus[1], pair.plus[2]);
  }
}

void insert_interface(MeshData& mesh)
{
  const std::size_t n_nodes = mesh.num_nodes();
  std::vector<std::uint8_t> used_by(n_nodes, 0); // bit 1 steel, bit 2 concrete
  for (std::size_t c = 0; c < mesh.num_cells(); ++c)
    for (int i = 0; i < 8; ++i)
      used_by[mesh.cells[8 * c + i]] |= mesh.material[c] == steel ? 1 : 2;

  // Concrete facets on the shared nodes, by their sorted node ids.
  std::map<std::array<std::int64_t, 4>, std::int64_t> concrete_facet;
  for (std::size_t c = 0; c < mesh.num_cells(); ++c)
  {
    if (mesh.material[c] != concrete)
      continue;
    const std::int64_t* cell = mesh.cells.data() + 8 * c;
    for (const auto& f : hex_facets)
    {
      std::array<std::int64_t, 4> key;
      bool shared = true;
      for (int i = 0; i < 4; ++i)
      {
        key[i] = cell[f[i]];
        shared = shared && used_by[key[i]] == 3;
      }
      if (shared)
      {
        std::sort(key.begin(), key.end());
        concrete_facet[key] = std::int64_t(c);
      }
    }
  }

  // Steel copies of the shared nodes.
  std::vector<std::int64_t> copy(n_nodes, -1);
  for (std::size_t i = 0; i < n_nodes; ++i)
  {
    if (used_by[i] == 3)
    {
      copy[i] = std::int64_t(mesh.num_nodes());
      for (int d = 0; d < 3; ++d)
        mesh.x.push_back(mesh.x[3 * i + d]);
    }
  }

  for (std::size_t c = 0; c < mesh.num_cells(); ++c)
  {
    if (mesh.material[c] != steel)
      continue;
    std::int64_t* cell = mesh.cells.data() + 8 * c;
    const std::array<double, 3> cell_centroid = centroid(mesh, c);

    for (const auto& f : hex_facets)
    {
      bool on_interface = true;
      for (int v : f)
        on_interface = on_interface && copy[cell[v]] >= 0;
      if (!on_interface)
        continue;
      InterfacePair pair;
      for (int i = 0; i < 4; ++i)
      {
        pair.plus[i] = cell[f[i]];
        pair.minus[i] = copy[cell[f[i]]];
      }
      std::array<std::int64_t, 4> key = pair.plus;
      std::sort(key.begin(), key.end());
      const auto partner = concrete_facet.find(key);
      if (partner == concrete_facet.end())
        throw std::runtime_error("interface facet without a concrete partner");
      pair.minus_cell = std::int64_t(c);
      pair.plus_cell = partner->second;
      orient(pair, mesh, cell_centroid);
      mesh.pairs.push_back(pair);
    }
    for (int i = 0; i < 8; ++i)
      if (copy[cell[i]] >= 0)
        cell[i] = copy[cell[i]];
  }
  if (mesh.pairs.empty())
    throw std::runtime_error("mesh has no steel-concrete interface");
}
} // namespace pushout::mesh

namespace pushout::mesh
{
namespace
{
template <typename T> void broadcast_vector(std::vector<T>& v, MPI_Comm comm, int root)
{
  std::uint64_t n = v.size();
  MPI_Bcast(&n, 1, MPI_UINT64_T, root, comm);
  v.resize(n);
  MPI_Bcast(v.data(), int(n * sizeof(T)), MPI_BYTE, root, comm);
}
} // namespace

void broadcast(MeshData& mesh, MPI_Comm comm, int root)
{
  broadcast_vector(mesh.x, comm, root);
  broadcast_vector(mesh.cells, comm, root);
  broadcast_vector(mesh.material, comm, root);
  broadcast_vector(mesh.pairs, comm, root);
  std::uint64_t n = mesh.cracks.size();
  MPI_Bcast(&n, 1, MPI_UINT64_T, root, comm);
  mesh.cracks.resize(n);
  for (CrackPlane& crack : mesh.cracks)
  {
    MPI_Bcast(&crack.angle, 1, MPI_DOUBLE, root, comm);
    broadcast_vector(crack.pairs, comm, root);
    broadcast_vector(crack.mouth, comm, root);
  }
}
} // namespace pushout::mesh

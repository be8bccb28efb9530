#include "Model.h"
#include "../common/mpi_errors.h"
#include "../common/petsc_check.h"
#include "../interface/Quadrature.h"
#include "../laws/LawRegistry.h"
#include "elasticity.h"
#include <algorithm>
#include <cmath>
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/fem/utils.h>
#include <dolfinx/graph/AdjacencyList.h>
#include <dolfinx/la/SparsityPattern.h>
#include <dolfinx/la/Vector.h>
#include <dolfinx/la/petsc.h>
#include <dolfinx/mesh/cell_types.h>
#include <dolfinx/mesh/utils.h>

namespace pushout::model
{
using petsc::check;

namespace
{
using dolfinx::fem::Function;

/// The cells that joint elements tie together (a steel-concrete pair, a
/// crack pair, and chains of them where a crack meets the interface), as a
/// representative cell per cell (union-find).
std::vector<std::int64_t> joined_cells(const mesh::MeshData& data)
{
  std::vector<std::int64_t> root(data.num_cells());
  for (std::size_t c = 0; c < root.size(); ++c)
    root[c] = std::int64_t(c);
  const auto find = [&root](std::int64_t c)
  {
    while (root[c] != c)
      c = root[c] = root[root[c]];
    return c;
  };
  const auto join = [&](const mesh::InterfacePair& p)
  { root[find(p.plus_cell)] = find(p.minus_cell); };
  for (const mesh::InterfacePair& p : data.pairs)
    join(p);
  for (const mesh::CrackPlane& crack : data.cracks)
    for (const mesh::InterfacePair& p : crack.pairs)
      join(p);
  for (std::size_t c = 0; c < root.size(); ++c)
    root[c] = find(std::int64_t(c));
  return root;
}

/// The default graph partitioner decides the owners; then the cells tied by
/// joint elements follow one of them (joined_cells), so that one process
/// owns both sides of every joint element. Every cell is also ghosted on the
/// processes that own a cell sharing a vertex with it
/// (GhostMode::shared_vertex): DOLFINx 0.5 finds shared vertices only
/// through ghosts or shared facets, and the partition may touch along edges
/// only.
dolfinx::mesh::CellPartitionFunction pair_keeping_partitioner(const mesh::MeshData& data)
{
  return [&data](MPI_Comm comm, int nparts, int tdim,
                 const dolfinx::graph::AdjacencyList<std::int64_t>& cells, dolfinx::mesh::GhostMode)
  {
    const dolfinx::graph::AdjacencyList<std::int32_t> dest =
        dolfinx::mesh::create_cell_partitioner()(comm, nparts, tdim, cells,
                                                 dolfinx::mesh::GhostMode::none);
    if (cells.num_nodes() == 0)
      return dest;
    // Rank 0 holds every cell, in input order. The first destination is the
    // owner.
    const std::int32_t n = cells.num_nodes();
    std::vector<std::int32_t> owner(n);
    const std::vector<std::int64_t> root = joined_cells(data);
    for (std::int32_t c = 0; c < n; ++c)
      owner[c] = dest.links(std::int32_t(root[c]))[0];

    // Owners of the cells around each vertex.
    std::int64_t n_vertices = 0;
    for (std::int64_t v : cells.array())
      n_vertices = std::max(n_vertices, v + 1);
    std::vector<std::vector<std::int32_t>> vertex_ranks(n_vertices);
    for (std::int32_t c = 0; c < n; ++c)
      for (std::int64_t v : cells.links(c))
        vertex_ranks[v].push_back(owner[c]);

    std::vector<std::int32_t> list, offsets = {0};
    for (std::int32_t c = 0; c < n; ++c)
    {
      std::vector<std::int32_t> ranks = {owner[c]};
      for (std::int64_t v : cells.links(c))
        for (std::int32_t r : vertex_ranks[v])
          if (std::find(ranks.begin(), ranks.end(), r) == ranks.end())
            ranks.push_back(r);
      list.insert(list.end(), ranks.begin(), ranks.end());
      offsets.push_back(std::int32_t(list.size()));
    }
    return dolfinx::graph::AdjacencyList<std::int32_t>(std::move(list), std::move(offsets));
  };
}

/// Fills a DG0 cell field from the cell materials.
void set_by_material(Function<double>& f, const dolfinx::mesh::Mesh& mesh,
                     const std::vector<std::int32_t>& material, double steel, double concrete)
{
  const auto& original = mesh.topology().original_cell_index;
  auto dofmap = f.function_space()->dofmap();
  std::span<double> values = f.x()->mutable_array();
  for (std::size_t c = 0; c < original.size(); ++c)
  {
    const double v = material[original[c]] == mesh::steel ? steel : concrete;
    values[dofmap->cell_dofs(std::int32_t(c))[0]] = v;
  }
  f.x()->scatter_fwd();
}

/// Step 1: rank 0 supplies the whole mesh; create_mesh distributes it.
std::shared_ptr<dolfinx::mesh::Mesh> distribute_mesh(MPI_Comm comm, const mesh::MeshData& data)
{
  const dolfinx::fem::CoordinateElement cmap(dolfinx::mesh::CellType::hexahedron, 1);
  int rank;
  MPI_Comm_rank(comm, &rank);
  const std::size_t n_in = rank == 0 ? data.num_cells() : 0;
  std::vector<std::int32_t> offsets(n_in + 1);
  for (std::size_t i = 0; i < offsets.size(); ++i)
    offsets[i] = std::int32_t(8 * i);
  const dolfinx::graph::AdjacencyList<std::int64_t> cells(
      std::vector<std::int64_t>(data.cells.begin(), data.cells.begin() + 8 * n_in),
      std::move(offsets));
  const std::span<const double> x_in(data.x.data(), rank == 0 ? data.x.size() : 0);
  return std::make_shared<dolfinx::mesh::Mesh>(
      dolfinx::mesh::create_mesh(comm, cells, cmap, x_in, {x_in.size() / 3, 3},
                                 dolfinx::mesh::GhostMode::none, pair_keeping_partitioner(data)));
}

/// Step 2: the displacement space, P1 or P2 (mesh.degree), block size 3.
std::shared_ptr<dolfinx::fem::FunctionSpace>
displacement_space(std::shared_ptr<dolfinx::mesh::Mesh> mesh, int degree)
{
  namespace fem = dolfinx::fem;
  return std::make_shared<fem::FunctionSpace>(
      degree == 2 ? fem::create_functionspace(functionspace_form_elasticity_a_q2, "u2", mesh)
                  : fem::create_functionspace(functionspace_form_elasticity_a, "u", mesh));
}

/// Step 3: E, nu, alpha per cell from its material ([steel], [concrete]).
Materials assign_materials(std::shared_ptr<dolfinx::mesh::Mesh> mesh,
                           const std::vector<std::int32_t>& material, const Material& steel,
                           const Material& concrete)
{
  namespace fem = dolfinx::fem;
  auto Q = std::make_shared<fem::FunctionSpace>(
      fem::create_functionspace(functionspace_form_elasticity_a, "E", mesh));
  Materials m{std::make_shared<Function<double>>(Q), std::make_shared<Function<double>>(Q),
              std::make_shared<Function<double>>(Q), std::make_shared<fem::Constant<double>>(0.0)};
  set_by_material(*m.E, *mesh, material, steel.E, concrete.E);
  set_by_material(*m.nu, *mesh, material, steel.nu, concrete.nu);
  set_by_material(*m.alpha, *mesh, material, steel.alpha, concrete.alpha);
  return m;
}

using Coefficients = std::map<std::string, std::shared_ptr<const Function<double>>>;
Coefficients coefficients(const Materials& m)
{
  return {{"E", m.E}, {"nu", m.nu}, {"alpha", m.alpha}};
}

/// Step 4a: the bulk bilinear form a(u, v) (forms/elasticity.py).
std::shared_ptr<dolfinx::fem::Form<double>>
bulk_form(std::shared_ptr<dolfinx::fem::FunctionSpace> V, int degree, const Materials& m)
{
  namespace fem = dolfinx::fem;
  return std::make_shared<fem::Form<double>>(fem::create_form<double>(
      degree == 2 ? *form_elasticity_a_q2 : *form_elasticity_a, {V, V}, coefficients(m),
      std::map<std::string, std::shared_ptr<const fem::Constant<double>>>{}, {}));
}

/// Step 4b: the thermal load form L(v) for the temperature change m.dT.
std::shared_ptr<dolfinx::fem::Form<double>>
thermal_form(std::shared_ptr<dolfinx::fem::FunctionSpace> V, int degree, const Materials& m)
{
  namespace fem = dolfinx::fem;
  return std::make_shared<fem::Form<double>>(fem::create_form<double>(
      degree == 2 ? *form_elasticity_L_thermal_q2 : *form_elasticity_L_thermal, {V},
      coefficients(m), {{"dT", m.dT}}, {}));
}

/// Step 5: input node -> local dof block. The first dofs of a cell (P1: all;
/// P2: the vertices' before the edges', faces' and interior's) sit at the
/// cell's geometry nodes, in the same local order.
std::vector<std::int32_t> node_blocks(const dolfinx::mesh::Mesh& mesh,
                                      const dolfinx::fem::FunctionSpace& V, std::size_t n_nodes)
{
  const auto& x_dofmap = mesh.geometry().dofmap();
  const auto& input_index = mesh.geometry().input_global_indices();
  const auto dofmap = V.dofmap();
  std::vector<std::int32_t> block(n_nodes, -1);
  for (std::int32_t c = 0; c < x_dofmap.num_nodes(); ++c)
  {
    auto xd = x_dofmap.links(c);
    auto cd = dofmap->cell_dofs(c);
    for (std::size_t i = 0; i < xd.size(); ++i)
      block[input_index[xd[i]]] = cd[i];
  }
  return block;
}

/// P2: the 9 dof blocks of a pair side's facet in the order of Quadrature.h,
/// found among the cell's dofs by position (the facet is the bilinear image
/// of the reference square with the 4 `corner` coordinates [4][3]).
void append_facet_blocks_p2(std::span<const std::int32_t> cell_dofs, std::span<const double> dof_x,
                            const double* corner, std::vector<std::int32_t>& blocks)
{
  for (const auto& [xi, eta] : interface::reference_nodes(9))
  {
    const std::array<double, 4> N = {(1 - xi) * (1 - eta), xi * (1 - eta), (1 - xi) * eta,
                                     xi * eta};
    std::array<double, 3> target{0, 0, 0};
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d)
        target[d] += N[a] * corner[3 * a + d];
    std::int32_t best = -1;
    double d_best = 1e-6 * (1 + std::abs(target[0]) + std::abs(target[1]) + std::abs(target[2]));
    for (std::int32_t dof : cell_dofs)
    {
      const double* y = dof_x.data() + 3 * dof;
      const double dist = std::hypot(y[0] - target[0], y[1] - target[1], y[2] - target[2]);
      if (dist < d_best)
      {
        d_best = dist;
        best = dof;
      }
    }
    if (best < 0)
      throw std::logic_error("P2 interface: no dof of the cell at a facet node");
    blocks.push_back(best);
  }
}

/// The laws of the [[interface]] layers.
std::vector<std::unique_ptr<laws::InterfaceLaw>> make_layers(const JointLaws& laws)
{
  std::vector<std::unique_ptr<laws::InterfaceLaw>> layers;
  for (std::size_t l = 0; l < laws.interface.size(); ++l)
  {
    const LayerSpec& spec = laws.interface[l];
    layers.push_back(
        laws::find_law(spec.law)->make(spec.params, "interface." + std::to_string(l) + "."));
  }
  return layers;
}

/// The law of [[crack]] i, as its one layer.
std::vector<std::unique_ptr<laws::InterfaceLaw>> crack_layers(const JointLaws& laws, std::size_t i)
{
  const LayerSpec& spec = laws.cracks[i];
  std::vector<std::unique_ptr<laws::InterfaceLaw>> layers;
  layers.push_back(laws::find_law(spec.law)->make(spec.params, "crack." + std::to_string(i) + "."));
  return layers;
}

/// Step 6: joint elements of this process (the steel-concrete interface or
/// a crack plane): the pairs of its cells (the partitioner keeps both cells
/// of a pair together), their dof blocks and minus-side coordinates, and
/// the layers' laws.
std::unique_ptr<interface::Interface>
build_joints(MPI_Comm comm, const mesh::MeshData& data,
             const std::vector<mesh::InterfacePair>& pairs,
             std::vector<std::unique_ptr<laws::InterfaceLaw>> layers, bool nodal_quadrature,
             const dolfinx::mesh::Mesh& mesh, const dolfinx::fem::FunctionSpace& V, int degree,
             const std::vector<std::int32_t>& node_block, std::array<double, 3> mirror = {0, 0, 0})
{
  const bool q2 = degree == 2;
  const auto& original = mesh.topology().original_cell_index;
  const std::int32_t n_owned_cells = mesh.topology().index_map(3)->size_local();
  std::vector<std::int32_t> local_cell(data.num_cells(), -1); // owned cells only
  for (std::int32_t c = 0; c < n_owned_cells; ++c)
    local_cell[original[c]] = c;
  const std::vector<double> dof_x = q2 ? V.tabulate_dof_coordinates(false) : std::vector<double>{};
  // A pair split across processes is found on one process: the same error
  // on all of them (common/mpi_errors.h), not one leaving the others in the
  // next collective.
  return mpi::collectively(
      comm,
      [&]
      {
        std::vector<std::int32_t> pair_blocks;
        std::vector<double> pair_x;
        for (const mesh::InterfacePair& p : pairs)
        {
          if (local_cell[p.minus_cell] < 0)
            continue;
          if (local_cell[p.plus_cell] < 0)
            throw std::logic_error("joint element split across processes");
          const std::size_t first_x = pair_x.size();
          for (std::int64_t n : p.minus)
            pair_x.insert(pair_x.end(), data.x.begin() + 3 * n, data.x.begin() + 3 * n + 3);
          if (!q2)
          {
            for (const auto& side : {p.minus, p.plus})
              for (std::int64_t n : side)
                pair_blocks.push_back(node_block[n]);
            continue;
          }
          for (std::int64_t cell : {p.minus_cell, p.plus_cell})
            append_facet_blocks_p2(V.dofmap()->cell_dofs(local_cell[cell]), dof_x,
                                   pair_x.data() + first_x, pair_blocks);
        }
        return std::make_unique<interface::Interface>(
            std::move(pair_blocks), pair_x,
            interface::make_quadrature(nodal_quadrature ? "nodal" : "gauss", q2 ? 9 : 4),
            std::move(layers), mirror);
      });
}

/// Step 6b: the joint elements of each crack plane.
std::vector<std::unique_ptr<interface::Interface>>
build_cracks(MPI_Comm comm, const mesh::MeshData& data, const ModelInput& in,
             const dolfinx::mesh::Mesh& mesh, const dolfinx::fem::FunctionSpace& V, int degree,
             const std::vector<std::int32_t>& node_block)
{
  std::vector<std::unique_ptr<interface::Interface>> cracks;
  for (std::size_t i = 0; i < data.cracks.size(); ++i)
    cracks.push_back(build_joints(comm, data, data.cracks[i].pairs, crack_layers(in.laws, i),
                                  in.nodal_quadrature, mesh, V, degree, node_block,
                                  data.cracks[i].mirror));
  return cracks;
}

/// Step 6c: the mouth of each crack plane: its node pairs on the slice's
/// outer face, as local dof blocks (-1: not on this process).
std::vector<Model::CrackMouth> crack_mouths(const mesh::MeshData& data,
                                            const std::vector<std::int32_t>& node_block)
{
  std::vector<Model::CrackMouth> mouths;
  for (const mesh::CrackPlane& crack : data.cracks)
  {
    Model::CrackMouth m;
    m.image_of = crack.image_of;
    for (const auto& pair : crack.mouth)
      if (node_block[pair[1]] >= 0)
        m.plus_blocks.push_back(node_block[pair[1]]);
    std::sort(m.plus_blocks.begin(), m.plus_blocks.end());
    mouths.push_back(std::move(m));
  }
  return mouths;
}

/// Step 7: K with the bulk pattern plus the couplings of the joint
/// elements, the bulk assembled into it.
Mat assemble_stiffness(MPI_Comm comm, const dolfinx::fem::Form<double>& a,
                       const std::vector<interface::Interface*>& joints)
{
  dolfinx::la::SparsityPattern pattern = dolfinx::fem::create_sparsity_pattern(a);
  for (const interface::Interface* itf : joints)
  {
    const auto blocks = itf->pair_blocks();
    const int nb = 2 * itf->nodes_per_side(); // blocks per joint element
    for (std::size_t p = 0; p < itf->num_pairs(); ++p)
    {
      std::span<const std::int32_t> b = blocks.subspan(nb * p, nb);
      pattern.insert(b, b);
    }
  }
  pattern.assemble();
  Mat K = dolfinx::la::petsc::create_matrix(comm, pattern);
  check(MatSetOption(K, MAT_KEEP_NONZERO_PATTERN, PETSC_TRUE), "MatSetOption");
  check(MatZeroEntries(K), "MatZeroEntries");
  // Explicit zeros keep the joint couplings in the assembled pattern
  // (PETSc squeezes out preallocated entries that were never set).
  for (const interface::Interface* itf : joints)
  {
    const auto blocks = itf->pair_blocks();
    const int nb = 2 * itf->nodes_per_side();
    const std::vector<double> zeros(9 * nb * nb, 0.0);
    for (std::size_t p = 0; p < itf->num_pairs(); ++p)
      check(MatSetValuesBlockedLocal(K, nb, blocks.data() + nb * p, nb, blocks.data() + nb * p,
                                     zeros.data(), ADD_VALUES),
            "MatSetValuesBlockedLocal");
  }
  dolfinx::fem::assemble_matrix(dolfinx::la::petsc::Matrix::set_block_fn(K, ADD_VALUES), a, {});
  check(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  return K;
}
} // namespace

JointLaws JointLaws::of(const Scene& scene)
{
  JointLaws laws{scene.layers(), {}};
  for (const CrackSpec& crack : scene.cracks())
    laws.cracks.push_back(crack.layer);
  return laws;
}

ModelInput ModelInput::of(const Scene& scene)
{
  return {scene.mesh().degree, scene.mesh().nodal_quadrature, scene.steel(),
          scene.concrete(),    JointLaws::of(scene),          scene.cracking(),
          scene.geometry()};
}

Model::Model(MPI_Comm comm, const mesh::MeshData& data, const ModelInput& in)
    : _mesh(distribute_mesh(comm, data)), _degree(in.degree),
      _V(displacement_space(_mesh, _degree)),
      _u(std::make_shared<dolfinx::fem::Function<double>>(_V)),
      _materials(assign_materials(_mesh, data.material, in.steel, in.concrete)),
      _a(bulk_form(_V, _degree, _materials)), _L_thermal(thermal_form(_V, _degree, _materials)),
      _node_block(node_blocks(*_mesh, *_V, data.num_nodes())),
      _interface(build_joints(comm, data, data.pairs, make_layers(in.laws), in.nodal_quadrature,
                              *_mesh, *_V, _degree, _node_block)),
      _cracks(build_cracks(comm, data, in, *_mesh, *_V, _degree, _node_block)),
      _mouths(crack_mouths(data, _node_block)), _K(assemble_stiffness(comm, *_a, joints()))
{
  _u->name = "displacement"; // in fields.xdmf
  if (in.cracking.embedded)
  {
    _bulk_cracking = std::make_unique<BulkCracking>(
        _mesh, _V, _u, _materials.alpha, data.material, in.concrete, in.cracking, in.geometry,
        (data.symmetry_planes[0] ? 2 : 1) * (data.symmetry_planes[1] ? 2 : 1));
    // K over the cracking cells at the crack band's points, where the
    // cracks take C away.
    _bulk_cracking->add_elastic_rule(_K);
    check(MatAssemblyBegin(_K, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(_K, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  }
}

Model::~Model()
{
  if (_K)
    petsc::check_nothrow(MatDestroy(&_K), "MatDestroy");
}

std::vector<interface::Interface*> Model::joints()
{
  std::vector<interface::Interface*> all = {_interface.get()};
  for (const auto& c : _cracks)
    all.push_back(c.get());
  return all;
}

std::vector<const interface::Interface*> Model::joints() const
{
  std::vector<const interface::Interface*> all = {_interface.get()};
  for (const auto& c : _cracks)
    all.push_back(c.get());
  return all;
}

std::vector<double> Model::crack_mouth_openings() const
{
  // {int w_n dA, int dA} near each mouth, over this process's joints, then
  // over processes.
  std::vector<double> sums(2 * _mouths.size(), 0.0);
  const std::span<const double> u = _u->x()->array();
  for (std::size_t i = 0; i < _mouths.size(); ++i)
    if (_mouths[i].image_of < 0)
    {
      const auto s = _cracks[i]->opening_near(u, _mouths[i].plus_blocks);
      sums[2 * i] = s[0];
      sums[2 * i + 1] = s[1];
    }
  MPI_Allreduce(MPI_IN_PLACE, sums.data(), int(sums.size()), MPI_DOUBLE, MPI_SUM, comm());
  std::vector<double> width(_mouths.size(), 0.0);
  for (std::size_t i = 0; i < _mouths.size(); ++i)
    if (_mouths[i].image_of < 0 && sums[2 * i + 1] > 0)
      width[i] = std::max(sums[2 * i] / sums[2 * i + 1], 0.0); // closed: 0, not the overlap
  for (std::size_t i = 0; i < _mouths.size(); ++i)
    if (_mouths[i].image_of >= 0)
      width[i] = width[std::size_t(_mouths[i].image_of)];
  return width;
}

std::vector<std::int64_t> Model::input_numbering() const
{
  if (_degree != 1)
    return {};
  const int bs = block_size();
  std::vector<std::int64_t> position(std::size_t(index_map().size_local()) * std::size_t(bs), -1);
  for (std::size_t node = 0; node < _node_block.size(); ++node)
    if (owned(_node_block[node]))
      for (int c = 0; c < bs; ++c)
        position[std::size_t(_node_block[node]) * std::size_t(bs) + std::size_t(c)] =
            std::int64_t(node) * bs + c;
  return position;
}

std::int64_t Model::num_dofs() const
{
  return index_map().size_global() * block_size();
}

Vec Model::create_vector() const
{
  return dolfinx::la::petsc::create_vector(index_map(), block_size());
}

Vec Model::thermal_load() const
{
  Vec b = create_vector();
  check(VecSet(b, 0.0), "VecSet");
  dolfinx::fem::petsc::assemble_vector(b, *_L_thermal);
  check(VecGhostUpdateBegin(b, ADD_VALUES, SCATTER_REVERSE), "VecGhostUpdateBegin");
  check(VecGhostUpdateEnd(b, ADD_VALUES, SCATTER_REVERSE), "VecGhostUpdateEnd");
  return b;
}

void Model::set_laws(const JointLaws& laws)
{
  if (laws.cracks.size() != _cracks.size())
    throw std::logic_error("Model::set_laws: another number of crack planes");
  _interface->set_layers(make_layers(laws));
  for (std::size_t i = 0; i < _cracks.size(); ++i)
    _cracks[i]->set_layers(crack_layers(laws, i));
  if (_bulk_cracking)
    _bulk_cracking->reset();
  std::fill(_u->x()->mutable_array().begin(), _u->x()->mutable_array().end(), 0.0);
}

Vec Model::mean_jump_functional(Jump jump) const
{
  dolfinx::la::Vector<double> a(_V->dofmap()->index_map, block_size());
  std::fill(a.mutable_array().begin(), a.mutable_array().end(), 0.0);
  _interface->add_jump_functional(
      jump == Jump::axial_slip ? laws::Vec3{0, 1, 0} : laws::Vec3{1, 0, 0}, a.mutable_array());
  a.scatter_rev(std::plus<double>());
  double area = _interface->area();
  MPI_Allreduce(MPI_IN_PLACE, &area, 1, MPI_DOUBLE, MPI_SUM, comm());
  if (!(area > 0))
    throw std::runtime_error("path following needs an interface (its area is 0)");
  Vec v = create_vector();
  double* va;
  check(VecGetArray(v, &va), "VecGetArray");
  const std::size_t n_owned = std::size_t(index_map().size_local() * block_size());
  for (std::size_t i = 0; i < n_owned; ++i)
    va[i] = a.array()[i] / area;
  check(VecRestoreArray(v, &va), "VecRestoreArray");
  return v;
}
} // namespace pushout::model

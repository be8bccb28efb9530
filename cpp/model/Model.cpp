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

/// The default graph partitioner decides the owners; then each pair's
/// concrete cell follows its steel cell, so that one process owns both sides
/// of every joint element (each interface cell has one interface facet: the
/// pairs are a matching). Every cell is also ghosted on the processes that
/// own a cell sharing a vertex with it (GhostMode::shared_vertex): DOLFINx
/// 0.5 finds shared vertices only through ghosts or shared facets, and the
/// partition may touch along edges only.
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
    for (std::int32_t c = 0; c < n; ++c)
      owner[c] = dest.links(c)[0];
    for (const mesh::InterfacePair& p : data.pairs)
      owner[p.concrete_cell] = owner[p.steel_cell];

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
} // namespace

Model::Model(MPI_Comm comm, const mesh::MeshData& data, const Scene& scene)
{
  namespace fem = dolfinx::fem;
  const fem::CoordinateElement cmap(dolfinx::mesh::CellType::hexahedron, 1);
  int rank;
  MPI_Comm_rank(comm, &rank);
  // Rank 0 supplies the whole mesh; create_mesh distributes it.
  const std::size_t n_in = rank == 0 ? data.num_cells() : 0;
  std::vector<std::int32_t> offsets(n_in + 1);
  for (std::size_t i = 0; i < offsets.size(); ++i)
    offsets[i] = std::int32_t(8 * i);
  const dolfinx::graph::AdjacencyList<std::int64_t> cells(
      std::vector<std::int64_t>(data.cells.begin(), data.cells.begin() + 8 * n_in),
      std::move(offsets));
  const std::span<const double> x_in(data.x.data(), rank == 0 ? data.x.size() : 0);
  mesh = std::make_shared<dolfinx::mesh::Mesh>(
      dolfinx::mesh::create_mesh(comm, cells, cmap, x_in, {x_in.size() / 3, 3},
                                 dolfinx::mesh::GhostMode::none, pair_keeping_partitioner(data)));

  degree = int(scene.integer("mesh.degree"));
  const bool q2 = degree == 2;
  V = std::make_shared<fem::FunctionSpace>(
      q2 ? fem::create_functionspace(functionspace_form_elasticity_a_q2, "u2", mesh)
         : fem::create_functionspace(functionspace_form_elasticity_a, "u", mesh));
  u = std::make_shared<Function<double>>(V);
  auto Q = std::make_shared<fem::FunctionSpace>(
      fem::create_functionspace(functionspace_form_elasticity_a, "E", mesh));
  E = std::make_shared<Function<double>>(Q);
  nu = std::make_shared<Function<double>>(Q);
  alpha = std::make_shared<Function<double>>(Q);
  set_by_material(*E, *mesh, data.material, scene.number("steel.E"), scene.number("concrete.E"));
  set_by_material(*nu, *mesh, data.material, scene.number("steel.nu"), scene.number("concrete.nu"));
  set_by_material(*alpha, *mesh, data.material, scene.number("steel.alpha"),
                  scene.number("concrete.alpha"));
  dT = std::make_shared<fem::Constant<double>>(0.0);

  const std::map<std::string, std::shared_ptr<const Function<double>>> coeffs = {
      {"E", E}, {"nu", nu}, {"alpha", alpha}};
  _a = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      q2 ? *form_elasticity_a_q2 : *form_elasticity_a, {V, V}, coeffs,
      std::map<std::string, std::shared_ptr<const fem::Constant<double>>>{}, {}));
  _L_thermal = std::make_shared<fem::Form<double>>(
      fem::create_form<double>(q2 ? *form_elasticity_L_thermal_q2 : *form_elasticity_L_thermal, {V},
                               coeffs, {{"dT", dT}}, {}));

  // Input node -> local dof block: the first dofs of a cell (P1: all; P2:
  // the vertices' before the edges', faces' and interior's) sit at the
  // cell's geometry nodes, in the same local order.
  const auto& x_dofmap = mesh->geometry().dofmap();
  const auto& input_index = mesh->geometry().input_global_indices();
  const auto dofmap = V->dofmap();
  node_block.assign(data.num_nodes(), -1);
  for (std::int32_t c = 0; c < x_dofmap.num_nodes(); ++c)
  {
    auto xd = x_dofmap.links(c);
    auto cd = dofmap->cell_dofs(c);
    for (std::size_t i = 0; i < xd.size(); ++i)
      node_block[input_index[xd[i]]] = cd[i];
  }

  // Interface: the pairs of this process's cells (the partitioner keeps
  // both cells of a pair together), their dof blocks and steel-side
  // coordinates.
  const auto& original = mesh->topology().original_cell_index;
  const std::int32_t n_owned_cells = mesh->topology().index_map(3)->size_local();
  std::vector<std::int32_t> local_cell(data.num_cells(), -1); // owned cells only
  for (std::int32_t c = 0; c < n_owned_cells; ++c)
    local_cell[original[c]] = c;
  std::vector<std::int32_t> pair_blocks;
  std::vector<double> pair_x;
  const std::vector<double> dof_x = q2 ? V->tabulate_dof_coordinates(false) : std::vector<double>{};
  // A pair split across processes is found on one process: the same error
  // on all of them (common/mpi_errors.h), not one leaving the others in the
  // next collective.
  mpi::collectively(
      comm,
      [&]
      {
        for (const mesh::InterfacePair& p : data.pairs)
        {
          if (local_cell[p.steel_cell] < 0)
            continue;
          if (local_cell[p.concrete_cell] < 0)
            throw std::logic_error("interface pair split across processes");
          const std::size_t first_x = pair_x.size();
          for (std::int64_t n : p.steel)
            pair_x.insert(pair_x.end(), data.x.begin() + 3 * n, data.x.begin() + 3 * n + 3);
          if (!q2)
          {
            for (std::int64_t n : p.steel)
              pair_blocks.push_back(node_block[n]);
            for (std::int64_t n : p.concrete)
              pair_blocks.push_back(node_block[n]);
            continue;
          }
          // P2: the 9 dofs of each side's facet, found by position (the facet is
          // the bilinear image of the reference square; Quadrature.h's order).
          const double* corner = pair_x.data() + first_x;
          for (std::int64_t cell : {p.steel_cell, p.concrete_cell})
          {
            const auto cd = dofmap->cell_dofs(local_cell[cell]);
            for (const auto& [xi, eta] : interface::reference_nodes(9))
            {
              const std::array<double, 4> N = {(1 - xi) * (1 - eta), xi * (1 - eta), (1 - xi) * eta,
                                               xi * eta};
              std::array<double, 3> target{0, 0, 0};
              for (int a = 0; a < 4; ++a)
                for (int d = 0; d < 3; ++d)
                  target[d] += N[a] * corner[3 * a + d];
              std::int32_t best = -1;
              double d_best =
                  1e-6 * (1 + std::abs(target[0]) + std::abs(target[1]) + std::abs(target[2]));
              for (std::int32_t dof : cd)
              {
                const double* y = dof_x.data() + 3 * dof;
                const double dist =
                    std::hypot(y[0] - target[0], y[1] - target[1], y[2] - target[2]);
                if (dist < d_best)
                {
                  d_best = dist;
                  best = dof;
                }
              }
              if (best < 0)
                throw std::logic_error("P2 interface: no dof of the cell at a facet node");
              pair_blocks.push_back(best);
            }
          }
        }
      });
  std::vector<std::unique_ptr<laws::InterfaceLaw>> layers;
  for (std::size_t l = 0; l < scene.layers().size(); ++l)
  {
    const LayerSpec& spec = scene.layers()[l];
    layers.push_back(
        laws::find_law(spec.law)->make(spec.params, "interface." + std::to_string(l) + "."));
  }
  interface = mpi::collectively(
      comm,
      [&]
      {
        return std::make_unique<interface::Interface>(
            std::move(pair_blocks), pair_x,
            interface::make_quadrature(scene.string("mesh.interface_quadrature"), q2 ? 9 : 4),
            std::move(layers));
      });

  // K with the bulk pattern plus the interface couplings.
  dolfinx::la::SparsityPattern pattern = fem::create_sparsity_pattern(*_a);
  const auto blocks = interface->pair_blocks();
  const int nb = 2 * interface->nodes_per_side(); // blocks per joint element
  for (std::size_t p = 0; p < interface->num_pairs(); ++p)
  {
    std::span<const std::int32_t> b = blocks.subspan(nb * p, nb);
    pattern.insert(b, b);
  }
  pattern.assemble();
  K = dolfinx::la::petsc::create_matrix(comm, pattern);
  check(MatSetOption(K, MAT_KEEP_NONZERO_PATTERN, PETSC_TRUE), "MatSetOption");
  check(MatZeroEntries(K), "MatZeroEntries");
  // Explicit zeros keep the interface couplings in the assembled pattern
  // (PETSc squeezes out preallocated entries that were never set).
  const std::vector<double> zeros(9 * nb * nb, 0.0);
  for (std::size_t p = 0; p < interface->num_pairs(); ++p)
    check(MatSetValuesBlockedLocal(K, nb, blocks.data() + nb * p, nb, blocks.data() + nb * p,
                                   zeros.data(), ADD_VALUES),
          "MatSetValuesBlockedLocal");
  fem::assemble_matrix(dolfinx::la::petsc::Matrix::set_block_fn(K, ADD_VALUES), *_a, {});
  check(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
}

Model::~Model()
{
  if (K)
    petsc::check_nothrow(MatDestroy(&K), "MatDestroy");
}

std::int64_t Model::num_dofs() const
{
  return V->dofmap()->index_map->size_global() * V->dofmap()->index_map_bs();
}

Vec Model::thermal_load(double dT_value) const
{
  dT->value = {dT_value};
  Vec b = dolfinx::la::petsc::create_vector(*V->dofmap()->index_map, V->dofmap()->index_map_bs());
  check(VecSet(b, 0.0), "VecSet");
  dolfinx::fem::petsc::assemble_vector(b, *_L_thermal);
  check(VecGhostUpdateBegin(b, ADD_VALUES, SCATTER_REVERSE), "VecGhostUpdateBegin");
  check(VecGhostUpdateEnd(b, ADD_VALUES, SCATTER_REVERSE), "VecGhostUpdateEnd");
  return b;
}

Vec Model::mean_axial_slip_functional() const
{
  const auto& map = V->dofmap()->index_map;
  const int bs = V->dofmap()->index_map_bs();
  dolfinx::la::Vector<double> a(map, bs);
  std::fill(a.mutable_array().begin(), a.mutable_array().end(), 0.0);
  interface->add_axial_jump_functional(a.mutable_array());
  a.scatter_rev(std::plus<double>());
  double area = interface->area();
  MPI_Allreduce(MPI_IN_PLACE, &area, 1, MPI_DOUBLE, MPI_SUM, mesh->comm());
  if (!(area > 0))
    throw std::runtime_error("path following needs an interface (its area is 0)");
  Vec v = dolfinx::la::petsc::create_vector(*map, bs);
  double* va;
  check(VecGetArray(v, &va), "VecGetArray");
  const std::size_t n_owned = std::size_t(map->size_local() * bs);
  for (std::size_t i = 0; i < n_owned; ++i)
    va[i] = a.array()[i] / area;
  check(VecRestoreArray(v, &va), "VecRestoreArray");
  return v;
}

StressProjection::StressProjection(const Model& model)
{
  namespace fem = dolfinx::fem;
  auto S = std::make_shared<fem::FunctionSpace>(
      fem::create_functionspace(functionspace_form_elasticity_L_stress, "tau", model.mesh));
  auto Q = model.E->function_space();
  const std::map<std::string, std::shared_ptr<const Function<double>>> coeffs = {
      {"E", model.E},
      {"nu", model.nu},
      {"alpha", model.alpha},
      {model.degree == 2 ? "u_h2" : "u_h", model.u}};
  _L_stress = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      model.degree == 2 ? *form_elasticity_L_stress_q2 : *form_elasticity_L_stress, {S}, coeffs,
      {{"dT", model.dT}}, {}));
  _sigma = std::make_shared<Function<double>>(S);
  _sigma->name = "stress";

  // Cell volumes, once: DG0 on both spaces, one dof (block) per cell.
  const auto L_volume = fem::create_form<double>(
      *form_elasticity_L_volume, {Q},
      std::map<std::string, std::shared_ptr<const Function<double>>>{},
      std::map<std::string, std::shared_ptr<const fem::Constant<double>>>{}, {});
  std::vector<double> volume(
      Q->dofmap()->index_map->size_local() + Q->dofmap()->index_map->num_ghosts(), 0.0);
  fem::assemble_vector(std::span<double>(volume), L_volume);
  const std::int32_t n_cells = model.mesh->topology().index_map(3)->size_local();
  for (std::int32_t c = 0; c < n_cells; ++c)
    _inverse_volume.emplace_back(S->dofmap()->cell_dofs(c)[0],
                                 1.0 / volume[Q->dofmap()->cell_dofs(c)[0]]);
}

const Function<double>& StressProjection::update()
{
  std::span<double> s = _sigma->x()->mutable_array();
  std::fill(s.begin(), s.end(), 0.0);
  dolfinx::fem::assemble_vector(s, *_L_stress);
  for (const auto& [block, inv] : _inverse_volume)
    for (int i = 0; i < 9; ++i)
      s[9 * block + i] *= inv;
  _sigma->x()->scatter_fwd();
  return *_sigma;
}
} // namespace pushout::model

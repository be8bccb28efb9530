#include "FieldWriter.h"
#include "elasticity.h"
#include <basix/finite-element.h>
#include <dolfinx/fem/utils.h>
#include <dolfinx/graph/AdjacencyList.h>
#include <dolfinx/mesh/cell_types.h>
#include <dolfinx/mesh/utils.h>

namespace pushout::output
{
FieldWriter::FieldWriter(const model::Model& model, const std::filesystem::path& dir)
    : _model(model), _stress(model)
{
  namespace fem = dolfinx::fem;
  MPI_Comm comm = model.comm();
  _fields = std::make_unique<dolfinx::io::XDMFFile>(comm, (dir / "fields.xdmf").string(), "w");
  _fields->write_mesh(*model.mesh());
  if (model.degree() == 2)
  {
    _u1 = std::make_shared<fem::Function<double>>(std::make_shared<fem::FunctionSpace>(
        fem::create_functionspace(functionspace_form_elasticity_a, "u", model.mesh())));
    _u1->name = "displacement";
  }

  // Interface surface mesh: one quadrilateral per pair of this process, on
  // the steel side, numbered globally after the lower processes' ones and
  // kept on this process.
  const auto& itf = model.interface();
  const std::vector<double> dof_x = model.space()->tabulate_dof_coordinates(false);
  const std::int64_t n_local = std::int64_t(itf.num_pairs());
  std::int64_t first = 0;
  MPI_Exscan(&n_local, &first, 1, MPI_INT64_T, MPI_SUM, comm);
  int rank;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0)
    first = 0;
  std::vector<double> coords;
  std::vector<std::int64_t> cells;
  const auto blocks = itf.pair_blocks();
  for (std::size_t p = 0; p < itf.num_pairs(); ++p)
    for (int a = 0; a < 4; ++a)
    {
      cells.push_back(4 * first + std::int64_t(coords.size() / 3));
      const std::int32_t b = blocks[2 * itf.nodes_per_side() * p + a]; // the corners
      coords.insert(coords.end(), dof_x.begin() + 3 * b, dof_x.begin() + 3 * b + 3);
    }
  std::vector<std::int32_t> offsets(itf.num_pairs() + 1);
  for (std::size_t i = 0; i < offsets.size(); ++i)
    offsets[i] = std::int32_t(4 * i);
  const fem::CoordinateElement cmap(dolfinx::mesh::CellType::quadrilateral, 1);
  const auto stay_here = [rank](MPI_Comm, int, int,
                                const dolfinx::graph::AdjacencyList<std::int64_t>& c,
                                dolfinx::mesh::GhostMode)
  {
    return dolfinx::graph::regular_adjacency_list(std::vector<std::int32_t>(c.num_nodes(), rank),
                                                  1);
  };
  _imesh = std::make_shared<dolfinx::mesh::Mesh>(dolfinx::mesh::create_mesh(
      comm, dolfinx::graph::AdjacencyList<std::int64_t>(cells, offsets), cmap, coords,
      {coords.size() / 3, 3}, dolfinx::mesh::GhostMode::none, stay_here));
  _imesh->name = "interface";
  const basix::FiniteElement e =
      basix::create_element(basix::element::family::P, basix::cell::type::quadrilateral, 0,
                            basix::element::lagrange_variant::gll_warped, true);
  auto Q = std::make_shared<fem::FunctionSpace>(fem::create_functionspace(_imesh, e, 1));
  std::vector<std::string> names = {"t_n", "t_s1", "t_s2", "w_n", "w_s1"};
  for (std::size_t l = 0; l < itf.num_layers(); ++l)
    for (const char* n : {"slip_s1_", "slip_s2_", "damage_"})
      names.push_back(n + std::to_string(l));
  for (const std::string& n : names)
  {
    auto f = std::make_shared<fem::Function<double>>(Q);
    f->name = n;
    _ifields.push_back(f);
  }
  const auto& original = _imesh->topology().original_cell_index;
  _pair_of_dof.assign(original.size(), 0);
  for (std::size_t c = 0; c < original.size(); ++c)
    _pair_of_dof[Q->dofmap()->cell_dofs(std::int32_t(c))[0]] = std::int32_t(original[c] - first);

  _interface =
      std::make_unique<dolfinx::io::XDMFFile>(comm, (dir / "interface.xdmf").string(), "w");
  _interface->write_mesh(*_imesh);
}

FieldWriter::~FieldWriter()
{
  _fields->close();
  _interface->close();
}

void FieldWriter::write(double t)
{
  if (_u1)
    _u1->interpolate(_model.displacement());
  _fields->write_function(_u1 ? *_u1 : _model.displacement(), t);
  _fields->write_function(_stress.update(), t);

  const auto& itf = _model.interface();
  const std::size_t nq = itf.points_per_pair();
  const std::size_t nf = _ifields.size();
  std::vector<double> sum(nf);
  for (std::size_t dof = 0; dof < _pair_of_dof.size(); ++dof)
  {
    const std::size_t p = _pair_of_dof[dof];
    std::fill(sum.begin(), sum.end(), 0.0);
    for (std::size_t q = 0; q < nq; ++q)
    {
      const interface::PointOutput o = itf.point_output(_model.displacement().x()->array(), p, q);
      std::vector<double> v = {o.t[0], o.t[1], o.t[2], o.w[0], o.w[1]};
      for (std::size_t l = 0; l < o.slip.size(); ++l)
        v.insert(v.end(), {o.slip[l][0], o.slip[l][1], o.damage[l]});
      for (std::size_t i = 0; i < nf; ++i)
        sum[i] += v[i] / double(nq);
    }
    for (std::size_t i = 0; i < nf; ++i)
      _ifields[i]->x()->mutable_array()[dof] = sum[i];
  }
  for (const auto& f : _ifields)
    _interface->write_function(*f, t);
}
} // namespace pushout::output

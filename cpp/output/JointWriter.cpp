#include "JointWriter.h"
#include "xdmf_checked.h"
#include <basix/finite-element.h>
#include <dolfinx/fem/utils.h>
#include <dolfinx/graph/AdjacencyList.h>
#include <dolfinx/mesh/cell_types.h>
#include <dolfinx/mesh/utils.h>

namespace pushout::output
{
JointWriter::JointWriter(MPI_Comm comm, std::vector<const interface::Interface*> sets,
                         const std::vector<double>& dof_x, std::vector<std::string> names,
                         Values values, const std::filesystem::path& file)
    : _sets(std::move(sets)), _values(std::move(values))
{
  namespace fem = dolfinx::fem;
  // One quadrilateral per pair of this process, numbered globally after the
  // lower processes' ones and kept on this process.
  std::int64_t n_local = 0;
  for (const interface::Interface* set : _sets)
    n_local += std::int64_t(set->num_pairs());
  std::int64_t first = 0;
  MPI_Exscan(&n_local, &first, 1, MPI_INT64_T, MPI_SUM, comm);
  int rank;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0)
    first = 0;
  std::vector<double> coords;
  std::vector<std::int64_t> cells;
  std::vector<std::pair<std::size_t, std::size_t>> pair_of_cell;
  for (std::size_t s = 0; s < _sets.size(); ++s)
  {
    const auto blocks = _sets[s]->pair_blocks();
    for (std::size_t p = 0; p < _sets[s]->num_pairs(); ++p)
    {
      pair_of_cell.push_back({s, p});
      for (int a = 0; a < 4; ++a)
      {
        cells.push_back(4 * first + std::int64_t(coords.size() / 3));
        const std::int32_t b = blocks[2 * _sets[s]->nodes_per_side() * p + a]; // the corners
        coords.insert(coords.end(), dof_x.begin() + 3 * b, dof_x.begin() + 3 * b + 3);
      }
    }
  }
  std::vector<std::int32_t> offsets(pair_of_cell.size() + 1);
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
  _mesh = std::make_shared<dolfinx::mesh::Mesh>(dolfinx::mesh::create_mesh(
      comm, dolfinx::graph::AdjacencyList<std::int64_t>(cells, offsets), cmap, coords,
      {coords.size() / 3, 3}, dolfinx::mesh::GhostMode::none, stay_here));
  _mesh->name = file.stem().string();
  const basix::FiniteElement e =
      basix::create_element(basix::element::family::P, basix::cell::type::quadrilateral, 0,
                            basix::element::lagrange_variant::gll_warped, true);
  auto Q = std::make_shared<fem::FunctionSpace>(fem::create_functionspace(_mesh, e, 1));
  for (const std::string& n : names)
  {
    auto f = std::make_shared<fem::Function<double>>(Q);
    f->name = n;
    _fields.push_back(f);
  }
  const auto& original = _mesh->topology().original_cell_index;
  _pair_of_dof.assign(original.size(), {0, 0});
  for (std::size_t c = 0; c < original.size(); ++c)
    _pair_of_dof[Q->dofmap()->cell_dofs(std::int32_t(c))[0]] =
        pair_of_cell[std::size_t(original[c] - first)];
  _path = file;
  try
  {
    _file = std::make_unique<XdmfSeries>(comm, file);
  }
  catch (...)
  {
    throw std::runtime_error(cannot_write_xdmf(file));
  }
  xdmf_checked(_file, _path, [&](XdmfSeries& f) { f.write_mesh(*_mesh); });
}

JointWriter::~JointWriter()
{
  if (_open)
    try
    {
      close();
    }
    catch (const std::exception&) // an error on the way out, reported before
    {
    }
}

void JointWriter::close()
{
  _open = false;
  xdmf_close(_file, _path);
}

void JointWriter::write(std::span<const double> u, double t)
{
  const std::size_t nf = _fields.size();
  std::vector<double> sum(nf);
  for (std::size_t dof = 0; dof < _pair_of_dof.size(); ++dof)
  {
    const auto [s, p] = _pair_of_dof[dof];
    const std::size_t nq = _sets[s]->points_per_pair();
    std::fill(sum.begin(), sum.end(), 0.0);
    for (std::size_t q = 0; q < nq; ++q)
    {
      const std::vector<double> v = _values(_sets[s]->point_output(u, p, q), s);
      for (std::size_t i = 0; i < nf; ++i)
        sum[i] += v[i] / double(nq);
    }
    for (std::size_t i = 0; i < nf; ++i)
      _fields[i]->x()->mutable_array()[dof] = sum[i];
  }
  xdmf_checked(_file, _path,
               [&](XdmfSeries& file)
               {
                 for (const auto& f : _fields)
                   file.write(*f, t);
                 file.save();
               });
}
} // namespace pushout::output

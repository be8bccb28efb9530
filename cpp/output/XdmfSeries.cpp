#include "XdmfSeries.h"
#include <algorithm>
#include <boost/lexical_cast.hpp>
#include <cmath>
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/io/HDF5Interface.h>
#include <dolfinx/io/xdmf_mesh.h>
#include <dolfinx/io/xdmf_utils.h>
#include <stdexcept>

namespace pushout::output
{
namespace
{
/// Holds the file's metadata in HDF5's cache until it is flushed (no
/// evictions, so no cache resizing either): between two flushes
/// (flush_hdf5_files, after each step) nothing but new raw data reaches the
/// disk, so a run killed while it writes a step leaves the file as the last
/// flush left it. With evictions on, the cache may write a group's object
/// header that points beyond the end of the file that the last flush
/// recorded, and the whole file then cannot be read ("addr overflow"). On
/// one process only: parallel HDF5 coordinates the processes' metadata
/// writes itself. False if HDF5 refused.
bool keep_metadata_until_flushed(hid_t h5)
{
  H5AC_cache_config_t config;
  config.version = H5AC__CURR_CACHE_CONFIG_VERSION;
  if (H5Fget_mdc_config(h5, &config) < 0)
    return false;
  config.evictions_enabled = false;
  config.incr_mode = H5C_incr__off;
  config.flash_incr_mode = H5C_flash_incr__off;
  config.decr_mode = H5C_decr__off;
  return H5Fset_mdc_config(h5, &config) >= 0;
}

/// The grid of the mesh, as XDMFFile::write_function finds it.
constexpr const char* mesh_xpath = "/Xdmf/Domain/Grid[@GridType='Uniform'][1]";

/// XDMF's components of a value: 2D vectors and tensors padded to 3D, as
/// XDMFFile pads them.
int padded_width(const dolfinx::fem::FiniteElement& e)
{
  const int width = e.value_size();
  const std::size_t rank = e.value_shape().size();
  if (rank == 1 && width == 2)
    return 3;
  if (rank == 2 && width == 4)
    return 9;
  return width;
}

/// Whether `V` is a space of cell functions (DG0), by XDMFFile's test.
bool cell_centred(const dolfinx::fem::FunctionSpace& V)
{
  int cell_based_dim = 1;
  for (std::size_t i = 0; i < V.element()->value_shape().size(); ++i)
    cell_based_dim *= V.mesh()->topology().dim();
  return V.dofmap()->element_dof_layout().num_dofs() * V.dofmap()->bs() == cell_based_dim;
}
} // namespace

XdmfSeries::XdmfSeries(MPI_Comm comm, const std::filesystem::path& file)
    : _comm(comm), _file(file), _doc(std::make_unique<pugi::xml_document>())
{
  MPI_Comm_rank(comm, &_rank);
  int size = 1;
  MPI_Comm_size(comm, &size);
  _mpi_io = size > 1;
  _h5 = dolfinx::io::HDF5Interface::open_file(
      comm, dolfinx::io::xdmf_utils::get_hdf5_filename(file), "w", _mpi_io);
  if (!_mpi_io && !keep_metadata_until_flushed(_h5))
  {
    close();
    throw std::runtime_error("cannot set HDF5's metadata cache for " + file.string());
  }
  _doc->append_child(pugi::node_doctype).set_value("Xdmf SYSTEM \"Xdmf.dtd\" []");
  pugi::xml_node xdmf = _doc->append_child("Xdmf");
  xdmf.append_attribute("Version") = "3.0";
  xdmf.append_attribute("xmlns:xi") = "http://www.w3.org/2001/XInclude";
  xdmf.append_child("Domain");
}

XdmfSeries::~XdmfSeries()
{
  try
  {
    close();
  }
  catch (const std::exception&) // an error on the way out, reported before
  {
  }
}

void XdmfSeries::write_mesh(const dolfinx::mesh::Mesh& mesh)
{
  pugi::xml_node domain = _doc->child("Xdmf").child("Domain");
  dolfinx::io::xdmf_mesh::add_mesh(_comm, domain, _h5, mesh, mesh.name);
  _mesh_reference = std::string("xpointer(") + mesh_xpath + "/*[self::Topology or self::Geometry])";
  save();
}

void XdmfSeries::write(const dolfinx::fem::Function<double>& u, double t)
{
  // The function's temporal collection, and in it the step's grid: the
  // mesh's topology and geometry by reference, the time, the values.
  pugi::xml_node& series = _series[u.name];
  if (!series)
  {
    series = _doc->child("Xdmf").child("Domain").append_child("Grid");
    series.append_attribute("Name") = u.name.c_str();
    series.append_attribute("GridType") = "Collection";
    series.append_attribute("CollectionType") = "Temporal";
  }
  pugi::xml_node grid = series.append_child("Grid");
  grid.append_attribute("Name") = u.name.c_str();
  grid.append_attribute("GridType") = "Uniform";
  grid.append_child("xi:include").append_attribute("xpointer") = _mesh_reference.c_str();
  const std::string time = boost::lexical_cast<std::string>(t);
  grid.append_child("Time").append_attribute("Value") = time.c_str();

  const dolfinx::fem::FunctionSpace& V = *u.function_space();
  const dolfinx::mesh::Mesh& mesh = *V.mesh();
  const bool cells = cell_centred(V);
  const std::vector<double> values =
      cells ? dolfinx::io::xdmf_utils::get_cell_data_values(u) : node_values(u);
  const int width = padded_width(*V.element());
  const std::int64_t global = cells
                                  ? mesh.topology().index_map(mesh.topology().dim())->size_global()
                                  : mesh.geometry().index_map()->size_global();
  static const char* const kinds[] = {"Scalar", "Vector", "Tensor"};
  const std::size_t rank = V.element()->value_shape().size();
  if (rank > 2)
    throw std::logic_error("XdmfSeries: a value of rank above 2");

  pugi::xml_node attribute = grid.append_child("Attribute");
  attribute.append_attribute("Name") = u.name.c_str();
  attribute.append_attribute("AttributeType") = kinds[rank];
  attribute.append_attribute("Center") = cells ? "Cell" : "Node";
  std::string dataset_time = time;
  std::replace(dataset_time.begin(), dataset_time.end(), '.', '_');
  const std::int64_t local = std::int64_t(values.size()) / width;
  std::int64_t offset = 0;
  MPI_Exscan(&local, &offset, 1, MPI_INT64_T, MPI_SUM, _comm);
  if (_rank == 0) // MPI_Exscan leaves the first process's undefined
    offset = 0;
  dolfinx::io::xdmf_utils::add_data_item(attribute, _h5, "/Function/" + u.name + "/" + dataset_time,
                                         values, offset, {global, width}, "", _mpi_io);
}

void XdmfSeries::save()
{
  // The first process writes the file; every process learns whether it
  // could (a failure is then given up on all: xdmf_checked.h).
  int saved = _rank == 0 ? int(_doc->save_file(_file.c_str(), "  ")) : 1;
  MPI_Bcast(&saved, 1, MPI_INT, 0, _comm);
  if (!saved)
    throw std::runtime_error("cannot save " + _file.string());
}

void XdmfSeries::close()
{
  if (_h5 > 0)
  {
    const hid_t h5 = _h5;
    _h5 = -1;
    dolfinx::io::HDF5Interface::close_file(h5);
  }
}

std::vector<double> XdmfSeries::node_values(const dolfinx::fem::Function<double>& u)
{
  const std::vector<std::int32_t>& dofs = node_dofs(*u.function_space());
  if (dofs.empty())
    return dolfinx::io::xdmf_utils::get_point_data_values(u);
  const dolfinx::fem::FunctionSpace& V = *u.function_space();
  const int bs = V.dofmap()->bs();
  const int width = padded_width(*V.element());
  const std::span<const double> x = u.x()->array();
  std::vector<double> values(dofs.size() * std::size_t(width), 0.0);
  for (std::size_t node = 0; node < dofs.size(); ++node)
    for (int k = 0; k < bs; ++k)
      values[node * std::size_t(width) + std::size_t(k)] = x[std::size_t(dofs[node]) * bs + k];
  return values;
}

const std::vector<std::int32_t>& XdmfSeries::node_dofs(const dolfinx::fem::FunctionSpace& V)
{
  auto [it, added] = _node_dofs.try_emplace(&V);
  std::vector<std::int32_t>& dofs = it->second;
  if (!added)
    return dofs;
  // A dof at every node of each cell, in the geometry's order of the cell's
  // nodes (a continuous degree-1 space on a degree-1 mesh), checked by the
  // coordinates of the dofs against the nodes'.
  const dolfinx::mesh::Mesh& mesh = *V.mesh();
  const dolfinx::mesh::Geometry& geometry = mesh.geometry();
  const auto& nodes_of = geometry.dofmap();
  const int tdim = mesh.topology().dim();
  const auto cell_map = mesh.topology().index_map(tdim);
  const std::int32_t n_cells = cell_map->size_local() + cell_map->num_ghosts();
  const std::size_t n_nodes = std::size_t(geometry.index_map()->size_local());
  const int bs = V.dofmap()->bs();
  // (A 2D tensor would need XDMFFile's padding of its components.)
  if (cell_centred(V) || V.dofmap()->element_dof_layout().num_dofs() != geometry.cmap().dim() ||
      bs != V.element()->value_size() || V.element()->value_shape().size() > 1)
    return dofs;
  std::vector<std::int32_t> found(n_nodes, -1);
  for (std::int32_t c = 0; c < n_cells; ++c)
  {
    const auto cell_nodes = nodes_of.links(c);
    const auto cell_dofs = V.dofmap()->cell_dofs(c);
    for (std::size_t j = 0; j < cell_nodes.size(); ++j)
      if (std::size_t(cell_nodes[j]) < n_nodes)
        found[std::size_t(cell_nodes[j])] = cell_dofs[j];
  }
  const std::vector<double> dof_x = V.tabulate_dof_coordinates(false);
  const std::span<const double> node_x = geometry.x();
  for (std::size_t node = 0; node < n_nodes; ++node)
  {
    if (found[node] < 0)
      return dofs;
    for (int k = 0; k < 3; ++k) // 1e-9 mm: the same point (coordinates in mm, up to 1e3)
      if (std::abs(dof_x[3 * std::size_t(found[node]) + k] - node_x[3 * node + k]) > 1e-9)
        return dofs;
  }
  dofs = std::move(found);
  return dofs;
}
} // namespace pushout::output

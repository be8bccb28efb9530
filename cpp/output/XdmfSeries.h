// An XDMF file of one mesh with time series of functions on it: the XML and
// HDF5 layout of dolfinx::io::XDMFFile (ParaView reads both alike: the mesh
// under /Mesh, each function's steps under /Function/NAME/T, a temporal
// collection of grids per function), written for a run of many steps:
// - the XML is saved once per step (save()), where XDMFFile saves the whole,
//   growing document after each function (5 to 11 a step here): the cost
//   of its saves still grows with the square of the steps (some 5 kB of XML
//   a step), at a fifth to a tenth of XDMFFile's;
// - a P1 function on the mesh's own nodes is written from its dofs, where
//   XDMFFile evaluates it at every node (a pull-back into a cell each: most
//   of the fields' output time on the paper's mesh).
// Cell functions (DG0) are written as XDMFFile writes them.
#pragma once

#include <dolfinx/fem/Function.h>
#include <dolfinx/mesh/Mesh.h>
#include <filesystem>
#include <hdf5.h>
#include <map>
#include <memory>
#include <mpi.h>
#include <pugixml.hpp>
#include <string>
#include <vector>

namespace pushout::output
{
class XdmfSeries
{
public:
  /// Creates the HDF5 file beside `file` (FILE.h5); throws if it cannot be
  /// made. Collective.
  XdmfSeries(MPI_Comm comm, const std::filesystem::path& file);
  /// Closes the HDF5 file if close() was not called (an error is not
  /// reported).
  ~XdmfSeries();
  XdmfSeries(const XdmfSeries&) = delete;
  XdmfSeries& operator=(const XdmfSeries&) = delete;

  MPI_Comm comm() const { return _comm; }
  /// Writes the mesh the functions live on and saves the XML. Collective.
  void write_mesh(const dolfinx::mesh::Mesh& mesh);
  /// Adds the step at time `t` of `u` (a function on the mesh, named by
  /// u.name): point data for a continuous function of degree 1 with a dof at
  /// each node of the mesh, cell data for a DG0 one. The XML is not saved
  /// (save()). Collective.
  void write(const dolfinx::fem::Function<double>& u, double t);
  /// Saves the XML (the first process writes it) with every step written
  /// so far; throws on every process if it could not. Collective.
  void save();
  /// Closes the HDF5 file. Collective.
  void close();

private:
  /// The value of each of this process's owned nodes (the geometry's local
  /// range, as the mesh's node data), padded to XDMF's 3 or 9 components.
  std::vector<double> node_values(const dolfinx::fem::Function<double>& u);
  /// The dof of each local node for the space of `u`, made once per space;
  /// empty if the space's dofs are not at the nodes (XDMFFile's evaluation
  /// then).
  const std::vector<std::int32_t>& node_dofs(const dolfinx::fem::FunctionSpace& V);

  MPI_Comm _comm;
  int _rank = 0;
  bool _mpi_io = false; ///< HDF5 through MPI-IO (several processes)
  std::filesystem::path _file;
  hid_t _h5 = -1;
  std::unique_ptr<pugi::xml_document> _doc;
  std::string _mesh_reference;                   ///< the xi:include xpointer of the mesh's grid
  std::map<std::string, pugi::xml_node> _series; ///< a function's temporal collection
  /// node_dofs() per space (the writer's callers keep their spaces alive)
  std::map<const dolfinx::fem::FunctionSpace*, std::vector<std::int32_t>> _node_dofs;
};
} // namespace pushout::output

// Joint elements as a surface in XDMF: one quadrilateral per joint element
// (its minus-side corners), with cell fields averaged over its quadrature
// points. FieldWriter writes the steel-concrete interface (interface.xdmf)
// and the crack planes (cracks.xdmf) with it.
#pragma once

#include "../interface/Interface.h"
#include "XdmfSeries.h"
#include <dolfinx/fem/Function.h>
#include <dolfinx/mesh/Mesh.h>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace pushout::output
{
class JointWriter
{
public:
  /// The values of the fields at one quadrature point, in the order of the
  /// names given to the constructor.
  using Values = std::function<std::vector<double>(const interface::PointOutput&, std::size_t set)>;

  /// A surface of the joint elements of `sets` (on this process; each
  /// process writes its own), with the cell fields `names`. `dof_x` are the
  /// coordinates of the displacement dofs (blocks), `file` the XDMF file.
  JointWriter(MPI_Comm comm, std::vector<const interface::Interface*> sets,
              const std::vector<double>& dof_x, std::vector<std::string> names, Values values,
              const std::filesystem::path& file);
  /// Closes the file if close() was not called (an error there is not
  /// reported).
  ~JointWriter();

  /// Writes the fields at displacement `u` (local, with ghosts) at time t;
  /// throws (output::cannot_write) if the file cannot be written.
  /// Collective.
  void write(std::span<const double> u, double t);
  /// Closes the file; throws as write(). Collective.
  void close();

private:
  std::vector<const interface::Interface*> _sets;
  Values _values;
  std::shared_ptr<dolfinx::mesh::Mesh> _mesh;
  std::vector<std::shared_ptr<dolfinx::fem::Function<double>>> _fields;
  /// DG0 dof -> (set, pair)
  std::vector<std::pair<std::size_t, std::size_t>> _pair_of_dof;
  std::filesystem::path _path;
  std::unique_ptr<XdmfSeries> _file;
  bool _open = true;
};
} // namespace pushout::output

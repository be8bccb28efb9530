// ParaView output (output.xdmf = true): fields.xdmf (displacement [mm], at
// the mesh nodes also for mesh.degree = 2; cell-averaged stress [MPa]) and interface.xdmf (per
// joint element, the average over its quadrature points: normal traction t_n, axial and
// circumferential shear tractions t_s1, t_s2 [MPa], jump w_n, w_s1 [mm],
// and per layer L the inelastic slip slip_L_s1, slip_L_s2 [mm] and damage_L),
// and with crack planes cracks.xdmf (per joint element of the cracks: t_n
// (opening traction), t_s1 (axial), t_s2 (radial) [MPa], w_n (opening),
// w_s1, w_s2 [mm], damage, and the crack's index), one time step per
// converged load step. With [cracking], fields.xdmf also has per cell the
// widest crack of its points: crack_opening (normal opening [mm]),
// crack_normal (unit) and crack_damage.
#pragma once

#include "../model/Model.h"
#include "JointWriter.h"
#include "StressProjection.h"
#include "XdmfSeries.h"
#include <filesystem>
#include <memory>
#include <vector>

namespace pushout::output
{
class FieldWriter
{
public:
  /// The files dir/PREFIXfields.xdmf, PREFIXinterface.xdmf (and
  /// PREFIXcracks.xdmf with crack planes), with their .h5 (`prefix`:
  /// "corrosion_" for the corrosion stage's). If they cannot be opened
  /// with the mesh in them (a full disk), none is left behind: they would
  /// hold no step.
  FieldWriter(const model::Model& model, const std::filesystem::path& dir,
              const std::string& prefix = "");
  /// Closes the files if close() was not called (an error there is not
  /// reported).
  ~FieldWriter();
  /// Writes the fields of time `t`; throws (cannot_write of fields.xdmf) on
  /// every process if the disk has no room for them, or if a file cannot be
  /// written. Collective.
  void write(double t);
  /// Closes the files; throws (cannot_write) if one cannot be written whole.
  /// Collective.
  void close();

private:
  /// The constructor's work: the files opened, the mesh written.
  void open(const std::string& prefix);
  /// Removes the files open() may have made (rank 0; those that are files).
  void remove_files(const std::string& prefix) const noexcept;
  /// The bytes of the HDF5 files so far (rank 0).
  std::uintmax_t data_bytes() const;
  /// Throws cannot_write(fields.xdmf) on every process if the next step may
  /// not fit on the disk (collective).
  void check_room();

  const model::Model& _model;
  std::filesystem::path _dir;
  std::filesystem::path _fields_file;
  std::vector<std::filesystem::path> _h5; ///< the HDF5 files of the XDMF files
  std::uintmax_t _bytes_before = 0;       ///< data_bytes() before the last step [B]
  std::unique_ptr<XdmfSeries> _fields;
  bool _open = true;
  std::unique_ptr<JointWriter> _interface, _cracks;
  StressProjection _stress;
  /// [cracking]: per cell, its widest crack's normal opening [mm], unit
  /// normal and damage (model/BulkCracking.h); null without.
  std::shared_ptr<dolfinx::fem::Function<double>> _crack_opening, _crack_normal, _crack_damage;
  /// mesh.degree = 2: the displacement interpolated to the trilinear space
  /// of the mesh for XDMF (which stores fields at the mesh's nodes).
  std::shared_ptr<dolfinx::fem::Function<double>> _u1;
};
} // namespace pushout::output

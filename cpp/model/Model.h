// The discrete model: DOLFINx mesh and spaces, the bulk forms (forms/
// elasticity.py), the bulk stiffness K (assembled once: the bulk is linear)
// and the interface (joint elements) with its laws and state.
#pragma once

#include "../interface/Interface.h"
#include "../mesh/MeshData.h"
#include "../scene/Scene.h"
#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/mesh/Mesh.h>
#include <memory>
#include <petscmat.h>
#include <petscvec.h>

namespace pushout::model
{
class Model
{
public:
  Model(MPI_Comm comm, const mesh::MeshData& data, const Scene& scene);
  ~Model();
  Model(const Model&) = delete;
  Model& operator=(const Model&) = delete;

  std::shared_ptr<dolfinx::mesh::Mesh> mesh;
  int degree = 1;                                    ///< of the displacement (mesh.degree)
  std::shared_ptr<dolfinx::fem::FunctionSpace> V;    ///< P1 or P2 displacement, bs 3
  std::shared_ptr<dolfinx::fem::Function<double>> u; ///< displacement [mm]
  std::shared_ptr<dolfinx::fem::Function<double>> E, nu, alpha; ///< per cell
  std::shared_ptr<dolfinx::fem::Constant<double>> dT;           ///< [degC]

  /// Local dof block of each input node (MeshData numbering); -1 if the
  /// node is not on this process.
  std::vector<std::int32_t> node_block;

  std::unique_ptr<interface::Interface> interface;

  /// Bulk stiffness K [N/mm], with room for the interface couplings.
  Mat K = nullptr;

  /// Number of global displacement dofs.
  std::int64_t num_dofs() const;

  /// Whether a local dof block is owned by this process (not a ghost).
  bool owned(std::int32_t block) const
  {
    return block >= 0 && block < V->dofmap()->index_map->size_local();
  }

  /// Coefficients a of the mean axial slip s = a . u [mm] (the axial jump
  /// averaged over the whole interface), owned part: the control variable
  /// of path following.
  Vec mean_axial_slip_functional() const;

  /// Equivalent nodal forces of the thermal strain for `dT` [N], owned part.
  Vec thermal_load(double dT_value) const;

private:
  std::shared_ptr<dolfinx::fem::Form<double>> _a, _L_thermal;
};
/// Cell-averaged stress [MPa] for output: the DG0 projection of the stress
/// of forms/elasticity.py (L_stress divided by the cell volumes). Built once;
/// update() reassembles it from the model's current displacement.
class StressProjection
{
public:
  explicit StressProjection(const Model& model);
  const dolfinx::fem::Function<double>& update();

private:
  std::shared_ptr<dolfinx::fem::Form<double>> _L_stress;
  std::shared_ptr<dolfinx::fem::Function<double>> _sigma;
  std::vector<std::pair<std::int32_t, double>> _inverse_volume; ///< (DG0 block, 1/volume)
};
} // namespace pushout::model

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
  std::shared_ptr<dolfinx::fem::FunctionSpace> V;               ///< P1 displacement, bs 3
  std::shared_ptr<dolfinx::fem::Function<double>> u;            ///< displacement [mm]
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

  /// Equivalent nodal forces of the thermal strain for `dT` [N], owned part.
  Vec thermal_load(double dT_value) const;

  /// Cell-averaged stress [MPa] for output (DG0 tensor).
  std::shared_ptr<dolfinx::fem::Function<double>> stress() const;

private:
  std::shared_ptr<dolfinx::fem::Form<double>> _a, _L_thermal;
};
} // namespace pushout::model

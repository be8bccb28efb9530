// The discrete model: DOLFINx mesh and spaces, the bulk forms (forms/
// elasticity.py), the bulk stiffness K (assembled once: the bulk is linear)
// and the interface (joint elements) with its laws and state.
//
// Built in named steps (Model.cpp): distribute the mesh, the displacement
// space, the materials, the bulk forms, the node -> dof map, the interface,
// the stiffness. The rest of the code reads it through the accessors.
#pragma once

#include "../interface/Interface.h"
#include "../mesh/MeshData.h"
#include "../scene/Scene.h"
#include "BulkCracking.h"
#include <dolfinx/common/IndexMap.h>
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
/// Cell-wise material fields (DG0) and the temperature change of the
/// thermal load, the coefficients of forms/elasticity.py.
struct Materials
{
  std::shared_ptr<dolfinx::fem::Function<double>> E;     ///< Young's modulus [MPa]
  std::shared_ptr<dolfinx::fem::Function<double>> nu;    ///< Poisson's ratio [-]
  std::shared_ptr<dolfinx::fem::Function<double>> alpha; ///< thermal expansion [1/degC]
  std::shared_ptr<dolfinx::fem::Constant<double>> dT;    ///< temperature change [degC]
};

/// The laws of the joints: each [[interface]] layer, each [[crack]] plane's.
struct JointLaws
{
  std::vector<LayerSpec> interface;
  std::vector<LayerSpec> cracks;
  static JointLaws of(const Scene& scene);
};

/// What the model is built from besides its mesh: the bulk's degree and
/// materials, the joints' quadrature and laws.
struct ModelInput
{
  int degree = 1;                ///< mesh.degree
  bool nodal_quadrature = false; ///< mesh.interface_quadrature
  Material steel, concrete;
  JointLaws laws;
  CrackingPart cracking; ///< [cracking]
  Geometry geometry;     ///< [geometry]: where the concrete's cracks are read
  static ModelInput of(const Scene& scene);
};

class Model
{
public:
  Model(MPI_Comm comm, const mesh::MeshData& data, const ModelInput& input);
  ~Model();
  Model(const Model&) = delete;
  Model& operator=(const Model&) = delete;

  std::shared_ptr<dolfinx::mesh::Mesh> mesh() const { return _mesh; }
  MPI_Comm comm() const { return _mesh->comm(); }
  /// Polynomial degree of the displacement (mesh.degree: 1 or 2).
  int degree() const { return _degree; }
  /// The displacement space (P1 or P2, block size 3).
  std::shared_ptr<const dolfinx::fem::FunctionSpace> space() const { return _V; }
  const dolfinx::common::IndexMap& index_map() const { return *_V->dofmap()->index_map; }
  int block_size() const { return _V->dofmap()->index_map_bs(); }
  /// A new vector of the displacement space (with ghosts); the caller
  /// destroys it.
  Vec create_vector() const;
  /// Number of global displacement dofs.
  std::int64_t num_dofs() const;

  /// The displacement [mm] the interface and the outputs read.
  dolfinx::fem::Function<double>& displacement() { return *_u; }
  const dolfinx::fem::Function<double>& displacement() const { return *_u; }
  std::shared_ptr<dolfinx::fem::Function<double>> displacement_ptr() const { return _u; }
  const Materials& materials() const { return _materials; }

  /// The concrete's own cracks ([cracking]); nullptr if it stays linear.
  BulkCracking* bulk_cracking() { return _bulk_cracking.get(); }
  const BulkCracking* bulk_cracking() const { return _bulk_cracking.get(); }

  /// The steel-concrete interface.
  interface::Interface& interface() { return *_interface; }
  const interface::Interface& interface() const { return *_interface; }
  /// The joint elements of crack plane i ([[crack]] i).
  const interface::Interface& crack(std::size_t i) const { return *_cracks[i]; }
  std::size_t num_cracks() const { return _cracks.size(); }
  /// The crack plane that crack plane i is the mirror image of, if a
  /// symmetric model cut it away (it has no joint elements; its openings
  /// are that plane's); else -1.
  int crack_image(std::size_t i) const { return _mouths[i].image_of; }
  /// Every set of joint elements: the interface, then the crack planes. What
  /// assembles, commits or reverts joints does it for all of these.
  std::vector<interface::Interface*> joints();
  std::vector<const interface::Interface*> joints() const;
  /// `laws` in place of the present ones, every joint's state and the
  /// displacement back to zero: the model as built for a scene with these
  /// laws, if it has the mesh, materials and crack planes this one was built
  /// for (driver/Run.h: Simulation).
  void set_laws(const JointLaws& laws);

  /// The mouth of a crack plane: its nodes on the slice's outer face.
  struct CrackMouth
  {
    std::vector<std::int32_t> plus_blocks; ///< local dof blocks of the plus side, sorted
    int image_of = -1;                     ///< cut away by symmetry: the opening is that plane's
  };
  /// Crack-mouth opening of each crack plane [mm], where experiments measure
  /// the crack width: the opening w . n averaged over the plane's quadrature
  /// points next to the slice's outer face (Interface::opening_near: the
  /// outer row of Gauss points, a fraction 0.21 of the element's radial size
  /// inside the face for 2-point Gauss), where the laws evaluate it. A nodal
  /// value at the face would extrapolate a linear jump over a coarse element
  /// and can read negative while every point of the plane opens. A closed
  /// mouth reads 0, as a gauge would (not the penalty's overlap in
  /// compression, w . n < 0). A plane cut away by symmetry has its image's.
  /// Collective.
  std::vector<double> crack_mouth_openings() const;

  /// Bulk stiffness K [N/mm], with room for the interface couplings.
  Mat stiffness() const { return _K; }

  /// Local dof block of input node `node` (MeshData numbering); -1 if the
  /// node is not on this process.
  std::int32_t node_block(std::int64_t node) const { return _node_block[node]; }
  /// Whether a local dof block is owned by this process (not a ghost).
  bool owned(std::int32_t block) const { return block >= 0 && block < index_map().size_local(); }
  /// Each owned dof's position in the input numbering of the dofs, in the
  /// order of this process's rows: block_size() times its node's input
  /// index (MeshData), plus its component. No partition changes it, so the
  /// LU on several processes can be ordered as on one
  /// (solver::use_single_precision_sparse_lu). Empty for P2, whose edge
  /// dofs are no input nodes.
  std::vector<std::int64_t> input_numbering() const;

  /// A jump of the steel-concrete interface averaged over it, as a linear
  /// functional s = a . u [mm].
  enum class Jump
  {
    axial_slip,    ///< w . s1: the control variable of path following
    normal_opening ///< w . n: that of the corrosion stage
  };
  /// Coefficients a of the mean jump (owned part; the caller destroys it).
  Vec mean_jump_functional(Jump jump) const;
  Vec mean_axial_slip_functional() const { return mean_jump_functional(Jump::axial_slip); }

  /// The temperature change of the thermal strain [degC], which the thermal
  /// load and the stress output read (a model reused for another run keeps
  /// the last one set: each run sets its own).
  void set_temperature_change(double dT_value) { _materials.dT->value = {dT_value}; }
  /// Equivalent nodal forces of the thermal strain for the temperature
  /// change set [N], owned part.
  Vec thermal_load() const;

private:
  std::shared_ptr<dolfinx::mesh::Mesh> _mesh;
  int _degree;
  std::shared_ptr<dolfinx::fem::FunctionSpace> _V;
  std::shared_ptr<dolfinx::fem::Function<double>> _u;
  Materials _materials;
  std::shared_ptr<dolfinx::fem::Form<double>> _a, _L_thermal;
  std::vector<std::int32_t> _node_block;
  std::unique_ptr<interface::Interface> _interface;
  std::vector<std::unique_ptr<interface::Interface>> _cracks;
  std::vector<CrackMouth> _mouths;
  Mat _K = nullptr;
  std::unique_ptr<BulkCracking> _bulk_cracking;
};
} // namespace pushout::model

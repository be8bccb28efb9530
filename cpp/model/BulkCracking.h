// Concrete that cracks, in the model (docs/cracking.md): the crack band of
// bulk/CrackBand.h at every quadrature point of the concrete that may crack
// (the cells within cracking.radius of the tube axis), each point with its
// own tensile strength from the random field of bulk/StrengthField.h.
//
// The linear stiffness K (forms/elasticity.py) stays as assembled; what
// cracking changes enters through forms/cracking.py on the cracking cells
// only: the forces of sigma - C : eps_e and the tangent C_t - C, both zero
// at a point that has not cracked. Per evaluation: the strain at the points
// (an FFCx expression of the displacement), the crack band's update from
// the committed state (one 3 x 3 equilibrium per cracked point), then the
// two differences into the forms' Quadrature coefficients.
//
// State: a committed and a trial copy at every point, as the joints'
// (interface/InterfaceState.h); evaluate() writes the trial one, commit()
// after a converged step, revert() before a retry.
#pragma once

#include "../bulk/CrackBand.h"
#include "../scene/SceneParts.h"
#include <array>
#include <cstdint>
#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/Expression.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/mesh/Mesh.h>
#include <dolfinx/mesh/MeshTags.h>
#include <memory>
#include <petscmat.h>
#include <span>
#include <vector>

namespace pushout::model
{
/// What the concrete's cracks add up to over all processes (collective).
struct CrackingTotals
{
  std::int64_t points = 0;         ///< quadrature points that may crack
  std::int64_t cracked_points = 0; ///< of those, cracked
  double max_opening = 0;          ///< the widest normal opening w . n at a point [mm]
  double dissipated = 0;           ///< energy the cracks dissipated [N mm]
};

class BulkCracking
{
public:
  /// `material` the input cells' materials (MeshData); `axis` the tube
  /// axis (x, y) [mm]. Throws SceneError, on every process, if a cracking
  /// cell is too large for its crack band to soften without snapping back.
  BulkCracking(std::shared_ptr<dolfinx::mesh::Mesh> mesh,
               std::shared_ptr<const dolfinx::fem::FunctionSpace> V,
               std::shared_ptr<const dolfinx::fem::Function<double>> u,
               std::shared_ptr<const dolfinx::fem::Function<double>> alpha,
               const std::vector<std::int32_t>& material, const Material& concrete,
               const CrackingPart& part, std::array<double, 2> axis);

  /// The temperature change whose free strain the stress does not see [degC].
  void set_temperature_change(double dT);

  /// The crack band at every point, from the committed state to the strain
  /// of the model's displacement (ghosts up to date): the trial state, and
  /// the forms' coefficients. False if a point failed (its equilibrium did
  /// not converge): the step is to be cut.
  bool evaluate();
  /// Adds the forces of the last evaluate() to f (local with ghosts; the
  /// caller sums the ghosts into their owners) [N].
  void add_forces(std::span<double> f) const;
  /// Adds the tangent of the last evaluate() to A (before its final
  /// assembly) [N/mm].
  void add_tangent(Mat A) const;

  /// The trial state becomes the committed one (a converged step).
  void commit();
  /// The trial state back to the committed one (a step to retry).
  void revert();
  /// Every point back to uncracked (a model reused for another scene).
  void reset();

  /// Totals of the state at the model's displacement, evaluated from the
  /// committed one: a converged step's, recorded before its commit
  /// (stepping/StepRecorder.h). Collective.
  CrackingTotals totals();

private:
  /// Band width of a cracking cell along a unit normal n: the extent of its
  /// vertices along n [mm] (bulk/CrackBand.h).
  double band_width(std::size_t cell, const bulk::Vec3& n) const;

  std::shared_ptr<dolfinx::mesh::Mesh> _mesh;
  bulk::CrackBand _band;
  std::vector<std::int32_t> _cells;       ///< cracking cells (local, owned), sorted
  std::vector<double> _strength;          ///< [cell][point] f_t factor of the field
  std::vector<double> _committed, _trial; ///< [cell][point][CrackBand::state_size]
  std::vector<double> _dissipated;        ///< [cell][point] committed energy density [N mm/mm^3]
  std::vector<double> _dissipated_trial;
  std::vector<double> _opening, _opening_trial; ///< [cell][point] normal opening w . n [mm]
  std::shared_ptr<dolfinx::fem::Constant<double>> _dT;
  std::shared_ptr<dolfinx::fem::Function<double>> _d_sigma, _d_C, _d_dissipated;
  std::unique_ptr<dolfinx::fem::Expression<double>> _strain;
  std::shared_ptr<dolfinx::mesh::MeshTags<std::int32_t>> _region;
  std::shared_ptr<dolfinx::fem::Form<double>> _L, _a, _M;
  std::vector<double> _strain_values; ///< [cell][point][6], of the last evaluate()
};
} // namespace pushout::model

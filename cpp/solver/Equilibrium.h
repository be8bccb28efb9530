// The nonlinear system of one load step:
//   F(u) = K u + f_interface(u) - f_thermal - f_external = 0
// on the free dofs, and u = g on the constrained dofs (F = u - g there).
// Internal forces at the constrained dofs are the reactions.
#pragma once

#include "../model/Model.h"
#include "NonlinearProblem.h"
#include <dolfinx/la/Vector.h>
#include <petscmat.h>
#include <petscvec.h>
#include <vector>

namespace pushout::solver
{
/// Prescribed values of some dofs. Dofs are local unblocked indices
/// (3 * block + component), owned by this process.
struct Constraints
{
  std::vector<std::int32_t> dofs;
  std::vector<double> values;
};

class Equilibrium : public NonlinearProblem
{
public:
  explicit Equilibrium(model::Model& model);
  ~Equilibrium();
  Equilibrium(const Equilibrium&) = delete;
  Equilibrium& operator=(const Equilibrium&) = delete;

  model::Model& model() { return _model; }
  const model::Model& model() const { return _model; }

  /// Thermal load of temperature change dT [degC] (0: none); assembled only
  /// when dT changes.
  void set_temperature_change(double dT);
  /// External nodal forces [N]: local unblocked dof -> value.
  void set_external_forces(const std::vector<std::pair<std::int32_t, double>>& forces);
  /// The prescribed dofs and values (collective: constraint_version() moves
  /// on every process when the dofs change on any, so that all of them
  /// refresh their factorisations together).
  void set_constraints(Constraints c);
  /// A number that changes whenever the loads or prescribed values may have
  /// changed (linear_rhs() is the same while it is).
  int load_version() const { return _load_version; }
  const Constraints& constraints() const { return _bc; }

  /// Puts the prescribed values into x (start of a step).
  void apply_constraints(Vec x) const;

  /// K x + f_int - loads at every dof: the reactions at the constrained
  /// ones. Returns false if an interface law failed.
  bool internal_forces(Vec x, Vec F);
  /// The right-hand side of the linear part: the loads at the free dofs and
  /// the prescribed values at the constrained ones, so that F(x) = J0 x +
  /// f_int(x) - b with J0 = K with unit constrained rows (owned part).
  void linear_rhs(Vec b) const;

  // NonlinearProblem; J has the pattern of the model's stiffness.
  Mat create_matrix() const override;
  Vec create_vector() const override;
  bool residual(Vec x, Vec F) override;
  bool residual(Vec x, Vec F, double& reaction_norm) override;
  bool jacobian(Vec x, Mat J) override;
  double residual_floor(Vec x) override;
  bool energy_release(Vec x, double& G, Vec gradient) override;
  void forget_trial_state() override
  {
    for (interface::Interface* joints : _model.joints())
      joints->state().revert();
    if (model::BulkCracking* cracking = _model.bulk_cracking())
      cracking->revert();
  }
  int constraint_version() const override { return _constraint_version; }
  /// GMRES on a lagged MUMPS LU, with solver.precision = "mixed": that LU
  /// in single precision (on any number of processes), and flexible GMRES
  /// (SinglePrecisionSparse.h). Any other solver as the options say.
  void configure(KSP ksp) const override;

  /// Whether configure() may take the lagged LU in single precision
  /// (solver.precision = "mixed"). Set before a solver is made.
  void set_single_precision(bool single) { _single_precision = single; }

  /// Before another run on this model (a sweep's or a fit's case that
  /// reuses the set-up, after Model::set_laws): the kept K plus cracks'
  /// tangent is built afresh, so that the run is the one a fresh set-up
  /// makes bit for bit (the kept one carries the round-off of the changes
  /// the last run added to it).
  void restart();

  /// Copies x into the model's displacement (ghosts updated).
  void update_displacement(Vec x);

private:
  /// Adds the forces of every set of joint elements (interface, crack
  /// planes) at the model's displacement to f, and their tangents to A if
  /// given. False if a law failed.
  bool assemble_interfaces(std::span<double> f, Mat A);
  /// The same, and the concrete's cracks' forces and tangent too.
  bool assemble_joints(std::span<double> f, Mat A);
  /// IMPL-EX cracks: K plus the cracks' tangent of the last evaluation,
  /// assembled again only when that tangent changed
  /// (BulkCracking::tangent_version). Collective.
  Mat bulk_tangent();
  /// IMPL-EX cracks, after BulkCracking::evaluate_tangent(): K x plus the
  /// cracks' forces less the thermal load, into F, by the kept K plus
  /// cracks' tangent M. At fixed sides of closure the cracks' forces are
  /// A (x - u_T), A their tangent and u_T the displacement whose strain is
  /// the concrete's free strain (alpha dT I on the cracking cells, exact on
  /// the trilinear cells), so that K x + f_crack - f_thermal = M (x - u_T)
  /// + (K u_T - f_thermal): one product, as K x is, where assembling
  /// f_crack took its own pass over every cracking point. Collective.
  void kept_tangent_forces(Vec x, Vec F);
  /// Whether the residual and Jacobian take the IMPL-EX cracks' kept
  /// tangent (not with the test hook PUSHOUT_TEST_NO_TANGENT_CACHE).
  bool kept_tangent() const;
  /// kept_tangent_forces()' u_T and K u_T - f_thermal for _dT (none at
  /// 0, or without the kept tangent); with the thermal load, once per
  /// temperature change.
  void make_free_expansion();

  model::Model& _model;
  Vec _f_thermal = nullptr, _f_external = nullptr;
  double _dT = 0; ///< temperature change of _f_thermal [degC]
  Constraints _bc;
  int _constraint_version = 0;
  int _load_version = 0;
  dolfinx::la::Vector<double> _f_interface;
  dolfinx::la::Vector<double> _g_energy; ///< dG/du of energy_release(), local with ghosts
  double _K_norm = -1;                   ///< ||K||_inf, once needed [N/mm]
  bool _single_precision = false;
  Vec _free_expansion = nullptr;           ///< u_T of kept_tangent_forces() [mm]
  Vec _expansion_load = nullptr;           ///< K u_T - f_thermal there [N]
  Vec _shifted = nullptr;                  ///< x - u_T there [mm]
  Mat _bulk_tangent = nullptr;             ///< bulk_tangent()
  std::uint64_t _bulk_tangent_version = 0; ///< of the cracks' tangent in it
  /// The cracks' tangent in _bulk_tangent (BulkCracking::add_tangent_change)
  std::vector<double> _bulk_assembled;
};
} // namespace pushout::solver

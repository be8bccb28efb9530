// Path following (ArcLengthSolver.h) on the whole model's displacement x,
// in whichever space the load step solver runs Newton (the whole model, or
// the interface jumps with the bulk condensed): the conversions between the
// two stay here, so the step loop only sees whole-model vectors.
//
// The condensed problem is built for the constraints of the moment
// (LoadStepSolver::problem); a PathFollower is made after the push's
// constraints are set, and lives while they keep their dofs.
#pragma once

#include "ArcLengthSolver.h"
#include "LoadStepSolver.h"
#include <functional>
#include <memory>

namespace pushout::solver
{
class PathFollower
{
public:
  /// Control by a linear functional of the whole model, a . x (owned
  /// entries; e.g. Model::mean_axial_slip_functional, [mm]). The solver's
  /// constraints must be those of the path (their values move with the load
  /// factor).
  PathFollower(LoadStepSolver& solver, Vec control);
  /// Control by the energy the joints release in the step [N mm]
  /// (NonlinearProblem::energy_release: dissipation control) plus beta
  /// times the whole model's functional `slip` (EnergyReleaseConstraint).
  static PathFollower by_energy(LoadStepSolver& solver, Vec slip);
  /// beta [N] of by_energy().
  void set_slip_weight(double beta);
  /// The load factor enters the laws (ArcLengthSolver::set_load_difference).
  void set_load_difference(double h) { _arc->set_load_difference(h); }

  /// One step of control increment `d_control` from the equilibrium
  /// (x, lambda); on success x (whole model) and lambda hold the next
  /// equilibrium; on failure x is left at an iterate (the caller restores
  /// it). `set_load(lambda)` puts the constraints of load factor lambda;
  /// `max_dlambda` and `loose`: ArcLengthSolver::step. `control_from`:
  /// where (x, lambda) is a prediction of the step's end, the control value
  /// of the equilibrium the step starts from (ArcLengthSolver::step's
  /// eta_from).
  SolveReport step(Vec x, double& lambda, double d_control,
                   const std::function<void(double)>& set_load, double max_dlambda = 0,
                   bool loose = false, std::optional<double> control_from = std::nullopt);

  /// The control value at the whole model's x (a . x; the energy released
  /// since the last commit).
  double control(Vec x);

  /// Numeric factorisations so far.
  int factorizations() const { return _arc->factorizations(); }
  /// Krylov iterations of its linear solves so far.
  std::int64_t linear_iterations() const { return _arc->linear_iterations(); }

private:
  PathFollower(LoadStepSolver& solver, std::unique_ptr<PathConstraint> control);

  LoadStepSolver& _solver;
  std::unique_ptr<PathConstraint> _control;
  EnergyReleaseConstraint* _energy = nullptr; ///< _control, if by_energy()
  std::unique_ptr<ArcLengthSolver> _arc;
};
} // namespace pushout::solver

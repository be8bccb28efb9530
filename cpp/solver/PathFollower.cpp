#include "PathFollower.h"
#include "../common/mpi_errors.h"
#include "../scene/SceneError.h"
#include "Vector.h"
#include <cmath>
#include <stdexcept>

namespace pushout::solver
{
PathFollower::PathFollower(LoadStepSolver& solver, std::unique_ptr<PathConstraint> control)
    : _solver(solver), _control(std::move(control))
{
  _arc = std::make_unique<ArcLengthSolver>(solver.problem(), *_control, solver.preconditioner(),
                                           solver.refactor_iterations());
}

PathFollower::PathFollower(LoadStepSolver& solver, Vec control)
    : PathFollower(solver, std::make_unique<LinearConstraint>(Vector(solver.functional(control))))
{
}

PathFollower PathFollower::by_energy(LoadStepSolver& solver, Vec slip)
{
  auto control =
      std::make_unique<EnergyReleaseConstraint>(solver.problem(), Vector(solver.functional(slip)));
  EnergyReleaseConstraint* energy = control.get();
  PathFollower path(solver, std::move(control));
  path._energy = energy;
  return path;
}

void PathFollower::set_slip_weight(double beta)
{
  if (!_energy)
    throw std::logic_error("PathFollower::set_slip_weight: not a by_energy() follower");
  _energy->set_slip_weight(beta);
}

SolveReport PathFollower::step(Vec x, double& lambda, double d_control,
                               const std::function<void(double)>& set_load, double max_dlambda,
                               bool loose, std::optional<double> control_from)
{
  // Agreed here: the follower (its factors) lives in the step loop, and a
  // process that failed must not destroy them on its way out while the
  // others go on (common/mpi_errors.h).
  SolveReport report = mpi::collectively<OptionError, SceneError>(
      PetscObjectComm(reinterpret_cast<PetscObject>(x)),
      [&]
      {
        return _arc->step(_solver.to_problem(x), lambda, d_control, set_load, max_dlambda, loose,
                          control_from);
      });
  if (report.converged)
  {
    _solver.from_problem(x);
    // A failed step (cut back) where the solution or the load factor is not
    // a number, whatever the residual's norm said.
    if (!finite(x) || !std::isfinite(lambda))
    {
      report.converged = false;
      report.reason = "DIVERGED_NONFINITE_SOLUTION (the displacement or the load factor is not a "
                      "number)";
    }
  }
  return report;
}

double PathFollower::control(Vec x)
{
  return _arc->control(_solver.to_problem(x));
}
} // namespace pushout::solver

#include "PathFollower.h"
#include "Vector.h"

namespace pushout::solver
{
PathFollower::PathFollower(LoadStepSolver& solver, Vec control) : _solver(solver)
{
  const Vector a(solver.functional(control)); // in the problem's space
  _arc = std::make_unique<ArcLengthSolver>(solver.problem(), a, solver.preconditioner(),
                                           solver.refactor_iterations());
}

SolveReport PathFollower::step(Vec x, double& lambda, double d_control,
                               const std::function<void(double)>& set_load)
{
  const SolveReport report = _arc->step(_solver.to_problem(x), lambda, d_control, set_load);
  if (report.converged)
    _solver.from_problem(x);
  return report;
}

double PathFollower::control(Vec x) const
{
  return _arc->control(_solver.to_problem(x));
}
} // namespace pushout::solver

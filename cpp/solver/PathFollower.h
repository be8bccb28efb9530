// Path following (ArcLengthSolver.h) on the whole model's displacement x,
// in whichever space the load step solver runs Newton (the whole model, or
// the interface jumps with the bulk condensed): the conversions between the
// two stay here, so the step loop only sees whole-model vectors.
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
  /// `control`: the whole model's control functional a (owned entries;
  /// e.g. Model::mean_axial_slip_functional). The solver's constraints must
  /// be those of the path (their values move with the load factor).
  PathFollower(LoadStepSolver& solver, Vec control);

  /// One step of control increment `d_control` [mm] from the equilibrium
  /// (x, lambda); on success x (whole model) and lambda hold the next
  /// equilibrium; on failure x is left at an iterate (the caller restores
  /// it). `set_load(lambda)` puts the constraints of load factor lambda.
  SolveReport step(Vec x, double& lambda, double d_control,
                   const std::function<void(double)>& set_load);

  /// The control value a . x of the whole model's x [mm].
  double control(Vec x) const;

  /// Numeric factorisations so far.
  int factorizations() const { return _arc->factorizations(); }

private:
  LoadStepSolver& _solver;
  std::unique_ptr<ArcLengthSolver> _arc;
};
} // namespace pushout::solver

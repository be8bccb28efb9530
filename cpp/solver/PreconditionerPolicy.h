// When to rebuild the preconditioner of the Newton systems J du = -F, shared
// by NewtonSolver and ArcLengthSolver:
//  - jacobian: J is its own preconditioner, rebuilt (factored) every time;
//  - lagged: P is a copy of an earlier J, refreshed from the current J only
//    when the last linear solve needed more than `refactor_iterations`
//    Krylov iterations, or when a caller asks (after a failure).
#pragma once

#include "NonlinearProblem.h"

namespace pushout::solver
{
class PreconditionerPolicy
{
public:
  PreconditionerPolicy(bool lagged, int refactor_iterations)
      : _lagged(lagged), _refactor_iterations(refactor_iterations)
  {
  }

  bool lagged() const { return _lagged; }
  /// Lagged: whether P holds a matrix yet.
  bool has_P() const { return _has_P; }

  /// P was filled by the caller (e.g. with the elastic tangent).
  void P_filled()
  {
    _has_P = true;
    _refresh = false;
    ++_factorizations;
  }

  /// After the problem's Jacobian is in J: copies it into P when due
  /// (lagged). Returns whether the preconditioner must be rebuilt (false:
  /// reuse it).
  bool update(const NonlinearProblem& problem, Mat J, Mat P)
  {
    if (!_lagged)
    {
      ++_factorizations;
      return true;
    }
    if (_has_P && !_refresh)
      return false;
    problem.copy_jacobian(J, P);
    P_filled();
    return true;
  }

  /// After a linear solve that took `its` Krylov iterations.
  void solved(PetscInt its)
  {
    if (_lagged && _has_P && its > _refactor_iterations)
      _refresh = true;
  }

  /// Whether P will be refreshed at the next update.
  bool refresh_due() const { return _refresh; }

  /// Refresh P at the next update (after a failed solve).
  void refresh() { _refresh = _lagged; }
  /// As before the first solve of a run: no P yet (a new run on the same
  /// set-up; the counters stay).
  void restart()
  {
    _has_P = false;
    _refresh = false;
  }

  /// Before a solve: refresh P if the problem's constrained rows changed
  /// since P was built (its unit rows would be the wrong ones).
  void check_constraints(const NonlinearProblem& problem)
  {
    if (problem.constraint_version() != _constraint_version)
      refresh();
    _constraint_version = problem.constraint_version();
  }

  /// Numeric factorisations (preconditioner builds) so far.
  int factorizations() const { return _factorizations; }

private:
  bool _lagged;
  int _refactor_iterations;
  bool _has_P = false;
  bool _refresh = false;
  int _factorizations = 0;
  int _constraint_version = 0;
};
} // namespace pushout::solver

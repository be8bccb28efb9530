// What the Newton and path-following solvers need of a system
//   F(x) = 0,   F_c = x_c - g_c on its constrained rows c,
// whatever space x lives in: the whole displacement (Equilibrium.h) or the
// interface dofs after condensing the linear bulk (Condensation.h).
#pragma once

#include "../common/petsc_check.h"
#include <petscksp.h>
#include <petscmat.h>
#include <petscvec.h>

namespace pushout::solver
{
/// C of the round-off floors (NonlinearProblem::residual_floor). Measured
/// where Newton stagnates on push-out models: ||F|| settles at 0.02 of eps
/// times the bound's scale on the whole model (full model, 2016 dofs: 7e-11
/// N against 3.4e-9 N) and at 0.1-0.2 of it on the condensed system, so C
/// = 1 sits above the noise with a margin, and far below the tolerances a
/// run needs (tests/e2e/test_newton_stops_at_round_off_floor.py: -snes_atol 1e-30).
constexpr double residual_floor_factor = 1.0;

class NonlinearProblem
{
public:
  virtual ~NonlinearProblem() = default;

  /// A new matrix with the layout of the Jacobian (the caller destroys it).
  virtual Mat create_matrix() const = 0;
  /// The Jacobian as an operator for Krylov methods (the caller destroys
  /// it): create_matrix() unless the problem has a cheaper matrix-free
  /// product; jacobian() updates it too.
  virtual Mat create_operator() const { return create_matrix(); }
  /// The Jacobian held by an operator J (after jacobian(x, J)) into a
  /// create_matrix() matrix P.
  virtual void copy_jacobian(Mat J, Mat P) const
  {
    petsc::check(MatCopy(J, P, SAME_NONZERO_PATTERN), "MatCopy");
  }
  /// A new vector of the problem's space (the caller destroys it).
  virtual Vec create_vector() const = 0;

  /// F(x), constrained rows x_c - g_c. Returns false if an interface law
  /// failed.
  virtual bool residual(Vec x, Vec F) = 0;
  /// F(x) as above, and the 2-norm over all processes of the forces at the
  /// constrained rows before they are replaced (the reactions [N]: the scale
  /// of the residual).
  virtual bool residual(Vec x, Vec F, double& reaction_norm) = 0;
  /// The Jacobian dF/dx into J (a matrix from create_matrix()).
  virtual bool jacobian(Vec x, Mat J) = 0;

  /// The energy the joint elements release from the committed state to x
  /// (interface::Interface::energy_release, summed over the sets of joints
  /// and the processes) [N mm], and its gradient dG/dx in this problem's
  /// space into `gradient` (a create_vector() vector): the constraint of
  /// dissipation-controlled path following. Evaluates the laws at x (trial
  /// state). Returns false if a law failed. Collective.
  virtual bool energy_release(Vec x, double& G, Vec gradient) = 0;

  /// The round-off floor of ||F|| (2-norm) near x, after residual() at x:
  /// the level below which ||F|| is the noise of evaluating F in floating
  /// point and no Newton step lowers it. Collective. A safe bound, e.g.
  ///   floor = C eps (||A||_inf ||x|| + ||loads|| + ...),
  /// for F = A x - loads + ...: evaluating row i of A x sums terms of size
  /// |A_ij x_j| with relative error eps each (the interface and the loads
  /// likewise), and || |A| |x| || <= ||A||_inf ||x|| (A symmetric).
  virtual double residual_floor(Vec x) = 0;

  /// Adjusts a linear solver already set from the options to what the
  /// matrices of this problem support (called by the solvers).
  virtual void configure(KSP /*ksp*/) const {}

  /// A number that changes when the constrained rows of the Jacobian
  /// change (not their values): a lagged preconditioner built before is
  /// then refreshed.
  virtual int constraint_version() const { return 0; }

  /// Forgets the interface state the last evaluation wrote (trial state
  /// back to the committed one).
  virtual void forget_trial_state() = 0;

  /// Tangents evaluated so far (jacobian(), by any solver): a solver that
  /// keeps a tangent to reuse knows whether another evaluation replaced it.
  int tangent_evaluations() const { return _tangent_evaluations; }

protected:
  /// Called by jacobian().
  void count_tangent() { ++_tangent_evaluations; }

private:
  int _tangent_evaluations = 0;
};
} // namespace pushout::solver

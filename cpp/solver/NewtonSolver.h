// Thin layer over PETSc SNES: Newton with line search (PETSc's newtonls/bt
// by default) on a NonlinearProblem (the whole model or its condensed
// interface system). Every PETSc option from the command line
// reaches SNES, KSP and PC (-snes_monitor, -ksp_type, -pc_type, ...); the
// defaults below apply only where the user gave none. Newton has converged
// when PETSc's test says so, or when ||F|| is at the round-off floor of the
// residual (NonlinearProblem::residual_floor), below which no tolerance can
// be met; it is then reported as CONVERGED_FNORM_ABS.
//
// Two ways to solve the Newton systems J du = -F:
//  - Preconditioner::jacobian: factor J (MUMPS LU) in every iteration.
//  - Preconditioner::lagged: the bulk is linear and only the interface
//    tangent changes, so J - P lives on the interface dofs for any earlier
//    Jacobian P, and GMRES preconditioned by the LU of P converges in a few
//    iterations. P starts as the elastic tangent (virgin interface, zero
//    jump) and is refreshed from the current J, at the start of a Newton
//    iteration, only when the previous linear solve needed more than
//    `refactor_iterations` GMRES iterations or failed. A MUMPS solve costs
//    about 1/20 of a factorisation here, so this saves most of them.
#pragma once

#include "NonlinearProblem.h"
#include "PreconditionerPolicy.h"
#include <petscsnes.h>
#include <string>

namespace pushout::solver
{
struct SolveReport
{
  bool converged = false;
  int iterations = 0;
  std::string reason; ///< PETSc's converged/diverged reason
};

class NewtonSolver
{
public:
  enum class Preconditioner
  {
    jacobian,
    lagged
  };

  NewtonSolver(NonlinearProblem& problem, Preconditioner pc, int refactor_iterations = 10);
  ~NewtonSolver();
  NewtonSolver(const NewtonSolver&) = delete;
  NewtonSolver& operator=(const NewtonSolver&) = delete;

  /// Solves F(x) = 0 from the initial guess x (constraints already in x).
  SolveReport solve(Vec x);

  /// Times one linear solve J(x) dx = -F(x) with the solver configured for
  /// the Newton systems (a fresh KSP from the same options, the first
  /// factorisation included) [s]. Leaves x and the committed state alone.
  double time_linear_solve(Vec x);

  /// Sets PETSc's options database defaults for pushout (MUMPS LU, tight
  /// tolerances) where the user did not set them. Call before NewtonSolver.
  static void set_default_options(Preconditioner pc);

  /// Whether the Newton systems are factored (-pc_type lu, the default, or
  /// cholesky) rather than preconditioned iteratively (-pc_type gamg, ...).
  /// Reads PETSc's options database.
  static bool direct_factorization();

private:
  NonlinearProblem& _problem;
  SNES _snes = nullptr;
  PreconditionerPolicy _policy;
  Mat _J = nullptr, _P = nullptr;
  Vec _F = nullptr;

public:
  /// Numeric factorisations so far (for the summary).
  int factorizations() const { return _policy.factorizations(); }
  /// The next solve starts as the first solve of a run (a new run on the
  /// same set-up: the same iterates, bit for bit).
  void restart() { _policy.restart(); }

private:
  static PetscErrorCode jacobian_callback(SNES snes, Vec x, Mat J, Mat P, void* ctx);
  static PetscErrorCode convergence_test(SNES snes, PetscInt it, PetscReal xnorm, PetscReal snorm,
                                         PetscReal fnorm, SNESConvergedReason* reason, void* ctx);
};

/// Why the last set-up of the preconditioner of `ksp` failed on any of its
/// processes, in words ("zero pivot", ...; "" if it did not). Collective.
std::string factorization_failure(KSP ksp);

/// Whether a PETSc error code is a zero pivot of a factorisation that raises
/// an error instead of recording a failed reason (PETSc's dense LU: the
/// condensed systems', on one process).
bool zero_pivot_error(PetscErrorCode code);
} // namespace pushout::solver

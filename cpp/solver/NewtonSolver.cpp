#include "NewtonSolver.h"
#include "../common/Interrupt.h"
#include <algorithm>

namespace pushout::solver
{
namespace
{
PetscErrorCode form_function(SNES snes, Vec x, Vec F, void* ctx)
{
  auto* problem = static_cast<NonlinearProblem*>(ctx);
  // A failed law or a pending signal fails this solve; the step loop decides.
  if (!problem->residual(x, F) || interrupt::received())
    SNESSetFunctionDomainError(snes);
  return 0;
}

void set_default(const char* name, const char* value)
{
  PetscBool set = PETSC_FALSE;
  PetscOptionsHasName(nullptr, nullptr, name, &set);
  if (!set)
    PetscOptionsSetValue(nullptr, name, value);
}
} // namespace

void NewtonSolver::set_default_options(Preconditioner pc)
{
  set_default("-snes_type", "newtonls");
  set_default("-snes_linesearch_type", "bt");
  set_default("-snes_rtol", "1e-10");
  set_default("-snes_atol", "1e-10");
  set_default("-snes_stol", "1e-14");
  set_default("-snes_max_it", "50");
  if (pc == Preconditioner::lagged)
  {
    set_default("-ksp_type", "gmres");
    set_default("-ksp_gmres_restart", "200");
    set_default("-ksp_rtol", "1e-10");
    set_default("-ksp_max_it", "1000");
  }
  else
    set_default("-ksp_type", "preonly");
  set_default("-pc_type", "lu");
  set_default("-pc_factor_mat_solver_type", "mumps");
}

bool NewtonSolver::direct_factorization()
{
  char pc_type[64] = "";
  PetscBool set = PETSC_FALSE;
  PetscOptionsGetString(nullptr, nullptr, "-pc_type", pc_type, sizeof(pc_type), &set);
  return !set || std::string(pc_type) == "lu" || std::string(pc_type) == "cholesky";
}

NewtonSolver::NewtonSolver(NonlinearProblem& problem, Preconditioner pc, int refactor_iterations)
    : _problem(problem), _policy(pc == Preconditioner::lagged, refactor_iterations)
{
  _J = _policy.lagged() ? problem.create_operator() : problem.create_matrix();
  _F = problem.create_vector();
  SNESCreate(PetscObjectComm(reinterpret_cast<PetscObject>(_F)), &_snes);
  SNESSetFunction(_snes, _F, form_function, &_problem);
  if (_policy.lagged())
  {
    _P = problem.create_matrix();
    SNESSetJacobian(_snes, _J, _P, jacobian_callback, this);
  }
  else
    SNESSetJacobian(_snes, _J, _J, jacobian_callback, this);
  SNESSetFromOptions(_snes);
  KSP ksp;
  SNESGetKSP(_snes, &ksp);
  problem.configure(ksp);
}

PetscErrorCode NewtonSolver::jacobian_callback(SNES snes, Vec x, Mat J, Mat P, void* ctx)
{
  auto* self = static_cast<NewtonSolver*>(ctx);
  if (!self->_problem.jacobian(x, J))
    SNESSetJacobianDomainError(snes);
  KSP ksp;
  SNESGetKSP(snes, &ksp);
  PetscInt its = 0;
  KSPGetIterationNumber(ksp, &its); // of the previous linear solve
  self->_policy.solved(its);
  KSPSetReusePreconditioner(ksp,
                            self->_policy.update(self->_problem, J, P) ? PETSC_FALSE : PETSC_TRUE);
  return 0;
}

NewtonSolver::~NewtonSolver()
{
  SNESDestroy(&_snes);
  MatDestroy(&_J);
  if (_P)
    MatDestroy(&_P);
  VecDestroy(&_F);
}

double NewtonSolver::time_linear_solve(Vec x)
{
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(x));
  Vec F, dx;
  VecDuplicate(x, &F);
  VecDuplicate(x, &dx);
  _problem.residual(x, F);
  VecScale(F, -1.0);
  _problem.jacobian(x, _J);
  KSP ksp;
  KSPCreate(comm, &ksp);
  KSPSetOperators(ksp, _J, _J);
  KSPSetFromOptions(ksp);
  _problem.configure(ksp);
  MPI_Barrier(comm);
  const double t0 = MPI_Wtime();
  KSPSetUp(ksp);
  KSPSolve(ksp, F, dx);
  MPI_Barrier(comm);
  const double t = MPI_Wtime() - t0;
  KSPDestroy(&ksp);
  VecDestroy(&F);
  VecDestroy(&dx);
  _problem.forget_trial_state();
  return t;
}

SolveReport NewtonSolver::solve(Vec x)
{
  _policy.check_constraints(_problem);
  if (_policy.lagged() && !_policy.has_P())
  {
    // The first solve of a run starts from the virgin interface state and
    // the constraints of the run (their dofs never change, only values):
    // the Jacobian at zero displacement is the elastic tangent.
    Vec zero;
    VecDuplicate(x, &zero);
    VecSet(zero, 0.0);
    _problem.jacobian(zero, _P);
    VecDestroy(&zero);
    _policy.P_filled();
  }
  SolveReport r;
  SNESSolve(_snes, nullptr, x);
  SNESConvergedReason reason;
  SNESGetConvergedReason(_snes, &reason);
  PetscInt its;
  SNESGetIterationNumber(_snes, &its);
  r.converged = reason > 0;
  r.iterations = int(its);
  r.reason = SNESConvergedReasons[reason];
  if (!r.converged)
    _policy.refresh(); // a retry starts from a fresh factorisation
  return r;
}
} // namespace pushout::solver

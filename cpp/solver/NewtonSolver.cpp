#include "NewtonSolver.h"

namespace pushout::solver
{
namespace
{
PetscErrorCode form_function(SNES snes, Vec x, Vec F, void* ctx)
{
  auto* problem = static_cast<Equilibrium*>(ctx);
  if (!problem->residual(x, F))
    SNESSetFunctionDomainError(snes);
  return 0;
}

PetscErrorCode form_jacobian(SNES snes, Vec x, Mat J, Mat, void* ctx)
{
  auto* problem = static_cast<Equilibrium*>(ctx);
  if (!problem->jacobian(x, J))
    SNESSetJacobianDomainError(snes);
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

void NewtonSolver::set_default_options()
{
  set_default("-snes_type", "newtonls");
  set_default("-snes_linesearch_type", "bt");
  set_default("-snes_rtol", "1e-10");
  set_default("-snes_atol", "1e-10");
  set_default("-snes_stol", "1e-14");
  set_default("-snes_max_it", "50");
  set_default("-ksp_type", "preonly");
  set_default("-pc_type", "lu");
  set_default("-pc_factor_mat_solver_type", "mumps");
}

NewtonSolver::NewtonSolver(Equilibrium& problem) : _problem(problem)
{
  Mat K = problem.model().K;
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(K));
  MatDuplicate(K, MAT_COPY_VALUES, &_J);
  MatSetOption(_J, MAT_KEEP_NONZERO_PATTERN, PETSC_TRUE);
  MatCreateVecs(K, nullptr, &_F);
  SNESCreate(comm, &_snes);
  SNESSetFunction(_snes, _F, form_function, &_problem);
  SNESSetJacobian(_snes, _J, _J, form_jacobian, &_problem);
  SNESSetFromOptions(_snes);
}

NewtonSolver::~NewtonSolver()
{
  SNESDestroy(&_snes);
  MatDestroy(&_J);
  VecDestroy(&_F);
}

SolveReport NewtonSolver::solve(Vec x)
{
  SolveReport r;
  SNESSolve(_snes, nullptr, x);
  SNESConvergedReason reason;
  SNESGetConvergedReason(_snes, &reason);
  PetscInt its;
  SNESGetIterationNumber(_snes, &its);
  r.converged = reason > 0;
  r.iterations = int(its);
  r.reason = SNESConvergedReasons[reason];
  return r;
}
} // namespace pushout::solver

#include "ArcLengthSolver.h"
#include "../common/Interrupt.h"
#include <cmath>

namespace pushout::solver
{
ArcLengthSolver::ArcLengthSolver(NonlinearProblem& problem, Vec control,
                                 NewtonSolver::Preconditioner pc, int refactor_iterations)
    : _problem(problem), _policy(pc == NewtonSolver::Preconditioner::lagged, refactor_iterations)
{
  if (_policy.lagged())
  {
    _J = problem.create_operator();
    _P = problem.create_matrix();
  }
  else
    _J = problem.create_matrix();
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(control));
  VecDuplicate(control, &_a);
  VecCopy(control, _a);
  for (Vec* v : {&_e, &_F, &_v1, &_v2})
    VecDuplicate(control, v);
  KSPCreate(comm, &_ksp);
  KSPSetFromOptions(_ksp);
  problem.configure(_ksp);
  PetscOptionsGetReal(nullptr, nullptr, "-snes_rtol", &_rtol, nullptr);
  PetscOptionsGetReal(nullptr, nullptr, "-snes_atol", &_atol, nullptr);
  PetscOptionsGetReal(nullptr, nullptr, "-snes_stol", &_stol, nullptr);
  PetscOptionsGetInt(nullptr, nullptr, "-snes_max_it", &_max_it, nullptr);
  PetscOptionsHasName(nullptr, nullptr, "-arc_monitor", &_monitor);
}

ArcLengthSolver::~ArcLengthSolver()
{
  KSPDestroy(&_ksp);
  MatDestroy(&_J);
  if (_P)
    MatDestroy(&_P);
  for (Vec* v : {&_a, &_e, &_F, &_v1, &_v2})
    VecDestroy(v);
}

double ArcLengthSolver::control(Vec x) const
{
  double s;
  VecDot(_a, x, &s);
  return s;
}

namespace
{
/// Whether `ok` holds on every process (a law may fail on one only).
bool all(bool ok, Vec v)
{
  int local = ok ? 1 : 0, global = 0;
  MPI_Allreduce(&local, &global, 1, MPI_INT, MPI_MIN,
                PetscObjectComm(reinterpret_cast<PetscObject>(v)));
  return global == 1;
}
} // namespace

bool ArcLengthSolver::residual(Vec x, double& reactions)
{
  return all(_problem.residual(x, _F, reactions), x);
}

bool ArcLengthSolver::setup_operators(Vec x)
{
  if (!all(_problem.jacobian(x, _J), x))
    return false;
  KSPSetReusePreconditioner(_ksp, _policy.update(_problem, _J, _P) ? PETSC_FALSE : PETSC_TRUE);
  KSPSetOperators(_ksp, _J, _policy.lagged() ? _P : _J);
  return true;
}

bool ArcLengthSolver::solve(Vec b, Vec y)
{
  for (int attempt = 0; attempt < 2; ++attempt)
  {
    VecSet(y, 0.0);
    KSPSolve(_ksp, b, y);
    KSPConvergedReason reason;
    KSPGetConvergedReason(_ksp, &reason);
    PetscInt its;
    KSPGetIterationNumber(_ksp, &its);
    _policy.solved(its);
    if (reason > 0)
      return true;
    if (!_policy.lagged())
      return false;
    // The lagged preconditioner was too far from J: factor J itself.
    _policy.refresh();
    KSPSetReusePreconditioner(_ksp, _policy.update(_problem, _J, _P) ? PETSC_FALSE : PETSC_TRUE);
    KSPSetOperators(_ksp, _J, _P);
  }
  return false;
}

SolveReport ArcLengthSolver::step(Vec x, double& lambda, double d_eta,
                                  const std::function<void(double)>& set_load)
{
  SolveReport rep;
  _policy.check_constraints(_problem);
  // e = -dF/dlambda = F(x, lambda) - F(x, lambda + 1): F is affine in lambda.
  double reactions = 0;
  set_load(lambda + 1.0);
  residual(x, reactions);
  VecCopy(_F, _e);
  set_load(lambda);
  residual(x, reactions);
  VecAYPX(_e, -1.0, _F);
  const double eta0 = control(x), eta = eta0 + d_eta;
  double lam = lambda;
  const auto fail = [&](std::string why)
  {
    rep.converged = false;
    rep.reason = std::move(why);
    _policy.refresh(); // a retry starts from a fresh factorisation
    return rep;
  };
  for (PetscInt it = 0;; ++it)
  {
    set_load(lam);
    if (!residual(x, reactions))
      return fail("an interface law failed");
    double fnorm;
    VecNorm(_F, NORM_2, &fnorm);
    if (!std::isfinite(fnorm))
      return fail("residual not finite");
    if (_monitor)
      PetscPrintf(PetscObjectComm(reinterpret_cast<PetscObject>(x)),
                  "  arc %d: |F| %.6e N (tol %.3e), lambda %.9e mm, slip - target %.3e mm\n",
                  int(it), fnorm, std::max(_atol, _rtol * reactions), lam, control(x) - eta);
    if (it > 0 && fnorm <= std::max(_atol, _rtol * reactions) &&
        std::abs(control(x) - eta) <= 1e-8 * std::abs(d_eta))
    {
      rep.converged = true;
      rep.reason = "CONVERGED_FNORM";
      break;
    }
    if (it == _max_it)
      return fail("DIVERGED_MAX_IT");
    if (!all(!interrupt::received(), x)) // a signal on any process
      return fail("interrupted");
    if (!setup_operators(x))
      return fail("an interface law failed");
    VecScale(_F, -1.0);
    if (!solve(_F, _v1) || !solve(_e, _v2))
      return fail("DIVERGED_LINEAR_SOLVE");
    const double r = control(_v2); // d(control)/d(lambda) along the tangent
    if (!std::isfinite(r) || r == 0.0)
      return fail("singular bordered system (d control / d lambda = 0)");
    const double dlambda = -(control(x) - eta + control(_v1)) / r;
    VecAXPY(_v1, dlambda, _v2); // dx
    lam += dlambda;
    VecAXPY(x, 1.0, _v1);
    rep.iterations = int(it + 1);
    double dx, xn;
    VecNorm(_v1, NORM_2, &dx);
    VecNorm(x, NORM_2, &xn);
    if (!std::isfinite(dx) || !std::isfinite(lam))
      return fail("update not finite");
    if (it > 0 && dx <= _stol * xn && std::abs(dlambda) <= _stol * std::abs(lam))
    {
      set_load(lam);
      rep.converged = true;
      rep.reason = "CONVERGED_SNORM_RELATIVE";
      break;
    }
  }
  lambda = lam;
  return rep;
}
} // namespace pushout::solver

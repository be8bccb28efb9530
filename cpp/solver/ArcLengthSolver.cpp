#include "ArcLengthSolver.h"
#include "../common/Interrupt.h"
#include "../common/build_or_release.h"
#include "../common/mpi_errors.h"
#include "../common/petsc_check.h"
#include "FactorizationFailure.h"
#include "NewtonHistory.h"
#include "Vector.h"
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace pushout::solver
{
using petsc::check;

LinearConstraint::LinearConstraint(Vec a)
{
  check(VecDuplicate(a, &_a), "VecDuplicate");
  check(VecCopy(a, _a), "VecCopy");
}

LinearConstraint::~LinearConstraint()
{
  petsc::check_nothrow(VecDestroy(&_a), "VecDestroy");
}

bool LinearConstraint::evaluate(Vec x, double& value, Vec gradient)
{
  value = this->value(x);
  check(VecCopy(_a, gradient), "VecCopy");
  return true;
}

double LinearConstraint::value(Vec x) const
{
  double v;
  check(VecDot(_a, x, &v), "VecDot");
  return v;
}

void LinearConstraint::add_to(Vec y, double beta) const
{
  check(VecAXPY(y, beta, _a), "VecAXPY");
}

bool EnergyReleaseConstraint::evaluate(Vec x, double& value, Vec gradient)
{
  const bool ok = _problem.energy_release(x, value, gradient);
  value += _beta * _slip.value(x);
  _slip.add_to(gradient, _beta);
  return ok;
}

ArcLengthSolver::ArcLengthSolver(NonlinearProblem& problem, PathConstraint& control,
                                 NewtonSolver::Preconditioner pc, int refactor_iterations)
    : _problem(problem), _control(control),
      _policy(pc == NewtonSolver::Preconditioner::lagged, refactor_iterations)
{
  build_or_release([&] { set_up(problem); }, [this] { release(); });
}

void ArcLengthSolver::set_up(NonlinearProblem& problem)
{
  if (_policy.lagged())
  {
    _J = problem.create_operator();
    _P = problem.create_matrix();
  }
  else
    _J = problem.create_matrix();
  _a = problem.create_vector();
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(_a));
  for (Vec* v : {&_e, &_F, &_v1, &_v2, &_w})
    check(VecDuplicate(_a, v), "VecDuplicate");
  check(KSPCreate(comm, &_ksp), "KSPCreate");
  check(KSPSetFromOptions(_ksp), "KSPSetFromOptions");
  problem.configure(_ksp);
  check(PetscOptionsGetReal(nullptr, nullptr, "-snes_rtol", &_rtol, nullptr),
        "PetscOptionsGetReal");
  check(PetscOptionsGetReal(nullptr, nullptr, "-snes_atol", &_atol, nullptr),
        "PetscOptionsGetReal");
  check(PetscOptionsGetReal(nullptr, nullptr, "-snes_stol", &_stol, nullptr),
        "PetscOptionsGetReal");
  check(PetscOptionsGetInt(nullptr, nullptr, "-snes_max_it", &_max_it, nullptr),
        "PetscOptionsGetInt");
  check(PetscOptionsHasName(nullptr, nullptr, "-arc_monitor", &_monitor), "PetscOptionsHasName");
}

ArcLengthSolver::~ArcLengthSolver()
{
  release();
}

void ArcLengthSolver::release() noexcept
{
  petsc::check_nothrow(KSPDestroy(&_ksp), "KSPDestroy");
  petsc::check_nothrow(MatDestroy(&_J), "MatDestroy");
  if (_P)
    petsc::check_nothrow(MatDestroy(&_P), "MatDestroy");
  for (Vec* v : {&_a, &_e, &_F, &_v1, &_v2, &_w})
    petsc::check_nothrow(VecDestroy(v), "VecDestroy");
}

namespace
{
MPI_Comm comm_of(Vec v)
{
  return PetscObjectComm(reinterpret_cast<PetscObject>(v));
}
} // namespace

bool ArcLengthSolver::constraint(Vec x, double& value)
{
  return mpi::all(comm_of(x),
                  mpi::collectively(comm_of(x), [&] { return _control.evaluate(x, value, _a); }));
}

double ArcLengthSolver::control(Vec x)
{
  double c;
  if (!constraint(x, c))
    throw std::runtime_error("path following: an interface law failed evaluating the control");
  return c;
}

// A law may fail on one process only, and so may an exception: both are
// agreed on by all (common/mpi_errors.h).
bool ArcLengthSolver::residual(Vec x, double& reactions)
{
  return mpi::all(comm_of(x), mpi::collectively(comm_of(x), [&]
                                                { return _problem.residual(x, _F, reactions); }));
}

bool ArcLengthSolver::setup_operators(Vec x)
{
  if (!mpi::all(comm_of(x),
                mpi::collectively(comm_of(x), [&] { return _problem.jacobian(x, _J); })))
    return false;
  check(
      KSPSetReusePreconditioner(_ksp, _policy.update(_problem, _J, _P) ? PETSC_FALSE : PETSC_TRUE),
      "KSPSetReusePreconditioner");
  check(KSPSetOperators(_ksp, _J, _policy.lagged() ? _P : _J), "KSPSetOperators");
  return true;
}

std::string ArcLengthSolver::solve(Vec b, Vec y)
{
  std::string why = "DIVERGED_LINEAR_SOLVE";
  for (int attempt = 0; attempt < 2; ++attempt)
  {
    check(VecSet(y, 0.0), "VecSet");
    // A failed factorisation fails the step (cut back), as in NewtonSolver.
    const PetscErrorCode code = KSPSolve(_ksp, b, y);
    if (zero_pivot_error(code, PetscObjectComm(reinterpret_cast<PetscObject>(_ksp))) &&
        !petsc::callback_failed())
      return "DIVERGED_LINEAR_SOLVE (zero pivot)";
    check(code, "KSPSolve");
    KSPConvergedReason reason;
    check(KSPGetConvergedReason(_ksp, &reason), "KSPGetConvergedReason");
    PetscInt its;
    check(KSPGetIterationNumber(_ksp, &its), "KSPGetIterationNumber");
    _linear_iterations += its;
    _policy.solved(its);
    if (reason > 0)
      return "";
    if (const std::string f = factorization_failure(_ksp); !f.empty())
      why = "DIVERGED_LINEAR_SOLVE (" + f + ")";
    if (!_policy.lagged())
      return why;
    // The lagged preconditioner was too far from J: factor J itself.
    _policy.refresh();
    check(KSPSetReusePreconditioner(_ksp,
                                    _policy.update(_problem, _J, _P) ? PETSC_FALSE : PETSC_TRUE),
          "KSPSetReusePreconditioner");
    check(KSPSetOperators(_ksp, _J, _P), "KSPSetOperators");
  }
  return why;
}

bool ArcLengthSolver::load_direction(Vec x, double lambda,
                                     const std::function<void(double)>& set_load, double& reactions)
{
  // Affine: e = F(x, lambda) - F(x, lambda + 1), exact. Otherwise
  // e = -(F(x, lambda + h) - F(x, lambda)) / h.
  const double h = _fd_step > 0 ? _fd_step : 1.0;
  set_load(lambda + h);
  bool ok = residual(x, reactions);
  check(VecCopy(_F, _e), "VecCopy");
  set_load(lambda);
  ok = residual(x, reactions) && ok;
  check(VecAYPX(_e, -1.0, _F), "VecAYPX");
  check(VecScale(_e, 1.0 / h), "VecScale");
  return ok;
}

std::string ArcLengthSolver::correction(Vec x, double c_minus_eta, double max_dlambda,
                                        double& dlambda)
{
  if (!setup_operators(x))
    return "an interface law failed";
  check(VecScale(_F, -1.0), "VecScale");
  if (std::string why = solve(_F, _v1); !why.empty())
    return why;
  if (std::string why = solve(_e, _v2); !why.empty())
    return why;
  double r, a_v1; // d(control)/d(lambda) along the tangent; a . v1
  check(VecDot(_a, _v2, &r), "VecDot");
  check(VecDot(_a, _v1, &a_v1), "VecDot");
  if (!std::isfinite(r) || r == 0.0)
    return "singular bordered system (d control / d lambda = 0)";
  dlambda = -(c_minus_eta + a_v1) / r;
  if (max_dlambda > 0 && std::abs(dlambda) > max_dlambda)
    dlambda = std::copysign(max_dlambda, dlambda);
  check(VecAXPY(_v1, dlambda, _v2), "VecAXPY"); // dx
  return "";
}

double ArcLengthSolver::control_terms(Vec x)
{
  check(VecPointwiseMult(_w, _a, x), "VecPointwiseMult");
  double terms;
  check(VecNorm(_w, NORM_1, &terms), "VecNorm");
  return terms;
}

double ArcLengthSolver::control_tolerance(double d_eta, double terms)
{
  return std::max(control_rtol * std::abs(d_eta),
                  control_round_off * std::numeric_limits<double>::epsilon() * terms);
}

std::string ArcLengthSolver::loose_convergence(double fnorm, double reactions, double control_error,
                                               double d_eta)
{
  if (!(fnorm <= loose_rtol * reactions) ||
      !(std::abs(control_error) <= loose_control * std::abs(d_eta)))
    return "";
  std::ostringstream s;
  s.precision(2);
  s << "CONVERGED_AT_STALL (its best iterate: |F| " << fnorm << " N, " << fnorm / reactions
    << " of the reactions; the control off by " << std::abs(control_error / d_eta)
    << " of the step)";
  return s.str();
}

std::string ArcLengthSolver::iterate(Vec x, double lam, const std::function<void(double)>& set_load,
                                     double& reactions, double& fnorm, double& c)
{
  // F at (x, lam), and e where it moves with the iterate.
  bool evaluated;
  if (_fd_step > 0)
    evaluated = load_direction(x, lam, set_load, reactions);
  else
  {
    set_load(lam);
    evaluated = residual(x, reactions);
  }
  if (!evaluated)
    return "an interface law failed";
  check(VecNorm(_F, NORM_2, &fnorm), "VecNorm");
  if (!std::isfinite(fnorm))
    return "residual not finite";
  if (!constraint(x, c)) // c(x) and its gradient _a
    return "an interface law failed";
  return "";
}

SolveReport ArcLengthSolver::step(Vec x, double& lambda, double d_eta,
                                  const std::function<void(double)>& set_load, double max_dlambda,
                                  bool loose, std::optional<double> eta_from)
{
  SolveReport rep;
  _policy.check_constraints(_problem);
  double reactions = 0;
  if (_fd_step == 0 && !load_direction(x, lambda, set_load, reactions))
  {
    rep.converged = false;
    rep.reason = "an interface law failed";
    return rep;
  }
  double eta0;
  if (!constraint(x, eta0))
  {
    rep.converged = false;
    rep.reason = "an interface law failed";
    return rep;
  }
  const double eta = eta_from.value_or(eta0) + d_eta;
  double lam = lambda;
  const auto fail = [&](std::string why)
  {
    rep.converged = false;
    rep.reason = std::move(why);
    _policy.refresh(); // a retry starts from a fresh factorisation
    return rep;
  };
  std::vector<double> fnorms; // |F| of the iterates so far
  // Of the iterates after the first whose control is within loose_control
  // of its target, the one of least |F| (where a stalled step may end).
  Vec best_copy;
  check(VecDuplicate(x, &best_copy), "VecDuplicate");
  const Vector best_x(best_copy); // destroyed on every way out
  double best_fnorm = INFINITY, best_lambda = lam, best_control_error = 0;
  for (PetscInt it = 0;; ++it)
  {
    double fnorm, c;
    if (std::string why = iterate(x, lam, set_load, reactions, fnorm, c); !why.empty())
      return fail(why);
    if (_monitor)
      check(PetscPrintf(PetscObjectComm(reinterpret_cast<PetscObject>(x)),
                        "  arc %d: |F| %.6e N (tol %.3e), lambda %.9e mm, control - target %.3e\n",
                        int(it), fnorm, std::max(_atol, _rtol * reactions), lam, c - eta),
            "PetscPrintf");
    // PETSc's tolerances, or the round-off floor of the residual below which
    // they cannot be met (NewtonSolver.h).
    const bool small = fnorm <= std::max(_atol, _rtol * reactions) ||
                       fnorm <= _problem.residual_floor(x); // the same on every process
    if (it > 0 && small && std::abs(c - eta) <= control_tolerance(d_eta, control_terms(x)))
    {
      rep.converged = true;
      rep.reason = "CONVERGED_FNORM";
      break;
    }
    if (it == _max_it)
      return fail("DIVERGED_MAX_IT");
    fnorms.push_back(fnorm);
    if (it > 0 && fnorm < best_fnorm && std::abs(c - eta) <= loose_control * std::abs(d_eta))
    {
      check(VecCopy(x, best_x), "VecCopy");
      best_fnorm = fnorm;
      best_lambda = lam;
      best_control_error = c - eta;
    }
    // Never once |F| meets its tolerance: the control equation may still be
    // converging.
    if (!small && stalled(fnorms))
    {
      const std::string why =
          loose ? loose_convergence(best_fnorm, reactions, best_control_error, d_eta) : "";
      if (why.empty())
        return fail("DIVERGED_NO_PROGRESS (|F| not halved in " + std::to_string(stall_iterations) +
                    " iterations)");
      // The best iterate, and the laws' evaluation there (outputs, commit).
      check(VecCopy(best_x, x), "VecCopy");
      lam = best_lambda;
      set_load(lam);
      if (!residual(x, reactions) || !constraint(x, c))
        return fail("an interface law failed");
      rep.converged = rep.loose = true;
      rep.reason = why;
      break;
    }
    if (!mpi::all(comm_of(x), !interrupt::received())) // a signal on any process
      return fail("interrupted");
    double dlambda;
    if (std::string why = correction(x, c - eta, it == 0 ? max_dlambda : 0, dlambda); !why.empty())
      return fail(why);
    lam += dlambda;
    check(VecAXPY(x, 1.0, _v1), "VecAXPY");
    rep.iterations = int(it + 1);
    double dx, xn;
    check(VecNorm(_v1, NORM_2, &dx), "VecNorm");
    check(VecNorm(x, NORM_2, &xn), "VecNorm");
    if (!std::isfinite(dx) || !std::isfinite(lam))
      return fail("update not finite");
    if (it > 0 && dx <= _stol * xn && std::abs(dlambda) <= _stol * std::abs(lam))
    {
      set_load(lam);
      // The laws' last evaluation at the converged x (outputs, commit).
      if (!residual(x, reactions))
        return fail("an interface law failed");
      rep.converged = true;
      rep.reason = "CONVERGED_SNORM_RELATIVE";
      break;
    }
  }
  lambda = lam;
  return rep;
}
} // namespace pushout::solver

#include "NewtonSolver.h"
#include "../common/Interrupt.h"
#include "../common/build_or_release.h"
#include "../common/mpi_errors.h"
#include "../common/petsc_check.h"
#include "../scene/SceneError.h"
#include "FactorizationFailure.h"
#include "NewtonHistory.h"
#include "SinglePrecisionSparse.h"
#include "Vector.h"
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>
#include <set>
#include <string>

namespace pushout::solver
{
using petsc::check;

namespace
{
MPI_Comm comm_of(SNES snes)
{
  return PetscObjectComm(reinterpret_cast<PetscObject>(snes));
}

PetscErrorCode form_function(SNES snes, Vec x, Vec F, void* ctx)
{
  return petsc::callback(
      [&]
      {
        auto* problem = static_cast<NonlinearProblem*>(ctx);
        // An exception on one process is the same error on all of them, not
        // one process leaving SNES while the others wait in its next norm.
        const bool ok = mpi::collectively(comm_of(snes), [&] { return problem->residual(x, F); });
        // A failed law or a pending signal fails this solve; the step loop
        // decides (SNES makes a domain error on one process everyone's).
        if (!ok || interrupt::received())
          check(SNESSetFunctionDomainError(snes), "SNESSetFunctionDomainError");
      });
}

/// Test hook, not a scene key (tests/e2e/test_no_silent_wrong_result.py): with
/// PUSHOUT_TEST_NONFINITE_FROM=n, the n-th converged Newton solve of the
/// process and every later one leave a NaN in their solution, as a solve
/// whose result is not a number would.
void test_non_finite(Vec x)
{
  static const char* from = std::getenv("PUSHOUT_TEST_NONFINITE_FROM");
  static long solves = 0;
  if (!from || ++solves < std::atol(from))
    return;
  PetscInt begin = 0, end = 0;
  check(VecGetOwnershipRange(x, &begin, &end), "VecGetOwnershipRange");
  if (end > begin)
  {
    check(VecSetValue(x, begin, std::numeric_limits<double>::quiet_NaN(), INSERT_VALUES),
          "VecSetValue");
  }
  check(VecAssemblyBegin(x), "VecAssemblyBegin");
  check(VecAssemblyEnd(x), "VecAssemblyEnd");
}

/// The PETSc options that hold a default of ours (set_default).
std::set<std::string>& ours()
{
  static std::set<std::string> names;
  return names;
}

/// Sets a PETSc option unless the user set it (on the command line). A
/// default set here for one run is replaced by the next run's default (the
/// runs of a sweep share one process: a case with cracks must not leave its
/// line search to the next case without).
void set_default(const char* name, const char* value)
{
  PetscBool set = PETSC_FALSE;
  check(PetscOptionsHasName(nullptr, nullptr, name, &set), "PetscOptionsHasName");
  if (set && !ours().contains(name))
    return;
  check(PetscOptionsSetValue(nullptr, name, value), "PetscOptionsSetValue");
  ours().insert(name);
}

/// Removes a default that an earlier run set (set_default), so that this
/// run has PETSc's own or the user's value.
void clear_default(const char* name)
{
  if (ours().erase(name) > 0)
    check(PetscOptionsClearValue(nullptr, name), "PetscOptionsClearValue");
}

} // namespace

bool finite(Vec x)
{
  // max |x_i| is NaN or inf if any entry is, on every process alike.
  PetscReal largest = 0;
  check(VecNorm(x, NORM_INFINITY, &largest), "VecNorm");
  return std::isfinite(largest);
}

void NewtonSolver::set_default_options(Preconditioner pc, Concrete concrete,
                                       bool single_precision_lu)
{
  const bool implex = concrete == Concrete::implex_cracks;
  set_default("-snes_type", "newtonls");
  set_default("-snes_linesearch_type", concrete == Concrete::cracks ? "l2" : "bt");
  set_default("-snes_rtol", implex ? implex_rtol : "1e-10");
  set_default("-snes_atol", "1e-10");
  set_default("-snes_stol", "1e-14");
  set_default("-snes_max_it", "50");
  // The implicit cracks factor every Jacobian (LoadStepSolver::make): GMRES
  // on that LU lets it be factored in single precision
  // (Equilibrium::configure); in double the LU is the solver.
  const char* krylov[] = {"-ksp_gmres_restart", "-ksp_rtol", "-ksp_max_it", "-ksp_pc_side"};
  if (gmres_by_default(pc, concrete, single_precision_lu))
  {
    set_default("-ksp_type", "gmres");
    set_default(krylov[0], "200");
    set_default(krylov[1], implex ? implex_rtol : "1e-10");
    set_default(krylov[2], "1000");
    // Right preconditioning: GMRES measures the Jacobian's own residual, so
    // that solver.inexact_newton can stop it at what Newton's test needs
    // where the LU is in double (solver.precision = "double"; flexible
    // GMRES, in single precision, is right-preconditioned anyway). On the
    // bench's scene on two processes, with the LU in double there then:
    // 3 188 GMRES iterations and 87 s against 4 010 and 103 s (left). A
    // solver of the user's PETSc options (-pc_type gamg, ...) keeps PETSc's
    // own side.
    if (linear_solver_from_options())
      clear_default(krylov[3]);
    else
      set_default(krylov[3], "right");
  }
  else
  {
    set_default("-ksp_type", "preonly");
    for (const char* name : krylov) // an earlier run's, in a sweep
      clear_default(name);
  }
  set_default("-pc_type", "lu");
  set_default("-pc_factor_mat_solver_type", "mumps");
}

bool NewtonSolver::direct_factorization()
{
  char pc_type[64] = "";
  PetscBool set = PETSC_FALSE;
  check(PetscOptionsGetString(nullptr, nullptr, "-pc_type", pc_type, sizeof(pc_type), &set),
        "PetscOptionsGetString");
  return !set || std::string(pc_type) == "lu" || std::string(pc_type) == "cholesky";
}

bool NewtonSolver::gmres_by_default(Preconditioner pc, Concrete concrete, bool single_precision_lu)
{
  return pc == Preconditioner::lagged || (concrete == Concrete::cracks && single_precision_lu);
}

std::string NewtonSolver::user_option(const char* name)
{
  if (ours().contains(name))
    return "";
  char value[256] = "";
  PetscBool set = PETSC_FALSE;
  check(PetscOptionsGetString(nullptr, nullptr, name, value, sizeof(value), &set),
        "PetscOptionsGetString");
  return set ? std::string(value) : "";
}

bool NewtonSolver::linear_solver_from_options()
{
  for (const char* name : {"-ksp_type", "-pc_type", "-pc_factor_mat_solver_type"})
  {
    PetscBool set = PETSC_FALSE;
    check(PetscOptionsHasName(nullptr, nullptr, name, &set), "PetscOptionsHasName");
    if (set && !ours().contains(name))
      return true;
  }
  return false;
}

NewtonSolver::NewtonSolver(NonlinearProblem& problem, Preconditioner pc, int refactor_iterations)
    : _problem(problem), _policy(pc == Preconditioner::lagged, refactor_iterations)
{
  build_or_release([&] { set_up(problem); }, [this] { release(); });
}

void NewtonSolver::set_up(NonlinearProblem& problem)
{
  _J = _policy.lagged() ? problem.create_operator() : problem.create_matrix();
  _F = problem.create_vector();
  check(SNESCreate(PetscObjectComm(reinterpret_cast<PetscObject>(_F)), &_snes), "SNESCreate");
  check(SNESSetFunction(_snes, _F, form_function, &_problem), "SNESSetFunction");
  if (_policy.lagged())
  {
    _P = problem.create_matrix();
    check(SNESSetJacobian(_snes, _J, _P, jacobian_callback, this), "SNESSetJacobian");
  }
  else
    check(SNESSetJacobian(_snes, _J, _J, jacobian_callback, this), "SNESSetJacobian");
  // A Jacobian that failed (a law at a point, agreed across the processes in
  // jacobian_callback) ends the solve as DIVERGED_JACOBIAN_DOMAIN: PETSc
  // reads SNESSetJacobianDomainError only when asked to check it.
  check(SNESSetCheckJacobianDomainError(_snes, PETSC_TRUE), "SNESSetCheckJacobianDomainError");
  // Before the options: -snes_convergence_test still replaces it.
  check(SNESSetConvergenceTest(_snes, convergence_test, this, nullptr), "SNESSetConvergenceTest");
  check(SNESSetFromOptions(_snes), "SNESSetFromOptions");
  KSP ksp;
  check(SNESGetKSP(_snes, &ksp), "SNESGetKSP");
  problem.configure(ksp);
  PetscBool ew = PETSC_FALSE;
  check(SNESKSPGetUseEW(_snes, &ew), "SNESKSPGetUseEW");
  if (!ew) // Eisenstat-Walker (-snes_ksp_ew) sets the tolerances itself (set_inexact)
  {
    check(KSPGetTolerances(ksp, &_ksp_rtol, nullptr, nullptr, nullptr), "KSPGetTolerances");
    check(KSPSetPreSolve(ksp, linear_tolerance, this), "KSPSetPreSolve");
  }
}

// The safeguard on the forcing term of inexact Newton (C. T. Kelley,
// Iterative Methods for Linear and Nonlinear Equations, SIAM 1995, ch. 6;
// docs/cracking-speed.md): from the second
// iteration on (from the first where a prediction made ||F_0|| smaller than
// solve()'s reference), the linear residual need not go below half of what
// Newton's test still asks, tolerance(), for the next iterate to pass it;
// -ksp_rtol stays the floor, and 0.1 the ceiling. Only
// where the KSP's norm is the true residual's (FGMRES, the single-precision
// LU's; right preconditioning): a preconditioned norm may be far from it.
// The hook sets the tolerance of every solve, -ksp_rtol where it does not
// loosen it (so a loosened one never carries over).
double NewtonSolver::inexact_rtol(double needed, double Fk, double ksp_rtol)
{
  if (!(Fk > 0))
    return ksp_rtol;
  return std::clamp(0.5 * needed / Fk, ksp_rtol, std::max(ksp_rtol, 0.1));
}

PetscErrorCode NewtonSolver::linear_tolerance(KSP ksp, Vec, Vec, void* ctx)
{
  return petsc::callback(
      [&]
      {
        auto* self = static_cast<NewtonSolver*>(ctx);
        PetscInt iteration = 0;
        check(SNESGetIterationNumber(self->_snes, &iteration), "SNESGetIterationNumber");
        double rtol = self->_ksp_rtol;
        KSPNormType norm = KSP_NORM_DEFAULT;
        check(KSPGetNormType(ksp, &norm), "KSPGetNormType");
        // _fnorms holds ||F|| of iterations 0 to `iteration` (the
        // convergence test runs before the solve): ||b|| = ||F_k||.
        // The first iteration solves to -ksp_rtol (a linear step converges
        // in one), unless a prediction made ||F_0|| smaller than what the
        // step's loads make: the test then asks for less than -ksp_rtol's.
        const bool known = self->_fnorms.size() == std::size_t(iteration) + 1;
        const bool loosened = known && (iteration > 0 || self->_reference > self->_fnorms.front());
        if (self->_inexact && loosened && norm == KSP_NORM_UNPRECONDITIONED)
          rtol = inexact_rtol(self->tolerance(self->_snes), self->_fnorms.back(), self->_ksp_rtol);
        check(KSPSetTolerances(ksp, rtol, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT),
              "KSPSetTolerances");
      });
}

PetscErrorCode NewtonSolver::jacobian_callback(SNES snes, Vec x, Mat J, Mat P, void* ctx)
{
  return petsc::callback(
      [&]
      {
        auto* self = static_cast<NewtonSolver*>(ctx);
        KSP ksp;
        check(SNESGetKSP(snes, &ksp), "SNESGetKSP");
        PetscInt iteration = 0;
        check(SNESGetIterationNumber(snes, &iteration), "SNESGetIterationNumber");
        if (iteration == 0 && self->_previous_tangent && self->_tangent_converged)
        {
          // The step's first iteration: the tangent (and preconditioner) of the
          // last converged step, as they are.
          self->_factored_now = false;
          check(KSPSetReusePreconditioner(ksp, PETSC_TRUE), "KSPSetReusePreconditioner");
          return;
        }
        if (self->in_linear_tail(iteration))
        {
          // The factorisation at hand, as it is (set_tail_reuse).
          self->_factored_now = false;
          check(KSPSetReusePreconditioner(ksp, PETSC_TRUE), "KSPSetReusePreconditioner");
          return;
        }
        if (!mpi::collectively(comm_of(snes), [&] { return self->_problem.jacobian(x, J); }))
          check(SNESSetJacobianDomainError(snes), "SNESSetJacobianDomainError");
        PetscInt its = 0;
        check(KSPGetIterationNumber(ksp, &its), "KSPGetIterationNumber"); // the previous solve's
        self->_policy.solved(its);
        self->_factored_now = self->_policy.update(self->_problem, J, P);
        check(KSPSetReusePreconditioner(ksp, self->_factored_now ? PETSC_FALSE : PETSC_TRUE),
              "KSPSetReusePreconditioner");
      });
}

double NewtonSolver::tolerance(SNES snes) const
{
  PetscReal atol = 0, rtol = 0, stol = 0;
  PetscInt max_it = 0, max_f = 0;
  check(SNESGetTolerances(snes, &atol, &rtol, &stol, &max_it, &max_f), "SNESGetTolerances");
  return newton_tolerance(atol, rtol, std::max(_fnorms.front(), _reference));
}

bool NewtonSolver::halfway(SNES snes) const
{
  const double start = _fnorms.front();
  return *std::min_element(_fnorms.begin(), _fnorms.end()) <= std::sqrt(start * tolerance(snes));
}

bool NewtonSolver::in_linear_tail(PetscInt iteration) const
{
  // _fnorms holds iterations 0 to `iteration` (the convergence test runs first)
  return !_policy.lagged() && iteration >= 2 && _fnorms.size() == std::size_t(iteration) + 1 &&
         solver::in_linear_tail(_fnorms, _tail_ratio);
}

// PETSc's test (-snes_atol, -snes_rtol, -snes_stol, -snes_max_it), and one
// more: ||F|| at the round-off floor of the residual (NonlinearProblem::
// residual_floor) has converged, whatever the tolerances ask. Below it ||F||
// is noise: a full Newton step no longer lowers it, the line search fails,
// and a step would be cut back for nothing (-snes_atol 1e-30). With
// set_stop_when_stalled, iterations that stall fail (NewtonHistory.h).
PetscErrorCode NewtonSolver::convergence_test(SNES snes, PetscInt it, PetscReal xnorm,
                                              PetscReal snorm, PetscReal fnorm,
                                              SNESConvergedReason* reason, void* ctx)
{
  return petsc::callback(
      [&]
      {
        check(SNESConvergedDefault(snes, it, xnorm, snorm, fnorm, reason, nullptr),
              "SNESConvergedDefault");
        auto* self = static_cast<NewtonSolver*>(ctx);
        if (it == 0) // ||F|| of each iteration of this solve (tail, stall)
          self->_fnorms.clear();
        self->_fnorms.resize(std::size_t(it) + 1);
        self->_fnorms[it] = fnorm;
        self->_stalled = false;
        // PETSc's relative and divergence tests are of ||F_0||; with a
        // prediction, of the larger reference (solve()): a prediction
        // within the tolerance takes no iteration (unless
        // -snes_force_iteration), and an iterate is not diverged while
        // within -snes_divergence_tolerance of the reference.
        if (self->_reference > self->_fnorms.front() && std::isfinite(fnorm))
        {
          PetscBool force = PETSC_FALSE;
          check(SNESGetForceIteration(snes, &force), "SNESGetForceIteration");
          PetscReal divtol = 0;
          check(SNESGetDivergenceTolerance(snes, &divtol), "SNESGetDivergenceTolerance");
          if (*reason == SNES_DIVERGED_DTOL && fnorm <= divtol * self->_reference)
            *reason = SNES_CONVERGED_ITERATING;
          if (*reason == SNES_CONVERGED_ITERATING && (it > 0 || !force) &&
              fnorm <= self->tolerance(snes))
            *reason = SNES_CONVERGED_FNORM_RELATIVE;
        }
        if (*reason > 0 || !std::isfinite(fnorm))
          return;
        Vec x;
        check(SNESGetSolution(snes, &x), "SNESGetSolution");
        if (fnorm <= self->_problem.residual_floor(x))
          *reason = SNES_CONVERGED_FNORM_ABS;
        else if (*reason == SNES_CONVERGED_ITERATING && self->_stop_when_stalled &&
                 stalled(self->_fnorms) && !self->halfway(snes))
        {
          self->_stalled = true;
          *reason = SNES_DIVERGED_DTOL; // reported as DIVERGED_NO_PROGRESS (attempt)
        }
      });
}

NewtonSolver::~NewtonSolver()
{
  release();
}

void NewtonSolver::release() noexcept
{
  petsc::check_nothrow(SNESDestroy(&_snes), "SNESDestroy");
  petsc::check_nothrow(MatDestroy(&_J), "MatDestroy");
  if (_P)
    petsc::check_nothrow(MatDestroy(&_P), "MatDestroy");
  petsc::check_nothrow(VecDestroy(&_F), "VecDestroy");
}

double NewtonSolver::time_linear_solve(Vec x)
{
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(x));
  // Owned, so that an error on the way (a failed factorisation, the
  // problem's) frees them, the factors too: a sweep goes on to its next
  // case. Owned outside the agreement below: destroying a MUMPS factor is
  // collective, so a process that failed agrees before it lets them go.
  Vec v;
  check(VecDuplicate(x, &v), "VecDuplicate");
  const Vector F(v);
  check(VecDuplicate(x, &v), "VecDuplicate");
  const Vector dx(v);
  KSP k;
  check(KSPCreate(comm, &k), "KSPCreate");
  const std::unique_ptr<_p_KSP, void (*)(KSP)> ksp(
      k, [](KSP p) { petsc::check_nothrow(KSPDestroy(&p), "KSPDestroy"); });
  // (A PETSc error on one process inside the solve, where the others wait
  // in its collectives, ends the run after abandon_after_s: mpi_errors.h.)
  return mpi::collectively<OptionError, SceneError>(
      comm,
      [&]
      {
        const std::string failed_law = "solver.time_linear_solve: an interface law failed at the "
                                       "first load step's start";
        mpi::throw_if_any(comm, !_problem.residual(x, F), failed_law);
        check(VecScale(F, -1.0), "VecScale");
        mpi::throw_if_any(comm, !_problem.jacobian(x, _J), failed_law);
        check(KSPSetOperators(k, _J, _J), "KSPSetOperators");
        check(KSPSetFromOptions(k), "KSPSetFromOptions");
        _problem.configure(k);
        MPI_Barrier(comm);
        const double t0 = MPI_Wtime();
        check(KSPSetUp(k), "KSPSetUp");
        if (const std::string why = factorization_failure(k); !why.empty())
          throw std::runtime_error("solver.time_linear_solve: the factorisation of the first "
                                   "load step's Jacobian failed (" +
                                   why + ")");
        check(KSPSolve(k, F, dx), "KSPSolve");
        MPI_Barrier(comm);
        const double t = MPI_Wtime() - t0;
        _problem.forget_trial_state();
        return t;
      });
}

SolveReport NewtonSolver::solve(Vec x, double reference)
{
  _reference = reference;
  _policy.check_constraints(_problem);
  if (_policy.lagged() && !_policy.has_P())
  {
    // The first solve of a run starts from the virgin interface state and
    // the constraints of the run (their dofs never change, only values):
    // the Jacobian at zero displacement is the elastic tangent.
    Vec v;
    check(VecDuplicate(x, &v), "VecDuplicate");
    const Vector zero(v); // freed if the Jacobian throws
    check(VecSet(zero, 0.0), "VecSet");
    _problem.jacobian(zero, _P);
    _policy.P_filled();
  }
  // The last converged tangent, if nothing evaluated another since (path
  // following on the same problem does) and the constraints are the same.
  _tangent_converged = _tangent_converged && !_policy.refresh_due() &&
                       _tangent_constraints == _problem.constraint_version() &&
                       _tangent_evaluation == _problem.tangent_evaluations();
  Vec copy;
  check(VecDuplicate(x, &copy), "VecDuplicate");
  const Vector start(copy); // destroyed on every way out
  check(VecCopy(x, start), "VecCopy");
  SolveReport r = attempt_from_tangents(x, start);
  if (!r.converged && _failed_on_stale_lu)
  {
    // GMRES failed on the LU of an earlier iterate: the same step again,
    // its first iteration on a fresh one (the failure queued it), before
    // the step loop cuts it.
    r = again(x, start, r);
  }
  if (r.converged || r.stalled || _fallback_line_search.empty())
    return r;
  // The same step again with the other line search, before the step loop
  // cuts it (set_fallback_line_search).
  SNESLineSearch search;
  check(SNESGetLineSearch(_snes, &search), "SNESGetLineSearch");
  SNESLineSearchType type;
  check(SNESLineSearchGetType(search, &type), "SNESLineSearchGetType");
  const std::string usual = type;
  check(SNESLineSearchSetType(search, _fallback_line_search.c_str()), "SNESLineSearchSetType");
  r = again(x, start, r);
  check(SNESLineSearchSetType(search, usual.c_str()), "SNESLineSearchSetType");
  return r;
}

SolveReport NewtonSolver::again(Vec x, Vec start, const SolveReport& failed)
{
  check(VecCopy(start, x), "VecCopy");
  _tangent_converged = false;
  SolveReport r = attempt(x);
  r.iterations += failed.iterations;
  return r;
}

SolveReport NewtonSolver::attempt_from_tangents(Vec x, Vec start)
{
  if (!(_previous_tangent && _tangent_converged))
    return attempt(x);
  // The first iteration takes the last converged tangent. Where it predicts
  // badly (a joint that switches between stick and slip under a stiff
  // penalty, a layer that stops softening) the solve may fail: then the same
  // step again from the tangent at its initial guess, before the step loop
  // cuts it (k = 1e6 N/mm^3, mu = 1, nodal quadrature, 1000 steps of the
  // stress matrix: 78 cuts and 7 519 Newton iterations without the retry).
  SolveReport r = attempt(x);
  if (!r.converged && !r.stalled)
    r = again(x, start, r);
  return r;
}

SolveReport NewtonSolver::attempt(Vec x)
{
  SolveReport r;
  // A factorisation that fails in a Newton iteration fails the solve, and
  // the step loop cuts the step back, as for any diverged solve: MUMPS and
  // PETSc's sparse LU record a failed reason (DIVERGED_LINEAR_SOLVE), a
  // dense LU (condensed systems, one process) raises a zero-pivot error.
  KSP ksp;
  check(SNESGetKSP(_snes, &ksp), "SNESGetKSP");
  PetscInt linear_before = 0, linear_after = 0;
  check(KSPGetTotalIterations(ksp, &linear_before), "KSPGetTotalIterations");
  _failed_on_stale_lu = false;
  const PetscErrorCode code = SNESSolve(_snes, nullptr, x);
  // Every Krylov iteration, those of a failed linear solve too.
  check(KSPGetTotalIterations(ksp, &linear_after), "KSPGetTotalIterations");
  _linear_iterations += linear_after - linear_before;
  if (zero_pivot_error(code, PetscObjectComm(reinterpret_cast<PetscObject>(_snes))) &&
      !petsc::callback_failed())
  {
    r.reason = "DIVERGED_LINEAR_SOLVE (zero pivot)";
    _tangent_converged = false;
    _policy.refresh();
    return r;
  }
  check(code, "SNESSolve");
  SNESConvergedReason reason;
  check(SNESGetConvergedReason(_snes, &reason), "SNESGetConvergedReason");
  PetscInt its;
  check(SNESGetIterationNumber(_snes, &its), "SNESGetIterationNumber");
  r.converged = reason > 0;
  _tangent_converged = r.converged;
  _tangent_constraints = _problem.constraint_version();
  _tangent_evaluation = _problem.tangent_evaluations();
  if (its > 0) // a solve with no iteration (a prediction within the tolerance) made none
  {
    // The last linear solve's iterations: the lagged preconditioner is
    // refreshed before the next solve if it slowed down (the Jacobian
    // callback counts the others).
    PetscInt linear_its = 0;
    check(KSPGetIterationNumber(ksp, &linear_its), "KSPGetIterationNumber");
    _policy.solved(linear_its);
  }
  r.iterations = int(its);
  r.stalled = _stalled;
  r.reason = _stalled ? "DIVERGED_NO_PROGRESS (|F| not halved in " +
                            std::to_string(stall_iterations) + " iterations)"
                      : SNESConvergedReasons[reason];
  if (r.converged)
    test_non_finite(x);
  if (r.converged && !finite(x))
  {
    // A finite residual norm does not vouch for every entry of x (a NaN
    // where no residual entry reads it): a failed solve, cut back.
    r.converged = _tangent_converged = false;
    r.reason = "DIVERGED_NONFINITE_SOLUTION (a displacement or jump is not a number)";
  }
  if (reason == SNES_DIVERGED_LINEAR_SOLVE)
  {
    const std::string why = factorization_failure(ksp);
    if (!why.empty())
      r.reason += " (" + why + ")";
    // Not a factorisation that failed: Krylov on an earlier iterate's LU.
    _failed_on_stale_lu = why.empty() && _policy.lagged() && !_factored_now;
  }
  if (!r.converged)
    _policy.refresh(); // a retry starts from a fresh factorisation
  return r;
}
} // namespace pushout::solver

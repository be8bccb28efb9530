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
//    about 1/20 of a factorisation here, so this saves most of them. A
//    Newton solve that fails as GMRES falls short on the LU of an earlier
//    iterate is tried again, its first iteration on a fresh LU, before the
//    step loop would cut the step (with -ksp_max_it 6 on a coarse corroded
//    slice with IMPL-EX cracks, 15 cuts instead of 26).
//
// The first iteration of a load step takes, by default, the tangent and the
// preconditioner of the last converged step as they are (the continuation
// of the path: an Euler predictor), not the tangent at the step's start.
// There the laws are at their committed state, where a sliding friction
// joint or an opening crack looks elastic (no increment yet): that tangent
// is a poor predictor, and so unlike the converged one that the lagged
// preconditioner is refactored in every step. Only the iterates change;
// the converged solution is the same (set_first_tangent).
#pragma once

#include "NonlinearProblem.h"
#include "PreconditionerPolicy.h"
#include <algorithm>
#include <petscsnes.h>
#include <string>
#include <vector>

namespace pushout::solver
{
struct SolveReport
{
  bool converged = false;
  int iterations = 0;
  std::string reason;   ///< PETSc's converged/diverged reason
  bool stalled = false; ///< failed as its iterates stalled (set_stop_when_stalled)
  bool loose = false;   ///< a stalled step ended at its best iterate (ArcLengthSolver::step)
};

class NewtonSolver
{
public:
  enum class Preconditioner
  {
    jacobian,
    lagged
  };

  /// What the concrete does within a load step, for the defaults of
  /// set_default_options.
  enum class Concrete
  {
    linear,       ///< no [cracking]
    cracks,       ///< cracks solved in every iteration (cracking.integration resolved to implicit)
    implex_cracks ///< cracks that hold their extrapolated damage (resolved to implex)
  };

  NewtonSolver(NonlinearProblem& problem, Preconditioner pc, int refactor_iterations = 10);
  ~NewtonSolver();
  NewtonSolver(const NewtonSolver&) = delete;
  NewtonSolver& operator=(const NewtonSolver&) = delete;

  /// Whether a solve's first iteration takes the last converged solve's
  /// tangent (true, the default) or the tangent at the initial guess. It
  /// takes the initial guess's after a failed solve, a restart or a change
  /// of the constrained dofs; and a solve that fails from the converged
  /// tangent is tried once more from the initial guess's.
  void set_first_tangent(bool converged) { _previous_tangent = converged; }

  /// Solves F(x) = 0 from the initial guess x (constraints already in x).
  /// `reference` [N]: where x is a prediction (extrapolated from the last
  /// steps), ||F|| at the step's start without it (the last converged state
  /// with this step's loads and constraints); Newton's relative test
  /// (-snes_rtol) and the inexact tolerances (set_inexact) are then relative
  /// to the larger of it and ||F_0||, so that a good prediction saves
  /// iterations instead of asking for a smaller ||F||. 0: ||F_0||.
  SolveReport solve(Vec x, double reference = 0);

  /// A solve that fails is tried once more from its initial guess with this
  /// PETSc line search type (SNESLineSearchType, e.g. "bt"); "" (the
  /// default): none. With cracks in the concrete neither l2 nor bt passes
  /// every step the other passes (docs/cracking.md, "Newton").
  void set_fallback_line_search(std::string type) { _fallback_line_search = std::move(type); }

  /// Keeps the factorisation at hand (no new Jacobian) for an iteration
  /// whose last two iterations each cut ||F|| by at least 1/`ratio`: in a
  /// linear tail, where the tangent is not exact anyway, a factorisation
  /// bought little. Concrete that cracks: a new crack's normal follows the
  /// strain and its tangent does not, so Newton's tails are linear (rates
  /// 0.05 to 0.25, docs/cracking.md "Newton"). 0 (the default): a new
  /// Jacobian in every iteration. Only for Preconditioner::jacobian.
  void set_tail_reuse(double ratio) { _tail_ratio = ratio; }

  /// Whether a solve fails as soon as its iterations stall (NewtonHistory.h:
  /// DIVERGED_NO_PROGRESS) rather than at -snes_max_it, unless |F| has come
  /// halfway to its tolerance in decades (there iterates that creep are at
  /// the floor of the crack band's own equilibria, and converge: the uniform
  /// ring at its peak crept from 7e-8 to 1e-8 N in 20 iterations). With
  /// cracking concrete, a step past a brittle event (the cover crack of the
  /// corroded demo, at x = 12 to 14 um) hovered at |F| = 0.2 to 0.3 N (from
  /// 150 N) through its three attempts (50 iterations from each tangent, 39
  /// with the fallback line search), then passed in halves. A stalled
  /// attempt is not tried again, from the tangent at the start or with the
  /// fallback line search: the step loop cuts the step at once. On the
  /// bench's case (docs/cracking.md, "Newton") the retries after a stall
  /// never converged (the same six cuts with and without them, the same
  /// curve to every digit) and took 163 of 868 iterations and 156 of 535
  /// factorisations. Off by default.
  void set_stop_when_stalled(bool stop) { _stop_when_stalled = stop; }

  /// Whether GMRES on a lagged LU stops where more accuracy cannot show in
  /// Newton's test (solver.inexact_newton): from a solve's second iteration
  /// on, at half the residual that the test still asks for (Kelley's
  /// safeguard), never below -ksp_rtol. The first iteration solves to
  /// -ksp_rtol, so that a step that is linear converges in one, unless a
  /// prediction made ||F_0|| smaller than solve()'s reference (then at what
  /// the test asks for, too). On the
  /// bench's corroded demo with IMPL-EX cracks: 1 688 back-solves instead of
  /// 2 103, the same Newton iterations, τ within 2e-6 of its value
  /// (docs/cracking-speed.md). Only with
  /// Preconditioner::lagged (elsewhere every iteration has its own LU),
  /// where GMRES measures the true residual (flexible GMRES on the LU in
  /// single precision, right-preconditioned GMRES on the LU in double; a
  /// preconditioned norm may be far from it), and without -snes_ksp_ew, which sets the tolerances
  /// itself. Off by default.
  void set_inexact(bool inexact) { _inexact = inexact && _policy.lagged(); }

  /// set_inexact's relative tolerance of a linear solve at ||F_k|| = Fk [N]
  /// when Newton's test asks for ||F|| <= `needed` [N] (tolerance()): half
  /// of that relative to Fk, between ksp_rtol and max(ksp_rtol, 0.1).
  static double inexact_rtol(double needed, double Fk, double ksp_rtol);
  /// The |F| [N] at which a solve that started at |F_0| = F0 [N] passes
  /// PETSc's test: max(snes_atol, snes_rtol F0).
  static double newton_tolerance(double snes_atol, double snes_rtol, double F0)
  {
    return std::max(snes_atol, snes_rtol * F0);
  }

  /// Times one linear solve J(x) dx = -F(x) with the solver configured for
  /// the Newton systems (a fresh KSP from the same options, the first
  /// factorisation included) [s]. Leaves x and the committed state alone.
  double time_linear_solve(Vec x);

  /// Sets PETSc's options database defaults for pushout (MUMPS LU, tight
  /// tolerances) where the user did not set them. Call before NewtonSolver.
  /// The LU is the solver (KSP preonly), or preconditions GMRES: lagged, or
  /// the LU of every Jacobian of implicit cracks when it is factored in
  /// single precision (`single_precision_lu`: solver.precision = "mixed";
  /// Equilibrium::configure). The line search backtracks (bt),
  /// or, if the concrete's cracks are solved in every iteration
  /// (Concrete::cracks), minimises |F|^2 along the Newton direction (l2):
  /// backtracking from a full step that cracks many points stalled on the
  /// crack band's kinks (docs/cracking.md, "Newton"). Newton and GMRES stop
  /// at implex_rtol instead of 1e-10 for IMPL-EX cracks.
  static void set_default_options(Preconditioner pc, Concrete concrete = Concrete::linear,
                                  bool single_precision_lu = false);

  /// The line search a failed solve is tried again with
  /// (set_fallback_line_search), for the line search set_default_options
  /// takes: with cracks solved in every iteration bt after l2; with IMPL-EX
  /// cracks l2 after bt (inside a snap of the centred cover a bt solve made
  /// |F| fall by 0.9 an iteration, 50 iterations at the smallest step, where
  /// l2 and full steps converge: docs/cracking.md, "IMPL-EX"); none without
  /// cracks.
  static const char* fallback_line_search(Concrete concrete)
  {
    return concrete == Concrete::cracks ? "bt" : concrete == Concrete::implex_cracks ? "l2" : "";
  }

  /// -snes_rtol and -ksp_rtol of IMPL-EX cracks: a step's error is of the
  /// order of cracking.implex_tolerance (2.5e-3 by default; 1e-2 when this
  /// was measured), and a Newton tolerance more than three decades below it
  /// does not show in the curve. On the
  /// bench's corroded demo (docs/cracking-speed.md) τ and p
  /// moved by 7e-7 and 4e-8 of their largest values against 1e-10, in 29
  /// instead of 64 factorisations and 71 s instead of 101 s. The implicit
  /// cracks keep 1e-10: at 1e-6 their non-smooth Newton stalled on the same
  /// bench (a corrosion step failed after 10 cuts).
  static constexpr const char* implex_rtol = "1e-6";

  /// Whether the Newton systems are factored (-pc_type lu, the default, or
  /// cholesky) rather than preconditioned iteratively (-pc_type gamg, ...).
  /// Reads PETSc's options database.
  static bool direct_factorization();

  /// Whether the user's PETSc options choose the linear solver
  /// (-ksp_type, -pc_type or -pc_factor_mat_solver_type, not ours:
  /// set_default_options), so that the run does not describe its own.
  static bool linear_solver_from_options();
  /// Whether set_default_options() makes the KSP GMRES (on the LU), else
  /// the LU alone (preonly).
  static bool gmres_by_default(Preconditioner pc, Concrete concrete, bool single_precision_lu);
  /// The value of the PETSc option `name` the user gave, "" if none (or if
  /// it holds a default of ours: set_default_options).
  static std::string user_option(const char* name);

private:
  void set_up(NonlinearProblem& problem); ///< the constructor's work
  void release() noexcept;                ///< destroys what set_up made

  NonlinearProblem& _problem;
  SNES _snes = nullptr;
  PreconditionerPolicy _policy;
  Mat _J = nullptr, _P = nullptr;
  Vec _F = nullptr;
  std::string _fallback_line_search; ///< set_fallback_line_search
  bool _previous_tangent = true;     ///< a step's first iteration takes the last converged tangent
  bool _tangent_converged = false;   ///< the last solve converged (its tangent is at hand)
  int _tangent_constraints = -1;     ///< the constraint version of that solve
  int _tangent_evaluation = -1;      ///< the problem's tangent count after it
  double _tail_ratio = 0;            ///< set_tail_reuse
  std::vector<double> _fnorms;       ///< ||F|| of each iteration of the current solve
  double _reference = 0;             ///< solve()'s reference of the current solve [N]
  bool _stop_when_stalled = false;   ///< set_stop_when_stalled
  bool _stalled = false;             ///< the current solve stalled
  /// The last Jacobian callback factored the preconditioner afresh (lagged:
  /// from that iterate's Jacobian), so a linear solve that failed after it
  /// did not fail for a stale LU.
  bool _factored_now = false;
  /// The last attempt failed in a linear solve on a lagged LU of an earlier
  /// iterate (solve() tries the step again on a fresh one).
  bool _failed_on_stale_lu = false;
  PetscReal _ksp_rtol = 1e-10;         ///< -ksp_rtol, the linear solves' floor
  bool _inexact = false;               ///< set_inexact
  std::int64_t _linear_iterations = 0; ///< linear_iterations()

public:
  /// Numeric factorisations so far (for the summary).
  int factorizations() const { return _policy.factorizations(); }
  /// Krylov iterations of the Newton systems so far (an application of the
  /// LU each; a direct solve counts one).
  std::int64_t linear_iterations() const { return _linear_iterations; }
  /// The next solve starts as the first solve of a run (a new run on the
  /// same set-up: the same iterates, bit for bit).
  void restart()
  {
    _policy.restart();
    _tangent_converged = false;
  }
  /// The next solve starts from the tangent at its initial guess (its
  /// committed state was reverted).
  void forget_tangent() { _tangent_converged = false; }

private:
  /// One SNES solve from x (solve() retries it once from the tangent at the
  /// initial guess when the last converged tangent's try failed).
  SolveReport attempt(Vec x);
  /// attempt(), from the last converged tangent if it is to be taken, then
  /// once more from the tangent at the initial guess `start` if that failed.
  SolveReport attempt_from_tangents(Vec x, Vec start);
  /// After the attempt `failed`: the same step again from `start`, from the
  /// tangent at it (and the fresh LU a failure queues), its iterations and
  /// `failed`'s counted.
  SolveReport again(Vec x, Vec start, const SolveReport& failed);
  /// newton_tolerance() of this solve with the tolerances of `snes`, of the
  /// larger of ||F_0|| and solve()'s reference.
  double tolerance(SNES snes) const;
  /// Whether the smallest |F| of this solve is halfway, in decades, from
  /// the first to the tolerance of `snes` (set_stop_when_stalled).
  bool halfway(SNES snes) const;
  /// Whether Newton's `iteration` keeps the factorisation (set_tail_reuse).
  bool in_linear_tail(PetscInt iteration) const;
  /// KSP pre-solve hook: the tolerance of this iteration's linear solve
  /// (set_inexact).
  static PetscErrorCode linear_tolerance(KSP ksp, Vec b, Vec x, void* ctx);
  static PetscErrorCode jacobian_callback(SNES snes, Vec x, Mat J, Mat P, void* ctx);
  static PetscErrorCode convergence_test(SNES snes, PetscInt it, PetscReal xnorm, PetscReal snorm,
                                         PetscReal fnorm, SNESConvergedReason* reason, void* ctx);
};

/// Whether every entry of x is finite (collective).
bool finite(Vec x);

} // namespace pushout::solver

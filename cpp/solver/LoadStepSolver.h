// The solver of one load step on the whole model's displacement x: Newton
// on the whole model, or on the interface jumps after condensing the linear
// bulk (Condensation.h), with x recovered after convergence. The
// condensation is built for the constrained dofs of the step and built
// again when they change (a thermal step with the tube top free, then the
// push). Path following works in the same space (PathFollower.h, through
// problem(), to_problem(), from_problem()).
//
// make() decides, from the scene's [solver] part and the number of processes,
// whether the bulk is condensed (Condensation::chosen) and says so in
// description() for the progress line.
#pragma once

#include "../scene/SceneParts.h"
#include "Condensation.h"
#include "NewtonSolver.h"
#include "Vector.h"
#include <memory>
#include <string>

namespace pushout::solver
{
class LoadStepSolver
{
public:
  /// `condense`: solve on the interface dofs (Condensation::possible must
  /// hold). `description`: what Newton runs on, for the progress line.
  LoadStepSolver(Equilibrium& eq, bool condense, NewtonSolver::Preconditioner pc,
                 int refactor_iterations, std::string description = "");

  /// The solver the scene's [solver] part asks for, condensed or not
  /// (solver.condensation, Condensation::chosen on this number of
  /// processes); sets PETSc's default Newton options for the preconditioner
  /// policy. Throws SceneError if solver.condensation = "on" is not possible.
  static std::unique_ptr<LoadStepSolver> make(Equilibrium& eq, const SolverPart& part);
  /// What make() and the solvers it makes would refuse of `part` and the
  /// user's PETSc options on `processes` processes for `concrete`, found
  /// before the model is built (so before a run touches its folder):
  /// solver.condensation = "on" where it is not possible (but for want of
  /// an interface), a -ksp_pc_side that the flexible GMRES of the
  /// single-precision LU has not. Throws SceneError.
  static void check_options(const SolverPart& part, NewtonSolver::Concrete concrete, int processes);
  /// The concrete's kind as the solvers take it: linear without cracks
  /// ([cracking] absent), else its cracks' integration (cracking.integration
  /// as resolved: `implex`). make() and the size guard both ask this.
  static NewtonSolver::Concrete concrete(bool cracks, bool implex)
  {
    using Concrete = NewtonSolver::Concrete;
    return !cracks ? Concrete::linear : implex ? Concrete::implex_cracks : Concrete::cracks;
  }
  /// The whole model's preconditioner policy that make() takes for
  /// `concrete`: solver.preconditioner, but the LU of every Jacobian for the
  /// implicit cracks.
  static NewtonSolver::Preconditioner preconditioner(const SolverPart& part,
                                                     NewtonSolver::Concrete concrete);
  /// Whether the whole model's LU is factored in single precision under
  /// GMRES (solver.precision = "mixed" where GMRES runs on the LU), unless
  /// the user's PETSc options chose another solver.
  static bool single_precision_lu(const SolverPart& part, NewtonSolver::Concrete concrete);

  /// What Newton runs on: "the N interface jumps (bulk condensed)" or "the
  /// whole model" (with " (not condensed: why)" when the choice was not the
  /// user's).
  const std::string& description() const { return _description; }

  /// Whether each step's first Newton iteration takes the last converged
  /// step's tangent (solver.first_tangent = "converged", the default; see
  /// NewtonSolver::set_first_tangent).
  void set_first_tangent(bool converged);
  bool first_tangent_converged() const { return _first_tangent_converged; }
  /// With cracking concrete: each solve is first made with no new cracks
  /// (BulkCracking::allow_new_cracks), and continued from its solution with
  /// them. For a step from the unloaded slice, whose first full Newton step
  /// cracks a great many points that the solution does not crack
  /// (StepLoop::initial_step); elsewhere it costs a few iterations more.
  void set_crack_free_predictor(bool on) { _crack_free_predictor = on; }
  bool crack_free_predictor() const { return _crack_free_predictor; }
  /// The next step starts from the tangent at its initial guess (the state
  /// of the last converged solve was reverted).
  void forget_tangent()
  {
    _whole.forget_tangent();
    if (_newton)
      _newton->forget_tangent();
  }

  /// Whether a change of solver (a condensation not accurate enough, the
  /// whole model instead) is said on stdout.
  void set_talk(bool talk) { _talk = talk; }

  /// Builds what the current constraints need before the first solve (the
  /// condensation, which takes a while on a large interface).
  void prepare() { update(); }
  ~LoadStepSolver();
  LoadStepSolver(const LoadStepSolver&) = delete;
  LoadStepSolver& operator=(const LoadStepSolver&) = delete;

  /// Solves the current load step from x (whole model, constraints in x).
  /// `unpredicted`: where x is a prediction (extrapolated from the last
  /// steps), the step's start without it, the last converged state with
  /// the constraints in it; Newton's relative tolerance is then relative to
  /// the residual there where that is the larger (NewtonSolver::solve's
  /// reference). Only on the whole model: the condensed system's residual
  /// lives on the jumps (no prediction is made for it: only cracking
  /// concrete extrapolates, and it is not condensed).
  SolveReport solve(Vec x, Vec unpredicted = nullptr);

  /// The problem the Newton systems are solved on, for the current
  /// constraints.
  NonlinearProblem& problem();
  /// x in the problem's space: x itself, or its interface entries (a vector
  /// owned by this object, valid until the next call).
  Vec to_problem(Vec x);
  /// After the problem's vector from to_problem() was solved: x from it
  /// (condensed: only its interface and constrained entries unless the
  /// bulk is needed).
  void from_problem(Vec x);
  /// Whether x must be whole after each solve (outputs of the bulk; the
  /// default) or only on the interface and constrained dofs.
  void set_bulk_needed(bool needed) { _bulk_needed = needed; }
  /// A new vector of the problem's space with the entries of the whole-model
  /// functional `a` (zero off the interface if condensed); the caller
  /// destroys it.
  Vec functional(Vec a);

  /// Times one linear solve of the whole model (NewtonSolver).
  double time_linear_solve(Vec x) { return _whole.time_linear_solve(x); }

  bool condensed() const { return _condense; }
  NewtonSolver::Preconditioner preconditioner() const { return _pc; }
  int refactor_iterations() const { return _refactor_iterations; }
  /// Size of the condensed system (0 if not condensed).
  std::int64_t condensed_size() const { return _condensation ? _condensation->size() : 0; }
  /// The relative asymmetry of the last condensed flexibility built (0 if
  /// none), kept where it was not trusted (Condensation::untrusted).
  double condensation_asymmetry() const { return _asymmetry; }
  /// Numeric factorisations so far (whole, condensed and J0 factors).
  int factorizations() const;
  /// Krylov iterations of the Newton systems so far (whole and condensed).
  std::int64_t linear_iterations() const;
  /// The next solve starts as the first solve of a run: its preconditioner
  /// and load directions afresh (a new run on the same set-up:
  /// driver/Run.h Simulation).
  void restart()
  {
    _bulk_needed = true;
    _whole.restart();
    if (_newton)
      _newton->restart();
    if (_condensation)
      _condensation->forget_loads();
  }

private:
  /// Builds the condensation again if the constrained dofs changed.
  void update();

  Equilibrium& _eq;
  bool _condense;
  NewtonSolver::Preconditioner _pc;
  int _refactor_iterations;
  bool _first_tangent_converged = true;
  bool _inexact = false; ///< solver.inexact_newton
  bool _crack_free_predictor = false;
  bool _single_precision = true;   ///< solver.precision = "mixed" (Condensation)
  bool _condense_required = false; ///< solver.condensation = "on"
  bool _talk = false;
  double _asymmetry = 0; ///< condensation_asymmetry()
  std::string _description;
  std::string _whole_linear; ///< ", GMRES on a lagged LU ...": the whole model's linear solver
  bool _bulk_needed = true;
  NewtonSolver _whole;
  /// The whole model's solve (set_crack_free_predictor).
  SolveReport solve_whole(Vec x, double reference);
  /// ||F|| at `unpredicted` on the whole model [N] (0 where a law failed
  /// there on any process: no reference).
  double residual_norm(Vec unpredicted);
  Vector _residual_work; ///< residual_norm's F
  std::unique_ptr<Condensation> _condensation;
  std::unique_ptr<NewtonSolver> _newton;       ///< on the condensation
  int _constraint_version = 0;                 ///< of the constraints it was built for
  Vec _x = nullptr;                            ///< interface entries of x
  std::int64_t _retired_linear_iterations = 0; ///< of condensations built before
  int _retired_factorizations = 0;             ///< of condensations built before
};
} // namespace pushout::solver

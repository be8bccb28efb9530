// The load steps of a run: step 0 (the thermal step or preload), the
// corrosion stage if the scene has one (specimen/Corrosion.h), then the push under
// displacement control (nominal steps, cut and grown back by Stepper.h),
// path following on the mean slip, or dissipation control (steps of the
// push or of the energy released, solver/PathFollower.h); each converged
// step recorded and committed, a failed one reverted and cut, a signal
// agreed on between tries (common/Interrupt.h).
//
// One class, its member functions in one file per control:
//   StepLoop.cpp            run(), step 0, and what the controls share
//                           (commit, revert, cut_back, stop_requested, the
//                           load factor path)
//   DisplacementControl.cpp nominal steps with cut-back, unloading to zero
//                           force (the search itself: ZeroForceSearch.h)
//   PathFollowing.cpp       path following on the mean axial slip
//   DissipationControl.cpp  dissipation control, and the joints' energy sums
//   CorrosionStage.cpp      the corrosion stage, by either control
// with StepLoopShared.h (constants and guards) and TestHooks.h.
#pragma once

#include "../output/Summary.h"
#include "../record/RunReport.h"
#include "../solver/LoadStepSolver.h"
#include "../solver/Vector.h"
#include "../specimen/Corrosion.h"
#include "../specimen/Scenario.h"
#include "StepRecorder.h"
#include "Stepper.h"
#include "TestHooks.h" // test_failure_at_setup, for driver/Run.cpp
#include <algorithm>
#include <functional>
#include <limits>
#include <string>

namespace pushout::stepping
{
class StepLoop
{
public:
  /// How the load steps are controlled (loading.control).
  enum class Control
  {
    displacement, ///< nominal steps of the load parameter
    arc_length,   ///< path following by the mean axial slip (specimen::Scenario::has_load_factor)
    dissipation   ///< steps of delta or of the energy released, as the step needs
  };

  /// `max_cuts`: halvings of a step before the run stops (loading.max_cuts);
  /// `dissipation_steps`: steps in which dissipation control releases the
  /// joints' fracture energy (loading.dissipation_steps).
  StepLoop(specimen::Scenario& scenario, specimen::Corrosion& corrosion,
           solver::Equilibrium& equilibrium, solver::LoadStepSolver& solver, StepRecorder& recorder,
           record::RunReport& report, int max_cuts, int dissipation_steps);

  /// Times one linear solve of the first load step (the thermal load
  /// included) from the unloaded state, into the summary.
  void time_linear_solve();

  /// Step 0, the corrosion stage, then the push. False if a step did not
  /// converge or a signal stopped the run (summary.message says which).
  bool run(Control control);

private:
  // --- StepLoop.cpp: step 0 and what the controls share ---

  bool initial_step();
  /// The push's start: the scenario's reference state and curve row 0
  /// (with the iterations and cuts of the step that reached it).
  void start_push(int iterations, int cuts = 0);

  /// The pseudo-time increment of the step, for every set of joints.
  void set_time_increment(double dt);
  /// Commits the converged state of a step (recorded before); after an
  /// IMPL-EX step in place of an implicit one (cut_back), the implicit
  /// cracks again.
  void commit();
  /// Back to the committed state.
  void revert();
  /// Words for an increment of a step, in a cut_back message.
  using Words = std::function<std::string(double increment)>;
  /// What cut_back did after a failed try.
  enum class Retry
  {
    cut,           ///< the increment cut: try the step again, smaller
    implex_rescue, ///< the same step once more, as one IMPL-EX step
    stop           ///< the run stops (the summary's message says why)
  };
  /// After a failed try (reverted): Retry::stop (with the summary's
  /// message) if the step cannot be cut again or a signal stops the run;
  /// otherwise halves the increment (until it is at most `factor` times
  /// what it was, or than `tried`, the failed try's increment where it was
  /// clipped short: Stepper::failed), counts the cut and says so
  /// (Retry::cut). `what` names the step, `size(increment)` words its size.
  /// The implicit cracks (cracking.implex_rescue): where Newton failed at
  /// the smallest step, of 2^-10 of a step or less, the same step once more
  /// as one IMPL-EX step (BulkCracking::set_implex_rescue,
  /// Retry::implex_rescue), which
  /// commit() ends; a rescue's try that fails is cut as any other, and
  /// stops the run at the smallest step.
  Retry cut_back(Stepper& stepper, int& cuts, const std::string& what, const std::string& reason,
                 const Words& size, double factor = 0.5,
                 double tried = std::numeric_limits<double>::infinity());
  /// Whether a signal asked to stop (agreed on by all processes); first an
  /// error of any process since the last agreement is thrown on all.
  bool stop_requested();
  /// The implicit cracks again if an IMPL-EX rescue is on
  /// (model::BulkCracking::set_implex_rescue; a stop, the run's end).
  void end_implex_rescue();
  /// run()'s stages.
  bool run_stages(Control control);

  /// What path following and dissipation control share: the push by its
  /// load factor lambda = delta [mm].
  struct LoadFactorPath
  {
    double lambda_final = 0;      ///< the final push [mm]
    double h_nominal = 0;         ///< a nominal step of it [mm]
    int max_steps = 0;            ///< steps before the run gives up
    std::string target = "push";  ///< the stage lambda runs (messages)
    std::string symbol = "delta"; ///< lambda's name (messages)
  };
  /// Sets the push's constraints (before a PathFollower takes the solver's
  /// problem) and `p`; false, with the summary's message naming `control`,
  /// if the final push is not positive.
  bool begin_load_factor_path(const std::string& control, LoadFactorPath& p);
  /// False, with the summary's message, once step k is past the limit.
  bool within_step_limit(const LoadFactorPath& p, int k, double lambda, const std::string& control);
  /// LoadFactorPath::max_steps of a stage of `nominal_steps`
  /// (path_step_limit of StepLoopShared.h with this model's IMPL-EX
  /// tolerance).
  int stage_step_limit(int nominal_steps) const;

  // --- DisplacementControl.cpp ---

  /// A stage of nominal steps s = 1, ..., steps of a load parameter s.
  struct Stage
  {
    std::string step_name;                          ///< "load step" (messages)
    int steps;                                      ///< nominal steps
    std::function<void(double s)> apply;            ///< constraints, loads, inputs at s
    std::function<double(double, double)> duration; ///< pseudo-time from s0 to s1
    /// Records a converged try of nominal step k that reached s (before its
    /// commit; a cut step has several).
    std::function<void(int iterations, int cuts, int k, double s)> record;
    /// Whether unloading segments may end where the scenario's load force
    /// falls to zero (Scenario::ends_at_zero_force): the push's stage.
    bool zero_force_ends = false;
    /// If set, the stage's load at s (x [mm] of corrosion, the push's
    /// prescribed displacement [mm]), and a try starts from the committed
    /// state plus the last converged step's increment scaled by the ratio of
    /// the loads' increments (a linear extrapolation; none where the load
    /// turns back): with cracking concrete (docs/cracking.md, "Newton").
    std::function<double(double s)> extrapolate_by = nullptr;
  };
  bool push_by_displacement();
  /// `load` as a Stage's extrapolate_by where the concrete cracks (Newton
  /// converges linearly there, and a good start saves iterations), else none.
  std::function<double(double)> extrapolation(std::function<double(double)> load) const;
  /// The trial state from the committed one plus `ratio` times the last
  /// committed step's increment; nothing unless ratio > 0. Whether it
  /// predicted.
  bool extrapolate(double ratio);
  /// A step whose loads are set, solved from the committed state plus
  /// `ratio` times the last committed step's increment (extrapolate), with
  /// Newton's relative test of the start without the prediction
  /// (LoadStepSolver::solve), or from the committed state if ratio <= 0.
  solver::SolveReport solve_predicted(double ratio);
  /// A converged try of the implicit cracks made to fail, where the test
  /// hook PUSHOUT_TEST_FAIL_IMPLICIT_ROW asks it (TestHooks.h).
  void test_fail_implicit_try(solver::SolveReport& rep) const;
  /// IMPL-EX cracks (model::BulkCracking::set_extrapolation) extrapolate
  /// their history by `ratio` in the next try (0: none).
  void set_crack_extrapolation(double ratio);
  /// What check_step_error found.
  struct StepErrorCheck
  {
    /// the step's error over its tolerance (BulkCracking::step_tolerance; 0:
    /// not checked)
    double ratio = 0;
    bool jump = false; ///< taken above the tolerance: no smaller step meets it
    double error = 0;  ///< the step's error (BulkCracking::step_error)
    std::string said;  ///< a jump's progress line, said when it is committed
    /// the implicit cracks' error read at the scene's steps, not held
    /// (BulkCracking::step_error_measured_only): never a cut
    bool measured_only = false;
    /// Whether the next step may grow: the step error is first order in
    /// the step, so one above half the tolerance would miss it at twice the
    /// increment (a jump: smaller steps did not help there).
    bool may_grow() const { return ratio <= 0.5 || jump; }
    /// The fraction of itself a try that missed is cut to: one that should
    /// meet the tolerance (0.8 of it), in halves at least.
    double cut_factor() const { return ratio > 1 ? std::min(0.5, 0.8 / ratio) : 0.5; }
  };
  /// IMPL-EX cracks, or the implicit cracks with cracking.implicit_tolerance
  /// (BulkCracking::step_tolerance; without one, and without a viscosity,
  /// the error is read, never held: StepErrorCheck::measured_only, for
  /// summary.json and note_unheld_step_error): the error of a converged step of
  /// `increment` (of the stage's parameter) against its tolerance; a step
  /// that misses it fails
  /// (`rep`, its reason), to be cut, unless it is a jump: a smaller try
  /// than the last that missed did not cut the error, or `stepper` cannot
  /// cut it (right after a jump, or where its smallest step is 2^-10 of a
  /// nominal one or less; the implicit cracks' from 2^-6 of one on). A step
  /// whose crack band update failed at a point
  /// fails. `why_taken`: what the progress line says of a jump (null: the
  /// cracks snap back under the load's control).
  StepErrorCheck check_step_error(solver::SolveReport& rep, double increment,
                                  const Stepper& stepper, const char* why_taken = nullptr);
  /// IMPL-EX cracks: whether the crack band's own update at a converged
  /// step's strain worked at every point (what commit() keeps; else `rep`
  /// fails, its reason said), for a step taken without check_step_error (one
  /// found by its force, zero_force_step). True without IMPL-EX cracks.
  bool crack_band_updated(solver::SolveReport& rep);
  /// The crack band's own update at a converged step's strain (IMPL-EX's,
  /// or an IMPL-EX rescue's) with its error and the points where it failed:
  /// those points, one more if a test hook asks (TestHooks.h); a rescue's
  /// error kept for commit() to count.
  std::int64_t band_update_failures(double error, std::int64_t failed_points);
  /// summary.json's step error readings (implex_error_max and implex_jumps,
  /// or the implicit_ ones), and a jump's progress line: a checked step
  /// that is committed (a try may still be reverted after its check).
  void count_step_error(const StepErrorCheck& c, const std::string& step);
  /// The implicit cracks whose steps were not held to their error: a note
  /// (summary.json notes, and said) where it went above IMPL-EX's
  /// tolerance, with the key that holds it. At the end of a run that
  /// completed.
  void note_unheld_step_error();
  /// A new stage (or a change between steps of energy and of the load):
  /// the last missed error and jump are another parameter's.
  void forget_step_error_misses();
  /// Nominal steps, each tried whole and cut in halves when Newton fails.
  bool nominal_steps(const Stage& stage);
  /// After a converged try of step k from the committed state at s0 (force
  /// P0 >= 0) to s1 (P1 < 0), reverted: the load parameter s where the
  /// force is zero (within `tol` [N]), into s, its state recorded and
  /// committed. Each try is one step from s0. False (with the summary's
  /// message) if a try did not converge or the search did not end.
  bool zero_force_step(const Stage& stage, int k, int cuts, double s0, double P0, double s1,
                       double P1, double tol, double& s);

  // --- PathFollowing.cpp ---

  bool path_following();
  /// The steps of path following, one member function per part of a step.
  class PathSteps;
  /// A displacement-controlled step of the load factor (pseudo-time: its
  /// change), IMPL-EX cracks extrapolated by `extrapolation`
  /// (set_crack_extrapolation).
  solver::SolveReport load_factor_step(double lambda_from, double lambda_to, double extrapolation);

  // --- DissipationControl.cpp ---

  /// What dissipation control needs of a stage: its load factor lambda
  /// [mm] (the push delta, the corrosion depth x), how it is set and what
  /// works on it.
  struct DissipationStage
  {
    std::string step_name;                ///< "load step", "corrosion step" (messages)
    std::string increment_words;          ///< "a push of" (messages, in mm)
    LoadFactorPath path;                  ///< from 0 to path.lambda_final
    std::function<void(double)> set_load; ///< constraints, loads, inputs at lambda
    double load_difference = 0;           ///< PathFollower::set_load_difference [mm]
    double time_per_lambda = 1;           ///< pseudo-time of a unit of lambda
    Vec control = nullptr;                ///< a mean jump that grows with lambda [mm]
    std::function<double()> force;        ///< that works on lambda [N]
    std::function<void(int iterations, int cuts, int k, double lambda)> record;
    std::function<bool()> without_softening; ///< the stage's run if nothing softens
  };
  /// Dissipation control (loading.control = "dissipation" or "auto") of
  /// the push.
  bool push_by_dissipation();
  /// Dissipation control of a stage: hands its steps to DissipationSteps.
  bool by_dissipation(const DissipationStage& stage);
  /// The steps of one stage under dissipation control, one member function
  /// per part of a step.
  class DissipationSteps;

  // --- CorrosionStage.cpp ---

  /// The corrosion stage: steps of the corrosion depth, constraints of step 0.
  bool corrode();
  /// The corrosion stage under dissipation control.
  bool corrode_by_dissipation();
  /// Records converged corrosion step k at stage parameter s (before its
  /// commit): corrosion.csv, the summary, and at the end of the stage the
  /// push's start. `numbered`: the progress line shows k of the stage's
  /// nominal steps.
  void record_corrosion(int iterations, int cuts, int k, double s, bool numbered);

  specimen::Scenario& _scenario;
  specimen::Corrosion& _corrosion;
  solver::Equilibrium& _equilibrium;
  solver::LoadStepSolver& _solver;
  StepRecorder& _recorder;
  record::RunReport& _report;
  output::Summary& _summary;
  int _max_cuts;
  int _dissipation_steps;
  MPI_Comm _comm;                  ///< the run's processes
  solver::Vector _x, _x_committed; ///< whole-model displacement [mm]: trial and committed
  solver::Vector _x_before;        ///< the committed one before the last commit [mm]
  solver::Vector _x_unpredicted;   ///< solve_predicted's start without the prediction [mm]
  /// The cracks' step error of the last try that missed its tolerance (0
  /// after a step taken; check_step_error)
  double _error_missed = 0;
  double _error_missed_increment = 0; ///< that try's increment of its stage's parameter
  bool _error_jumped = false;         ///< the last committed step was taken above the tolerance
  /// The IMPL-EX error of the last try that stood in for an implicit
  /// cracks' step (check_step_error; cracking.implex_rescue) [-]
  double _rescue_error = 0;
  /// The implicit cracks' steps whose error was read and not held
  /// (StepErrorCheck::measured_only), and those of them above
  /// cracking.implex_tolerance (note_unheld_step_error).
  int _unheld_steps = 0, _unheld_steps_above = 0;
  /// The stage the loop is in, as summary.json's stopped_in says it when a
  /// signal stops the run: "step 0", "corrosion steps" or "load steps".
  const char* _stage = "step 0";
  /// A step that fails under displacement control may be a snap-back: the
  /// joints or cracks soften. Its failure message says what passes one:
  /// loading.control = "auto" on a monotonic push, a damage viscosity on a
  /// push_path (which only displacement control runs).
  bool _may_snap_back = false;
  /// Whether the joints or the concrete's cracks soften (they release
  /// energy; DissipationControl.cpp). Collective.
  bool softens();
};
} // namespace pushout::stepping

// What the files of the step loop (StepLoop.cpp and one file per control)
// share beyond StepLoop.h: the stepping constants more than one control
// uses, the words of cut_back's messages, and guards of the solver's state.
// Internal to cpp/stepping/.
#pragma once

#include "../model/Model.h"
#include "../output/Summary.h"
#include "../solver/LoadStepSolver.h"
#include "../solver/PathFollower.h"
#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <string>

namespace pushout::stepping::detail
{
/// A try that converged in at most this many Newton iterations is easy;
/// two easy tries in a row double the increment again (Stepper.h).
constexpr int easy_iterations = 4;
/// The same for the steps of the bordered system (arc length, and the energy
/// steps of dissipation control): their Newton iterations close the control
/// equation too (and energy steps start from the committed state's tangent,
/// StartTangent), so an easy one takes a few more (arc length on brittle
/// adhesion: 5 per step from the last equilibrium; from the secant
/// prediction, 1 to 3, and 4 to 5 at the peak). With 4, a step cut once
/// never grew back.
constexpr int easy_bordered_iterations = 6;
/// What concrete that cracks adds to an easy try: its Newton converges
/// linearly (a new crack's normal follows the strain, and its tangent does
/// not: tails at rates 0.05 to 0.25, docs/cracking.md "Newton"), so even a
/// small step takes about ten iterations. With 4, the corroded demo with
/// [cracking] cut one step twice and took every later step in four tries
/// of 8 to 14 iterations each.
constexpr int cracking_tail_iterations = 10;
/// easy_iterations, or easy_bordered_iterations if `bordered`, for `model`.
inline int easy_tries(const model::Model& model, bool bordered = false)
{
  return (bordered ? easy_bordered_iterations : easy_iterations) +
         (model.bulk_cracking() ? cracking_tail_iterations : 0);
}
/// IMPL-EX cracks under dissipation control and arc length: the largest
/// ratio by which a step extrapolates the cracks' growth in the last
/// committed step, as a step grows at most twice its last (Stepper.h). An
/// energy step after a step of lambda that released little, a whole step of
/// lambda after a short one (a hand-over to energy steps and back), or the
/// push's last step after a short one, would take a large ratio, and the
/// extrapolated cracks would be far from the step's own.
constexpr double max_extrapolation = 2.0;
/// The ratio by which a step of `increment` extrapolates the cracks' growth
/// in the last committed step of `last` (of the same parameter): at most
/// max_extrapolation; 0 if the last did not move it forwards.
inline double extrapolation_ratio(double increment, double last)
{
  return last > 0 ? std::min(increment / last, max_extrapolation) : 0.0;
}
/// The largest step (of a nominal one) that, being the smallest
/// loading.max_cuts allows, IMPL-EX takes as a jump without a smaller try
/// to compare with: the default max_cuts's 2^-10. A larger smallest step
/// (max_cuts < 10) may miss only because it is large. Also the largest
/// that an IMPL-EX step takes in place of an implicit cracks' step that
/// Newton did not pass (StepLoop::cut_back, cracking.implex_rescue).
constexpr double jump_smallest_step = 1.0 / 1024;
/// The load parameter reaches a nominal step within this tolerance.
constexpr double step_tolerance = 1e-12;
/// Path following: snap-back makes the path longer than the final push, so
/// a run whose path never reaches it stops after path_steps_per_step x the
/// nominal steps + path_steps_extra (path_step_limit).
constexpr int path_steps_per_step = 20;
constexpr int path_steps_extra = 100;
/// The IMPL-EX tolerance for which those limits were set (the default
/// until docs/cracking.md "Accuracy and the tolerance" made it 0.0025).
constexpr double path_steps_implex_tolerance = 0.01;

/// The steps a path-following or dissipation-controlled stage of
/// `nominal_steps` may take before it gives up. IMPL-EX's error is first
/// order in the step, so a tolerance k times below
/// path_steps_implex_tolerance asks for k times the steps where the
/// cracks grow: the limit grows by k (`step_tolerance`, the cracks'
/// model::BulkCracking::step_tolerance: IMPL-EX's or the implicit cracks';
/// 0: none). Under dissipation control the centred tube's corrosion stage
/// (12 / 4, beta 3, seed 1, x to 50 um in 20 steps) took 243 steps at
/// 0.01 and ran into the limit of 500 at 0.0025.
inline int path_step_limit(int nominal_steps, double step_tolerance)
{
  const double k = step_tolerance > 0 && step_tolerance < path_steps_implex_tolerance
                       ? std::ceil(path_steps_implex_tolerance / step_tolerance)
                       : 1.0;
  return int(k * (path_steps_per_step * nominal_steps + path_steps_extra));
}

/// Words for an increment of a step in `scale` units (cut_back's messages):
/// "a push of 0.025 mm".
inline std::function<std::string(double)> sized(std::string what, double scale, std::string unit)
{
  return [=](double increment)
  {
    std::ostringstream s;
    s << what << " " << increment * scale << " " << unit;
    return s.str();
  };
}

/// Where a step that no cut passed stopped (failure_hint).
struct FailureCase
{
  /// How the concrete's cracks were integrated, as far as the hint goes.
  enum class Cracks
  {
    other,            ///< none, or IMPL-EX's
    implicit,         ///< implicit, at the scene's steps (cracking.implicit_tolerance = 0)
    implicit_held,    ///< implicit, held to cracking.implicit_tolerance > 0
    implicit_viscous, ///< implicit with cracking.viscosity > 0
  };
  /// The implicit cracks without a viscosity: the IMPL-EX step that may
  /// stand in for one that no cut passed (cracking.implex_rescue).
  enum class Rescue
  {
    none,     ///< not the implicit cracks' case
    failed,   ///< tried in the failed step's place, and failed too
    not_tried ///< none tried: cracking.implex_rescue = false, or loading.max_cuts < 10
  };
  Cracks cracks = Cracks::other;
  Rescue rescue = Rescue::none;
  bool may_snap_back = false; ///< the structure may snap back under displacement control
  bool monotonic = true;      ///< a monotonic push (no loading.push_path)
};

/// What cut_back adds to the message of a step that no cut passed where
/// Newton failed (an IMPL-EX miss says what to change itself,
/// check_step_error): with implicit cracks in the concrete, IMPL-EX, which
/// passes the steps where their Newton cycles (docs/cracking.md, "Still to
/// come" 3: cracks on the kink between loading and unloading; IMPL-EX has
/// no kink in a step), or smaller steps where the cracks need them: their
/// steps held to their error (cracking.implicit_tolerance, unless held
/// already), or the run again with four times the steps (coarse steps can
/// reach a state where several cracks compete and no cut passes; the
/// corroded study's stopped runs passed both ways); with a viscosity, which
/// neither IMPL-EX nor the step error takes, the steps alone. Else, where
/// the structure may snap back under displacement control, the control
/// that follows it: dissipation control on a monotonic push, a damage
/// viscosity on a push path. Where one IMPL-EX step in the smallest step's
/// place failed too (cracking.implex_rescue), the steps alone; where none
/// was tried, also the rescue. "" if none applies.
inline std::string failure_hint(const FailureCase& c)
{
  const std::string more_steps = "run again with four times the steps, corrosion.steps and "
                                 "loading.steps";
  using Cracks = FailureCase::Cracks;
  using Rescue = FailureCase::Rescue;
  if (c.cracks == Cracks::implicit_viscous)
    return " (the implicit cracks' Newton can cycle where cracks turn between loading and "
           "unloading: " +
           more_steps + " together; docs/cracking.md, \"Newton\", on a damage viscosity)";
  if (c.cracks != Cracks::other && c.rescue == Rescue::failed)
    return " (the implicit cracks' Newton can cycle where cracks turn between loading and "
           "unloading, and the smallest step failed as one IMPL-EX step too: " +
           more_steps + "; docs/cracking.md, \"The IMPL-EX rescue\")";
  if (c.cracks != Cracks::other)
    return std::string(" (the implicit cracks' Newton can cycle where cracks turn between "
                       "loading and unloading; IMPL-EX cracks pass such steps: "
                       "cracking.integration = \"implex\", which the default \"auto\" takes "
                       "without a viscosity; or ") +
           (c.cracks == Cracks::implicit_held ? ""
                                              : "hold the implicit cracks' steps to their error, "
                                                "cracking.implicit_tolerance = 0.0025, or ") +
           (c.rescue == Rescue::not_tried
                ? "let one IMPL-EX step take a step that no cut passes, "
                  "cracking.implex_rescue = true with loading.max_cuts >= 10, "
                  "or "
                : "") +
           more_steps + "; docs/cracking.md, \"IMPL-EX\" and \"The implicit cracks' step error\")";
  if (c.may_snap_back && c.monotonic)
    return " (where the structure snaps back, loading.control = \"auto\" follows it: "
           "docs/numerics.md, \"Dissipation control\")";
  if (c.may_snap_back) // a push_path: only displacement control runs it
    return " (where the structure snaps back on a push path, a damage viscosity lets "
           "displacement control pass it: a softening layer's eta, or cracking.viscosity with "
           "implicit cracks; docs/numerics.md, \"Viscous regularisation\")";
  return "";
}

/// Adds a path follower's factorisations and linear iterations to the
/// summary on every way out of a loop that uses it.
struct SolverCounts
{
  output::Summary& summary;
  const solver::PathFollower& path;
  ~SolverCounts()
  {
    summary.factorizations += path.factorizations();
    summary.linear_iterations += path.linear_iterations();
  }
};

/// While it lives, each Newton solve starts from the tangent at its initial
/// guess (solver.first_tangent = "current").
struct StartTangent
{
  solver::LoadStepSolver& solver;
  const bool converged = solver.first_tangent_converged();
  explicit StartTangent(solver::LoadStepSolver& s) : solver(s) { solver.set_first_tangent(false); }
  ~StartTangent() { solver.set_first_tangent(converged); }
  StartTangent(const StartTangent&) = delete;
  StartTangent& operator=(const StartTangent&) = delete;
};
/// Solves with the crack-free predictor (LoadStepSolver::
/// set_crack_free_predictor) while it lives.
struct CrackFreePredictor
{
  solver::LoadStepSolver& solver;
  const bool was = solver.crack_free_predictor();
  explicit CrackFreePredictor(solver::LoadStepSolver& s) : solver(s)
  {
    solver.set_crack_free_predictor(true);
  }
  ~CrackFreePredictor() { solver.set_crack_free_predictor(was); }
  CrackFreePredictor(const CrackFreePredictor&) = delete;
  CrackFreePredictor& operator=(const CrackFreePredictor&) = delete;
};
} // namespace pushout::stepping::detail

// Test hooks, not scene keys: environment variables that make one process
// fail, or a step slow, where the end-to-end tests need it
// (tests/e2e/test_error_on_one_process_ends_all.py,
// tests/e2e/test_signals_under_mpirun_recorded.py). Unset, they do nothing.
//
// With PUSHOUT_TEST_FAIL_RANK=r and PUSHOUT_TEST_FAIL_AT=`at`, process r
// alone throws, as an error found on one process only would: "setup" at
// the end of the set-up (driver/Run.cpp), "setup_collective" in it where
// the others next wait in a collective, "step" after two load steps,
// "collective" there too but where the others next wait in a collective
// that is no agreement (common/mpi_errors.h: the run ends with MPI_Abort
// after abandon_after_s). With PUSHOUT_TEST_SLOW_STEP_S=t, from the third
// load step on, each step spends t seconds without looking at signals, as
// a long factorisation does (the tests of a stop that cannot wait for the
// step). With PUSHOUT_TEST_NO_PREDICTION_REFERENCE set, Newton's relative
// test of a predicted step is of the prediction's own residual
// (tests/e2e/test_solver_paths_give_same_curve.py); with
// PUSHOUT_TEST_NO_STEP_PREDICTION set, a path-following step, and a step
// of the load under dissipation control, starts from the last equilibrium
// (tests/e2e/test_arc_length_follows_snap_back.py,
// tests/e2e/test_implex_tends_to_implicit.py); with
// PUSHOUT_TEST_FAIL_TO_FINAL=n, the first n converged path-following tries
// that end at the final delta are taken as failed (the fallback of steps of
// delta, tests/e2e/test_arc_length_follows_snap_back.py); with
// PUSHOUT_TEST_FAIL_CRACK_BAND_UPDATE set, the IMPL-EX crack band's update
// of every try at the zero force of an unloading fails at one point more
// than it did (tests/e2e/test_push_path_unloads_and_reloads.py); with
// PUSHOUT_TEST_ENERGY_OVERSHOOTS set, every energy step overshoots and the
// steps of the load that replace it fail
// (tests/e2e/test_dissipation_control_passes_snap_back.py).
#pragma once

#include <mpi.h>

namespace pushout::stepping
{
/// PUSHOUT_TEST_FAIL_AT=setup: process PUSHOUT_TEST_FAIL_RANK alone throws
/// at the end of the set-up.
void test_failure_at_setup(MPI_Comm comm);

/// PUSHOUT_TEST_FAIL_AT=setup_collective: process PUSHOUT_TEST_FAIL_RANK
/// alone throws in the set-up, before the collectives of the model's
/// matrices (solver::Equilibrium), which the others go on into.
void test_failure_in_setup(MPI_Comm comm);

/// Before the agreement between tries (StepLoop::stop_requested), after
/// `steps` load steps: the slow step (PUSHOUT_TEST_SLOW_STEP_S), and
/// PUSHOUT_TEST_FAIL_AT=step.
void test_hooks_before_agreement(int steps, MPI_Comm comm);

/// After that agreement: PUSHOUT_TEST_FAIL_AT=collective.
void test_hooks_after_agreement(int steps, MPI_Comm comm);

/// PUSHOUT_TEST_NO_PREDICTION_REFERENCE: a predicted step is solved
/// without the residual of its unpredicted start (LoadStepSolver::solve).
bool test_no_prediction_reference();

/// PUSHOUT_TEST_NO_STEP_PREDICTION: a path-following step, and a step of
/// the load under dissipation control, starts from the last equilibrium,
/// not from the last step's increment extrapolated
/// (StepLoop::path_following, StepLoop::DissipationSteps::lambda_step).
bool test_no_step_prediction();

/// PUSHOUT_TEST_FAIL_TO_FINAL=n: true for the first n calls, each for a
/// converged path-following try that ends at the final delta, which is then
/// taken as failed (StepLoop::path_following); n in the whole process (a
/// sweep's first cases only).
bool test_fail_step_to_final();

/// PUSHOUT_TEST_FAIL_CRACK_BAND_UPDATE: the IMPL-EX crack band's update at
/// a zero-force try's strain, or at an IMPL-EX step's in place of an
/// implicit one (cracking.implex_rescue), fails at one point more than it
/// did (StepLoop::crack_band_updated, StepLoop::check_step_error; the same
/// on every process).
bool test_fail_crack_band_update();

/// PUSHOUT_TEST_FAIL_IMPLICIT_ROW=n: every try of the implicit cracks (not
/// an IMPL-EX rescue) after n committed steps (corrosion.csv and curve.csv
/// rows after step 0, `rows`) fails as if Newton had, so that no cut passes
/// it (StepLoop::test_fail_implicit_try, after a step of the load, of
/// energy or of path following; the same on every process).
bool test_fail_implicit_row(int rows);

/// PUSHOUT_TEST_ENERGY_OVERSHOOTS: under dissipation control every
/// converged energy step is taken as one that overshot (more than a step
/// of the load), and every step of the load that replaces it fails as if
/// Newton had (StepLoop::DissipationSteps::try_step; the same on every
/// process): the hand-backs between the two kinds must end.
bool test_energy_overshoots();
} // namespace pushout::stepping

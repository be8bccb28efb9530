// `pushout fit`: the values of chosen scene keys (law parameters, loads)
// that make the model's push-out curve match a measured one, by least
// squares with PETSc TAO (Gauss-Newton as its bounded Newton line search,
// TAOBNLS, with a forward-difference Jacobian), and how well each value is
// determined.
//
//   residual r_i = tau_model(delta_i) - tau_data_i, i = 1..m (MPa)
//
// at the data's delta, the model's curve (pushed to the data's largest
// delta in loading.steps steps) interpolated linearly between its rows.
// The free values p_j are scaled by their start values (TAO sees p_j /
// p0_j, so that one trust region suits all). At the optimum,
//   s^2 = |r|^2 / (m - n),  cov = s^2 (J^T J)^-1,
// the standard errors sqrt(cov_jj) and the correlations cov_jk /
// (se_j se_k), J the forward-difference Jacobian there (in the keys' units).
//
// Every run of the fit is a run_case (driver/Run.h) on its group's reused set-up:
// the Jacobian's n runs spread over the groups of --ranks-per-case
// processes (MPI_Comm_split, as pushout sweep), each process driving the
// same TAO on the same numbers.
//
// DIR/fit.json (parameters, standard_errors, correlation, rms_MPa,
// evaluations, converged, ...), DIR/fit.csv (data and fitted tau at the
// data's delta), DIR/scene.toml (the fitted scene, rerunnable), DIR/best/
// (its run), DIR/fit.png.
//
// Fit.cpp holds the set-up and the steps; MeasuredCurve.h the data,
// FitEvaluator.h the runs, TaoFit.h the TAO solver, FitStatistics.h the
// standard errors and correlations, FitReport.h what is written.
#pragma once

#include "ManyRuns.h"
#include "MeasuredCurve.h"
#include <filesystem>
#include <string>
#include <vector>

namespace pushout::study
{
struct FitOptions : ManyRunsOptions
{
  std::filesystem::path data;      ///< measured.csv: delta_mm, tau_MPa
  std::vector<std::string> free;   ///< --free keys
  std::vector<std::string> bounds; ///< --bounds key=lo:hi
};

/// Runs the fit on MPI_COMM_WORLD; returns the exit code (0: converged; 3:
/// TAO did not converge or the runs failed; 2: bad input). Collective.
int fit(const FitOptions& options);
} // namespace pushout::study

// What a finished fit leaves (Fit.h): DIR/fit.json (the values, their
// standard errors and correlations, the rms, how the fit went), DIR/scene.toml
// (the fitted scene, rerunnable), DIR/fit.csv (the data and the fitted tau at
// the data's delta), DIR/fit.png, and its closing lines.
#pragma once

#include "Fit.h"
#include "FitStatistics.h"
#include "FreeValue.h"
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace pushout::study
{
/// What a finished fit found and how it went.
struct FitOutcome
{
  std::vector<double> x;         ///< the fitted values, scaled (value / scale)
  std::vector<double> r;         ///< the residuals there [MPa]
  FitStatistics statistics;      ///< at x
  std::vector<std::string> sets; ///< the --set overrides of the fitted scene
  int evaluations = 0;           ///< runs made
  int failed_runs = 0;           ///< runs that did not converge or ended with an error
  int refused_runs = 0;          ///< runs at values the scene refused (counted as a misfit)
  int iterations = 0;            ///< TAO's
  double relative_offset = NAN;  ///< at x (FitStatistics.h)
  bool converged = false;        ///< TAO converged, and every run did
  std::string reason;            ///< why TAO stopped (PETSc's name)
  std::string failure;           ///< why a run failed ("" if none did)
  std::string refusal;           ///< why the scene refused a run ("" if none)
  std::string best_failure;      ///< how the fitted run (best/) failed ("" if it converged)
  bool refusal_by_size = false;  ///< `refusal` is the size guard's (the scene refused none)
  double wall_s = 0;             ///< the fit's wall time [s]
};

/// Why the fit did not converge, and where to look (the error's words,
/// less "pushout: error: "): TAO's reason, the failed runs' and the refused
/// runs' count, one of their reasons and what to do about them.
std::string not_converged_message(const FitOutcome& fit, const std::filesystem::path& fit_json);

/// Writes the fit's files into opt.out, says what is wrong on stderr (its
/// warnings, no convergence) and, if `talk`, the fitted values on stdout.
/// Rank 0 only. Returns the exit code: 0 if converged, 3 if not, 1 if a file
/// could not be written.
int write_fit(const FitOptions& opt, const MeasuredCurve& data, const std::vector<Free>& free,
              const FitOutcome& fit, bool talk);
} // namespace pushout::study

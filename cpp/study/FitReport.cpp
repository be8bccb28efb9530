// What a finished fit leaves (FitReport.h): fit.json, scene.toml, fit.csv,
// fit.png and its closing lines.
#include "FitReport.h"
#include "../common/exit_codes.h"
#include "../output/OutputFiles.h"
#include "../output/plot.h"
#include "../scene/Scene.h"
#include "../scene/SceneError.h"
#include "../specimen/Scenario.h"
#include <algorithm>
#include <cmath>
#include <exception>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace pushout::study
{
namespace
{
/// fit.json's part on the values: `parameters`, `standard_errors`,
/// `correlation`, `start`, `bounds`, `bounds_exclusive`.
nlohmann::json fitted_values(const std::vector<Free>& free, const std::vector<double>& x,
                             const FitStatistics& st)
{
  const auto number_or_null = [](double v)
  { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
  nlohmann::json params = nlohmann::json::object(), errors = nlohmann::json::object(),
                 starts = nlohmann::json::object(), bounds = nlohmann::json::object(),
                 exclusive = nlohmann::json::array(), exclusive_hi = nlohmann::json::array(),
                 correlation = nlohmann::json::array();
  std::vector<std::string> keys;
  for (std::size_t k = 0; k < free.size(); ++k)
  {
    keys.push_back(free[k].key);
    params[free[k].key] = x[k] * free[k].scale;
    errors[free[k].key] = number_or_null(st.se[k]);
    starts[free[k].key] = free[k].start;
    // [lo, hi], null where unbounded; lo itself excluded where the law says
    // so or the key's range is open (bounds_exclusive), hi where the key's
    // range is open (bounds_exclusive_hi).
    bounds[free[k].key] = {number_or_null(free[k].lo), number_or_null(free[k].hi)};
    if (free[k].lo_exclusive)
      exclusive.push_back(free[k].key);
    if (free[k].hi_exclusive)
      exclusive_hi.push_back(free[k].key);
    nlohmann::json row = nlohmann::json::array();
    for (double c : st.corr[k])
      row.push_back(number_or_null(c));
    correlation.push_back(row);
  }
  nlohmann::json j;
  j["parameters"] = params;
  j["standard_errors"] = errors;
  j["correlation"] = {{"keys", keys}, {"matrix", correlation}};
  j["start"] = starts;
  j["bounds"] = bounds;
  j["bounds_exclusive"] = exclusive;
  j["bounds_exclusive_hi"] = exclusive_hi;
  return j;
}
} // namespace

std::string not_converged_message(const FitOutcome& fit, const std::filesystem::path& fit_json)
{
  std::string m = "the fit did not converge (" + fit.reason;
  if (fit.failed_runs)
    m += "; " + std::to_string(fit.failed_runs) + " runs did not converge: " + fit.failure;
  m += ")";
  const bool no_derivative = fit.reason == "DIVERGED_NO_DERIVATIVE";
  if (no_derivative)
    m += ": no free value has a derivative where it stopped (the runs beside it were refused "
         "or failed, and the warnings name them, or gave the same curve: check the data's "
         "units, delta_mm in mm and tau_MPa in MPa), so nothing tells which way its optimum "
         "lies; start it elsewhere or hold that value";
  if (!fit.best_failure.empty())
    m += "; the fitted run in " + (fit_json.parent_path() / "best").string() + " " +
         fit.best_failure;
  m += "; " + fit_json.string() + " has where it stopped";
  if (fit.refused_runs && fit.refusal_by_size)
    m += "; " + std::to_string(fit.refused_runs) +
         " runs were refused (one of them: " + fit.refusal +
         "): this machine could not hold their models, which a --bounds on the "
         "values that enlarge them keeps the fit off";
  else if (fit.refused_runs)
    m += "; " + std::to_string(fit.refused_runs) +
         " runs were at values the scene refuses (one of them: " + fit.refusal + ")" +
         (no_derivative ? "" // it did not move: no relation was met on the way
                        : ": the best fit may lie beyond a relation between keys (such as f_fr "
                          "<= f_t), which a --bounds at the relation lets the fit end on");
  return m;
}

int write_fit(const FitOptions& opt, const MeasuredCurve& data, const std::vector<Free>& free,
              const FitOutcome& fit, bool talk)
{
  const std::vector<double>& x = fit.x;
  const FitStatistics& stats = fit.statistics;
  const std::size_t m = data.delta.size();
  const double rss = stats.rss;
  int code = fit.converged ? exit_code::done : exit_code::not_converged;
  nlohmann::json j = fitted_values(free, x, stats);
  j["rms_MPa"] = std::sqrt(rss / double(m));
  j["points"] = m;
  j["evaluations"] = fit.evaluations;
  j["failed_runs"] = fit.failed_runs;
  j["refused_runs"] = fit.refused_runs;
  j["refusal"] = fit.refusal;           // "" where none was refused
  j["best_failure"] = fit.best_failure; // "" where the fitted run converged
  j["iterations"] = fit.iterations;
  j["relative_offset"] = fit.relative_offset; // null where infinite (an exact fit) or none
                                              // (DIVERGED_NO_DERIVATIVE)
  j["converged"] = fit.converged;
  j["reason"] = fit.reason;
  j["warnings"] = stats.warnings;
  j["data"] = opt.data.string();
  j["wall_s"] = fit.wall_s;
  // The fitted scene, rerunnable; the bounds keep every value in its key's
  // range, but a scene check that relates keys may still refuse it.
  std::string scene_text, scene_refused;
  try
  {
    const Scene fitted = scene_of(opt, fit.sets);
    specimen::check_scene(fitted); // the checks that relate keys
    scene_text = fitted.to_toml();
  }
  catch (const SceneError& e)
  {
    scene_refused = e.what();
    code = code == exit_code::done ? exit_code::not_converged : code;
  }
  std::vector<std::filesystem::path> written;
  try
  {
    output::write_file(opt.out / "fit.json", j.dump(2) + "\n");
    written.push_back(opt.out / "fit.json");
    if (!scene_text.empty())
    {
      output::write_file(opt.out / "scene.toml", scene_text);
      written.push_back(opt.out / "scene.toml");
    }
    std::ostringstream csv;
    csv << "delta_mm,tau_data_MPa,tau_model_MPa\n" << std::setprecision(12);
    for (std::size_t i = 0; i < m; ++i)
      csv << data.delta[i] << "," << data.tau[i] << "," << data.tau[i] + fit.r[i] << "\n";
    output::write_file(opt.out / "fit.csv", csv.str());
    written.push_back(opt.out / "fit.csv");
  }
  catch (const std::exception& e)
  {
    std::cerr << "pushout: error: " << e.what() << std::endl;
    code = exit_code::failure;
  }
  std::string why;
  if (std::find(written.begin(), written.end(), opt.out / "fit.csv") != written.end())
  {
    if (output::plot_fit(opt.out, opt.out / "fit.png", why))
      written.push_back(opt.out / "fit.png");
    else
      std::cerr << "pushout: warning: no fit.png: " << why << std::endl;
  }
  for (const std::string& w : stats.warnings)
    std::cerr << "pushout: warning: " << w << std::endl;
  if (!scene_refused.empty())
    std::cerr << "pushout: error: the fitted values make no valid scene (" << scene_refused
              << "); no scene.toml" << std::endl;
  if (!fit.converged)
    std::cerr << "pushout: error: " << not_converged_message(fit, opt.out / "fit.json")
              << std::endl;
  if (talk)
  {
    std::cout << "pushout fit: rms " << std::setprecision(6) << std::sqrt(rss / double(m))
              << " MPa after " << fit.evaluations << " runs"
              << (fit.refused_runs
                      ? " (" + std::to_string(fit.refused_runs) + " at values the scene refuses)"
                      : std::string())
              << ", " << std::fixed << std::setprecision(1) << fit.wall_s
              << " s:" << std::defaultfloat << std::endl;
    for (std::size_t k = 0; k < free.size(); ++k)
      std::cout << "  " << free[k].key << " = " << std::setprecision(6) << x[k] * free[k].scale
                << " +- " << stats.se[k] << std::endl;
    std::string files;
    for (const auto& f : written)
      files += (files.empty() ? "" : ", ") + f.string();
    std::cout << "results: " << (files.empty() ? "none" : files) << std::endl;
  }
  return code;
}
} // namespace pushout::study

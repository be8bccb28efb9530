// The measured curve a fit matches (Fit.h): read from a CSV file, and the
// linear interpolation by which a model's curve is read at its points.
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace pushout::study
{
/// A measured curve: delta [mm] increasing, tau [MPa].
struct MeasuredCurve
{
  std::vector<double> delta, tau;
  /// The largest |tau| measured [MPa] (0 for no points).
  double largest_tau() const
  {
    double largest = 0;
    for (double t : tau)
      largest = std::max(largest, std::abs(t));
    return largest;
  }
};
/// The text of the measured curve's `file` (refused if no file of
/// reasonable size). Throws SceneError.
std::string read_measured_text(const std::filesystem::path& file);
/// The curve in `text`, read from `file` (CSV with a header naming
/// delta_mm and tau_MPa; other columns ignored); throws SceneError saying
/// what is wrong.
MeasuredCurve parse_measured(const std::string& text, const std::filesystem::path& file);

/// tau of the curve (delta, tau) at d, linear between its points, its
/// first/last value outside them.
double interpolate(const std::vector<double>& delta, const std::vector<double>& tau, double d);
} // namespace pushout::study

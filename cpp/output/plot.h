// curve.png from curve.csv (and corrosion.png from corrosion.csv), drawn by
// scripts/plot_curve.py, sweep.png of a sweep (scripts/plot_sweep.py) and
// fit.png of a fit (scripts/plot_fit.py), with matplotlib.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>

namespace pushout::output
{
/// The plots of a run, drawn by one python process started with the run:
/// importing matplotlib (most of a plot's 0.7 s) overlaps the run, and the
/// plots are drawn when it ends (scripts/plot_curve.py --serve). One
/// process (rank 0) makes it.
class CurvePlotter
{
public:
  /// Starts the plotting process.
  CurvePlotter();
  /// Ends it if finish() was not called (the run failed before).
  ~CurvePlotter();
  CurvePlotter(const CurvePlotter&) = delete;
  CurvePlotter& operator=(const CurvePlotter&) = delete;

  /// Asks for a plot (`kind`: the model type, or "corrosion"); drawn by
  /// finish().
  void draw(const std::filesystem::path& csv, const std::filesystem::path& png,
            const std::string& kind);
  /// Waits for the plots; false (and why) if the process could not start or
  /// a plot failed. Never throws.
  bool finish(std::string& why);

private:
  std::FILE* _pipe = nullptr;
  bool _failed = false; ///< a request could not be written
};

/// The measured and fitted curves of a fit (`folder`/fit.csv and
/// `folder`/best/curve.csv) into `png`; false (and why) if python3 or
/// matplotlib is missing or the script failed. Never throws.
bool plot_fit(const std::filesystem::path& folder, const std::filesystem::path& png,
              std::string& why);

/// Overlays the curves of the cases of a sweep (`folder`/sweep.csv and each
/// case's curve.csv) into `png`; as plot_fit.
bool plot_sweep(const std::filesystem::path& folder, const std::filesystem::path& png,
                std::string& why);
} // namespace pushout::output

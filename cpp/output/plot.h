// curve.png from curve.csv (and corrosion.png from corrosion.csv), drawn by
// scripts/plot_curve.py, sweep.png of a sweep (scripts/plot_sweep.py) and
// fit.png of a fit (scripts/plot_fit.py), with matplotlib.
#pragma once

#include <filesystem>
#include <string>

namespace pushout::output
{
/// Draws the curve (`kind`: the model type, or "corrosion"); returns false (and says why in `why`)
/// if python3 or matplotlib is missing or the script failed. Never throws.
bool plot_curve(const std::filesystem::path& csv, const std::filesystem::path& png,
                const std::string& kind, std::string& why);

/// The measured and fitted curves of a fit (`folder`/fit.csv and
/// `folder`/best/curve.csv) into `png`; as plot_curve.
bool plot_fit(const std::filesystem::path& folder, const std::filesystem::path& png,
              std::string& why);

/// Overlays the curves of the cases of a sweep (`folder`/sweep.csv and each
/// case's curve.csv) into `png`; as plot_curve.
bool plot_sweep(const std::filesystem::path& folder, const std::filesystem::path& png,
                std::string& why);
} // namespace pushout::output

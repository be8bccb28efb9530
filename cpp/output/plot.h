// curve.png from curve.csv (and corrosion.png from corrosion.csv), drawn by
// scripts/plot_curve.py (matplotlib).
#pragma once

#include <filesystem>
#include <string>

namespace pushout::output
{
/// Draws the curve (`kind`: the model type, or "corrosion"); returns false (and says why in `why`)
/// if python3 or matplotlib is missing or the script failed. Never throws.
bool plot_curve(const std::filesystem::path& csv, const std::filesystem::path& png,
                const std::string& kind, std::string& why);
} // namespace pushout::output

// curve.png from curve.csv, drawn by scripts/plot_curve.py (matplotlib).
#pragma once

#include <filesystem>
#include <string>

namespace pushout::output
{
/// Draws the curve; returns false (and says why in `why`) if python3 or
/// matplotlib is missing or the script failed. Never throws.
bool plot_curve(const std::filesystem::path& csv, const std::filesystem::path& png,
                const std::string& model_type, std::string& why);
} // namespace pushout::output

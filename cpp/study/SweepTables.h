// The tables of `pushout sweep`, written on rank 0 once the cases have run,
// from what each case folder holds (curve.csv, summary.json):
//
//  - sweep.csv: one row per case, its varied values, the curve's peak and
//    last point and, for a push-out, the pressure on the tube at the push's
//    start and the widest surface crack then; whether it converged, its
//    exit code, wall time and message;
//  - sweep_seeds.csv, when `cracking.seed` (the random strength field's
//    seed) is varied over two values or more: the cases that differ only in
//    the seed are one row, with the number of seeds and of those that
//    converged, and the mean, smallest and largest of each number over the
//    converged ones: the seeds as error bars (docs/sweeps.md).
#pragma once

#include "../driver/Run.h"
#include "Sweep.h"
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace pushout::study
{
/// The outcome of one case, as its group's first process knows it.
struct CaseResult : driver::RunOutcome
{
  int index = -1;
};

/// The folder name of case i: case_000, case_001, ...
std::string case_name(std::size_t i);

/// The varied key whose values are replicates of one random specimen.
inline const std::string seed_key = "cracking.seed";

/// The numbers of one case that sweep.csv gives after its varied values
/// (in the order of its columns); NaN where the case has none.
using CaseNumbers = std::vector<double>;

/// What became of a case of the sweep.
enum class CaseState
{
  not_run,  ///< a signal stopped the sweep first
  failed,   ///< ran and did not converge (or was refused)
  converged ///< ran to its end
};

/// The cases grouped by their values of every varied key but seed_key.
struct SeedGroup
{
  std::vector<std::string> values; ///< of the other keys, in --vary order
  int seeds = 0;                   ///< cases of the group that ran
  int converged = 0;               ///< of which converged (the statistics' cases)
  /// Per number, over the converged cases where it is a number; NaN where
  /// there is none.
  std::vector<double> mean, min, max;
};

/// The groups of `cases` (cartesian_cases of `vary`, which varies seed_key),
/// in the order of their first case; `numbers[i]` and `states[i]` are case
/// i's. Pure.
std::vector<SeedGroup> group_seeds(const std::vector<Variation>& vary,
                                   const std::vector<std::vector<std::string>>& cases,
                                   const std::vector<CaseNumbers>& numbers,
                                   const std::vector<CaseState>& states);

/// Whether `vary` makes seed groups: seed_key with two values or more.
bool varies_seed(const std::vector<Variation>& vary);

/// sweep.csv, and sweep_seeds.csv if varies_seed(vary), in `out` from the
/// case folders there; `results` are the cases that ran (sorted by index).
/// Throws if a file cannot be written.
void write_tables(const std::filesystem::path& out, const std::string& model_type,
                  const std::vector<Variation>& vary,
                  const std::vector<std::vector<std::string>>& cases,
                  const std::vector<CaseResult>& results);
} // namespace pushout::study

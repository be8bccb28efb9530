// `pushout sweep`: a parameter study, the Cartesian product of the values of
// one or more scene keys, each case run as `pushout run` would run it, in
// its own folder (case_000, case_001, ...: resolved scene.toml, curve.csv,
// summary.json). The cases that share a set-up (mesh, model, factorisation)
// run one after the other on a group that reuses it (set_up_order).
//
// Under MPI the processes split into groups of `ranks_per_case`
// (MPI_Comm_split); each group takes the next case from a counter that all
// share (an MPI window on rank 0, MPI_Fetch_and_op) and runs it on its own
// communicator, so one command runs a sweep on a laptop or, through
// mpirun/srun, on a cluster. A case is the same computation as a `pushout
// run` on that many processes: its results equal those of the serial run.
//
// At the end rank 0 writes sweep.csv, one row per case: the case, the
// varied values, the peak of the curve and where it is, the last point
// (a push-out's: also the pressure and the widest surface crack at the
// push's start), whether it converged, its exit code and wall time; with
// cracking.seed varied, sweep_seeds.csv, the seeds as error bars
// (SweepTables.h); and sweep.png, the curves overlaid (a seed group's as a
// range).
#pragma once

#include "ManyRuns.h"
#include <filesystem>
#include <string>
#include <vector>

namespace pushout::study
{
struct SweepOptions : ManyRunsOptions
{
  std::vector<std::string> vary; ///< --vary key=v1,v2,...
  /// --max-cases: the most cases a sweep runs (more is refused, exit 2).
  std::size_t max_cases = default_max_cases;
  static constexpr std::size_t default_max_cases = 10000;
  /// The largest --max-cases takes: a sweep of more is split by hand.
  static constexpr std::size_t largest_max_cases = 100000000;
};

/// One varied key and its values, from "key=v1,v2,..." (commas inside
/// [...] belong to an array value, and inside a TOML string's quotes to
/// the string; an integer in decimal, such as 16 for 0x10). Throws
/// SceneError if malformed.
struct Variation
{
  std::string key;
  std::vector<std::string> values;
};
Variation parse_variation(const std::string& text);

/// The cases: each a list of "key=value" overrides, the last key varying
/// fastest.
std::vector<std::vector<std::string>> cartesian_cases(const std::vector<Variation>& vary);

/// The order the cases are taken in: the cases that share a set-up (the
/// same Simulation::set_up_fingerprint, given per case) one after the other,
/// each set-up where its first case is, so that a group rebuilds a set-up
/// as rarely as possible; otherwise the cases' own order. The case folders
/// keep the cases' numbers.
std::vector<std::size_t> set_up_order(const std::vector<std::string>& set_ups);

/// Runs the sweep on MPI_COMM_WORLD; returns the process exit code (0: every
/// case converged; 3: some did not; 2: bad input; 128 + signal if a signal
/// stopped it). Collective.
int sweep(const SweepOptions& options);
} // namespace pushout::study

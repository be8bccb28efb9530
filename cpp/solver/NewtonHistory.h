// What the |F| of a Newton solve's iterations so far (iteration 0 first)
// say, shared by NewtonSolver (with cracking concrete) and ArcLengthSolver:
// - stalled: in `stall_iterations` iterations they have not halved the
//   smallest |F| so far. Near a brittle event the iterates can wander for
//   all of -snes_max_it, and a step is better cut now than after the last
//   iteration. Slower than that (a factor 0.93 per iteration) no step
//   converges within -snes_max_it (50); a slow but steady one is left alone.
// - in a linear tail: the last two iterations each cut |F| by `ratio` or
//   better, where a new factorisation buys little (set_tail_reuse).
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace pushout::solver
{
/// Iterations without halving the smallest |F| after which a solve fails
/// (DIVERGED_NO_PROGRESS).
constexpr std::ptrdiff_t stall_iterations = 10;

/// Whether iterations whose |F| so far are `fnorms` (iteration 0 first) have
/// stalled. The initial |F| does not count as the smallest: a first step
/// that raises |F| (a crack's first opening) is not a stall.
inline bool stalled(const std::vector<double>& fnorms)
{
  const auto n = std::ptrdiff_t(fnorms.size());
  if (n <= stall_iterations + 1)
    return false;
  const auto recent = fnorms.end() - stall_iterations;
  return *std::min_element(recent, fnorms.end()) >
         0.5 * *std::min_element(fnorms.begin() + 1, recent);
}

/// Whether the last two iterations of `fnorms` each cut |F| by `ratio` or
/// better (never if ratio <= 0).
inline bool in_linear_tail(const std::vector<double>& fnorms, double ratio)
{
  const std::size_t n = fnorms.size();
  return ratio > 0 && n >= 3 && fnorms[n - 1] <= ratio * fnorms[n - 2] &&
         fnorms[n - 2] <= ratio * fnorms[n - 3];
}
} // namespace pushout::solver

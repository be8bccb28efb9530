// Adaptive sub-stepping of the nominal load steps.
//
// Each nominal step (s from k-1 to k) is tried whole; a failed try is
// retried from the committed state with half the increment, down to
// 2^-max_cuts of a nominal step; after `easy` consecutive tries that
// converged in at most `easy_iterations` Newton iterations the increment
// doubles again (never beyond one nominal step, so every nominal step still
// ends on a curve row).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

namespace pushout::stepping
{
class Stepper
{
public:
  Stepper(int max_cuts, int easy_iterations)
      : _max_cuts(max_cuts), _easy_iterations(easy_iterations)
  {
  }

  /// Load parameter to try next from committed s towards nominal target.
  double next(double s, double target) const { return std::min(s + _ds, target); }

  /// After a converged try; `may_grow` false: it does not count as easy
  /// whatever its iterations (an IMPL-EX step whose error would exceed its
  /// tolerance at twice the increment).
  void converged(int iterations, bool may_grow = true)
  {
    _easy = iterations <= _easy_iterations && may_grow ? _easy + 1 : 0;
    if (_easy >= 2 && _ds < 1.0)
    {
      _ds = std::min(2 * _ds, 1.0);
      _easy = 0;
    }
  }

  /// After a failed try: halves the increment, or halves it until it is at
  /// most `factor` times what it was (an error that says by how much);
  /// false if it is already the smallest allowed. `tried`: the failed try's
  /// own increment where next() clipped it short of the increment (at the
  /// end of a nominal step); the cut is from it, else the retry could be
  /// the same try.
  bool failed(double factor = 0.5, double tried = std::numeric_limits<double>::infinity())
  {
    _easy = 0;
    const double smallest = std::ldexp(1.0, -_max_cuts);
    if (_ds <= smallest)
      return false;
    const double target = factor * std::min(_ds, tried);
    do
      _ds /= 2;
    while (_ds > target && _ds > smallest);
    return true;
  }

  /// Whether the increment is the smallest allowed.
  bool smallest() const { return _ds <= std::ldexp(1.0, -_max_cuts); }

  /// Current increment, in nominal steps.
  double increment() const { return _ds; }

private:
  int _max_cuts;
  int _easy_iterations;
  double _ds = 1.0;
  int _easy = 0;
};
} // namespace pushout::stepping

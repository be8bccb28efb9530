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

  /// After a converged try.
  void converged(int iterations)
  {
    _easy = iterations <= _easy_iterations ? _easy + 1 : 0;
    if (_easy >= 2 && _ds < 1.0)
    {
      _ds = std::min(2 * _ds, 1.0);
      _easy = 0;
    }
  }

  /// After a failed try: halves the increment; false if it is already the
  /// smallest allowed.
  bool failed()
  {
    _easy = 0;
    if (_ds <= std::ldexp(1.0, -_max_cuts))
      return false;
    _ds /= 2;
    return true;
  }

  /// Current increment, in nominal steps.
  double increment() const { return _ds; }

private:
  int _max_cuts;
  int _easy_iterations;
  double _ds = 1.0;
  int _easy = 0;
};
} // namespace pushout::stepping

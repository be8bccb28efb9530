// One event of dissipation control's energy steps (StepLoop::DissipationSteps,
// DissipationControl.cpp; docs/numerics.md, "Dissipation control"): the
// energy steps since the last hand-over to them, and when they hand back to
// steps of the load.
#pragma once

namespace pushout::stepping
{
/// Dissipation control: the event the energy steps trace, from its first
/// committed energy step on.
class EnergyEvent
{
public:
  /// Why an event's energy steps hand back to steps of the load.
  enum class End
  {
    none,            ///< they go on
    traced,          ///< lambda, having fallen, is back past where they began
    passed,          ///< after a failure: lambda a nominal step past it, never fallen
    released_little, ///< the event released more than a nominal increment, the step little
  };

  /// Energy steps take over because a short step of the load failed (not
  /// for a dissipation or a snap): once they have carried lambda a nominal
  /// step past it without it falling, what failed is passed (End::passed).
  /// An event's cause is its first hand-over's: within an event (a step of
  /// the load after an energy step that overshot, handed over again) a
  /// later one does not change it.
  void handed_over_by_failure()
  {
    if (!_on)
      _by_failure = true;
  }
  /// Energy steps take over for a dissipation or a snap.
  void handed_over_by_event()
  {
    if (!_on)
      _by_failure = false;
  }

  /// A committed energy step from `lambda` to `lambda_new` [mm] in which the
  /// softening layers released `released` of its increment `dG_step`
  /// [N mm]: whether the event ends with it, given the stage's nominal
  /// energy increment `dG_nominal` [N mm] and step `h_nominal` [mm].
  End energy_step(double lambda, double lambda_new, double released, double dG_step,
                  double dG_nominal, double h_nominal)
  {
    if (!_on) // the event's first energy step
    {
      _on = true;
      _start = lambda;
      _fell = false;
    }
    _fell = _fell || lambda_new < _start;
    _released += released;
    End end = End::none;
    if (_fell && lambda_new > _start)
      end = End::traced;
    else if (_by_failure && !_fell && lambda_new > _start + h_nominal)
      end = End::passed;
    else if (_released > dG_nominal && released < released_to_return * dG_step)
      end = End::released_little;
    if (end != End::none)
    {
      // The released energy is kept until a step of the load is committed.
      _on = false;
      _by_failure = false;
    }
    return end;
  }
  /// A committed step of the load: no event.
  void load_step() { *this = EnergyEvent{}; }

  /// Where the event (or the last one) began: lambda [mm].
  double start() const { return _start; }

  /// Steps of the load again after an energy step in which the softening
  /// layers released less than this fraction of its increment (the slip
  /// term of the control did the rest), once the event has released more
  /// than one nominal increment (it is over, not beginning).
  static constexpr double released_to_return = 0.25;

private:
  bool _on = false;         ///< an energy step of the event has been committed
  double _start = 0;        ///< lambda where it began [mm]
  bool _fell = false;       ///< one of its steps took lambda below _start
  double _released = 0;     ///< by the softening layers in its steps so far [N mm]
  bool _by_failure = false; ///< handed_over_by_failure()
};
} // namespace pushout::stepping

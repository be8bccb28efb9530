// When dissipation control's energy steps hand back to steps of the load
// (stepping/EnergyEvent.h; docs/numerics.md, "Dissipation control"): once
// the event has released more than a nominal increment and a step
// releases little; once lambda, having fallen, is back past where the
// event began; and, where the energy steps took over from a failed step of
// the load, once lambda is a nominal step past it without having fallen.
#include "stepping/EnergyEvent.h"
#include <gtest/gtest.h>

using pushout::stepping::EnergyEvent;
using End = EnergyEvent::End;

namespace
{
constexpr double dG = 1.0; // the nominal energy increment [N mm]
constexpr double h = 0.1;  // the nominal step of lambda [mm]

/// An energy step from `from` to `to` that released its whole increment.
End step(EnergyEvent& e, double from, double to, double released = dG)
{
  return e.energy_step(from, to, released, dG, dG, h);
}
} // namespace

TEST(EnergyEvent, ASnapBackTracedEndsBackPastItsStart)
{
  EnergyEvent e;
  EXPECT_EQ(step(e, 1.0, 0.98), End::none);
  EXPECT_EQ(step(e, 0.98, 0.95), End::none);
  EXPECT_EQ(step(e, 0.95, 0.99), End::none); // risen, not yet past 1.0
  EXPECT_EQ(step(e, 0.99, 1.01), End::traced);
  EXPECT_DOUBLE_EQ(e.start(), 1.0);
}

TEST(EnergyEvent, ARisingBranchEndsAStepPastAFailureOnly)
{
  // Handed over for a dissipation: lambda rising by more than h goes on.
  EnergyEvent by_event;
  by_event.handed_over_by_event();
  for (double x = 1.0; x < 1.5; x += 0.05)
    EXPECT_EQ(step(by_event, x, x + 0.05), End::none) << x;

  // Handed over after a failure: a step of h past it ends the event.
  EnergyEvent by_failure;
  by_failure.handed_over_by_failure();
  EXPECT_EQ(step(by_failure, 1.0, 1.05), End::none);
  EXPECT_EQ(step(by_failure, 1.05, 1.1), End::none); // exactly h: not past it
  EXPECT_EQ(step(by_failure, 1.1, 1.11), End::passed);

  // ... but not once lambda has fallen: that is a snap-back, traced.
  EnergyEvent fell;
  fell.handed_over_by_failure();
  EXPECT_EQ(step(fell, 1.0, 0.99), End::none);
  EXPECT_EQ(step(fell, 0.99, 1.2), End::traced);

  // A later hand-over for a snap or a dissipation clears the cause.
  EnergyEvent cleared;
  cleared.handed_over_by_failure();
  cleared.handed_over_by_event();
  EXPECT_EQ(step(cleared, 1.0, 1.2), End::none);
}

TEST(EnergyEvent, AFailureWithinAnEventKeepsItsCause)
{
  // Handed over for a dissipation; a step of the load after one that
  // overshot fails: the event's cause stays a dissipation.
  EnergyEvent e;
  e.handed_over_by_event();
  EXPECT_EQ(step(e, 1.0, 1.05), End::none);
  e.handed_over_by_failure();
  EXPECT_EQ(step(e, 1.05, 1.2), End::none);
}

TEST(EnergyEvent, EndsWhenAStepReleasesLittleAfterMoreThanAnIncrement)
{
  EnergyEvent e;
  // Little released before the event has released an increment: on.
  EXPECT_EQ(step(e, 1.0, 1.01, 0.5), End::none);
  EXPECT_EQ(step(e, 1.01, 1.02, 0.1), End::none); // 0.6 released in all
  EXPECT_EQ(step(e, 1.02, 1.03, 0.6), End::none); // 1.2: over an increment
  EXPECT_EQ(step(e, 1.03, 1.04, EnergyEvent::released_to_return * dG * 0.99), End::released_little);
}

TEST(EnergyEvent, AStepOfTheLoadStartsAfresh)
{
  EnergyEvent e;
  e.handed_over_by_failure();
  EXPECT_EQ(step(e, 1.0, 0.9), End::none);
  e.load_step();
  // A new event: it begins where its first energy step starts, has not
  // fallen, and was handed over for no failure.
  EXPECT_EQ(step(e, 2.0, 2.05), End::none);
  EXPECT_EQ(step(e, 2.05, 2.3), End::none);
  EXPECT_DOUBLE_EQ(e.start(), 2.0);
}

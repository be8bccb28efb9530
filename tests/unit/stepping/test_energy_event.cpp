// When dissipation control's energy steps hand back to steps of the load
// (stepping/EnergyEvent.h; docs/numerics.md, "Dissipation control"): once
// the event has released more than a nominal increment and a step
// releases little; once lambda, having fallen, is back past where the
// event began; and, where the energy steps took over from a failed step of
// the load, once lambda is a nominal step past it without having fallen.
// (Loads in binary fractions, so that "exactly a step past" is exact.)
#include "stepping/EnergyEvent.h"
#include <gtest/gtest.h>

using pushout::stepping::EnergyEvent;
using End = EnergyEvent::End;

namespace
{
constexpr double dG = 1.0;  // the nominal energy increment [N mm]
constexpr double h = 0.125; // the nominal step of lambda [mm]

/// An energy step from `from` to `to` that released `released` (its whole
/// increment by default).
End step(EnergyEvent& e, double from, double to, double released = dG)
{
  return e.energy_step(from, to, released, dG, dG, h);
}
} // namespace

TEST(EnergyEvent, ASnapBackTracedEndsBackPastItsStart)
{
  EnergyEvent e;
  EXPECT_EQ(step(e, 1.0, 0.96875), End::none);
  EXPECT_EQ(step(e, 0.96875, 0.9375), End::none);
  EXPECT_EQ(step(e, 0.9375, 1.0), End::none); // risen back to 1.0, not past it
  EXPECT_EQ(step(e, 1.0, 1.015625), End::traced);
  EXPECT_DOUBLE_EQ(e.start(), 1.0);
}

TEST(EnergyEvent, ARisingBranchEndsAStepPastAFailureOnly)
{
  // Handed over for a dissipation: lambda rising by more than h goes on.
  EnergyEvent by_event;
  by_event.handed_over_by_event();
  for (double x = 1.0; x < 1.5; x += 0.0625)
    EXPECT_EQ(step(by_event, x, x + 0.0625), End::none) << x;

  // Handed over after a failure: a step of h past it ends the event.
  EnergyEvent by_failure;
  by_failure.handed_over_by_failure();
  EXPECT_EQ(step(by_failure, 1.0, 1.0625), End::none);
  EXPECT_EQ(step(by_failure, 1.0625, 1.125), End::none); // exactly h: not past it
  EXPECT_EQ(step(by_failure, 1.125, 1.140625), End::passed);

  // ... but not once lambda has fallen: that is a snap-back, traced.
  EnergyEvent fell;
  fell.handed_over_by_failure();
  EXPECT_EQ(step(fell, 1.0, 0.984375), End::none);
  EXPECT_EQ(step(fell, 0.984375, 1.25), End::traced);

  // A hand-over for a snap or a dissipation before the event begins sets
  // its cause.
  EnergyEvent cleared;
  cleared.handed_over_by_failure();
  cleared.handed_over_by_event();
  EXPECT_EQ(step(cleared, 1.0, 1.25), End::none);
}

TEST(EnergyEvent, AnEventKeepsTheCauseOfItsFirstHandOver)
{
  // Handed over for a dissipation; within the event a step of the load
  // (after an energy step that overshot) fails: still a dissipation's.
  EnergyEvent dissipation;
  dissipation.handed_over_by_event();
  EXPECT_EQ(step(dissipation, 1.0, 1.0625), End::none);
  dissipation.handed_over_by_failure();
  EXPECT_EQ(step(dissipation, 1.0625, 1.25), End::none);

  // Handed over after a failure; within the event a step of the load
  // dissipates too much: still a failure's.
  EnergyEvent failure;
  failure.handed_over_by_failure();
  EXPECT_EQ(step(failure, 1.0, 1.0625), End::none);
  failure.handed_over_by_event();
  EXPECT_EQ(step(failure, 1.0625, 1.25), End::passed);
}

TEST(EnergyEvent, EndsWhenAStepReleasesLittleAfterMoreThanAnIncrement)
{
  EnergyEvent e;
  // Little released before the event has released an increment: on.
  EXPECT_EQ(step(e, 1.0, 1.0078125, 0.5), End::none);
  EXPECT_EQ(step(e, 1.0078125, 1.015625, 0.125), End::none);            // 0.625 in all
  EXPECT_EQ(step(e, 1.015625, 1.0234375, 0.5), End::none);              // 1.125: over an increment
  EXPECT_EQ(step(e, 1.0234375, 1.03125, 0.1875), End::released_little); // below a quarter
}

TEST(EnergyEvent, TheReleasedEnergyIsKeptUntilAStepOfTheLoad)
{
  // An event that ends (traced) keeps what it released: handed over again
  // before a step of the load is committed, the next event ends as soon as
  // a step releases little.
  EnergyEvent e;
  EXPECT_EQ(step(e, 1.0, 0.9375, 2.0), End::none);
  EXPECT_EQ(step(e, 0.9375, 1.0625), End::traced);
  EXPECT_EQ(step(e, 1.0625, 1.0703125, 0.125), End::released_little);

  // After a step of the load the sum starts again from zero.
  e.load_step();
  EXPECT_EQ(step(e, 2.0, 2.0078125, 0.125), End::none);
}

TEST(EnergyEvent, AStepOfTheLoadStartsAfresh)
{
  EnergyEvent e;
  e.handed_over_by_failure();
  EXPECT_EQ(step(e, 1.0, 0.875), End::none);
  e.load_step();
  // A new event: it begins where its first energy step starts, has not
  // fallen, and was handed over for no failure.
  EXPECT_EQ(step(e, 2.0, 2.0625), End::none);
  EXPECT_EQ(step(e, 2.0625, 2.375), End::none);
  EXPECT_DOUBLE_EQ(e.start(), 2.0);
}

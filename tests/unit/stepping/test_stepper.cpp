// The cut and regrowth of load steps (stepping/Stepper.h): a failed try
// halves the increment down to 2^-max_cuts of a nominal step, then the step
// cannot be cut again; two easy tries in a row double it back, never beyond
// one nominal step; the next try never passes its nominal step.
#include "stepping/Stepper.h"
#include <gtest/gtest.h>

using pushout::stepping::Stepper;

namespace
{
constexpr int easy = 4; // Newton iterations of an easy try
} // namespace

TEST(Stepper, HalvesDownToTwoToTheMinusMaxCutsThenRefuses)
{
  Stepper stepper(3, easy);
  EXPECT_EQ(stepper.increment(), 1.0);
  EXPECT_TRUE(stepper.failed());
  EXPECT_EQ(stepper.increment(), 0.5);
  EXPECT_TRUE(stepper.failed());
  EXPECT_EQ(stepper.increment(), 0.25);
  EXPECT_TRUE(stepper.failed());
  EXPECT_EQ(stepper.increment(), 0.125);
  EXPECT_FALSE(stepper.failed()); // 2^-3: no further cut
  EXPECT_EQ(stepper.increment(), 0.125);
  EXPECT_FALSE(stepper.failed());
}

TEST(Stepper, NoCutsAllowedRefusesTheFirstFailure)
{
  Stepper stepper(0, easy);
  EXPECT_FALSE(stepper.failed());
  EXPECT_EQ(stepper.increment(), 1.0);
}

TEST(Stepper, TwoEasyTriesDoubleBackNeverBeyondOne)
{
  Stepper stepper(5, easy);
  stepper.failed();
  stepper.failed();
  ASSERT_EQ(stepper.increment(), 0.25);
  stepper.converged(easy);
  EXPECT_EQ(stepper.increment(), 0.25); // one easy try is not enough
  stepper.converged(1);
  EXPECT_EQ(stepper.increment(), 0.5);
  stepper.converged(easy);
  stepper.converged(easy);
  EXPECT_EQ(stepper.increment(), 1.0);
  for (int i = 0; i < 6; ++i)
    stepper.converged(1);
  EXPECT_EQ(stepper.increment(), 1.0); // a nominal step at most
}

TEST(Stepper, AHardTryOrAFailureStartsTheEasyCountAgain)
{
  Stepper stepper(5, easy);
  stepper.failed();
  stepper.failed();
  stepper.converged(easy);
  stepper.converged(easy + 1); // hard
  stepper.converged(easy);
  EXPECT_EQ(stepper.increment(), 0.25);
  stepper.converged(easy);
  EXPECT_EQ(stepper.increment(), 0.5);

  stepper.converged(easy);
  stepper.failed(); // to 0.25, the easy try forgotten
  stepper.converged(easy);
  EXPECT_EQ(stepper.increment(), 0.25);
  stepper.converged(easy);
  EXPECT_EQ(stepper.increment(), 0.5);
}

TEST(Stepper, NextClampsAtTheTarget)
{
  Stepper stepper(5, easy);
  EXPECT_EQ(stepper.next(0.0, 1.0), 1.0);
  EXPECT_EQ(stepper.next(2.5, 3.0), 3.0); // a whole step would pass the target
  stepper.failed();
  stepper.failed();
  EXPECT_EQ(stepper.next(2.5, 3.0), 2.75);
  EXPECT_EQ(stepper.next(2.75, 3.0), 3.0);
}

// An error that says by how much a try missed (IMPL-EX's, first order in
// the step) cuts at once to the power of two below that fraction, never
// below the smallest increment; a try that may not grow is not easy.
TEST(Stepper, AFailureByAKnownFactorCutsAtOnce)
{
  Stepper stepper(5, easy);
  EXPECT_TRUE(stepper.failed(0.8 / 17)); // 1 -> 1/32 (1/16 > 0.047)
  EXPECT_EQ(stepper.increment(), 1.0 / 32);
  EXPECT_FALSE(stepper.failed(0.1)); // already the smallest
  EXPECT_EQ(stepper.increment(), 1.0 / 32);

  Stepper other(5, easy);
  EXPECT_TRUE(other.failed(0.01)); // clamped at the smallest, 2^-5
  EXPECT_EQ(other.increment(), 1.0 / 32);
  EXPECT_TRUE(Stepper(5, easy).failed(0.7)); // at least one halving
}

// A try that next() clipped at the end of a nominal step (0.75 -> 1 with
// an increment of 0.5) is cut from its own size: halved from 0.5 only, the
// retry would be the same try from 0.75 to 1 again.
TEST(Stepper, AClippedTryIsCutFromItsOwnSize)
{
  Stepper stepper(5, easy);
  stepper.failed(); // 0.5
  EXPECT_EQ(stepper.next(0.75, 1.0), 1.0);
  EXPECT_TRUE(stepper.failed(0.5, 0.25));
  EXPECT_EQ(stepper.increment(), 0.125);
  EXPECT_EQ(stepper.next(0.75, 1.0), 0.875);
  // A known factor from the try's size: 0.8 / 3 of 0.125 -> 1/32.
  EXPECT_TRUE(stepper.failed(0.8 / 3, 0.125));
  EXPECT_EQ(stepper.increment(), 1.0 / 32);
  // A try the size of the increment is cut as before.
  Stepper whole(5, easy);
  EXPECT_TRUE(whole.failed(0.5, 1.0));
  EXPECT_EQ(whole.increment(), 0.5);
}

TEST(Stepper, ATryThatMayNotGrowIsNotEasy)
{
  Stepper stepper(5, easy);
  stepper.failed();
  stepper.converged(1, false);
  stepper.converged(1, false);
  EXPECT_EQ(stepper.increment(), 0.5);
  stepper.converged(1);
  stepper.converged(1);
  EXPECT_EQ(stepper.increment(), 1.0);
}

// A fit's free value (study/FreeValue.h): the lower bound TAO is given where
// the value's own lower bound is excluded (a law's positive parameter).
#include "../../../cpp/study/FreeValue.h"
#include <gtest/gtest.h>

using pushout::study::Free;

TEST(FreeValue, AnExcludedBoundStaysExcludedThroughTheScale)
{
  // f_t > 0 MPa, started at 3: TAO works on the value over its scale, and the
  // value it hands back (its variable times the scale) must stay above 0.
  Free f{"interface.1.f_t", 3.0, 0.0, INFINITY, 3.0, true};
  const double x_lo = f.tao_lo() / f.scale; // TAO's bound
  EXPECT_GT(x_lo * f.scale, 0.0);
  EXPECT_LE(f.tao_lo(), 1e-6 * f.scale); // counted as on its bound (FitStatistics)
  // Far from 0 the bound moves by no more than the relative 1e-9.
  Free g{"k", 5.0, 2.0, INFINITY, 5.0, true};
  EXPECT_GT(g.tao_lo() / g.scale * g.scale, 2.0);
  EXPECT_LE(g.tao_lo() - 2.0, 1e-8 * g.scale);
  // An included bound is given as it is.
  Free h{"mu", 0.4, 0.0, INFINITY, 0.4, false};
  EXPECT_EQ(h.tao_lo(), 0.0);
}

TEST(FreeValue, OnItsBoundWithinAMillionthOfTheScale)
{
  // mu >= 0, started at 0.4 (TAO's variable x = mu / 0.4): on its bound
  // within 1e-6 of the scale, as the fit's warning and its offset read it.
  Free f{"mu", 0.4, 0.0, 1.0, 0.4, false};
  EXPECT_TRUE(f.on_lo(0.0));
  EXPECT_TRUE(f.on_lo(0.9e-6));
  EXPECT_FALSE(f.on_lo(1.1e-6 / 0.4 * 1.0));
  EXPECT_TRUE(f.on_hi(1.0 / 0.4));
  EXPECT_FALSE(f.on_hi(0.5));
  // TAO's bound of an excluded lower bound counts as on it.
  Free g{"f_t", 3.0, 0.0, INFINITY, 3.0, true};
  EXPECT_TRUE(g.on_lo(g.tao_lo() / g.scale));
  EXPECT_FALSE(g.on_hi(1e300)); // no upper bound
}

// The zero-force search of an unloading segment (stepping/ZeroForceSearch.h):
// Illinois false position on a bracket s0 (P0 >= 0), s1 (P1 < 0), each try
// a callable that gives the force or fails. The sequence of tries is the
// curve's: the first tries are checked point by point.
#include "stepping/ZeroForceSearch.h"
#include <cmath>
#include <functional>
#include <gtest/gtest.h>
#include <optional>
#include <utility>
#include <vector>

using namespace pushout::stepping;
using Outcome = ZeroForceResult::Outcome;

namespace
{
/// A force P(s) [N] as a try, the load parameters tried kept in order.
struct Force
{
  explicit Force(std::function<double(double)> force) : P(std::move(force)) {}
  std::function<double(double)> P;
  std::vector<double> tried;
  ZeroForceTry try_at()
  {
    return [this](double s) -> std::optional<double>
    {
      tried.push_back(s);
      return P(s);
    };
  }
};
} // namespace

TEST(ZeroForceSearch, LinearForceIsHitByOneSecantStep)
{
  Force f{[](double s) { return 3.0 - 4.0 * s; }}; // zero at 0.75
  const ZeroForceResult r = find_zero_force(0.0, 3.0, 1.0, -1.0, 1e-12, f.try_at());
  EXPECT_EQ(r.outcome, Outcome::found);
  EXPECT_EQ(r.tries, 1);
  EXPECT_DOUBLE_EQ(r.s, 0.75);
  EXPECT_EQ(f.tried, std::vector<double>{0.75});
}

TEST(ZeroForceSearch, NonlinearForceConvergesWithinTol)
{
  // Convex, zero at sqrt(1/2): the end at s1 is kept, its force halved
  // (Illinois) from the second try on.
  const double tol = 1e-12; // [N]
  Force f{[](double s) { return 0.5 - s * s; }};
  const ZeroForceResult r = find_zero_force(0.0, 0.5, 1.0, -0.5, tol, f.try_at());
  EXPECT_EQ(r.outcome, Outcome::found);
  EXPECT_LE(std::abs(f.P(r.s)), tol);
  EXPECT_NEAR(r.s, std::sqrt(0.5), 1e-11);
  EXPECT_EQ(r.tries, int(f.tried.size()));
  EXPECT_LE(r.tries, 10);
  // Try 1: the secant of [0, 1], 1/2 (P = 1/4 > 0 replaces s0). Try 2: the
  // secant of [1/2, 1], 2/3 (s0 replaced again: P1 halved to -1/4). Try 3:
  // 1 - (1/4)(1/3) / (1/4 + 1/18) = 8/11.
  ASSERT_GE(f.tried.size(), 3u);
  EXPECT_DOUBLE_EQ(f.tried[0], 0.5);
  EXPECT_DOUBLE_EQ(f.tried[1], 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(f.tried[2], 8.0 / 11.0);
  for (const double s : f.tried)
  {
    EXPECT_GT(s, 0.0);
    EXPECT_LE(s, 1.0);
  }
}

TEST(ZeroForceSearch, ConcaveForceConvergesWithinTol)
{
  // Zero at 1/2, from the other side: the end at s0 is kept.
  const double tol = 1e-12; // [N]
  Force f{[](double s) { return std::pow(1.0 - s, 3) - 0.125; }};
  const ZeroForceResult r = find_zero_force(0.0, 0.875, 1.0, -0.125, tol, f.try_at());
  EXPECT_EQ(r.outcome, Outcome::found);
  EXPECT_LE(std::abs(f.P(r.s)), tol);
  EXPECT_NEAR(r.s, 0.5, 1e-11);
  EXPECT_LE(r.tries, 15);
}

TEST(ZeroForceSearch, ForceNoisierThanTolEndsWhenTheBracketIsRoundOff)
{
  // A jump at 0.3: |P| is never within tol; the search ends once the
  // bracket is down to 1e-12 of the load parameter, at the jump.
  Force f{[](double s) { return s < 0.3 ? 1.0 : -1.0; }};
  const ZeroForceResult r = find_zero_force(0.0, 1.0, 1.0, -1.0, 1e-9, f.try_at());
  EXPECT_EQ(r.outcome, Outcome::found);
  EXPECT_NEAR(r.s, 0.3, 1e-11);
  EXPECT_LE(r.tries, zero_force_max_tries);
}

TEST(ZeroForceSearch, FailedTryEndsTheSearch)
{
  int calls = 0;
  const ZeroForceTry try_at = [&](double s) -> std::optional<double>
  {
    if (++calls == 2)
      return std::nullopt; // did not converge
    return 0.5 - s * s;
  };
  const ZeroForceResult r = find_zero_force(0.0, 0.5, 1.0, -0.5, 1e-12, try_at);
  EXPECT_EQ(r.outcome, Outcome::try_failed);
  EXPECT_EQ(r.tries, 2);
  EXPECT_EQ(calls, 2);
  EXPECT_DOUBLE_EQ(r.s, 2.0 / 3.0); // where the second try was
}

TEST(ZeroForceSearch, SearchThatDoesNotEndWithinItsTriesIsNotFound)
{
  Force f{[](double s) { return 0.5 - s * s; }};
  const ZeroForceResult r = find_zero_force(0.0, 0.5, 1.0, -0.5, 1e-14, f.try_at(), 3);
  EXPECT_EQ(r.outcome, Outcome::not_found);
  EXPECT_EQ(r.tries, 3);
  EXPECT_EQ(f.tried.size(), 3u);
  EXPECT_DOUBLE_EQ(r.s, 8.0 / 11.0); // the last try
  EXPECT_GT(std::abs(f.P(r.s)), 1e-14);
}

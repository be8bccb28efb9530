// The steps a path-following or dissipation-controlled stage may take
// (stepping/StepLoopShared.h, path_step_limit): 20 per nominal step and 100
// more, as many times more as IMPL-EX's tolerance is below 0.01, the
// tolerance the limit was set for (a first-order error: a k times finer
// tolerance asks for k times the steps where the cracks grow).
#include "stepping/StepLoopShared.h"
#include <gtest/gtest.h>

using pushout::stepping::detail::path_step_limit;

TEST(PathStepLimit, TwentyPerNominalStepWithoutImplexCracks)
{
  EXPECT_EQ(path_step_limit(20, 0.0), 500);
  EXPECT_EQ(path_step_limit(1, 0.0), 120);
}

TEST(PathStepLimit, GrowsAsTheImplexToleranceFalls)
{
  EXPECT_EQ(path_step_limit(20, 0.01), 500);
  EXPECT_EQ(path_step_limit(20, 0.05), 500);    // a coarser tolerance: never fewer
  EXPECT_EQ(path_step_limit(20, 0.0025), 2000); // the default: 4 times
  EXPECT_EQ(path_step_limit(20, 0.003), 2000);  // 3.3 times, rounded up
  EXPECT_EQ(path_step_limit(20, 0.001), 5000);
}

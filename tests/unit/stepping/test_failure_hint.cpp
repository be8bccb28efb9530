// What a step that no cut passed adds to its message (stepping/
// StepLoopShared.h, failure_hint): implicit cracks are pointed to IMPL-EX
// before anything else, since dissipation control, the snap-back's hint,
// stalls on the same cracks (docs/cracking.md, "Still to come" 3); a
// snap-back under displacement control to the control that follows it.
// Implicit cracks are also told to hold their steps to their error
// (unless they are) or to run again with smaller steps: the corroded
// study's three stopped runs passed both ways (docs/cracking.md, "The
// implicit cracks' step error"), where no cut of the stopped step did.
#include "stepping/StepLoopShared.h"
#include <gtest/gtest.h>

using pushout::stepping::detail::failure_hint;

namespace
{
bool says(const std::string& hint, const std::string& what)
{
  return hint.find(what) != std::string::npos;
}
} // namespace

TEST(FailureHint, ImplicitCracksArePointedToImplexFirst)
{
  for (const bool snap_back : {false, true})
    for (const bool monotonic : {false, true})
    {
      for (const bool held : {false, true})
      {
        const std::string hint = failure_hint(true, held, snap_back, monotonic);
        EXPECT_TRUE(says(hint, "cracking.integration = \"implex\"")) << hint;
        EXPECT_TRUE(says(hint, "four times the steps, corrosion.steps and loading.steps")) << hint;
        EXPECT_EQ(says(hint, "cracking.implicit_tolerance = 0.0025"), !held) << hint;
        EXPECT_FALSE(says(hint, "loading.control")) << hint;
        EXPECT_FALSE(says(hint, "viscosity lets")) << hint;
      }
    }
}

TEST(FailureHint, SnapBackUnderDisplacementControlGetsItsControl)
{
  EXPECT_TRUE(says(failure_hint(false, false, true, true), "loading.control = \"auto\""));
  EXPECT_TRUE(says(failure_hint(false, false, true, false), "damage viscosity"));
  EXPECT_FALSE(says(failure_hint(false, false, true, false), "loading.control"));
}

TEST(FailureHint, NoneWhereNeitherApplies)
{
  EXPECT_EQ(failure_hint(false, false, false, true), "");
  EXPECT_EQ(failure_hint(false, false, false, false), "");
}

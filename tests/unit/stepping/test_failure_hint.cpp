// What a step that no cut passed adds to its message (stepping/
// StepLoopShared.h, failure_hint): implicit cracks are pointed to IMPL-EX
// before anything else, since dissipation control, the snap-back's hint,
// stalls on the same cracks (docs/cracking.md, "Still to come" 3); a
// snap-back under displacement control to the control that follows it.
// Implicit cracks are also told to hold their steps to their error
// (unless they are) or to run again with smaller steps: the corroded
// study's three stopped runs passed both ways (docs/cracking.md, "The
// implicit cracks' step error"), where no cut of the stopped step did.
// With a damage viscosity only the steps apply.
#include "stepping/StepLoopShared.h"
#include <gtest/gtest.h>

using pushout::stepping::detail::failure_hint;
using Cracks = pushout::stepping::detail::FailureCase::Cracks;
using Rescue = pushout::stepping::detail::FailureCase::Rescue;

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
        for (const Rescue rescue : {Rescue::none, Rescue::not_tried})
        {
          const std::string hint =
              failure_hint({.cracks = held ? Cracks::implicit_held : Cracks::implicit,
                            .rescue = rescue,
                            .may_snap_back = snap_back,
                            .monotonic = monotonic});
          EXPECT_TRUE(says(hint, "cracking.integration = \"implex\"")) << hint;
          EXPECT_EQ(says(hint, "cracking.implex_rescue = true"), rescue == Rescue::not_tried)
              << hint;
          EXPECT_TRUE(says(hint, "four times the steps, corrosion.steps and loading.steps"))
              << hint;
          EXPECT_EQ(says(hint, "cracking.implicit_tolerance = 0.0025"), !held) << hint;
          EXPECT_FALSE(says(hint, "loading.control")) << hint;
          EXPECT_FALSE(says(hint, "viscosity lets")) << hint;
        }
    }
}

// With a damage viscosity neither IMPL-EX nor the step error may be set
// (the scene is refused): the hint names the steps alone.
TEST(FailureHint, ViscousImplicitCracksAreToldOfTheStepsAlone)
{
  const std::string hint =
      failure_hint({.cracks = Cracks::implicit_viscous, .may_snap_back = true});
  EXPECT_TRUE(says(hint, "four times the steps, corrosion.steps and loading.steps together"))
      << hint;
  EXPECT_FALSE(says(hint, "implex")) << hint;
  EXPECT_FALSE(says(hint, "IMPL-EX")) << hint;
  EXPECT_FALSE(says(hint, "implicit_tolerance")) << hint;
  EXPECT_FALSE(says(hint, "loading.control")) << hint;
}

TEST(FailureHint, SnapBackUnderDisplacementControlGetsItsControl)
{
  EXPECT_TRUE(says(failure_hint({.may_snap_back = true}), "loading.control = \"auto\""));
  EXPECT_TRUE(says(failure_hint({.may_snap_back = true, .monotonic = false}), "damage viscosity"));
  EXPECT_FALSE(says(failure_hint({.may_snap_back = true, .monotonic = false}), "loading.control"));
}

TEST(FailureHint, NoneWhereNeitherApplies)
{
  EXPECT_EQ(failure_hint({}), "");
  EXPECT_EQ(failure_hint({.monotonic = false}), "");
}

// An implicit cracks' step that failed as one IMPL-EX step too
// (cracking.implex_rescue) is not pointed to IMPL-EX again, nor to the
// step error: smaller steps are what is left.
TEST(FailureHint, AFailedRescueIsToldOfTheSteps)
{
  const std::string hint =
      failure_hint({.cracks = Cracks::implicit, .rescue = Rescue::failed, .may_snap_back = true});
  EXPECT_TRUE(says(hint, "failed as one IMPL-EX step too")) << hint;
  EXPECT_TRUE(says(hint, "four times the steps, corrosion.steps and loading.steps")) << hint;
  EXPECT_FALSE(says(hint, "cracking.integration")) << hint;
  EXPECT_FALSE(says(hint, "implicit_tolerance")) << hint;
  EXPECT_FALSE(says(hint, "loading.control")) << hint;
}

// build_or_release (common/build_or_release.h): a constructor's work that
// throws gives back what it got, and the error goes on unchanged; work that
// succeeds releases nothing.
#include "common/build_or_release.h"
#include <gtest/gtest.h>
#include <stdexcept>

using pushout::build_or_release;

TEST(BuildOrRelease, ReleasesWhatWasGotAndRethrowsTheError)
{
  int got = 0, released = 0;
  try
  {
    build_or_release(
        [&]
        {
          got = 2; // part of the work done
          throw std::runtime_error("the third part failed");
        },
        [&] { released = got; });
    FAIL() << "the error did not go on";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_STREQ(e.what(), "the third part failed");
  }
  EXPECT_EQ(released, 2);
}

TEST(BuildOrRelease, WorkThatSucceedsReleasesNothing)
{
  bool built = false, released = false;
  build_or_release([&] { built = true; }, [&] { released = true; });
  EXPECT_TRUE(built);
  EXPECT_FALSE(released);
}

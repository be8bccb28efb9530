// A piecewise-linear load path (specimen/LoadPath.h), here the push along
// 0 -> 10 um -> 4 um (unloading) -> 20 um in 4 nominal steps per segment:
// its value and length at each load parameter, the segment of a step, and
// an unloading segment ended early (where the push force falls to zero).
#include "scene/SceneError.h"
#include "specimen/LoadPath.h"
#include <gtest/gtest.h>
#include <string>
#include <vector>

using pushout::specimen::LoadPath;

namespace
{
LoadPath loop()
{
  return LoadPath({0.0, 0.01, 0.004, 0.02}, 4);
} // [mm]
} // namespace

TEST(LoadPath, SegmentsAndSteps)
{
  const LoadPath path = loop();
  EXPECT_FALSE(path.empty());
  EXPECT_EQ(path.segments(), 3u);
  EXPECT_EQ(path.steps(), 12);
  const LoadPath none;
  EXPECT_TRUE(none.empty());
  EXPECT_EQ(none.segments(), 0u);
  EXPECT_EQ(none.steps(), 0);
}

TEST(LoadPath, PiecewiseLinearValue)
{
  const LoadPath path = loop();
  EXPECT_DOUBLE_EQ(path.value(0.0), 0.0);
  EXPECT_DOUBLE_EQ(path.value(2.0), 0.005);
  EXPECT_DOUBLE_EQ(path.value(4.0), 0.01); // a vertex
  EXPECT_DOUBLE_EQ(path.value(6.0), 0.007);
  EXPECT_DOUBLE_EQ(path.value(8.0), 0.004);
  EXPECT_DOUBLE_EQ(path.value(9.0), 0.008);
  EXPECT_DOUBLE_EQ(path.value(12.0), 0.02); // the end
}

TEST(LoadPath, SegmentOfALoadParameterAndOfAStep)
{
  const LoadPath path = loop();
  EXPECT_EQ(path.segment_at(0.0), 0u);
  EXPECT_EQ(path.segment_at(3.5), 0u);
  EXPECT_EQ(path.segment_at(4.0), 0u); // a vertex: the segment it ends
  EXPECT_EQ(path.segment_at(4.5), 1u);
  EXPECT_EQ(path.segment_at(8.0), 1u);
  EXPECT_EQ(path.segment_at(12.0), 2u); // the end: the last segment
  EXPECT_EQ(path.segment_at(-1.0), 0u);
  for (int k = 1; k <= 12; ++k) // step k: from k - 1 to k
    EXPECT_EQ(path.segment_of_step(k), std::size_t((k - 1) / 4)) << "step " << k;
  EXPECT_FALSE(path.decreasing(0));
  EXPECT_TRUE(path.decreasing(1)); // the unloading
  EXPECT_FALSE(path.decreasing(2));
}

TEST(LoadPath, LengthTravelled)
{
  const LoadPath path = loop();
  EXPECT_DOUBLE_EQ(path.length_to(0.0), 0.0);
  EXPECT_DOUBLE_EQ(path.length_to(4.0), 0.01);
  EXPECT_DOUBLE_EQ(path.length_to(6.0), 0.013); // unloading counts too
  EXPECT_DOUBLE_EQ(path.length_to(8.0), 0.016);
  EXPECT_DOUBLE_EQ(path.length_to(12.0), 0.032);
}

TEST(LoadPath, UnloadingEndedEarlyStartsTheNextSegmentThere)
{
  LoadPath path = loop();
  // The push force falls to zero at s = 6 (delta = 7 um) in the unloading
  // segment: the segment ends there, and the path goes on from its end.
  const double s_next = path.end_segment(1, 6.0);
  EXPECT_EQ(s_next, 8.0);
  EXPECT_DOUBLE_EQ(path.value(8.0), 0.007);
  EXPECT_EQ(path.segments(), 3u);
  EXPECT_EQ(path.steps(), 12);
  EXPECT_TRUE(path.decreasing(1));
  EXPECT_DOUBLE_EQ(path.value(10.0), 0.0135); // the reload from 7 um to 20 um
  EXPECT_DOUBLE_EQ(path.value(12.0), 0.02);
  EXPECT_DOUBLE_EQ(path.length_to(8.0), 0.013);
  EXPECT_DOUBLE_EQ(path.length_to(12.0), 0.026);
}

TEST(LoadPath, UnloadingEndedEarlySkipsTheUnloadingsAfterIt)
{
  // 0 -> 30 -> 5 -> 0 -> 50 um in 4 steps a segment: the force falls to zero
  // at s = 6 (delta = 17.5 um) in the first unloading; the second (to 0)
  // would pull, and ends there too: the path goes on at s = 12, reloading
  // from 17.5 um (it searched a zero again 1e-12 mm further, and wrote a
  // second permanent displacement).
  LoadPath path({0.0, 0.03, 0.005, 0.0, 0.05}, 4);
  EXPECT_EQ(path.end_segment(1, 6.0), 12.0);
  EXPECT_DOUBLE_EQ(path.value(8.0), 0.0175);
  EXPECT_DOUBLE_EQ(path.value(12.0), 0.0175);
  EXPECT_FALSE(path.decreasing(2)); // a segment of no length
  EXPECT_DOUBLE_EQ(path.value(16.0), 0.05);
  EXPECT_DOUBLE_EQ(path.length_to(16.0), 0.03 + 0.0125 + 0.0325);
  // A segment after it that loads is not ended, nor the unloading after
  // that (to 10 um, below the zero: its own zero is searched for there).
  LoadPath above({0.0, 0.03, 0.005, 0.02, 0.01}, 4);
  EXPECT_EQ(above.end_segment(1, 6.0), 8.0);
  EXPECT_DOUBLE_EQ(above.value(12.0), 0.02);
  EXPECT_DOUBLE_EQ(above.value(16.0), 0.01);
}

TEST(LoadPath, PathKeysChecked)
{
  // push_path and shear_path alike: a segment at least, from 0, and at most
  // 100000 steps on all segments (loading.steps_per_segment's bound).
  using pushout::specimen::check_load_path;
  const auto refused = [](const std::vector<double>& path, std::int64_t per_segment)
  {
    try
    {
      check_load_path("loading.shear_path", path, per_segment);
    }
    catch (const pushout::SceneError& e)
    {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(refused({0.0, 0.02, 0.0}, 20), "");
  EXPECT_EQ(refused({0.0, -0.01}, 100000), "");
  EXPECT_NE(refused({0.0}, 20).find("'loading.shear_path' has no segment"), std::string::npos);
  EXPECT_NE(refused({}, 20).find("has no segment"), std::string::npos);
  EXPECT_NE(refused({0.1, 0.2}, 20).find("must start at 0"), std::string::npos);
  EXPECT_NE(refused({0.0, 0.01, 0.0, 0.01}, 40000).find("120000 steps, more than 100000"),
            std::string::npos);
}

// A sweep's --vary option (study/Sweep.h): its values split at the commas
// outside [ ], each integer in one spelling.
#include "scene/SceneError.h"
#include "study/Sweep.h"
#include <gtest/gtest.h>

using pushout::SceneError;
using pushout::study::cartesian_cases;
using pushout::study::parse_variation;
using pushout::study::Variation;

TEST(SweepVariation, ValuesSplitAtCommasOutsideArrays)
{
  const Variation v = parse_variation("crack.0.angles=[0,90],[45, 135],\"a,b\"");
  EXPECT_EQ(v.key, "crack.0.angles");
  // A comma in a quoted string splits it: a --vary value holds no comma
  // outside [ ].
  EXPECT_EQ(v.values, (std::vector<std::string>{"[0,90]", "[45, 135]", "\"a", "b\""}));
  EXPECT_EQ(parse_variation("interface.0.mu=0.3,0.45").values,
            (std::vector<std::string>{"0.3", "0.45"}));
}

TEST(SweepVariation, IntegersInDecimalFloatsAndWordsAsTyped)
{
  EXPECT_EQ(parse_variation("cracking.seed=0x10,0o20,0b10000,1_6,16,+7,-3").values,
            (std::vector<std::string>{"16", "16", "16", "16", "16", "7", "-3"}));
  // Not TOML integers: kept as typed (the scene reads or refuses them).
  EXPECT_EQ(parse_variation("k=1e3,0.50,007,1__0,0x,inf,word").values,
            (std::vector<std::string>{"1e3", "0.50", "007", "1__0", "0x", "inf", "word"}));
}

TEST(SweepVariation, MalformedOptionsAreRefused)
{
  for (const char* text : {"mu", "=0.3", "mu=", "mu=0.3,", "mu=,0.3", "k=[1,2"})
    EXPECT_THROW(parse_variation(text), SceneError) << text;
}

TEST(SweepVariation, CasesVaryTheLastKeyFastest)
{
  const auto cases = cartesian_cases({{"a", {"1", "2"}}, {"b", {"x", "y"}}});
  ASSERT_EQ(cases.size(), 4u);
  EXPECT_EQ(cases[1], (std::vector<std::string>{"a=1", "b=y"}));
  EXPECT_EQ(cases[2], (std::vector<std::string>{"a=2", "b=x"}));
}

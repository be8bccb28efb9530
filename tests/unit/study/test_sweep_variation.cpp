// A sweep's --vary option (study/Sweep.h): its values split at the commas
// outside [ ] and quotes, each integer in one spelling.
#include "scene/SceneError.h"
#include "study/Sweep.h"
#include <gtest/gtest.h>

using pushout::SceneError;
using pushout::study::cartesian_cases;
using pushout::study::parse_variation;
using pushout::study::Variation;

TEST(SweepVariation, ValuesSplitAtCommasOutsideArrays)
{
  const Variation v = parse_variation("crack.0.angles=[0,90],[45, 135]");
  EXPECT_EQ(v.key, "crack.0.angles");
  EXPECT_EQ(v.values, (std::vector<std::string>{"[0,90]", "[45, 135]"}));
  EXPECT_EQ(parse_variation("interface.0.mu=0.3,0.45").values,
            (std::vector<std::string>{"0.3", "0.45"}));
}

TEST(SweepVariation, QuotedStringsKeepTheirCommasAndBrackets)
{
  // TOML's strings, basic (with escapes) and literal: a path with a comma
  // is one value.
  EXPECT_EQ(parse_variation(R"(mesh.file="a,b.msh",'c,[d.msh',"e\",f",g)").values,
            (std::vector<std::string>{R"("a,b.msh")", "'c,[d.msh'", R"("e\",f")", "g"}));
  // A literal string has no escapes: its backslash ends nothing.
  EXPECT_EQ(parse_variation(R"(k='a\',b)").values, (std::vector<std::string>{R"('a\')", "b"}));
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
  for (const char* text : {"mu", "=0.3", "mu=", "mu=0.3,", "mu=,0.3", "k=[1,2", "k=\"a,b", "k='a"})
    EXPECT_THROW(parse_variation(text), SceneError) << text;
}

TEST(SweepVariation, CasesVaryTheLastKeyFastest)
{
  const auto cases = cartesian_cases({{"a", {"1", "2"}}, {"b", {"x", "y"}}});
  ASSERT_EQ(cases.size(), 4u);
  EXPECT_EQ(cases[1], (std::vector<std::string>{"a=1", "b=y"}));
  EXPECT_EQ(cases[2], (std::vector<std::string>{"a=2", "b=x"}));
}

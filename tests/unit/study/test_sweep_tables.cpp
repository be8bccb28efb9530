// The seeds as error bars of `pushout sweep` (study/SweepTables.h): the
// cases that differ only in cracking.seed are one group, whose statistics
// count the converged seeds alone.
#include "../../../cpp/study/SweepTables.h"
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <unistd.h>

using namespace pushout::study;

namespace
{
// mu x seed x dT: 2 x 3 x 2 cases, the seed in the middle of the --vary
// options; case i's numbers are {i, 10 i}.
struct ThreeKeys : ::testing::Test
{
  std::vector<Variation> vary = {{"interface.0.mu", {"0.2", "0.4"}},
                                 {"cracking.seed", {"1", "2", "3"}},
                                 {"loading.temperature_change", {"-5", "-25"}}};
  std::vector<std::vector<std::string>> cases = cartesian_cases(vary);
  std::vector<CaseNumbers> numbers;
  std::vector<CaseState> states = std::vector<CaseState>(12, CaseState::converged);
  ThreeKeys()
  {
    for (std::size_t i = 0; i < cases.size(); ++i)
      numbers.push_back({double(i), 10.0 * double(i)});
  }
};
} // namespace

TEST_F(ThreeKeys, GroupsAreTheOtherKeysValuesInTheOrderOfTheirFirstCase)
{
  ASSERT_TRUE(varies_seed(vary));
  const std::vector<SeedGroup> groups = group_seeds(vary, cases, numbers, states);
  ASSERT_EQ(groups.size(), 4u);
  const std::vector<std::vector<std::string>> expected = {
      {"0.2", "-5"}, {"0.2", "-25"}, {"0.4", "-5"}, {"0.4", "-25"}};
  for (std::size_t g = 0; g < 4; ++g)
  {
    EXPECT_EQ(groups[g].values, expected[g]);
    EXPECT_EQ(groups[g].seeds, 3);
    EXPECT_EQ(groups[g].converged, 3);
  }
  // mu 0.2, dT -25: cases 1, 3, 5 (the last key varies fastest).
  EXPECT_DOUBLE_EQ(groups[1].mean[0], 3.0);
  EXPECT_DOUBLE_EQ(groups[1].min[0], 1.0);
  EXPECT_DOUBLE_EQ(groups[1].max[0], 5.0);
  EXPECT_DOUBLE_EQ(groups[1].mean[1], 30.0);
  // mu 0.4, dT -5: cases 6, 8, 10.
  EXPECT_DOUBLE_EQ(groups[2].mean[0], 8.0);
  EXPECT_DOUBLE_EQ(groups[2].min[1], 60.0);
  EXPECT_DOUBLE_EQ(groups[2].max[1], 100.0);
}

TEST_F(ThreeKeys, CasesThatDidNotConvergeAreCountedButNotAveraged)
{
  states[3] = CaseState::failed; // mu 0.2, seed 2, dT -25
  numbers[3] = {1e9, 1e9};
  states[1] = states[5] = CaseState::failed; // and the group's two others
  states[6] = CaseState::failed;             // mu 0.4, seed 1, dT -5
  states[10] = CaseState::not_run;           // mu 0.4, seed 3, dT -5
  numbers[8][1] = std::nan("");              // mu 0.4, seed 2, dT -5: a number missing
  const std::vector<SeedGroup> groups = group_seeds(vary, cases, numbers, states);
  EXPECT_EQ(groups[1].seeds, 3);
  EXPECT_EQ(groups[1].converged, 0);
  EXPECT_TRUE(std::isnan(groups[1].mean[0]) && std::isnan(groups[1].min[0]) &&
              std::isnan(groups[1].max[1]));
  // mu 0.4, dT -5: case 6 failed, 8 converged, 10 did not run.
  EXPECT_EQ(groups[2].seeds, 2);
  EXPECT_EQ(groups[2].converged, 1);
  EXPECT_DOUBLE_EQ(groups[2].mean[0], 8.0);
  EXPECT_DOUBLE_EQ(groups[2].min[0], 8.0);
  EXPECT_TRUE(std::isnan(groups[2].mean[1]) && std::isnan(groups[2].min[1]) &&
              std::isnan(groups[2].max[1]));
}

TEST(SweepTables, OneSeedValueOrNoSeedKeyMakesNoGroups)
{
  EXPECT_FALSE(varies_seed({{"interface.0.mu", {"0.2", "0.4"}}}));
  EXPECT_FALSE(varies_seed({{"cracking.seed", {"1"}}, {"interface.0.mu", {"0.2", "0.4"}}}));
  EXPECT_TRUE(varies_seed({{"cracking.seed", {"1", "2"}}}));
  // The seed alone: one group with no other values.
  const std::vector<Variation> vary = {{"cracking.seed", {"1", "2"}}};
  const auto groups = group_seeds(vary, cartesian_cases(vary), {{1.0}, {2.0}},
                                  {CaseState::converged, CaseState::converged});
  ASSERT_EQ(groups.size(), 1u);
  EXPECT_TRUE(groups[0].values.empty());
  EXPECT_DOUBLE_EQ(groups[0].mean[0], 1.5);
}

// sweep.csv's numbers from case folders written here: the peak is of the
// load steps (step 0's row, the thermal step, is not one of them, however
// large), a case stopped at step 0 has no peak, and p and the crack width
// are the push's start.
TEST(SweepTables, ThePeakIsOfTheLoadStepsAlone)
{
  const std::filesystem::path out =
      std::filesystem::temp_directory_path() /
      ("pushout_sweep_tables_" + std::to_string(::getpid())); // one per test process
  std::filesystem::remove_all(out);
  auto write = [&](const std::string& name, const std::string& curve, const std::string& summary)
  {
    std::filesystem::create_directories(out / name);
    std::ofstream(out / name / "curve.csv") << curve;
    std::ofstream(out / name / "summary.json") << summary;
  };
  write("case_000",
        "step,delta_mm,tau_MPa,p_MPa\n0,0,9,4.5\n1,0.01,1.5,4.4\n2,0.02,2.5,4.3\n3,0.03,2,4.2\n",
        R"({"surface_crack_width_mm": 0.125})");
  write("case_001", "step,delta_mm,tau_MPa,p_MPa\n0,0,7,4.0\n", "{}");
  const std::vector<Variation> vary = {{"interface.0.mu", {"0.3", "0.4"}}};
  std::vector<CaseResult> results(2);
  results[0].index = 0;
  results[0].exit_code = 0;
  results[1].index = 1;
  results[1].exit_code = 3;
  results[1].message = "step 1: Newton did not converge, \"cut\" 10 times";
  write_tables(out, "pushout", vary, cartesian_cases(vary), results);

  std::ifstream in(out / "sweep.csv");
  std::string header, row0, row1;
  std::getline(in, header);
  std::getline(in, row0);
  std::getline(in, row1);
  EXPECT_EQ(header, "case,interface.0.mu,peak_tau_MPa,delta_at_peak_mm,tau_last_MPa,"
                    "delta_last_mm,p_before_push_MPa,crack_width_mm,steps,converged,exit_code,"
                    "wall_s,message");
  EXPECT_EQ(row0, "case_000,0.3,2.5,0.02,2,0.03,4.5,0.125,3,1,0,0,");
  // No load step: no peak, its last point step 0's; the message quoted.
  EXPECT_EQ(row1, "case_001,0.4,nan,nan,7,0,4,nan,0,0,3,0,"
                  "\"step 1: Newton did not converge, \"\"cut\"\" 10 times\"");
  EXPECT_FALSE(std::filesystem::exists(out / "sweep_seeds.csv"));
  std::filesystem::remove_all(out);
}

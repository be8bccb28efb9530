// No converged step is written with a value that is not a number: the
// recorder's check (record/NonFinite.h) names the column and stops the run,
// and the curve writer (output/CurveWriter.h) refuses such a row on its own.
#include "output/CurveWriter.h"
#include "record/NonFinite.h"
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <limits>
#include <string>
#include <unistd.h>

using namespace pushout;

TEST(Recorder, NonFiniteValueStopsTheRun)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NO_THROW(record::refuse_non_finite({0.0, 1.0, -2.5}, {"delta_mm", "P_N", "tau_MPa"},
                                            "step 1", MPI_COMM_WORLD));
  for (const double bad : {nan, std::numeric_limits<double>::infinity()})
  {
    try
    {
      record::refuse_non_finite({0.01, bad, 1.0}, {"delta_mm", "P_N", "tau_MPa"}, "step 2",
                                MPI_COMM_WORLD);
      ADD_FAILURE() << "a non-finite P_N was accepted";
    }
    catch (const record::NonFiniteResult& e)
    {
      const std::string what = e.what();
      EXPECT_NE(what.find("step 2"), std::string::npos) << what;
      EXPECT_NE(what.find("P_N"), std::string::npos) << what;
    }
  }
}

TEST(Recorder, CurveWriterRefusesANonFiniteRow)
{
  const auto file = std::filesystem::temp_directory_path() /
                    ("pushout-test-curve-" + std::to_string(::getpid()) + ".csv");
  {
    output::CurveWriter curve(file, {"delta_mm", "P_N"});
    curve.row(0, {0.0, 1.0});
    EXPECT_THROW(curve.row(1, {0.01, std::numeric_limits<double>::quiet_NaN()}),
                 std::runtime_error);
    EXPECT_THROW(curve.row(1, {-std::numeric_limits<double>::infinity(), 2.0}), std::runtime_error);
  }
  std::ifstream in(file);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "step,delta_mm,P_N\n0,0,1\n"); // the refused rows are not written
  std::filesystem::remove(file);
}

// A fit's measured curve (study/MeasuredCurve.h): read from its CSV text as
// spreadsheets write it, refused with the line that is wrong.
#include "scene/SceneError.h"
#include "study/MeasuredCurve.h"
#include <gtest/gtest.h>

using pushout::SceneError;
using pushout::study::MeasuredCurve;
using pushout::study::parse_measured;

TEST(MeasuredCurve, ReadAsSpreadsheetsWriteIt)
{
  // A byte order mark, CRLF line ends, another column, a blank line.
  const MeasuredCurve c = parse_measured(
      "\xEF\xBB\xBFnote,delta_mm,tau_MPa\r\na,0.0,-0.1\r\n\r\nb,0.01,1.5\r\nc,0.02,1.25\r\n",
      "data.csv");
  EXPECT_EQ(c.delta, (std::vector<double>{0.0, 0.01, 0.02}));
  EXPECT_EQ(c.tau, (std::vector<double>{-0.1, 1.5, 1.25}));
}

TEST(MeasuredCurve, RefusedWithWhatIsWrong)
{
  const std::pair<const char*, const char*> cases[] = {
      {"", "is empty"},
      {"delta_mm,tau\n0.01,1\n", "no column 'tau_MPa'"},
      {"delta_mm,tau_MPa\n", "has no rows"},
      {"delta_mm,tau_MPa\n0.01,abc\n", "line 2: tau_MPa 'abc' is not a number"},
      {"delta_mm,tau_MPa\n0.01,1\n0.02\n", "line 3: tau_MPa '' is not a number"},
      {"delta_mm,tau_MPa\n-0.01,1\n", "line 2: delta_mm -0.01 is negative"},
      {"delta_mm,tau_MPa\n0.02,1\n0.01,1\n", "line 3: delta_mm must increase"},
      {"delta_mm,tau_MPa\n0.01,-1\n0.02,0\n", "no tau_MPa above 0"},
      {"delta_mm,tau_MPa\n0,1\n", "the largest delta_mm must be > 0"}};
  for (const auto& [text, words] : cases)
  {
    try
    {
      parse_measured(text, "data.csv");
      ADD_FAILURE() << "accepted: " << text;
    }
    catch (const SceneError& e)
    {
      const std::string m = e.what();
      EXPECT_NE(m.find("--data 'data.csv'"), std::string::npos) << m;
      EXPECT_NE(m.find(words), std::string::npos) << m;
    }
  }
}

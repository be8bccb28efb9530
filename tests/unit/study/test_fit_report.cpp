// The error a fit that did not converge ends with (FitReport.h): what it
// says of refused runs depends on who refused them.
#include "study/FitReport.h"
#include <gtest/gtest.h>

using pushout::study::FitOutcome;
using pushout::study::not_converged_message;

namespace
{
FitOutcome refused(const std::string& why, bool by_size)
{
  FitOutcome fit;
  fit.reason = "DIVERGED_LS_FAILURE";
  fit.refused_runs = 3;
  fit.refusal = why;
  fit.refusal_by_size = by_size;
  return fit;
}
} // namespace

TEST(FitReport, ARelationBetweenKeysIsNamedWhereTheSceneRefusedRuns)
{
  const std::string m = not_converged_message(
      refused("'interface.1.f_fr' must not exceed 'interface.1.f_t'", false), "out/fit.json");
  EXPECT_NE(m.find("DIVERGED_LS_FAILURE"), std::string::npos) << m;
  EXPECT_NE(m.find("out/fit.json has where it stopped"), std::string::npos) << m;
  EXPECT_NE(m.find("3 runs were at values the scene refuses (one of them: 'interface.1.f_fr'"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("relation between keys"), std::string::npos) << m;
}

TEST(FitReport, TheSizeGuardsRefusalIsNotTakenForARelation)
{
  const std::string m =
      not_converged_message(refused("this run needs about 30 GB of memory, more than the 20 GB "
                                    "available here; --force runs it anyway",
                                    true),
                            "out/fit.json");
  EXPECT_NE(m.find("3 runs were refused (one of them: this run needs about 30 GB"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("could not hold"), std::string::npos) << m;
  EXPECT_EQ(m.find("relation between keys"), std::string::npos) << m;
  EXPECT_EQ(m.find("values the scene refuses"), std::string::npos) << m;
}

TEST(FitReport, FailedRunsAreCountedWithOneReason)
{
  FitOutcome fit;
  fit.reason = "DIVERGED_MAXITS";
  fit.failed_runs = 2;
  fit.failure = "Newton did not converge at step 4";
  const std::string m = not_converged_message(fit, "f/fit.json");
  EXPECT_NE(m.find("(DIVERGED_MAXITS; 2 runs did not converge: Newton did not converge at step 4)"),
            std::string::npos)
      << m;
  EXPECT_EQ(m.find("refuse"), std::string::npos) << m;
}

TEST(FitReport, AFittedRunThatDidNotConvergeIsNamed)
{
  FitOutcome fit;
  fit.reason = "CONVERGED_RELATIVE_OFFSET"; // TAO's: the fit itself converged
  fit.best_failure = "did not converge: step 12: Newton did not converge after 10 cuts";
  const std::string m = not_converged_message(fit, "out/fit.json");
  EXPECT_NE(m.find("the fitted run in out/best did not converge: step 12: Newton did not converge "
                   "after 10 cuts"),
            std::string::npos)
      << m;
  EXPECT_EQ(m.find("runs did not converge"), std::string::npos) << m;
}

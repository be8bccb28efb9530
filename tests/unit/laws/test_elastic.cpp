#include "law_testing.h"
#include "laws/Elastic.h"
#include <gtest/gtest.h>
#include <iostream>

using pushout::laws::Elastic;

TEST(Elastic, TractionIsEquation2)
{
  const Elastic law(200.0, 50.0);
  const auto r = law.update({}, {-0.01, 0.02, 0.03}, {});
  EXPECT_DOUBLE_EQ(r.t[0], -2.0);
  EXPECT_DOUBLE_EQ(r.t[1], 1.0);
  EXPECT_DOUBLE_EQ(r.t[2], 1.5);
}

TEST(Elastic, TangentMatchesFiniteDifferences)
{
  const Elastic law(1e3, 2e2);
  const double err = pushout::testing::tangent_error(law, {}, {0.001, -0.002, 0.0005}, 1e-7, 1.0);
  std::cout << "elastic: FD tangent error " << err << "\n";
  EXPECT_LT(err, 1e-6);
}

// Bates and Watts' relative offset (study/FitStatistics.h), against hand
// computations: the Gauss-Newton step still to go against the radius of the
// confidence region, the same whatever the scaling of the values; the
// gradient J^T r and the Gauss-Newton Hessian J^T J that TAO minimises with.
#include "../../../cpp/study/FitStatistics.h"
#include <cmath>
#include <gtest/gtest.h>

using pushout::study::relative_offset;

TEST(FitStatistics, RelativeOffsetOfOneValue)
{
  // One value fitting a constant: J = (1, 1, 1, 1), r = (1, -1, 2, 0) MPa.
  // P r is the mean 0.5 at each point: |P r|^2 = 1, |r - P r|^2 = 6 - 1 = 5,
  // so the offset is sqrt(1 / 1) / sqrt(5 / 3).
  const std::vector<double> J{1, 1, 1, 1}, r{1, -1, 2, 0};
  EXPECT_NEAR(relative_offset(J, r), 1 / std::sqrt(5.0 / 3.0), 1e-14);
  // Scaling the value (its column) leaves the projection as it is.
  EXPECT_NEAR(relative_offset({3, 3, 3, 3}, r), 1 / std::sqrt(5.0 / 3.0), 1e-14);
}

TEST(FitStatistics, RelativeOffsetOfTwoValues)
{
  // A line a + b t at t = 0, 1, 2, 3 (columns 1 and t), r = (1, 0, 0, 1):
  // J^T r = (2, 3), J^T J = [[4, 6], [6, 14]], |P r|^2 = (J^T r)^T (J^T
  // J)^-1 J^T r = (14*4 - 2*6*2*3 + 4*9) / 20 = 1, |r|^2 = 2.
  const std::vector<double> J{1, 1, 1, 1, 0, 1, 2, 3}, r{1, 0, 0, 1};
  EXPECT_NEAR(relative_offset(J, r), std::sqrt(1.0 / 2) / std::sqrt(1.0 / 2), 1e-14);
  // At the optimum (r orthogonal to both columns) nothing is left to go.
  EXPECT_NEAR(relative_offset(J, {1, -1, -1, 1}), 0.0, 1e-14);
}

TEST(FitStatistics, RelativeOffsetUndefined)
{
  // A value that does not change the curve (J^T J singular), residuals the
  // model meets exactly (in J's columns), no more points than values.
  EXPECT_TRUE(std::isinf(relative_offset({0, 0, 0}, {1, 2, 3})));
  EXPECT_TRUE(std::isinf(relative_offset({1, 1, 1}, {2, 2, 2})));
  EXPECT_TRUE(std::isinf(relative_offset({1}, {1})));
}

TEST(FitStatistics, GradientAndGaussNewtonHessian)
{
  // The line of RelativeOffsetOfTwoValues: J^T r = (2, 3) and J^T J = [[4,
  // 6], [6, 14]], by hand; TAO's gradient and Hessian of |r|^2 / 2.
  const std::vector<double> J{1, 1, 1, 1, 0, 1, 2, 3}, r{1, 0, 0, 1};
  EXPECT_EQ(pushout::study::transpose_times(J, r), (std::vector<double>{2, 3}));
  const auto H = pushout::study::normal_matrix(J.data(), 4, 2);
  EXPECT_EQ(H, (std::vector<std::vector<double>>{{4, 6}, {6, 14}}));
}

TEST(FitStatistics, AValueWithoutDerivativeHasNoStandardError)
{
  // Column 0 fits a constant (r of RelativeOffsetOfOneValue); column 1 holds
  // a refused run's misfit (1000 at two points) instead of a derivative.
  // Marked, b has no standard error and a has its own with b held: s^2 =
  // |r|^2 / (m - 1) = 6 / 3, se_a = sqrt(s^2 / 4).
  Mat J;
  ASSERT_EQ(MatCreateSeqDense(PETSC_COMM_SELF, 4, 2, nullptr, &J), 0);
  for (PetscInt i = 0; i < 4; ++i)
  {
    MatSetValue(J, i, 0, 1.0, INSERT_VALUES);
    MatSetValue(J, i, 1, i == 0 || i == 3 ? 1000.0 : 0.0, INSERT_VALUES);
  }
  MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY);
  const std::vector<double> r{1, -1, 2, 0}, x{0.5, 0.5};
  const std::vector<pushout::study::Free> free{{"a"}, {"b"}};
  const auto st = pushout::study::statistics(J, r, free, x, {false, true});
  EXPECT_NEAR(st.se[0], std::sqrt(2.0 / 4.0), 1e-14);
  EXPECT_TRUE(std::isinf(st.se[1]));
  EXPECT_TRUE(std::isnan(st.corr[0][1]) && std::isnan(st.corr[1][1]));
  ASSERT_EQ(st.warnings.size(), 1u);
  EXPECT_EQ(st.warnings[0].rfind("b = 0.5 has no standard error", 0), 0u) << st.warnings[0];
  MatDestroy(&J);
}

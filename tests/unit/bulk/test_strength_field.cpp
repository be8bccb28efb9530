// The random strength field (bulk/StrengthField.h): its statistics over
// seeds against the lognormal and the Gaussian correlation it declares, and
// its reproducibility (a pure function of position and seed).
#include "bulk/StrengthField.h"
#include <cmath>
#include <gtest/gtest.h>
#include <vector>

using pushout::bulk::StrengthField;

namespace
{
/// Sample mean and standard deviation.
std::array<double, 2> moments(const std::vector<double>& v)
{
  double mean = 0, square = 0;
  for (double x : v)
    mean += x;
  mean /= double(v.size());
  for (double x : v)
    square += (x - mean) * (x - mean);
  return {mean, std::sqrt(square / double(v.size() - 1))};
}
constexpr int seeds = 4000;
} // namespace

TEST(StrengthField, UniformWithoutScatter)
{
  const StrengthField field(0.0, 5.0, 1);
  EXPECT_EQ(field.factor({1, 2, 3}), 1.0);
}

TEST(StrengthField, LognormalOfMeanOneAndTheDeclaredScatterOverSeeds)
{
  // At one point, over 4000 seeds: s has mean 1 and std = cov. Tolerances:
  // 4 standard errors of the estimates (cov / sqrt(n) for the mean; about
  // cov / sqrt(2 n) times the lognormal's kurtosis factor for the std).
  for (double cov : {0.1, 0.2})
  {
    std::vector<double> s;
    for (int seed = 0; seed < seeds; ++seed)
      s.push_back(StrengthField(cov, 5.0, std::uint64_t(seed)).factor({12.5, -3.0, 7.0}));
    const auto [mean, sd] = moments(s);
    EXPECT_NEAR(mean, 1.0, 4 * cov / std::sqrt(double(seeds)));
    EXPECT_NEAR(sd, cov, 4 * 1.5 * cov / std::sqrt(2.0 * seeds));
    for (double x : s)
      EXPECT_GT(x, 0.0);
  }
}

TEST(StrengthField, GaussianCorrelationOverTheDeclaredLength)
{
  // corr(g(x), g(x + r e)) = exp(-(r/l)^2): at r = l, 0.368; at 3 l, 1e-4.
  // The sample correlation's standard error is (1 - rho^2) / sqrt(n): 4 of
  // them as tolerance.
  // Along each axis and a diagonal: a field constant along one of them (a
  // wave vector's component lost) would have correlation 1 there.
  const double l = 5.0;
  const std::array<double, 3> x = {3.0, 4.0, 5.0};
  for (const std::array<double, 3>& e :
       {std::array<double, 3>{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.6, 0, 0.8}})
    for (double r : {0.5 * l, l, 3 * l})
    {
      std::vector<double> a, b;
      for (int seed = 0; seed < seeds; ++seed)
      {
        const StrengthField field(0.2, l, std::uint64_t(seed));
        a.push_back(field.gaussian(x));
        b.push_back(field.gaussian({x[0] + r * e[0], x[1] + r * e[1], x[2] + r * e[2]}));
      }
      const auto [ma, sa] = moments(a);
      const auto [mb, sb] = moments(b);
      double cross = 0;
      for (int i = 0; i < seeds; ++i)
        cross += (a[i] - ma) * (b[i] - mb);
      const double rho = cross / ((seeds - 1) * sa * sb), expected = std::exp(-(r / l) * (r / l));
      EXPECT_NEAR(rho, expected, 4 * (1 - expected * expected) / std::sqrt(double(seeds)))
          << "r = " << r << " mm along (" << e[0] << ", " << e[1] << ", " << e[2] << ")";
    }
}

TEST(StrengthField, StandardGaussianEverywhereOverSeeds)
{
  // g has mean 0 and variance 1 at any point, the origin too (where every
  // mode's phase alone makes it: phases that were not uniform would show
  // there). Tolerances: 4 standard errors, 1 / sqrt(n) for the mean and
  // sqrt(2 / n) for the variance of a Gaussian.
  for (const std::array<double, 3>& x :
       {std::array<double, 3>{0, 0, 0}, {50.0, 25.0, 10.0}, {-7.0, 91.0, 0.5}})
  {
    std::vector<double> g;
    for (int seed = 0; seed < seeds; ++seed)
      g.push_back(StrengthField(0.2, 5.0, std::uint64_t(seed)).gaussian(x));
    const auto [mean, sd] = moments(g);
    EXPECT_NEAR(mean, 0.0, 4 / std::sqrt(double(seeds))) << x[0] << ", " << x[1] << ", " << x[2];
    EXPECT_NEAR(sd * sd, 1.0, 4 * std::sqrt(2.0 / seeds)) << x[0] << ", " << x[1] << ", " << x[2];
  }
}

TEST(StrengthField, SameSeedSameFieldAnywhere)
{
  const StrengthField a(0.15, 5.0, 42), b(0.15, 5.0, 42), c(0.15, 5.0, 43);
  const std::array<double, 3> x = {10.0, 20.0, 3.0};
  EXPECT_EQ(a.factor(x), b.factor(x));
  EXPECT_NE(a.factor(x), c.factor(x));
  // The field of seed 1 at one point, pinned: the generator (mt19937_64,
  // this file's Box-Muller) is specified to the bit, so any machine gives it
  // within libm's last-digit differences of cos, exp and log.
  EXPECT_NEAR(StrengthField(0.2, 5.0, 1).factor({1.0, 2.0, 3.0}), 0.91578885847411295, 1e-12);
}

// The mirror images of a direction in a symmetric model (mesh/symmetry.h):
// how a cut model's surface cracks count in the whole specimen.
#include "../../../cpp/mesh/symmetry.h"
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

using pushout::mesh::images_of;
using pushout::mesh::Symmetry;

namespace
{
constexpr double deg = std::numbers::pi / 180;

/// The directions in degrees, in [0, 360), sorted.
std::vector<double> degrees(const std::vector<double>& rays)
{
  std::vector<double> d;
  for (double r : rays)
    d.push_back(std::fmod(r / deg + 720, 360));
  std::sort(d.begin(), d.end());
  return d;
}

void expect_near(const std::vector<double>& got, const std::vector<double>& want)
{
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i)
    EXPECT_NEAR(got[i], want[i], 1e-9) << "image " << i;
}
} // namespace

TEST(Symmetry, ImagesOfARayOffThePlanesAreTheCopies)
{
  EXPECT_EQ(images_of({}, 30 * deg), std::vector<double>{30 * deg}); // full model: itself
  EXPECT_NEAR(images_of({true, true}, 30 * deg)[0], 30 * deg, 0);    // itself first
  // Half about x = xc (kept x >= xc), half about y = yc, a quarter.
  expect_near(degrees(images_of({true, false}, 30 * deg)), {30, 150});
  expect_near(degrees(images_of({false, true}, 30 * deg)), {30, 330});
  expect_near(degrees(images_of({true, true}, 30 * deg)), {30, 150, 210, 330});
}

TEST(Symmetry, ARayOnAPlaneIsItsOwnImageAboutIt)
{
  // The quarter's cracks along its planes (0 deg on y = yc, 90 deg on x = xc).
  expect_near(degrees(images_of({true, true}, 0)), {0, 180});
  expect_near(degrees(images_of({true, true}, 90 * deg)), {90, 270});
  expect_near(degrees(images_of({true, false}, 90 * deg)), {90});
  expect_near(degrees(images_of({false, true}, 0)), {0});
  // Within the planes' tolerance of the direction, as side_of decides.
  expect_near(degrees(images_of({true, true}, 90 * deg + 1e-12)), {90, 270});
}

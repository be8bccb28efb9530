#include "CrackPlanes.h"
#include "SceneError.h"
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

namespace pushout
{
namespace
{
constexpr double pi = std::numbers::pi;

/// a reduced to [0, 2 pi).
double turn(double a)
{
  a = std::fmod(a, 2 * pi);
  return a < 0 ? a + 2 * pi : a;
}

double degrees(double a)
{
  return a * 180 / pi;
}

} // namespace

/// The block corner directions: towards the square's corners from the tube
/// centre (so that every ray between two of them meets one side), or 45 +
/// 90 k degrees in a circle (slice.geo's, for a centred tube).
std::array<double, 4> corner_angles(const Geometry& g)
{
  if (g.circle)
    return {pi / 4, 3 * pi / 4, 5 * pi / 4, 7 * pi / 4};
  const double W = g.width, x = g.tube_center[0], y = g.tube_center[1];
  return {turn(std::atan2(W - y, W - x)), turn(std::atan2(W - y, -x)), turn(std::atan2(-y, -x)),
          turn(std::atan2(-y, W - x))};
}

std::array<std::array<double, 2>, 4> block_corners(const Geometry& g)
{
  const double W = g.width;
  if (!g.circle)
    return {{{W, W}, {0, W}, {0, 0}, {W, 0}}};
  std::array<std::array<double, 2>, 4> corners;
  for (std::size_t k = 0; k < 4; ++k)
    corners[k] = boundary_point(g, pi / 4 + double(k) * pi / 2);
  return corners;
}

double graded_line_angle(std::int64_t nq, std::size_t j)
{
  return pi / 4 + double(j) * pi / 2 / double(nq);
}

std::vector<std::array<double, 2>> radial_line_ends(const Geometry& g, std::int64_t nq)
{
  const std::size_t n = 4 * std::size_t(nq);
  const auto ray = [&](std::size_t j) { return graded_line_angle(nq, j); };
  std::vector<std::array<double, 2>> ends(n);
  for (std::size_t j = 0; j < n; ++j)
    ends[j] = boundary_point(g, ray(j));
  if (g.circle)
    return ends;
  const std::array<double, 4> corner = corner_angles(g);
  const auto corners = block_corners(g);
  // Each corner lies in its own quadrant of directions from the tube axis
  // (the +x+y corner between 0 and 90 degrees, ...), and its nearest ray
  // lies in that quadrant or on its edge, so two corners could share only a
  // ray on their quadrants' common edge (nq even): both within 45 / nq
  // degrees of it would put the tube farther from a side than the square
  // is wide (for the +y side: W - y >= cot(45 / nq degrees) max(x, W - x)
  // >= 1.2 W). So no line ends at two corners. A corner
  // midway between two rays goes to the one nearer its quadrant's middle,
  // so that a slice symmetric about the tube's axis keeps a symmetric mesh.
  for (std::size_t k = 0; k < 4; ++k)
  {
    const double middle = pi / 4 + double(k) * pi / 2;
    std::size_t nearest = 0;
    for (std::size_t j = 1; j < n; ++j)
    {
      const double d = angle_between(ray(j), corner[k]),
                   best = angle_between(ray(nearest), corner[k]);
      if (d < best - 1e-12 ||
          (d < best + 1e-12 && angle_between(ray(j), middle) < angle_between(ray(nearest), middle)))
        nearest = j;
    }
    ends[nearest] = corners[k];
  }
  return ends;
}

/// Where the ray from the tube centre at angle a meets the slice boundary.
std::array<double, 2> boundary_point(const Geometry& g, double a)
{
  const double W = g.width;
  const std::array<double, 2>& c = g.tube_center;
  const double dx = std::cos(a), dy = std::sin(a);
  if (g.circle)
    return {c[0] + W / 2 * dx, c[1] + W / 2 * dy};
  const double inf = std::numeric_limits<double>::infinity();
  const double tx = dx > 1e-14 ? (W - c[0]) / dx : dx < -1e-14 ? -c[0] / dx : inf;
  const double ty = dy > 1e-14 ? (W - c[1]) / dy : dy < -1e-14 ? -c[1] / dy : inf;
  const double t = std::min(tx, ty);
  return {c[0] + t * dx, c[1] + t * dy};
}
double angle_between(double a, double b)
{
  const double d = turn(a - b);
  return std::min(d, 2 * pi - d);
}

CrackDirections crack_directions(const Geometry& g, std::int64_t elements_per_quarter,
                                 const std::vector<CrackSpec>& cracks)
{
  CrackDirections d;
  if (cracks.empty())
    return d;
  const std::array<double, 4> corners = corner_angles(g);
  const double element = pi / 2 / double(elements_per_quarter); // angle of one interface element
  for (std::size_t i = 0; i < cracks.size(); ++i)
  {
    const std::string key = "crack." + std::to_string(i) + ".angle";
    double a;
    if (cracks[i].angle_deg)
      a = turn(*cracks[i].angle_deg * pi / 180);
    else
    {
      if (g.circle)
        throw SceneError("'" + key +
                         "' = \"nearest_face\" needs a square slice: every face of a "
                         "circular slice is equally near; give the angle in degrees");
      // Distances to the sides -y, +x, +y, -x (ties: the first).
      const double W = g.width, x = g.tube_center[0], y = g.tube_center[1];
      const std::array<double, 4> cover = {y, W - x, W - y, x};
      const std::array<double, 4> towards = {3 * pi / 2, 0, pi / 2, pi};
      a = towards[std::min_element(cover.begin(), cover.end()) - cover.begin()];
    }
    d.asked.push_back(a);
    bool snapped = false;
    for (double corner : corners)
      if (angle_between(a, corner) < element / 2)
      {
        snapped = angle_between(a, corner) > 1e-9;
        a = corner; // exactly, so that the sectors do not get a sliver
      }
    // A plane's angle as the scene gave it (not turned into [0, 360)).
    const auto given = [&](std::size_t k)
    {
      std::ostringstream s;
      s << "'crack." << k << ".angle' = ";
      if (cracks[k].angle_deg)
        s << *cracks[k].angle_deg << " deg";
      else
        s << "\"nearest_face\" (" << degrees(k == i ? a : d.angles[k]) << " deg)";
      return s.str();
    };
    for (std::size_t j = 0; j < d.angles.size(); ++j)
      if (angle_between(a, d.angles[j]) < element)
      {
        std::ostringstream m;
        m << given(i) << " is within one interface element (" << degrees(element) << " deg) of "
          << given(j) << ": two crack planes need at least one element between them";
        throw SceneError(m.str());
      }
    d.angles.push_back(a);
    d.snapped.push_back(snapped);
  }
  return d;
}

} // namespace pushout

#include "SurfaceCracks.h"
#include <algorithm>
#include <cmath>
#include <numbers>

namespace pushout::model
{
namespace
{
/// How far the crack at the face column `start` runs in towards the tube
/// axis: followed from column to column, each step to the widest cracked
/// column within one and a half column sizes that is nearer the axis by a
/// quarter of a column at least, until none is (the crack's tip). Its
/// length is the straight line from its mouth on the face to the last
/// column's centre, or on to the tube's surface if that is within a column
/// (the surface's point nearest that centre); `along` (a unit vector from
/// the axis): measured along that line instead, a crack on a symmetry
/// plane, whose path runs through the band beside the plane [mm].
double length_from(const FaceColumn& start, const std::vector<CrackColumn>& columns,
                   std::array<double, 2> axis, double tube_radius, double resolution,
                   const std::array<double, 2>* along)
{
  auto to_axis = [&](double x, double y) { return std::hypot(x - axis[0], y - axis[1]); };
  const CrackColumn* here = nullptr; // the face column among the concrete's
  for (const CrackColumn& c : columns)
    if (!here ||
        std::hypot(c.x - start.x, c.y - start.y) < std::hypot(here->x - start.x, here->y - start.y))
      here = &c;
  if (!here || !(here->opening >= resolution))
    return 0;
  for (std::size_t steps = 0; steps < columns.size(); ++steps)
  {
    const CrackColumn* next = nullptr;
    for (const CrackColumn& c : columns)
      if (c.opening >= resolution &&
          std::hypot(c.x - here->x, c.y - here->y) <= 1.5 * std::max(c.size, here->size) &&
          to_axis(c.x, c.y) <= to_axis(here->x, here->y) - here->size / 4 &&
          (!next || c.opening > next->opening))
        next = &c;
    if (!next)
      break;
    here = next;
  }
  const double r = to_axis(here->x, here->y);
  const bool to_tube = r - tube_radius <= here->size; // the tube's surface within a column
  if (along)                                          // distances from the axis along the plane
  {
    const auto [dx, dy] = *along;
    const double mouth = (start.mouth[0] - axis[0]) * dx + (start.mouth[1] - axis[1]) * dy;
    const double tip = to_tube ? tube_radius : (here->x - axis[0]) * dx + (here->y - axis[1]) * dy;
    return std::max(mouth - tip, 0.0);
  }
  const double scale = to_tube && r > 0 ? tube_radius / r : 1.0;
  const double tip_x = axis[0] + scale * (here->x - axis[0]),
               tip_y = axis[1] + scale * (here->y - axis[1]);
  return std::hypot(start.mouth[0] - tip_x, start.mouth[1] - tip_y);
}
} // namespace

std::vector<SurfaceCrack> surface_cracks(std::vector<FaceColumn> faces,
                                         const std::vector<CrackColumn>& columns,
                                         std::array<double, 2> axis, double tube_radius,
                                         double resolution, int copies)
{
  const bool cut = copies > 1;
  std::vector<SurfaceCrack> cracks;
  const std::size_t n = faces.size();
  if (n == 0)
    return cracks;
  std::sort(faces.begin(), faces.end(),
            [](const FaceColumn& a, const FaceColumn& b) { return a.angle < b.angle; });
  auto reads = [&](std::size_t i) { return faces[i % n].gauge >= resolution; };
  // A run of columns [first, end) (cyclic); `plane`: its column at a
  // symmetry plane, whose mirror image completes it (null: none);
  // `all_round`: the specimen's faces all round, `copies` of the run.
  auto add_run = [&](std::size_t first, std::size_t end, const FaceColumn* plane, bool all_round)
  {
    double width = 0;
    std::size_t widest = first % n;
    for (std::size_t i = first; i < end; ++i)
    {
      width += faces[i % n].gauge;
      if (faces[i % n].gauge > faces[widest].gauge)
        widest = i % n;
    }
    const FaceColumn& w = faces[widest];
    const double degrees = 180 / std::numbers::pi;
    double angle = std::atan2(w.y - axis[1], w.x - axis[0]) * degrees;
    if (plane) // along the plane: planes through the axis, along x or y
      angle = 90 * std::round(std::atan2(plane->y - axis[1], plane->x - axis[0]) * degrees / 90);
    if (angle < 0)
      angle += 360;
    const std::array<double, 2> along = {std::cos(angle / degrees), std::sin(angle / degrees)};
    cracks.push_back(
        {angle,
         (all_round ? copies
          : plane   ? 2
                    : 1) *
             width,
         length_from(w, columns, axis, tube_radius, resolution, plane ? &along : nullptr),
         all_round});
  };
  // One scan of the perimeter from `start`: on a cut model the column after
  // the widest gap between neighbours (the cut), which no run crosses; on a
  // closed one a column that reads nothing, so that no run is cut where the
  // angles wrap around.
  std::size_t start = 0;
  if (cut)
  {
    double widest_gap = -1;
    for (std::size_t i = 0; i < n; ++i)
    {
      const double next = i + 1 < n ? faces[i + 1].angle : faces[0].angle + 2 * std::numbers::pi;
      if (next - faces[i].angle > widest_gap)
      {
        widest_gap = next - faces[i].angle;
        start = (i + 1) % n;
      }
    }
  }
  else
    while (start < n && reads(start))
      ++start;
  if (!cut && start == n) // cracked all round: one run
    add_run(0, n, nullptr, true);
  else
    for (std::size_t k = start; k < start + n;)
    {
      if (!reads(k))
      {
        ++k;
        continue;
      }
      std::size_t end = k;
      while (end < start + n && reads(end))
        ++end;
      // From plane to plane: the specimen's faces all round, mirrored.
      if (cut && k == start && end == start + n)
      {
        add_run(k, end, nullptr, true);
        break;
      }
      const FaceColumn* plane = !cut               ? nullptr
                                : k == start       ? &faces[k % n]
                                : end == start + n ? &faces[(end - 1) % n]
                                                   : nullptr;
      add_run(k, end, plane, false);
      k = end;
    }
  std::sort(cracks.begin(), cracks.end(),
            [](const SurfaceCrack& a, const SurfaceCrack& b) { return a.width_mm > b.width_mm; });
  return cracks;
}
} // namespace pushout::model

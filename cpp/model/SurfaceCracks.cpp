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
/// quarter of a column at least, until none is (the crack's tip); its
/// length the straight distance from the face (`start.depth` outside the
/// first centre) to the last centre, and on to the tube's surface if that
/// is within a column [mm].
double length_from(const FaceColumn& start, const std::vector<CrackColumn>& columns,
                   std::array<double, 2> axis, double tube_radius, double resolution)
{
  auto to_axis = [&](double x, double y) { return std::hypot(x - axis[0], y - axis[1]); };
  const CrackColumn* here = nullptr; // the face column among the concrete's
  for (const CrackColumn& c : columns)
    if (!here ||
        std::hypot(c.x - start.x, c.y - start.y) < std::hypot(here->x - start.x, here->y - start.y))
      here = &c;
  if (!here || !(here->opening >= resolution))
    return 0;
  const CrackColumn* first = here;
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
  const double gap = to_axis(here->x, here->y) - tube_radius; // to the tube's surface [mm]
  return start.depth + std::hypot(here->x - first->x, here->y - first->y) +
         (gap <= here->size ? std::max(gap, 0.0) : 0.0);
}
} // namespace

std::vector<SurfaceCrack> surface_cracks(std::vector<FaceColumn> faces,
                                         const std::vector<CrackColumn>& columns,
                                         std::array<double, 2> axis, double tube_radius,
                                         double resolution, bool cut)
{
  std::vector<SurfaceCrack> cracks;
  const std::size_t n = faces.size();
  if (n == 0)
    return cracks;
  std::sort(faces.begin(), faces.end(),
            [](const FaceColumn& a, const FaceColumn& b) { return a.angle < b.angle; });
  auto reads = [&](std::size_t i) { return faces[i % n].gauge >= resolution; };
  // A run of columns [first, end) (cyclic); `plane`: its column at a
  // symmetry plane, whose mirror image completes it (null: none).
  auto add_run = [&](std::size_t first, std::size_t end, const FaceColumn* plane)
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
    cracks.push_back(
        {angle, (plane ? 2 : 1) * width, length_from(w, columns, axis, tube_radius, resolution)});
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
    add_run(0, n, nullptr);
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
      const FaceColumn* plane = !cut               ? nullptr
                                : k == start       ? &faces[k % n]
                                : end == start + n ? &faces[(end - 1) % n]
                                                   : nullptr;
      add_run(k, end, plane);
      k = end;
    }
  std::sort(cracks.begin(), cracks.end(),
            [](const SurfaceCrack& a, const SurfaceCrack& b) { return a.width_mm > b.width_mm; });
  return cracks;
}
} // namespace pushout::model

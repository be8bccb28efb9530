// The checks of [cracking] that need the mesh: the crack band's size
// condition (BandSizeCheck) and the cracking region (CrackBandCheck.h).
#include "CrackBandCheck.h"
#include "../bulk/StrengthField.h"
#include "../scene/SceneError.h"
#include "CrackingCells.h"
#include "cracking.h"
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace pushout::model
{
namespace
{
/// The width [mm] of cell c's nodes along each axis.
std::array<double, 3> extent(const mesh::MeshData& data, std::size_t c)
{
  std::array<double, 3> lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  for (int k = 0; k < 8; ++k)
    for (int d = 0; d < 3; ++d)
    {
      const double x = data.x[3 * std::size_t(data.cells[8 * c + k]) + d];
      lo[d] = std::min(lo[d], x);
      hi[d] = std::max(hi[d], x);
    }
  return {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
}

/// The position [mm] of reference point X in cell c: the trilinear map of
/// the hexahedron, its nodes in DOLFINx's order (vertex i at the corner
/// whose x, y, z are bits 0, 1, 2 of i).
std::array<double, 3> position(const mesh::MeshData& data, std::size_t c, const double* X)
{
  std::array<double, 3> p{0, 0, 0};
  for (int k = 0; k < 8; ++k)
  {
    double phi = 1;
    for (int d = 0; d < 3; ++d)
      phi *= (k >> d & 1) ? X[d] : 1 - X[d];
    for (int d = 0; d < 3; ++d)
      p[d] += phi * data.x[3 * std::size_t(data.cells[8 * c + k]) + d];
  }
  return p;
}

/// The concrete cells of `data` that may crack (CrackingCells.h's rule,
/// the centre's distance summed as there), and the least distance of a
/// concrete cell's centre from the axis [mm].
std::vector<std::size_t> cracking_cells(const mesh::MeshData& data, double radius,
                                        std::array<double, 2> axis, double& nearest)
{
  std::vector<std::size_t> cells;
  nearest = INFINITY;
  for (std::size_t c = 0; c < data.num_cells(); ++c)
  {
    if (data.material[c] != mesh::concrete)
      continue;
    double centre[2] = {0, 0};
    for (int k = 0; k < 8; ++k)
      for (int d = 0; d < 2; ++d)
        centre[d] += data.x[3 * std::size_t(data.cells[8 * c + k]) + d] / 8.0;
    const double distance = std::hypot(centre[0] - axis[0], centre[1] - axis[1]);
    nearest = std::min(nearest, distance);
    if (may_crack(distance, radius))
      cells.push_back(c);
  }
  return cells;
}
} // namespace

laws::Envelope envelope_of(const CrackingPart& part)
{
  if (part.linear_softening)
    return {laws::Envelope::Kind::linear, part.f_t, part.w_c2, 0.0, 0.0};
  return {laws::Envelope::Kind::exponential, part.f_t, 0.0, 0.0, part.c};
}

BandSizeCheck::BandSizeCheck(const bulk::CrackBand& band, const CrackingPart& part)
    : _band(band), _part(part), _mean_band(band.max_band_width(1.0))
{
}

void BandSizeCheck::add(double diagonal, std::array<double, 2> centre, double strength)
{
  const double width = _band.max_band_width(strength);
  if (diagonal / width > _worst)
  {
    _worst = diagonal / width;
    _where = {diagonal, width, centre[0], centre[1], strength};
  }
  _worst_mean = std::max(_worst_mean, diagonal / _mean_band);
}

void BandSizeCheck::agree(MPI_Comm comm)
{
  struct
  {
    double ratio;
    int rank;
  } worst{_worst, 0};
  MPI_Comm_rank(comm, &worst.rank);
  MPI_Allreduce(MPI_IN_PLACE, &worst, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm);
  MPI_Allreduce(MPI_IN_PLACE, &_worst_mean, 1, MPI_DOUBLE, MPI_MAX, comm);
  MPI_Bcast(_where.data(), int(_where.size()), MPI_DOUBLE, worst.rank, comm);
  _worst = worst.ratio;
}

void BandSizeCheck::refuse_if_too_wide(std::array<double, 2> axis) const
{
  if (_worst < 1)
    return;
  std::ostringstream why;
  why << std::setprecision(3) << "cracking: the concrete element at (" << _where[2] << ", "
      << _where[3] << ") mm, " << _where[0] << " mm across, is " << _worst
      << " times the widest band its crack can soften over there without snapping back ("
      << _where[1] << " mm: mu / |d sigma / d w|, docs/cracking.md)";
  if (_worst_mean < 1) // only where the field raises f_t
    why << ", at a point where the strength field (cracking.strength_cov = " << _part.strength_cov
        << ") raises f_t to " << _where[4] << " times its mean (at the mean f_t the largest "
        << "element is " << _worst_mean << " times the band)";
  why << ". A softening less steep widens the band: "
      << (_part.linear_softening ? "raise cracking.w_c2" : "lower cracking.c")
      << " (a larger G_F) or lower cracking.f_t (in MPa)"
      << (_worst_mean < 1 ? ", or lower cracking.strength_cov" : "")
      << "; or keep the largest elements linear with cracking.radius (this one's centre lies "
      << std::hypot(_where[2] - axis[0], _where[3] - axis[1])
      << " mm from the tube axis; the cracks then stop at the radius)";
  throw SceneError(why.str());
}

void check_cracking_mesh(const mesh::MeshData& data, const Material& concrete,
                         const CrackingPart& part, const Geometry& slice)
{
  if (!part.embedded)
    return;
  double nearest = INFINITY;
  const std::vector<std::size_t> cells =
      cracking_cells(data, part.radius, slice.tube_center, nearest);
  if (cells.empty())
    throw SceneError(takes_no_concrete(part.radius, nearest));
  const bulk::CrackBand band(concrete.E, concrete.nu, envelope_of(part), part.viscosity);
  const bulk::StrengthField field(part.strength_cov, part.correlation_length,
                                  std::uint64_t(part.seed));
  BandSizeCheck check(band, part);
  const int n_points = expression_cracking_position->num_points;
  const double* X = expression_cracking_position->points;
  constexpr std::array<double, 3> middle{0.5, 0.5, 0.5};
  for (const std::size_t c : cells)
  {
    const auto [dx, dy, dz] = extent(data, c);
    const double diagonal = std::hypot(dx, dy, dz);
    const std::array<double, 3> centre = position(data, c, middle.data());
    for (int q = 0; q < n_points; ++q)
      check.add(diagonal, {centre[0], centre[1]}, field.factor(position(data, c, X + 3 * q)));
  }
  check.refuse_if_too_wide(slice.tube_center);
}
} // namespace pushout::model

// What the concrete's cracks look like from outside (BulkCracking.h): the
// totals a step records (cracked points, dissipation, the widest crack),
// the cells' places on the slice, the gauge's reading at the outer faces
// (SurfaceCracks.h) and the per-cell fields of fields.xdmf.
#include "../common/mpi_gather.h"
#include "../laws/CamanhoDavila.h"
#include "BulkCrackingPoints.h"
#include "cracking.h"
#include <algorithm>
#include <cmath>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/utils.h>
#include <map>
#include <mpi.h>
#include <numeric>
#include <stdexcept>
#include <tuple>

namespace pushout::model
{
namespace
{
/// A cell's record: [face (-1: the column), x, y, weight * value, size (a
/// face's: depth), outline (8)].
constexpr int record_size = 13;

/// The corners (x, y) of a hexahedron of an extruded mesh seen along z,
/// counter-clockwise about its centre (x, y); a square of side `size` if
/// its nodes do not stand on four corners.
std::array<double, 8> outline_of(std::span<const std::int32_t> nodes, std::span<const double> x,
                                 double cx, double cy, double size, double tol)
{
  std::vector<std::array<double, 2>> corners;
  for (std::int32_t n : nodes)
  {
    const std::array<double, 2> p = {x[3 * n], x[3 * n + 1]};
    if (std::none_of(corners.begin(), corners.end(),
                     [&](const auto& q) { return std::hypot(p[0] - q[0], p[1] - q[1]) < tol; }))
      corners.push_back(p);
  }
  if (corners.size() != 4)
    corners = {{cx - size / 2, cy - size / 2},
               {cx + size / 2, cy - size / 2},
               {cx + size / 2, cy + size / 2},
               {cx - size / 2, cy + size / 2}};
  std::sort(corners.begin(), corners.end(),
            [&](const auto& a, const auto& b)
            { return std::atan2(a[1] - cy, a[0] - cx) < std::atan2(b[1] - cy, b[0] - cx); });
  std::array<double, 8> outline;
  for (int k = 0; k < 4; ++k)
  {
    outline[2 * k] = corners[k][0];
    outline[2 * k + 1] = corners[k][1];
  }
  return outline;
}

/// The length of the chord through (px, py) along (tx, ty) of the convex
/// outline `o` (corners counter-clockwise) [mm].
double chord(const std::array<double, 8>& o, double px, double py, double tx, double ty)
{
  double lo = INFINITY, hi = -INFINITY;
  for (int k = 0; k < 4; ++k)
  {
    const double ax = o[2 * k], ay = o[2 * k + 1];
    const double ex = o[(2 * k + 2) % 8] - ax, ey = o[(2 * k + 3) % 8] - ay;
    const double det = ex * ty - ey * tx; // P + s t = A + r e
    if (std::abs(det) < 1e-14 * (std::abs(ex) + std::abs(ey)))
      continue; // parallel
    const double dx = px - ax, dy = py - ay;
    const double r = (dx * ty - dy * tx) / det, s = (dx * ey - dy * ex) / det;
    if (r >= -1e-12 && r <= 1 + 1e-12)
    {
      lo = std::min(lo, s);
      hi = std::max(hi, s);
    }
  }
  return hi > lo ? hi - lo : 0.0;
}
/// The outer faces' indices in a record: the square's x = 0, x = W, y = 0
/// and y = W (their outward normals `square_normals`), and the circle about
/// the tube axis.
constexpr std::array<std::array<double, 2>, 4> square_normals{{{-1, 0}, {1, 0}, {0, -1}, {0, 1}}};
constexpr int circle_face = 4;

/// The depth [mm] of (x, y) below outer face `index` of a slice `W` [mm]
/// wide (its diameter for the circle about `axis`).
double depth_below(int index, double x, double y, double W, std::array<double, 2> axis)
{
  if (index == circle_face)
    return W / 2 - std::hypot(x - axis[0], y - axis[1]);
  const auto [nx, ny] = square_normals[std::size_t(index)];
  return (nx + ny > 0 ? W : 0) - (nx * x + ny * y); // the face lies at n . p = 0 or W
}

/// Where a crack through the face column at (x, y), `depth` below face
/// `index`, meets the face: moved out along the face's normal [mm].
std::array<double, 2> mouth_of(int index, double x, double y, double depth,
                               std::array<double, 2> axis)
{
  if (index == circle_face)
  {
    const double r = std::hypot(x - axis[0], y - axis[1]);
    return {x + depth * (x - axis[0]) / r, y + depth * (y - axis[1]) / r};
  }
  const auto [nx, ny] = square_normals[std::size_t(index)];
  return {x + depth * nx, y + depth * ny};
}
} // namespace

void BulkCracking::place_cells(const Geometry& slice, const std::vector<double>& positions)
{
  const int n_points = expression_cracking_position->num_points;
  const auto& x_dofmap = _mesh->geometry().dofmap();
  const std::span<const double> x = _mesh->geometry().x();
  const double tol = 1e-6 * slice.width; // gmsh places boundary nodes to ~1e-9 of it [mm]
  _places.assign(_cells.size(), {});
  for (std::size_t c = 0; c < _cells.size(); ++c)
  {
    CellPlace& p = _places[c];
    const auto nodes = x_dofmap.links(_cells[c]);
    for (std::int32_t node : nodes)
    {
      p.x += x[3 * node] / double(nodes.size());
      p.y += x[3 * node + 1] / double(nodes.size());
    }
    p.weight = extent(c, {0, 0, 1}) / slice.thickness;
    p.size = std::max(extent(c, {1, 0, 0}), extent(c, {0, 1, 0}));
    p.outline = outline_of(nodes, x, p.x, p.y, p.size, tol);
    // Depth below face `index` of a point (x, y): the cell's centre for the
    // face, its points' for the half of them that the gauge reads.
    auto depth = [&](int index, double a, double b)
    { return depth_below(index, a, b, slice.width, _axis); };
    // A face of the hexahedron (4 of its nodes) on outer face `index`.
    auto on_face = [&](int index)
    {
      return std::count_if(nodes.begin(), nodes.end(),
                           [&](std::int32_t n)
                           { return std::abs(depth(index, x[3 * n], x[3 * n + 1])) < tol; }) >= 4;
    };
    auto add_face = [&](int index, double tx, double ty)
    {
      CellPlace::Face f{index, tx, ty, depth(index, p.x, p.y), {}, {}};
      f.points.resize(std::size_t(n_points));
      std::iota(f.points.begin(), f.points.end(), 0);
      auto point_depth = [&](int q)
      {
        const std::size_t i = 3 * (c * std::size_t(n_points) + std::size_t(q));
        return depth(index, positions[i], positions[i + 1]);
      };
      std::stable_sort(f.points.begin(), f.points.end(),
                       [&](int a, int b) { return point_depth(a) < point_depth(b); });
      f.points.resize(std::size_t(n_points) / 2);
      for (int q : f.points)
      {
        const std::size_t i = 3 * (c * std::size_t(n_points) + std::size_t(q));
        f.chords.push_back(chord(p.outline, positions[i], positions[i + 1], tx, ty));
      }
      p.faces.push_back(f);
    };
    if (slice.circle) // centred on the tube axis (meshes/slice.geo)
    {
      if (on_face(circle_face))
      {
        const double phi = std::atan2(p.y - _axis[1], p.x - _axis[0]);
        add_face(circle_face, -std::sin(phi), std::cos(phi));
      }
      continue;
    }
    for (int index = 0; index < 4; ++index) // along each face: the tangent (|n_y|, |n_x|)
      if (on_face(index))
        add_face(index, std::abs(square_normals[std::size_t(index)][1]),
                 std::abs(square_normals[std::size_t(index)][0]));
  }
}

double BulkCracking::crack_strain_along(std::size_t i, double tx, double ty) const
{
  const bulk::CrackState<const double> s = points::crack_of(_trial, i);
  if (!s.cracked())
    return 0;
  const bulk::Mat3 R = s.frame();                  // rows n, s1, s2
  const double* w = _opening_trial.data() + 3 * i; // in the crack frame
  double w_t = 0;                                  // w . t, t = (tx, ty, 0)
  for (int k = 0; k < 3; ++k)
    w_t += w[k] * (R[3 * k] * tx + R[3 * k + 1] * ty);
  const bulk::Vec3 n = s.normal();
  return w_t * (n[0] * tx + n[1] * ty) / s.band_width();
}

void BulkCracking::read_surface(CrackingTotals& t) const
{
  const int n_points = expression_cracking_strain->num_points;
  std::vector<double> mine;
  for (std::size_t c = 0; c < _cells.size(); ++c)
  {
    const CellPlace& p = _places[c];
    double widest = 0; // the cell's widest normal opening [mm]
    for (int q = 0; q < n_points; ++q)
    {
      const std::size_t i = c * std::size_t(n_points) + q;
      if (points::crack_of(_trial, i).cracked())
        widest = std::max(widest, _opening_trial[3 * i]);
    }
    mine.insert(mine.end(), {-1.0, p.x, p.y, p.weight * widest, p.size});
    mine.insert(mine.end(), p.outline.begin(), p.outline.end());
    for (const CellPlace::Face& f : p.faces)
    {
      double gauge = 0; // the crack strain along the face over the chord, at the points nearest it
      for (std::size_t k = 0; k < f.points.size(); ++k)
        gauge +=
            crack_strain_along(c * std::size_t(n_points) + std::size_t(f.points[k]), f.tx, f.ty) *
            f.chords[k] / double(f.points.size());
      mine.insert(mine.end(), {double(f.index), p.x, p.y, p.weight * gauge, f.depth});
      mine.insert(mine.end(), p.outline.begin(), p.outline.end());
    }
  }

  // Process 0 sums the cells of each column (same face, same centre).
  MPI_Comm comm = _mesh->comm();
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const std::vector<double> all =
      mpi::gather_to_first(comm, mine.data(), int(mine.size()), MPI_DOUBLE);
  std::vector<double> flat; // the surface cracks, 4 numbers each
  if (rank == 0)
  {
    // Cells of a column share their (x, y) (the mesh is extruded): keyed to 1e-6 mm.
    std::map<std::tuple<int, long long, long long>, CrackColumn> sums;
    for (std::size_t r = 0; r < all.size(); r += record_size)
    {
      const auto key = std::make_tuple(int(all[r]), std::llround(all[r + 1] * 1e6),
                                       std::llround(all[r + 2] * 1e6));
      CrackColumn column{all[r + 1], all[r + 2], 0.0, all[r + 4]};
      std::copy_n(all.begin() + std::ptrdiff_t(r) + 5, 8, column.outline.begin());
      sums.try_emplace(key, column).first->second.opening += all[r + 3];
    }
    std::vector<FaceColumn> faces;
    for (const auto& [key, c] : sums) // a face column's opening is its gauge, its size its depth
      if (std::get<0>(key) < 0)
        t.columns.push_back(c);
      else
        faces.push_back({std::atan2(c.y - _axis[1], c.x - _axis[0]), c.x, c.y, c.opening,
                         mouth_of(std::get<0>(key), c.x, c.y, c.size, _axis)});
    t.surface = surface_cracks(faces, t.columns, _axis, _tube_radius,
                               gauge_resolution(_visible_width), _copies);
    for (const SurfaceCrack& s : t.surface)
      flat.insert(flat.end(), {s.angle_deg, s.width_mm, s.length_mm, double(s.all_round)});
  }
  int n_flat = int(flat.size());
  MPI_Bcast(&n_flat, 1, MPI_INT, 0, comm);
  flat.resize(std::size_t(n_flat));
  MPI_Bcast(flat.data(), n_flat, MPI_DOUBLE, 0, comm);
  t.surface.clear();
  for (std::size_t k = 0; k < flat.size(); k += 4)
    t.surface.push_back({flat[k], flat[k + 1], flat[k + 2], flat[k + 3] != 0});
}

void BulkCracking::cell_fields(dolfinx::fem::Function<double>& opening,
                               dolfinx::fem::Function<double>& normal,
                               dolfinx::fem::Function<double>& damage) const
{
  const int n_points = expression_cracking_strain->num_points;
  std::span<double> w = opening.x()->mutable_array(), n = normal.x()->mutable_array(),
                    d = damage.x()->mutable_array();
  std::fill(w.begin(), w.end(), 0.0);
  std::fill(n.begin(), n.end(), 0.0);
  std::fill(d.begin(), d.end(), 0.0);
  for (std::size_t c = 0; c < _cells.size(); ++c)
  {
    const std::int32_t dof = opening.function_space()->dofmap()->cell_dofs(_cells[c])[0];
    const std::int32_t vector_dof = normal.function_space()->dofmap()->cell_dofs(_cells[c])[0];
    double widest = -INFINITY; // normal opening of the cell's widest cracked point [mm]
    for (int q = 0; q < n_points; ++q)
    {
      const std::size_t i = c * std::size_t(n_points) + q;
      const bulk::CrackState<const double> s = points::crack_of(_trial, i);
      if (!s.cracked())
        continue;
      if (!(_opening_trial[3 * i] > widest))
        continue;
      // The widest point's crack: its opening, normal and damage.
      widest = _opening_trial[3 * i];
      w[dof] = std::max(widest, 0.0); // closed: 0
      d[dof] = laws::DamageHistory<const double>(s.law_state()).damage();
      const bulk::Vec3 normal_q = s.normal();
      std::copy(normal_q.begin(), normal_q.end(), n.begin() + 3 * std::size_t(vector_dof));
    }
  }
  opening.x()->scatter_fwd();
  normal.x()->scatter_fwd();
  damage.x()->scatter_fwd();
}
void BulkCracking::add_stress_share(std::span<double> L,
                                    std::shared_ptr<const dolfinx::fem::FunctionSpace> S) const
{
  namespace fem = dolfinx::fem;
  if (_implex && !_trial_implicit) // evaluate() left the step's prediction in _stress_trial
    throw std::logic_error("BulkCracking::add_stress_share: the cracks are not settle()d");
  if (!_L_stress_share || _L_stress_share->function_spaces()[0] != S)
  {
    const std::map<fem::IntegralType, const dolfinx::mesh::MeshTags<int>*> subdomains = {
        {fem::IntegralType::cell, _region.get()}};
    _L_stress_share = std::make_shared<fem::Form<double>>(fem::create_form<double>(
        *form_cracking_L_stress_crack, {S}, {{"d_sigma", _stress_share}}, {}, subdomains));
  }
  const bulk::Voigt66& C = _band.stiffness();
  const points::PointValues share_at(*_stress_share, points::voigt);
  const int n_points = expression_cracking_strain->num_points;
  for (std::size_t c = 0; c < _cells.size(); ++c)
    for (int q = 0; q < n_points; ++q)
    {
      const std::size_t i = c * std::size_t(n_points) + q;
      const bulk::Voigt elastic = bulk::multiply(C, points::voigt_at(_strain_values, i));
      const std::span<double> share = share_at(_cells[c], q);
      for (int k = 0; k < points::voigt; ++k)
        share[k] = _stress_trial[points::voigt * i + k] - elastic[k];
    }
  fem::assemble_vector(L, *_L_stress_share);
}

CrackingTotals BulkCracking::totals()
{
  // A failure was the converged step's, and is not one. IMPL-EX: the
  // state the step commits, the crack band's own at the converged strain.
  if (_implex)
    implicit_update();
  else
    evaluate();
  CrackingTotals t;
  t.points = std::int64_t(_strength.size());
  for (std::size_t i = 0; i < _strength.size(); ++i)
  {
    const bulk::CrackState<const double> s = points::crack_of(_trial, i);
    if (!s.cracked())
      continue;
    ++t.cracked_points;
    t.max_opening = std::max(t.max_opening, _opening_trial[3 * i]);
  }
  t.dissipated = integrate([&](std::size_t i) { return _dissipated_trial[i]; });
  MPI_Comm comm = _mesh->comm();
  MPI_Allreduce(MPI_IN_PLACE, &t.points, 1, MPI_INT64_T, MPI_SUM, comm);
  MPI_Allreduce(MPI_IN_PLACE, &t.cracked_points, 1, MPI_INT64_T, MPI_SUM, comm);
  MPI_Allreduce(MPI_IN_PLACE, &t.dissipated, 1, MPI_DOUBLE, MPI_SUM, comm);
  MPI_Allreduce(MPI_IN_PLACE, &t.max_opening, 1, MPI_DOUBLE, MPI_MAX, comm);
  read_surface(t);
  t.edge = edge_of(_trial, _opening_trial);
  return t;
}

EdgeCracks BulkCracking::edge_of(const std::vector<double>& state,
                                 const std::vector<double>& opening) const
{
  EdgeCracks e;
  e.radius = _radius;
  if (_radius <= 0)
    return e; // no edge (a scene value: every process returns here)
  const std::size_t n_points = _cells.empty() ? 0 : _strength.size() / _cells.size();
  e.points = std::int64_t(_edge.size() * n_points);
  for (std::size_t k : _edge)
    for (std::size_t i = k * n_points; i < (k + 1) * n_points; ++i)
      if (points::crack_of(state, i).cracked())
      {
        ++e.cracked_points;
        e.max_opening = std::max(e.max_opening, opening[3 * i]);
      }
  MPI_Comm comm = _mesh->comm();
  std::int64_t counts[2] = {e.points, e.cracked_points};
  MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPI_INT64_T, MPI_SUM, comm);
  e.points = counts[0];
  e.cracked_points = counts[1];
  MPI_Allreduce(MPI_IN_PLACE, &e.max_opening, 1, MPI_DOUBLE, MPI_MAX, comm);
  return e;
}
} // namespace pushout::model

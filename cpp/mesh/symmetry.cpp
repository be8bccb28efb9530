#include "symmetry.h"
#include "../scene/CrackPlanes.h"
#include "cracks.h"
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace pushout::mesh
{
namespace
{
constexpr double pi = std::numbers::pi;
/// Directions closer than this are the same [rad].
constexpr double same_direction = 1e-9;

/// The mirror image of direction a about x = xc (x_plane) or y = yc.
double reflected(double a, bool x_plane)
{
  return x_plane ? pi - a : -a;
}

/// Whether the set of directions is its own mirror image.
bool invariant(const std::vector<double>& angles, bool x_plane)
{
  return std::all_of(angles.begin(), angles.end(),
                     [&](double a)
                     {
                       return std::any_of(
                           angles.begin(), angles.end(),
                           [&](double b)
                           { return angle_between(reflected(a, x_plane), b) < same_direction; });
                     });
}

/// Why the slice is not symmetric about one plane ("" if it is).
std::string asymmetry(const MeshInput& in, bool x_plane)
{
  const char* axis = x_plane ? "x" : "y";
  if (!in.geometry.circle)
  {
    const double W = in.geometry.width;
    const double c = in.geometry.tube_center[x_plane ? 0 : 1];
    if (std::abs(c - W / 2) > 1e-12 * W)
      return std::string("the tube is not centred in ") + axis;
  }
  if (!invariant(in.cracks.angles, x_plane))
    return std::string("the crack planes are not symmetric about ") + axis + " = " +
           (x_plane ? "xc" : "yc");
  return "";
}
} // namespace

std::string Symmetry::name() const
{
  switch (copies())
  {
  case 4:
    return "quarter";
  case 2:
    return "half";
  default:
    return "full";
  }
}

Side side_of(Symmetry s, double angle)
{
  const double c = std::cos(angle), sn = std::sin(angle);
  if ((s.x_plane && c < -same_direction) || (s.y_plane && sn < -same_direction))
    return Side::outside;
  if ((s.x_plane && std::abs(c) <= same_direction) || (s.y_plane && std::abs(sn) <= same_direction))
    return Side::on_plane;
  return Side::inside;
}

std::vector<double> images_of(Symmetry s, double angle)
{
  std::vector<double> rays = {angle};
  for (const bool x_plane : {true, false})
  {
    if (!(x_plane ? s.x_plane : s.y_plane))
      continue;
    const std::size_t n = rays.size();
    for (std::size_t i = 0; i < n; ++i)
    {
      const double image = reflected(rays[i], x_plane);
      if (std::none_of(rays.begin(), rays.end(),
                       [&](double b) { return angle_between(image, b) < same_direction; }))
        rays.push_back(image);
    }
  }
  return rays;
}

Symmetry geometric_symmetry(const MeshInput& in)
{
  if (!in.pushout)
    return {};
  return {asymmetry(in, true).empty(), asymmetry(in, false).empty()};
}

Symmetry model_symmetry(const MeshInput& in, std::string& why)
{
  why.clear();
  if (!in.pushout)
    return {};
  if (in.symmetry == ModelPart::Symmetry::full)
  {
    why = "model.symmetry = \"full\"";
    return {};
  }
  if (in.bulk_cracking && in.symmetry == ModelPart::Symmetry::automatic)
  {
    why = "the concrete may crack anywhere ([cracking]): a crack may open on one side of a "
          "symmetry plane only (with a uniform strength, model.symmetry = \"symmetric\" cuts "
          "there)";
    return {};
  }
  if (in.fields && in.symmetry == ModelPart::Symmetry::automatic)
  {
    // (model.symmetry = "symmetric" asks for the cut: its fields are the
    // part's, and the whole slice would solve another problem where crack
    // planes that are mirror images open unalike.)
    why = "output.xdmf asks for fields of the whole specimen";
    return {};
  }
  // slice_cracked.geo has a sector boundary on each symmetry plane; slice.geo
  // has a mesh line there only with an even number of elements per quarter.
  if (!in.cracked() && in.mesh.elements_per_quarter % 2 != 0)
  {
    why = "mesh.elements_per_quarter is odd (the symmetry planes are not mesh surfaces)";
    return {};
  }
  std::string x_why = asymmetry(in, true), y_why = asymmetry(in, false);
  // Crack planes that are each other's mirror images (not on the plane):
  // the cut model makes them open alike; the whole slice may localise in
  // one. Only model.symmetry = "symmetric" cuts there.
  if (in.symmetry == ModelPart::Symmetry::automatic)
  {
    const Symmetry x_only{true, false}, y_only{false, true};
    for (double a : in.cracks.angles)
    {
      const char* paired = "crack planes that are mirror images of each other could open "
                           "unalike (model.symmetry = \"symmetric\" cuts there)";
      if (x_why.empty() && side_of(x_only, a) != Side::on_plane)
        x_why = paired;
      if (y_why.empty() && side_of(y_only, a) != Side::on_plane)
        y_why = paired;
    }
  }
  const Symmetry s{x_why.empty(), y_why.empty()};
  if (s.copies() == 1)
    why = x_why == y_why ? x_why : x_why + "; " + y_why;
  else if (s.copies() == 2)
    why = "not a quarter: " + x_why + y_why;
  return s;
}

namespace
{
/// The numbers in the part of the full mesh's cells and nodes (-1: cut
/// away).
struct Renumbering
{
  std::vector<std::int64_t> cell, node;

  /// A joint element's face, its nodes renumbered.
  std::array<std::int64_t, 4> face(const std::array<std::int64_t, 4>& side) const
  {
    std::array<std::int64_t, 4> r;
    for (int i = 0; i < 4; ++i)
      r[i] = node[side[i]];
    return r;
  }
  /// A joint element whose two cells are kept, renumbered.
  InterfacePair pair(const InterfacePair& p) const
  {
    return {face(p.minus), face(p.plus), cell[p.minus_cell], cell[p.plus_cell]};
  }
};

/// Copies into `q` the cells of `m` in the part (x >= xc if s.x_plane, y >=
/// yc if s.y_plane; by centroid), their materials and nodes, renumbered in
/// the order met; throws logic_error if a kept cell has a node outside the
/// part (it straddles a plane: not a mesh surface).
Renumbering keep_cells(const MeshData& m, Symmetry s, std::array<double, 2> centre, MeshData& q)
{
  const auto [xc, yc] = centre;
  double extent = 0;
  for (double v : m.x)
    extent = std::max(extent, std::abs(v));
  // gmsh places the nodes of an arc to ~1e-9 of the slice (a circle's
  // outer nodes on the planes are off them by 1e-7 mm); the push-out's
  // symmetry conditions take nodes within 1e-6 of the tube's size.
  const double tol = 1e-7 * extent; // [mm]
  const auto in_part = [&](double x, double y, double margin)
  { return (!s.x_plane || x >= xc + margin) && (!s.y_plane || y >= yc + margin); };

  Renumbering r{std::vector<std::int64_t>(m.num_cells(), -1),
                std::vector<std::int64_t>(m.num_nodes(), -1)};
  std::int64_t nodes = 0;
  for (std::size_t c = 0; c < m.num_cells(); ++c)
  {
    const std::array<double, 3> x = centroid(m, c);
    if (!in_part(x[0], x[1], 0.0))
      continue;
    for (int i = 0; i < 8; ++i)
    {
      const std::int64_t n = m.cells[8 * c + i];
      if (!in_part(m.x[3 * n], m.x[3 * n + 1], -tol))
        throw std::logic_error("symmetry: a cell straddles a symmetry plane (not a mesh surface)");
    }
    r.cell[c] = std::int64_t(q.num_cells());
    q.material.push_back(m.material[c]);
    for (int i = 0; i < 8; ++i)
    {
      std::int64_t& n = r.node[m.cells[8 * c + i]];
      if (n < 0)
        n = nodes++;
      q.cells.push_back(n);
    }
  }
  q.x.resize(3 * std::size_t(nodes));
  for (std::size_t n = 0; n < m.num_nodes(); ++n)
    if (r.node[n] >= 0)
      for (int d = 0; d < 3; ++d)
        q.x[3 * r.node[n] + d] = m.x[3 * n + d];
  return r;
}

/// A crack plane of the full mesh in the part `q` (its cells and nodes
/// kept, `kept`): its joint elements inside the part; on a symmetry plane
/// (one face kept) a mirror crack, each pair the kept face against its
/// mirror image; outside the part, no joint elements (linked to its image
/// by link_images). Throws logic_error if a plane off the symmetry planes
/// is cut.
CrackPlane cut_crack(const CrackPlane& crack, Symmetry s, std::array<double, 2> centre,
                     const Renumbering& kept, const MeshData& q)
{
  const auto [xc, yc] = centre;
  const std::vector<std::int64_t>& new_cell = kept.cell;
  const std::vector<std::int64_t>& new_node = kept.node;
  CrackPlane r;
  r.angle = crack.angle;
  const bool on_x = s.x_plane && std::abs(std::cos(crack.angle)) <= same_direction;
  const bool on_y = s.y_plane && std::abs(std::sin(crack.angle)) <= same_direction;
  for (const InterfacePair& p : crack.pairs)
  {
    const bool minus = new_cell[p.minus_cell] >= 0, plus = new_cell[p.plus_cell] >= 0;
    if (minus && plus)
    {
      r.pairs.push_back(kept.pair(p));
      continue;
    }
    if (!minus && !plus)
      continue;
    if (!on_x && !on_y)
      throw std::logic_error("symmetry: a crack plane off the symmetry planes is cut");
    const std::int64_t cell = new_cell[minus ? p.minus_cell : p.plus_cell];
    const std::array<std::int64_t, 4> face = kept.face(minus ? p.minus : p.plus);
    InterfacePair mirrored = {face, face, cell, cell};
    // Oriented from the mirror image of the kept cell into it.
    std::array<double, 3> image = centroid(q, std::size_t(cell));
    if (on_x)
      image[0] = 2 * xc - image[0];
    else
      image[1] = 2 * yc - image[1];
    orient(mirrored, q, image);
    r.pairs.push_back(mirrored);
    r.mirror = on_x ? std::array<double, 3>{1, 0, 0} : std::array<double, 3>{0, 1, 0};
  }
  for (const auto& [minus, plus] : crack.mouth)
  {
    if (r.mirrored())
    {
      const std::int64_t node = new_node[minus] >= 0 ? new_node[minus] : new_node[plus];
      r.mouth.push_back({node, node});
    }
    else if (new_node[minus] >= 0 && new_node[plus] >= 0)
      r.mouth.push_back({new_node[minus], new_node[plus]});
  }
  return r;
}

/// Each crack plane cut away (no joint elements in the part): the plane in
/// the part it is the image of, by one symmetry plane or by both; throws
/// logic_error if there is none.
void link_images(std::vector<CrackPlane>& cracks, Symmetry s)
{
  for (std::size_t i = 0; i < cracks.size(); ++i)
  {
    CrackPlane& crack = cracks[i];
    if (!crack.pairs.empty())
      continue;
    // Its image by one plane or by both.
    std::vector<double> images;
    if (s.x_plane)
      images.push_back(reflected(crack.angle, true));
    if (s.y_plane)
      images.push_back(reflected(crack.angle, false));
    if (s.x_plane && s.y_plane)
      images.push_back(crack.angle + pi);
    for (std::size_t j = 0; j < cracks.size() && crack.image_of < 0; ++j)
      if (!cracks[j].pairs.empty())
        for (double a : images)
          if (angle_between(a, cracks[j].angle) < same_direction)
            crack.image_of = int(j);
    if (crack.image_of < 0)
      throw std::logic_error("symmetry: a crack plane cut away has no image in the part");
  }
}
} // namespace

void keep_symmetric_part(MeshData& m, Symmetry s, std::array<double, 2> centre)
{
  MeshData q;
  const Renumbering kept = keep_cells(m, s, centre, q);
  for (const InterfacePair& p : m.pairs)
    if (kept.cell[p.minus_cell] >= 0 && kept.cell[p.plus_cell] >= 0)
      q.pairs.push_back(kept.pair(p));
  // Crack planes: inside the part, on a symmetry plane (one face kept: a
  // mirror crack), or outside it (the image of one inside).
  for (const CrackPlane& crack : m.cracks)
    q.cracks.push_back(cut_crack(crack, s, centre, kept, q));
  link_images(q.cracks, s);
  q.copies = s.copies();
  q.symmetry_center = centre;
  q.symmetry_planes = {s.x_plane, s.y_plane};
  m = std::move(q);
}
} // namespace pushout::mesh

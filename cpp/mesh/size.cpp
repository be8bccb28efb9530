#include "size.h"
#include "../scene/CrackPlanes.h"
#include "cracks.h"
#include "symmetry.h"
#include <algorithm>
#include <cmath>
#include <numbers>

namespace pushout::mesh
{
namespace
{
constexpr double q_max = graded_growth_max;

/// How many elements from `first` [mm], growing by q_max, fill L [mm].
std::int64_t elements_to_fill(double first, double L)
{
  return std::int64_t(std::ceil(std::log(1 + L * (q_max - 1) / first) / std::log(q_max)));
}

/// The growth q in [1, q_max] of n elements from `first` [mm] that fill L
/// [mm]: first (q^n - 1) / (q - 1) = L (bisection); 1 (uniform, smaller
/// than `first`) where n of `first` already fill L.
double growth_to_fill(double first, std::int64_t n, double L)
{
  if (double(n) * first >= L)
    return 1;
  double lo = 1, hi = q_max;
  for (int i = 0; i < 60; ++i)
  {
    const double q = (lo + hi) / 2;
    (first * (std::pow(q, double(n)) - 1) / (q - 1) < L ? lo : hi) = q;
  }
  return (lo + hi) / 2;
}

/// The first element of n that fill L with growth q [mm].
double first_element(double L, std::int64_t n, double q)
{
  return q > 1 ? L * (q - 1) / (std::pow(q, double(n)) - 1) : L / double(n);
}

/// The lengths of the graded block's lines, support circle to boundary [mm],
/// in the .geo's order: slice.geo's from the support circle at 45 + 90 k
/// degrees to block corner k (with radial lines, every line), slice_cracked.geo's
/// along each sector boundary (mesh/cracks.h).
std::vector<double> graded_lines(const MeshInput& in, double Rs)
{
  const Geometry& g = in.geometry;
  const auto& c = g.tube_center;
  std::vector<double> angles;
  std::vector<std::array<double, 2>> outer;
  if (in.cracked())
  {
    const SliceSectors sec = slice_sectors(in);
    angles = sec.angles;
    outer = sec.outer;
  }
  else if (in.mesh.radial_lines && !g.circle)
  {
    // Every line of the graded block is one of its own (the longest ends at
    // a square corner), not the blocks' interpolation between their corner
    // lines.
    outer = radial_line_ends(g, in.mesh.elements_per_quarter);
    for (std::size_t j = 0; j < outer.size(); ++j)
      angles.push_back(graded_line_angle(in.mesh.elements_per_quarter, j));
  }
  else
    for (int k = 0; k < 4; ++k)
    {
      angles.push_back(std::numbers::pi / 4 + k * std::numbers::pi / 2);
      outer.push_back(block_corners(g)[std::size_t(k)]);
    }
  std::vector<double> lengths;
  for (std::size_t k = 0; k < angles.size(); ++k)
    lengths.push_back(std::hypot(outer[k][0] - c[0] - Rs * std::cos(angles[k]),
                                 outer[k][1] - c[1] - Rs * std::sin(angles[k])));
  return lengths;
}
} // namespace

SliceDivisions slice_divisions(const MeshInput& in)
{
  const Geometry& g = in.geometry;
  const double R = g.tube_radius();
  const double Rs = g.support_inner_diameter / 2;
  const double ratio = in.mesh.outer_size_ratio;
  SliceDivisions d;
  d.circumferential = in.mesh.elements_per_quarter;
  d.steel = in.mesh.steel_layers;
  d.thickness = in.mesh.elements_through_thickness;
  const double h = interface_element_size(R, d.circumferential); // [mm]
  d.ring = std::max<std::int64_t>(std::int64_t(std::floor((Rs - R) / h + 0.5)), 1);

  // One growth for every line, from the shortest way out Lr: towards ratio
  // h where that is gentle, else from h by at most q_max (also where ratio
  // h is beyond Lr: the coarsest the growth allows); ratio 1: uniform.
  const double Lr = g.nearest_face_distance() - Rs;
  const double he = ratio * h;
  d.graded = std::max<std::int64_t>(std::int64_t(std::ceil(Lr / h)), 1);
  double q = 1;
  if (ratio > 1)
  {
    const double q0 = he < Lr ? (Lr - h) / (Lr - he) : q_max + 1;
    if (q0 <= q_max)
    {
      d.graded =
          std::max<std::int64_t>(std::int64_t(std::floor(std::log(ratio) / std::log(q0) + 1.5)), 2);
      q = std::exp(std::log(ratio) / double(d.graded - 1));
      for (; q > q_max; q = std::exp(std::log(ratio) / double(d.graded - 1)))
        ++d.graded; // the count rounded down: one more, until the growth is q_max at most
    }
    else
    {
      d.graded = std::max<std::int64_t>(elements_to_fill(h, Lr), 1);
      q = growth_to_fill(h, d.graded, Lr);
    }
  }
  d.growth = q;

  // The longest line (to a far corner) has the same number of elements,
  // stretched: where its first one would jump from the ring's (more than
  // q_max h), enough elements to start it at q_max h (the shorter lines
  // start smaller). near_tube: growing by q_max at most, with the growth
  // that fills it so; their number then grows only with log(1 / h), so the
  // outer elements keep their size as the mesh is refined and the graded
  // cells grow longer along the way out. whole: growing to `ratio` times
  // the first, as the shortest way would; their number grows as 1 / h, and
  // every element shrinks with h (ratio 1: uniform, either way). One growth
  // for all lines: gmsh's transfinite blocks are mirror images only between
  // lines of the same growth, and a half or quarter model is cut from the
  // whole mesh (mesh/symmetry.h).
  const std::vector<double> lines = graded_lines(in, Rs);
  const double longest = *std::max_element(lines.begin(), lines.end());
  if (first_element(longest, d.graded, q) > q_max * h * (1 + 1e-9))
  {
    if (ratio == 1) // uniform, as asked
    {
      d.graded = std::int64_t(std::ceil(longest / (q_max * h)));
      return d;
    }
    // near_tube's count: the fewest that start it so.
    d.graded = std::max(d.graded, elements_to_fill(q_max * h, longest));
    if (in.mesh.refine_whole)
    {
      // As many more as reach `ratio` across n elements (by q_max at most,
      // as the shortest way: a larger ratio never gives more elements).
      const auto growth = [&](std::int64_t n)
      { return std::min(std::pow(ratio, 1.0 / double(n - 1)), q_max); };
      while (first_element(longest, d.graded, growth(d.graded)) > q_max * h * (1 + 1e-9))
        ++d.graded;
      d.growth = growth(d.graded);
    }
    else
      d.growth = growth_to_fill(q_max * h, d.graded, longest);
  }
  return d;
}

MeshSize predict_size(const MeshInput& in)
{
  MeshSize s;
  const int p = in.mesh.degree; // nodes per element edge - 1
  if (!in.pushout)
  {
    // meshes/single_joint.geo: two stacked unit cells, one joint element.
    s.cells = s.cells_generated = 2;
    s.concrete_cells = 1; // the upper cell
    // Two stacked cells whose shared face is the interface: no node shared.
    s.nodes = 2 * (p + 1) * (p + 1) * (p + 1);
    s.joint_elements = 1;
    s.interface_dofs = 6 * (p + 1) * (p + 1);
    s.dofs = 3 * s.nodes;
    return s;
  }
  const SliceDivisions d = slice_divisions(in);
  const std::int64_t radial = d.steel + d.ring + d.graded; // elements along a radius
  std::string why;
  const Symmetry symmetry = model_symmetry(in, why);
  s.symmetry = symmetry;
  const int copies = symmetry.copies();
  // Elements around the circumference: of the whole slice, and of the part
  // the model keeps (with crack planes the circumference is cut into
  // sectors, cracks.h, with a boundary on each symmetry plane).
  const bool cracked = in.cracked();
  std::int64_t full_around = 4 * d.circumferential, around = full_around / copies;
  if (cracked)
  {
    const SliceSectors sec = slice_sectors(in);
    full_around = sec.around();
    around = 0;
    for (std::size_t i = 0; i < sec.angles.size(); ++i)
    {
      const double next =
          i + 1 < sec.angles.size() ? sec.angles[i + 1] : sec.angles[0] + 2 * std::numbers::pi;
      if (side_of(symmetry, (sec.angles[i] + next) / 2) == Side::inside)
        around += sec.elements[i];
    }
  }
  s.cells_generated = full_around * radial * d.thickness;
  s.cells = around * radial * d.thickness;
  s.concrete_cells = around * (d.ring + d.graded) * d.thickness;
  s.joint_elements = around * d.thickness;
  // Node positions of the degree: around the tube (a closed ring for the
  // full model, an arc for a part), along a radius (the interface position
  // twice) and through the thickness.
  const std::int64_t n_around = copies > 1 ? p * around + 1 : p * around;
  const std::int64_t n_radial = p * radial + 2;
  const std::int64_t n_thick = p * d.thickness + 1;
  s.nodes = n_around * n_radial * n_thick;
  s.interface_dofs = 6 * n_around * n_thick;
  // A crack plane inside the part duplicates its concrete nodes (from the
  // interface to the boundary: one more interface node column, and its plus
  // face's node pairs); one on a symmetry plane keeps one face (its node
  // pairs only); one outside is cut away. Each kept plane adds its joint
  // elements; 6 dofs per node pair.
  const std::int64_t crack_nodes = (p * (d.ring + d.graded) + 1) * n_thick;
  for (double angle : in.cracks.angles)
  {
    const Side side = side_of(symmetry, angle);
    if (side == Side::outside)
      continue;
    s.joint_elements += (d.ring + d.graded) * d.thickness;
    s.interface_dofs += 6 * crack_nodes;
    if (side == Side::inside)
    {
      s.nodes += crack_nodes;
      s.interface_dofs += 6 * n_thick;
    }
  }
  s.dofs = 3 * s.nodes;
  return s;
}
} // namespace pushout::mesh

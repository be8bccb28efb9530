#include "size.h"
#include "cracks.h"
#include "symmetry.h"
#include <algorithm>
#include <cmath>
#include <numbers>

namespace pushout::mesh
{
SliceDivisions slice_divisions(const MeshInput& in)
{
  // meshes/slice.geo, line for line.
  const Geometry& g = in.geometry;
  const double W = g.width;
  const double R = g.tube_radius();
  const double Rs = g.support_inner_diameter / 2;
  const double ratio = in.mesh.outer_size_ratio;
  const auto& c = g.tube_center;
  SliceDivisions d;
  d.circumferential = in.mesh.elements_per_quarter;
  d.steel = in.mesh.steel_layers;
  d.thickness = in.mesh.elements_through_thickness;
  const double h = std::numbers::pi / 2 * R / double(d.circumferential); // interface element [mm]
  d.ring = std::max<std::int64_t>(std::int64_t(std::floor((Rs - R) / h + 0.5)), 1);
  double Lr = W / 2 - Rs;
  if (!g.circle)
    Lr = std::min({W / 2, c[0], c[1], W - c[0], W - c[1]}) - Rs;
  const double he = ratio * h;
  d.graded = std::int64_t(std::ceil(Lr / h));
  if (ratio > 1 && he < Lr)
  {
    const double q0 = (Lr - h) / (Lr - he);
    d.graded = q0 <= graded_growth_max
                   ? std::max<std::int64_t>(
                         std::int64_t(std::floor(std::log(ratio) / std::log(q0) + 1.5)), 2)
                   : std::int64_t(std::ceil(std::log(1 + Lr * (graded_growth_max - 1) / h) /
                                            std::log(graded_growth_max)));
  }
  d.graded = std::max<std::int64_t>(d.graded, 1);
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

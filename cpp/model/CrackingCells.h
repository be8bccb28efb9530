// Which cells of the concrete may crack: those whose centre lies within
// cracking.radius of the tube axis (docs/cracking.md), on this process, and
// which of them lie at the edge of that region, where a crack that reaches
// it meets concrete that stays linear.
#pragma once

#include <array>
#include <cstdint>
#include <dolfinx/mesh/Mesh.h>
#include <string>
#include <vector>

namespace pushout::model
{
/// Whether a concrete cell whose centre lies `distance` [mm] from the tube
/// axis may crack, within cracking.radius `radius` [mm] (0: all of them).
inline bool may_crack(double distance, double radius)
{
  return radius <= 0 || distance <= radius;
}

/// The owned concrete cells (`material`, by original cell index) whose
/// centre lies within `radius` [mm] of the tube `axis` (x, y) [mm]; every
/// owned concrete cell if radius <= 0.
std::vector<std::int32_t> cracking_cells(const dolfinx::mesh::Mesh& mesh,
                                         const std::vector<std::int32_t>& material, double radius,
                                         std::array<double, 2> axis);

/// Of `cells` (cracking_cells' list), the positions of those at the edge of
/// the cracking region: sharing a vertex with a concrete cell that may not
/// crack, on any process. None when every concrete cell may crack.
/// Collective.
std::vector<std::size_t> region_edge(const dolfinx::mesh::Mesh& mesh,
                                     const std::vector<std::int32_t>& material,
                                     const std::vector<std::int32_t>& cells);

/// The refusal of a cracking.radius `radius` [mm] that takes in no concrete
/// cell, the nearest centre `nearest` [mm] from the tube axis.
std::string takes_no_concrete(double radius, double nearest);

/// The least distance of an owned concrete cell's centre from the tube
/// `axis` [mm] (infinity if none).
double nearest_concrete_centre(const dolfinx::mesh::Mesh& mesh,
                               const std::vector<std::int32_t>& material,
                               std::array<double, 2> axis);
} // namespace pushout::model

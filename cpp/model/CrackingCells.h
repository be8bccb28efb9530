// Which cells of the concrete may crack: those whose centre lies within
// cracking.radius of the tube axis (docs/cracking.md), on this process.
#pragma once

#include <array>
#include <cstdint>
#include <dolfinx/mesh/Mesh.h>
#include <vector>

namespace pushout::model
{
/// The owned concrete cells (`material`, by original cell index) whose
/// centre lies within `radius` [mm] of the tube `axis` (x, y) [mm]; every
/// owned concrete cell if radius <= 0.
std::vector<std::int32_t> cracking_cells(const dolfinx::mesh::Mesh& mesh,
                                         const std::vector<std::int32_t>& material, double radius,
                                         std::array<double, 2> axis);

/// The least distance of an owned concrete cell's centre from the tube
/// `axis` [mm] (infinity if none).
double nearest_concrete_centre(const dolfinx::mesh::Mesh& mesh,
                               const std::vector<std::int32_t>& material,
                               std::array<double, 2> axis);
} // namespace pushout::model

// The directions of a push-out's crack planes ([[crack]] tables;
// docs/corrosion.md), resolved once from the geometry where the scene is
// parsed, and the geometry of the slice's mesh blocks they are placed
// against (meshes/slice.geo, slice_cracked.geo).
#pragma once

#include "SceneParts.h"
#include <array>
#include <cstdint>
#include <vector>

namespace pushout
{
/// Smallest angle between two directions [rad].
double angle_between(double a, double b);

/// The block corner directions from the tube centre [rad]: towards the
/// square's corners (so that every ray between two of them meets one
/// side), or 45 + 90 k degrees in a circle.
std::array<double, 4> corner_angles(const Geometry& g);

/// The outer ends of the four block corner lines [mm], in corner_angles'
/// order: the square's corners (+x+y, -x+y, -x-y, +x-y), or the circle's
/// points at 45 + 90 k degrees from the tube axis. meshes/slice.geo's
/// graded block runs to them (passed as constants, mesh/generate.cpp).
std::array<std::array<double, 2>, 4> block_corners(const Geometry& g);

/// Where the ray from the tube centre at angle a [rad] meets the slice's
/// outer boundary [mm].
std::array<double, 2> boundary_point(const Geometry& g, double a);

/// The direction of meshes/slice.geo's graded line j of 4 nq from the tube
/// axis [rad]: its node on the support circle, at 45 + 90 j / nq degrees.
double graded_line_angle(std::int64_t nq, std::size_t j);

/// The outer ends of the graded block's lines when they are radial
/// (mesh.graded_lines = "radial") [mm], 4 nq of them: line j from
/// meshes/slice.geo's node on the support circle at 45 + 90 j / nq degrees
/// along its ray from the tube axis to the boundary, but each of a square's
/// corners at the end of the line whose ray is nearest to it, so that the
/// boundary keeps its corners.
std::vector<std::array<double, 2>> radial_line_ends(const Geometry& g, std::int64_t nq);

/// The directions of `cracks` [rad, in [0, 2 pi)], in their order.
/// "nearest_face" is the direction of the square's side nearest the tube
/// axis (ties: -y, +x, +y, -x). A crack within half an interface element
/// (of `elements_per_quarter` around a quarter) of a block corner direction
/// is moved onto it (snapped[i] says so). Throws SceneError on cracks that
/// cannot be meshed (two in one element, "nearest_face" in a circle).
CrackDirections crack_directions(const Geometry& g, std::int64_t elements_per_quarter,
                                 const std::vector<CrackSpec>& cracks);
} // namespace pushout

// Exact symmetry: a push-out slice whose tube is centred in a square (or a
// circle) is symmetric about the planes x = xc and y = yc, and so is its
// solution (the laws are isotropic in the interface plane, the loads are
// symmetric). Then one quarter of the mesh with symmetry conditions gives
// the whole specimen's curve at a quarter of the dofs.
//
// The quarter is cut from the full mesh: the slice.geo blocks are mirror
// images of each other about both planes (corners at 45 degrees), so with
// an even number of elements per quarter the planes are mesh surfaces, and
// the quarter model's nodes are exactly the full model's.
#pragma once

#include "../scene/Scene.h"
#include "MeshData.h"
#include <string>

namespace pushout::mesh
{
/// Whether the scene runs on a quarter model: model.symmetry = "auto", a
/// push-out, the tube centred (square) or any circle, an even
/// mesh.elements_per_quarter, and no field output (fields cover the whole
/// specimen). `why` says why not.
bool use_quarter_model(const Scene& scene, std::string& why);

/// Keeps the cells in x >= xc, y >= yc (by centroid) and the joint elements
/// between them, renumbers nodes and cells, and records the symmetry.
void keep_quarter(MeshData& mesh, double xc, double yc);
} // namespace pushout::mesh

// The six rigid-body modes of the displacement space as the near-nullspace
// of a matrix, for algebraic multigrid (-pc_type gamg) on elasticity.
#pragma once

#include "../model/Model.h"
#include <petscmat.h>

namespace pushout::solver
{
/// Attaches the rigid-body modes (from the owned dof coordinates) to A.
void set_rigid_body_modes(const model::Model& model, Mat A);
} // namespace pushout::solver

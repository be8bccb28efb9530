#include "RigidBodyModes.h"
#include <algorithm>
#include <dolfinx/common/IndexMap.h>

namespace pushout::solver
{
void set_rigid_body_modes(const model::Model& m, Mat A)
{
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(A));
  const std::vector<double> x = m.V->tabulate_dof_coordinates(false);
  const PetscInt n_owned = m.V->dofmap()->index_map->size_local();
  Vec coords;
  VecCreateMPI(comm, 3 * n_owned, PETSC_DETERMINE, &coords);
  VecSetBlockSize(coords, 3);
  double* c;
  VecGetArray(coords, &c);
  std::copy_n(x.begin(), 3 * n_owned, c);
  VecRestoreArray(coords, &c);
  MatNullSpace rigid;
  MatNullSpaceCreateRigidBody(coords, &rigid);
  MatSetNearNullSpace(A, rigid);
  MatNullSpaceDestroy(&rigid);
  VecDestroy(&coords);
}
} // namespace pushout::solver

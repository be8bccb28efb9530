#include "RigidBodyModes.h"
#include "../common/petsc_check.h"
#include <algorithm>
#include <dolfinx/common/IndexMap.h>

namespace pushout::solver
{
using petsc::check;

void set_rigid_body_modes(const model::Model& m, Mat A)
{
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(A));
  const std::vector<double> x = m.space()->tabulate_dof_coordinates(false);
  const PetscInt n_owned = m.index_map().size_local();
  Vec coords;
  check(VecCreateMPI(comm, 3 * n_owned, PETSC_DETERMINE, &coords), "VecCreateMPI");
  check(VecSetBlockSize(coords, 3), "VecSetBlockSize");
  double* c;
  check(VecGetArray(coords, &c), "VecGetArray");
  std::copy_n(x.begin(), 3 * n_owned, c);
  check(VecRestoreArray(coords, &c), "VecRestoreArray");
  MatNullSpace rigid;
  check(MatNullSpaceCreateRigidBody(coords, &rigid), "MatNullSpaceCreateRigidBody");
  check(MatSetNearNullSpace(A, rigid), "MatSetNearNullSpace");
  check(MatNullSpaceDestroy(&rigid), "MatNullSpaceDestroy");
  check(VecDestroy(&coords), "VecDestroy");
}
} // namespace pushout::solver

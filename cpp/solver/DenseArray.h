// The column-major array of a sequential dense PETSc matrix (SEQDENSE),
// writable while a DenseArray lives: the condensation's Z, C and Jacobian
// entries (Condensation.h).
#pragma once

#include "../common/petsc_check.h"
#include <petscmat.h>

namespace pushout::solver
{
class DenseArray
{
public:
  explicit DenseArray(Mat M) : _A(M)
  {
    petsc::check(MatDenseGetLDA(_A, &_lda), "MatDenseGetLDA");
    petsc::check(MatDenseGetArray(_A, &_a), "MatDenseGetArray");
  }
  ~DenseArray() { petsc::check_nothrow(MatDenseRestoreArray(_A, &_a), "MatDenseRestoreArray"); }
  DenseArray(const DenseArray&) = delete;
  DenseArray& operator=(const DenseArray&) = delete;

  /// Entry (i, j), row i and column j.
  double& operator()(PetscInt i, PetscInt j) { return _a[i + j * _lda]; }

private:
  Mat _A;
  double* _a = nullptr;
  PetscInt _lda = 0; ///< leading dimension
};
} // namespace pushout::solver

#include "FactorizationFailure.h"
#include "../common/petsc_check.h"
#include "SinglePrecisionSparse.h"
#include <mpi.h>
#include <stdexcept>

namespace pushout::solver
{
using petsc::check;

namespace
{
/// A failed factorisation in words.
std::string factor_failure_text(PCFailedReason reason)
{
  switch (reason)
  {
  case PC_FACTOR_STRUCT_ZEROPIVOT:
    return "structurally zero pivot";
  case PC_FACTOR_NUMERIC_ZEROPIVOT:
    return "zero pivot";
  case PC_FACTOR_OUTMEMORY:
    return "out of memory";
  case PC_NOERROR:
    return "";
  default:
    return "the factorisation failed";
  }
}
} // namespace

std::string factorization_failure(KSP ksp)
{
  PC pc;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  PCFailedReason reason = PC_NOERROR;
  check(PCGetFailedReasonRank(pc, &reason), "PCGetFailedReasonRank");
  int worst = int(reason);
  MPI_Allreduce(MPI_IN_PLACE, &worst, 1, MPI_INT, MPI_MAX,
                PetscObjectComm(reinterpret_cast<PetscObject>(ksp)));
  // PETSc's MUMPS says "out of memory" for its workspace errors too
  // (INFOG(1) -8, -9, -11 ... -15, which delayed pivots cause): cut as any
  // failure. Only an allocation that failed is the machine's memory.
  if (PCFailedReason(worst) == PC_FACTOR_OUTMEMORY)
  {
    PetscBool factor = PETSC_FALSE;
    check(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCLU, &factor),
          "PetscObjectTypeCompare");
    MatSolverType type = nullptr;
    Mat F = nullptr;
    if (factor)
    {
      check(PCFactorGetMatSolverType(pc, &type), "PCFactorGetMatSolverType");
      check(PCFactorGetMatrix(pc, &F), "PCFactorGetMatrix");
    }
    if (type && std::string(type) == MATSOLVERMUMPS && F)
    {
      PetscInt infog1 = 0; // the same on every process
      check(MatMumpsGetInfog(F, 1, &infog1), "MatMumpsGetInfog");
      if (infog1 != mumps_allocation_failed)
        return "MUMPS's workspace (INFOG(1) = " + std::to_string(infog1) + ")";
    }
    throw std::runtime_error(
        "the LU factorisation ran out of memory: the model needs more memory than this "
        "machine or its limits (ulimit -v, a cgroup) give: fewer elements "
        "(mesh.elements_per_quarter, mesh.elements_through_thickness), or more processes on "
        "more machines");
  }
  return factor_failure_text(PCFailedReason(worst));
}

bool zero_pivot_error(PetscErrorCode code, MPI_Comm comm)
{
  int processes = 1;
  MPI_Comm_size(comm, &processes);
  return processes == 1 && (code == PETSC_ERR_MAT_LU_ZRPVT || code == PETSC_ERR_MAT_CH_ZRPVT);
}
} // namespace pushout::solver

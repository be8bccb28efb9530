// A PCSHELL that owns its context: the single-precision LU preconditioners
// (SinglePrecision.h, SinglePrecisionSparse.h) are made this way; and the
// flexible GMRES that such a preconditioner needs (its rounding depends on
// the right-hand side, so it is not quite linear).
#pragma once

#include "../common/petsc_check.h"
#include <petscksp.h>
#include <petscpc.h>

namespace pushout::solver
{
/// Makes `pc` a PCSHELL with a new Context, deleted with the PC, that PETSc
/// sets up with `set_up` (on new operators) and applies with `apply`.
template <typename Context>
void make_shell_preconditioner(PC pc, PetscErrorCode (*set_up)(PC),
                               PetscErrorCode (*apply)(PC, Vec, Vec), const char* name)
{
  using petsc::check;
  PetscErrorCode (*destroy)(PC) = [](PC shell) -> PetscErrorCode
  {
    Context* context = nullptr;
    const PetscErrorCode code = PCShellGetContext(shell, &context);
    delete context;
    return code;
  };
  check(PCSetType(pc, PCSHELL), "PCSetType");
  check(PCShellSetDestroy(pc, destroy), "PCShellSetDestroy"); // first: it owns the context
  check(PCShellSetContext(pc, new Context), "PCShellSetContext");
  check(PCShellSetSetUp(pc, set_up), "PCShellSetSetUp");
  check(PCShellSetApply(pc, apply), "PCShellSetApply");
  check(PCShellSetName(pc, name), "PCShellSetName");
}

/// Makes a GMRES `ksp` flexible (FGMRES, right preconditioning) keeping
/// what PETSc lets us read of its GMRES options (a user's -ksp_gmres_*):
/// the restart, the orthogonalisation and its refinement; not
/// -ksp_gmres_preallocate nor -ksp_gmres_haptol. The tolerances stay.
inline void make_gmres_flexible(KSP ksp)
{
  using petsc::check;
  PetscInt restart;
  PetscErrorCode (*orthogonalize)(KSP, PetscInt);
  KSPGMRESCGSRefinementType refinement;
  check(KSPGMRESGetRestart(ksp, &restart), "KSPGMRESGetRestart");
  check(KSPGMRESGetOrthogonalization(ksp, &orthogonalize), "KSPGMRESGetOrthogonalization");
  check(KSPGMRESGetCGSRefinementType(ksp, &refinement), "KSPGMRESGetCGSRefinementType");
  check(KSPSetType(ksp, KSPFGMRES), "KSPSetType");
  check(KSPGMRESSetRestart(ksp, restart), "KSPGMRESSetRestart");
  check(KSPGMRESSetOrthogonalization(ksp, orthogonalize), "KSPGMRESSetOrthogonalization");
  check(KSPGMRESSetCGSRefinementType(ksp, refinement), "KSPGMRESSetCGSRefinementType");
}
} // namespace pushout::solver

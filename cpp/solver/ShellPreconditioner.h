// A PCSHELL that owns its context: the single-precision LU preconditioners
// (SinglePrecision.h, SinglePrecisionSparse.h) are made this way; and the
// flexible GMRES that such a preconditioner needs (its rounding depends on
// the right-hand side, so it is not quite linear).
#pragma once

#include "../common/petsc_check.h"
#include "../scene/SceneError.h"
#include <petscksp.h>
#include <petscpc.h>
#include <string>

namespace pushout::solver
{
namespace detail
{
/// The name under which a shell made by make_shell_preconditioner carries
/// its Context's tag (PETSc's composed functions end in "_C").
inline constexpr const char* context_tag_name = "PushoutShellContext_C";

/// One function per Context type, composed on the shell as its tag: its
/// address says which Context the shell holds. The body reads a static of
/// its own, so that no linker folds two of them into one.
template <typename Context> void context_tag()
{
  static volatile char own = 0;
  (void)own;
}
} // namespace detail

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
  // A shell already (PCSetType would keep it as it is): the old one goes
  // first, its context with it.
  PetscBool shell = PETSC_FALSE;
  check(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCSHELL, &shell),
        "PetscObjectTypeCompare");
  if (shell)
    check(PCSetType(pc, PCNONE), "PCSetType");
  check(PCSetType(pc, PCSHELL), "PCSetType");
  check(PCShellSetDestroy(pc, destroy), "PCShellSetDestroy"); // first: it owns the context
  // The tag; PCSetType to another type and PCDestroy drop it with the
  // shell (they drop every composed function).
  check(PetscObjectComposeFunction(reinterpret_cast<PetscObject>(pc), detail::context_tag_name,
                                   &detail::context_tag<Context>),
        "PetscObjectComposeFunction");
  check(PCShellSetContext(pc, new Context), "PCShellSetContext");
  check(PCShellSetSetUp(pc, set_up), "PCShellSetSetUp");
  check(PCShellSetApply(pc, apply), "PCShellSetApply");
  check(PCShellSetName(pc, name), "PCShellSetName");
}

/// The Context of `pc` if make_shell_preconditioner<Context> made it (by
/// the tag it composed, not the shell's name); nullptr for any other PC.
template <typename Context> Context* shell_context(PC pc)
{
  using petsc::check;
  void (*tag)(void) = nullptr;
  check(PetscObjectQueryFunction(reinterpret_cast<PetscObject>(pc), detail::context_tag_name, &tag),
        "PetscObjectQueryFunction");
  if (tag != &detail::context_tag<Context>)
    return nullptr;
  Context* context = nullptr;
  check(PCShellGetContext(pc, &context), "PCShellGetContext");
  return context;
}

/// Makes a GMRES `ksp` flexible (FGMRES, right preconditioning) keeping
/// what PETSc lets us read of its GMRES options (a user's -ksp_gmres_*):
/// the restart, the orthogonalisation and its refinement; not
/// -ksp_gmres_preallocate nor -ksp_gmres_haptol. The tolerances stay.
/// Throws OptionError where the user's -ksp_pc_side (with the options'
/// `prefix`) asks for a side flexible GMRES has not (PETSc would fail in
/// the first solve, "does not support preconditioner side LEFT"), saying
/// what does have it (exit 2). PETSc reads the value as it does (any case).
inline void refuse_side_flexible_gmres_lacks(const char* prefix)
{
  PetscEnum side = PetscEnum(PC_RIGHT);
  PetscBool given = PETSC_FALSE;
  petsc::check(PetscOptionsGetEnum(nullptr, prefix, "-ksp_pc_side", PCSides, &side, &given),
               "PetscOptionsGetEnum");
  if (given && PCSide(side) != PC_RIGHT)
    throw OptionError(std::string("-ksp_pc_side ") +
                      (PCSide(side) == PC_LEFT ? "left" : "symmetric") +
                      ": GMRES on the single-precision LU (solver.precision = \"mixed\", the "
                      "default) is flexible GMRES, which preconditions on the right only; "
                      "with solver.precision = \"double\" it is GMRES on the LU in double, "
                      "which preconditions on the left too");
}

inline void make_gmres_flexible(KSP ksp)
{
  using petsc::check;
  const char* prefix = nullptr;
  check(KSPGetOptionsPrefix(ksp, &prefix), "KSPGetOptionsPrefix");
  refuse_side_flexible_gmres_lacks(prefix); // before the steps (and in check_options())
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

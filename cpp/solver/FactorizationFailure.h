// Why a factorisation of the Newton systems failed, in words, for the
// reasons of failed solves (NewtonSolver, ArcLengthSolver).
#pragma once

#include <petscksp.h>
#include <string>

namespace pushout::solver
{
/// Why the last set-up of the preconditioner of `ksp` failed on any of its
/// processes, in words ("zero pivot", ...; "" if it did not). Collective.
/// An allocation that failed (MUMPS out of memory) throws instead, on every
/// process alike: a smaller step needs as much memory, so the run ends (exit
/// 1) rather than being cut.
std::string factorization_failure(KSP ksp);

/// Whether a PETSc error code is a zero pivot of a factorisation that raises
/// an error instead of recording a failed reason (PETSc's dense LU: the
/// condensed systems', on one process), on `comm` of one process: on more,
/// a process's own factor (a block of -pc_type bjacobi) may raise it while
/// the others wait in the solve, so it is an error (agreed on, the run
/// ended), not a step cut on that process alone.
bool zero_pivot_error(PetscErrorCode code, MPI_Comm comm);
} // namespace pushout::solver

// Single precision for GMRES on the condensed Newton systems
// (Condensation.h): the LU factors of the lagged preconditioner here, the
// flexibility C in the Jacobian's action as a SymmetricMatrix<float>.
//
// Why: GMRES on the condensed system is bound by memory traffic, not by
// arithmetic. Each iteration streams C (the operator) and the LU factors
// (the preconditioner) once; on the half model of the paper's mesh with one
// crack plane (963 jumps) the LU factors are 7.4 MB in double. In single
// precision each is half the bytes.
//
// What it changes: the preconditioner only steers GMRES, and the rounding
// of its factors (~1e-7 relative) changes the path of the iterates, not the
// solution. The Jacobian's action in single precision makes each Newton
// step inexact by ~1e-7 relative (GMRES is asked for no more:
// single_precision_rtol), which Newton corrects in its next iteration: the
// residual (and so the converged solution and every Newton tolerance) stays
// in double precision. solver.precision = "double" keeps both in double.
//
// The kernels are compiled for the machine's widest vectors (AVX2 and FMA
// where the CPU has them, chosen at run time; the plain x86-64 ones
// elsewhere).
#pragma once

#include <petscpc.h>

namespace pushout::solver
{
/// The smallest relative tolerance of a Krylov solve whose operator is
/// applied in single precision (a few roundings of 6e-8).
constexpr double single_precision_rtol = 1e-7;

/// Makes `pc` (of a sequential KSP whose preconditioning matrix is dense) a
/// PCSHELL that applies the LU factors of that matrix, computed in double
/// precision (LAPACK getrf, partial pivoting) whenever PETSc sets the
/// preconditioner up, and kept and applied in single precision. A zero pivot
/// is reported as PETSc's factorisations report it (PCGetFailedReason:
/// PC_FACTOR_NUMERIC_ZEROPIVOT; the Newton solve fails with
/// DIVERGED_LINEAR_SOLVE and the step is cut).
void use_single_precision_lu(PC pc);
} // namespace pushout::solver

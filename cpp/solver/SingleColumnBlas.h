// The single-column products and triangular solves of MUMPS's single-
// precision back-solves, done by the BLAS's matrix-vector routines.
//
// Why: a back-solve with one right-hand side (every GMRES iteration on the
// lagged LU, SinglePrecisionSparse.h) walks the factors' fronts and calls
// the BLAS's matrix-matrix routines sgemm and strsm with a single column.
// OpenBLAS takes those through its matrix-matrix machinery: its small-
// matrix kernel and, in strsm, a packed copy of each front's triangle made
// before it is used once. The same operations as sgemv and strsv stream
// each factor entry once. On the bench's IMPL-EX case
// (docs/cracking-speed.md) a back-solve took about 12 ms instead of 15.3 ms.
//
// How: SingleColumnBlas.cpp defines sgemm_ and strsm_ in the program. The
// dynamic linker binds MUMPS's calls (and any other caller's) to the
// program's definitions before the BLAS library's; a call with one column
// is done by sgemv_ / strsv_ (the same result up to the order of the sums),
// and every other call is passed on unchanged to the BLAS library's own
// sgemm_ / strsm_ (found with dlsym(RTLD_NEXT)). Only single precision:
// PETSc and the double-precision MUMPS use the double-precision routines,
// which are left alone.
#pragma once

#include <cstdint>

namespace pushout::solver
{
/// Whether the BLAS's sgemm_ and strsm_ seen by the libraries of this
/// process are the single-column ones of SingleColumnBlas.cpp. Throws
/// std::runtime_error if the BLAS library's own, which they pass the other
/// calls to, cannot be found (called before MUMPS runs: a missing routine
/// found in a call from Fortran could only abort).
bool single_column_blas_bound();

/// The calls with one column (or one row of a right solve) done by sgemv /
/// strsv in this process so far.
std::int64_t single_column_calls();
} // namespace pushout::solver

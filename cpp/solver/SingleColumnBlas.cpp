#include "SingleColumnBlas.h"
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <dlfcn.h>

// The Fortran BLAS interface, as gfortran calls it: every argument by
// address, then the lengths of the character arguments.
using fortran_length = std::size_t;

extern "C"
{
  void sgemv_(const char* trans, const int* m, const int* n, const float* alpha, const float* a,
              const int* lda, const float* x, const int* incx, const float* beta, float* y,
              const int* incy, fortran_length trans_length);
  void strsv_(const char* uplo, const char* trans, const char* diag, const int* n, const float* a,
              const int* lda, float* x, const int* incx, fortran_length uplo_length,
              fortran_length trans_length, fortran_length diag_length);
  void sscal_(const int* n, const float* alpha, float* x, const int* incx);

  void sgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
              const float* alpha, const float* a, const int* lda, const float* b, const int* ldb,
              const float* beta, float* c, const int* ldc, fortran_length transa_length,
              fortran_length transb_length);
  void strsm_(const char* side, const char* uplo, const char* transa, const char* diag,
              const int* m, const int* n, const float* alpha, const float* a, const int* lda,
              float* b, const int* ldb, fortran_length side_length, fortran_length uplo_length,
              fortran_length transa_length, fortran_length diag_length);
}

namespace
{
using gemm_function = decltype(&sgemm_);
using trsm_function = decltype(&strsm_);

/// The BLAS library's own definition of `name`, the next after this
/// program's. Called from Fortran, so a failure cannot be thrown: it stops
/// the process with a message (it would mean that no BLAS is loaded).
template <typename Function> Function blas_library(const char* name)
{
  void* f = dlsym(RTLD_NEXT, name);
  if (f == nullptr)
  {
    std::fprintf(stderr, "pushout: the BLAS library's %s was not found (%s)\n", name, dlerror());
    std::abort();
  }
  return reinterpret_cast<Function>(f);
}

bool transposed(const char* trans)
{
  return *trans != 'N' && *trans != 'n';
}
bool left(const char* side)
{
  return *side == 'L' || *side == 'l';
}
} // namespace

extern "C"
{
  /// C = alpha op(A) op(B) + beta C; with one column (n = 1) op(B) is a
  /// vector (a column of B, or a row with stride ldb), so C's column is
  /// sgemv's y.
  void sgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
              const float* alpha, const float* a, const int* lda, const float* b, const int* ldb,
              const float* beta, float* c, const int* ldc, fortran_length transa_length,
              fortran_length transb_length)
  {
    if (*n == 1 && *m > 0 && *k > 0)
    {
      const int incx = transposed(transb) ? *ldb : 1, incy = 1;
      if (transposed(transa)) // A is k x m
        sgemv_("T", k, m, alpha, a, lda, b, &incx, beta, c, &incy, 1);
      else // A is m x k
        sgemv_("N", m, k, alpha, a, lda, b, &incx, beta, c, &incy, 1);
      return;
    }
    static const gemm_function library = blas_library<gemm_function>("sgemm_");
    library(transa, transb, m, n, k, alpha, a, lda, b, ldb, beta, c, ldc, transa_length,
            transb_length);
  }

  /// op(A) X = alpha B (side L) or X op(A) = alpha B (side R), B m x n
  /// overwritten by X. One column of a left solve (n = 1) is strsv's x; one
  /// row of a right solve (m = 1, stride ldb) is too, with op(A) transposed:
  /// x op(A) = b is op(A)^T x^T = b^T.
  void strsm_(const char* side, const char* uplo, const char* transa, const char* diag,
              const int* m, const int* n, const float* alpha, const float* a, const int* lda,
              float* b, const int* ldb, fortran_length side_length, fortran_length uplo_length,
              fortran_length transa_length, fortran_length diag_length)
  {
    const bool column = left(side) && *n == 1 && *m > 0;
    const bool row = !left(side) && *m == 1 && *n > 0;
    if (column || row)
    {
      const int size = column ? *m : *n, stride = column ? 1 : *ldb;
      // A row's solve is with op(A) transposed.
      const bool solve_transposed = column ? transposed(transa) : !transposed(transa);
      if (*alpha == 0.0f) // strsm does not read A then
      {
        for (int i = 0; i < size; ++i)
          b[std::size_t(i) * std::size_t(stride)] = 0.0f;
        return;
      }
      if (*alpha != 1.0f)
        sscal_(&size, alpha, b, &stride);
      strsv_(uplo, solve_transposed ? "T" : "N", diag, &size, a, lda, b, &stride, 1, 1, 1);
      return;
    }
    static const trsm_function library = blas_library<trsm_function>("strsm_");
    library(side, uplo, transa, diag, m, n, alpha, a, lda, b, ldb, side_length, uplo_length,
            transa_length, diag_length);
  }
}

namespace pushout::solver
{
bool single_column_blas_bound()
{
  return dlsym(RTLD_DEFAULT, "sgemm_") == reinterpret_cast<void*>(&sgemm_) &&
         dlsym(RTLD_DEFAULT, "strsm_") == reinterpret_cast<void*>(&strsm_);
}
} // namespace pushout::solver

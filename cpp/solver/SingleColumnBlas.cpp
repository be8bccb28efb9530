#include "SingleColumnBlas.h"
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <dlfcn.h>
#include <stdexcept>

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
/// The BLAS library's own sgemm_ and strsm_, the next definitions after
/// this program's (null if there is none: single_column_blas_bound() says
/// so before MUMPS runs).
struct Library
{
  decltype(&sgemm_) gemm = nullptr;
  decltype(&strsm_) trsm = nullptr;
};

const Library& library()
{
  static const Library l{reinterpret_cast<decltype(&sgemm_)>(dlsym(RTLD_NEXT, "sgemm_")),
                         reinterpret_cast<decltype(&strsm_)>(dlsym(RTLD_NEXT, "strsm_"))};
  return l;
}

/// Called from Fortran, so a failure cannot be thrown: a call that only the
/// library can make, without the library, stops the process with a message.
void missing(const char* name)
{
  std::fprintf(stderr, "pushout: the BLAS library's %s was not found\n", name);
  std::abort();
}

/// single_column_calls()
std::atomic<std::int64_t> single_columns{0};

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
      single_columns.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    if (!library().gemm)
      missing("sgemm_");
    library().gemm(transa, transb, m, n, k, alpha, a, lda, b, ldb, beta, c, ldc, transa_length,
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
      single_columns.fetch_add(1, std::memory_order_relaxed);
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
    if (!library().trsm)
      missing("strsm_");
    library().trsm(side, uplo, transa, diag, m, n, alpha, a, lda, b, ldb, side_length, uplo_length,
                   transa_length, diag_length);
  }
}

namespace pushout::solver
{
bool single_column_blas_bound()
{
  if (!library().gemm || !library().trsm)
    throw std::runtime_error("the BLAS library's sgemm_ and strsm_ were not found after "
                             "pushout's own (cpp/solver/SingleColumnBlas.h): is a BLAS linked?");
  return dlsym(RTLD_DEFAULT, "sgemm_") == reinterpret_cast<void*>(&sgemm_) &&
         dlsym(RTLD_DEFAULT, "strsm_") == reinterpret_cast<void*>(&strsm_);
}

std::int64_t single_column_calls()
{
  return single_columns.load(std::memory_order_relaxed);
}
} // namespace pushout::solver

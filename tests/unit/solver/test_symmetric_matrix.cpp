// The packed symmetric matrix of the condensed flexibility
// (solver/SymmetricMatrix.h): its products agree with the full matrix's
// (PETSc's MatMult) to the rounding of its precision, for sizes around the
// kernel's vector lanes and for a column stride other than the size;
// asymmetry is measured and averaged away.
#include "common/petsc_check.h"
#include "solver/SymmetricMatrix.h"
#include <cmath>
#include <gtest/gtest.h>
#include <random>
#include <vector>

using namespace pushout;
using petsc::check;

namespace
{
/// A random n x n dense matrix with entries in [-1, 1]: symmetric, or with
/// a_ij - a_ji = `skew` for i < j.
Mat random_matrix(PetscInt n, unsigned seed, double skew = 0.0)
{
  Mat A;
  check(MatCreateSeqDense(PETSC_COMM_SELF, n, n, nullptr, &A), "MatCreateSeqDense");
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> U(-1, 1);
  for (PetscInt i = 0; i < n; ++i)
    for (PetscInt j = i; j < n; ++j)
    {
      const double a = U(gen);
      check(MatSetValue(A, i, j, a, INSERT_VALUES), "MatSetValue");
      check(MatSetValue(A, j, i, i == j ? a : a - skew, INSERT_VALUES), "MatSetValue");
    }
  check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  return A;
}

/// max |A x - S x| / max |A x| for a random x.
template <class T> double product_error(Mat A, const solver::SymmetricMatrix<T>& S)
{
  Vec x, y;
  check(MatCreateVecs(A, &x, &y), "MatCreateVecs");
  check(VecSetRandom(x, nullptr), "VecSetRandom");
  check(MatMult(A, x, y), "MatMult");
  PetscInt n;
  check(VecGetSize(x, &n), "VecGetSize");
  std::vector<double> ys(std::size_t(n), -1.0);
  const double *xa, *ya;
  check(VecGetArrayRead(x, &xa), "VecGetArrayRead");
  check(VecGetArrayRead(y, &ya), "VecGetArrayRead");
  S.multiply(xa, ys.data());
  double scale = 0, worst = 0;
  for (PetscInt i = 0; i < n; ++i)
  {
    scale = std::max(scale, std::abs(ya[i]));
    worst = std::max(worst, std::abs(ya[i] - ys[std::size_t(i)]));
  }
  check(VecRestoreArrayRead(x, &xa), "VecRestoreArrayRead");
  check(VecRestoreArrayRead(y, &ya), "VecRestoreArrayRead");
  check(VecDestroy(&x), "VecDestroy");
  check(VecDestroy(&y), "VecDestroy");
  return worst / scale;
}
} // namespace

TEST(SymmetricMatrix, ProductsAgreeWithTheFullMatrix)
{
  // Sizes below, at and around the kernel's lanes (16 floats, 8 doubles).
  for (PetscInt n : {1, 2, 7, 8, 9, 16, 17, 33, 100})
  {
    Mat A = random_matrix(n, unsigned(n));
    const solver::SymmetricMatrix<double> Sd(A);
    const solver::SymmetricMatrix<float> Sf(A);
    EXPECT_EQ(Sd.size(), std::size_t(n));
    EXPECT_LT(product_error(A, Sd), 1e-14) << "n = " << n;
    EXPECT_LT(product_error(A, Sf), 1e-6) << "n = " << n;
    check(MatDestroy(&A), "MatDestroy");
  }
}

TEST(SymmetricMatrix, AsymmetryIsMeasuredAndAveragedAway)
{
  const PetscInt n = 20;
  Mat A = random_matrix(n, 3, 1e-3);
  double largest = 0;
  {
    const double* a;
    check(MatDenseGetArrayRead(A, &a), "MatDenseGetArrayRead");
    for (PetscInt k = 0; k < n * n; ++k)
      largest = std::max(largest, std::abs(a[k]));
    check(MatDenseRestoreArrayRead(A, &a), "MatDenseRestoreArrayRead");
  }
  EXPECT_NEAR(solver::relative_asymmetry(A), 1e-3 / largest, 1e-12);
  solver::symmetrize(A);
  EXPECT_EQ(solver::relative_asymmetry(A), 0.0);
  // The average: a_ij = a_ji = a_ij(before) - skew / 2 for i < j.
  Mat B = random_matrix(n, 3, 1e-3);
  const PetscInt i = 2, j = 11;
  double a_ij, b_ij;
  check(MatGetValues(A, 1, &i, 1, &j, &a_ij), "MatGetValues");
  check(MatGetValues(B, 1, &i, 1, &j, &b_ij), "MatGetValues");
  EXPECT_NEAR(a_ij, b_ij - 0.5e-3, 1e-15);
  check(MatDestroy(&A), "MatDestroy");
  check(MatDestroy(&B), "MatDestroy");
}

TEST(SymmetricMatrix, ReadsAMatrixWhoseColumnStrideIsNotItsSize)
{
  // The leading 30 x 30 block of a 40 x 40 matrix (column stride 40), as
  // condensation's dense matrices may be laid out.
  const PetscInt N = 40, n = 30;
  Mat big = random_matrix(N, 7), A;
  check(MatDenseGetSubMatrix(big, 0, n, 0, n, &A), "MatDenseGetSubMatrix");
  PetscInt lda;
  check(MatDenseGetLDA(A, &lda), "MatDenseGetLDA");
  ASSERT_EQ(lda, N);
  const solver::SymmetricMatrix<double> Sd(A);
  const solver::SymmetricMatrix<float> Sf(A);
  EXPECT_EQ(solver::relative_asymmetry(A), 0.0);
  EXPECT_LT(product_error(A, Sd), 1e-14);
  EXPECT_LT(product_error(A, Sf), 1e-6);
  check(MatDenseRestoreSubMatrix(big, &A), "MatDenseRestoreSubMatrix");
  check(MatDestroy(&big), "MatDestroy");
}

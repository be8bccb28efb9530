// petsc::BlockAdd (common/BlockAdd.h) adds element matrices of 3 x 3 blocks
// as MatSetValuesBlockedLocal(..., ADD_VALUES) does: in place into an
// assembled AIJ matrix (through its local-to-global map of blocks; on
// several processes the owned rows, a ghost node's rows through the
// stash), skipping negative indices; a block outside the pattern is an
// error; a matrix it cannot add to in place (not assembled) goes through
// MatSetValuesBlockedLocal.
#include "common/BlockAdd.h"
#include "common/petsc_check.h"
#include <array>
#include <cstdint>
#include <gtest/gtest.h>
#include <mpi.h>
#include <petscmat.h>
#include <stdexcept>
#include <vector>

namespace
{
using pushout::petsc::BlockAdd;
using pushout::petsc::check;

constexpr PetscInt nodes = 5, bs = 3;

/// Reproducible values of an element matrix of `n` blocks square.
std::vector<double> element(std::size_t n, double seed)
{
  std::vector<double> v(9 * n * n);
  for (std::size_t k = 0; k < v.size(); ++k)
    v[k] = seed + 0.37 * double(k) - 0.011 * double(k * k % 97);
  return v;
}

/// A sequential AIJ matrix of block size 3 whose local blocks map to
/// global ones by a permutation, with the pattern of two elements, local
/// blocks {0, 1, 2} and {2, 3, 4}, filled with values and assembled
/// (unless `assemble` is false).
Mat make_matrix(bool assemble = true)
{
  Mat A;
  check(MatCreateSeqAIJ(PETSC_COMM_SELF, bs * nodes, bs * nodes, 9 * bs, nullptr, &A),
        "MatCreateSeqAIJ");
  check(MatSetBlockSize(A, bs), "MatSetBlockSize");
  const std::array<PetscInt, nodes> global = {3, 0, 4, 1, 2};
  ISLocalToGlobalMapping map;
  check(ISLocalToGlobalMappingCreate(PETSC_COMM_SELF, bs, nodes, global.data(), PETSC_COPY_VALUES,
                                     &map),
        "ISLocalToGlobalMappingCreate");
  check(MatSetLocalToGlobalMapping(A, map, map), "MatSetLocalToGlobalMapping");
  check(ISLocalToGlobalMappingDestroy(&map), "ISLocalToGlobalMappingDestroy");
  for (const std::array<std::int32_t, 3>& e : {std::array<std::int32_t, 3>{0, 1, 2}, {2, 3, 4}})
    check(
        MatSetValuesBlockedLocal(A, 3, e.data(), 3, e.data(), element(3, e[0]).data(), ADD_VALUES),
        "MatSetValuesBlockedLocal");
  if (assemble)
  {
    check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  }
  return A;
}

void assemble(Mat A)
{
  check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
}

/// Every entry of A and B after their assembly, compared exactly (the same
/// additions in the same order give the same sums); both destroyed.
void expect_same(Mat A, Mat B)
{
  assemble(A);
  assemble(B);
  for (PetscInt i = 0; i < bs * nodes; ++i)
    for (PetscInt j = 0; j < bs * nodes; ++j)
    {
      PetscScalar a, b;
      check(MatGetValue(A, i, j, &a), "MatGetValue");
      check(MatGetValue(B, i, j, &b), "MatGetValue");
      EXPECT_EQ(a, b) << "entry (" << i << ", " << j << ")";
    }
  MatDestroy(&A);
  MatDestroy(&B);
}
} // namespace

TEST(BlockAdd, AddsInPlaceAsMatSetValuesBlockedLocal)
{
  Mat A = make_matrix(), B = make_matrix();
  const std::vector<std::array<std::int32_t, 3>> elements = {{2, 3, 4}, {0, 1, 2}, {2, -1, 4}};
  {
    BlockAdd add(A);
    EXPECT_TRUE(add.in_place());
    for (std::size_t e = 0; e < elements.size(); ++e)
      add(elements[e], elements[e], element(3, 10.0 + double(e)));
  }
  for (std::size_t e = 0; e < elements.size(); ++e)
    check(MatSetValuesBlockedLocal(B, 3, elements[e].data(), 3, elements[e].data(),
                                   element(3, 10.0 + double(e)).data(), ADD_VALUES),
          "MatSetValuesBlockedLocal");
  expect_same(A, B);
}

TEST(BlockAdd, BlockOutsideThePatternIsAnError)
{
  Mat A = make_matrix();
  {
    BlockAdd add(A);
    ASSERT_TRUE(add.in_place());
    const std::array<std::int32_t, 2> apart = {0, 4}; // never in one element
    EXPECT_THROW(add(apart, apart, element(2, 1.0)), std::runtime_error);
  }
  MatDestroy(&A);
}

TEST(BlockAdd, MatrixNotAssembledGoesThroughPetsc)
{
  Mat A = make_matrix(false), B = make_matrix(false);
  const std::array<std::int32_t, 3> e = {2, 3, 4};
  {
    BlockAdd add(A);
    EXPECT_FALSE(add.in_place());
    add(e, e, element(3, 5.0));
  }
  check(MatSetValuesBlockedLocal(B, 3, e.data(), 3, e.data(), element(3, 5.0).data(), ADD_VALUES),
        "MatSetValuesBlockedLocal");
  expect_same(A, B);
}

namespace
{
/// A parallel AIJ matrix of block size 3 over the processes of
/// PETSC_COMM_WORLD (a sequential one on one process): each owns three
/// nodes, 3r to 3r + 2, and sees the next process's first node as a
/// ghost, its local block 3; the pattern of the elements `parallel_elements`,
/// filled with values and assembled.
const std::vector<std::vector<std::int32_t>> parallel_elements = {{0, 1, 2}, {2, 3}, {1, 3}};

Mat make_parallel_matrix()
{
  int rank = 0, size = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  Mat A;
  check(MatCreate(PETSC_COMM_WORLD, &A), "MatCreate");
  check(MatSetSizes(A, 3 * bs, 3 * bs, PETSC_DETERMINE, PETSC_DETERMINE), "MatSetSizes");
  check(MatSetType(A, MATAIJ), "MatSetType");
  check(MatSetBlockSize(A, bs), "MatSetBlockSize");
  check(MatSeqAIJSetPreallocation(A, 4 * bs, nullptr), "MatSeqAIJSetPreallocation");
  check(MatMPIAIJSetPreallocation(A, 4 * bs, nullptr, 4 * bs, nullptr),
        "MatMPIAIJSetPreallocation");
  const std::array<PetscInt, 4> global = {3 * rank, 3 * rank + 1, 3 * rank + 2,
                                          3 * ((rank + 1) % size)};
  ISLocalToGlobalMapping map;
  check(
      ISLocalToGlobalMappingCreate(PETSC_COMM_WORLD, bs, 4, global.data(), PETSC_COPY_VALUES, &map),
      "ISLocalToGlobalMappingCreate");
  check(MatSetLocalToGlobalMapping(A, map, map), "MatSetLocalToGlobalMapping");
  check(ISLocalToGlobalMappingDestroy(&map), "ISLocalToGlobalMappingDestroy");
  for (const std::vector<std::int32_t>& e : parallel_elements)
    check(MatSetValuesBlockedLocal(A, PetscInt(e.size()), e.data(), PetscInt(e.size()), e.data(),
                                   element(e.size(), double(e[0] + 7 * rank)).data(), ADD_VALUES),
          "MatSetValuesBlockedLocal");
  assemble(A);
  return A;
}
} // namespace

// Under mpirun (tests/CMakeLists.txt) the matrix is parallel: the owned
// rows are added in place into its diagonal part (owned columns) and its
// off-diagonal one (the ghost's columns), the ghost's rows go to their
// owner at the assembly. Compared exactly: the same additions in the same
// order, the ghost rows' at the assembly in both.
TEST(BlockAdd, AddsInPlaceAsMatSetValuesBlockedLocalOnEveryProcess)
{
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  Mat A = make_parallel_matrix(), B = make_parallel_matrix();
  const std::vector<std::vector<std::int32_t>> elements = {{2, 3}, {0, 1, 2}, {3, -1, 1}};
  // Two additions before the assembly, as a Jacobian's joints and cracks:
  // the second is in place too, though the first left a ghost node's rows
  // in the matrix's stash.
  for (const std::size_t first : {std::size_t(0), std::size_t(2)})
  {
    BlockAdd add(A);
    EXPECT_TRUE(add.in_place()) << "the addition from element " << first;
    for (std::size_t e = first; e < (first == 0 ? 2 : elements.size()); ++e)
      add(elements[e], elements[e], element(elements[e].size(), 10.0 + double(e + rank)));
  }
  for (std::size_t e = 0; e < elements.size(); ++e)
    check(MatSetValuesBlockedLocal(B, PetscInt(elements[e].size()), elements[e].data(),
                                   PetscInt(elements[e].size()), elements[e].data(),
                                   element(elements[e].size(), 10.0 + double(e + rank)).data(),
                                   ADD_VALUES),
          "MatSetValuesBlockedLocal");
  assemble(A);
  assemble(B);
  PetscInt first = 0, end = 0;
  check(MatGetOwnershipRange(A, &first, &end), "MatGetOwnershipRange");
  for (PetscInt i = first; i < end; ++i)
  {
    PetscInt na = 0, nb = 0;
    const PetscInt *ca = nullptr, *cb = nullptr;
    const PetscScalar *va = nullptr, *vb = nullptr;
    check(MatGetRow(A, i, &na, &ca, &va), "MatGetRow");
    const std::vector<PetscInt> cols_a(ca, ca + na);
    const std::vector<PetscScalar> values_a(va, va + na);
    check(MatRestoreRow(A, i, &na, &ca, &va), "MatRestoreRow");
    check(MatGetRow(B, i, &nb, &cb, &vb), "MatGetRow");
    const std::vector<PetscInt> cols_b(cb, cb + nb);
    const std::vector<PetscScalar> values_b(vb, vb + nb);
    check(MatRestoreRow(B, i, &nb, &cb, &vb), "MatRestoreRow");
    EXPECT_EQ(cols_a, cols_b) << "row " << i;
    EXPECT_EQ(values_a, values_b) << "row " << i;
  }
  MatDestroy(&A);
  MatDestroy(&B);
}

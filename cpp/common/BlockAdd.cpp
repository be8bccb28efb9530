#include "BlockAdd.h"
#include "build_or_release.h"
#include "petsc_check.h"
#include <algorithm>
#include <stdexcept>
#include <string>

namespace pushout::petsc
{
namespace
{
constexpr PetscInt bs = 3; ///< a node's displacements
}

BlockAdd::BlockAdd(Mat A) : _A(A)
{
  PetscBool seq = PETSC_FALSE, assembled = PETSC_FALSE;
  check(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(A), MATSEQAIJ, &seq),
        "PetscObjectTypeCompare");
  check(MatAssembled(A, &assembled), "MatAssembled");
  PetscInt block = 0;
  check(MatGetBlockSize(A, &block), "MatGetBlockSize");
  ISLocalToGlobalMapping map = nullptr, col_map = nullptr;
  check(MatGetLocalToGlobalMapping(A, &map, &col_map), "MatGetLocalToGlobalMapping");
  // Both maps of node blocks (or none: local is global).
  PetscInt row_block = bs, col_block = bs;
  if (map)
    check(ISLocalToGlobalMappingGetBlockSize(map, &row_block),
          "ISLocalToGlobalMappingGetBlockSize");
  if (col_map)
    check(ISLocalToGlobalMappingGetBlockSize(col_map, &col_block),
          "ISLocalToGlobalMappingGetBlockSize");
  if (!seq || !assembled || block != bs || !map != !col_map || row_block != bs || col_block != bs)
    return; // MatSetValuesBlockedLocal
  PetscBool done = PETSC_FALSE;
  check(MatGetRowIJ(A, 0, PETSC_FALSE, PETSC_FALSE, &_n, &_ia, &_ja, &done), "MatGetRowIJ");
  if (!done)
    return;
  build_or_release(
      [&]
      {
        if (map)
        {
          _maps = {map, col_map};
          for (int k = 0; k < 2; ++k)
            check(ISLocalToGlobalMappingGetBlockIndices(_maps[k], &_blocks[k]),
                  "ISLocalToGlobalMappingGetBlockIndices");
        }
        check(MatSeqAIJGetArray(A, &_a), "MatSeqAIJGetArray");
      },
      [this] { restore(); });
}

BlockAdd::~BlockAdd()
{
  restore();
}

void BlockAdd::restore() noexcept
{
  // Not thrown from a destructor: said, as PETSc's other unchecked calls.
  if (_a)
    check_nothrow(MatSeqAIJRestoreArray(_A, &_a), "MatSeqAIJRestoreArray");
  for (int k = 0; k < 2; ++k)
    if (_blocks[k])
      check_nothrow(ISLocalToGlobalMappingRestoreBlockIndices(_maps[k], &_blocks[k]),
                    "ISLocalToGlobalMappingRestoreBlockIndices");
  if (_ia)
  {
    PetscBool done;
    check_nothrow(MatRestoreRowIJ(_A, 0, PETSC_FALSE, PETSC_FALSE, &_n, &_ia, &_ja, &done),
                  "MatRestoreRowIJ");
  }
}

int BlockAdd::operator()(std::span<const std::int32_t> rows, std::span<const std::int32_t> cols,
                         std::span<const double> values)
{
  const std::size_t width = bs * cols.size(); // of a row of `values`
  if (!_a)
  {
    check(MatSetValuesBlockedLocal(_A, PetscInt(rows.size()), rows.data(), PetscInt(cols.size()),
                                   cols.data(), values.data(), ADD_VALUES),
          "MatSetValuesBlockedLocal");
    return 0;
  }
  // Local block indices to global ones, by the rows' map (k 0) or the
  // columns' (k 1).
  const auto global = [&](int k, std::int32_t local)
  { return _blocks[k] ? _blocks[k][local] : PetscInt(local); };
  for (std::size_t i = 0; i < rows.size(); ++i)
  {
    if (rows[i] < 0)
      continue;
    const PetscInt row = bs * global(0, rows[i]);
    for (std::size_t j = 0; j < cols.size(); ++j)
    {
      if (cols[j] < 0)
        continue;
      const PetscInt col = bs * global(1, cols[j]);
      std::ptrdiff_t offset = -1; // of the block's first column in its first row
      for (PetscInt a = 0; a < bs; ++a)
      {
        // The block's three columns lie one after the other in each of its
        // rows (sorted), at the same place in each (the rows of a node have
        // the same columns): searched for in the first row, checked in the
        // others (and searched for again where that does not hold).
        const PetscInt *begin = _ja + _ia[row + a], *end = _ja + _ia[row + a + 1];
        const PetscInt* at = offset >= 0 && offset < end - begin && begin[offset] == col
                                 ? begin + offset
                                 : std::lower_bound(begin, end, col);
        if (end - at < bs || at[0] != col || at[bs - 1] != col + bs - 1)
          throw std::runtime_error("a 3 x 3 block at row " + std::to_string(row + a) + ", column " +
                                   std::to_string(col) + " is not in the matrix's pattern");
        offset = at - begin;
        PetscScalar* target = _a + (at - _ja);
        const double* source = values.data() + (bs * i + std::size_t(a)) * width + bs * j;
        for (PetscInt b = 0; b < bs; ++b)
          target[b] += source[b];
      }
    }
  }
  return 0;
}
} // namespace pushout::petsc

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

bool is_type(Mat A, const char* type)
{
  PetscBool same = PETSC_FALSE;
  check(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(A), type, &same),
        "PetscObjectTypeCompare");
  return same;
}
} // namespace

BlockAdd::BlockAdd(Mat A) : _A(A)
{
  const bool seq = is_type(A, MATSEQAIJ), mpi = is_type(A, MATMPIAIJ);
  Mat diagonal = A, off_diagonal = nullptr; // the parts with the rows' values
  if (mpi)
  {
    check(MatMPIAIJGetSeqAIJ(A, &diagonal, &off_diagonal, &_ghost_columns), "MatMPIAIJGetSeqAIJ");
    check(MatGetSize(off_diagonal, nullptr, &_n_ghost_columns), "MatGetSize");
  }
  // Assembled, so that each row's columns are final and sorted. A parallel
  // matrix's parts are asked, not the matrix itself: a ghost node's rows
  // added since its assembly (this class's, for another BlockAdd before
  // the matrix is assembled again) wait in its stash and leave the parts
  // as they are. Its off-diagonal part's columns must be those of its
  // sorted ghost columns (none before the first assembly).
  PetscBool assembled = PETSC_FALSE, off_assembled = PETSC_TRUE;
  check(MatAssembled(diagonal, &assembled), "MatAssembled");
  if (off_diagonal)
    check(MatAssembled(off_diagonal, &off_assembled), "MatAssembled");
  assembled =
      PetscBool(assembled && off_assembled && (!mpi || _ghost_columns || _n_ghost_columns == 0));
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
  if (!(seq || (mpi && map)) || !assembled || block != bs || !map != !col_map || row_block != bs ||
      col_block != bs)
    return; // MatSetValuesBlockedLocal
  check(MatGetOwnershipRange(A, &_row_start, &_row_end), "MatGetOwnershipRange");
  check(MatGetOwnershipRangeColumn(A, &_col_start, &_col_end), "MatGetOwnershipRangeColumn");
  build_or_release(
      [&]
      {
        _parts[0].M = diagonal;
        _parts[1].M = off_diagonal;
        for (Part& part : _parts)
          if (part.M && !get(part))
          {
            restore();
            _parts = {};
            return;
          }
        if (map)
        {
          _maps = {map, col_map};
          for (int k = 0; k < 2; ++k)
            check(ISLocalToGlobalMappingGetBlockIndices(_maps[k], &_blocks[k]),
                  "ISLocalToGlobalMappingGetBlockIndices");
        }
      },
      [this] { restore(); });
}

bool BlockAdd::get(Part& part)
{
  PetscBool done = PETSC_FALSE;
  check(MatGetRowIJ(part.M, 0, PETSC_FALSE, PETSC_FALSE, &part.n, &part.ia, &part.ja, &done),
        "MatGetRowIJ");
  if (!done)
  {
    part.ia = part.ja = nullptr;
    return false;
  }
  check(MatSeqAIJGetArray(part.M, &part.a), "MatSeqAIJGetArray");
  return true;
}

BlockAdd::~BlockAdd()
{
  restore();
}

void BlockAdd::restore() noexcept
{
  // Not thrown from a destructor: said, as PETSc's other unchecked calls.
  for (Part& part : _parts)
  {
    if (part.a)
    {
      check_nothrow(MatSeqAIJRestoreArray(part.M, &part.a), "MatSeqAIJRestoreArray");
      part.a = nullptr;
    }
    if (part.ia)
    {
      PetscBool done;
      check_nothrow(
          MatRestoreRowIJ(part.M, 0, PETSC_FALSE, PETSC_FALSE, &part.n, &part.ia, &part.ja, &done),
          "MatRestoreRowIJ");
      part.ia = part.ja = nullptr;
    }
  }
  for (int k = 0; k < 2; ++k)
    if (_blocks[k])
    {
      check_nothrow(ISLocalToGlobalMappingRestoreBlockIndices(_maps[k], &_blocks[k]),
                    "ISLocalToGlobalMappingRestoreBlockIndices");
      _blocks[k] = nullptr;
    }
}

void BlockAdd::add_block(PetscInt row, PetscInt col, const double* source, std::size_t width)
{
  // The part that holds the column, and the column's index there.
  const bool diagonal = col >= _col_start && col < _col_end;
  const Part& part = _parts[diagonal ? 0 : 1];
  PetscInt at_col = col - _col_start;
  if (!diagonal)
  {
    const PetscInt* end = _ghost_columns + _n_ghost_columns;
    const PetscInt* g = std::lower_bound(_ghost_columns, end, col);
    at_col = PetscInt(g - _ghost_columns);
    if (!part.a || end - g < bs || g[0] != col || g[bs - 1] != col + bs - 1)
      at_col = -1;
  }
  std::ptrdiff_t offset = -1; // of the block's first column in its first row
  for (PetscInt a = 0; a < bs; ++a)
  {
    // The block's three columns lie one after the other in each of its
    // rows (sorted), at the same place in each (the rows of a node have
    // the same columns): searched for in the first row, checked in the
    // others (and searched for again where that does not hold).
    const PetscInt local_row = row - _row_start + a;
    const PetscInt *begin = part.ja + part.ia[local_row], *end = part.ja + part.ia[local_row + 1];
    const PetscInt* at = offset >= 0 && offset < end - begin && begin[offset] == at_col
                             ? begin + offset
                             : std::lower_bound(begin, end, at_col);
    if (at_col < 0 || end - at < bs || at[0] != at_col || at[bs - 1] != at_col + bs - 1)
      throw std::runtime_error("a 3 x 3 block at row " + std::to_string(row + a) + ", column " +
                               std::to_string(col) + " is not in the matrix's pattern");
    offset = at - begin;
    PetscScalar* target = part.a + (at - part.ja);
    const double* from = source + std::size_t(a) * width;
    for (PetscInt b = 0; b < bs; ++b)
      target[b] += from[b];
  }
}

int BlockAdd::operator()(std::span<const std::int32_t> rows, std::span<const std::int32_t> cols,
                         std::span<const double> values)
{
  const std::size_t width = bs * cols.size(); // of a row of `values`
  if (!in_place())
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
    const double* block_row = values.data() + bs * i * width; // its three rows
    const PetscInt row = bs * global(0, rows[i]);
    if (row < _row_start || row >= _row_end)
    {
      // Another process's row: to it at the assembly.
      check(MatSetValuesBlockedLocal(_A, 1, &rows[i], PetscInt(cols.size()), cols.data(), block_row,
                                     ADD_VALUES),
            "MatSetValuesBlockedLocal");
      continue;
    }
    for (std::size_t j = 0; j < cols.size(); ++j)
      if (cols[j] >= 0)
        add_block(row, bs * global(1, cols[j]), block_row + bs * j, width);
  }
  return 0;
}
} // namespace pushout::petsc

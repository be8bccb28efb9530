// Adding element matrices of 3 x 3 blocks (a node's three displacements)
// into an assembled PETSc matrix, as MatSetValuesBlockedLocal(..., ADD_VALUES)
// does: the concrete's cracking tangent (model/BulkCracking.cpp) and the
// joints' (interface/Interface.cpp) are added this way at every Jacobian.
//
// In an assembled AIJ matrix with the 3 x 3 block pattern that dolfinx makes
// (sequential, or parallel: its diagonal and off-diagonal parts), the
// values of the rows this process owns are added where they lie: a binary
// search of a block row's columns for each block column, shared by the
// block's three rows. MatSetValuesBlockedLocal expands every block index
// into three, maps them and searches for every entry; on the corroded demo
// with cracks that was most of the time the cracking tangent's change took
// to assemble (docs/cracking-speed.md). Rows another process owns (a ghost
// node's), and any other matrix (not assembled, another type), go through
// MatSetValuesBlockedLocal itself, so to the owner at the assembly.
#pragma once

#include <array>
#include <cstdint>
#include <petscmat.h>
#include <span>

namespace pushout::petsc
{
class BlockAdd
{
public:
  /// Adds into `A` (block size 3) until destroyed; `A` must not be
  /// assembled or read meanwhile but through this, and is assembled
  /// afterwards as after MatSetValuesBlockedLocal.
  explicit BlockAdd(Mat A);
  ~BlockAdd();
  BlockAdd(const BlockAdd&) = delete;
  BlockAdd& operator=(const BlockAdd&) = delete;

  /// Adds the (3 rows.size()) x (3 cols.size()) row-major `values` at the
  /// local block rows and columns `rows` and `cols`; a negative index is
  /// skipped, as MatSetValuesBlockedLocal skips it. Throws if a block is
  /// not in the matrix's pattern (petsc::Error where PETSc adds). Returns 0
  /// (the signature of dolfinx's matrix insertion functions).
  int operator()(std::span<const std::int32_t> rows, std::span<const std::int32_t> cols,
                 std::span<const double> values);

  /// Whether the owned rows' values are added in place (an assembled AIJ
  /// matrix with the block pattern), not by MatSetValuesBlockedLocal.
  bool in_place() const { return _parts[0].a != nullptr; }

private:
  /// A sequential AIJ matrix whose values are added in place: the whole
  /// matrix on one process; the diagonal part (columns owned) or the
  /// off-diagonal one (the others, by their place in `_ghost_columns`) of
  /// a parallel matrix.
  struct Part
  {
    Mat M = nullptr;
    PetscScalar* a = nullptr;     ///< the values
    const PetscInt* ia = nullptr; ///< row starts
    const PetscInt* ja = nullptr; ///< column indices, sorted in each row
    PetscInt n = 0;               ///< rows
  };

  /// Gets the rows and values of `part.M` into `part`; false if PETSc has
  /// no rows.
  static bool get(Part& part);
  /// Gives back the matrix's rows, values and maps that were got.
  void restore() noexcept;
  /// Adds the block at global row `row` (owned) and global column `col`
  /// from `source`, row a at source + a * width.
  void add_block(PetscInt row, PetscInt col, const double* source, std::size_t width);

  Mat _A;
  std::array<Part, 2> _parts{};          ///< diagonal (or whole) and off-diagonal
  PetscInt _row_start = 0, _row_end = 0; ///< the rows owned (global)
  PetscInt _col_start = 0, _col_end = 0; ///< the columns of the diagonal part (global)
  /// The off-diagonal part's columns (global, sorted); none on one process.
  const PetscInt* _ghost_columns = nullptr;
  PetscInt _n_ghost_columns = 0;
  /// The rows' and the columns' maps of local blocks to global ones (none:
  /// the same), and their arrays.
  std::array<ISLocalToGlobalMapping, 2> _maps{};
  std::array<const PetscInt*, 2> _blocks{};
};
} // namespace pushout::petsc

// Adding element matrices of 3 x 3 blocks (a node's three displacements)
// into an assembled PETSc matrix, as MatSetValuesBlockedLocal(..., ADD_VALUES)
// does: the concrete's cracking tangent (model/BulkCracking.cpp) and the
// joints' (interface/Interface.cpp) are added this way at every Jacobian.
//
// On one process (a sequential AIJ matrix, assembled, with the 3 x 3 block
// pattern that dolfinx makes) the values are added where they lie in the
// matrix's rows: a binary search of a block row's columns for each block
// column, shared by the block's three rows. MatSetValuesBlockedLocal expands
// every block index into three, maps them and searches for every entry;
// on the corroded demo with cracks that was most of the time the cracking
// tangent's change took to assemble (docs/cracking-speed.md).
// Elsewhere (several processes, another matrix type) it is
// MatSetValuesBlockedLocal itself.
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
  /// assembled or read meanwhile but through this.
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

  /// Whether the values are added in place (one process, a sequential AIJ
  /// matrix with the block pattern), not by MatSetValuesBlockedLocal.
  bool in_place() const { return _a != nullptr; }

private:
  /// Gives back the matrix's rows, values and maps that were got.
  void restore() noexcept;

  Mat _A;
  PetscScalar* _a = nullptr;     ///< the values, in place
  const PetscInt* _ia = nullptr; ///< row starts
  const PetscInt* _ja = nullptr; ///< column indices, sorted in each row
  PetscInt _n = 0;               ///< rows
  /// The rows' and the columns' maps of local blocks to global ones (none:
  /// the same), and their arrays.
  std::array<ISLocalToGlobalMapping, 2> _maps{};
  std::array<const PetscInt*, 2> _blocks{};
};
} // namespace pushout::petsc

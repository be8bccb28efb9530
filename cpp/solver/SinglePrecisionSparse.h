// Single precision for GMRES on the whole model: the sparse LU of the
// lagged preconditioner factored and applied by MUMPS in single precision
// (smumps), the whole model's counterpart of SinglePrecision.h. On several
// processes each gives MUMPS its own rows (ICNTL(18) = 3) and the
// right-hand side is gathered on the first, MUMPS's host, which holds the
// solution after the solve and scatters it back.
//
// Why: on the whole model of the paper's mesh with cracking concrete
// (25 920 dofs) the LU factors hold 22 million entries (MUMPS, PORD
// ordering): every back-solve streams them once, and GMRES on the lagged LU
// takes 5 to 6 back-solves per Newton iteration (the bench's IMPL-EX case:
// 1 400 for 248). In single precision the factors are half the bytes, and
// the factorisation's dense kernels run on twice the numbers per vector
// instruction (docs/performance.md, "Otherwise, Newton on the whole
// model").
//
// What it changes: only the preconditioner. The whole model's Jacobian is
// less well conditioned than a condensed one (condition ~1e6 on that mesh),
// so that a single-precision LU alone solves to a few per cent; that
// rounding depends on the right-hand side, so the preconditioner is not
// quite linear and GMRES must be flexible (FGMRES, right preconditioning:
// its residual is the Jacobian's own, applied in double). The Krylov
// tolerance, the Newton iterates' residuals and every Newton tolerance stay
// as in double precision; the curve differs by Newton's tolerance.
#pragma once

#include <cstdint>
#include <petscpc.h>
#include <vector>

namespace pushout::solver
{
/// Makes `pc` (whose preconditioning matrix is an AIJ matrix, sequential or
/// parallel) a PCSHELL that factors that matrix with MUMPS in
/// single precision whenever PETSc sets the preconditioner up (the
/// analysis once per nonzero pattern) and applies the factors. A failed
/// factorisation is reported as PETSc's own are (PCGetFailedReason: a zero
/// pivot, out of memory; the Newton solve fails with DIVERGED_LINEAR_SOLVE
/// and the step is cut).
///
/// `numbering`: this process's rows' positions in a numbering of the
/// matrix's rows that no partition changes (Model::input_numbering), or
/// empty; `block_size` consecutive positions are one node's. On several
/// processes MUMPS's own ordering (PORD: Debian's MUMPS has neither METIS
/// nor SCOTCH) depends on the numbering of the rows it is given, which is
/// the partition's: on the paper's mesh with cracking concrete, 37.2
/// million entries in the factors and 4.15e10 flops on two processes
/// against 29.9 million and 2.30e10 on one (in dolfinx's numbering). With a
/// numbering, the first process orders the whole pattern in it twice, as
/// one process would order it in that numbering and by SCOTCH's nested
/// dissection of its nodes (NestedDissection.h), an analysis of its own
/// for each, once per pattern, and MUMPS takes the order whose
/// factorisation MUMPS estimates the cheaper (ICNTL(7) = 1): on the blocks
/// PORD's, 30.3 million entries and 2.31e10 flops on two processes; on
/// radial lines refined whole SCOTCH's (PORD in that numbering 6.23e10,
/// one process 3.90e10). One process, no numbering on some process, or
/// one that is not a permutation of the rows: MUMPS orders the rows as
/// given (PetscInfo says so on several processes). One process keeps
/// MUMPS's own order: SCOTCH's was not cheaper there on either layout.
void use_single_precision_sparse_lu(PC pc, std::vector<std::int64_t> numbering = {},
                                    int block_size = 1);

/// What MUMPS says of the factors of a `pc` made by
/// use_single_precision_sparse_lu, after its last factorisation.
struct SparseFactors
{
  std::int64_t entries = -1; ///< in the factors, on all processes (INFOG(29)); -1: none
  int ordering = 0;          ///< INFOG(7): 1 the order given, 2 AMF, 4 PORD, ...; 0: none
  /// Several processes with a numbering: the first process's estimates of
  /// the factorisation's flops (MUMPS's RINFOG(1)) in MUMPS's own choice of
  /// order (PORD on the slices' meshes) and in SCOTCH's (0: not made), and
  /// whether the order given is SCOTCH's
  double own_flops = 0, scotch_flops = 0;
  bool scotch = false;
};
/// None before a factorisation, or for another preconditioner.
SparseFactors single_precision_lu_factors(PC pc);

/// MUMPS's INFOG(1) for an allocation that failed: the machine's memory
/// (PC_FACTOR_OUTMEMORY; factorization_failure ends the run on it).
inline constexpr int mumps_allocation_failed = -13;
} // namespace pushout::solver

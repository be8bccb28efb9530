// An elimination order of a sparse matrix's rows by SCOTCH's nested
// dissection of the graph of its nodes. The single-precision LU
// (SinglePrecisionSparse.cpp) compares it with MUMPS's own ordering (PORD)
// on several processes and takes the cheaper.
#pragma once

#include <cstdint>
#include <vector>

namespace pushout::solver
{
/// The step (0-based) at which each of the `n` rows of a sparse matrix is
/// eliminated in SCOTCH's nested dissection (SCOTCH_graphOrder, its
/// default strategy) of the graph of the matrix's nodes: `block_size`
/// consecutive rows are one node's (a vector field's components, which
/// share their pattern) and are eliminated one after the other; two nodes
/// are neighbours where an entry (rows[k], cols[k]) (1-based, as MUMPS's
/// coordinates) couples them. Empty where `n` is not a multiple of
/// `block_size`, a coordinate is outside 1..n, or SCOTCH fails.
std::vector<std::int64_t> nested_dissection(std::int64_t n, int block_size,
                                            const std::vector<int>& rows,
                                            const std::vector<int>& cols);
} // namespace pushout::solver

// Gathering every process's values on the first process, in rank order: the
// count of each, their offsets, and MPI_Gatherv, written once.
#pragma once

#include <cstddef>
#include <mpi.h>
#include <vector>

namespace pushout::mpi
{
/// Every process's `mine` (elements of MPI type `type`), one after the other
/// in rank order, on the first process of `comm`; empty on the others.
/// `offsets`, if given, gets on the first process where each process's part
/// starts (size + 1 entries, the last the total). Collective. Counts are
/// MPI's ints: the caller keeps the total below INT_MAX.
template <typename T>
std::vector<T> gather_to_first(MPI_Comm comm, const T* mine, int count, MPI_Datatype type,
                               std::vector<int>* offsets = nullptr)
{
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const auto processes = static_cast<std::size_t>(size);
  std::vector<int> counts(processes, 0), starts(processes + 1, 0);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  for (std::size_t p = 0; p < processes; ++p)
    starts[p + 1] = starts[p] + counts[p];
  std::vector<T> all(rank == 0 ? std::size_t(starts[processes]) : 0);
  MPI_Gatherv(mine, count, type, all.data(), counts.data(), starts.data(), type, 0, comm);
  if (offsets)
    *offsets = std::move(starts);
  return all;
}
} // namespace pushout::mpi

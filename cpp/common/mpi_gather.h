// Gathering every process's values on the first process, in rank order: the
// count of each, their offsets, and MPI_Gatherv, written once; and the
// message of the first process that has one, on every process.
#pragma once

#include <cstddef>
#include <mpi.h>
#include <string>
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

/// The first process's `text` on every process of `comm`. Collective.
inline std::string broadcast_from_first(std::string text, MPI_Comm comm)
{
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  long long length = static_cast<long long>(text.size());
  MPI_Bcast(&length, 1, MPI_LONG_LONG, 0, comm);
  text.resize(std::size_t(length));
  MPI_Bcast(text.data(), int(length), MPI_CHAR, 0, comm);
  return text;
}

/// The message of the lowest-ranked process of `comm` that has one ("" if
/// none has). Collective.
inline std::string first_message(const std::string& mine, MPI_Comm comm)
{
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  int first = size;
  const int have = mine.empty() ? size : rank;
  MPI_Allreduce(&have, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == size)
    return "";
  long long length = rank == first ? static_cast<long long>(mine.size()) : 0;
  MPI_Bcast(&length, 1, MPI_LONG_LONG, first, comm);
  std::string message = rank == first ? mine : std::string(std::size_t(length), ' ');
  MPI_Bcast(message.data(), int(length), MPI_CHAR, first, comm);
  return message;
}
} // namespace pushout::mpi

// No run writes a value that is not a number and calls itself converged: a
// recorded step whose outputs are not finite stops the run (StepLoop::run:
// exit code 3, not converged) with a message naming the value.
#pragma once

#include "../common/mpi_errors.h"
#include <cmath>
#include <cstddef>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace pushout::record
{
/// A converged step whose outputs are not finite (every process throws it).
class NonFiniteResult : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// Throws NonFiniteResult on every process of comm if any of `values` (of
/// `columns`, named in the message where given) is not finite on any of
/// them. Collective.
inline void refuse_non_finite(const std::vector<double>& values,
                              const std::vector<std::string>& columns, const std::string& where,
                              MPI_Comm comm)
{
  std::size_t bad = values.size();
  for (std::size_t i = 0; i < values.size() && bad == values.size(); ++i)
    if (!std::isfinite(values[i]))
      bad = i;
  if (mpi::all(comm, bad == values.size()))
    return;
  std::ostringstream what;
  what << where << ": a non-finite result";
  if (bad < values.size())
    what << " (" << (bad < columns.size() ? columns[bad] : "value " + std::to_string(bad)) << " = "
         << values[bad] << ")";
  what << " in a step the solver reported converged";
  throw NonFiniteResult(what.str());
}
} // namespace pushout::record

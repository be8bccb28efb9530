// The arrays of BulkCracking's points, for its own .cpp files only: one
// entry per quadrature point of the cracking cells, [cell][point] in the
// order of BulkCracking::_cells, and the values of its Quadrature functions
// (forms/cracking.py).
#pragma once

#include "BulkCracking.h"
#include "cracking.h"
#include <algorithm>
#include <dolfinx/fem/Function.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <span>
#include <vector>

namespace pushout::model
{
namespace points
{
namespace fem = dolfinx::fem;
constexpr int voigt = 6;     ///< strain and stress components
constexpr int voigt_sq = 36; ///< tangent components
constexpr int state = bulk::CrackBand::state_size;
/// Point i's crack in `states` ([point][state]).
inline bulk::CrackState<const double> crack_of(const std::vector<double>& states, std::size_t i)
{
  return bulk::CrackState<const double>(std::span<const double>(states.data() + state * i, state));
}

/// The history kappa of point i's crack in `states` ([point][state]) [mm].
inline double kappa_of(const std::vector<double>& states, std::size_t i)
{
  return laws::DamageHistory<const double>(crack_of(states, i).law_state()).kappa();
}

/// Point i's six Voigt components in `values` ([point][6]).
inline bulk::Voigt voigt_at(const std::vector<double>& values, std::size_t i)
{
  bulk::Voigt v;
  std::copy_n(values.begin() + voigt * i, voigt, v.begin());
  return v;
}

/// The values of a Quadrature function at (cell, point), `bs` per point.
/// Made once per loop over the points: the dofmap and the array are looked
/// up here, not at each point (two shared_ptr copies a point cost 4 % of
/// an IMPL-EX run).
class PointValues
{
public:
  PointValues(fem::Function<double>& f, int bs)
      : _dofs(f.function_space()->dofmap()->list()), _values(f.x()->mutable_array()), _bs(bs)
  {
  }
  std::span<double> operator()(std::int32_t cell, int point) const
  {
    return _values.subspan(std::size_t(_dofs.links(cell)[point]) * _bs, _bs);
  }

private:
  const dolfinx::graph::AdjacencyList<std::int32_t>& _dofs; // f's space's, alive with f
  std::span<double> _values;
  std::size_t _bs;
};

} // namespace points

/// BulkCracking.h: at(cell, point, strain, d_sigma, d_C) at every point.
template <typename At> void BulkCracking::for_each_point(At&& at)
{
  const int n_points = expression_cracking_strain->num_points;
  const points::PointValues d_sigma_at(*_d_sigma, points::voigt), d_C_at(*_d_C, points::voigt_sq);
  for (std::size_t c = 0; c < _cells.size(); ++c)
    for (int q = 0; q < n_points; ++q)
    {
      const std::size_t i = c * std::size_t(n_points) + q;
      at(c, i, points::voigt_at(_strain_values, i), d_sigma_at(_cells[c], q),
         [&] { return d_C_at(_cells[c], q); });
    }
}

} // namespace pushout::model

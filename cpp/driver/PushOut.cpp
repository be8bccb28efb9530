#include "PushOut.h"
#include <cmath>
#include <limits>
#include <mpi.h>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace pushout::driver
{
namespace
{
/// Node of `candidates` nearest to p.
std::int64_t nearest(const mesh::MeshData& m, const std::vector<std::int64_t>& candidates,
                     std::array<double, 3> p)
{
  std::int64_t best = -1;
  double d_best = std::numeric_limits<double>::infinity();
  for (std::int64_t n : candidates)
  {
    const double d = std::hypot(m.x[3 * n] - p[0], m.x[3 * n + 1] - p[1], m.x[3 * n + 2] - p[2]);
    if (d < d_best)
    {
      d_best = d;
      best = n;
    }
  }
  if (best < 0)
    throw std::runtime_error("push-out mesh: no node for a constraint");
  return best;
}
} // namespace

PushOut::PushOut(const Scene& scene, const mesh::MeshData& m,
                 const std::vector<std::int32_t>& node_block)
    : _D(scene.number("geometry.tube_outer_diameter")), _L(scene.number("geometry.thickness")),
      _delta_final(scene.number("loading.push_displacement")),
      _dT(scene.number("loading.temperature_change")), _steps(int(scene.integer("loading.steps")))
{
  const auto& c = scene.numbers("geometry.tube_center");
  const double Rs = scene.number("geometry.support_inner_diameter") / 2;
  const double Ri = scene.number("geometry.tube_inner_diameter") / 2;
  const double tol = 1e-6 * std::max(_L, _D);

  std::vector<std::uint8_t> is_steel(m.num_nodes(), 0), is_concrete(m.num_nodes(), 0);
  for (std::size_t cell = 0; cell < m.num_cells(); ++cell)
    for (int i = 0; i < 8; ++i)
      (m.material[cell] == mesh::steel ? is_steel : is_concrete)[m.cells[8 * cell + i]] = 1;

  std::vector<std::int64_t> top, support;
  for (std::size_t n = 0; n < m.num_nodes(); ++n)
  {
    const double x = m.x[3 * n], y = m.x[3 * n + 1], z = m.x[3 * n + 2];
    if (is_steel[n] && std::abs(z - _L) < tol)
      top.push_back(std::int64_t(n));
    if (is_concrete[n] && std::abs(z) < tol && std::hypot(x - c[0], y - c[1]) > Rs - tol)
      support.push_back(std::int64_t(n));
  }
  const auto dof = [&](std::int64_t node, int comp) { return 3 * node_block[node] + comp; };
  for (std::int64_t n : top)
    _top_z.push_back(dof(n, 2));
  for (std::int64_t n : support)
    _support_z.push_back(dof(n, 2));
  const std::int64_t a = nearest(m, support, {c[0] + Rs, c[1], 0});
  const std::int64_t b = nearest(m, support, {c[0] - Rs, c[1], 0});
  const std::int64_t t = nearest(m, top, {c[0] + Ri, c[1], _L});
  _fixed = {dof(a, 0), dof(a, 1), dof(b, 1), dof(t, 1)};
}

void PushOut::apply_load(double s, solver::Equilibrium& eq) const
{
  const double delta = _delta_final * s / _steps;
  solver::Constraints bc;
  for (std::int32_t d : _top_z)
  {
    bc.dofs.push_back(d);
    bc.values.push_back(-delta);
  }
  for (const auto& list : {_support_z, _fixed})
    for (std::int32_t d : list)
    {
      bc.dofs.push_back(d);
      bc.values.push_back(0.0);
    }
  eq.set_constraints(std::move(bc));
  eq.set_temperature_change(_dT);
}

std::vector<double> PushOut::row(std::span<const double> reactions, std::span<const double> x) const
{
  double P = 0, delta = 0;
  for (std::int32_t d : _support_z)
    P += reactions[d];
  for (std::int32_t d : _top_z)
    delta += -x[d];
  double local[3] = {P, delta, double(_top_z.size())}, global[3];
  MPI_Allreduce(local, global, 3, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  P = global[0];
  delta = global[1] / global[2];
  const double tau = P / (std::numbers::pi * _D * (_L - delta)); // eq. (1)
  return {delta, P, tau};
}

std::string PushOut::progress(const std::vector<double>& r) const
{
  std::ostringstream s;
  s.precision(4);
  s << "delta = " << r[0] * 1e3 << " um  P = " << r[1] << " N  tau = " << r[2] << " MPa";
  return s.str();
}
} // namespace pushout::driver

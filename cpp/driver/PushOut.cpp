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

PushOut::PushOut(const Scene& scene, const mesh::MeshData& m, const model::Model& model)
    : _D(scene.number("geometry.tube_outer_diameter")), _L(scene.number("geometry.thickness")),
      _delta_final(scene.number("loading.push_displacement")),
      _dT(scene.number("loading.temperature_change")), _growth(scene.number("loading.step_growth")),
      _steps(int(scene.integer("loading.steps"))),
      _hold_top_in_thermal_step(scene.string("loading.thermal_tube_top") == "held"),
      _layers(scene.layers().size())
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
  // Dof lists of the owned nodes only: each constraint is applied, and each
  // reaction counted, by exactly one process.
  const auto add = [&](std::vector<std::int32_t>& list, std::int64_t node, int comp)
  {
    if (model.owned(model.node_block[node]))
      list.push_back(3 * model.node_block[node] + comp);
  };
  for (std::int64_t n : top)
    add(_top_z, n, 2);
  for (std::int64_t n : support)
    add(_support_z, n, 2);
  const std::int64_t a = nearest(m, support, {c[0] + Rs, c[1], 0});
  const std::int64_t b = nearest(m, support, {c[0] - Rs, c[1], 0});
  const std::int64_t t = nearest(m, top, {c[0] + Ri, c[1], _L});
  add(_fixed, a, 0);
  add(_fixed, a, 1);
  add(_fixed, b, 1);
  add(_fixed, t, 1);
  _top_start.assign(_top_z.size(), 0.0);
}

std::vector<std::string> PushOut::columns() const
{
  std::vector<std::string> c = {"delta_mm", "P_N", "tau_MPa", "p_MPa"};
  if (_layers > 1)
    for (std::size_t l = 0; l < _layers; ++l)
      c.push_back("p_" + std::to_string(l) + "_MPa");
  return c;
}

double PushOut::delta_at(double s) const
{
  if (_growth == 1.0)
    return _delta_final * s / _steps;
  return _delta_final * (std::pow(_growth, s) - 1) / (std::pow(_growth, _steps) - 1);
}

void PushOut::start_loading(std::span<const double> x)
{
  for (std::size_t i = 0; i < _top_z.size(); ++i)
    _top_start[i] = x[_top_z[i]];
}

void PushOut::apply_load(double s, solver::Equilibrium& eq) const
{
  solver::Constraints bc;
  if (s > 0 || _hold_top_in_thermal_step)
  {
    const double delta = delta_at(s);
    for (std::size_t i = 0; i < _top_z.size(); ++i)
    {
      bc.dofs.push_back(_top_z[i]);
      bc.values.push_back(_top_start[i] - delta);
    }
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

std::vector<double> PushOut::row(std::span<const double> reactions, std::span<const double> x,
                                 const model::Model& model) const
{
  const interface::Interface& itf = *model.interface;
  // Local sums: P, delta, number of top dofs, area, normal force per layer.
  std::vector<double> local = {0, 0, double(_top_z.size()), itf.area()};
  // (sums over owned dofs and local pairs, reduced over processes)
  for (std::int32_t d : _support_z)
    local[0] += reactions[d];
  for (std::size_t i = 0; i < _top_z.size(); ++i)
    local[1] += _top_start[i] - x[_top_z[i]];
  const std::vector<double> normal = itf.normal_force(model.u->x()->array());
  local.insert(local.end(), normal.begin(), normal.end());
  std::vector<double> g(local.size());
  MPI_Allreduce(local.data(), g.data(), int(local.size()), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  const double P = g[0], delta = g[1] / g[2], area = g[3];
  const double tau = P / (std::numbers::pi * _D * (_L - delta)); // eq. (1)
  double p_total = 0;
  std::vector<double> p_layer;
  for (std::size_t l = 0; l < _layers; ++l)
  {
    p_layer.push_back(-g[4 + l] / area);
    p_total += p_layer.back();
  }
  std::vector<double> out = {delta, P, tau, p_total};
  if (_layers > 1)
    out.insert(out.end(), p_layer.begin(), p_layer.end());
  return out;
}

std::string PushOut::progress(const std::vector<double>& r) const
{
  std::ostringstream s;
  s.precision(4);
  s << "delta = " << r[0] * 1e3 << " um  P = " << r[1] << " N  tau = " << r[2]
    << " MPa  p = " << r[3] << " MPa";
  return s.str();
}
} // namespace pushout::driver

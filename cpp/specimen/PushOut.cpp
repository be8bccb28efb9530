#include "PushOut.h"
#include "../mesh/cracks.h"
#include "../mesh/size.h"
#include "../mesh/symmetry.h"
#include "../solver/Vector.h"
#include <algorithm>
#include <cmath>
#include <limits>
#include <mpi.h>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace pushout::specimen
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

PushOut::PushOut(const mesh::MeshInput& shape, const Loading& loading, std::size_t layers,
                 const mesh::MeshData& m, const model::Model& model)
    : _D(shape.geometry.tube_outer_diameter), _L(shape.geometry.thickness),
      _delta_final(loading.push_displacement), _dT(loading.temperature_change),
      _growth(loading.step_growth), _steps(int(loading.steps)),
      _path(loading.push_path, int(loading.steps_per_segment)),
      _zero_force_unloading(loading.unload_to_zero_force),
      _hold_top_in_thermal_step(!loading.tube_top_free), _layers(layers), _copies(m.copies)
{
  const auto& c = shape.geometry.tube_center;
  const double Rs = shape.geometry.support_inner_diameter / 2;
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
  // Dof lists of the owned dof blocks only: each constraint is applied, and
  // each reaction counted, by exactly one process. Chosen by the blocks'
  // positions and materials, so that a P2 bulk's edge, face and interior
  // dofs on the constrained surfaces are included.
  const std::vector<double> X = model.space()->tabulate_dof_coordinates(false);
  const auto dofmap = model.space()->dofmap();
  const auto& original = model.mesh()->topology().original_cell_index;
  std::vector<std::uint8_t> block_steel(X.size() / 3, 0), block_concrete(X.size() / 3, 0);
  for (std::size_t cell = 0; cell < original.size(); ++cell)
    for (std::int32_t b : dofmap->cell_dofs(std::int32_t(cell)))
      (m.material[original[cell]] == mesh::steel ? block_steel : block_concrete)[b] = 1;
  const auto [xc, yc] = m.symmetry_center;
  const auto [x_plane, y_plane] = m.symmetry_planes;
  // The faces of the crack planes on a symmetry plane are held by their
  // joints (mirror cracks), not by the symmetry condition: the concrete
  // blocks on the plane along such a crack's ray (found by position, so
  // that a process knows its blocks whoever holds the joint elements).
  const double R = _D / 2;
  const auto on_mirror_crack = [&](std::int32_t b)
  {
    if (!block_concrete[b])
      return false;
    const double dx = X[3 * b] - c[0], dy = X[3 * b + 1] - c[1];
    for (const mesh::CrackPlane& crack : m.cracks)
      if (crack.mirrored() && std::hypot(dx, dy) > R - tol &&
          dx * std::cos(crack.angle) + dy * std::sin(crack.angle) > 0 &&
          std::abs(dx * std::sin(crack.angle) - dy * std::cos(crack.angle)) < tol)
        return true;
    return false;
  };
  const std::int32_t n_owned = dofmap->index_map->size_local();
  for (std::int32_t b = 0; b < n_owned; ++b)
  {
    const double x = X[3 * b], y = X[3 * b + 1], z = X[3 * b + 2];
    if (block_steel[b] && std::abs(z - _L) < tol)
      _top_z.push_back(3 * b + 2);
    if (block_concrete[b] && std::abs(z) < tol && std::hypot(x - c[0], y - c[1]) > Rs - tol)
      _support_z.push_back(3 * b + 2);
    // Symmetry: u_x = 0 on x = xc, u_y = 0 on y = yc (both sides of the
    // interface); they also remove the in-plane rigid modes across them and
    // the tube's rotation.
    if (x_plane && std::abs(x - xc) < tol && !on_mirror_crack(b))
      _fixed.push_back(3 * b);
    if (y_plane && std::abs(y - yc) < tol && !on_mirror_crack(b))
      _fixed.push_back(3 * b + 1);
  }
  fix_rigid_modes(shape, m, model, top, support);
  for (std::size_t l = 0; l < _layers; ++l)
    if (model.interface().softens(l))
      _damage_layers.push_back(l);
  _top_start.assign(_top_z.size(), 0.0);
  const solver::Vector slip(model.mean_axial_slip_functional());
  const solver::ReadView slip_view(slip);
  _slip.assign(slip_view.span().begin(), slip_view.span().end());
}

void PushOut::fix_rigid_modes(const mesh::MeshInput& shape, const mesh::MeshData& m,
                              const model::Model& model, const std::vector<std::int64_t>& top,
                              const std::vector<std::int64_t>& support)
{
  const auto& c = shape.geometry.tube_center;
  const double Rs = shape.geometry.support_inner_diameter / 2;
  const double Ri = shape.geometry.tube_inner_diameter / 2;
  const auto [x_plane, y_plane] = m.symmetry_planes;
  const auto add = [&](std::int64_t node, int comp)
  {
    if (model.owned(model.node_block(node)))
      _fixed.push_back(3 * model.node_block(node) + comp);
  };
  if (_copies == 2)
  {
    // Half model: the plane holds the translations across it and the
    // rotations; along it, one fixing of the full model that lies in the
    // half, in that direction: the concrete's (or, with cracks, the tube
    // top's) at (xc + R, yc). Its reaction is zero, as in the full model.
    const int along = x_plane ? 1 : 0;
    if (m.cracks.empty())
      add(nearest(m, support, {c[0] + Rs, c[1], 0}), along);
    else
      add(nearest(m, top, {c[0] + Ri, c[1], _L}), along);
  }
  if (_copies == 1)
  {
    if (m.cracks.empty())
    {
      // Every fixing on a symmetry plane of the slice, or in mirror pairs,
      // so that none carries a force: the symmetric solution moves nothing
      // across the plane there. With the plane y = yc (the tube centred in
      // y, or in both): the support nodes at (xc +- Rs, yc) in y, the first
      // in x too, and the tube top at (xc + Ri, yc) in y (its rotation).
      // With only x = xc (the tube off-centre in y), the same turned: the
      // support at (xc, yc + Rs) in x, the pair (xc +- Rs, yc) in y, the
      // tube top at (xc, yc + Ri) in x (the tube top is not held in y
      // there: that would hold its shift in y against the slice). A slice
      // without symmetry keeps the first set; its tube-top fixing may then
      // carry a little.
      const mesh::Symmetry symmetry = mesh::geometric_symmetry(shape);
      const std::int64_t a = nearest(m, support, {c[0] + Rs, c[1], 0});
      const std::int64_t b = nearest(m, support, {c[0] - Rs, c[1], 0});
      add(a, 1);
      add(b, 1);
      // (On the plane only where it is a mesh line: an even number of
      // elements per quarter.)
      if (symmetry.x_plane && !symmetry.y_plane && shape.mesh.elements_per_quarter % 2 == 0)
      {
        add(nearest(m, support, {c[0], c[1] + Rs, 0}), 0);
        add(nearest(m, top, {c[0], c[1] + Ri, _L}), 0);
      }
      else
      {
        add(a, 0);
        add(nearest(m, top, {c[0] + Ri, c[1], _L}), 1);
      }
    }
    else
    {
      // Crack planes may cut the concrete into pieces held by the joints
      // alone: a fixing on one piece would carry the pieces' forces. The
      // tube is never cut: its top holds the in-plane rigid modes of the
      // whole specimen (statically determinate: no reaction at equilibrium).
      const std::int64_t a = nearest(m, top, {c[0] + Ri, c[1], _L});
      const std::int64_t b = nearest(m, top, {c[0] - Ri, c[1], _L});
      add(a, 0);
      add(a, 1);
      add(b, 1);
    }
  }
}

std::vector<std::string> PushOut::columns() const
{
  std::vector<std::string> c = {"delta_mm", "P_N", "tau_MPa", "p_MPa"};
  if (_layers > 1)
    for (std::size_t l = 0; l < _layers; ++l)
      c.push_back("p_" + std::to_string(l) + "_MPa");
  c.insert(c.end(), {"slip_mm", "t_s1_min_MPa", "t_s1_max_MPa", "t_s1_cv"});
  for (std::size_t l : _damage_layers)
    c.insert(c.end(), {"d_" + std::to_string(l) + "_mean", "d_" + std::to_string(l) + "_max"});
  return c;
}

double PushOut::delta_at(double s) const
{
  if (!_path.empty())
    return _path.value(s);
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
  constrain(s > 0 || _hold_top_in_thermal_step, delta_at(s), _dT, eq);
}

void PushOut::apply_initial_load(double fraction, solver::Equilibrium& eq) const
{
  constrain(_hold_top_in_thermal_step, 0.0, fraction * _dT, eq);
}

void PushOut::apply_load_factor(double delta, solver::Equilibrium& eq) const
{
  constrain(true, delta, _dT, eq);
}

void PushOut::constrain(bool top_held, double delta, double dT, solver::Equilibrium& eq) const
{
  solver::Constraints bc;
  if (top_held)
    for (std::size_t i = 0; i < _top_z.size(); ++i)
    {
      bc.dofs.push_back(_top_z[i]);
      bc.values.push_back(_top_start[i] - delta);
    }
  for (const auto& list : {_support_z, _fixed})
    for (std::int32_t d : list)
    {
      bc.dofs.push_back(d);
      bc.values.push_back(0.0);
    }
  eq.set_constraints(std::move(bc));
  eq.set_temperature_change(dT);
}

double PushOut::load_force(const model::Model& model) const
{
  // The interface forces are internal forces (f = +int N t on the concrete
  // side): the tube pushes the concrete with -t, downwards when P > 0.
  double local = model.interface().resultant()[2], P = 0;
  MPI_Allreduce(&local, &P, 1, MPI_DOUBLE, MPI_SUM, model.comm());
  return P;
}

std::vector<double> PushOut::row(std::span<const double> /*reactions*/, std::span<const double> x,
                                 const model::Model& model) const
{
  const interface::Interface& itf = model.interface();
  // Local sums: -, delta, number of top dofs, area, mean slip, normal force
  // per layer (sums over owned dofs and local pairs, reduced over
  // processes); P from load_force().
  std::vector<double> local = {0, 0, double(_top_z.size()), itf.area(), 0};
  for (std::size_t i = 0; i < _top_z.size(); ++i)
    local[1] += _top_start[i] - x[_top_z[i]];
  for (std::size_t i = 0; i < _slip.size(); ++i)
    local[4] += _slip[i] * x[i];
  const std::vector<double> normal = itf.normal_force();
  local.insert(local.end(), normal.begin(), normal.end());
  std::vector<double> g(local.size());
  MPI_Allreduce(local.data(), g.data(), int(local.size()), MPI_DOUBLE, MPI_SUM, model.comm());
  const double P = _copies * load_force(model), delta = g[1] / g[2], area = g[3];
  // eq. (1): the contact length shrinks by |delta| whichever way the tube
  // moves (a push_path may pull it back, delta < 0).
  const double tau = P / (std::numbers::pi * _D * (_L - std::abs(delta)));
  double p_total = 0;
  std::vector<double> p_layer;
  for (std::size_t l = 0; l < _layers; ++l)
  {
    p_layer.push_back(-g[5 + l] / area);
    p_total += p_layer.back();
  }
  std::vector<double> out = {delta, P, tau, p_total};
  if (_layers > 1)
    out.insert(out.end(), p_layer.begin(), p_layer.end());
  out.push_back(g[4]);

  // The spread of t_s1 and the damage of each damage layer: sums, minima
  // and maxima over the processes.
  const interface::Interface::ShearSpread spread = itf.shear_spread();
  std::vector<double> sums = {spread.integral, spread.integral_of_square,
                              spread.integral_of_magnitude};
  std::vector<double> maxima = {-spread.min, spread.max};
  for (std::size_t l : _damage_layers)
  {
    const auto [integral, largest] = itf.damage_of(l);
    sums.push_back(integral);
    maxima.push_back(largest);
  }
  MPI_Allreduce(MPI_IN_PLACE, sums.data(), int(sums.size()), MPI_DOUBLE, MPI_SUM, model.comm());
  MPI_Allreduce(MPI_IN_PLACE, maxima.data(), int(maxima.size()), MPI_DOUBLE, MPI_MAX, model.comm());
  // The spread relative to the mean magnitude (the mean itself vanishes
  // where the push force does: unloaded to zero force).
  const double mean = sums[0] / area, magnitude = sums[2] / area;
  const double variance = std::max(sums[1] / area - mean * mean, 0.0);
  out.insert(out.end(),
             {-maxima[0], maxima[1], magnitude > 0 ? std::sqrt(variance) / magnitude : 0.0});
  for (std::size_t k = 0; k < _damage_layers.size(); ++k)
    out.insert(out.end(), {sums[3 + k] / area, maxima[2 + k]});
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
} // namespace pushout::specimen

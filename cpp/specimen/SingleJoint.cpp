#include "SingleJoint.h"
#include "../scene/SceneError.h"
#include <algorithm>
#include <cmath>
#include <mpi.h>
#include <sstream>

namespace pushout::specimen
{
SingleJoint::SingleJoint(const Loading& loading, const mesh::MeshData& m, const model::Model& model)
    : _path(loading.shear_path, int(loading.steps_per_segment)),
      _force_per_node(loading.normal_force_per_node)
{
  std::vector<std::uint8_t> in_steel(m.num_nodes(), 0), in_concrete(m.num_nodes(), 0);
  for (std::size_t c = 0; c < m.num_cells(); ++c)
    for (int i = 0; i < 8; ++i)
      (m.material[c] == mesh::steel ? in_steel : in_concrete)[m.cells[8 * c + i]] = 1;
  std::vector<std::uint8_t> on_joint(m.num_nodes(), 0);
  for (const auto& p : m.pairs)
    for (std::int64_t n : p.plus)
      on_joint[n] = 1;
  for (std::size_t n = 0; n < m.num_nodes(); ++n)
  {
    const std::int32_t b = model.node_block(n);
    if (!model.owned(b))
      continue; // another process applies its constraints and loads
    if (in_steel[n])
      for (int d = 0; d < 3; ++d)
        _lower.push_back(3 * b + d);
    if (in_concrete[n])
    {
      _upper_x.push_back(3 * b);
      _upper_y.push_back(3 * b + 1);
    }
    if (on_joint[n])
      _joint_z.push_back(3 * b + 2);
  }
}

void SingleJoint::apply(double s, double preload, solver::Equilibrium& eq) const
{
  solver::Constraints bc;
  for (std::int32_t d : _lower)
  {
    bc.dofs.push_back(d);
    bc.values.push_back(0.0);
  }
  for (std::int32_t d : _upper_x)
  {
    bc.dofs.push_back(d);
    bc.values.push_back(_path.value(s));
  }
  for (std::int32_t d : _upper_y)
  {
    bc.dofs.push_back(d);
    bc.values.push_back(0.0);
  }
  eq.set_constraints(std::move(bc));
  std::vector<std::pair<std::int32_t, double>> forces;
  for (std::int32_t d : _joint_z)
    forces.emplace_back(d, preload * _force_per_node);
  eq.set_external_forces(forces);
}

std::vector<double> SingleJoint::row(std::span<const double> reactions, std::span<const double> x,
                                     const model::Model& model) const
{
  // Sums over owned dofs: u_s, F_s, count of x dofs, u_n, F_n, count of
  // joint nodes; reduced over processes.
  double local[6] = {0, 0, double(_upper_x.size()), 0, 0, double(_joint_z.size())};
  for (std::int32_t d : _upper_x)
  {
    local[0] += x[d];
    local[1] += reactions[d];
  }
  for (std::int32_t d : _joint_z)
  {
    local[3] += x[d];
    local[4] += _force_per_node;
  }
  double g[6];
  MPI_Allreduce(local, g, 6, MPI_DOUBLE, MPI_SUM, model.comm());
  return {g[0] / g[2], g[1], g[3] / g[5], g[4]};
}

std::string SingleJoint::progress(const std::vector<double>& r) const
{
  std::ostringstream s;
  s.precision(5);
  s << "u_s = " << r[0] << " mm  F_s = " << r[1] << " N  u_n = " << r[2] << " mm";
  return s.str();
}
} // namespace pushout::specimen

namespace pushout::specimen
{
void SingleJoint::check_scene(const Scene& scene)
{
  if (scene.mesh().degree == 2)
    throw SceneError("'mesh.degree' = 2 is implemented for model.type = \"pushout\" only");
  check_load_path("loading.shear_path", scene.loading().shear_path,
                  scene.loading().steps_per_segment);
}
} // namespace pushout::specimen

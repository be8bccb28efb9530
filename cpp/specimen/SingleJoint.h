// One joint element between two cubes (paper §3 Fig. 6, §4.3 Fig. 9): the
// lower (steel) cube is fixed, so the joint's lower face is fixed; every
// node of the upper (concrete) cube follows the shear path in x and is held
// in y, so the cube translates rigidly and its bulk carries no stress; the
// joint's 4 upper nodes carry the normal force in z.
// Measured: u_s (x) and u_n (z) of the upper face; F_s = total x reaction
// on the upper cube (the force the joint resists with); F_n = total z force
// on the 4 upper nodes.
#pragma once

#include "../scene/Scene.h"
#include "LoadPath.h"
#include "Scenario.h"

namespace pushout::specimen
{
class SingleJoint : public Scenario
{
public:
  /// Constraints and loads go to the dofs this process owns.
  SingleJoint(const Loading& loading, const mesh::MeshData& mesh, const model::Model& model);

  /// The single joint's checks of the scene beyond the keys' ranges;
  /// throws SceneError.
  static void check_scene(const Scene& scene);

  std::vector<std::string> columns() const override
  {
    return {"u_s_mm", "F_s_N", "u_n_mm", "F_n_N"};
  }
  int steps() const override { return _path.steps(); }
  bool initial_solve() const override { return true; }
  double time_at(double s) const override { return _path.length_to(s); }
  double prescribed_at(double s) const override { return _path.value(s); }
  void apply_load(double s, solver::Equilibrium& eq) const override { apply(s, 1.0, eq); }
  void apply_initial_load(double fraction, solver::Equilibrium& eq) const override
  {
    apply(0.0, fraction, eq);
  }
  std::vector<double> row(std::span<const double> reactions, std::span<const double> x,
                          const model::Model& model) const override;
  std::string progress(const std::vector<double>& row) const override;

  /// Shear displacement u_s at load parameter s [mm].

private:
  /// Constraints at shear parameter s, the normal preload times `preload`.
  void apply(double s, double preload, solver::Equilibrium& eq) const;

  LoadPath _path; ///< of the shear displacement [mm]
  double _force_per_node;
  std::vector<std::int32_t> _lower;   ///< all dofs of the steel cube
  std::vector<std::int32_t> _upper_x; ///< x dofs of the concrete cube
  std::vector<std::int32_t> _upper_y; ///< y dofs of the concrete cube
  std::vector<std::int32_t> _joint_z; ///< z dofs of the joint's upper nodes
};
} // namespace pushout::specimen

// The push-out test of a slice (paper §4.1): the slice rests on z = 0
// outside the support circle; the tube's top nodes are pushed down by delta.
//
// Constraints:
//  - tube top (steel nodes at z = L): u_z = -delta. During the thermal step
//    they are held at 0 (loading.thermal_tube_top = "held": the paper's
//    choice, §4.2, which causes its negative initial stress) or free
//    ("free"); the push then moves them by -delta from where the thermal
//    step left them;
//  - support (concrete nodes at z = 0, r >= support radius): u_z = 0;
//  - in-plane rigid modes of the slice: the bottom concrete node nearest to
//    (xc + Rs, yc) fixed in x and y, the one nearest to (xc - Rs, yc) in y
//    (the paper's "two nodes ... for a proper conditioning");
//  - the tube's rotation about its axis, which only friction resists and
//    nothing resists when the interface carries no pressure: the top steel
//    node nearest to (xc + Ri, yc) fixed in y. By symmetry its reaction is
//    zero when the tube is centred in y. A tube centred in x only has the
//    same fixings turned by 90 degrees (on the plane x = xc: the support
//    at (xc, yc + Rs) and the tube top at (xc, yc + Ri) in x), so that
//    none carries a force there either; off-centre both ways, the tube-top
//    fixing may carry a little.
// Quarter model (mesh/symmetry.h): symmetry conditions u_x = 0 on x = xc
// and u_y = 0 on y = yc replace the in-plane fixings, and P counts the
// four quarters. Half model: the condition on its plane, the full model's
// fixings in the direction along it, and P counts two halves. The faces of
// crack planes on a symmetry plane are held by their joints instead.
// Push steps: delta(s) = delta_final (r^s - 1) / (r^N - 1) for step growth
// r (delta_final s / N for r = 1); or, with loading.push_path, piecewise
// linear through its values with loading.steps_per_segment steps each
// (LoadPath.h), unloading segments ending where P falls to zero with
// loading.unload_to = "zero_force" (the device cannot pull).
// Measured: delta, P = the push force, from the interface: the axial
// resultant of the interface tractions (the tube's equilibrium: the top
// reactions carry it; equal to the sum of the support reactions, the
// thermal loads being self-equilibrated), tau = P / (pi D (L -
// delta)) (paper eq. 1), the mean interface pressure p = -int t_n dA / A,
// with several layers each layer's share p_L, the mean axial slip s
// over the interface (the control variable of path following), the spread
// of the axial shear traction t_s1 over the interface (its smallest and
// largest value at a quadrature point, and its standard deviation over its
// mean magnitude, std/mean(|t_s1|), area-weighted: 0 where the shear is
// uniform, paper §2.3; the coefficient of variation where t_s1 keeps its
// sign), and
// for each damage layer L its mean (area-weighted) and largest damage.
#pragma once

#include "../mesh/MeshInput.h"
#include "../scene/Scene.h"
#include "LoadPath.h"
#include "Scenario.h"
#include <cmath>

namespace pushout::specimen
{
class PushOut : public Scenario
{
public:
  /// Constraints and loads go to the dofs this process owns.
  /// `shape`: the slice and its mesh keys; `layers`: the number of
  /// [[interface]] layers.
  PushOut(const mesh::MeshInput& shape, const Loading& loading, std::size_t layers,
          const mesh::MeshData& mesh, const model::Model& model);

  /// The relations between the push-out's geometry keys that no single
  /// key's range can express (the tube inside the slice, the support
  /// outside the tube, ...); throws SceneError naming the keys.
  static void check_scene(const Scene& scene);

  /// A joint's penalty stiffness so far above the concrete's over an
  /// interface element (k h / E > stiff_joint_ratio) that Newton may cycle
  /// between the joints' contact and sliding states, for a curve that a
  /// softer one gives as well: one note per such layer or crack plane (on
  /// its stiffest parameter). h is the interface's element size around the
  /// tube, taken for the crack planes' joints too (whose elements are the
  /// radial block's); measured with trilinear bulk elements.
  static std::vector<std::string> scene_notes(const Scene& scene);

  /// Above this k h / E (h the interface element's size around the tube),
  /// scene_notes speaks. Measured on demo/pushout_friction.toml: tau at
  /// 0.01 mm moves by 0.1 % from k h / E = 33 to 100; with 2x2 Gauss points
  /// Newton cycles without converging from about 130 (k 4e6 N/mm^3 with 16
  /// elements per quarter; not always: 5e6 ran, 1e7 did not), with nodal
  /// quadrature from about 3000 (docs/numerics.md, "Stiff joints").
  static constexpr double stiff_joint_ratio = 100;

  std::vector<std::string> columns() const override;
  int steps() const override { return _path.empty() ? _steps : _path.steps(); }
  bool initial_solve() const override { return _dT != 0.0; }
  /// The push's path length: |delta| (a pull's too), or the length
  /// travelled along push_path.
  double time_at(double s) const override
  {
    return _path.empty() ? std::abs(delta_at(s)) : _path.length_to(s);
  }
  void apply_load(double s, solver::Equilibrium& eq) const override;
  void apply_initial_load(double fraction, solver::Equilibrium& eq) const override;
  void start_loading(std::span<const double> x) override;
  /// The load factor of path following is the push delta [mm].
  bool has_load_factor() const override { return true; }
  double final_load_factor() const override { return _delta_final; }
  bool monotonic() const override { return _path.empty(); }
  void apply_load_factor(double delta, solver::Equilibrium& eq) const override;
  /// The push force on the model as meshed (a quarter's on a quarter model,
  /// a half's on a half).
  double load_force(const model::Model& model) const override;
  bool uses_bulk() const override { return false; }
  std::vector<double> row(std::span<const double> reactions, std::span<const double> x,
                          const model::Model& model) const override;
  std::string progress(const std::vector<double>& row) const override;
  double prescribed_at(double s) const override { return delta_at(s); }
  bool ends_at_zero_force(int k) const override
  {
    return _zero_force_unloading && !_path.empty() && _path.decreasing(_path.segment_of_step(k));
  }
  double end_segment_at(int k, double s) override
  {
    return _path.end_segment(_path.segment_of_step(k), s);
  }

  /// Push displacement at load parameter s [mm].
  double delta_at(double s) const;

private:
  static void check_cracking(const Scene& scene);
  /// Constraints of the push (top held at start - delta if `top_held`) and
  /// the temperature change dT [degC].
  void constrain(bool top_held, double delta, double dT, solver::Equilibrium& eq) const;
  /// The in-plane fixings that hold the rigid modes a symmetry condition
  /// does not (none carries a force at equilibrium); `top` and `support`:
  /// the tube-top and support nodes.
  void fix_rigid_modes(const mesh::MeshInput& shape, const mesh::MeshData& m,
                       const model::Model& model, const std::vector<std::int64_t>& top,
                       const std::vector<std::int64_t>& support);

  double _D, _L, _delta_final, _dT, _growth;
  int _steps;
  LoadPath _path;                     ///< loading.push_path (empty: monotonic) [mm]
  bool _zero_force_unloading = false; ///< loading.unload_to = "zero_force"
  bool _hold_top_in_thermal_step;
  std::size_t _layers;
  int _copies; ///< mirror copies of the mesh in the specimen (2: half, 4: quarter model)
  std::vector<std::int32_t> _top_z;        ///< tube top z dofs
  std::vector<double> _top_start;          ///< their u_z when the push starts
  std::vector<std::int32_t> _support_z;    ///< support z dofs
  std::vector<std::int32_t> _fixed;        ///< in-plane fixings (value 0)
  std::vector<double> _slip;               ///< mean axial slip functional, owned dofs
  std::vector<std::size_t> _damage_layers; ///< the layers that soften (damage columns)
};
} // namespace pushout::specimen

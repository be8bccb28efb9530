// The push-out test of a slice (paper §4.1): the slice rests on z = 0
// outside the support circle; the tube's top nodes are pushed down by delta.
//
// Constraints:
//  - tube top (steel nodes at z = L): u_z = -delta (0 during the thermal
//    step: the paper's choice, §4.2, which causes its negative initial
//    stress);
//  - support (concrete nodes at z = 0, r >= support radius): u_z = 0;
//  - in-plane rigid modes of the slice: the bottom concrete node nearest to
//    (xc + Rs, yc) fixed in x and y, the one nearest to (xc - Rs, yc) in y
//    (the paper's "two nodes ... for a proper conditioning");
//  - the tube's rotation about its axis, which only friction resists and
//    nothing resists when the interface carries no pressure: the top steel
//    node nearest to (xc + Ri, yc) fixed in y. By symmetry its reaction is
//    zero in every scene with the tube centred.
// Measured: delta, P = sum of the support reactions, tau = P / (pi D (L -
// delta)) (paper eq. 1).
#pragma once

#include "../scene/Scene.h"
#include "Scenario.h"

namespace pushout::driver
{
class PushOut : public Scenario
{
public:
  PushOut(const Scene& scene, const mesh::MeshData& mesh,
          const std::vector<std::int32_t>& node_block);

  std::vector<std::string> columns() const override { return {"delta_mm", "P_N", "tau_MPa"}; }
  int steps() const override { return _steps; }
  bool initial_solve() const override { return _dT != 0.0; }
  void apply_load(double s, solver::Equilibrium& eq) const override;
  std::vector<double> row(std::span<const double> reactions,
                          std::span<const double> x) const override;
  std::string progress(const std::vector<double>& row) const override;

private:
  double _D, _L, _delta_final, _dT;
  int _steps;
  std::vector<std::int32_t> _top_z;     ///< tube top z dofs
  std::vector<std::int32_t> _support_z; ///< support z dofs
  std::vector<std::int32_t> _fixed;     ///< in-plane fixings (value 0)
};
} // namespace pushout::driver

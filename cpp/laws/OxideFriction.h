// Coulomb friction on the pressure of an expanding oxide layer: the friction
// law of paper §3 (Friction.h) whose normal part is the oxide's.
//
// The corrosion stage gives every step the oxide layer's free opening g0 [mm]
// and normal compliance c_ox [mm^3/N] (Oxide.h, StepInputs). The joint's
// penalty k and the oxide are springs in series, so in contact (w_n < g0)
//   p = (g0 - w_n) / (1/k + c_ox),   t_n = -p,   dp/dw_n = -1/(1/k + c_ox)
// and the shear is eq. (6) on that pressure: trial k (w_s - w^p), limit mu p,
// radial return with vector plastic slip, consistent tangent (the shear
// couples to w_n through mu dp/dw_n). Opening beyond the oxide (w_n > g0):
// t_n = 0, no shear, no stiffness: a layer of rust cannot pull the concrete
// back (unilateral contact). Where the concrete cracks, the segments between
// the cracks then carry no tension from the oxide, and the pressure the
// interface reports is the one the cover feels. The fixings of the model, not
// the joint, hold the rigid modes. With g0 = c_ox = 0 (no corrosion) the law
// is Friction in contact and carries nothing in opening.
//
// Why one law and not an oxide layer superposed on a friction layer: layers
// share the jump, so an expansion taken up by one layer would open the
// other's jump and it would carry no friction.
//
// State: [w^p_s1, w^p_s2] in mm. Parameters: k [N/mm^3], mu [-].
#pragma once

#include "Friction.h"
#include "InterfaceLaw.h"
#include "LawRegistry.h"

namespace pushout::laws
{
/// Friction (Friction.h) whose normal part is the oxide's: the same state,
/// slip and return mapping, the step's oxide inputs as the gap and the
/// compliance.
class OxideFriction : public Friction
{
public:
  static constexpr const char* name = "oxide_friction";
  static constexpr const char* doc =
      "Coulomb friction on the pressure of the corrosion oxide (k, mu), which never pulls; "
      "friction in contact without corrosion";

  static std::vector<ParamDef> params()
  {
    return {penalty_param("k", 1000.0, "penalty stiffness, in series with the oxide layer"),
            {"mu", 0.4, "-", "friction coefficient", 0, false}};
  }

  using Friction::Friction;

  LawResult update(std::span<const double> state_old, const Vec3& w, std::span<double> state_new,
                   const StepInputs& in = {}) const
  {
    return update_with_gap(state_old, w, state_new, in.oxide_gap, in.oxide_compliance,
                           Opening::unilateral);
  }
};
} // namespace pushout::laws

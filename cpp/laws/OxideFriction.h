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
// p = 0, no shear, and the penalty resists the separation, t_n = k (w_n - g0),
// as Friction does for w_n > 0. With g0 = c_ox = 0 (no corrosion) the law is
// Friction exactly.
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
class OxideFriction
{
public:
  static constexpr const char* name = "oxide_friction";
  static constexpr const char* doc =
      "Coulomb friction on the pressure of the corrosion oxide (k, mu); friction without corrosion";
  static constexpr int state_size = PlasticSlip<double>::size;

  static std::vector<ParamDef> params()
  {
    return {{"k", 1000.0, "N/mm^3", "penalty stiffness, in series with the oxide layer", 0, true},
            {"mu", 0.4, "-", "friction coefficient", 0, false}};
  }

  OxideFriction(double k, double mu) : _k(k), _mu(mu) {}
  OxideFriction(const Params& p, const std::string&) : OxideFriction(p.at("k"), p.at("mu")) {}

  LawResult update(std::span<const double> state_old, const Vec3& w, std::span<double> state_new,
                   const StepInputs& in = {}) const
  {
    LawResult r;
    const double k = _k;
    const double opening = w[0] - in.oxide_gap; // beyond the oxide's free opening [mm]
    const double k_contact = 1 / (1 / k + in.oxide_compliance);
    const bool contact = opening < 0;
    const double kn = contact ? k_contact : k;
    r.t[0] = kn * opening;
    r.D = {kn, 0, 0, 0, k, 0, 0, 0, k};
    const double p = contact ? -r.t[0] : 0.0;
    const double dp_dwn = contact ? -k_contact : 0.0;
    coulomb_return(k, _mu, p, dp_dwn, w, PlasticSlip(state_old), PlasticSlip(state_new), r);
    return r;
  }

  std::array<double, 2> slip(std::span<const double> state) const
  {
    return PlasticSlip(state).vector();
  }
  double damage(std::span<const double>) const { return 0; }

private:
  double _k;  // penalty stiffness [N/mm^3]
  double _mu; // friction coefficient [-]
};
} // namespace pushout::laws

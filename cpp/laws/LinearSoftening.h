// Linear softening (paper §2.3, Fig. 5a; Table 1 "Lin. soft."): elastic to
// f_t at w0 = f_t / k, then sigma = f_t (1 - (kappa - w0) / w_c2) down to zero
// at kappa = w0 + w_c2; secant unloading; compression elastic.
// Parameters: k [N/mm^3], f_t [MPa], w_c2 [mm].
#pragma once

#include "SofteningLaw.h"

namespace pushout::laws
{
struct LinearSofteningSpec
{
  static constexpr const char* name = "linear_softening";
  static constexpr const char* doc =
      "Camanho-Davila damage, linear softening, paper §2.3 Fig. 5a (k, f_t, w_c2)";
  static std::vector<ParamDef> params()
  {
    return {penalty_param("k", 100.0, "penalty stiffness (Table 1: Lin. soft.)"),
            {"f_t", 1.0, "MPa", "tensile strength (peak traction)", 0, true},
            {"w_c2", 0.3, "mm", "softening length from the peak to zero traction", 0, true}};
  }
  static Envelope envelope(const Params& p, const std::string&)
  {
    return {Envelope::Kind::linear, p.at("f_t"), p.at("w_c2")};
  }
};
using LinearSoftening = SofteningLaw<LinearSofteningSpec>;
} // namespace pushout::laws

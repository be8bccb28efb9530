// Exponential softening (paper §2.3, Fig. 5b; Table 1 "Exp. soft."): elastic
// to f_t at w0 = f_t / k, then sigma = f_fr + (f_t - f_fr) exp(-c (kappa -
// w0)); secant unloading; compression elastic.
// Parameters: k [N/mm^3], f_t [MPa], c [1/mm], f_fr [MPa] (<= f_t, 0 allowed).
#pragma once

#include "SofteningLaw.h"

namespace pushout::laws
{
struct ExponentialSofteningSpec
{
  static constexpr const char* name = "exponential_softening";
  static constexpr const char* doc =
      "Camanho-Davila damage, exponential softening to f_fr, paper §2.3 Fig. 5b";
  static std::vector<ParamDef> params()
  {
    return {penalty_param("k", 1000.0, "penalty stiffness (Table 1: Exp. soft.)"),
            {"f_t", 3.0, "MPa", "tensile strength (peak traction)", 0, true},
            {"c", 25.0, "1/mm", "exponential decay rate", 0, true},
            {"f_fr", 0.0, "MPa", "asymptotic residual traction (<= f_t)", 0, false}};
  }
  static Envelope envelope(const Params& p, const std::string& prefix)
  {
    check_residual(p, prefix);
    return {Envelope::Kind::exponential, p.at("f_t"), 0.0, p.at("f_fr"), p.at("c")};
  }
};
using ExponentialSoftening = SofteningLaw<ExponentialSofteningSpec>;
} // namespace pushout::laws

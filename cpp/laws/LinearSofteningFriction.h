// Linear softening with a constant residual ("linear softening plus constant
// friction after a given displacement", paper §2.3): the linear branch of
// LinearSoftening until it reaches f_fr, then f_fr; secant unloading;
// compression elastic. The residual is a constant stress, not Coulomb.
// Parameters: k [N/mm^3], f_t [MPa], w_c2 [mm], f_fr [MPa] (<= f_t).
#pragma once

#include "SofteningLaw.h"

namespace pushout::laws
{
struct LinearSofteningFrictionSpec
{
  static constexpr const char* name = "linear_softening_friction";
  static constexpr const char* doc =
      "Camanho-Davila damage, linear softening to a constant residual f_fr, paper §2.3";
  static std::vector<ParamDef> params()
  {
    return {penalty_param("k", 100.0, "penalty stiffness"),
            {"f_t", 1.0, "MPa", "tensile strength (peak traction)", 0, true},
            {"w_c2", 0.3, "mm", "softening length of the linear branch (to zero)", 0, true},
            {"f_fr", std::nullopt, "MPa", "residual traction (<= f_t)", 0, false}};
  }
  static Envelope envelope(const Params& p, const std::string& prefix)
  {
    check_residual(p, prefix);
    return {Envelope::Kind::linear_residual, p.at("f_t"), p.at("w_c2"), p.at("f_fr")};
  }
};
using LinearSofteningFriction = SofteningLaw<LinearSofteningFrictionSpec>;
} // namespace pushout::laws

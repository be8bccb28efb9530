// The three cohesive softening laws of the paper (§2.3, Fig. 5a/b, Table 1),
// each a CamanhoDavila damage with its envelope (Envelope.h). State: [kappa]
// (the largest equivalent jump reached, mm).
#pragma once

#include "../scene/SceneError.h"
#include "CamanhoDavila.h"
#include "LawRegistry.h"

namespace pushout::laws
{
/// Shared body of the softening laws: `Spec` supplies name, doc, params()
/// and envelope(Params).
template <typename Spec> class SofteningLaw
{
public:
  static constexpr const char* name = Spec::name;
  static constexpr const char* doc = Spec::doc;
  static constexpr int state_size = 1;
  static std::vector<ParamDef> params() { return Spec::params(); }

  SofteningLaw(const Params& p, const std::string& prefix)
      : _cd(p.at("k"), Spec::envelope(p, prefix))
  {
  }

  LawResult update(std::span<const double> state_old, const Vec3& w,
                   std::span<double> state_new) const
  {
    return _cd.update(state_old[0], w, state_new[0]);
  }
  std::array<double, 2> slip(std::span<const double>) const { return {0, 0}; }
  double damage(std::span<const double> state) const { return _cd.damage(state[0]); }

private:
  CamanhoDavila _cd;
};

/// Throws unless f_fr <= f_t.
inline void check_residual(const Params& p, const std::string& prefix)
{
  if (p.at("f_fr") > p.at("f_t"))
    throw SceneError("'" + prefix + "f_fr' = " + std::to_string(p.at("f_fr")) +
                     " MPa must not exceed '" + prefix + "f_t' = " + std::to_string(p.at("f_t")) +
                     " MPa");
}
} // namespace pushout::laws

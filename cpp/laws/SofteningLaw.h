// The three cohesive softening laws of the paper (§2.3, Fig. 5a/b, Table 1),
// each a CamanhoDavila damage with its envelope (Envelope.h) and optional
// viscosity `eta`. State: [kappa (the largest equivalent jump reached, mm),
// D_v (the acting damage)].
#pragma once

#include "CamanhoDavila.h"
#include "LawRegistry.h"
#include "ParameterError.h"
#include <sstream>

namespace pushout::laws
{
/// The optional damage viscosity shared by the damage laws.
inline ParamDef viscosity_param()
{
  return {"eta",
          0.0,
          "mm",
          "damage viscosity: pseudo-time constant in mm of push (single joint: mm of shear "
          "path); 0: rate independent",
          0,
          false};
}

/// Throws unless f_fr <= f_t.
inline void check_residual(const Params& p, const std::string& prefix)
{
  if (p.at("f_fr") > p.at("f_t"))
  {
    std::ostringstream s;
    s.precision(10); // the values as given, to 10 digits
    s << "'" << prefix << "f_fr' = " << p.at("f_fr") << " MPa must not exceed '" << prefix
      << "f_t' = " << p.at("f_t") << " MPa";
    throw ParameterError(s.str());
  }
}
/// Shared body of the softening laws: `Spec` supplies name, doc, params()
/// and envelope(Params).
template <typename Spec> class SofteningLaw
{
public:
  static constexpr const char* name = Spec::name;
  static constexpr const char* doc = Spec::doc;
  static constexpr int state_size = CamanhoDavila::state_size;
  static std::vector<ParamDef> params()
  {
    std::vector<ParamDef> p = Spec::params();
    p.push_back(viscosity_param());
    return p;
  }

  SofteningLaw(const Params& p, const std::string& prefix)
      : _cd(p.at("k"), Spec::envelope(p, prefix), p.at("eta"))
  {
  }

  LawResult update(std::span<const double> state_old, const Vec3& w, std::span<double> state_new,
                   const StepInputs& in = {}) const
  {
    return _cd.update(state_old, w, state_new, in.dt);
  }
  std::array<double, 2> slip(std::span<const double>) const { return {0, 0}; }
  double damage(std::span<const double> state) const { return DamageHistory(state).damage(); }
  /// Energy released to full softening [N/mm] (CamanhoDavila::fracture_energy).
  double fracture_energy() const { return _cd.fracture_energy(); }

private:
  CamanhoDavila _cd;
};

} // namespace pushout::laws

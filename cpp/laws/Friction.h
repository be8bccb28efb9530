// Coulomb friction with inelastic (plastic) slip, paper §3, eqs. (4)-(6).
//
//   t = k (w - w^p),   w^p a vector in the tangent plane (w^p . n = 0)
//   p = max(-t_n, 0)                               (contact pressure)
//   trial: t_s = k (w_s - w^p_old);   f = |t_s| - mu p          (eq. 6)
//   f <= 0: stick.  f > 0: radial return
//       t_s = mu p m,   m = t_s / |t_s|,   w^p = w^p_old + (f / k) m
//
// Consistent tangent while sliding (unsymmetric: shear couples to w_n via mu):
//   dt_s/dw_s = (mu p / |t_s^trial|) k (I - m m^T),  dt_s/dw_n = -mu k m
//   (the second only in contact, t_n < 0, where dp/dw_n = -k).
//
// Opening (w_n > 0): p = 0, so the joint carries no shear (t_s = 0, the whole
// shear jump becomes slip) and keeps the penalty k in the normal direction, as
// eq. (5) applies K = k 1 to the whole jump: the joint resists separation
// elastically. State: [w^p_s1, w^p_s2] in mm.
//
// Parameters: k [N/mm^3], mu [-]. Reference: Sanz, Planas, Sancho §3.
#pragma once

#include "InterfaceLaw.h"
#include "LawRegistry.h"
#include <cmath>

namespace pushout::laws
{
/// Named view of the plastic slip at a point, the one place that knows its
/// layout [w^p_s1, w^p_s2] (mm). T is double (to write) or const double.
template <typename T> class PlasticSlip
{
public:
  static constexpr int size = 2;
  explicit PlasticSlip(std::span<T> state) : _s(state.first(size)) {}
  T& s1() const { return _s[0]; } ///< along the tangent s1 (axial) [mm]
  T& s2() const { return _s[1]; } ///< along the tangent s2 (circumferential) [mm]
  std::array<double, 2> vector() const { return {_s[0], _s[1]}; }

private:
  std::span<T> _s;
};

/// The shear part of eq. (6) on a given contact pressure p [MPa] (with
/// dp/dw_n [N/mm^3] for the tangent): trial t_s = k (w_s - w^p_old), limit
/// mu p, radial return. Writes r.t[1], r.t[2], the shear rows of r.D (the
/// caller has set r.D to its elastic tangent) and the new slip; adds the
/// slip's dissipation mu p |dw^p| to r.dissipation; marks r failed if the
/// traction is not finite.
inline void coulomb_return(double k, double mu, double p, double dp_dwn, const Vec3& w,
                           PlasticSlip<const double> old, PlasticSlip<double> now, LawResult& r)
{
  const double ts1 = k * (w[1] - old.s1());
  const double ts2 = k * (w[2] - old.s2());
  const double norm = std::hypot(ts1, ts2);
  const double f = norm - mu * p;
  now.s1() = old.s1();
  now.s2() = old.s2();
  if (f > 0)
  {
    const double m1 = ts1 / norm, m2 = ts2 / norm;
    const double scale = mu * p / norm;
    r.t[1] = mu * p * m1;
    r.t[2] = mu * p * m2;
    now.s1() += f / k * m1;
    now.s2() += f / k * m2;
    r.dissipation += mu * p * f / k; // |t_s| |dw^p|, t_s parallel to dw^p
    r.D[4] = scale * k * (1 - m1 * m1);
    r.D[5] = -scale * k * m1 * m2;
    r.D[7] = -scale * k * m2 * m1;
    r.D[8] = scale * k * (1 - m2 * m2);
    r.D[3] = mu * dp_dwn * m1;
    r.D[6] = mu * dp_dwn * m2;
  }
  else
  {
    r.t[1] = ts1;
    r.t[2] = ts2;
  }
  if (!std::isfinite(r.t[0] + r.t[1] + r.t[2]))
    r.status = LawStatus::failed;
}

class Friction
{
public:
  static constexpr const char* name = "friction";
  static constexpr const char* doc = "Coulomb friction with vector plastic slip, paper §3 (k, mu)";
  static constexpr int state_size = PlasticSlip<double>::size;

  static std::vector<ParamDef> params()
  {
    return {penalty_param("k", 1000.0, "penalty stiffness (Table 1: Friction 2)"),
            {"mu", 0.4, "-", "friction coefficient", 0, false}};
  }

  Friction(double k, double mu) : _k(k), _mu(mu) {}
  Friction(const Params& p, const std::string&) : Friction(p.at("k"), p.at("mu")) {}

  LawResult update(std::span<const double> state_old, const Vec3& w, std::span<double> state_new,
                   const StepInputs& /*in*/ = {}) const
  {
    return update_with_gap(state_old, w, state_new, 0.0, 0.0);
  }

  std::array<double, 2> slip(std::span<const double> state) const
  {
    return PlasticSlip(state).vector();
  }
  double damage(std::span<const double>) const { return 0; }

protected:
  /// How the joint answers an opening beyond its free gap.
  enum class Opening
  {
    penalty,   ///< t_n = k (w_n - gap): it resists separation (eq. 5)
    unilateral ///< t_n = 0: nothing pulls (the oxide of OxideFriction.h)
  };

  /// The update when the joint has a free normal opening `gap` [mm] and a
  /// normal compliance [mm^3/N] in series with k in contact (OxideFriction.h);
  /// with both 0 and Opening::penalty it is eqs. (4)-(6) as above, to the bit.
  LawResult update_with_gap(std::span<const double> state_old, const Vec3& w,
                            std::span<double> state_new, double gap, double compliance,
                            Opening opening_law = Opening::penalty) const
  {
    LawResult r;
    const double k = _k;
    const double opening = w[0] - gap; // [mm]
    const bool contact = opening < 0;
    const double kn = contact && compliance > 0 ? 1 / (1 / k + compliance) : k;
    if (opening_law == Opening::unilateral && opening > 0)
    {
      // Separated: no normal traction and no normal stiffness. At w_n = gap
      // exactly the penalty k stays, so a joint at rest is not singular.
      r.t[0] = 0;
      r.D = {0, 0, 0, 0, k, 0, 0, 0, k};
    }
    else
    {
      r.t[0] = kn * opening;
      r.D = {kn, 0, 0, 0, k, 0, 0, 0, k};
    }
    const double p = contact ? -r.t[0] : 0.0;
    const double dp_dwn = contact ? -kn : 0.0;
    coulomb_return(k, _mu, p, dp_dwn, w, PlasticSlip(state_old), PlasticSlip(state_new), r);
    return r;
  }

private:
  double _k;  // penalty stiffness [N/mm^3]
  double _mu; // friction coefficient [-]
};
} // namespace pushout::laws

// One law carrying cohesion and friction (the paper's future work, §4.3, §5),
// after Alfano & Sacco (2006), "Combining interface damage and friction in a
// cohesive-zone model", Int. J. Numer. Meth. Engng 68:542-582.
//
// A fraction D of the interface is damaged (D from the Camanho-Davila
// envelope, CamanhoDavila.h); the undamaged part is elastic, the damaged
// part is in unilateral contact with Coulomb friction and plastic slip
// (Friction.h):
//
//   t = (1 - D) k w + D t_d
//   t_d,n = k min(w_n, 0)                  (contact: no tension)
//   t_d,s = Coulomb return mapping of k (w_s - w^p), p = max(-k w_n, 0)
//
// Limits: D = 0 is `elastic` (k); D = 1 is `friction` (k, mu) in contact.
// In compression t_n = k w_n whatever D; in opening t_n = (1 - D) k w_n.
// Consistent tangent: (1 - D) k I + D dt_d/dw + (t_d - k w) (x) dD/dw, with
// dD/dw = -(g'(delta)/k) w_open/delta on loading (0 otherwise).
// Dissipation: (1/2 k |w|^2 - psi_d) dD + D mu p |dw^p|, psi_d the damaged
// part's elastic energy (contact and stick).
//
// Envelope: linear (give w_c2) or exponential (give c), both to zero: the
// residual stress comes from friction. Optional damage viscosity eta as in
// CamanhoDavila.h (D is then the acting damage D_v). State: [kappa (mm),
// D_v, w^p_s1, w^p_s2 (mm)].
// Parameters: k [N/mm^3], mu [-], f_t [MPa], w_c2 [mm] or c [1/mm], eta [mm].
#pragma once

#include "CamanhoDavila.h"
#include "Friction.h"
#include "LawRegistry.h"
#include "ParameterError.h"
#include "SofteningLaw.h"

namespace pushout::laws
{
/// Named view of the state of CohesiveFriction: its damage history, then
/// the plastic slip of its damaged part. T is double or const double.
template <typename T> class CohesiveFrictionState
{
public:
  static constexpr int size = DamageHistory<T>::size + PlasticSlip<T>::size;
  explicit CohesiveFrictionState(std::span<T> state)
      : _history(state.first(DamageHistory<T>::size)),
        _slip(state.subspan(DamageHistory<T>::size, PlasticSlip<T>::size))
  {
  }
  std::span<T> slip() const { return _slip; } ///< for Friction
  DamageHistory<T> damage_history() const { return DamageHistory<T>(_history); }
  PlasticSlip<T> plastic_slip() const { return PlasticSlip<T>(_slip); }

private:
  std::span<T> _history, _slip;
};

class CohesiveFriction
{
public:
  static constexpr const char* name = "cohesive_friction";
  static constexpr const char* doc = "damage transfers load from cohesion to Coulomb friction "
                                     "(Alfano & Sacco 2006): k, mu, f_t, and w_c2 or c";
  static constexpr int state_size = CohesiveFrictionState<double>::size;

  static std::vector<ParamDef> params()
  {
    ParamDef w_c2{"w_c2", std::nullopt, "mm", "linear envelope: softening length", 0, true};
    ParamDef c{"c", std::nullopt, "1/mm", "exponential envelope: decay rate", 0, true};
    w_c2.optional = c.optional = true;
    return {penalty_param("k", 1000.0, "penalty stiffness"),
            {"mu", 0.4, "-", "friction coefficient of the damaged part", 0, false},
            {"f_t", 3.0, "MPa", "tensile strength (peak traction)", 0, true},
            w_c2,
            c,
            viscosity_param()};
  }

  CohesiveFriction(double k, double mu, Envelope envelope, double eta = 0)
      : _cd(k, envelope, eta), _friction(k, mu)
  {
  }
  CohesiveFriction(const Params& p, const std::string& prefix)
      : CohesiveFriction(p.at("k"), p.at("mu"), envelope(p, prefix), p.at("eta"))
  {
  }

  LawResult update(std::span<const double> state_old, const Vec3& w, std::span<double> state_new,
                   const StepInputs& in = {}) const
  {
    const double dt = in.dt;
    const double k = _cd.k();
    const CohesiveFrictionState old(state_old);
    const CohesiveFrictionState now(state_new);
    const DamageHistory history_old = old.damage_history();
    const DamageHistory history = now.damage_history();
    double& kappa = history.kappa();
    const bool on_envelope = _cd.loading(history_old.kappa(), w, kappa);
    const double D = history.damage() = _cd.acting_damage(kappa, history_old.damage(), dt);
    const LawResult fr = _friction.update(old.slip(), w, now.slip());

    // Damaged part: contact normal and friction shear.
    Vec3 td = {k * std::min(w[0], 0.0), fr.t[1], fr.t[2]};
    Mat3 Dd = fr.D;
    Dd[0] = w[0] < 0 ? k : 0.0;

    LawResult r;
    for (int a = 0; a < 3; ++a)
    {
      r.t[a] = (1 - D) * k * w[a] + D * td[a];
      for (int b = 0; b < 3; ++b)
        r.D[3 * a + b] = (a == b ? (1 - D) * k : 0.0) + D * Dd[3 * a + b];
    }
    if (on_envelope)
    {
      const double delta = kappa;
      const Vec3 we = {std::max(w[0], 0.0), w[1], w[2]};
      const double dD = -_cd.theta(dt) * _cd.dsecant(delta) / k / delta; // times we_b
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          r.D[3 * a + b] += (td[a] - k * w[a]) * dD * we[b];
    }
    // Dissipation: the free energy (1 - D) 1/2 k |w|^2 + D psi_d released by
    // the damage, and the damaged part's frictional slip.
    const double wn_c = std::min(w[0], 0.0);
    const double ws1 = w[1] - now.plastic_slip().s1(), ws2 = w[2] - now.plastic_slip().s2();
    const double psi_d = 0.5 * k * (wn_c * wn_c + ws1 * ws1 + ws2 * ws2);
    const double psi_0 =
        0.5 * k * (_cd.released_square(history_old.kappa(), w, on_envelope) + wn_c * wn_c);
    r.dissipation = (psi_0 - psi_d) * (D - history_old.damage()) + D * fr.dissipation;
    r.status = fr.status;
    if (!std::isfinite(r.t[0] + r.t[1] + r.t[2]))
      r.status = LawStatus::failed;
    return r;
  }

  /// The plastic slip of the damaged part [mm].
  std::array<double, 2> slip(std::span<const double> state) const
  {
    return CohesiveFrictionState(state).plastic_slip().vector();
  }
  /// The acting damage D_v (with viscosity, behind D(kappa)).
  double damage(std::span<const double> state) const
  {
    return CohesiveFrictionState(state).damage_history().damage();
  }
  /// Energy the cohesion releases to full damage [N/mm] (its friction's
  /// dissipation is not counted: CamanhoDavila::fracture_energy).
  double fracture_energy() const { return _cd.fracture_energy(); }

private:
  static Envelope envelope(const Params& p, const std::string& prefix)
  {
    const bool linear = p.count("w_c2"), exponential = p.count("c");
    if (linear == exponential)
      throw ParameterError(
          "'" + prefix + "w_c2' (linear envelope) or '" + prefix +
          "c' (exponential envelope): give exactly one for law 'cohesive_friction'");
    if (linear)
      return {Envelope::Kind::linear, p.at("f_t"), p.at("w_c2")};
    return {Envelope::Kind::exponential, p.at("f_t"), 0.0, 0.0, p.at("c")};
  }

  CamanhoDavila _cd;
  Friction _friction;
};
} // namespace pushout::laws

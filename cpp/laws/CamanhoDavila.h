// Cohesive damage after Camanho & Davila (2002), as the paper uses it (§2.3,
// Fig. 5a/b, eq. 3), shared by the softening laws.
//
//   equivalent jump  delta = sqrt(|w_s|^2 + <w_n>^2)
//     (the paper writes w_m = w_s + <w_n>, eq. 3; we take the Euclidean norm
//      of the opening part of the jump, which is frame invariant)
//   history          kappa = max(kappa_old, delta),  w0 = f_t / k
//   secant stiffness g(kappa) = k for kappa <= w0, sigma(kappa) / kappa after
//   traction         t_s = g w_s;  t_n = g w_n in opening, k w_n in
//                    compression (always elastic, never damaged)
//   damage           D = 1 - g / k (unloading and reloading run secant to the
//                    origin)
//   dissipation      1/2 k |w_open|^2 (D_new - D_old) per update: the free
//                    energy 1/2 (1 - D) k |w_open|^2 released by the damage
//                    (w_open = (<w_n>, w_s); on the envelope |w_open|^2 is
//                    the step's mean of kappa^2 weighted by dD, exact
//                    whatever the step); summed to full
//                    separation it is G_F = f_t^2 / (2 k) + the area under
//                    sigma beyond w0
// Consistent tangent on loading (delta > kappa_old, delta > w0):
//   dt_a/dw_b = g I_ab + g'(delta) w_a w_b / delta over the opening
//   components, g' = (sigma' delta - sigma) / delta^2; secant otherwise.
#pragma once

#include "Envelope.h"
#include "InterfaceLaw.h"
#include <cmath>
#include <span>

namespace pushout::laws
{
/// Named view of the damage history at a point, the one place that knows
/// its layout [kappa, D_v]. T is double (to write) or const double.
template <typename T> class DamageHistory
{
public:
  static constexpr int size = 2;
  explicit DamageHistory(std::span<T> state) : _s(state.first(size)) {}
  /// The largest equivalent jump reached [mm].
  T& kappa() const { return _s[0]; }
  /// The acting damage D_v in [0, 1]: D(kappa), or behind it with viscosity.
  T& damage() const { return _s[1]; }

private:
  std::span<T> _s;
};

class CamanhoDavila
{
public:
  static constexpr int state_size = DamageHistory<double>::size;

  CamanhoDavila(double k, Envelope envelope, double eta = 0)
      : _k(k), _env(envelope), _w0(envelope.f_t / k), _eta(eta)
  {
  }

  double k() const { return _k; }
  double w0() const { return _w0; }
  const Envelope& envelope() const { return _env; }

  /// The energy per unit area released from the unloaded state to full
  /// softening [N/mm]: f_t^2 / (2 k) + the softening's
  /// (Envelope::softening_energy); with f_fr = 0 the fracture energy G_F
  /// (tests/unit/laws/test_dissipation.cpp).
  double fracture_energy() const { return 0.5 * _env.f_t * _w0 + _env.softening_energy(); }

  /// Secant stiffness g(kappa) [N/mm^3].
  double secant(double kappa) const
  {
    if (kappa <= _w0)
      return _k;
    return _env.evaluate(kappa, _w0).sigma / kappa;
  }

  /// Damage D = 1 - g / k in [0, 1].
  double damage(double kappa) const { return 1 - secant(kappa) / _k; }

  /// Equivalent jump delta of w.
  static double equivalent(const Vec3& w)
  {
    const double wn = std::max(w[0], 0.0);
    return std::sqrt(wn * wn + w[1] * w[1] + w[2] * w[2]);
  }

  /// History update kappa_new and whether this is loading on the envelope.
  bool loading(double kappa_old, const Vec3& w, double& kappa_new) const
  {
    const double delta = equivalent(w);
    kappa_new = std::max(kappa_old, delta);
    return delta > kappa_old && delta > _w0;
  }

  /// d g / d delta at delta (on the envelope, delta > w0).
  double dsecant(double delta) const
  {
    const Envelope::Value v = _env.evaluate(delta, _w0);
    return (v.dsigma * delta - v.sigma) / (delta * delta);
  }

  /// The energy per unit area a point dissipates by softening from the
  /// unloaded state to the history kappa on the envelope [N/mm]: the work
  /// done, 1/2 f_t w0 + int_w0^kappa sigma, less the free energy left,
  /// 1/2 sigma(kappa) kappa (zero at w0, fracture_energy() at separation).
  double softened(double kappa) const
  {
    if (kappa <= _w0)
      return 0;
    return 0.5 * _env.f_t * _w0 + _env.work(kappa, _w0) -
           0.5 * _env.evaluate(kappa, _w0).sigma * kappa;
  }

  /// |w_open|^2 for the dissipation 1/2 k |w_open|^2 dD of a step [mm^2]:
  /// on the envelope the mean of kappa^2 over the step weighted by dD,
  /// exactly (the difference of softened() over 1/2 k dD(kappa), from
  /// kappa_old, or w0 where damage starts: a trapezoid of kappa^2 overstated
  /// a step from w0 to 5 w0 2.7 times, as D rises steepest where kappa is
  /// smallest); off it (unloading, viscous lag) the end of the step's.
  double released_square(double kappa_old, const Vec3& w, bool on_envelope) const
  {
    const double delta = equivalent(w);
    if (!on_envelope)
      return delta * delta;
    const double from = std::max(kappa_old, _w0);
    const double dD = damage(delta) - damage(from);
    if (!(dD > 0)) // past full damage: nothing left to release on the envelope
      return delta * delta;
    return (softened(delta) - softened(from)) / (0.5 * _k * dD);
  }

  /// Weight theta of the new damage in the implicit viscous update.
  double theta(double dt) const { return _eta > 0 ? (dt / _eta) / (1 + dt / _eta) : 1.0; }

  /// The acting damage D_v after a step from (kappa_new, D_v,old) over dt.
  double acting_damage(double kappa_new, double damage_old, double dt) const
  {
    return damage_old + theta(dt) * (damage(kappa_new) - damage_old);
  }

  /// The cohesive traction and tangent from the committed damage history
  /// over the pseudo-time increment dt; writes the new history.
  LawResult update(std::span<const double> state_old, const Vec3& w, std::span<double> state_new,
                   double dt) const
  {
    LawResult r;
    const DamageHistory old(state_old);
    const DamageHistory now(state_new);
    const bool on_envelope = loading(old.kappa(), w, now.kappa());
    now.damage() = acting_damage(now.kappa(), old.damage(), dt);
    const double g = (1 - now.damage()) * _k;
    const bool open = w[0] > 0;
    r.t = {(open ? g : _k) * w[0], g * w[1], g * w[2]};
    r.D = {open ? g : _k, 0, 0, 0, g, 0, 0, 0, g};
    r.dissipation =
        0.5 * _k * released_square(old.kappa(), w, on_envelope) * (now.damage() - old.damage());
    if (on_envelope)
    {
      const double c = theta(dt) * dsecant(now.kappa()) / now.kappa();
      const Vec3 we = {open ? w[0] : 0.0, w[1], w[2]};
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          r.D[3 * a + b] += c * we[a] * we[b];
    }
    if (!std::isfinite(r.t[0] + r.t[1] + r.t[2]))
      r.status = LawStatus::failed;
    return r;
  }

private:
  double _k;
  Envelope _env;
  double _w0;
  double _eta; ///< viscosity (pseudo-time) of the damage; 0: none
};
} // namespace pushout::laws

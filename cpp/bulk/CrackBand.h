// Concrete that cracks: linear elastic until the largest principal stress
// reaches f_t, then a cohesive crack smeared over a band (Bazant & Oh 1983),
// at one quadrature point. The bulk law of cracks anywhere in the concrete
// (docs/cracking.md).
//
// Why a crack band and not an embedded discontinuity: the concrete's
// hexahedra are not constant-strain elements, so their quadrature points
// carry different strains; the crack lives where the strain does, at the
// points, and the element's size along the crack normal is the band width h
// over which the crack's opening w is smeared:
//
//   epsilon = epsilon_e + sym(w (x) n) / h,     sigma = C : epsilon_e
//
// Then a crack of opening w dissipates G_F per unit crack area whatever the
// element size: the band's energy density G_F / h times its volume A h.
//
// Onset: the point is uncracked while the largest principal stress of
// C : epsilon is below f_t; when it reaches f_t a crack is inserted with its
// normal n along that principal direction, fixed from then on (state: n, a
// tangent s1, h). The crack's traction-opening law is a softening law of the
// interface registry (laws/CamanhoDavila.h with the envelope of
// `exponential_softening` or `linear_softening`): central force (the
// traction parallel to the opening), damage with secant unloading to the
// origin, closure in compression by a penalty. Its penalty k_p is stiff
// against the band, k_p = penalty_factor (lambda + 2 mu) / h, so that the
// inserted crack takes 1/penalty_factor of the band's compliance (the stress
// drops by that fraction, 0.1 % by default, where it is inserted).
//
// At each update the opening w solves the crack's equilibrium, the traction
// of the band's stress on the crack plane equal to the cohesive traction:
//
//   r(w) = t(w) + A w / h - sigma_0 n = 0,   A = P^T C P (acoustic tensor),
//
// sigma_0 = C : epsilon the stress of the uncracked point, P the map
// w -> sym(w (x) n): a 3 x 3 Newton iteration with backtracking. The
// consistent tangent follows by eliminating dw:
//
//   d sigma / d epsilon = C - (1/h) (C P) J^-1 (C P)^T,   J = R^T D_t R + A / h
//
// (D_t the cohesive law's tangent in the crack frame R = [n, s1, s2]). J must
// stay positive definite on the softening branch: h < mu / |sigma'|_max
// (max_band_width), the size condition of the crack band; a wider band would
// snap back at the point and is reported as a failure.
//
// Units: stress MPa, strain -, opening and h mm, energy density N mm/mm^3.
#pragma once

#include "../laws/CamanhoDavila.h"
#include "../laws/Envelope.h"
#include "Voigt.h"
#include <algorithm>
#include <cmath>
#include <span>

namespace pushout::bulk
{
/// Named view of a point's state, the one place that knows its layout
/// [cracked, n (3), s1 (3), h, kappa, D]. T is double (to write) or const
/// double.
template <typename T> class CrackState
{
public:
  static constexpr int size = 10;
  explicit CrackState(std::span<T> s) : _s(s.first(size)) {}
  bool cracked() const { return _s[0] != 0; }
  T& cracked_flag() const { return _s[0]; }
  /// Unit normal of the crack (global frame).
  Vec3 normal() const { return {_s[1], _s[2], _s[3]}; }
  /// Unit tangent s1 of the crack plane; s2 = n x s1.
  Vec3 tangent() const { return {_s[4], _s[5], _s[6]}; }
  /// The crack frame: rows n, s1, s2 = n x s1 (right-handed).
  Mat3 frame() const
  {
    const Vec3 n = normal(), s1 = tangent();
    return {n[0],
            n[1],
            n[2],
            s1[0],
            s1[1],
            s1[2],
            n[1] * s1[2] - n[2] * s1[1],
            n[2] * s1[0] - n[0] * s1[2],
            n[0] * s1[1] - n[1] * s1[0]};
  }
  /// Band width: the element's size along n [mm].
  T& band_width() const { return _s[7]; }
  /// The cohesive law's history [kappa, D] (laws::DamageHistory).
  std::span<T> law_state() const { return _s.subspan(8, 2); }
  void set_frame(const Vec3& n, const Vec3& s1) const
  {
    for (int i = 0; i < 3; ++i)
    {
      _s[1 + i] = n[i];
      _s[4 + i] = s1[i];
    }
  }

private:
  std::span<T> _s;
};

/// Whether CrackBand::update() computes the tangent, or leaves it zero
/// (IMPL-EX's updates keep the state and the stress, and never read it).
enum class Tangent
{
  compute,
  skip
};

/// What an update returns.
struct CrackBandResult
{
  Voigt stress{};    ///< [MPa]
  Voigt66 tangent{}; ///< d stress / d strain (Voigt, engineering shears) [MPa]
  Vec3 opening{};    ///< crack opening in the crack frame [n, s1, s2] [mm]; 0 uncracked
  double damage = 0; ///< the crack's damage D in [0, 1]; 0 uncracked
  /// Energy dissipated per unit volume from the committed state to the
  /// trial one [N mm/mm^3]: the crack's dissipation per unit area over h.
  double dissipation = 0;
  /// secant_response(): the crack is closed (its normal stiffness the
  /// closure penalty)
  bool closed = false;
  enum class Status
  {
    ok,
    not_converged, ///< the crack's 3 x 3 equilibrium did not converge
    band_too_wide, ///< h >= max_band_width(): the point would snap back
    not_finite     ///< the strain is not finite (an iterate that blew up)
  } status = Status::ok;
};

/// IMPL-EX: a cracked point's secant response (CrackBand::secant_response)
/// at a fixed history as linear maps of the strain, one on each side of
/// closure, and the functional whose sign picks the side: what every
/// evaluation of a step needs, computed once per step
/// (CrackBand::secant_operator, applied by CrackBand::secant_apply).
///
/// What picks the side comes first, on one cache line: an evaluation reads
/// it at every point, and then one of the two maps (BulkCracking::evaluate
/// streams them, 40 960 points on the bench's mesh).
struct alignas(64) SecantOperator
{
  bool cracked = false;
  /// That side's crack equilibrium J is regular (else its response fails).
  std::array<bool, 2> regular{true, true};
  double damage = 0; ///< the crack's damage at the history [-]
  /// n . w of the open crack per unit strain [mm]: the crack is open where
  /// closing . epsilon > 0.
  Voigt closing{};
  /// d sigma / d epsilon with the crack open [0] and closed [1] [MPa]
  std::array<Voigt66, 2> tangent{};
  /// What the maps were made of: the crack's normal and band width (n, h),
  /// the history and the strength (not s1: an open crack's secant is the
  /// same along every direction of its plane). The same again leaves them
  /// as they are (a crack that unloads keeps its history from step to step).
  std::array<double, 6> made_of{};
};

class CrackBand
{
public:
  static constexpr int state_size = CrackState<double>::size;

  /// E [MPa], nu [-]; `envelope` the cohesive law's softening curve (its
  /// f_t the tensile strength); `eta` the damage viscosity of the cohesive
  /// law [pseudo time] (0: none).
  CrackBand(double E, double nu, laws::Envelope envelope, double eta = 0,
            double penalty_factor = 1e3)
      : _C(isotropic_stiffness(E, nu)), _lame(lame(E, nu)), _env(envelope), _eta(eta),
        _penalty_factor(penalty_factor)
  {
  }

  const Voigt66& stiffness() const { return _C; }

  /// The envelope of a point whose strength is `strength` times the
  /// envelope's (a random strength field scales the tractions, f_t and f_fr;
  /// the openings stay).
  laws::Envelope envelope(double strength = 1) const
  {
    laws::Envelope e = _env;
    e.f_t *= strength;
    e.f_fr *= strength;
    return e;
  }

  /// The damage viscosity of the cracks' cohesive law [mm of push]; 0: none.
  double viscosity() const { return _eta; }

  /// The cohesive law of a crack whose band is h wide [mm].
  laws::CamanhoDavila cohesive_law(double h, double strength = 1) const
  {
    return {_penalty_factor * (_lame[0] + 2 * _lame[1]) / h, envelope(strength), _eta};
  }

  /// The widest band a point can soften over without snapping back [mm]:
  /// mu / |d sigma / d w|_max (conservative: mode II's stiffness).
  double max_band_width(double strength = 1) const
  {
    const laws::Envelope e = envelope(strength);
    const double slope =
        e.kind == laws::Envelope::Kind::exponential ? e.c * (e.f_t - e.f_fr) : e.f_t / e.w_c2;
    return slope > 0 ? _lame[1] / slope : INFINITY;
  }

  /// The response of an uncracked point held so whatever its stress (a
  /// predictor that lets no crack in): the committed state, C : strain.
  CrackBandResult held_uncracked(std::span<const double> old, const Voigt& strain,
                                 std::span<double> now) const
  {
    std::copy(old.begin(), old.begin() + state_size, now.begin());
    CrackBandResult r;
    r.stress = multiply(_C, strain);
    r.tangent = _C;
    return r;
  }

  /// The update from the committed state `old` at the strain `strain`;
  /// writes the trial state `now` (same size). `band_width(n)` gives the
  /// element's size along a unit normal n [mm] (called when a crack is
  /// inserted); `strength` is the point's f_t over the envelope's; `dt` the
  /// step's pseudo-time increment (viscous damage). With Tangent::skip the
  /// result's tangent stays zero, and everything else is as computed.
  template <typename BandWidth>
  CrackBandResult update(std::span<const double> old, const Voigt& strain, std::span<double> now,
                         BandWidth&& band_width, double strength = 1, double dt = 0,
                         Tangent tangent = Tangent::compute) const
  {
    const bool with_tangent = tangent == Tangent::compute;
    CrackBandResult r;
    std::copy(old.begin(), old.begin() + state_size, now.begin());
    const CrackState<const double> before(old);
    const CrackState<double> after(now);
    if (!finite(strain))
    {
      r.status = CrackBandResult::Status::not_finite;
      return r;
    }
    const Voigt sigma0 = multiply(_C, strain);
    if (!before.cracked())
    {
      // Below the strength whatever the principal axes: the largest
      // principal stress is at most the largest Gershgorin row bound (most
      // points, so their eigenproblem is skipped). The margin, far above the
      // eigensolver's round-off of a few ulps of the stress, keeps the
      // decision it makes where the bound is exact (equal normal stresses
      // and one shear: the rounded eigenvalue may exceed the rounded bound).
      if (gershgorin_bound(sigma0) + 1e-12 * largest_magnitude(sigma0) < strength * _env.f_t)
      {
        r.stress = sigma0;
        if (with_tangent)
          r.tangent = _C;
        return r;
      }
      Vec3 principal;
      Mat3 axes;
      symmetric_eigen(stress_tensor(sigma0), principal, axes);
      if (!(principal[0] >= strength * _env.f_t))
      {
        r.stress = sigma0;
        if (with_tangent)
          r.tangent = _C;
        return r;
      }
      // Onset: a crack normal to the largest principal stress.
      const Vec3 n = {axes[0], axes[1], axes[2]}, s1 = {axes[3], axes[4], axes[5]};
      after.cracked_flag() = 1;
      after.set_frame(n, s1);
      after.band_width() = band_width(n);
      std::fill(after.law_state().begin(), after.law_state().end(), 0.0);
    }
    const double h = after.band_width();
    if (!(h < max_band_width(strength)))
    {
      r.status = CrackBandResult::Status::band_too_wide;
      return r;
    }
    solve_crack(before.cracked() ? before.law_state() : std::span<const double>(zero_history),
                after, sigma0, strength, dt, with_tangent, r);
    return r;
  }

  /// IMPL-EX (Oliver, Huespe & Cante 2008; docs/cracking.md, "IMPL-EX"):
  /// the response at `strain` of a point whose crack, if the committed
  /// state `old` has one, holds the damage of the history `kappa` [mm] (the
  /// committed history extrapolated over the step; never less than the
  /// committed one): a secant spring, closed by the penalty in compression.
  /// The stress is linear in the strain on either side of closure, and the
  /// tangent symmetric. An uncracked point is elastic whatever its stress:
  /// onset is found after the step, by update() at the converged strain.
  /// The state stays; nothing is dissipated.
  CrackBandResult secant_response(std::span<const double> old, const Voigt& strain, double kappa,
                                  double strength = 1) const
  {
    const CrackState<const double> state(old);
    CrackBandResult r;
    const Voigt sigma0 = multiply(_C, strain);
    r.stress = sigma0;
    r.tangent = _C;
    if (!finite(strain))
    {
      r.status = CrackBandResult::Status::not_finite;
      return r;
    }
    if (!state.cracked())
      return r;
    const CrackPlane plane(*this, state, sigma0);
    const laws::CamanhoDavila law = cohesive_law(plane.h, strength);
    kappa = std::max(kappa, laws::DamageHistory<const double>(state.law_state()).kappa());
    const double g = law.secant(kappa);
    // J with k_n = g open, the penalty closed (secant_jacobian). The crack's
    // energy is convex in w, so one of the two is consistent: open if its
    // w . n > 0, else closed.
    Vec3 w{};
    Mat3 J{};
    for (const double k_n : {g, law.k()})
    {
      J = secant_jacobian(plane, g, k_n);
      if (!solve3(J, plane.s0, w))
      {
        r.status = CrackBandResult::Status::not_converged;
        return r;
      }
      r.closed = k_n != g;
      if (plane.R[0] * w[0] + plane.R[1] * w[1] + plane.R[2] * w[2] > 0)
        break;
    }
    std::array<Vec3, 3> Jinv; // columns of J^-1
    if (!inverse_columns(J, Jinv))
    {
      r.status = CrackBandResult::Status::not_converged;
      return r;
    }
    point_response(plane, sigma0, w, Jinv, r);
    r.opening = rotate(plane.R, w);
    r.damage = law.damage(kappa);
    return r;
  }

  /// secant_response() of the committed state `old` at the history `kappa`
  /// [mm] as linear maps of the strain, into `op`: secant_apply() of it at a
  /// strain is secant_response() there. Written in place (an operator is
  /// 704 bytes, made at every point at every step); where `old` is
  /// uncracked only op.cracked is, the rest is never read. Where `op` holds
  /// the maps of the same crack at the same history and strength already
  /// (op.made_of), they stay: the same numbers without making them again.
  void secant_operator(std::span<const double> old, double kappa, double strength,
                       SecantOperator& op) const
  {
    const CrackState<const double> state(old);
    const bool was_cracked = op.cracked;
    op.cracked = state.cracked();
    if (!op.cracked)
      return;
    kappa = std::max(kappa, laws::DamageHistory<const double>(state.law_state()).kappa());
    const Vec3 n = state.normal();
    const std::array<double, 6> made_of = {n[0], n[1], n[2], state.band_width(), kappa, strength};
    if (was_cracked && made_of == op.made_of)
      return;
    op.made_of = made_of;
    op.closing = {};
    const CrackPlane plane(*this, state, Voigt{});
    const laws::CamanhoDavila law = cohesive_law(plane.h, strength);
    const double g = law.secant(kappa);
    op.damage = law.damage(kappa);
    const std::array<double, 2> k_n = {g, law.k()};
    for (int side = 0; side < 2; ++side)
    {
      std::array<Vec3, 3> Jinv;
      op.regular[side] = inverse_columns(secant_jacobian(plane, g, k_n[side]), Jinv);
      if (!op.regular[side])
        continue;
      op.tangent[side] = tangent_of(plane, Jinv);
      if (side == 1)
        continue;
      // n . w = n . J^-1 s0(epsilon), s0 the traction of C epsilon: column
      // j of C is the stress of the unit strain e_j.
      for (int j = 0; j < 6; ++j)
      {
        Voigt column;
        for (int i = 0; i < 6; ++i)
          column[i] = _C[6 * i + j];
        const Vec3 s0 = traction(column, plane.R_n());
        for (int i = 0; i < 3; ++i)
          for (int k = 0; k < 3; ++k)
            op.closing[j] += plane.R[i] * Jinv[k][i] * s0[k];
      }
    }
  }

  /// The stress and tangent of secant_operator() `op` at `strain`, and
  /// whether the crack is closed there (as secant_response(): no opening,
  /// no dissipation).
  CrackBandResult secant_apply(const SecantOperator& op, const Voigt& strain) const
  {
    CrackBandResult r;
    const int side = secant_side(op, strain);
    if (side == secant_elastic || side == secant_failed)
    {
      // Uncracked; or as secant_response() fails: elastic, not closed, not
      // converged.
      r.stress = multiply(_C, strain);
      r.tangent = _C;
      if (side == secant_failed)
        r.status = finite(strain) ? CrackBandResult::Status::not_converged
                                  : CrackBandResult::Status::not_finite;
      return r;
    }
    r.closed = side == secant_closed;
    r.tangent = op.tangent[side];
    r.stress = multiply(r.tangent, strain);
    r.damage = op.damage;
    return r;
  }

  /// Which map of secant_operator() `op` answers at `strain`, as
  /// secant_apply() picks it: op.tangent[secant_open] or
  /// op.tangent[secant_closed], or C (secant_elastic: uncracked;
  /// secant_failed: that side's crack equilibrium is singular, and
  /// secant_response() fails; or the strain is not finite, cracked or
  /// not). What an evaluation needs without the result's copy of the
  /// tangent.
  static int secant_side(const SecantOperator& op, const Voigt& strain)
  {
    if (!finite(strain))
      return secant_failed; // an iterate that blew up: no map answers it
    if (!op.cracked)
      return secant_elastic;
    double opening = 0;
    for (int j = 0; j < 6; ++j)
      opening += op.closing[j] * strain[j];
    // An undamaged crack (D = 0: its secant is the penalty) has the same map
    // on both sides: open, as secant_response() labels it, so that a sign
    // change of its opening is not a crack that opens or closes.
    const int side = op.regular[0] && (opening > 0 || op.damage == 0) ? secant_open : secant_closed;
    return op.regular[0] && op.regular[side] ? side : secant_failed;
  }
  static constexpr int secant_open = 0, secant_closed = 1, secant_failed = 2, secant_elastic = 3;

private:
  static constexpr std::array<double, 2> zero_history = {0, 0};

  /// Whether every component of `e` is finite.
  static bool finite(const Voigt& e)
  {
    double sum = 0;
    for (const double v : e)
      sum += v;
    return std::isfinite(sum); // an inf or a NaN anywhere makes the sum one
  }

  /// The largest magnitude of a component of `s` [MPa].
  static double largest_magnitude(const Voigt& s)
  {
    double m = 0;
    for (const double v : s)
      m = std::max(m, std::abs(v));
    return m;
  }

  /// An upper bound of the largest principal stress of `s` [MPa]: the
  /// largest diagonal entry plus its row's off-diagonal magnitudes
  /// (Gershgorin's circle theorem).
  static double gershgorin_bound(const Voigt& s)
  {
    return std::max({s[0] + std::abs(s[5]) + std::abs(s[4]), s[1] + std::abs(s[5]) + std::abs(s[3]),
                     s[2] + std::abs(s[4]) + std::abs(s[3])});
  }

  /// A crack's plane at a point of stress sigma_0 = C : epsilon: its frame,
  /// C P, A / h, and the traction of sigma_0 on it.
  struct CrackPlane
  {
    template <typename T>
    CrackPlane(const CrackBand& band, const CrackState<T>& state, const Voigt& sigma0)
        : h(state.band_width()), R(state.frame())
    {
      const Vec3 n = state.normal();
      // C P (6 x 3, column k: the stress of a unit opening along e_k over a
      // unit band) and A / h = P^T C P / h.
      for (int k = 0; k < 3; ++k)
      {
        Vec3 e{};
        e[k] = 1;
        CP[k] = multiply(band.stiffness(), band_strain(e, n));
        const Vec3 a = traction(CP[k], n);
        for (int i = 0; i < 3; ++i)
          A_h[3 * i + k] = a[i] / h;
      }
      s0 = traction(sigma0, n);
    }

    /// The crack's normal n (R's first row).
    Vec3 R_n() const { return {R[0], R[1], R[2]}; }

    double h;                ///< band width [mm]
    Mat3 R;                  ///< rows n, s1, s2
    std::array<Voigt, 3> CP; ///< C P by columns [MPa]
    Mat3 A_h{};              ///< A / h [N/mm^3]
    Vec3 s0;                 ///< traction of the uncracked stress on the crack [MPa]
  };

  /// The equilibrium of a crack at one update: the residual
  /// r(w) = R^T t(R w) + A w / h - s0 of its opening w (global frame) and its
  /// Jacobian, from the cohesive law's update, which writes the law's trial
  /// history.
  class CrackEquilibrium : public CrackPlane
  {
  public:
    CrackEquilibrium(const CrackBand& band, std::span<const double> law_old,
                     const CrackState<double>& state, const Voigt& sigma0, double strength,
                     double dt)
        : CrackPlane(band, state, sigma0), law(band.cohesive_law(h, strength)), law_old(law_old),
          law_now(state.law_state()), _dt(dt)
    {
    }

    /// r(w) into `res`; returns its largest component [MPa].
    double residual(const Vec3& w, Vec3& res)
    {
      cohesive = law.update(law_old, rotate(R, w), law_now, _dt);
      const Vec3 t = rotate_back(R, cohesive.t);
      double norm = 0;
      for (int i = 0; i < 3; ++i)
      {
        res[i] = t[i] - s0[i];
        for (int k = 0; k < 3; ++k)
          res[i] += A_h[3 * i + k] * w[k];
        norm = std::max(norm, std::abs(res[i]));
      }
      return norm;
    }

    /// dr/dw at the w of the last residual() [N/mm^3].
    Mat3 jacobian() const
    {
      Mat3 J = A_h;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b)
              J[3 * i + j] += R[3 * a + i] * cohesive.D[3 * a + b] * R[3 * b + j];
      return J;
    }

    /// Newton with backtracking on the largest residual component (the
    /// cohesive law is only piecewise smooth: loading, unloading, closure),
    /// from the secant of the committed damage (exact if the crack unloads
    /// or stays closed). Converged when the traction balance holds to
    /// `tol` [MPa], or when no step along Newton's direction lowers it any
    /// more and it holds to `floor` [MPa] (its round-off); the law's trial
    /// history is then w's.
    bool solve(Vec3& w, double tol, double floor)
    {
      const double g = (1 - laws::DamageHistory<const double>(law_old).damage()) * law.k();
      Mat3 K0 = A_h;
      for (int i = 0; i < 3; ++i)
        K0[4 * i] += g;
      if (!solve3(K0, s0, w))
        return false;
      Vec3 res;
      double norm = residual(w, res);
      // The last residual() was w's (the law's trial state); false where no
      // step along Newton's direction lowered the residual (it stalled).
      bool at_w = true;
      for (int it = 0; it < 60 && norm > tol; ++it)
      {
        Vec3 dw;
        if (!solve3(jacobian(), {-res[0], -res[1], -res[2]}, dw))
          break;
        Vec3 trial{}, trial_res{};
        double trial_norm = INFINITY, alpha = 1;
        for (int cut = 0; cut < 30 && !(trial_norm < norm); ++cut, alpha *= 0.5)
        {
          for (int i = 0; i < 3; ++i)
            trial[i] = w[i] + alpha * dw[i];
          trial_norm = residual(trial, trial_res);
        }
        if (!(trial_norm < norm))
        {
          at_w = false;
          break;
        }
        w = trial;
        res = trial_res;
        norm = trial_norm;
      }
      if (!at_w)
        norm = residual(w, res); // the state and tangent of the final w
      return (norm <= tol || (!at_w && norm <= floor)) && cohesive.status == laws::LawStatus::ok;
    }

    laws::CamanhoDavila law;
    std::span<const double> law_old;
    std::span<double> law_now;
    laws::LawResult cohesive; ///< of the last residual()

  private:
    double _dt;
  };

  /// The columns of J^-1 into `Jinv`; false if J is singular.
  static bool inverse_columns(const Mat3& J, std::array<Vec3, 3>& Jinv)
  {
    Mat3 inverse;
    if (!invert3(J, inverse))
      return false;
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i)
        Jinv[k][i] = inverse[3 * i + k];
    return true;
  }

  /// The point's stress and tangent from its crack's opening w (global
  /// frame) and the columns of J^-1: sigma = C (epsilon - P w / h),
  /// d sigma / d epsilon = C - (1/h) (C P) J^-1 (C P)^T.
  void point_response(const CrackPlane& plane, const Voigt& sigma0, const Vec3& w,
                      const std::array<Vec3, 3>& Jinv, CrackBandResult& r) const
  {
    r.stress = point_stress(plane, sigma0, w);
    r.tangent = tangent_of(plane, Jinv);
  }

  /// sigma = C (epsilon - P w / h) [MPa].
  static Voigt point_stress(const CrackPlane& plane, const Voigt& sigma0, const Vec3& w)
  {
    Voigt stress = sigma0;
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 6; ++i)
        stress[i] -= plane.CP[k][i] * w[k] / plane.h;
    return stress;
  }

  /// d sigma / d epsilon = C - (1/h) (C P) J^-1 (C P)^T, J^-1 by columns.
  Voigt66 tangent_of(const CrackPlane& plane, const std::array<Vec3, 3>& Jinv) const
  {
    // M = J^-1 (C P)^T / h (3 x 6) first: 54 + 108 products instead of the
    // 324 of the four-index sum.
    std::array<Voigt, 3> M{};
    for (int k = 0; k < 3; ++k)
    {
      for (int l = 0; l < 3; ++l)
        for (int j = 0; j < 6; ++j)
          M[k][j] += Jinv[l][k] * plane.CP[l][j];
      for (int j = 0; j < 6; ++j)
        M[k][j] /= plane.h;
    }
    Voigt66 T = _C;
    for (int i = 0; i < 6; ++i)
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 6; ++j)
          T[6 * i + j] -= plane.CP[k][i] * M[k][j];
    return T;
  }

  /// The crack equilibrium's J of a secant spring g with normal stiffness
  /// k_n (g open, the penalty closed): R^T diag(k_n, g, g) R + A / h =
  /// g I + (k_n - g) n n + A / h.
  static Mat3 secant_jacobian(const CrackPlane& plane, double g, double k_n)
  {
    Mat3 J = plane.A_h;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        J[3 * i + j] += (i == j ? g : 0.0) + (k_n - g) * plane.R[i] * plane.R[j];
    return J;
  }

  /// The crack's equilibrium and the point's stress, and its tangent if
  /// `with_tangent`.
  void solve_crack(std::span<const double> law_old, const CrackState<double>& state,
                   const Voigt& sigma0, double strength, double dt, bool with_tangent,
                   CrackBandResult& r) const
  {
    CrackEquilibrium eq(*this, law_old, state, sigma0, strength, dt);
    // Converged when the traction balance holds to 1e-10 f_t, or to the
    // round-off of the trial traction s0 (which grows with the opening).
    // Where s0 is large that round-off is not always reached: a fully
    // damaged crack dragged along by the push (shear strains of 0.2, |s0|
    // some 3e4 MPa) balances to 1.03e-14 |s0| and no closer, just above
    // 1e-14 |s0| (tests/unit/bulk/test_crack_band.cpp,
    // CrackBand.BalancesAtItsRoundOffWhereTheTrialTractionIsLarge). Where
    // Newton can lower it no more, 1e-12 |s0| is accepted: still far below
    // anything the structure's Newton (1e-6 of the reactions) can see.
    const double s0_size = std::abs(eq.s0[0]) + std::abs(eq.s0[1]) + std::abs(eq.s0[2]);
    const double tol = std::max(1e-10 * strength * _env.f_t, 1e-14 * s0_size);
    const double floor = std::max(tol, 1e-12 * s0_size);
    Vec3 w{};
    std::array<Vec3, 3> Jinv; // columns of J^-1 at w
    // A singular J at w fails the update with or without the tangent.
    const bool ok = eq.solve(w, tol, floor) &&
                    (with_tangent ? inverse_columns(eq.jacobian(), Jinv) : regular3(eq.jacobian()));
    if (!ok)
    {
      r.status = CrackBandResult::Status::not_converged;
      return;
    }
    if (with_tangent)
      point_response(eq, sigma0, w, Jinv, r);
    else
      r.stress = point_stress(eq, sigma0, w);
    r.opening = rotate(eq.R, w);
    const laws::DamageHistory<double> now(eq.law_now);
    r.damage = now.damage();
    // Without viscosity the energy dissipated is a function of the history
    // alone, exact whatever the step; the law's own estimate is second order
    // in the step, and a crack's first step overshoots its w0 = f_t / k_p (a
    // fraction of a micrometre) many times.
    r.dissipation =
        (_eta > 0 ? eq.cohesive.dissipation
                  : dissipated(eq.law, now.kappa()) -
                        dissipated(eq.law, laws::DamageHistory<const double>(law_old).kappa())) /
        eq.h;
  }

  /// The energy per unit crack area a crack has dissipated when its history
  /// is kappa [N/mm]: the work along the envelope less the energy its
  /// secant unloading would give back, 1/2 f_t w0 + int sigma - 1/2 sigma(kappa) kappa.
  double dissipated(const laws::CamanhoDavila& law, double kappa) const
  {
    if (kappa <= law.w0())
      return 0;
    const laws::Envelope e = law.envelope();
    return 0.5 * e.f_t * law.w0() + e.work(kappa, law.w0()) -
           0.5 * e.evaluate(kappa, law.w0()).sigma * kappa;
  }

  static Vec3 rotate(const Mat3& R, const Vec3& v)
  {
    return {R[0] * v[0] + R[1] * v[1] + R[2] * v[2], R[3] * v[0] + R[4] * v[1] + R[5] * v[2],
            R[6] * v[0] + R[7] * v[1] + R[8] * v[2]};
  }
  static Vec3 rotate_back(const Mat3& R, const Vec3& v)
  {
    return {R[0] * v[0] + R[3] * v[1] + R[6] * v[2], R[1] * v[0] + R[4] * v[1] + R[7] * v[2],
            R[2] * v[0] + R[5] * v[1] + R[8] * v[2]};
  }

  Voigt66 _C;
  std::array<double, 2> _lame; ///< lambda, mu [MPa]
  laws::Envelope _env;
  double _eta;
  double _penalty_factor;
};
} // namespace pushout::bulk

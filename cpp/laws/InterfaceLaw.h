// The contract every interface (joint) law fulfils.
//
// A law works in the local frame of a quadrature point, [n, s1, s2]: n the
// unit normal from steel to concrete, s1, s2 an orthonormal tangent pair.
// Its one update maps (committed state, jump) to (traction, consistent
// tangent, trial state, status), purely: no side effects, no allocation, no
// exceptions: a failure is a status the driver acts on (cutting the step).
// Traction and tangent come from the same call.
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

namespace pushout::laws
{
/// Components in the local frame: [normal, shear 1, shear 2].
using Vec3 = std::array<double, 3>;
/// Row-major 3x3 in the local frame: D[3*i + j] = d t_i / d w_j.
using Mat3 = std::array<double, 9>;

enum class LawStatus
{
  ok,
  failed ///< non-finite input or result: the driver cuts the step
};

/// What the load stage gives every law at a step besides the jump: values of
/// the step, not scene constants. Laws read what they need and ignore the rest.
struct StepInputs
{
  double dt = 0;               ///< pseudo-time increment (viscous laws; 0: none)
  double oxide_gap = 0;        ///< free normal opening g0 of the oxide layer [mm]
  double oxide_compliance = 0; ///< normal compliance of the oxide layer [mm^3/N]
};

/// Result of one law update at one quadrature point.
struct LawResult
{
  Vec3 t{}; ///< traction [MPa]
  Mat3 D{}; ///< consistent tangent d t / d w [N/mm^3]
  /// Energy dissipated per unit area from the committed state to the trial
  /// one [N/mm = mJ/mm^2]: damage (1/2 k |w_open|^2 dD) and frictional slip
  /// (t_s . dw^p). Summed to full separation it is the law's fracture
  /// energy G_F (tests/unit/laws/test_dissipation.cpp).
  double dissipation = 0;
  LawStatus status = LawStatus::ok;
};

/// Type-erased law, so layers of different laws can sit in one list.
/// Concrete laws are value types (see Friction.h) wrapped by LawAdapter.
class InterfaceLaw
{
public:
  virtual ~InterfaceLaw() = default;

  /// Number of history variables per quadrature point.
  virtual int state_size() const = 0;

  /// The update: `state_old` is the committed state, `w` the jump [mm],
  /// `in` the inputs of the step (pseudo-time increment for viscous laws,
  /// the oxide layer's opening and compliance during corrosion); writes the
  /// trial state into `state_new` (same size).
  virtual LawResult update(std::span<const double> state_old, const Vec3& w,
                           std::span<double> state_new, const StepInputs& in) const = 0;

  /// Inelastic (plastic) slip in the tangent plane [mm], for output.
  virtual std::array<double, 2> slip(std::span<const double> state) const = 0;

  /// Scalar damage in [0, 1], for output (0 for laws without damage).
  virtual double damage(std::span<const double> state) const = 0;

  /// The energy per unit area a softening law releases from the unloaded
  /// state to full softening [N/mm] (its G_F without the residual's
  /// plateau); 0 for laws that do not soften (elastic, friction). Sets the
  /// scale of dissipation-controlled steps (stepping/StepLoop.cpp).
  virtual double fracture_energy() const = 0;

  /// Whether the law softens (releases a fracture energy): its joints then
  /// take part in dissipation control.
  bool softens() const { return fracture_energy() > 0; }
};

/// Wraps a law value type `L` (with `state_size`, `update`, `slip`,
/// `damage`, and `fracture_energy` if it softens) as an InterfaceLaw.
template <typename L> class LawAdapter final : public InterfaceLaw
{
public:
  explicit LawAdapter(L law) : _law(std::move(law)) {}
  int state_size() const override { return L::state_size; }
  LawResult update(std::span<const double> state_old, const Vec3& w, std::span<double> state_new,
                   const StepInputs& in) const override
  {
    return _law.update(state_old, w, state_new, in);
  }
  std::array<double, 2> slip(std::span<const double> state) const override
  {
    return _law.slip(state);
  }
  double damage(std::span<const double> state) const override { return _law.damage(state); }
  double fracture_energy() const override
  {
    if constexpr (requires(const L& l) { l.fracture_energy(); })
      return _law.fracture_energy();
    else
      return 0.0;
  }

private:
  L _law;
};
} // namespace pushout::laws

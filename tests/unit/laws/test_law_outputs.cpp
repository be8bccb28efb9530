// Every registered law, driven through the type-erased InterfaceLaw as the
// interface drives it (update from the committed state, outputs read from
// the trial state, then commit), along one path of jumps: shear growing
// along a fixed direction e under growing compression, shear unloading, then
// opening. At every step the per-point outputs -- tractions, slip_s1,
// slip_s2 and damage -- are checked against the law's closed forms, computed
// here independently of the law's code. A law registered without closed
// forms here fails the test.
#include "laws/LawRegistry.h"
#include <cmath>
#include <functional>
#include <gtest/gtest.h>
#include <map>

using namespace pushout::laws;

namespace
{
/// What a point must report after a step.
struct Expected
{
  Vec3 t;                     ///< traction [MPa]
  std::array<double, 2> slip; ///< plastic slip [mm]
  double damage;
};

/// The analytic history the closed forms carry along the path.
struct History
{
  double kappa = 0;  ///< largest equivalent jump [mm]
  double damage = 0; ///< acting damage D_v
  double slip_e = 0; ///< plastic slip along e [mm] (the path's shear is along e)
};

const std::array<double, 2> e = {0.6, 0.8}; // the shear direction in (s1, s2)
constexpr double dt = 1e-3;                 // pseudo-time per step [mm]
// Every law gets the same oxide inputs; only oxide_friction reads them.
constexpr double oxide_gap = 5e-4;        // free opening g0 [mm]
constexpr double oxide_compliance = 2e-4; // [mm^3/N]: with k 1000 in series, 833.3 N/mm^3

/// The path: 20 steps of growing shear (to 0.02 mm) and compression (to
/// -0.002 mm), 8 of unloading shear (to 0.012 mm), 4 of opening (to 0.001 mm).
std::vector<std::pair<double, double>> path() // (w_n, |w_s| along e)
{
  std::vector<std::pair<double, double>> p;
  for (int i = 1; i <= 20; ++i)
    p.push_back({-0.002 * i / 20, 0.02 * i / 20});
  for (int i = 1; i <= 8; ++i)
    p.push_back({-0.002, 0.02 - 0.001 * i});
  for (int i = 1; i <= 4; ++i)
    p.push_back({-0.002 + 0.00075 * i, 0.012});
  return p;
}

/// Coulomb friction along a line (paper §3, eqs. 4-6): the 1D return map
/// clamps the slip to within mu p / k of the jump, p the contact pressure.
double friction_slip(double slip_old, double ws, double p, double k, double mu)
{
  const double reach = mu * p / k;
  return std::clamp(slip_old, ws - reach, ws + reach);
}

/// Damage of the Camanho-Davila laws: D(kappa) = 1 - sigma(kappa) / (k kappa)
/// beyond w0 = f_t / k (paper §2.3, Fig. 5).
double damage_of(double kappa, double k, double f_t, const std::function<double(double)>& sigma)
{
  const double w0 = f_t / k;
  return kappa <= w0 ? 0.0 : 1 - sigma(kappa - w0) / (k * kappa);
}

/// The acting damage after a step: D_v + theta (D - D_v), theta = (dt/eta) /
/// (1 + dt/eta), 1 without viscosity.
double acting(double damage_old, double damage_now, double eta)
{
  const double theta = eta > 0 ? (dt / eta) / (1 + dt / eta) : 1.0;
  return damage_old + theta * (damage_now - damage_old);
}

using Analytic = std::function<Expected(double wn, double ws, History& h)>;
struct Case
{
  std::string label;
  Params set; ///< parameters beyond the declared defaults
  Analytic expect;
};

/// Softening laws: damage from the envelope, secant in opening and shear,
/// always elastic in compression, no slip.
Analytic softening(double k, double f_t, double eta, std::function<double(double)> sigma)
{
  return [=](double wn, double ws, History& h)
  {
    h.kappa = std::max(h.kappa, std::hypot(std::max(wn, 0.0), ws));
    h.damage = acting(h.damage, damage_of(h.kappa, k, f_t, sigma), eta);
    const double g = (1 - h.damage) * k;
    return Expected{{(wn > 0 ? g : k) * wn, g * ws * e[0], g * ws * e[1]}, {0, 0}, h.damage};
  };
}

/// cohesive_friction (Alfano & Sacco): t = (1 - D) k w + D t_d, the damaged
/// part in contact with Coulomb friction; its slip is the friction's.
Analytic cohesive_friction(double k, double mu, double f_t, double eta,
                           std::function<double(double)> sigma)
{
  return [=](double wn, double ws, History& h)
  {
    h.kappa = std::max(h.kappa, std::hypot(std::max(wn, 0.0), ws));
    h.damage = acting(h.damage, damage_of(h.kappa, k, f_t, sigma), eta);
    h.slip_e = friction_slip(h.slip_e, ws, std::max(-k * wn, 0.0), k, mu);
    const double D = h.damage;
    const double td_s = k * (ws - h.slip_e);
    return Expected{{(1 - D) * k * wn + D * k * std::min(wn, 0.0),
                     ((1 - D) * k * ws + D * td_s) * e[0], ((1 - D) * k * ws + D * td_s) * e[1]},
                    {h.slip_e * e[0], h.slip_e * e[1]},
                    D};
  };
}

std::function<double(double)> linear(double f_t, double w_c2)
{
  return [=](double x) { return std::max(f_t * (1 - x / w_c2), 0.0); };
}
std::function<double(double)> exponential(double f_t, double f_fr, double c)
{
  return [=](double x) { return f_fr + (f_t - f_fr) * std::exp(-c * x); };
}

/// The closed forms of every law, by registered name.
std::map<std::string, std::vector<Case>> cases()
{
  std::map<std::string, std::vector<Case>> c;
  c["elastic"] = {
      {"k_n 500, k_s 200", {{"k_n", 500.0}, {"k_s", 200.0}}, [](double wn, double ws, History&) {
         return Expected{{500 * wn, 200 * ws * e[0], 200 * ws * e[1]}, {0, 0}, 0};
       }}};
  c["friction"] = {
      {"k 1000, mu 0.4",
       {},
       [](double wn, double ws, History& h)
       {
         h.slip_e = friction_slip(h.slip_e, ws, std::max(-1000 * wn, 0.0), 1000, 0.4);
         const double ts = 1000 * (ws - h.slip_e);
         return Expected{{1000 * wn, ts * e[0], ts * e[1]}, {h.slip_e * e[0], h.slip_e * e[1]}, 0};
       }}};
  // The oxide's pressure p = (g0 - w_n) / (1/k + c_ox) in contact; opening
  // beyond g0 pulls nothing.
  c["oxide_friction"] = {
      {"k 1000, mu 0.4, g0 5e-4, c_ox 2e-4",
       {},
       [](double wn, double ws, History& h)
       {
         const double k = 1000, k_contact = 1 / (1 / k + oxide_compliance);
         const double tn = wn < oxide_gap ? k_contact * (wn - oxide_gap) : 0.0;
         h.slip_e = friction_slip(h.slip_e, ws, std::max(-tn, 0.0), k, 0.4);
         const double ts = k * (ws - h.slip_e);
         return Expected{{tn, ts * e[0], ts * e[1]}, {h.slip_e * e[0], h.slip_e * e[1]}, 0};
       }}};
  for (double eta : {0.0, 5e-3})
  {
    const std::string v = eta > 0 ? ", eta 5e-3" : "";
    c["linear_softening"].push_back(
        {"k 100, f_t 1, w_c2 0.3" + v, {{"eta", eta}}, softening(100, 1, eta, linear(1, 0.3))});
    c["linear_softening_friction"].push_back(
        {"k 100, f_t 1, w_c2 0.015, f_fr 0.5" + v,
         {{"w_c2", 0.015}, {"f_fr", 0.5}, {"eta", eta}},
         softening(100, 1, eta, [](double x) { return std::max(1 - x / 0.015, 0.5); })});
    c["exponential_softening"].push_back({"k 1000, f_t 3, c 25, f_fr 0.4" + v,
                                          {{"f_fr", 0.4}, {"eta", eta}},
                                          softening(1000, 3, eta, exponential(3, 0.4, 25))});
    c["cohesive_friction"].push_back({"linear, w_c2 0.05" + v,
                                      {{"w_c2", 0.05}, {"eta", eta}},
                                      cohesive_friction(1000, 0.4, 3, eta, linear(3, 0.05))});
    c["cohesive_friction"].push_back({"exponential, c 25" + v,
                                      {{"c", 25.0}, {"eta", eta}},
                                      cohesive_friction(1000, 0.4, 3, eta, exponential(3, 0, 25))});
  }
  return c;
}

/// The declared defaults (and defaults taken from other parameters), then `set`.
Params parameters(const LawInfo& law, const Params& set)
{
  Params p;
  for (const ParamDef& d : law.params)
    if (d.default_value)
      p[d.name] = *d.default_value;
  for (const auto& [name, value] : set)
    p[name] = value;
  for (const ParamDef& d : law.params)
    if (!d.default_from.empty() && !p.count(d.name))
      p[d.name] = p.at(d.default_from);
  return p;
}
} // namespace

TEST(LawOutputs, EveryRegisteredLawMatchesItsClosedForms)
{
  const auto all = cases();
  for (const LawInfo& info : registered_laws())
  {
    ASSERT_TRUE(all.count(info.name))
        << "law '" << info.name
        << "' is registered but has no closed forms in test_law_outputs.cpp";
    for (const Case& c : all.at(info.name))
    {
      SCOPED_TRACE(info.name + " (" + c.label + ")");
      const auto law = info.make(parameters(info, c.set), "interface.0.");
      std::vector<double> committed(law->state_size(), 0.0), trial(committed.size());
      History h;
      int step = 0;
      for (const auto& [wn, ws] : path())
      {
        ++step;
        const Vec3 w = {wn, ws * e[0], ws * e[1]};
        const LawResult r = law->update(committed, w, trial, {dt, oxide_gap, oxide_compliance});
        const Expected x = c.expect(wn, ws, h);
        ASSERT_EQ(r.status, LawStatus::ok) << "step " << step;
        const double tol = 1e-9 * (1 + std::abs(x.t[0]) + std::abs(x.t[1]) + std::abs(x.t[2]));
        for (int i = 0; i < 3; ++i)
          EXPECT_NEAR(r.t[i], x.t[i], tol) << "traction " << i << ", step " << step;
        const auto slip = law->slip(trial);
        EXPECT_NEAR(slip[0], x.slip[0], 1e-12) << "slip_s1, step " << step;
        EXPECT_NEAR(slip[1], x.slip[1], 1e-12) << "slip_s2, step " << step;
        EXPECT_NEAR(law->damage(trial), x.damage, 1e-12) << "damage, step " << step;
        committed = trial;
      }
      // The path reaches what it is meant to: damage, slip, opening.
      const bool frictional = info.name.find("friction") != std::string::npos;
      if (info.name != "elastic" && info.name != "friction" && info.name != "oxide_friction")
      {
        EXPECT_GT(h.damage, 0.1) << "the path damages the law";
      }
      if (frictional && info.name != "linear_softening_friction")
      {
        EXPECT_GT(std::abs(h.slip_e), 1e-3) << "the path slides the law";
      }
    }
  }
}

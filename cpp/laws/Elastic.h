// Elastic joint, paper eq. (2):  t = k_n (w.n) n + k_s (w - (w.n) n).
//
// Parameters: k [N/mm^3] (default of both), k_n, k_s [N/mm^3].
// No history. Reference: Sanz, Planas, Sancho, §2.3, eq. (2).
#pragma once

#include "InterfaceLaw.h"
#include "LawRegistry.h"

namespace pushout::laws
{
class Elastic
{
public:
  static constexpr const char* name = "elastic";
  static constexpr const char* doc = "linear elastic joint, paper eq. 2 (k_n normal, k_s shear)";
  static constexpr int state_size = 0;

  static std::vector<ParamDef> params()
  {
    return {penalty_param("k", 1000.0, "penalty stiffness (default of k_n, k_s)"),
            penalty_param("k_n", std::nullopt, "normal stiffness", "k"),
            penalty_param("k_s", std::nullopt, "shear stiffness", "k")};
  }

  Elastic(double k_n, double k_s) : _kn(k_n), _ks(k_s) {}
  Elastic(const Params& p, const std::string&) : Elastic(p.at("k_n"), p.at("k_s")) {}

  LawResult update(std::span<const double>, const Vec3& w, std::span<double>,
                   const StepInputs& /*in*/ = {}) const
  {
    LawResult r;
    r.t = {_kn * w[0], _ks * w[1], _ks * w[2]};
    r.D = {_kn, 0, 0, 0, _ks, 0, 0, 0, _ks};
    return r;
  }
  std::array<double, 2> slip(std::span<const double>) const { return {0, 0}; }
  double damage(std::span<const double>) const { return 0; }

private:
  double _kn, _ks;
};
} // namespace pushout::laws

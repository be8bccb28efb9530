// The oxide layer of a corroding steel surface, as the interface sees it
// (Molina, Alonso & Andrade 1993; the Sanz-Planas-Sancho corrosion papers,
// 2013 Eng. Fract. Mech. 114:26 and 2015 Int. J. Solids Struct. 62:256).
//
// A depth x [mm] of steel turns into oxide that occupies beta times its
// volume, so the oxide layer is beta x thick and the interface gets a free
// normal opening (what the oxide would open with nothing resisting)
//   g0 = max((beta - 1) x - porous_zone, 0)      [mm]
// (the porous zone of the concrete absorbs the first of the expansion). The
// layer is confined and nearly fluid (Molina et al. model it as water, bulk
// modulus about 2 GPa): stiff in compression, shear-free. A laterally
// confined layer of thickness beta x and bulk modulus B_ox has the normal
// compliance
//   c_ox = beta x / B_ox                          [mm^3/N]
// (a derivation, not a quotation), in series with the joint's penalty.
// These two numbers are the oxide inputs of a step (StepInputs) that the law
// oxide_friction reads.
#pragma once

#include <algorithm>

namespace pushout::laws
{
/// Material of the oxide layer (scene section [corrosion]).
struct OxideLayer
{
  double beta = 2.0;        ///< oxide volume / steel volume [-] (>= 1)
  double porous_zone = 0.0; ///< free expansion absorbed by the pores [mm]
  double bulk = 2000.0;     ///< oxide bulk modulus B_ox [MPa]
};

/// The oxide inputs of a step at corrosion depth x [mm].
struct OxideInputs
{
  double gap = 0;        ///< free normal opening g0 [mm]
  double compliance = 0; ///< normal compliance beta x / B_ox [mm^3/N]
};

inline OxideInputs oxide_inputs(const OxideLayer& oxide, double x)
{
  return {std::max((oxide.beta - 1) * x - oxide.porous_zone, 0.0), oxide.beta * x / oxide.bulk};
}
} // namespace pushout::laws

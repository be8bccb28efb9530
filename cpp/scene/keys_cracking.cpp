// The scene keys of the [cracking] section: cracks anywhere in the concrete
// (docs/cracking.md), declared as those of cpp/scene/keys.cpp.
#include "KeyDef.h"

namespace pushout
{
namespace
{
/// The crack and its law: whether the concrete cracks, the softening law.
std::vector<KeyDef> law_keys()
{
  using K = KeyType;
  using A = Applies;
  constexpr double inf = std::numeric_limits<double>::infinity();
  return {
      {"cracking.model",
       K::string,
       std::string("none"),
       "",
       "none: the concrete stays linear elastic; embedded: a cohesive crack may open at any "
       "quadrature point of the concrete within cracking.radius (a crack band: docs/cracking.md)",
       -inf,
       inf,
       false,
       {"none", "embedded"},
       A::pushout},
      {"cracking.law",
       K::string,
       std::string("exponential_softening"),
       "",
       "mode-I softening of the concrete's cracks (the envelope of that interface law): "
       "G_F = f_t / c (exponential) or f_t w_c2 / 2 (linear)",
       -inf,
       inf,
       false,
       {"exponential_softening", "linear_softening"},
       A::pushout},
      {"cracking.f_t",
       K::number,
       3.0,
       "MPa",
       "tensile strength of the concrete: a crack opens where the largest principal stress "
       "reaches it (its mean, with a random field)",
       0,
       inf,
       true,
       {},
       A::pushout},
      {"cracking.c",
       K::number,
       30.0,
       "1/mm",
       "exponential_softening: decay of the crack's traction, sigma = f_t exp(-c w)",
       0,
       inf,
       true,
       {},
       A::pushout},
      {"cracking.w_c2",
       K::number,
       0.1,
       "mm",
       "linear_softening: the opening at which the crack's traction reaches zero",
       0,
       inf,
       true,
       {},
       A::pushout},
      {"cracking.band_width",
       K::string,
       std::string("projected"),
       "",
       "the width h of the band a crack's opening is smeared over (G_F / h per unit volume): "
       "projected: the cell's extent along the crack's normal; row: the width of the "
       "thinnest row of cells the crack can run along (at most the extent), exact for a crack "
       "running along one row of parallelepiped cells whose faces it crosses obliquely (sheared "
       "cells), where the extent is too wide and the crack dissipates too little "
       "(docs/cracking.md, \"The band's width\")",
       -inf,
       inf,
       false,
       {"projected", "row"},
       A::pushout},
  };
}

/// How the cracks are integrated over a step: implicitly or by IMPL-EX,
/// and the damage viscosity.
std::vector<KeyDef> integration_keys()
{
  using K = KeyType;
  using A = Applies;
  constexpr double inf = std::numeric_limits<double>::infinity();
  return {
      {"cracking.integration",
       K::string,
       std::string("auto"),
       "",
       "implicit: each step solves the cracks' own update (Newton through every onset and "
       "kink); implex: in a step each point holds a crack state predicted from the last steps "
       "(implex_predictor; Oliver, Huespe & Cante 2008), so a step's bulk is linear "
       "but for closure: faster and never stuck, with an error of the order of the step held "
       "to implex_tolerance (any loading.control; no viscosity); auto: implex without a "
       "viscosity, implicit with one (summary.json cracking_integration says which; "
       "docs/cracking.md, \"IMPL-EX\")",
       -inf,
       inf,
       false,
       {"auto", "implicit", "implex"},
       A::pushout},
      {"cracking.implex_tolerance",
       K::number,
       0.0025,
       "-",
       "implex: a step is cut (and retried in halves) when its stress differs from the crack "
       "band's own at its strain by more than this, in the energy norm over the cracking "
       "concrete; at 0.0025 the widest surface crack and the peaks within a few per cent of a "
       "converged integration's, but where neighbouring cracks compete the pattern may differ (the "
       "corroded demo's residual bond -2.3 to +9.7 % off over five seeds: docs/cracking.md, "
       "\"How far to trust a corroded run\"); 0.01 takes half the time but may pick another "
       "crack where the concrete localises or miss a crack's snap (docs/cracking.md, "
       "\"IMPL-EX\", \"Accuracy and the tolerance\"); "
       "also the implicit cracks' IMPL-EX rescue's where its step is not the smallest",
       0,
       inf,
       true,
       {},
       A::pushout},
      {"cracking.implicit_tolerance",
       K::number,
       0.0,
       "-",
       "implicit: a step is cut (and retried in halves) when its stress differs from what "
       "IMPL-EX's prediction from the last steps (implex_predictor) answers at its strain by "
       "more than this, in implex_tolerance's norm: an estimate of the step's own error, as "
       "the cracks are path dependent; 0: the scene's steps, cut only where Newton fails, "
       "their error read all the same (summary.json implicit_error_max; a note where it "
       "exceeds implex_tolerance); not with a viscosity, which the prediction does not take "
       "(docs/cracking.md, \"The implicit cracks' step error\")",
       0,
       inf,
       false,
       {},
       A::pushout},
      {"cracking.implex_rescue",
       K::boolean,
       true,
       "",
       "implicit: a step that Newton fails at every cut, down to the smallest (2^-10 of a step "
       "or less: loading.max_cuts >= 10), is taken as one IMPL-EX step, whose bulk is linear "
       "but for closure, and the implicit steps go on from it (summary.json implex_rescues); "
       "false: the run stops there. Not with a viscosity "
       "(docs/cracking.md, \"The IMPL-EX rescue\")",
       -inf,
       inf,
       false,
       {},
       A::pushout},
      {"cracking.implex_predictor",
       K::string,
       std::string("strain"),
       "",
       "implex: what a step's cracks hold: strain: the crack band's own update at the strain "
       "extrapolated from the last step (a point may crack, a crack may stop growing); "
       "history: each crack's damage extrapolated from the last steps (Oliver, Huespe & Cante "
       "2008), no point cracks in the step; both explicit. strain has about half the error "
       "at the same steps: a quarter fewer steps and time on the cracking demo, as close to "
       "the implicit cracks (docs/cracking.md, \"The strain predictor\"); also the prediction "
       "the implicit cracks' step error compares with (implicit_tolerance), and their "
       "IMPL-EX rescue's (implex_rescue)",
       -inf,
       inf,
       false,
       {"history", "strain"},
       A::pushout},
      {"cracking.viscosity",
       K::number,
       0.0,
       "mm",
       "damage viscosity of the concrete's cracks, as the damage laws' eta: pseudo-time "
       "constant in mm of push; a corrosion step lasts the push's first step's (push_"
       "displacement / loading.steps, or the first growing step with step_growth; with "
       "push_path, its first segment's length / steps_per_segment), so the corrosion "
       "stage's cracks depend on those too; 0: rate independent. It delays cracking far more "
       "than its size suggests (the crack's penalty keeps a lagging damage's crack shut): 0.1 "
       "of a step's pseudo-time left the corroded demo's cover uncracked at x = 20 um "
       "(docs/cracking.md)",
       0,
       inf,
       false,
       {},
       A::pushout},
  };
}

/// Where it may crack, and the random field of its tensile strength.
std::vector<KeyDef> field_keys()
{
  using K = KeyType;
  using A = Applies;
  constexpr double inf = std::numeric_limits<double>::infinity();
  return {
      {"cracking.radius",
       K::number,
       0.0,
       "mm",
       "the concrete may crack within this distance from the tube axis (element centres); 0: "
       "all of it. Outside, it stays linear elastic; a run notes cracks that reach the edge "
       "(summary.json cracking_edge)",
       0,
       inf,
       false,
       {},
       A::pushout},
      {"cracking.strength_cov",
       K::number,
       0.0,
       "-",
       "coefficient of variation of the tensile strength over the concrete (a lognormal, "
       "spatially correlated field); 0: uniform",
       0,
       1,
       false,
       {},
       A::pushout},
      {"cracking.correlation_length",
       K::number,
       5.0,
       "mm",
       "correlation length l of the strength field: its logarithm's correlation is "
       "exp(-(r/l)^2) at distance r; the strength's own is below that by at most "
       "ln(1 + strength_cov^2) / 2 of it (2 % at strength_cov 0.2); at least 0.001 (a "
       "micrometre; a note says where the mesh does not resolve it)",
       0.001,
       inf,
       false,
       {},
       A::pushout},
      {"cracking.seed",
       K::integer,
       std::int64_t(1),
       "",
       "seed of the strength field: the same seed gives the same field on any number of "
       "processes",
       0,
       9007199254740992.0,
       false,
       {},
       A::pushout},
  };
}

/// How the cracks are read at the slice's outer faces.
std::vector<KeyDef> reading_keys()
{
  using K = KeyType;
  using A = Applies;
  constexpr double inf = std::numeric_limits<double>::infinity();
  return {
      {"cracking.visible_width",
       K::number,
       0.05,
       "mm",
       "a crack at the slice's outer faces counts (corrosion.csv cracks_at_surface: the "
       "planes' mouths too; the concrete's entries of summary.json cracks) from this width, "
       "as a crack-width gauge reads it there; the "
       "gauge resolves a tenth of it, at most 5 um (corrosion.csv crack_width_mm, the widest "
       "crack, does not depend on it above 0.05 mm)",
       0,
       inf,
       true,
       {},
       A::pushout,
       true},
  };
}

} // namespace

std::vector<KeyDef> cracking_keys()
{
  // Cracks anywhere in the concrete (docs/cracking.md): a crack band at
  // each quadrature point of the concrete near the tube (bulk/CrackBand.h),
  // with a random tensile strength (bulk/StrengthField.h). In progress:
  // off unless cracking.model = "embedded".
  std::vector<KeyDef> keys = law_keys();
  for (auto part : {integration_keys, field_keys, reading_keys})
  {
    std::vector<KeyDef> more = part();
    keys.insert(keys.end(), more.begin(), more.end());
  }
  return keys;
}
} // namespace pushout

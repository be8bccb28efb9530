// The typed parts of a scene: what the modules take, each its own part.
//
// Scene::parse validates the user's TOML once against the key table
// (keys.cpp: type, default, unit, range, doc of every key) and fills these
// plain structs; nothing outside scene/ reads a key by its name. Each
// member is the key of the same name in the same section (docs/
// scene-reference.md); a key of another model type (model.type) holds its
// declared default. The defaults are the key table's, never written here.
#pragma once

#include "../laws/LawRegistry.h"
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace pushout
{
/// [model]
struct ModelPart
{
  enum class Type
  {
    pushout,     ///< the slice test (paper §2)
    single_joint ///< one 1x1 mm joint (a law check, paper Fig. 6)
  };
  /// Whether a symmetric push-out runs on a half or a quarter (mesh/symmetry.h).
  enum class Symmetry
  {
    automatic, ///< "auto"
    symmetric,
    full
  };
  Type type{};
  Symmetry symmetry{};
  bool pushout() const { return type == Type::pushout; }
  /// model.type as written in the scene.
  const char* name() const { return pushout() ? "pushout" : "single_joint"; }
};

/// [geometry]: the slice and the tube (paper §2.1, Fig. 1).
struct Geometry
{
  bool circle{};                       ///< outer_shape: circle (else square)
  double width{};                      ///< square side or circle diameter [mm]
  double thickness{};                  ///< slice thickness L (eq. 1) [mm]
  double tube_outer_diameter{};        ///< D (eq. 1) [mm]
  double tube_inner_diameter{};        ///< [mm]
  std::array<double, 2> tube_center{}; ///< tube axis (x, y) [mm]
  double support_inner_diameter{};     ///< the slice rests outside this circle [mm]
  double area{};                       ///< single joint: the joint's area [mm^2]
  double tube_radius() const { return tube_outer_diameter / 2; } ///< R [mm]
  /// From the tube axis to the nearest point of the slice's outer boundary
  /// [mm] (the cover is this less R).
  double nearest_face_distance() const
  {
    const auto [x, y] = tube_center;
    return circle ? width / 2 : std::min({x, y, width - x, width - y});
  }
  bool operator==(const Geometry&) const = default;
};

/// [mesh] (paper §4.1).
struct MeshPart
{
  std::int64_t elements_per_quarter{};       ///< around a quarter of the interface
  std::int64_t elements_through_thickness{}; ///< layers through L
  std::int64_t steel_layers{};               ///< layers across the tube wall
  double outer_size_ratio{};                 ///< outer / interface element size
  bool radial_lines{};     ///< graded_lines: radial (else blocks; meshes/slice.geo)
  bool refine_whole{};     ///< graded_refinement: whole (else near_tube; mesh/size.h)
  int degree{};            ///< bulk displacement: 1 or 2
  bool nodal_quadrature{}; ///< interface_quadrature: nodal (else 2x2 Gauss)
  bool operator==(const MeshPart&) const = default;
};

/// [concrete] and [steel] (paper Table 1).
struct Material
{
  double E{};     ///< Young's modulus [MPa]
  double nu{};    ///< Poisson's ratio [-]
  double alpha{}; ///< thermal expansion [1/degC]
};

/// [loading] (paper §4.2).
struct Loading
{
  /// How the load steps are controlled (docs/numerics.md).
  enum class Control
  {
    displacement,
    arc_length,
    dissipation,
    automatic ///< "auto": today the same as dissipation
  };
  double temperature_change{};   ///< the thermal step [degC]
  double push_displacement{};    ///< final push delta [mm]
  double step_growth{};          ///< ratio of each push step to the previous one
  bool tube_top_free{};          ///< thermal_tube_top: free (else held, §4.2)
  std::int64_t steps{};          ///< push steps
  std::vector<double> push_path; ///< push delta path [mm] (empty: monotonic)
  bool unload_to_zero_force{};   ///< unload_to: zero_force (else path)
  Control control{};
  std::int64_t dissipation_steps{}; ///< steps releasing the fracture energy
  std::int64_t max_cuts{};          ///< halvings of a failed step
  double normal_force_per_node{};   ///< single joint [N]
  std::vector<double> shear_path;   ///< single joint: shear path [mm]
  std::int64_t steps_per_segment{}; ///< steps on each path segment

  /// The length of the push's first step [mm]: the pseudo-time it lasts,
  /// and each corrosion step with it (the first of growing steps; a
  /// push_path's first segment over its steps).
  double first_push_step() const
  {
    if (!push_path.empty())
      return std::abs(push_path[1] - push_path[0]) / double(steps_per_segment);
    const double g = step_growth, n = double(steps);
    return std::abs(push_displacement) * (g == 1 ? 1 / n : (g - 1) / (std::pow(g, n) - 1));
  }
};

/// [corrosion] (docs/corrosion.md).
struct CorrosionPart
{
  double penetration{}; ///< corrosion depth x [mm] (0: no corrosion stage)
  std::int64_t steps{}; ///< steps of x
  double beta{};        ///< oxide / steel volume ratio [-]
  double porous_zone{}; ///< expansion the pores absorb [mm]
  double oxide_bulk{};  ///< oxide bulk modulus B_ox [MPa]
};

/// [cracking]: cracks anywhere in the concrete (docs/cracking.md).
struct CrackingPart
{
  bool embedded{};             ///< model = "embedded" (else the concrete is linear)
  bool linear_softening{};     ///< law: linear_softening (else exponential_softening)
  double f_t{};                ///< tensile strength [MPa]
  double c{};                  ///< exponential decay [1/mm]
  double w_c2{};               ///< linear softening: the opening at zero traction [mm]
  bool row_band{};             ///< band_width: row (else projected; model/CellWidth.h)
  double radius{};             ///< cracking region around the tube axis [mm]; 0: all concrete
  double strength_cov{};       ///< coefficient of variation of f_t [-]
  double correlation_length{}; ///< of the strength field [mm]
  std::int64_t seed{};
  double visible_width{};    ///< a surface crack counts from this gauge reading [mm]
  double viscosity{};        ///< damage viscosity eta [mm of push]; 0: none
  bool implex{};             ///< integration: implex, or auto that chose it (else implicit)
  double implex_tolerance{}; ///< IMPL-EX: the largest error of a step [-]
  /// The implicit cracks: the largest error of a step [-]; 0: the scene's
  /// steps, cut only where Newton fails
  double implicit_tolerance{};
  /// IMPL-EX: a step's cracks from the strain extrapolated from the last
  /// step (implex_predictor = "strain"), else their history extrapolated
  bool predict_strain{};
  /// The implicit cracks: a step that Newton fails at the smallest cut is
  /// taken as one IMPL-EX step (implex_rescue)
  bool implex_rescue{};

  /// The implicit cracks' steps are held to their error (implicit_tolerance).
  bool implicit_steps_held() const { return embedded && !implex && implicit_tolerance > 0; }
  /// The implicit cracks' step error is read at every committed step, held
  /// to implicit_tolerance or not (summary.json implicit_error_max): all but
  /// viscous cracks', where it would measure the damage's lag, not the step.
  bool implicit_step_error_read() const { return embedded && !implex && !(viscosity > 0); }
};

/// [solver].
struct SolverPart
{
  enum class Condensation
  {
    automatic, ///< "auto"
    on,
    off
  };
  bool lagged_preconditioner{}; ///< preconditioner: lagged (else jacobian)
  Condensation condensation{};
  std::int64_t refactor_iterations{};
  bool inexact_newton{};          ///< GMRES to what Newton needs (NewtonSolver::set_inexact)
  bool first_tangent_converged{}; ///< first_tangent: converged (else current)
  bool mixed_precision{};         ///< precision: mixed (else double)
  bool time_linear_solve{};
};

/// [output].
struct OutputPart
{
  bool xdmf{}; ///< fields.xdmf and interface.xdmf
  bool plot{}; ///< curve.png
};

/// One [[interface]] layer: its law and resolved parameters.
struct LayerSpec
{
  std::string law;
  laws::Params params;
  /// Parameters the law does not read: only the defaults of others
  /// (laws::ParamDef::default_from), which are all given.
  std::vector<std::string> defaults_only;
};

/// One [[crack]] plane of a push-out (docs/corrosion.md): a plane through
/// the whole thickness of the concrete, from the interface to the slice's
/// outer boundary, with a cohesive law.
struct CrackSpec
{
  /// Direction from the tube axis in the x-y plane [deg, from +x towards
  /// +y]; unset: "nearest_face" (the cover side, resolved with the geometry).
  std::optional<double> angle_deg;
  LayerSpec layer; ///< the crack's law (one layer)
};

/// The directions of the crack planes, resolved once from the geometry
/// (scene/CrackPlanes.h), in the order of the [[crack]] tables.
struct CrackDirections
{
  std::vector<double> angles; ///< [rad, in [0, 2 pi)]
  std::vector<bool> snapped;  ///< moved onto a block corner
  std::vector<double> asked;  ///< the scene's angle [rad] before snapping
  bool operator==(const CrackDirections&) const = default;
};
} // namespace pushout

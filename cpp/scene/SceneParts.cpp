// The typed parts of a scene (SceneParts.h), filled once from its
// validated values: the one place that reads a key by its name.
#include "CrackPlanes.h"
#include "Scene.h"
#include "SceneError.h"
#include <algorithm>
#include <cmath>
#include <sstream>

namespace pushout
{
namespace
{
/// The value `text` names among `choices` (a key's declared choices, which
/// parsing has checked it is one of).
template <class T>
T choice(const std::string& text, std::initializer_list<std::pair<const char*, T>> choices)
{
  for (const auto& [name, value] : choices)
    if (text == name)
      return value;
  throw std::logic_error("scene choice '" + text + "' has no typed value");
}
} // namespace

void Scene::fill_parts()
{
  using Type = ModelPart::Type;
  _model.type = choice<Type>(string("model.type"),
                             {{"pushout", Type::pushout}, {"single_joint", Type::single_joint}});
  using Symmetry = ModelPart::Symmetry;
  _model.symmetry = choice<Symmetry>(string("model.symmetry"), {{"auto", Symmetry::automatic},
                                                                {"symmetric", Symmetry::symmetric},
                                                                {"full", Symmetry::full}});

  _geometry.circle = string("geometry.outer_shape") == "circle";
  _geometry.width = number("geometry.width");
  _geometry.thickness = number("geometry.thickness");
  _geometry.tube_outer_diameter = number("geometry.tube_outer_diameter");
  _geometry.tube_inner_diameter = number("geometry.tube_inner_diameter");
  const std::vector<double>& c = numbers("geometry.tube_center");
  if (c.size() != 2)
    throw SceneError("'geometry.tube_center' must have 2 entries (x, y)");
  _geometry.tube_center = {c[0], c[1]};
  // A circle slice is meshed around its tube (meshes/slice.geo).
  if (_geometry.circle &&
      *find("geometry.tube_center") != find_key("geometry.tube_center")->default_value)
    throw SceneError("'geometry.tube_center' places the tube in a square slice; a circle slice "
                     "('geometry.outer_shape' = \"circle\") is concentric with its tube: leave "
                     "tube_center out");
  _geometry.support_inner_diameter = number("geometry.support_inner_diameter");
  _geometry.area = number("geometry.area");

  _mesh.elements_per_quarter = integer("mesh.elements_per_quarter");
  _mesh.elements_through_thickness = integer("mesh.elements_through_thickness");
  _mesh.steel_layers = integer("mesh.steel_layers");
  _mesh.outer_size_ratio = number("mesh.outer_size_ratio");
  _mesh.radial_lines = string("mesh.graded_lines") == "radial";
  _mesh.refine_whole = string("mesh.graded_refinement") == "whole";
  _mesh.degree = int(integer("mesh.degree"));
  _mesh.nodal_quadrature = string("mesh.interface_quadrature") == "nodal";

  _concrete = {number("concrete.E"), number("concrete.nu"), number("concrete.alpha")};
  _steel = {number("steel.E"), number("steel.nu"), number("steel.alpha")};

  _loading.temperature_change = number("loading.temperature_change");
  _loading.push_displacement = number("loading.push_displacement");
  _loading.step_growth = number("loading.step_growth");
  _loading.tube_top_free = string("loading.thermal_tube_top") == "free";
  _loading.steps = integer("loading.steps");
  _loading.push_path = numbers("loading.push_path");
  _loading.unload_to_zero_force = string("loading.unload_to") == "zero_force";
  using Control = Loading::Control;
  _loading.control =
      choice<Control>(string("loading.control"), {{"displacement", Control::displacement},
                                                  {"arc_length", Control::arc_length},
                                                  {"dissipation", Control::dissipation},
                                                  {"auto", Control::automatic}});
  _loading.dissipation_steps = integer("loading.dissipation_steps");
  _loading.max_cuts = integer("loading.max_cuts");
  _loading.normal_force_per_node = number("loading.normal_force_per_node");
  _loading.shear_path = numbers("loading.shear_path");
  _loading.steps_per_segment = integer("loading.steps_per_segment");
  check_max_cuts();

  _corrosion.penetration = number("corrosion.penetration");
  _corrosion.steps = integer("corrosion.steps");
  _corrosion.beta = number("corrosion.beta");
  _corrosion.porous_zone = number("corrosion.porous_zone");
  _corrosion.oxide_bulk = number("corrosion.oxide_bulk");

  _cracking.embedded = string("cracking.model") == "embedded";
  _cracking.linear_softening = string("cracking.law") == "linear_softening";
  _cracking.f_t = number("cracking.f_t");
  _cracking.c = number("cracking.c");
  _cracking.w_c2 = number("cracking.w_c2");
  _cracking.row_band = string("cracking.band_width") == "row";
  _cracking.radius = number("cracking.radius");
  _cracking.strength_cov = number("cracking.strength_cov");
  _cracking.correlation_length = number("cracking.correlation_length");
  _cracking.seed = integer("cracking.seed");
  _cracking.visible_width = number("cracking.visible_width");
  _cracking.viscosity = number("cracking.viscosity");
  // auto: IMPL-EX where it applies (no viscosity), the implicit cracks with
  // a viscosity (keys_cracking.cpp; under dissipation control and arc length
  // since the corroded series converged 40 of 40 under each,
  // docs/cracking.md "Under dissipation control", "Under arc length").
  const std::string integration = string("cracking.integration");
  _cracking.implex = integration == "implex" || (integration == "auto" && _cracking.viscosity == 0);
  _cracking.implex_tolerance = number("cracking.implex_tolerance");
  _cracking.implicit_tolerance = number("cracking.implicit_tolerance");
  _cracking.predict_strain = string("cracking.implex_predictor") == "strain";
  _cracking.implex_rescue = boolean("cracking.implex_rescue");

  _solver.lagged_preconditioner = string("solver.preconditioner") == "lagged";
  using Condensation = SolverPart::Condensation;
  _solver.condensation = choice<Condensation>(
      string("solver.condensation"),
      {{"auto", Condensation::automatic}, {"on", Condensation::on}, {"off", Condensation::off}});
  _solver.refactor_iterations = integer("solver.refactor_iterations");
  _solver.inexact_newton = boolean("solver.inexact_newton");
  _solver.first_tangent_converged = string("solver.first_tangent") == "converged";
  _solver.mixed_precision = string("solver.precision") == "mixed";
  _solver.time_linear_solve = boolean("solver.time_linear_solve");

  _output.xdmf = boolean("output.xdmf");
  _output.plot = boolean("output.plot");

  _crack_directions = pushout::crack_directions(_geometry, _mesh.elements_per_quarter, _cracks);
}

void Scene::check_max_cuts() const
{
  // A stage's load parameter runs to its nominal steps N; an increment of
  // 2^-max_cuts of a step is lost in its round-off (N 2^-52) unless it is
  // well above it: 2^8 times.
  const auto path_steps = [&](const std::vector<double>& path)
  { return path.empty() ? 0 : std::int64_t(path.size() - 1) * _loading.steps_per_segment; };
  const std::int64_t N =
      std::max({_loading.steps, integer("corrosion.steps"), path_steps(_loading.push_path),
                path_steps(_loading.shear_path), std::int64_t(1)});
  const int most = 44 - int(std::ceil(std::log2(double(N))));
  if (_loading.max_cuts > most)
  {
    std::ostringstream s;
    s << "'loading.max_cuts' = " << _loading.max_cuts << " with " << N
      << " nominal steps in a stage: its smallest increment, 2^-" << _loading.max_cuts
      << " of a step, is lost in the round-off of the load's position there; at most " << most
      << " with " << N << " steps";
    throw SceneError(s.str());
  }
}

std::vector<Scene::Unread> Scene::unread(const std::string& set) const
{
  // The keys among `paths` whose value is not their default (and `set`).
  auto changed = [&](const std::vector<std::string>& paths)
  {
    std::vector<std::string> keys;
    for (const std::string& path : paths)
      if (const KeyDef* def = find_key(path);
          path == set || (def && find(path) && *find(path) != def->default_value))
        keys.push_back(path);
    return keys;
  };
  std::vector<Unread> notes;
  auto note = [&](std::vector<std::string> keys, std::string why)
  {
    if (!keys.empty())
      notes.push_back({std::move(keys), std::move(why)});
  };
  // A layer's parameter that only defaults others, all given (elastic's k
  // beside k_n and k_s), set to other than its default (or `set`).
  const auto layer_notes = [&](const std::string& section, const std::vector<LayerSpec>& layers)
  {
    for (std::size_t i = 0; i < layers.size(); ++i)
    {
      const std::string prefix = section + "." + std::to_string(i) + ".";
      const laws::LawInfo& law = *laws::find_law(layers[i].law);
      for (const std::string& p : layers[i].defaults_only)
      {
        const auto def = std::find_if(law.params.begin(), law.params.end(),
                                      [&](const laws::ParamDef& d) { return d.name == p; });
        const auto value = layers[i].params.find(p);
        if (prefix + p != set && (value == layers[i].params.end() ||
                                  (def->default_value && value->second == *def->default_value)))
          continue;
        std::string others;
        for (const laws::ParamDef& q : law.params)
          if (q.default_from == p)
            others += (others.empty() ? "" : " and ") + prefix + q.name;
        note({prefix + p}, "it is only the default of " + others + ", which are given");
      }
    }
  };
  layer_notes("interface", _layers);
  std::vector<LayerSpec> crack_layers;
  for (const CrackSpec& c : _cracks)
    crack_layers.push_back(c.layer);
  layer_notes("crack", crack_layers);
  if (!_model.pushout())
    return notes;
  if (_corrosion.penetration == 0)
    note(changed({"corrosion.steps", "corrosion.beta", "corrosion.porous_zone",
                  "corrosion.oxide_bulk"}),
         "corrosion.penetration = 0: no corrosion stage");
  if (!_cracking.embedded)
  {
    std::vector<std::string> others; // every [cracking] key but the switch
    for (const KeyDef& def : cracking_keys())
      if (def.path != "cracking.model")
        others.push_back(def.path);
    note(changed(others), "cracking.model = \"none\" keeps the concrete linear (\"embedded\" "
                          "lets it crack)");
  }
  else
  {
    note(changed({_cracking.linear_softening ? "cracking.c" : "cracking.w_c2"}),
         std::string("cracking.law = \"") +
             (_cracking.linear_softening ? "linear_softening" : "exponential_softening") +
             "\" takes " + (_cracking.linear_softening ? "cracking.w_c2" : "cracking.c"));
    if (_cracking.strength_cov == 0)
      note(changed({"cracking.seed", "cracking.correlation_length"}),
           "cracking.strength_cov = 0 makes the tensile strength uniform (no random field)");
    // The implicit cracks read IMPL-EX's keys for their IMPL-EX rescue (the
    // tolerance where its step is not the smallest) and the predictor for
    // their step error too.
    if (_cracking.implex)
      note(changed({"cracking.implex_rescue"}),
           "the cracks are integrated by IMPL-EX; cracking.implex_rescue is the implicit "
           "cracks'");
    else if (_cracking.viscosity > 0)
      note(changed({"cracking.implex_rescue"}),
           "a cracking.viscosity is integrated implicitly to the end: IMPL-EX takes no "
           "viscosity, so no IMPL-EX step rescues the implicit cracks");
    const bool rescued = _cracking.implex_rescue && _cracking.viscosity == 0;
    if (!_cracking.implex && !rescued)
      note(changed(_cracking.implicit_tolerance > 0
                       ? std::vector<std::string>{"cracking.implex_tolerance"}
                       : std::vector<std::string>{"cracking.implex_tolerance",
                                                  "cracking.implex_predictor"}),
           _cracking.viscosity > 0 && string("cracking.integration") == "auto"
               ? "cracking.integration = \"auto\" with a cracking.viscosity integrates the "
                 "cracks implicitly (IMPL-EX takes no viscosity)"
               : "cracking.integration = \"implicit\" solves each step's cracks, without "
                 "IMPL-EX rescues (cracking.implex_rescue, or a viscosity); they are "
                 "IMPL-EX's");
    else if (_cracking.implex)
      note(changed({"cracking.implicit_tolerance"}),
           "the cracks are integrated by IMPL-EX, whose steps cracking.implex_tolerance holds; "
           "cracking.implicit_tolerance is the implicit cracks'");
  }
  // The push: a path, or a monotonic push to push_displacement.
  if (!_loading.push_path.empty())
    note(changed({"loading.push_displacement", "loading.steps"}),
         "loading.push_path sets the push (in loading.steps_per_segment steps a segment)");
  else
    note(changed({"loading.steps_per_segment", "loading.unload_to"}),
         "they apply to loading.push_path, and the push is monotonic (to "
         "loading.push_displacement)");
  if (_loading.control == Loading::Control::displacement ||
      _loading.control == Loading::Control::arc_length)
    note(changed({"loading.dissipation_steps"}),
         "it sizes the energy steps of loading.control = \"auto\" or \"dissipation\"");
  return notes;
}

namespace
{
/// "a, b not read: why"
std::string unread_line(const std::vector<std::string>& keys, const std::string& why)
{
  std::string line;
  for (const std::string& k : keys)
    line += (line.empty() ? "" : ", ") + k;
  return line + " not read: " + why;
}
} // namespace

std::vector<std::string> Scene::unread_keys() const
{
  std::vector<std::string> lines;
  for (const Unread& u : unread())
    lines.push_back(unread_line(u.keys, u.why));
  return lines;
}

std::string Scene::unread_note(const std::string& path) const
{
  for (const Unread& u : unread(path))
    if (std::find(u.keys.begin(), u.keys.end(), path) != u.keys.end())
      return unread_line({path}, u.why);
  return "";
}
} // namespace pushout

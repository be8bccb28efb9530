// The typed parts of a scene (SceneParts.h), filled once from its
// validated values: the one place that reads a key by its name.
#include "CrackPlanes.h"
#include "Scene.h"
#include "SceneError.h"

namespace pushout
{
void Scene::fill_parts()
{
  _model.type = string("model.type") == "single_joint" ? ModelPart::Type::single_joint
                                                       : ModelPart::Type::pushout;
  const std::string& symmetry = string("model.symmetry");
  _model.symmetry = symmetry == "full"        ? ModelPart::Symmetry::full
                    : symmetry == "symmetric" ? ModelPart::Symmetry::symmetric
                                              : ModelPart::Symmetry::automatic;

  _geometry.circle = string("geometry.outer_shape") == "circle";
  _geometry.width = number("geometry.width");
  _geometry.thickness = number("geometry.thickness");
  _geometry.tube_outer_diameter = number("geometry.tube_outer_diameter");
  _geometry.tube_inner_diameter = number("geometry.tube_inner_diameter");
  const std::vector<double>& c = numbers("geometry.tube_center");
  if (c.size() != 2)
    throw SceneError("'geometry.tube_center' must have 2 entries (x, y)");
  _geometry.tube_center = {c[0], c[1]};
  _geometry.support_inner_diameter = number("geometry.support_inner_diameter");
  _geometry.area = number("geometry.area");

  _mesh.elements_per_quarter = integer("mesh.elements_per_quarter");
  _mesh.elements_through_thickness = integer("mesh.elements_through_thickness");
  _mesh.steel_layers = integer("mesh.steel_layers");
  _mesh.outer_size_ratio = number("mesh.outer_size_ratio");
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
  const std::string& control = string("loading.control");
  _loading.control = control == "arc_length"    ? Loading::Control::arc_length
                     : control == "dissipation" ? Loading::Control::dissipation
                     : control == "auto"        ? Loading::Control::automatic
                                                : Loading::Control::displacement;
  _loading.dissipation_steps = integer("loading.dissipation_steps");
  _loading.max_cuts = integer("loading.max_cuts");
  _loading.normal_force_per_node = number("loading.normal_force_per_node");
  _loading.shear_path = numbers("loading.shear_path");
  _loading.steps_per_segment = integer("loading.steps_per_segment");

  _corrosion.penetration = number("corrosion.penetration");
  _corrosion.steps = integer("corrosion.steps");
  _corrosion.beta = number("corrosion.beta");
  _corrosion.porous_zone = number("corrosion.porous_zone");
  _corrosion.oxide_bulk = number("corrosion.oxide_bulk");

  _solver.lagged_preconditioner = string("solver.preconditioner") == "lagged";
  const std::string& condensation = string("solver.condensation");
  _solver.condensation = condensation == "on"    ? SolverPart::Condensation::on
                         : condensation == "off" ? SolverPart::Condensation::off
                                                 : SolverPart::Condensation::automatic;
  _solver.refactor_iterations = integer("solver.refactor_iterations");
  _solver.first_tangent_converged = string("solver.first_tangent") == "converged";
  _solver.mixed_precision = string("solver.precision") == "mixed";
  _solver.time_linear_solve = boolean("solver.time_linear_solve");

  _output.xdmf = boolean("output.xdmf");
  _output.plot = boolean("output.plot");

  _crack_directions = pushout::crack_directions(_geometry, _mesh.elements_per_quarter, _cracks);
}
} // namespace pushout

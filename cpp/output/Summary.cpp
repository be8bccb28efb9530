#include "Summary.h"
#include "OutputFiles.h"
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

namespace pushout::output
{
void Summary::write(const std::filesystem::path& file) const
{
  nlohmann::json crack_list = nlohmann::json::array();
  for (const Crack& c : cracks)
    if (c.plane)
      crack_list.push_back({{"source", "plane"},
                            {"angle_deg", c.angle_deg},
                            {"width_mm", c.width_mm},
                            {"snapped", c.snapped},
                            {"mouth_opening_mm", c.mouth_opening_mm},
                            {"max_opening_mm", c.max_opening_mm},
                            {"max_damage", c.max_damage}});
    else
      crack_list.push_back({{"source", "concrete"},
                            {"angle_deg", c.angle_deg},
                            {"width_mm", c.width_mm},
                            {"length_mm", c.length_mm}});
  // IMPL-EX's readings only where its cracks ran (null elsewhere: no step measured).
  const bool implex = cracking_integration == "implex";
  const bool implicit = cracking_integration == "implicit"; // its rescues, the same way
  nlohmann::json damage_list = nlohmann::json::array();
  for (const LayerDamage& d : initial_damage)
    damage_list.push_back({{"layer", d.layer}, {"mean", d.mean}, {"max", d.max}});
  nlohmann::json edge; // null without an edge
  if (cracking_edge)
    edge = {{"radius_mm", cracking_edge->radius_mm},
            {"points", cracking_edge->points},
            {"cracked_points", cracking_edge->cracked_points},
            {"max_opening_mm", cracking_edge->max_opening_mm},
            {"reached_in", cracking_edge->reached_in}};
  const nlohmann::json j = {
      {"run_id", run_id},
      {"converged", converged},
      {"interrupted", interrupted},
      {"signal", signal},
      {"message", message},
      {"notes", notes},
      {"model_type", model_type},
      {"symmetry", symmetry},
      {"condensed_dofs", condensed_dofs},
      {"condensation_asymmetry", condensation_asymmetry},
      {"steps", steps},
      {"corrosion_steps", corrosion_steps},
      {"dissipation_steps", dissipation_steps},
      {"loose_steps", loose_steps},
      {"cracking_integration", cracking_integration},
      {"implex_error_max", implex ? nlohmann::json(step_error_max) : nlohmann::json()},
      {"implex_jumps", implex ? nlohmann::json(step_error_jumps) : nlohmann::json()},
      {"implicit_error_max",
       implicit_step_error ? nlohmann::json(step_error_max) : nlohmann::json()},
      {"implicit_jumps", implicit_steps_held ? nlohmann::json(step_error_jumps) : nlohmann::json()},
      {"implex_rescues", implicit ? nlohmann::json(implex_rescues) : nlohmann::json()},
      {"implex_rescue_error_max",
       implicit ? nlohmann::json(implex_rescue_error_max) : nlohmann::json()},
      {"cracking_edge", edge},
      {"penetration_mm", penetration_mm},
      {"permanent_displacements_mm", permanent_displacements_mm},
      {"cracks", crack_list},
      {"surface_crack_width_mm", std::isfinite(surface_crack_width_mm)
                                     ? nlohmann::json(surface_crack_width_mm)
                                     : nlohmann::json()},
      {"initial_damage", damage_list},
      {"newton_iterations", newton_iterations},
      {"cuts", cuts},
      {"factorizations", factorizations},
      {"linear_iterations", linear_iterations},
      {"wall_s", wall_s},
      {"time_s", {{"mesh", mesh_s}, {"setup", setup_s}, {"solve", solve_s}, {"output", output_s}}},
      {"linear_solve_s",
       linear_solve_s >= 0 ? nlohmann::json(linear_solve_s) : nlohmann::json()}, // null: not timed
      {"mesh_reused", mesh_reused},
      {"setup_reused", setup_reused},
      {"dofs", dofs},
      {"cells", cells},
      {"interface_pairs", interface_pairs},
      {"processes", processes},
      {"peak_memory_mb", peak_memory_mb},
      {"estimate",
       {{"dofs", estimate.dofs},
        {"cells", estimate.cells},
        {"interface_pairs", estimate.interface_pairs},
        {"peak_memory_mb", estimate.peak_memory_mb}}},
      {"stopped_in", stopped_in}};
  write_file(file, j.dump(2) + "\n");
}

void add_unused_petsc_options(const std::filesystem::path& file,
                              const std::vector<std::string>& unused)
{
  std::ifstream in(file);
  if (!in)
    return; // a run refused before it wrote one
  nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  // Only this command's own: a run refused before it wrote one leaves an
  // earlier run's (or a live run's, behind the folder's lock) as it is.
  if (!j.is_object() || !j.contains("run_id") || j["run_id"] != run_id())
    return;
  j["unused_petsc_options"] = unused;
  write_file(file, j.dump(2) + "\n");
}
} // namespace pushout::output

// summary.json: the run's outcome and costs.
#pragma once

#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace pushout::output
{
struct Summary
{
  std::string run_id;       ///< the run's id (output::run_id): which run wrote the folder
  bool converged = false;   ///< every requested step converged
  bool interrupted = false; ///< stopped by a signal
  int signal = 0;           ///< the signal, if interrupted
  std::string message;      ///< why it stopped, if it did not finish
  /// The notes printed before the run (driver/Run.cpp, note_scene): keys
  /// set that nothing reads, values that may not run well.
  std::vector<std::string> notes;
  int steps = 0;             ///< converged load steps (rows after step 0)
  int corrosion_steps = 0;   ///< converged corrosion steps (corrosion.csv rows after step 0)
  int dissipation_steps = 0; ///< corrosion and push steps controlled by the energy released
  /// Of those, the steps whose Newton iterations stalled and that ended at
  /// their best iterate, |F| within 1e-5 of the reactions and the energy
  /// released within 1 % of the step's (solver/ArcLengthSolver.h, step).
  int loose_steps = 0;
  /// How the concrete's cracks were integrated: "implex" or "implicit"
  /// (cracking.integration, "auto" resolved), "none" without [cracking].
  std::string cracking_integration = "none";
  /// The concrete's cracks' step error where it is checked
  /// (model::BulkCracking::step_error: IMPL-EX cracks, or the implicit
  /// cracks without a viscosity, held to cracking.implicit_tolerance or
  /// only read): the largest of a committed step [-], written as
  /// implex_error_max or implicit_error_max.
  double step_error_max = 0;
  /// Of its steps, those taken above the tolerance (no smaller step met
  /// it: the cracks snapped back under the load's control, or the implicit
  /// cracks' floor), written as implex_jumps or implicit_jumps.
  int step_error_jumps = 0;
  /// The implicit cracks without a viscosity: step_error_max is written
  /// as implicit_error_max, whether the steps were held to it or not
  /// (model::BulkCracking::step_error_measured_only).
  bool implicit_step_error = false;
  /// ... with cracking.implicit_tolerance > 0: step_error_jumps too, as
  /// implicit_jumps.
  bool implicit_steps_held = false;
  /// The implicit cracks: the steps that Newton failed at every cut and
  /// that one IMPL-EX step took instead (cracking.implex_rescue), and the
  /// largest IMPL-EX error of those [-] (model::BulkCracking::implex_error);
  /// null in summary.json without the implicit cracks.
  int implex_rescues = 0;
  double implex_rescue_error_max = 0;
  /// With cracking.radius > 0: the cracks at the edge of the cracking
  /// region at the end of the run (model::EdgeCracks, the specimen's
  /// points as the other counts), and the corrosion step they first
  /// reached it in ("the push" where no corrosion step found them; "step 0
  /// or the push (no corrosion stage)" without one; "": none reached it).
  /// Null otherwise.
  struct CrackingEdge
  {
    double radius_mm = 0;
    std::int64_t points = 0, cracked_points = 0;
    double max_opening_mm = 0;
    std::string reached_in;
  };
  std::optional<CrackingEdge> cracking_edge;
  double penetration_mm = 0; ///< corrosion depth x reached [mm]
  /// Where each unloading of the push ended at zero force
  /// (loading.unload_to = "zero_force"): the tube's permanent displacement.
  std::vector<double> permanent_displacements_mm;
  int newton_iterations = 0;
  int cuts = 0;           ///< step cut-backs
  int factorizations = 0; ///< LU factorisations of the Newton systems
  /// Krylov iterations of the Newton systems and of the path followers'
  /// solves (an application of an LU each; a direct solve counts one)
  std::int64_t linear_iterations = 0;
  double wall_s = 0;
  double mesh_s = 0, setup_s = 0, solve_s = 0, output_s = 0;
  /// One linear solve of the first load step with the run's solver
  /// (solver.time_linear_solve; < 0: not measured, null in summary.json) [s]:
  /// the floor of a curve.
  double linear_solve_s = -1;
  bool mesh_reused = false;
  /// The set-up (factorisation, condensed flexibility) of an earlier case
  /// of the same process was reused (pushout sweep, fit).
  bool setup_reused = false;
  std::int64_t dofs = 0;
  std::int64_t cells = 0;
  std::int64_t interface_pairs = 0;
  int processes = 1;
  double peak_memory_mb = 0; ///< largest peak resident memory of a process
  /// The size guard's estimate, made before meshing (record/ResourceGuard.h).
  struct Estimate
  {
    std::int64_t dofs = 0, cells = 0, interface_pairs = 0;
    double peak_memory_mb = 0;
  } estimate;
  std::string stopped_in; ///< the phase a signal stopped the run in ("": none)
  std::string model_type;
  std::string symmetry = "full"; ///< quarter: the model is a quarter of the specimen
  /// Size of the condensed system Newton ran on (0: the whole model).
  std::int64_t condensed_dofs = 0;
  /// max|C - C^T| / max|C| of the condensed flexibility (the round-off of
  /// its factorisation; 0: not condensed), also where it was not trusted
  /// and the whole model ran instead.
  double condensation_asymmetry = 0;
  /// A crack at the start of the push (after the thermal step and the
  /// corrosion stage; where the corrosion stage stopped, at its last
  /// finished step): a crack plane ([[crack]]), or a crack of the concrete
  /// ([cracking]) that reaches an outer face as wide as
  /// cracking.visible_width (model/SurfaceCracks.h).
  struct Crack
  {
    bool plane = true; ///< a crack plane (else a crack of the concrete)
    double angle_deg =
        0; ///< direction from the tube axis (a plane's after "nearest_face" or snapping)
    double width_mm = 0;         ///< at the outer face: a plane's mouth opening, a gauge's reading
    double length_mm = 0;        ///< the concrete's: how far it runs in from the face
    bool snapped = false;        ///< plane: moved onto a block corner of the mesh
    double mouth_opening_mm = 0; ///< plane: mean opening at the slice's outer face
    double max_opening_mm = 0;   ///< plane: largest opening w_n at a quadrature point
    double max_damage = 0;       ///< plane: largest damage at a quadrature point
  };
  std::vector<Crack> cracks;
  /// The widest crack at the slice's outer faces at the start of the push
  /// [mm], as corrosion.csv's crack_width_mm reads it (a plane's mouth
  /// opening, or the concrete's gauge reading from its resolution up); 0: none;
  /// where the corrosion stage stopped, at its last finished step; NaN
  /// (null) where the run stopped in step 0 or the set-up.
  double surface_crack_width_mm = std::numeric_limits<double>::quiet_NaN();
  /// The damage of a damage layer of the interface at the start of the push
  /// (what the thermal step and the corrosion stage left).
  struct LayerDamage
  {
    int layer = 0;
    double mean = 0; ///< area-weighted
    double max = 0;
  };
  std::vector<LayerDamage> initial_damage;

  /// Writes it whole (output::write_file); throws if it cannot.
  void write(const std::filesystem::path& file) const;
};

/// Adds `unused_petsc_options` (the user's PETSc options that no solver
/// read, known only once the command has ended) to the summary.json `file`
/// that this command's run wrote (its run_id); nothing to another or where
/// there is none. Throws if it cannot write it.
void add_unused_petsc_options(const std::filesystem::path& file,
                              const std::vector<std::string>& unused);
} // namespace pushout::output

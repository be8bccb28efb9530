// One simulation: scene -> mesh -> model -> step loop -> outputs.
//
// What depends on the bulk alone (the mesh, the model, the solver of a load
// step with its factorisation and condensed flexibility) is a Simulation,
// kept by `pushout sweep` (and `pushout fit`) for the next evaluation of a
// scene that differs only in what that does not depend on: the interface
// and crack laws, the loads, the corrosion stage, the outputs.
#pragma once

#include "../mesh/MeshData.h"
#include "../model/Model.h"
#include "../output/Summary.h"
#include "../record/RunReport.h"
#include "../scene/Scene.h"
#include "../solver/Equilibrium.h"
#include "../solver/LoadStepSolver.h"
#include <filesystem>
#include <memory>
#include <mpi.h>
#include <string>
#include <string_view>
#include <vector>

namespace pushout::driver
{
struct RunOptions
{
  std::filesystem::path out;        ///< output folder
  std::filesystem::path mesh_cache; ///< gmsh mesh cache folder
  bool quiet = false;               ///< no progress lines
  bool force = false;               ///< run even if the size guard says it cannot fit
  MPI_Comm comm = MPI_COMM_WORLD;   ///< the processes that run it (pushout sweep: a group)
  bool plot = true;                 ///< curve.png if output.plot (a sweep draws sweep.png)
  /// Processes of other cases on this machine while this one runs (pushout
  /// sweep and fit: study::ProcessGroups::others_here); the size guard
  /// counts each at this run's solving peak.
  int others_here = 0;
};

class Simulation
{
public:
  /// The size guard, the mesh and the set-up of `scene` on options.comm,
  /// their sizes and times into the report's summary. Collective.
  Simulation(const Scene& scene, const RunOptions& options, record::RunReport& report);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  /// Whether `scene` can run on this set-up: the same set-up keys
  /// (set_up_fingerprint).
  bool fits(const Scene& scene) const { return set_up_fingerprint(scene) == _fingerprint; }

  /// The load steps of `scene` (its laws made anew, the state zero) with
  /// their outputs in options.out, into the report's summary (the set-up's
  /// sizes copied, its times zero if it was built for another scene).
  /// Collective.
  void load_steps(const Scene& scene, const RunOptions& options, record::RunReport& report);

  /// The scene keys the set-up depends on, as text: model, geometry, mesh,
  /// materials, solver keys, the thermal tube-top condition, the crack
  /// planes' directions and output.xdmf (which uncuts an "auto" symmetric model).
  static std::string set_up_fingerprint(const Scene& scene);

private:
  std::string _fingerprint;
  mesh::MeshData _data;
  std::unique_ptr<model::Model> _model;
  std::unique_ptr<solver::Equilibrium> _equilibrium;
  std::unique_ptr<solver::LoadStepSolver> _solver;
  output::Summary _set_up; ///< the summary's set-up fields
  int _runs = 0;           ///< load_steps() so far
};

/// The refusals a run can make before it touches its output folder (so
/// that a refused run leaves an earlier run's outputs there as they were):
/// the scene's checks of its model type and the solver's of its [solver]
/// part (SceneError) and PETSc options (OptionError), the size guard
/// (record::TooLarge, unless options.force) and a $PUSHOUT_CACHE_MAX_MB
/// that is no size (OptionError). Collective.
void check_before_run(const Scene& scene, const RunOptions& options);

/// The solver's refusals of the scene's [solver] part and the user's PETSc
/// options on `processes` processes (solver::LoadStepSolver::check_options),
/// before any model is built. Throws SceneError.
void check_solver_options(const Scene& scene, int processes);

/// Runs the scene, which check_before_run passed; writes curve.csv,
/// summary.json, scene.toml (and
/// curve.png, XDMF) into options.out. Returns the summary; a step that
/// cannot converge ends the run with summary.converged = false.
output::Summary run(const Scene& scene, const RunOptions& options);

/// How a run ended, as `pushout run` would exit: 0 converged, 2 a bad
/// scene or refused by the size guard, 3 a step did not converge, 1 another
/// error, 128 + signal if a signal stopped it.
struct RunOutcome
{
  /// Who refused a run that exit 2 ended.
  enum class Refusal
  {
    none,  ///< not refused
    scene, ///< a scene the scene's checks refuse (SceneError)
    size   ///< the size guard: more than the machine holds (record::TooLarge)
  };
  int exit_code = 1;
  double wall_s = 0;
  std::string message; ///< why it did not converge ("" if it did), as the run says it
  Refusal refused = Refusal::none;
  /// The label of a scene's refusal in `message`, as `pushout run` says it.
  static constexpr std::string_view scene_label = "error in scene: ";
  /// `message` without scene_label.
  std::string reason() const
  {
    return refused == Refusal::scene ? message.substr(scene_label.size()) : message;
  }
};

/// One run of many (pushout sweep, fit): the scene `scene_text` (read from
/// `scene_file`, which names it in messages) with `sets`, run on
/// options.comm on the set-up `simulation` holds if the scene fits it
/// (else on a new one, kept for the next run; dropped after an error).
/// Never throws: an error, agreed on by the run's processes, is the
/// outcome. Collective on options.comm.
RunOutcome run_case(const std::string& scene_text, const std::filesystem::path& scene_file,
                    const std::vector<std::string>& sets, const RunOptions& options,
                    std::unique_ptr<Simulation>& simulation);
} // namespace pushout::driver

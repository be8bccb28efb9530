// What a model type (push-out slice, single joint) adds to the common step
// loop: its constraints and loads as a function of the load parameter, and
// the quantities it measures for curve.csv.
#pragma once

#include "../mesh/MeshData.h"
#include "../model/Model.h"
#include "../scene/Scene.h"
#include "../solver/Equilibrium.h"
#include <memory>
#include <string>
#include <vector>

namespace pushout::specimen
{
class Scenario
{
public:
  virtual ~Scenario() = default;

  /// curve.csv columns measured by row() (after the leading `step`).
  virtual std::vector<std::string> columns() const = 0;

  /// Number of load steps; the load parameter s runs over [0, steps].
  virtual int steps() const = 0;

  /// Whether s = 0 needs a solve (preload, thermal step) or is the
  /// unloaded state.
  virtual bool initial_solve() const = 0;

  /// Pseudo-time at load parameter s, for viscous laws (push-out: the push
  /// displacement in mm; single joint: the shear path length in mm).
  virtual double time_at(double s) const = 0;

  /// Sets constraints and loads for load parameter s.
  virtual void apply_load(double s, solver::Equilibrium& eq) const = 0;

  /// The constraints of s = 0 with its loads (temperature change, preload)
  /// scaled by `fraction` in [0, 1]: step 0 in parts, when it does not
  /// converge whole (fraction 1 is apply_load(0)).
  virtual void apply_initial_load(double fraction, solver::Equilibrium& eq) const = 0;

  /// Path following (loading.control = "arc_length"): whether the scenario
  /// has a load factor lambda that moves its prescribed displacements
  /// affinely, and lambda's final value.
  virtual bool has_load_factor() const { return false; }
  virtual double final_load_factor() const { return 0.0; }
  /// Whether the load factor only grows, to its final value (a push-out's
  /// monotonic push, not its push_path): what path following and
  /// dissipation control run.
  virtual bool monotonic() const { return has_load_factor(); }
  /// Sets constraints and loads for load factor lambda (after step 0).
  virtual void apply_load_factor(double /*lambda*/, solver::Equilibrium& /*eq*/) const {}
  /// The force that works on the load factor, on the model as meshed (a
  /// quarter model's quarter: the work of a step is its product with
  /// d lambda, in the units of Interface::energy_release), from the laws'
  /// last evaluation [N]. Collective.
  virtual double load_force(const model::Model& /*model*/) const { return 0.0; }

  /// The prescribed displacement at load parameter s (push-out: delta;
  /// single joint: the shear) [mm].
  virtual double prescribed_at(double s) const = 0;

  /// Unloading that ends where the load force (load_force) falls to zero,
  /// as a push-out device that cannot pull (loading.unload_to =
  /// "zero_force"): whether nominal step k (1-based) is on such a segment.
  virtual bool ends_at_zero_force(int /*k*/) const { return false; }
  /// Ends the segment of nominal step k at load parameter s (converged
  /// there with zero force), so that the next segment starts from that
  /// state; returns the load parameter the steps go on from (the segment's
  /// nominal end).
  virtual double end_segment_at(int /*k*/, double s) { return s; }

  /// Called once with the converged state of step 0 (owned dofs), before
  /// the load steps.
  virtual void start_loading(std::span<const double> /*x*/) {}

  /// Whether row() reads reactions, or displacements off the interface and
  /// the constrained dofs (if not, a condensed solver need not recover the
  /// bulk after each step).
  virtual bool uses_bulk() const { return true; }

  /// Measured values, given the internal forces at all dofs (reactions at
  /// the constrained ones), owned part, the displacement x (owned part) and
  /// the model (for interface quantities).
  virtual std::vector<double> row(std::span<const double> reactions, std::span<const double> x,
                                  const model::Model& model) const = 0;

  /// One line for the progress output.
  virtual std::string progress(const std::vector<double>& row) const = 0;
};

/// The checks of the scene that belong to its model type (model.type):
/// relations between keys no single range expresses. Throws SceneError.
void check_scene(const Scene& scene);

/// What a valid scene of the scene's model type asks that may not run well
/// (one line each, printed as notes before the run).
std::vector<std::string> scene_notes(const Scene& scene);

/// The scenario of the scene's model type.
std::unique_ptr<Scenario> make_scenario(const Scene& scene, const mesh::MeshData& mesh,
                                        const model::Model& model);
} // namespace pushout::specimen

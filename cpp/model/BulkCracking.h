// Concrete that cracks, in the model (docs/cracking.md): the crack band of
// bulk/CrackBand.h at every quadrature point of the concrete that may crack
// (the cells within cracking.radius of the tube axis), each point with its
// own tensile strength from the random field of bulk/StrengthField.h.
//
// The linear stiffness K (forms/elasticity.py) stays as assembled, its
// cracking cells integrated at the crack band's points (add_elastic_rule);
// what cracking changes enters through forms/cracking.py on the cracking
// cells only: the forces of sigma - C : eps_e and the tangent C_t - C, both zero
// at a point that has not cracked. Per evaluation: the strain at the points
// (an FFCx expression of the displacement), the crack band's update from
// the committed state (one 3 x 3 equilibrium per cracked point), then the
// two differences into the forms' Quadrature coefficients.
//
// State: a committed and a trial copy at every point, as the joints'
// (interface/InterfaceState.h); evaluate() writes the trial one, commit()
// after a converged step, revert() before a retry.
#pragma once

#include "../bulk/CrackBand.h"
#include "../scene/SceneParts.h"
#include "CellWidth.h"
#include "SurfaceCracks.h"
#include <array>
#include <cstdint>
#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/Expression.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/mesh/Mesh.h>
#include <dolfinx/mesh/MeshTags.h>
#include <functional>
#include <memory>
#include <petscmat.h>
#include <span>
#include <vector>

namespace pushout::solver
{
class Equilibrium;
}

namespace pushout::model
{
/// The cracks at the edge of the cracking region (cracking.radius > 0): the
/// cells there share a vertex with concrete that stays linear, so a crack
/// that reaches them cannot run on. Over all processes.
struct EdgeCracks
{
  /// cracking.radius [mm]; 0: no edge (radius 0, or one that takes in all
  /// the concrete)
  double radius = 0;
  std::int64_t points = 0;         ///< quadrature points of the cells at the edge
  std::int64_t cracked_points = 0; ///< of those, cracked
  double max_opening = 0;          ///< the widest normal opening w . n there [mm]
};

/// What the concrete's cracks add up to over all processes (collective).
struct CrackingTotals
{
  std::int64_t points = 0;         ///< quadrature points that may crack
  std::int64_t cracked_points = 0; ///< of those, cracked
  double max_opening = 0;          ///< the widest normal opening w . n at a point [mm]
  double dissipated = 0;           ///< energy the cracks dissipated [N mm]
  /// The cracks at the slice's outer faces as a gauge reads them, widest
  /// first (model/SurfaceCracks.h); the same on every process.
  std::vector<SurfaceCrack> surface;
  /// The cracking concrete's columns through the thickness (the crack
  /// pattern seen along the tube axis); on process 0 only.
  std::vector<CrackColumn> columns;
  EdgeCracks edge; ///< at the edge of the cracking region
};

class BulkCracking
{
public:
  /// `material` the input cells' materials (MeshData); `slice` the
  /// slice's geometry (the tube axis, the outer faces). Throws SceneError, on every process, if a
  /// cracking cell is too large for its crack band to soften without snapping back.
  BulkCracking(std::shared_ptr<dolfinx::mesh::Mesh> mesh,
               std::shared_ptr<const dolfinx::fem::FunctionSpace> V,
               std::shared_ptr<const dolfinx::fem::Function<double>> u,
               std::shared_ptr<const dolfinx::fem::Function<double>> alpha,
               const std::vector<std::int32_t>& material, const Material& concrete,
               const CrackingPart& part, const Geometry& slice, int copies = 1);

  /// cracking.visible_width: a surface crack counts from this width [mm].
  double visible_width() const { return _visible_width; }

  /// Who may set the temperature change: only Equilibrium can make one.
  class TemperatureKey
  {
    friend class solver::Equilibrium;
    TemperatureKey() = default;
  };
  /// The temperature change whose free strain the stress does not see [degC].
  /// Only Equilibrium::set_temperature_change sets it (the key), with the
  /// thermal load and the IMPL-EX residual's free-strain shift, which are
  /// made of the same value; Equilibrium::internal_forces refuses a crack
  /// band whose value another Equilibrium on the same model set since.
  void set_temperature_change(double dT, TemperatureKey);
  /// What set_temperature_change() set [degC].
  double temperature_change() const { return _dT->value[0]; }
  /// The step's pseudo-time increment, for the cracks' damage viscosity
  /// (cracking.viscosity) [mm of push].
  void set_time_increment(double dt)
  {
    _dt = dt;
    ++_trial_version;
  }

  /// Whether the cracks are integrated by IMPL-EX (cracking.integration
  /// resolved to "implex"; docs/cracking.md, "IMPL-EX"): in a step each
  /// point holds a predicted crack state as the linear maps of
  /// CrackBand::secant_operator, so that the bulk is linear but for
  /// closure; after the step the crack band's own update at the converged
  /// strain (onset, the history, the dissipation) is what is committed.
  /// The prediction (cracking.implex_predictor): "strain", the default, the
  /// crack band's update at the strain extrapolated from the last step (a
  /// point predicted to crack holds that crack); "history", each crack's
  /// damage extrapolated from the last committed step
  /// (CrackBand::secant_response), and no point cracks in the step.
  bool implex() const { return _implex; }
  /// The implicit cracks (cracking.integration resolved to "implicit"), so
  /// that a step of IMPL-EX may stand in for one (implex_rescue) [-].
  bool implicit_run() const { return !_implex || _rescue; }
  /// The implicit cracks without a viscosity: the steps from the next try
  /// on are integrated by IMPL-EX (`on`), or implicitly again. A step that
  /// no cut lets the implicit cracks' Newton pass is tried once more as an
  /// IMPL-EX step (cracking.implex_rescue; StepLoop::cut_back), which is
  /// linear but for closure; its cracks' own update at its strain is what
  /// is committed, as IMPL-EX's is, and the implicit steps go on from it.
  /// A logic error with IMPL-EX cracks or a viscosity.
  void set_implex_rescue(bool on);
  /// Whether the steps are an implicit run's IMPL-EX rescue
  /// (set_implex_rescue).
  bool implex_rescue() const { return _rescue; }
  /// Whether set_implex_rescue(true) may be called: the implicit cracks,
  /// no viscosity, cracking.implex_rescue, and no rescue on already.
  bool may_rescue() const { return _rescue_allowed && !_implex && !viscous(); }
  /// Whether the cracks' damage is viscous (cracking.viscosity > 0).
  bool viscous() const { return _band.viscosity() > 0; }
  /// IMPL-EX: the extrapolation of this try, the ratio of its load
  /// increment to the last committed step's (0: none, the committed
  /// history: a stage's first step, a load that turns back). The history
  /// a crack holds is kappa_n + ratio (kappa_n - kappa_n-1); with the strain
  /// predictor, the crack band's update at eps_n + ratio (eps_n - eps_n-1).
  void set_extrapolation(double ratio)
  {
    const double r = ratio > 0 ? ratio : 0.0;
    if (r != _extrapolation)
      history_changed();
    _extrapolation = r;
  }
  /// A number that changes whenever the tangent of the next evaluate() at
  /// another displacement may differ from the last one's. With IMPL-EX it
  /// holds while no crack opens or closes and nothing is committed or
  /// extrapolated anew (a step's tangent is the same at every iteration,
  /// Equilibrium::jacobian keeps it); otherwise it changes at every
  /// evaluate().
  std::uint64_t tangent_version() const { return _tangent_version; }
  /// A number that changes at every evaluate() that evaluates and at
  /// whatever may change the next one's result at the same displacement (a
  /// commit, a revert, an update, a setting): evaluate() at the displacement
  /// of the last one keeps its result while this has not changed.
  std::uint64_t trial_version() const { return _trial_version; }
  /// IMPL-EX: how far the converged step's stress is from the crack band's
  /// own at its strain, the energy norm of the difference over the
  /// cracking concrete's: sqrt(int ds : C^-1 : ds / int s : C^-1 : s), s the
  /// crack band's stress, ds the difference [-]. Leaves the crack band's
  /// update as the trial state (what commit() commits); the points whose
  /// crack's equilibrium failed there (they keep their committed state)
  /// into `failed_points`. Call right after the step's solve (its last
  /// evaluate() at the converged displacement). Collective.
  double implex_error(std::int64_t& failed_points);
  /// cracking.implex_tolerance: a step whose implex_error() exceeds it is
  /// cut [-].
  double implex_tolerance() const { return _implex_tolerance; }
  /// The implicit cracks: how far the converged step's stress (the crack
  /// band's own at its strain) is from what IMPL-EX's prediction from the
  /// last steps (cracking.implex_predictor) answers at the same strain, in
  /// implex_error()'s norm [-]. The predictor-corrector difference of a
  /// first-order integration, so an estimate of the step's own error: the
  /// cracks are path dependent, and a step through which the growth of
  /// the cracks turns (a crack that localises, points that stop loading)
  /// ends elsewhere than smaller steps would. Call right after the step's
  /// solve. Collective.
  double implicit_error();
  /// The step's error that step_tolerance() holds: implex_error() with
  /// IMPL-EX, implicit_error() otherwise. Collective.
  double step_error(std::int64_t& failed_points)
  {
    if (_implex)
      return implex_error(failed_points);
    failed_points = 0;
    return implicit_error();
  }
  /// The largest step_error() of a step before it is cut [-]: with IMPL-EX
  /// cracking.implex_tolerance, else cracking.implicit_tolerance; 0: the
  /// steps are not held to an error.
  double step_tolerance() const { return _implex ? _implex_tolerance : _implicit_tolerance; }
  /// The implicit cracks whose step error is read but whose steps are not
  /// held to it (CrackingPart::implicit_step_error_read, not
  /// implicit_steps_held; not in a rescue's step): step_error() is read
  /// all the same, for summary.json's implicit_error_max (a pass over the
  /// points a step).
  bool step_error_measured_only() const { return !_implex && _step_error_unheld; }
  /// The scene key that sets step_tolerance().
  const char* step_tolerance_key() const
  {
    return _implex ? "cracking.implex_tolerance" : "cracking.implicit_tolerance";
  }

  /// Whether a point uncracked in the committed state may crack (true; false:
  /// it answers elastically, whatever its stress: the predictor of a step,
  /// LoadStepSolver::set_crack_free_predictor).
  void allow_new_cracks(bool allow)
  {
    _new_cracks = allow;
    ++_trial_version;
  }

  /// The crack band at every point, from the committed state to the strain
  /// of the model's displacement (ghosts up to date): the trial state, and
  /// the forms' coefficients. False if a point failed (its equilibrium did
  /// not converge): the step is to be cut. At the displacement of the last
  /// evaluation, with trial_version() unchanged, that evaluation stands.
  /// Local to the process.
  bool evaluate() { return evaluate_points(true); }
  /// IMPL-EX: evaluate() as far as the tangent goes: each point's side of
  /// closure, and the tangent's coefficient where it changed; not the
  /// stresses nor the forces' coefficient. At fixed sides a step's cracks'
  /// forces are linear in the strain, so the kept K plus tangent gives them
  /// (Equilibrium::internal_forces, with thermal_expansion()). evaluate() at the
  /// same displacement completes it. False if a point's map failed.
  bool evaluate_tangent() { return evaluate_points(false); }
  /// The concrete's thermal expansion [1/degC]: the free strain of every
  /// cracking cell is thermal_expansion() dT I (forms/cracking.py's strain).
  double thermal_expansion() const { return _alpha; }
  /// Adds the forces of the last evaluate() to f (local with ghosts; the
  /// caller sums the ghosts into their owners) [N]. Not after an
  /// evaluate_tangent(), which leaves the forces' coefficient as it was (a
  /// logic error).
  void add_forces(std::span<double> f) const;
  /// Adds the tangent of the last evaluation (evaluate() or
  /// evaluate_tangent()) to A (before its final
  /// assembly) [N/mm].
  void add_tangent(Mat A) const;
  /// Adds to the stiffness K (assembled; the caller assembles it again)
  /// what moves its integral over the cracking cells to the crack band's
  /// points (forms/cracking.py, a_rule), where the cracks take C away: a
  /// crack that lost its stiffness keeps none of K. Once, on the model's K.
  void add_elastic_rule(Mat K) const;
  /// Adds to A what the tangent of the last evaluation adds beyond
  /// `assembled`, the tangent's point values last added to A (empty: none,
  /// the whole tangent), integrated over the cells where it changed only;
  /// `assembled` becomes the last evaluate()'s. So A keeps K plus the
  /// current tangent from call to call at the cost of the cells whose
  /// cracks changed (IMPL-EX: on the bench's corroded demo, a quarter of
  /// the cracking cells per step; Equilibrium::bulk_tangent). Only the
  /// cells whose tangent an evaluation changed since the last call are
  /// compared with `assembled`, if it is the last call's; another's is
  /// compared at every cell (a second such sum on the model).
  void add_tangent_change(Mat A, std::vector<double>& assembled);

  /// The energy the cracks release from the committed state to the
  /// model's displacement [N mm], this process's cells, in the form of
  /// Gutierrez (2004) at each point (Interface::energy_release for the
  /// joints): G = int 1/2 (sigma_0 : eps_e - sigma(eps_e) : eps_e0) dV,
  /// sigma_0 and eps_e0 the committed stress and strain. The linear part of
  /// sigma cancels (C is symmetric), and with the crack band's secant
  /// unloading it is 1/2 eps_e0 : (C_s0 - C_s) : eps_e, the cracks'
  /// dissipation to second order in the step, 0 where no crack grows.
  /// Evaluates the points as evaluate() does (trial state); adds dG/du =
  /// int 1/2 (sigma_0 - C_t^T eps_e0) : eps(v) dV to `gradient` (local with
  /// ghosts, as add_forces), C_t evaluate()'s (the loading tangent of a
  /// crack that grew in the last step, where the strain has not moved:
  /// loading_tangent). False if a point failed.
  bool energy_release(std::span<double> gradient, double& G);
  /// The energy the cracks dissipated from the committed state to the last
  /// evaluation, this process's cells [N mm] (the band's own account,
  /// CrackBandResult::dissipation).
  double dissipation();
  /// A crack through the cover: G_F times the slice's thickness times the
  /// cover (the tube's surface to the nearest outer face) [N mm]. The
  /// energy of the first brittle event of a corroded slice, the scale of
  /// dissipation control's steps (stepping/DissipationControl.cpp).
  double nominal_fracture_energy() const { return _nominal_fracture_energy; }

  /// The trial state becomes the committed one (a converged step).
  void commit();
  /// The trial state back to the committed one (a step to retry).
  void revert();
  /// Every point back to uncracked, and no IMPL-EX rescue on (a model
  /// reused for another scene).
  void reset();

  /// The trial state as a converged step commits it, at the model's
  /// displacement: with IMPL-EX the crack band's own update there
  /// (implicit_update, made once per displacement; commit() then finds it
  /// made), nothing otherwise. What the outputs read (add_stress_share).
  void settle()
  {
    if (_implex)
      implicit_update();
  }
  /// Totals of the state at the model's displacement, evaluated from the
  /// committed one: a converged step's, recorded before its commit
  /// (stepping/StepRecorder.h). Collective.
  CrackingTotals totals();
  /// The committed cracks at the edge of the cracking region (none where
  /// every concrete cell may crack). Collective.
  EdgeCracks edge_cracks() const { return edge_of(_committed, _opening); }

  /// Per cell, the widest crack of its points (of the last evaluate()):
  /// its normal opening w . n [mm] (0: none), unit normal and damage, into
  /// DG0 functions of the model's mesh (zero where the concrete may not
  /// crack).
  void cell_fields(dolfinx::fem::Function<double>& opening, dolfinx::fem::Function<double>& normal,
                   dolfinx::fem::Function<double>& damage) const;
  /// Adds the cracks' share of the stress, the integral of (sigma - C :
  /// eps_e) : tau over the cracking cells, to `L`, the vector of
  /// forms/elasticity.py's L_stress on its DG0 tensor space `S`: with it, L
  /// over the cells' volumes is the cell-averaged stress of the cracked
  /// concrete, not the elastic one (output/StressProjection.h). sigma of the
  /// trial state, settle()d: as the step commits it and as cell_fields
  /// reports the cracks (a logic error otherwise).
  void add_stress_share(std::span<double> L,
                        std::shared_ptr<const dolfinx::fem::FunctionSpace> S) const;

private:
  /// Where a cracking cell stands: its column and, on an outer face, what a
  /// gauge along the face reads across it (model/SurfaceCracks.h).
  struct CellPlace
  {
    double x = 0, y = 0;             ///< centre [mm]
    double weight = 0;               ///< its share of the slice's thickness
    double size = 0;                 ///< horizontal extent [mm]
    std::array<double, 8> outline{}; ///< corners (x, y) seen along the axis [mm]
    /// Outer faces it lies on: the face's index and horizontal tangent t,
    /// with the cell's extent along t and its centre's depth below the face
    /// [mm], and the half of its points nearest the face (where the gauge
    /// reads) with the cell's chord along t through each [mm].
    struct Face
    {
      int index = 0;
      double tx = 0, ty = 0, depth = 0;
      std::vector<int> points;
      std::vector<double> chords;
    };
    std::vector<Face> faces;
  };
  /// The places of the cracking cells on the slice `slice`; `positions`
  /// their points' (x, y, z) [mm].
  void place_cells(const Geometry& slice, const std::vector<double>& positions);
  /// The point's crack opening along the face tangent t, the crack strain
  /// t . eps_cr . t of point i [-].
  double crack_strain_along(std::size_t i, double tx, double ty) const;
  /// Gathers the columns on process 0 and reads the surface cracks there;
  /// into `t`. Collective.
  void read_surface(CrackingTotals& t) const;
  /// The cracks of `state` (_committed or _trial) at the region's edge,
  /// their normal openings in `opening` (_opening or _opening_trial).
  /// Collective.
  EdgeCracks edge_of(const std::vector<double>& state, const std::vector<double>& opening) const;

  /// IMPL-EX: the crack band's own update of every point from the committed
  /// state to the strain of the model's displacement, into the trial state
  /// (no forms' coefficients); once per converged step (the displacement
  /// does not move between the step's check, record and commit).
  void implicit_update();
  /// evaluate() (`stresses`) or evaluate_tangent().
  bool evaluate_points(bool stresses);
  /// The strain at every point from the model's displacement, into
  /// _strain_values.
  void evaluate_strains();
  /// Whether evaluate()'s last evaluation stands: nothing it read (the
  /// displacement, bit for bit, the state and settings) has changed since.
  bool evaluated_here() const;
  /// evaluate()'s implicit cracks: the crack band's update of every point
  /// from the committed state to _strain_values, into the trial state and
  /// the forms' coefficients. Whether every point's update converged.
  bool update_points();
  /// evaluate()'s IMPL-EX cracks: every point's side of closure at
  /// _strain_values by its step's secant maps (made at the step's first
  /// evaluation), and the tangent's coefficient where it changed. Whether
  /// every map answered; `tangent_changed`: whether some point's tangent
  /// changed.
  bool apply_sides(bool& tangent_changed);
  /// evaluate()'s IMPL-EX cracks after apply_sides(): every point's stress
  /// by the map of its side, into the trial stress and the forces'
  /// coefficient.
  void apply_stresses();
  /// IMPL-EX: every point's secant maps for the step (_secant), from the
  /// committed state and the last step's growth, extrapolated by
  /// set_extrapolation()'s ratio: of the history, or of the strain
  /// (cracking.implex_predictor).
  void make_secants();
  /// sqrt(int ds : C^-1 : ds / int s : C^-1 : s) over the cracking
  /// concrete, s the trial stress and ds = s - other(point) [-]: the steps'
  /// errors' norm (implex_error, implicit_error). Collective.
  double error_against_trial(const std::function<bulk::Voigt(std::size_t)>& other);
  /// Point i's (of cracking cell c) secant maps as make_secants() makes
  /// them, into `op`; `scratch` holds a crack state (state_size values).
  void predict_secant(std::size_t c, std::size_t i, std::vector<double>& scratch,
                      bulk::SecantOperator& op) const;
  /// Calls at(cell, point, strain, d_sigma, d_C) at every point, in the
  /// order of the points' arrays ([cell][point]): the strain is
  /// _strain_values', d_sigma the stress coefficient's values there, d_C()
  /// the tangent coefficient's. evaluate()'s loop (defined in
  /// BulkCrackingPoints.h).
  template <typename At> void for_each_point(At&& at);
  /// What a step's cracks hold changed (a commit, a reset, a new
  /// extrapolation): their tangent and secant maps are to be made again.
  void history_changed()
  {
    ++_tangent_version;
    ++_trial_version;
    _secant_current = false;
  }

  /// Whether `strain` is point i's committed strain (to a relative 1e-9).
  bool at_committed_strain(std::size_t i, const bulk::Voigt& strain) const;
  /// The tangent of point i (of cracking cell c) just beyond `strain` along
  /// itself: where a crack that grew in the last step starts the next one
  /// at its committed strain, its law's tangent is the secant (nothing
  /// loads yet), and a
  /// Newton step from it sees none of the softening ahead. The loading
  /// tangent instead keeps the first iteration of every step (and the
  /// gradient of energy_release()) on the path, as the joints' energy
  /// release does (interface::Interface::loading_probe). The probe's trial
  /// state is thrown away. Into `tangent`, which keeps the tangent at
  /// `strain` itself if the probe's update fails.
  void loading_tangent(std::size_t c, std::size_t i, const bulk::Voigt& strain,
                       bulk::Voigt66& tangent) const;

  /// The integral over this process's cracking cells of a value per point
  /// [value's unit times mm^3].
  double integrate(const std::function<double(std::size_t)>& value_at_point);

  /// A cracking cell's vertices [mm] (model/CellWidth.h's order).
  CellVertices vertices(std::size_t cell) const;
  /// The extent of a cracking cell's vertices along a unit normal n [mm].
  double extent(std::size_t cell, const bulk::Vec3& n) const;
  /// The crack band's width of a cracking cell along a crack's unit normal n
  /// [mm]: cracking.band_width's rule (model/CellWidth.h, bulk/CrackBand.h).
  double crack_band_width(std::size_t cell, const bulk::Vec3& n) const;
  /// The crack band's own update of point i (of cracking cell c) from its
  /// committed state to `strain`, the new state into `now`; its tangent only
  /// with bulk::Tangent::compute.
  bulk::CrackBandResult update_point(std::size_t c, std::size_t i, const bulk::Voigt& strain,
                                     std::span<double> now,
                                     bulk::Tangent tangent = bulk::Tangent::compute) const;

  std::shared_ptr<dolfinx::mesh::Mesh> _mesh;
  std::shared_ptr<const dolfinx::fem::Function<double>> _u; ///< the model's displacement [mm]
  bulk::CrackBand _band;
  std::vector<std::int32_t> _cells; ///< cracking cells (local, owned), sorted
  std::vector<std::size_t> _edge;   ///< of _cells, those at the region's edge (region_edge)
  double _radius = 0; ///< cracking.radius [mm]; 0 where it leaves no edge (all the concrete)
  std::vector<double> _strength;          ///< [cell][point] f_t factor of the field
  std::vector<double> _committed, _trial; ///< [cell][point][CrackBand::state_size]
  std::vector<double> _dissipated;        ///< [cell][point] committed energy density [N mm/mm^3]
  std::vector<double> _dissipated_trial;
  /// [cell][point] the crack grew (kappa) in the last committed step
  std::vector<bool> _loading;
  std::vector<double> _dissipated_step; ///< [cell][point] of the last evaluate() [N mm/mm^3]
  /// [cell][point][6] stress [MPa] and strain eps_e [-] of the last
  /// evaluate() and of the committed state (energy_release)
  std::vector<double> _stress_trial, _stress_committed, _strain_committed;
  /// [cell][point][3] crack opening in the crack's frame [n, s1, s2] [mm]
  std::vector<double> _opening, _opening_trial;
  std::vector<CellPlace> _places; ///< [cell]
  std::array<double, 2> _axis{};  ///< the tube axis (x, y) [mm]
  double _tube_radius = 0;        ///< [mm]
  double _visible_width = 0;      ///< cracking.visible_width [mm]
  /// The specimen's copies of the part meshed (above 1: cut by symmetry,
  /// its faces do not close round the slice).
  int _copies = 1;
  double _nominal_fracture_energy = 0; ///< [N mm]
  bool _new_cracks = true;             ///< allow_new_cracks
  double _dt = 0;                      ///< set_time_increment [mm of push]
  bool _row_band = false;              ///< cracking.band_width = "row"
  /// cracking.integration = "implex", or an implicit run's rescue
  /// (set_implex_rescue)
  bool _implex = false;
  double _implex_tolerance = 0;   ///< cracking.implex_tolerance
  double _implicit_tolerance = 0; ///< cracking.implicit_tolerance
  /// CrackingPart::implicit_step_error_read and not implicit_steps_held
  bool _step_error_unheld = false;
  bool _predict_strain = false; ///< cracking.implex_predictor = "strain"
  bool _rescue = false;         ///< set_implex_rescue
  bool _rescue_allowed = false; ///< cracking.implex_rescue
  double _E = 0, _nu = 0;       ///< the concrete's [MPa], [-]
  double _alpha = 0;            ///< the concrete's thermal expansion [1/degC]
  double _extrapolation = 0;    ///< set_extrapolation
  /// IMPL-EX: the trial state is implicit_update()'s, and no evaluate()
  /// came after it
  bool _trial_implicit = false;
  /// IMPL-EX: points whose update failed in the last implicit_update()
  std::int64_t _implicit_failures = 0;
  /// [point] IMPL-EX (and the implicit cracks' step error and rescue): the
  /// growth of kappa in the last committed step [mm]
  std::vector<double> _kappa_step;
  /// The same, implex_predictor = "strain": [point][6] the growth of the
  /// strain in the last committed step (empty before the first)
  std::vector<double> _strain_step;
  /// [point] IMPL-EX: the side of closure of the last evaluate(): 0 open,
  /// 1 closed, 2 neither (its map failed, elastic); its tangent changes
  /// with it
  std::vector<std::uint8_t> _closed;
  /// [cell] an evaluation changed a point's tangent coefficient since the
  /// last add_tangent_change()
  std::vector<std::uint8_t> _tangent_written;
  /// The `assembled` of the last add_tangent_change(), whose values
  /// _tangent_written's unmarked cells hold
  const std::vector<double>* _tangent_written_for = nullptr;
  /// [point] IMPL-EX: the response at the committed state and the
  /// extrapolated history as linear maps (CrackBand::secant_operator), the
  /// same at every evaluation of a step; current unless something was
  /// committed or extrapolated anew since they were computed
  std::vector<bulk::SecantOperator> _secant;
  bool _secant_current = false;
  std::uint64_t _tangent_version = 0; ///< tangent_version()
  std::uint64_t _trial_version = 0;   ///< trial_version()
  struct Evaluated
  {
    bool valid = false;              ///< an evaluation was made
    std::uint64_t trial_version = 0; ///< trial_version() after it
    std::vector<double> u;           ///< its displacement (with ghosts) [mm]
    bool ok = false;                 ///< its result
    bool stresses = false;           ///< the stresses made too (not evaluate_tangent())
  } _evaluated;                      ///< evaluate()'s last evaluation
  std::shared_ptr<dolfinx::fem::Constant<double>> _dT;
  std::shared_ptr<dolfinx::fem::Function<double>> _d_sigma, _d_C;
  /// add_tangent_change()'s difference of d_C (on the changed cells)
  std::shared_ptr<dolfinx::fem::Function<double>> _d_C_change;
  /// energy_release()'s dG/du density (on _d_sigma's space) and a scalar
  /// per point (integrate())
  std::shared_ptr<dolfinx::fem::Function<double>> _release_gradient, _point_value;
  /// add_stress_share()'s sigma - C : eps_e (on _d_sigma's space), and its
  /// form (made on the caller's space, again for another: an output's cache)
  std::shared_ptr<dolfinx::fem::Function<double>> _stress_share;
  mutable std::shared_ptr<dolfinx::fem::Form<double>> _L_stress_share;
  std::unique_ptr<dolfinx::fem::Expression<double>> _strain;
  std::shared_ptr<dolfinx::mesh::MeshTags<std::int32_t>> _region;
  /// _L_release: L_crack on _release_gradient; _M: the integral of _point_value
  std::shared_ptr<dolfinx::fem::Form<double>> _L, _a, _M, _L_release;
  std::vector<double> _strain_values; ///< [cell][point][6], of the last evaluate()
};
} // namespace pushout::model

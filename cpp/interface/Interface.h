// The joint elements: kinematics, quadrature and assembly of the interface
// forces  f = int_Gamma N^T t(w) dGamma  and their tangent, for all layers.
//
// Why C++ and not UFL: after the node duplication the steel facet and the
// concrete facet of a pair belong to different cells that share no mesh
// entity, so DOLFINx 0.5.2 sees two exterior facets, not one interior facet,
// and a UFL dS integral cannot couple them. This kernel pairs them itself:
//   w(xi) = sum_a N_a(xi) (u_concrete,a - u_steel,a)         (jump, mm)
//   f_concrete,a = +int N_a t dA,   f_steel,a = -int N_a t dA  (N)
// with t and D = dt/dw from the laws in the local frame [n, s1, s2] of each
// quadrature point: n from steel to concrete, s1 the tangent closest to +z
// (axial for the slice), s2 = n x s1. The frame is fixed at the reference
// geometry (small displacements). Layers superpose (paper §4.3): tractions
// and tangents add.
//
// A mirror set (a crack plane on a symmetry plane of a half or quarter
// model, mesh/symmetry.h) has one face meshed: its minus nodes are its plus
// nodes, standing for their mirror images about the plane (unit normal m):
// u_minus = M u_plus, M = I - 2 m m^T, and their forces act back through
// M (f_plus += M f_minus). So w = 2 (m . u) m, a pure opening, and the
// weights are halved: the model holds half the plane's energy, as it holds
// half (a quarter) of the bulk's.
#pragma once

#include "../laws/InterfaceLaw.h"
#include "../mesh/MeshData.h"
#include "InterfaceState.h"
#include "Quadrature.h"
#include <array>
#include <cmath>
#include <memory>
#include <petscmat.h>
#include <span>
#include <vector>

namespace pushout::interface
{
/// Quantities at one quadrature point, for output.
struct PointOutput
{
  laws::Vec3 t;                            ///< total traction, local frame [MPa]
  laws::Vec3 w;                            ///< jump, local frame [mm]
  std::vector<std::array<double, 2>> slip; ///< per layer, local (s1, s2) [mm]
  std::vector<double> damage;              ///< per layer
};

class Interface
{
public:
  /// `pair_blocks[2 n p + i]`: local dof block of node i of pair p, with n
  /// = 4 or 9 nodes per side in the order of Quadrature.h (steel nodes 0 to
  /// n-1, then concrete). `x` are the corner coordinates of the pairs'
  /// steel side, [pair][4][3] (the facets are bilinear). `quadrature` is for
  /// n nodes.
  /// `mirror`: nonzero for a mirror set, the symmetry plane's unit normal
  /// (then the minus blocks are the plus blocks).
  Interface(std::vector<std::int32_t> pair_blocks, const std::vector<double>& x,
            Quadrature quadrature, std::vector<std::unique_ptr<laws::InterfaceLaw>> layers,
            std::array<double, 3> mirror = {0, 0, 0});

  /// A mirror set (its minus nodes are the plus nodes' mirror images).
  bool mirrored() const { return _mirrored; }
  /// A mirror set's symmetry-plane unit normal m (zero otherwise): its
  /// joints see only the plus nodes' displacement along m (jump 2 (u.m) m).
  const std::array<double, 3>& mirror_normal() const { return _mirror; }

  std::size_t num_pairs() const { return _num_pairs; }
  /// Nodes per side of a joint element (4, or 9 for mesh.degree = 2).
  int nodes_per_side() const { return _n; }
  std::size_t num_points() const { return num_pairs() * points_per_pair(); }
  std::size_t points_per_pair() const { return _q.weights.size(); }
  std::size_t num_layers() const { return _layers.size(); }
  std::span<const std::int32_t> pair_blocks() const { return _blocks; }
  const InterfaceState& state() const { return _state; }
  InterfaceState& state() { return _state; }

  /// Pseudo-time increment of the current step, for viscous laws (the
  /// scenario's time unit; 0: none).
  void set_time_increment(double dt) { _inputs.dt = dt; }

  /// New laws for the layers (a fit's or a sweep's next evaluation on the
  /// same mesh): the state back to zero, as after construction.
  void set_layers(std::vector<std::unique_ptr<laws::InterfaceLaw>> layers);

  /// The oxide layer of the corrosion stage: free normal opening g0 [mm] and
  /// normal compliance [mm^3/N], read by laws that model it (oxide_friction).
  void set_oxide(double gap, double compliance)
  {
    _inputs.oxide_gap = gap;
    _inputs.oxide_compliance = compliance;
  }

  /// Evaluates the laws at the displacement `u` (local blocked array,
  /// ghosts included), writes the trial state, adds the interface forces to
  /// `f` (same layout) and, if `A` is given, the tangent to `A` (blocked
  /// local indices, ADD_VALUES; the caller assembles A). Returns false if
  /// any law failed.
  bool assemble(std::span<const double> u, std::span<double> f, Mat A);

  /// Commits the trial state of the last evaluation (assemble(), at the
  /// converged displacement of a step) and keeps its softening tractions and
  /// jumps as the start of the next step, t0 and w0 of energy_release().
  void commit();

  /// The energy the softening layers (InterfaceLaw::fracture_energy > 0)
  /// release from the committed state to the jumps of `u` [N mm], in the
  /// form of Gutierrez (2004) at each point:
  ///   G = int_Gamma 1/2 (t0 . w - t(w) . w0) dA,
  /// t the softening layers' traction, t0 and w0 the committed ones. For a
  /// damage law with secant unloading it is 1/2 k (D - D0) w0 . w, the
  /// damage's dissipation to second order in the step, and 0 for elastic
  /// loading or unloading. Friction layers are left out: their dissipation
  /// grows whichever way the tube slips, and would let a step slip back.
  /// (cohesive_friction is one law: its friction counts, half its work.)
  /// Evaluates every layer at `u` as assemble() does (trial state,
  /// tractions); adds dG/du to `gradient` (the layout of f in assemble();
  /// the caller sums ghosts to owners) and sets G (this process's pairs).
  /// Returns false if a law failed.
  bool energy_release(std::span<const double> u, std::span<double> gradient, double& G);

  /// The energy dissipated from the committed state to the last evaluation
  /// over this process's pairs, as the laws report it
  /// (laws::LawResult::dissipation) [N mm]; by the softening layers only if
  /// `softening_only`.
  double dissipation(bool softening_only = false) const;

  /// The energy the layers release to full softening over this process's
  /// pairs, sum of InterfaceLaw::fracture_energy times the area [N mm].
  double fracture_energy() const;

  /// Output quantities of quadrature point q of pair p: the tractions of
  /// the last evaluation (assemble()), the jump of `u`, the trial state's
  /// slips and damage. After a converged step all are the converged state's.
  PointOutput point_output(std::span<const double> u, std::size_t p, std::size_t q) const;

  /// Adds the coefficients of the linear functional
  ///   u -> int_Gamma w . v dA   [mm^3]
  /// for `v` in the local frame (n, s1, s2): {0, 1, 0} the axial jump,
  /// {1, 0, 0} the normal opening, integrated over this process's pairs, to
  /// `a` (local blocked layout, ghosts included; the caller sums ghosts to
  /// owners). Divided by the area it is a mean jump, the control variable
  /// of path following (Model::mean_jump_functional).
  void add_jump_functional(const laws::Vec3& v, std::span<double> a) const;

  /// Area of the interface on this process [mm^2].
  double area() const;

  /// The normal opening w . n of `u` near a set of plus-side nodes (a crack
  /// plane's mouth on the slice's outer face), read where the laws evaluate
  /// it: at the quadrature points whose shape functions give those nodes a
  /// weight above one half (the points of the adjacent pairs nearer to them:
  /// the nodes themselves with nodal quadrature, the outer row of Gauss
  /// points otherwise). `plus_blocks`: local dof blocks of the nodes, sorted.
  /// Returns this process's {int w_n dA [mm^3], int dA [mm^2]}.
  std::array<double, 2> opening_near(std::span<const double> u,
                                     std::span<const std::int32_t> plus_blocks) const;

  /// Integral of each layer's normal traction over this process's pairs
  /// [N], from the last evaluation (assemble(): after a converged step, its
  /// state; stored, not re-evaluated, since a viscous law's update from the
  /// new committed state would advance it again).
  std::vector<double> normal_force() const;

  /// This process's share of the spread of the axial shear traction t_s1
  /// (all layers) over the interface, from the last evaluation as above:
  /// int t_s1 dA [N], int |t_s1| dA [N], int t_s1^2 dA [N MPa], its
  /// smallest and largest value at a quadrature point [MPa].
  struct ShearSpread
  {
    double integral = 0, integral_of_magnitude = 0, integral_of_square = 0;
    double min = INFINITY, max = -INFINITY;
  };
  ShearSpread shear_spread() const;

  /// Whether layer l softens (InterfaceLaw::softens: a damage law).
  bool softens(std::size_t layer) const { return _softens[layer]; }

  /// Of layer l over this process's pairs: int D dA [mm^2] and the largest
  /// D of its damage (the trial state: after a converged step, its state).
  std::array<double, 2> damage_of(std::size_t layer) const;

  /// Resultant int t dA of the tractions over this process's pairs, global
  /// frame [N] (the internal force on the concrete side; the tube acts on
  /// the concrete with its opposite), from the last evaluation as above.
  laws::Vec3 resultant() const;

  /// The local frame [n, s1, s2] (row-major 3x3) at point (p, q).
  std::span<const double> frame(std::size_t p, std::size_t q) const
  {
    return {_frame.data() + 9 * (p * _q.weights.size() + q), 9};
  }

  /// Largest number of history variables of a law per point.
  static constexpr int max_state_size = 16;

private:
  laws::Vec3 jump(std::span<const double> u, std::size_t p, std::size_t q) const;
  /// Evaluates every layer at point i with jump w (local frame): the trial
  /// state, the layer tractions and the jump are kept; t, D the totals.
  /// False if a law failed.
  /// `D_softening`, if given: the tangent of the softening layers only.
  bool evaluate(std::size_t i, const laws::Vec3& w, laws::Vec3& t, laws::Mat3& D,
                laws::Mat3* D_softening = nullptr);
  /// The traction of the softening layers at point i, last evaluation, into t[3].
  void softening_traction(std::size_t i, double* t) const;
  /// Adds int N^T R^T v dA of point (p, q) to f: +v on the concrete (plus)
  /// side, -v on the steel (minus) side (local-frame v, global f).
  void scatter(std::size_t p, std::size_t q, const laws::Vec3& v, std::span<double> f) const;
  /// Relative size of the step beyond w0 at which energy_release() takes
  /// the loading tangent where the jump has not moved.
  static constexpr double loading_probe = 1e-9;

  /// The minus side's value of a plus-side vector v: M v (mirror set) or v.
  laws::Vec3 minus_side(const laws::Vec3& v) const;

  std::vector<std::int32_t> _blocks;
  std::size_t _num_pairs;
  std::array<double, 3> _mirror; ///< the symmetry plane's unit normal (mirror set)
  bool _mirrored;
  int _n; ///< nodes per side
  Quadrature _q;
  std::vector<double> _N;     ///< shape values [quad point][node]
  std::vector<double> _Ke;    ///< element tangent scratch, (6 n)^2
  std::vector<double> _dA;    ///< weight * area element [mm^2]
  std::vector<double> _frame; ///< rows n, s1, s2 per point
  std::vector<std::unique_ptr<laws::InterfaceLaw>> _layers;
  InterfaceState _state;
  std::vector<double> _t_layer; ///< traction per point and layer, local frame, last evaluation
  const double* layer_traction(std::size_t i, std::size_t l) const
  {
    return _t_layer.data() + 3 * (i * _layers.size() + l);
  }
  std::vector<double> _w_last; ///< jump per point, local frame, last evaluation [mm]
  std::vector<bool> _softens;  ///< per layer: InterfaceLaw::softens()
  /// The state, tractions and step inputs of the layers as before any step.
  void reset();
  std::vector<double> _t0, _w0; ///< softening traction, jump per point at the last commit
  /// per point: all layers, softening layers; last evaluation [N/mm]
  std::vector<double> _dissipation_last;
  laws::StepInputs _inputs; ///< inputs of the current step
};
} // namespace pushout::interface

// Condensation of the linear bulk onto the jumps of the joint elements.
//
// Only the joint elements are nonlinear, and they see the displacement
// only through the jumps d = u_plus - u_minus of their node pairs (3 per
// pair, 1 for a mirror crack's, below; the steel-concrete interface's pairs
// are (steel, concrete), a crack plane's its two faces): their nodal forces are f_int = G^T F(d),
// with G the difference operator (d = G x) and F the forces on the plus nodes. A node may belong to
// pairs of two sets (a crack's root node is concrete in the interface and a face of the crack): G
// then has dependent rows, and Newton's iterates stay in its range (R below maps it to itself), so
// each set's forces are evaluated with its own minus nodes at zero.
//
// Everything else is linear. With
//   J0 = K with unit constrained rows, plus eps G^T G on the free rows of
//        the interface nodes (a linear joint of stiffness eps [N/mm] per
//        node pair that makes J0 regular when a body is held only by the
//        interface, like the tube of the full model, free in x),
//   b  = the linear right-hand side (loads at free rows, prescribed values
//        at constrained ones; Equilibrium::linear_rhs),
// the whole model's F(x) = 0 reads  J0 x = b - E_I G_I^T (F(d) - eps d)
// (E_I G_I^T: onto the free interface rows). Hence, exactly,
//   x = J0^-1 b - Z r,    Z = J0^-1 E_I G_I^T,   r = F(d) - eps d,
//   R(d) = d + C r - d_b = 0,   C = G Z,   d_b = G J0^-1 b,
// a dense system of 3 unknowns per node pair (a quarter of the paper's
// mesh: 459; fewer for a mirror crack) that the Newton and arc-length solvers take in place of the
// whole model. R is scaled by k = 1 / mean diag(C) [N/mm] so that its
// tolerances are forces. Jacobian: k (I - eps C + C dF/dd), dF/dd sparse;
// the Krylov solver applies it matrix-free (a sparse and a dense product),
// and it is formed only when the lagged preconditioner is refreshed.
//
// One MUMPS factorisation of J0 with the interface dofs last gives their
// Schur complement S; Z restricted to the interface is S^-1 E_I G_I^T
// (dense), so C costs no more solves with J0. Loads: d_b is linear in b and
// the loads of a run span a few directions (thermal load, push), so it
// comes from an orthonormal basis of the b solved so far; a solve with J0
// happens only when b leaves that span. After a step: the interface
// displacements from the basis and Z (cheap), or the whole x by one solve
// with J0 (expand(), when outputs need the bulk).
//
// A mirror set's pair (a crack on a symmetry plane: its minus node is the
// plus node's mirror image, interface/Interface.h) has the plus node's
// displacement as its "jump", as if its minus node were fixed; the set's
// forces depend on it alone and G is the identity there. Its joints see only
// the component along the plane's normal m (the opening 2 u.m), and when m
// is a coordinate axis (symmetry planes are) only that component is a jump:
// the two others carry no joint force, so they stay bulk dofs of J0 (no eps
// spring), and the system has 1 unknown for such a pair instead of 3. The
// tangents dF/dd are assembled per node pair (3 x 3 blocks, "extended"
// components) and read at the kept ones.
//
// One process only (PETSc 3.18 has no parallel MUMPS Schur complements);
// the Newton systems are dense LU (PETSc's, LAPACK), lagged as on the whole
// model.
#pragma once

#include "../scene/SceneParts.h"
#include "Equilibrium.h"
#include "NonlinearProblem.h"
#include "SinglePrecision.h"
#include "SymmetricMatrix.h"
#include <string>
#include <utility>
#include <vector>

namespace pushout::solver
{
class Condensation : public NonlinearProblem
{
public:
  /// Largest number of interface dofs condensed by default (two dense
  /// matrices of the node-pair jumps, 3000 x 3000).
  static constexpr std::int64_t default_max_dofs = 6000;

  /// Whether the model can be condensed (a linear bulk, its interface has
  /// node pairs, one process, an LU preconditioner); `why` says why not.
  static bool possible(const Equilibrium& eq, std::string& why);
  /// The same from the numbers alone (the run's processes and interface
  /// dofs, and whether the concrete may crack), so that it can be decided
  /// before the model exists.
  static bool possible(int processes, std::int64_t interface_dofs, bool bulk_cracks,
                       std::string& why);

  /// Whether Newton runs on the condensed system for solver.condensation =
  /// `mode`: "auto" condenses what is possible up to default_max_dofs. `why`
  /// says why not ("" when "off" was asked for); "on" when it is not
  /// possible is the caller's error to report.
  static bool chosen(SolverPart::Condensation mode, int processes, std::int64_t interface_dofs,
                     bool bulk_cracks, std::string& why);

  /// Number of joint dofs, both sides of every node pair (6 per pair).
  static std::int64_t interface_dofs(const model::Model& model);
  /// Unknowns of the condensed system of `model` (size() once built).
  static std::int64_t unknowns(const model::Model& model);

  /// Factors J0 and computes C. The constrained dofs of `eq` (set by the
  /// scenario, values not needed) must stay the same while it is used.
  explicit Condensation(Equilibrium& eq);
  ~Condensation();
  Condensation(const Condensation&) = delete;
  Condensation& operator=(const Condensation&) = delete;

  /// Why C is not accurate enough to solve on (its round-off asymmetry
  /// above trusted_asymmetry, SymmetricMatrix.h), or "" if it is.
  const std::string& untrusted() const { return _untrusted; }
  /// max|C - C^T| / max|C| as computed, before C was symmetrised.
  double asymmetry() const { return _asymmetry; }

  /// Whether GMRES applies C and the lagged preconditioner's LU in single
  /// precision (SinglePrecision.h; the default) or in double. Set before
  /// the first solve.
  void set_single_precision(bool single);

  /// Unknowns of the condensed system (3 per node pair, 1 per pair of a
  /// mirror set on a coordinate plane).
  std::int64_t size() const { return std::int64_t(_minus.size()); }

  /// d = the jumps of the whole-model x.
  void restrict_to(Vec x, Vec d) const;
  /// The jump-space coefficients of a whole-model functional of the jumps
  /// (a . x = a_d . d; a must be opposite on the two sides of each pair).
  void restrict_functional(Vec a, Vec a_d) const;
  /// The whole-model x of jumps d at the current loads (one solve).
  void expand(Vec d, Vec x);
  /// Only the interface and constrained entries of x from d (no solve);
  /// the other entries are left alone, among them a mirror crack's
  /// tangential components (bulk dofs here, no jump).
  void expand_interface(Vec d, Vec x);
  /// Forgets the load directions solved so far: the next loads are solved
  /// afresh, as in a first run (bit for bit).
  void forget_loads();

  // NonlinearProblem on the jumps.
  Mat create_matrix() const override;
  Mat create_operator() const override;
  void copy_jacobian(Mat J, Mat P) const override;
  Vec create_vector() const override;
  bool residual(Vec d, Vec R) override;
  bool residual(Vec d, Vec R, double& reaction_norm) override;
  bool jacobian(Vec d, Mat J) override;
  double residual_floor(Vec d) override;
  bool energy_release(Vec d, double& G, Vec gradient) override;
  void configure(KSP ksp) const override;
  void forget_trial_state() override { _eq.forget_trial_state(); }

private:
  /// The constructor's work, the steps below in turn; release() frees what
  /// they made (also when one throws part way).
  void build();
  void release() noexcept;
  /// Numbers the jumps set by set (3 per node pair, 1 for a pair of a mirror
  /// set on a coordinate plane: _minus, _plus, _ext_of_jump, _jump_of_ext,
  /// _set_end) and the joint dofs (_gamma, and each jump's ends in it).
  /// Returns, per set, the node pair of each block (its plus blocks; -1 for
  /// the others): the local-to-global map of its tangent.
  std::vector<std::vector<std::int32_t>> number_jumps();
  /// Which ends of each jump are free dofs under the current constraints (a
  /// mirror set's minus end never is: it stands for the plus node's image).
  void mark_free_ends();
  /// J0 = K with unit constrained rows, plus eps G^T G on the free rows of
  /// the interface dofs; eps [N/mm] a hundredth of K's mean diagonal there.
  void assemble_J0();
  /// One MUMPS factorisation of J0 with the joint dofs (_gamma) last, and
  /// the dense LU of their Schur complement S; throws a clear error if
  /// MUMPS fails (a zero pivot: a body held by nothing).
  void factor_J0();
  /// Z on the joint dofs = S^-1 E_I G_I^T (dense).
  void compute_Z();
  /// C = G Z (dense) and the residual scale k = 1 / mean diag(C).
  void compute_C();
  /// C's round-off asymmetry (asymmetry(), untrusted()); then C symmetrised
  /// and packed for its products.
  void check_symmetry();
  /// The tangent dF/dd of each set: sparse, 3 x 3 blocks of node pairs
  /// (extended components), its plus blocks mapped to their pairs by
  /// `pair_of_block` (number_jumps()).
  void create_tangents(const std::vector<std::vector<std::int32_t>>& pair_of_block);
  /// The scratch vectors and the whole-model arrays of the joints' kernel.
  void create_work_vectors();
  /// F(d) and r = F - eps d into _r (and dF/dd into _T if asked); false if
  /// a law failed.
  bool interface_forces(Vec d, bool tangent, double* force_norm = nullptr);
  /// Puts the jumps d (array) of set s into _u (its minus nodes at 0, plus
  /// nodes at d) and zeroes its nodes in _f; the set's range [first, end)
  /// of the jumps.
  std::pair<std::size_t, std::size_t> load_set(std::size_t s, const double* d);
  /// J = I - eps C, the Jacobian's part without the joints (unscaled).
  void set_linear_part(Mat J) const;
  /// The Jacobian at the last jacobian() call, explicitly, into J.
  void form_jacobian(Mat J) const;
  static PetscErrorCode operator_mult(Mat J, Vec v, Vec y);
  /// The coefficients of the current b on the basis (extended if needed).
  const std::vector<double>& load_coefficients();
  /// Adds sum_k c_k v_k to y.
  static void combine(const std::vector<double>& c, const std::vector<Vec>& v, Vec y);

  Equilibrium& _eq;
  std::vector<std::int32_t> _minus, _plus; ///< whole-model dof of each jump (plus - minus)
  std::vector<PetscInt> _ext_of_jump;      ///< each jump's extended component (3 per pair)
  std::vector<PetscInt> _jump_of_ext;      ///< each extended component's jump, or -1
  std::vector<std::uint8_t> _minus_free, _plus_free;
  std::vector<std::uint8_t> _mirror;           ///< a mirror set's pair: the jump is the plus node's
  std::vector<std::size_t> _set_end;           ///< end of each set's jumps (interface, cracks)
  std::vector<PetscInt> _gamma;                ///< the joint dofs, each once (sorted)
  std::vector<PetscInt> _pos_minus, _pos_plus; ///< positions of a jump's dofs in _gamma
  int _constraint_version;                     ///< of the constraints it was built for
  int _load_version = -1;                      ///< of the loads of _load_c
  std::vector<double> _load_c;                 ///< coefficients of the current b on the basis
  double _eps = 0;                             ///< J0's joint stiffness [N/mm]
  double _k = 1;                               ///< residual scale [N/mm]
  std::string _untrusted;                      ///< untrusted()
  double _asymmetry = 0;                       ///< asymmetry()
  double _C_norm = -1;                         ///< a bound of ||C||_2, once needed [mm/N]
  Mat _J0 = nullptr, _factor = nullptr;
  Mat _Z = nullptr;                  ///< Z on the joint dofs (_gamma), dense
  Mat _C = nullptr;                  ///< C = G Z, dense (symmetric)
  SymmetricMatrix<double> _C_packed; ///< C's upper triangle, for its products
  bool _single = false;              ///< GMRES in single precision (set_single_precision)
  SymmetricMatrix<float> _C_single;  ///< the same in single precision, for the Jacobian's action
  std::vector<Mat> _T;               ///< dF/dd of each set, sparse (node-pair blocks, extended)
  Vec _b = nullptr;                  ///< whole model: right-hand side
  Vec _r = nullptr;                  ///< jumps: F(d) - eps d
  Vec _d_b = nullptr;                ///< jumps: d_b of the current loads
  Vec _g = nullptr;                  ///< interface dofs: scratch
  Vec _rest = nullptr;               ///< whole model: scratch
  Vec _Tv = nullptr;                 ///< jumps: scratch
  Vec _v_ext = nullptr, _Tv_ext = nullptr; ///< extended components: scratch
  Vec _Zr = nullptr;                       ///< interface dofs: scratch
  std::vector<double> _u, _f;              ///< whole-model local arrays for the interface kernel
  /// Orthonormal load directions, their J0^-1 on the interface dofs, and
  /// their jumps d_b.
  std::vector<Vec> _basis, _basis_g, _basis_d;
  std::vector<ISLocalToGlobalMapping> _l2g; ///< per set: its plus blocks -> node pairs
};
} // namespace pushout::solver

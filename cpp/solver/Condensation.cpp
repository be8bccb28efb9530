#include "Condensation.h"
#include "../common/petsc_check.h"
#include "Vector.h"
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <dolfinx/common/IndexMap.h>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace pushout::solver
{
using petsc::check;

namespace
{
/// Load directions kept before the basis starts again.
constexpr std::size_t max_basis = 6;

/// Node pairs of this process, per set of joint elements (the interface,
/// then the crack planes): (minus block, plus block), sorted by plus block.
/// Within a set every plus node has one partner; a node may be in pairs of
/// two sets (a crack's root node: concrete in the interface, a face of the
/// crack).
std::vector<std::vector<std::pair<std::int32_t, std::int32_t>>>
node_pairs(const model::Model& model)
{
  std::vector<std::vector<std::pair<std::int32_t, std::int32_t>>> sets;
  for (const interface::Interface* joints : model.joints())
  {
    const auto b = joints->pair_blocks();
    const int n = joints->nodes_per_side();
    std::vector<std::pair<std::int32_t, std::int32_t>> pairs; // (plus, minus) to sort
    for (std::size_t p = 0; p < joints->num_pairs(); ++p)
      for (int a = 0; a < n; ++a)
        pairs.emplace_back(b[2 * n * p + n + a], b[2 * n * p + a]);
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    for (std::size_t k = 1; k < pairs.size(); ++k)
      if (pairs[k].first == pairs[k - 1].first)
        throw std::logic_error("condensation: a plus-side joint node has two partners");
    for (auto& [plus, minus] : pairs)
      std::swap(plus, minus);
    sets.push_back(std::move(pairs));
  }
  return sets;
}

/// The components of a set's node pairs that are jumps: all 3, or a mirror
/// set's normal axis when its normal is a coordinate axis.
std::array<bool, 3> jump_components(const interface::Interface& joints)
{
  const std::array<double, 3>& m = joints.mirror_normal();
  for (int a = 0; a < 3; ++a)
    if (joints.mirrored() && std::abs(m[a]) == 1.0 && m[(a + 1) % 3] == 0.0 &&
        m[(a + 2) % 3] == 0.0)
      return {a == 0, a == 1, a == 2};
  return {true, true, true};
}

/// Column-major dense array of a SEQDENSE matrix and its leading dimension.
struct Dense
{
  Mat A;
  double* a = nullptr;
  PetscInt lda = 0;
  explicit Dense(Mat M) : A(M)
  {
    check(MatDenseGetLDA(A, &lda), "MatDenseGetLDA");
    check(MatDenseGetArray(A, &a), "MatDenseGetArray");
  }
  ~Dense() { petsc::check_nothrow(MatDenseRestoreArray(A, &a), "MatDenseRestoreArray"); }
  double& operator()(PetscInt i, PetscInt j) { return a[i + j * lda]; }
};
} // namespace

std::int64_t Condensation::interface_dofs(const model::Model& model)
{
  std::int64_t pairs = 0;
  for (const auto& set : node_pairs(model))
    pairs += std::int64_t(set.size());
  return 6 * pairs;
}

std::int64_t Condensation::unknowns(const model::Model& model)
{
  const auto joints = model.joints();
  const auto sets = node_pairs(model);
  std::int64_t n = 0;
  for (std::size_t s = 0; s < sets.size(); ++s)
  {
    const std::array<bool, 3> kept = jump_components(*joints[s]);
    n += std::int64_t(sets[s].size()) * std::count(kept.begin(), kept.end(), true);
  }
  return n;
}

bool Condensation::possible(const Equilibrium& eq, std::string& why)
{
  int size = 1;
  MPI_Comm_size(PetscObjectComm(reinterpret_cast<PetscObject>(eq.model().stiffness())), &size);
  return possible(size, interface_dofs(eq.model()), why);
}

bool Condensation::possible(int processes, std::int64_t n_interface, std::string& why)
{
  char pc_type[64] = "";
  PetscBool pc_set = PETSC_FALSE;
  check(PetscOptionsGetString(nullptr, nullptr, "-pc_type", pc_type, sizeof(pc_type), &pc_set),
        "PetscOptionsGetString");
  if (processes > 1)
    why = "more than one process";
  else if (pc_set && std::string(pc_type) != "lu")
    why = std::string("-pc_type ") + pc_type + " (condensed systems are solved by dense LU)";
  else if (n_interface == 0)
    why = "no interface";
  else
    return true;
  return false;
}

bool Condensation::chosen(const std::string& mode, int processes, std::int64_t n_interface,
                          std::string& why)
{
  if (mode == "off")
    return false;
  if (!possible(processes, n_interface, why))
    return false;
  if (mode == "auto" && n_interface > default_max_dofs)
  {
    why = std::to_string(n_interface) + " interface dofs, more than " +
          std::to_string(default_max_dofs);
    return false;
  }
  return true;
}

Condensation::Condensation(Equilibrium& eq) : _eq(eq)
{
  try
  {
    build();
  }
  catch (...)
  {
    release(); // what was made so far
    throw;
  }
}

void Condensation::build()
{
  Equilibrium& eq = _eq;
  std::string why;
  if (!possible(eq, why))
    throw std::runtime_error("cannot condense the bulk: " + why);
  const model::Model& model = eq.model();
  const auto& map = model.index_map();
  const std::int32_t n_blocks = map.size_local() + map.num_ghosts();
  // The jumps: 3 per node pair (1 for a mirror set on a coordinate plane),
  // set by set; the l2g of each set maps its plus blocks to their pairs
  // (its minus blocks to nothing).
  std::vector<std::vector<std::int32_t>> pair_of_block;
  std::int32_t n_pairs = 0;
  const auto joints = model.joints();
  const auto sets = node_pairs(model);
  for (std::size_t s = 0; s < sets.size(); ++s)
  {
    const std::array<bool, 3> kept = jump_components(*joints[s]);
    pair_of_block.emplace_back(n_blocks, -1);
    for (const auto& [minus, plus] : sets[s])
    {
      pair_of_block.back()[plus] = n_pairs;
      for (int c = 0; c < 3; ++c)
      {
        if (!kept[c])
        {
          _jump_of_ext.push_back(-1);
          continue;
        }
        _jump_of_ext.push_back(PetscInt(_minus.size()));
        _ext_of_jump.push_back(3 * n_pairs + c);
        _minus.push_back(3 * minus + c);
        _plus.push_back(3 * plus + c);
      }
      ++n_pairs;
    }
    _set_end.push_back(_minus.size());
  }
  const PetscInt n_ext = 3 * n_pairs;
  const PetscInt n = PetscInt(_minus.size());
  // The interface dofs: every dof of a pair, once.
  _gamma.assign(_minus.begin(), _minus.end());
  _gamma.insert(_gamma.end(), _plus.begin(), _plus.end());
  std::sort(_gamma.begin(), _gamma.end());
  _gamma.erase(std::unique(_gamma.begin(), _gamma.end()), _gamma.end());
  const auto position = [this](std::int32_t dof)
  { return PetscInt(std::lower_bound(_gamma.begin(), _gamma.end(), dof) - _gamma.begin()); };
  for (PetscInt j = 0; j < n; ++j)
  {
    _pos_minus.push_back(position(_minus[j]));
    _pos_plus.push_back(position(_plus[j]));
  }
  const PetscInt n_gamma = PetscInt(_gamma.size());

  const Constraints& bc = eq.constraints();
  _constraint_version = eq.constraint_version();
  std::vector<std::uint8_t> constrained(std::size_t(3) * n_blocks, 0);
  for (std::int32_t d : bc.dofs)
    constrained[d] = 1;
  for (PetscInt j = 0; j < n; ++j)
  {
    // A pair of a mirror set (its minus node is the plus node's mirror
    // image): its jump is the plus node's displacement, as if the minus
    // node were fixed; the set's forces (Interface) depend on it alone.
    _mirror.push_back(_minus[j] == _plus[j]);
    _minus_free.push_back(!constrained[_minus[j]] && !_mirror[j]);
    _plus_free.push_back(!constrained[_plus[j]]);
  }

  // J0: K with unit constrained rows, plus eps G^T G on the free interface
  // rows; eps a hundredth of K's mean diagonal there.
  check(MatDuplicate(model.stiffness(), MAT_COPY_VALUES, &_J0), "MatDuplicate");
  check(MatZeroRowsLocal(_J0, PetscInt(bc.dofs.size()), bc.dofs.data(), 1.0, nullptr, nullptr),
        "MatZeroRowsLocal");
  {
    Vec diag;
    check(MatCreateVecs(model.stiffness(), &diag, nullptr), "MatCreateVecs");
    check(MatGetDiagonal(model.stiffness(), diag), "MatGetDiagonal");
    const double* dg;
    check(VecGetArrayRead(diag, &dg), "VecGetArrayRead");
    double sum = 0;
    for (PetscInt j = 0; j < n; ++j)
      sum += std::abs(dg[_minus[j]]) + std::abs(dg[_plus[j]]);
    check(VecRestoreArrayRead(diag, &dg), "VecRestoreArrayRead");
    check(VecDestroy(&diag), "VecDestroy");
    _eps = 1e-2 * sum / double(2 * n);
  }
  for (PetscInt j = 0; j < n; ++j)
  {
    const PetscInt m = _minus[j], p = _plus[j];
    if (_minus_free[j])
    {
      check(MatSetValueLocal(_J0, m, m, _eps, ADD_VALUES), "MatSetValueLocal");
      check(MatSetValueLocal(_J0, m, p, -_eps, ADD_VALUES), "MatSetValueLocal");
    }
    if (_plus_free[j])
    {
      check(MatSetValueLocal(_J0, p, p, _eps, ADD_VALUES), "MatSetValueLocal");
      if (!_mirror[j])
        check(MatSetValueLocal(_J0, p, m, -_eps, ADD_VALUES), "MatSetValueLocal");
    }
  }
  check(MatAssemblyBegin(_J0, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(_J0, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");

  // One MUMPS factorisation with the interface dofs (gamma) last; their Schur complement S comes
  // out of it. MUMPS records a failure (a zero pivot: a body held by nothing) instead of raising an
  // error: it is a clear error here.
  const auto factored = [&](const std::string& phase)
  {
    MatFactorError error;
    check(MatFactorGetError(_factor, &error), "MatFactorGetError");
    if (error == MAT_FACTOR_NOERROR)
      return;
    std::string what = "MUMPS failed";
    if (error == MAT_FACTOR_STRUCT_ZEROPIVOT || error == MAT_FACTOR_NUMERIC_ZEROPIVOT)
    {
      PetscReal pivot = 0;
      PetscInt row = -1;
      check(MatFactorGetErrorZeroPivot(_factor, &pivot, &row), "MatFactorGetErrorZeroPivot");
      what = "zero pivot" + (row >= 0 ? " in row " + std::to_string(row) : std::string());
    }
    else if (error == MAT_FACTOR_OUTMEMORY)
      what = "out of memory";
    throw std::runtime_error("condensation: the " + phase +
                             " of the bulk stiffness J0 (MUMPS, with the interface Schur "
                             "complement) failed: " +
                             what + "; solver.condensation = \"off\" solves the whole model");
  };
  check(MatGetFactor(_J0, MATSOLVERMUMPS, MAT_FACTOR_LU, &_factor), "MatGetFactor");
  {
    IS is;
    check(ISCreateGeneral(PETSC_COMM_SELF, n_gamma, _gamma.data(), PETSC_COPY_VALUES, &is),
          "ISCreateGeneral");
    check(MatFactorSetSchurIS(_factor, is), "MatFactorSetSchurIS");
    check(ISDestroy(&is), "ISDestroy");
  }
  MatFactorInfo info;
  check(MatFactorInfoInitialize(&info), "MatFactorInfoInitialize");
  check(MatLUFactorSymbolic(_factor, _J0, nullptr, nullptr, &info), "MatLUFactorSymbolic");
  factored("analysis");
  check(MatLUFactorNumeric(_factor, _J0, &info), "MatLUFactorNumeric");
  factored("numerical factorisation");
  check(MatFactorFactorizeSchurComplement(_factor),
        "MatFactorFactorizeSchurComplement"); // dense LU of S, kept in the factor

  // Z on the interface = S^-1 E_I G_I^T; column j: -1 at the minus dof of
  // jump j, +1 at its plus dof (free ones only).
  Mat B;
  check(MatCreateSeqDense(PETSC_COMM_SELF, n_gamma, n, nullptr, &B), "MatCreateSeqDense");
  {
    Dense Bd(B);
    for (PetscInt j = 0; j < n; ++j)
    {
      Bd(_pos_minus[j], j) = _minus_free[j] ? -1.0 : 0.0;
      Bd(_pos_plus[j], j) = _plus_free[j] ? 1.0 : 0.0;
    }
  }
  Mat S;
  MatFactorSchurStatus status;
  check(MatFactorGetSchurComplement(_factor, &S, &status),
        "MatFactorGetSchurComplement"); // factored; the factor owns it
  check(MatCreateSeqDense(PETSC_COMM_SELF, n_gamma, n, nullptr, &_Z), "MatCreateSeqDense");
  check(MatMatSolve(S, B, _Z), "MatMatSolve");
  check(MatFactorRestoreSchurComplement(_factor, &S, status), "MatFactorRestoreSchurComplement");
  check(MatDestroy(&B), "MatDestroy");

  // C = G Z, k = 1 / mean diag(C).
  check(MatCreateSeqDense(PETSC_COMM_SELF, n, n, nullptr, &_C), "MatCreateSeqDense");
  {
    Dense Z(_Z), C(_C);
    double trace = 0;
    int counted = 0;
    for (PetscInt col = 0; col < n; ++col)
      for (PetscInt j = 0; j < n; ++j)
      {
        C(j, col) = Z(_pos_plus[j], col) - (_mirror[j] ? 0.0 : Z(_pos_minus[j], col));
      }
    for (PetscInt j = 0; j < n; ++j)
      if (C(j, j) > 0)
      {
        trace += C(j, j);
        ++counted;
      }
    _k = counted > 0 ? double(counted) / trace : 1.0;
  }
  // C = G_f (J0_ff)^-1 G_f^T on the free dofs (Z is zero on the
  // constrained ones) is symmetric; what the factorisation left of
  // asymmetry is its round-off, averaged away, and its products stream the
  // upper triangle only (SymmetricMatrix.h). Where the asymmetry says that
  // C is not accurate enough for the curve, the caller solves the whole
  // model instead (LoadStepSolver::update).
  // (Test hook, not a scene key: PUSHOUT_TEST_TRUSTED_ASYMMETRY sets
  // another limit, so that tests/e2e/test_condensation_checked_or_whole_model.py can make a
  // scene's C untrusted.)
  static const double trusted = []
  {
    const char* v = std::getenv("PUSHOUT_TEST_TRUSTED_ASYMMETRY");
    return v && *v ? std::strtod(v, nullptr) : trusted_asymmetry;
  }();
  _asymmetry = relative_asymmetry(_C);
  if (!(_asymmetry <= trusted)) // NaN too
  {
    std::ostringstream what;
    what << "the condensed flexibility C is not accurate enough: max|C - C^T| = " << std::scientific
         << std::setprecision(2) << _asymmetry << " max|C| (at most " << trusted << " trusted)";
    _untrusted = what.str();
  }
  symmetrize(_C);
  _C_packed = SymmetricMatrix<double>(_C);

  // dF/dd: 3 x 3 blocks of node pairs, one matrix per set of joints (its
  // plus blocks map to their pairs, its minus blocks to nothing).
  for (const std::vector<std::int32_t>& map_of_set : pair_of_block)
  {
    ISLocalToGlobalMapping l2g;
    check(ISLocalToGlobalMappingCreate(PETSC_COMM_SELF, 3, n_blocks, map_of_set.data(),
                                       PETSC_COPY_VALUES, &l2g),
          "ISLocalToGlobalMappingCreate");
    _l2g.push_back(l2g);
    Mat T;
    check(MatCreate(PETSC_COMM_SELF, &T), "MatCreate");
    _T.push_back(T);
    check(MatSetSizes(T, n_ext, n_ext, n_ext, n_ext), "MatSetSizes");
    check(MatSetType(T, MATSEQBAIJ), "MatSetType");
    check(MatSetBlockSize(T, 3), "MatSetBlockSize");
    check(MatSeqBAIJSetPreallocation(T, 3, 9, nullptr), "MatSeqBAIJSetPreallocation");
    check(MatSetOption(T, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE), "MatSetOption");
    check(MatSetLocalToGlobalMapping(T, l2g, l2g), "MatSetLocalToGlobalMapping");
  }

  check(MatCreateVecs(_J0, &_b, nullptr), "MatCreateVecs");
  _r = create_vector();
  _d_b = create_vector();
  check(VecCreateSeq(PETSC_COMM_SELF, n_gamma, &_g), "VecCreateSeq");
  check(VecDuplicate(_b, &_rest), "VecDuplicate");
  _Tv = create_vector();
  check(VecCreateSeq(PETSC_COMM_SELF, n_ext, &_v_ext), "VecCreateSeq");
  check(VecDuplicate(_v_ext, &_Tv_ext), "VecDuplicate");
  check(VecDuplicate(_g, &_Zr), "VecDuplicate");
  _u.assign(std::size_t(3) * n_blocks, 0.0);
  _f.assign(_u.size(), 0.0);
}

void Condensation::forget_loads()
{
  for (auto* list : {&_basis, &_basis_g, &_basis_d})
  {
    for (Vec& v : *list)
      check(VecDestroy(&v), "VecDestroy");
    list->clear();
  }
  _load_version = -1;
}

Condensation::~Condensation()
{
  release();
}

void Condensation::release()
{
  for (Vec* v : {&_b, &_r, &_d_b, &_g, &_rest, &_Tv, &_Zr, &_v_ext, &_Tv_ext})
    petsc::check_nothrow(VecDestroy(v), "VecDestroy");
  for (auto* list : {&_basis, &_basis_g, &_basis_d})
    for (Vec& v : *list)
      petsc::check_nothrow(VecDestroy(&v), "VecDestroy");
  for (Mat* m : {&_Z, &_C, &_factor, &_J0})
    petsc::check_nothrow(MatDestroy(m), "MatDestroy");
  for (Mat& T : _T)
    petsc::check_nothrow(MatDestroy(&T), "MatDestroy");
  for (ISLocalToGlobalMapping& l2g : _l2g)
    petsc::check_nothrow(ISLocalToGlobalMappingDestroy(&l2g), "ISLocalToGlobalMappingDestroy");
}

void Condensation::set_single_precision(bool single)
{
  _single = single;
  _C_single = single ? SymmetricMatrix<float>(_C) : SymmetricMatrix<float>();
}

Mat Condensation::create_matrix() const
{
  Mat J;
  check(MatCreateSeqDense(PETSC_COMM_SELF, size(), size(), nullptr, &J), "MatCreateSeqDense");
  set_linear_part(J);
  return J;
}

Vec Condensation::create_vector() const
{
  Vec v;
  check(VecCreateSeq(PETSC_COMM_SELF, size(), &v), "VecCreateSeq");
  return v;
}

void Condensation::configure(KSP ksp) const
{
  PC pc;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  KSPType type;
  check(KSPGetType(ksp, &type), "KSPGetType");
  if (_single && std::string(type) != KSPPREONLY)
  {
    // A preconditioner of GMRES: its LU in single precision is as good a
    // guide at half the memory traffic (SinglePrecision.h). Flexible GMRES
    // (right preconditioning): its residual is the operator's, whatever the
    // rounding of the preconditioner. The operator is applied in single
    // precision too, so a relative tolerance below its rounding would only
    // iterate on noise: Newton's next residual, in double, corrects the
    // step.
    use_single_precision_lu(pc);
    if (std::string(type) == KSPGMRES)
    {
      PetscInt restart;
      check(KSPGMRESGetRestart(ksp, &restart), "KSPGMRESGetRestart");
      check(KSPSetType(ksp, KSPFGMRES), "KSPSetType");
      check(KSPGMRESSetRestart(ksp, restart), "KSPGMRESSetRestart");
    }
    PetscReal rtol, abstol, dtol;
    PetscInt max_it;
    check(KSPGetTolerances(ksp, &rtol, &abstol, &dtol, &max_it), "KSPGetTolerances");
    check(KSPSetTolerances(ksp, std::max(rtol, single_precision_rtol), abstol, dtol, max_it),
          "KSPSetTolerances");
    return;
  }
  // The LU in double; with KSP preonly it is the solver
  // (solver.preconditioner = "jacobian").
  check(PCFactorSetMatSolverType(pc, MATSOLVERPETSC), "PCFactorSetMatSolverType");
  check(PCFactorSetMatOrderingType(pc, MATORDERINGNATURAL), "PCFactorSetMatOrderingType");
}

void Condensation::restrict_to(Vec x, Vec d) const
{
  const double* a;
  double* g;
  check(VecGetArrayRead(x, &a), "VecGetArrayRead");
  check(VecGetArray(d, &g), "VecGetArray");
  for (std::size_t j = 0; j < _minus.size(); ++j)
    g[j] = a[_plus[j]] - (_mirror[j] ? 0.0 : a[_minus[j]]);
  check(VecRestoreArray(d, &g), "VecRestoreArray");
  check(VecRestoreArrayRead(x, &a), "VecRestoreArrayRead");
}

void Condensation::restrict_functional(Vec a, Vec a_d) const
{
  const double* aa;
  double* g;
  check(VecGetArrayRead(a, &aa), "VecGetArrayRead");
  check(VecGetArray(a_d, &g), "VecGetArray");
  // a_d on the first set's pairs (the interface): the functionals of the
  // jumps the solvers use (the mean axial slip) are the interface's. Then
  // a must equal G^T a_d on every interface dof.
  const std::size_t n = _minus.size();
  std::vector<double> Gt(_gamma.size(), 0.0);
  double scale = 0;
  for (std::size_t j = 0; j < n; ++j)
  {
    g[j] = j < _set_end[0] ? aa[_plus[j]] : 0.0;
    Gt[std::size_t(_pos_plus[j])] += g[j];
    if (!_mirror[j])
      Gt[std::size_t(_pos_minus[j])] -= g[j];
    scale = std::max(scale, std::abs(g[j]));
  }
  double mismatch = 0;
  for (std::size_t i = 0; i < _gamma.size(); ++i)
    mismatch = std::max(mismatch, std::abs(Gt[i] - aa[_gamma[i]]));
  check(VecRestoreArray(a_d, &g), "VecRestoreArray");
  check(VecRestoreArrayRead(a, &aa), "VecRestoreArrayRead");
  if (mismatch > 1e-12 * scale)
    throw std::logic_error("condensation: the functional is not one of the interface's jumps");
}

void Condensation::combine(const std::vector<double>& c, const std::vector<Vec>& v, Vec y)
{
  check(VecSet(y, 0.0), "VecSet");
  for (std::size_t k = 0; k < c.size(); ++k)
    check(VecAXPY(y, c[k], v[k]), "VecAXPY");
}

const std::vector<double>& Condensation::load_coefficients()
{
  if (_eq.constraint_version() != _constraint_version)
    throw std::logic_error("condensation: the constrained dofs changed");
  if (_eq.load_version() == _load_version)
    return _load_c; // the loads did not change (Newton iterations of a step)
  _load_version = _eq.load_version();
  _eq.linear_rhs(_b);
  double b_norm;
  check(VecNorm(_b, NORM_2, &b_norm), "VecNorm");
  // Project b on the basis (classical Gram-Schmidt, twice).
  Vec rest = _rest;
  check(VecCopy(_b, rest), "VecCopy");
  std::vector<double>& c = _load_c;
  c.assign(_basis.size(), 0.0);
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t k = 0; k < _basis.size(); ++k)
    {
      double ck;
      check(VecDot(_basis[k], rest, &ck), "VecDot");
      check(VecAXPY(rest, -ck, _basis[k]), "VecAXPY");
      c[k] += ck;
    }
  double r_norm;
  check(VecNorm(rest, NORM_2, &r_norm), "VecNorm");
  if (r_norm > 1e-12 * b_norm)
  {
    if (_basis.size() == max_basis) // start again from b
    {
      forget_loads();
      c.clear();
      check(VecCopy(_b, rest), "VecCopy");
      r_norm = b_norm;
    }
    // The new direction q = rest / |rest|: J0^-1 q on the interface, and
    // its jumps.
    check(VecDuplicate(_b, &rest), "VecDuplicate");
    check(VecCopy(_rest, rest), "VecCopy");
    check(VecScale(rest, 1.0 / r_norm), "VecScale");
    Vec y, g, d;
    check(VecDuplicate(_b, &y), "VecDuplicate");
    check(MatSolve(_factor, rest, y), "MatSolve");
    check(VecDuplicate(_g, &g), "VecDuplicate");
    d = create_vector();
    const double* ya;
    double *ga, *da;
    check(VecGetArrayRead(y, &ya), "VecGetArrayRead");
    check(VecGetArray(g, &ga), "VecGetArray");
    check(VecGetArray(d, &da), "VecGetArray");
    for (std::size_t i = 0; i < _gamma.size(); ++i)
      ga[i] = ya[_gamma[i]];
    for (std::size_t j = 0; j < _minus.size(); ++j)
      da[j] = ga[_pos_plus[j]] - (_mirror[j] ? 0.0 : ga[_pos_minus[j]]);
    check(VecRestoreArray(d, &da), "VecRestoreArray");
    check(VecRestoreArray(g, &ga), "VecRestoreArray");
    check(VecRestoreArrayRead(y, &ya), "VecRestoreArrayRead");
    check(VecDestroy(&y), "VecDestroy");
    _basis.push_back(rest);
    _basis_g.push_back(g);
    _basis_d.push_back(d);
    c.push_back(r_norm);
  }
  return c;
}

std::pair<std::size_t, std::size_t> Condensation::load_set(std::size_t s, const double* d)
{
  const std::size_t first = s == 0 ? 0 : _set_end[s - 1], end = _set_end[s];
  for (std::size_t j = first; j < end; ++j)
  {
    _u[_minus[j]] = 0.0;
    _u[_plus[j]] = d[j];
    _f[_minus[j]] = _f[_plus[j]] = 0.0;
  }
  return {first, end};
}

bool Condensation::interface_forces(Vec d, bool tangent, double* force_norm)
{
  // Set by set: the set's minus nodes at 0 and plus nodes at the jumps (its
  // joints see only their jumps), its forces F at the plus nodes.
  const double* da;
  check(VecGetArrayRead(d, &da), "VecGetArrayRead");
  double* r;
  check(VecGetArray(_r, &r), "VecGetArray");
  double f2 = 0;
  bool ok = true;
  const std::vector<interface::Interface*> sets = _eq.model().joints();
  for (std::size_t s = 0; s < sets.size(); ++s)
  {
    const auto [first, end] = load_set(s, da);
    if (tangent)
      check(MatZeroEntries(_T[s]), "MatZeroEntries");
    ok = sets[s]->assemble(_u, _f, tangent ? _T[s] : nullptr) && ok;
    if (tangent)
    {
      check(MatAssemblyBegin(_T[s], MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
      check(MatAssemblyEnd(_T[s], MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    }
    for (std::size_t j = first; j < end; ++j)
    {
      const double F = _f[_plus[j]];
      f2 += F * F;
      r[j] = F - _eps * da[j];
    }
  }
  check(VecRestoreArray(_r, &r), "VecRestoreArray");
  check(VecRestoreArrayRead(d, &da), "VecRestoreArrayRead");
  if (force_norm)
    *force_norm = std::sqrt(f2);
  return ok;
}

// As interface_forces(): each set with its minus nodes at 0 and plus nodes
// at the jumps, so that dG/du at the plus nodes is dG/dd.
bool Condensation::energy_release(Vec d, double& G, Vec gradient)
{
  const double* da;
  check(VecGetArrayRead(d, &da), "VecGetArrayRead");
  double* g;
  check(VecGetArray(gradient, &g), "VecGetArray");
  bool ok = true;
  G = 0;
  const std::vector<interface::Interface*> sets = _eq.model().joints();
  for (std::size_t s = 0; s < sets.size(); ++s)
  {
    const auto [first, end] = load_set(s, da);
    double G_set;
    ok = sets[s]->energy_release(_u, _f, G_set) && ok;
    G += G_set;
    for (std::size_t j = first; j < end; ++j)
      g[j] = _f[_plus[j]];
  }
  check(VecRestoreArray(gradient, &g), "VecRestoreArray");
  check(VecRestoreArrayRead(d, &da), "VecRestoreArrayRead");
  return ok;
}

bool Condensation::residual(Vec d, Vec R)
{
  double reaction_norm;
  return residual(d, R, reaction_norm);
}

bool Condensation::residual(Vec d, Vec R, double& reaction_norm)
{
  combine(load_coefficients(), _basis_d, _d_b);
  const bool ok = interface_forces(d, false, &reaction_norm);
  {
    const ReadView r(_r);
    WriteView Ra(R);
    _C_packed.multiply(r.data(), Ra.data());
  }
  check(VecAXPY(R, 1.0, d), "VecAXPY");
  check(VecAXPY(R, -1.0, _d_b), "VecAXPY");
  check(VecScale(R, _k), "VecScale");
  return ok;
}

// R = k (d + C r - d_b): floor = C_f eps k (||d|| + ||C|| ||r|| + ||d_b||),
// C_f = residual_floor_factor, ||C|| = sqrt(||C||_1 ||C||_inf) >= ||C||_2,
// r from the last residual. (C and d_b carry the round-off of J0's
// factorisation too, but the same in every evaluation: Newton solves the
// condensed system as computed, and that error is not a floor of it.)
double Condensation::residual_floor(Vec d)
{
  if (_C_norm < 0)
  {
    double n1, ninf;
    check(MatNorm(_C, NORM_1, &n1), "MatNorm");
    check(MatNorm(_C, NORM_INFINITY, &ninf), "MatNorm");
    _C_norm = std::sqrt(n1 * ninf);
  }
  double d_norm, r_norm, b_norm;
  check(VecNorm(d, NORM_2, &d_norm), "VecNorm");
  check(VecNorm(_r, NORM_2, &r_norm), "VecNorm");
  check(VecNorm(_d_b, NORM_2, &b_norm), "VecNorm");
  return residual_floor_factor * std::numeric_limits<double>::epsilon() * _k *
         (d_norm + _C_norm * r_norm + b_norm);
}

bool Condensation::jacobian(Vec d, Mat J)
{
  count_tangent();
  const bool ok = interface_forces(d, true); // dF/dd into _T (per set)
  PetscBool shell;
  check(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(J), MATSHELL, &shell),
        "PetscObjectTypeCompare");
  if (!shell)
    form_jacobian(J);
  return ok;
}

void Condensation::set_linear_part(Mat J) const
{
  check(MatCopy(_C, J, SAME_NONZERO_PATTERN), "MatCopy");
  check(MatScale(J, -_eps), "MatScale");
  check(MatShift(J, 1.0), "MatShift");
}

void Condensation::form_jacobian(Mat J) const
{
  set_linear_part(J);
  {
    // J += C dF/dd, column by column: J(:, j) += T(i, j) C(:, i), T read
    // at the extended components that are jumps.
    Dense Jd(J), C(_C);
    const PetscInt n = size();
    for (Mat T : _T)
      for (PetscInt i = 0; i < n; ++i)
      {
        PetscInt ncols;
        const PetscInt* cols;
        const double* vals;
        check(MatGetRow(T, _ext_of_jump[i], &ncols, &cols, &vals), "MatGetRow");
        for (PetscInt c = 0; c < ncols; ++c)
        {
          const double t = vals[c];
          const PetscInt j = _jump_of_ext[cols[c]];
          if (t == 0.0 || j < 0)
            continue;
          double* Jj = &Jd(0, j);
          const double* Ci = &C(0, i);
          for (PetscInt r = 0; r < n; ++r)
            Jj[r] += t * Ci[r];
        }
        check(MatRestoreRow(T, _ext_of_jump[i], &ncols, &cols, &vals), "MatRestoreRow");
      }
  }
  check(MatScale(J, _k), "MatScale");
}

Mat Condensation::create_operator() const
{
  Mat J;
  check(MatCreateShell(PETSC_COMM_SELF, size(), size(), size(), size(),
                       const_cast<Condensation*>(this), &J),
        "MatCreateShell");
  check(MatShellSetOperation(J, MATOP_MULT, reinterpret_cast<void (*)(void)>(operator_mult)),
        "MatShellSetOperation");
  return J;
}

PetscErrorCode Condensation::operator_mult(Mat J, Vec v, Vec y)
{
  return petsc::callback(
      [&]
      {
        // y = k (v + C (dF/dd - eps) v).
        Condensation* self;
        check(MatShellGetContext(J, &self), "MatShellGetContext");
        {
          // v onto the extended components (the others zero).
          const ReadView va(v);
          WriteView ve(self->_v_ext);
          std::fill(ve.span().begin(), ve.span().end(), 0.0);
          for (std::size_t j = 0; j < self->_ext_of_jump.size(); ++j)
            ve.data()[self->_ext_of_jump[j]] = va.data()[j];
        }
        check(MatMult(self->_T[0], self->_v_ext, self->_Tv_ext), "MatMult");
        for (std::size_t s = 1; s < self->_T.size(); ++s)
          check(MatMultAdd(self->_T[s], self->_v_ext, self->_Tv_ext, self->_Tv_ext), "MatMultAdd");
        {
          const ReadView Te(self->_Tv_ext);
          WriteView Tv(self->_Tv);
          for (std::size_t j = 0; j < self->_ext_of_jump.size(); ++j)
            Tv.data()[j] = Te.data()[self->_ext_of_jump[j]];
        }
        check(VecAXPY(self->_Tv, -self->_eps, v), "VecAXPY");
        {
          const ReadView Tv(self->_Tv);
          WriteView ya(y);
          if (self->_single)
            self->_C_single.multiply(Tv.data(), ya.data());
          else
            self->_C_packed.multiply(Tv.data(), ya.data());
        }
        check(VecAXPY(y, 1.0, v), "VecAXPY");
        check(VecScale(y, self->_k), "VecScale");
      });
}

void Condensation::copy_jacobian(Mat J, Mat P) const
{
  PetscBool shell;
  check(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(J), MATSHELL, &shell),
        "PetscObjectTypeCompare");
  if (shell)
    form_jacobian(P);
  else
    check(MatCopy(J, P, SAME_NONZERO_PATTERN), "MatCopy");
}

void Condensation::expand_interface(Vec d, Vec x)
{
  combine(load_coefficients(), _basis_g, _g);
  interface_forces(d, false);
  check(MatMult(_Z, _r, _Zr), "MatMult");
  check(VecAXPY(_g, -1.0, _Zr), "VecAXPY");
  const double* g;
  double* xa;
  check(VecGetArrayRead(_g, &g), "VecGetArrayRead");
  check(VecGetArray(x, &xa), "VecGetArray");
  for (std::size_t i = 0; i < _gamma.size(); ++i)
    xa[_gamma[i]] = g[i];
  check(VecRestoreArray(x, &xa), "VecRestoreArray");
  check(VecRestoreArrayRead(_g, &g), "VecRestoreArrayRead");
  _eq.apply_constraints(x);
}

void Condensation::expand(Vec d, Vec x)
{
  load_coefficients(); // _b: the current loads
  interface_forces(d, false);
  // x = J0^-1 (b - E_I G_I^T r).
  Vec rhs = _rest;
  check(VecCopy(_b, rhs), "VecCopy");
  double* ra;
  const double* r;
  check(VecGetArray(rhs, &ra), "VecGetArray");
  check(VecGetArrayRead(_r, &r), "VecGetArrayRead");
  for (std::size_t j = 0; j < _minus.size(); ++j)
  {
    if (_minus_free[j])
      ra[_minus[j]] += r[j];
    if (_plus_free[j])
      ra[_plus[j]] -= r[j];
  }
  check(VecRestoreArrayRead(_r, &r), "VecRestoreArrayRead");
  check(VecRestoreArray(rhs, &ra), "VecRestoreArray");
  check(MatSolve(_factor, rhs, x), "MatSolve");
  check(VecGhostUpdateBegin(x, INSERT_VALUES, SCATTER_FORWARD), "VecGhostUpdateBegin");
  check(VecGhostUpdateEnd(x, INSERT_VALUES, SCATTER_FORWARD), "VecGhostUpdateEnd");
}
} // namespace pushout::solver

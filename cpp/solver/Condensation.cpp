// Condensation: whether the bulk is condensed, and the building of the
// condensed system in named steps (the jumps' numbering, J0 with its eps
// springs, the MUMPS factorisation with the interface's Schur complement, Z,
// C and its symmetry check, the tangent blocks); Condensation.h has the
// mathematics. Its use per Newton iteration is in CondensationNewton.cpp,
// the loads and the whole model's displacements in CondensationLoads.cpp.
#include "Condensation.h"
#include "../common/build_or_release.h"
#include "../common/petsc_check.h"
#include "DenseArray.h"
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <dolfinx/common/IndexMap.h>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace pushout::solver
{
using petsc::check;

namespace
{
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

/// The node blocks of this process, owned and ghosts (3 dofs each).
std::int32_t local_blocks(const model::Model& model)
{
  const auto& map = model.index_map();
  return map.size_local() + map.num_ghosts();
}

/// Throws a clear error if the `phase` of `factor` (MUMPS) failed: MUMPS
/// records a failure (a zero pivot: a body held by nothing) instead of
/// raising an error.
void check_factored(Mat factor, const std::string& phase)
{
  MatFactorError error;
  check(MatFactorGetError(factor, &error), "MatFactorGetError");
  if (error == MAT_FACTOR_NOERROR)
    return;
  std::string what = "MUMPS failed";
  if (error == MAT_FACTOR_STRUCT_ZEROPIVOT || error == MAT_FACTOR_NUMERIC_ZEROPIVOT)
  {
    PetscReal pivot = 0;
    PetscInt row = -1;
    check(MatFactorGetErrorZeroPivot(factor, &pivot, &row), "MatFactorGetErrorZeroPivot");
    what = "zero pivot" + (row >= 0 ? " in row " + std::to_string(row) : std::string());
  }
  else if (error == MAT_FACTOR_OUTMEMORY)
    what = "out of memory";
  throw std::runtime_error("condensation: the " + phase +
                           " of the bulk stiffness J0 (MUMPS, with the interface Schur "
                           "complement) failed: " +
                           what + "; solver.condensation = \"off\" solves the whole model");
}
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
  return possible(size, interface_dofs(eq.model()), eq.model().bulk_cracking() != nullptr, why);
}

bool Condensation::possible(int processes, std::int64_t n_interface, bool bulk_cracks,
                            std::string& why)
{
  char pc_type[64] = "";
  PetscBool pc_set = PETSC_FALSE;
  check(PetscOptionsGetString(nullptr, nullptr, "-pc_type", pc_type, sizeof(pc_type), &pc_set),
        "PetscOptionsGetString");
  if (bulk_cracks)
    why = "the concrete may crack ([cracking]): its bulk is not linear";
  else if (processes > 1)
    why = "more than one process";
  else if (pc_set && std::string(pc_type) != "lu")
    why = std::string("-pc_type ") + pc_type + " (condensed systems are solved by dense LU)";
  else if (n_interface == 0)
    why = "no interface";
  else
    return true;
  return false;
}

bool Condensation::chosen(SolverPart::Condensation mode, int processes, std::int64_t n_interface,
                          bool bulk_cracks, std::string& why)
{
  if (mode == SolverPart::Condensation::off)
    return false;
  if (!possible(processes, n_interface, bulk_cracks, why))
    return false;
  if (mode == SolverPart::Condensation::automatic && n_interface > default_max_dofs)
  {
    why = std::to_string(n_interface) + " interface dofs, more than " +
          std::to_string(default_max_dofs);
    return false;
  }
  return true;
}

Condensation::Condensation(Equilibrium& eq) : _eq(eq)
{
  build_or_release([this] { build(); }, [this] { release(); });
}

void Condensation::build()
{
  std::string why;
  if (!possible(_eq, why))
    throw std::runtime_error("cannot condense the bulk: " + why);
  const std::vector<std::vector<std::int32_t>> pair_of_block = number_jumps();
  mark_free_ends();
  assemble_J0();
  factor_J0();
  compute_Z();
  compute_C();
  check_symmetry();
  create_tangents(pair_of_block);
  create_work_vectors();
}

std::vector<std::vector<std::int32_t>> Condensation::number_jumps()
{
  const model::Model& model = _eq.model();
  const std::int32_t n_blocks = local_blocks(model);
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
  return pair_of_block;
}

void Condensation::mark_free_ends()
{
  const Constraints& bc = _eq.constraints();
  _constraint_version = _eq.constraint_version();
  std::vector<std::uint8_t> constrained(std::size_t(3) * local_blocks(_eq.model()), 0);
  for (std::int32_t d : bc.dofs)
    constrained[d] = 1;
  for (std::size_t j = 0; j < _minus.size(); ++j)
  {
    // A pair of a mirror set (its minus node is the plus node's mirror
    // image): its jump is the plus node's displacement, as if the minus
    // node were fixed; the set's forces (Interface) depend on it alone.
    _mirror.push_back(_minus[j] == _plus[j]);
    _minus_free.push_back(!constrained[_minus[j]] && !_mirror[j]);
    _plus_free.push_back(!constrained[_plus[j]]);
  }
}

void Condensation::assemble_J0()
{
  const model::Model& model = _eq.model();
  const Constraints& bc = _eq.constraints();
  const PetscInt n = PetscInt(size());
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
}

void Condensation::factor_J0()
{
  check(MatGetFactor(_J0, MATSOLVERMUMPS, MAT_FACTOR_LU, &_factor), "MatGetFactor");
  {
    IS is;
    check(ISCreateGeneral(PETSC_COMM_SELF, PetscInt(_gamma.size()), _gamma.data(),
                          PETSC_COPY_VALUES, &is),
          "ISCreateGeneral");
    check(MatFactorSetSchurIS(_factor, is), "MatFactorSetSchurIS");
    check(ISDestroy(&is), "ISDestroy");
  }
  MatFactorInfo info;
  check(MatFactorInfoInitialize(&info), "MatFactorInfoInitialize");
  check(MatLUFactorSymbolic(_factor, _J0, nullptr, nullptr, &info), "MatLUFactorSymbolic");
  check_factored(_factor, "analysis");
  check(MatLUFactorNumeric(_factor, _J0, &info), "MatLUFactorNumeric");
  check_factored(_factor, "numerical factorisation");
  check(MatFactorFactorizeSchurComplement(_factor),
        "MatFactorFactorizeSchurComplement"); // dense LU of S, kept in the factor
}

void Condensation::compute_Z()
{
  const PetscInt n = PetscInt(size()), n_gamma = PetscInt(_gamma.size());
  // Column j of E_I G_I^T: -1 at the minus dof of jump j, +1 at its plus
  // dof (free ones only).
  Mat B;
  check(MatCreateSeqDense(PETSC_COMM_SELF, n_gamma, n, nullptr, &B), "MatCreateSeqDense");
  {
    DenseArray Bd(B);
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
  try
  {
    check(MatMatSolve(S, B, _Z), "MatMatSolve");
  }
  catch (...) // B and the borrowed Schur complement go back before the error does
  {
    petsc::check_nothrow(MatFactorRestoreSchurComplement(_factor, &S, status),
                         "MatFactorRestoreSchurComplement");
    petsc::check_nothrow(MatDestroy(&B), "MatDestroy");
    throw;
  }
  check(MatFactorRestoreSchurComplement(_factor, &S, status), "MatFactorRestoreSchurComplement");
  check(MatDestroy(&B), "MatDestroy");
}

void Condensation::compute_C()
{
  const PetscInt n = PetscInt(size());
  check(MatCreateSeqDense(PETSC_COMM_SELF, n, n, nullptr, &_C), "MatCreateSeqDense");
  DenseArray Z(_Z), C(_C);
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

void Condensation::check_symmetry()
{
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
}

void Condensation::create_tangents(const std::vector<std::vector<std::int32_t>>& pair_of_block)
{
  const std::int32_t n_blocks = local_blocks(_eq.model());
  const PetscInt n_ext = PetscInt(_jump_of_ext.size());
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
}

void Condensation::create_work_vectors()
{
  const std::int32_t n_blocks = local_blocks(_eq.model());
  check(MatCreateVecs(_J0, &_b, nullptr), "MatCreateVecs");
  _r = create_vector();
  _d_b = create_vector();
  check(VecCreateSeq(PETSC_COMM_SELF, PetscInt(_gamma.size()), &_g), "VecCreateSeq");
  check(VecDuplicate(_b, &_rest), "VecDuplicate");
  _Tv = create_vector();
  check(VecCreateSeq(PETSC_COMM_SELF, PetscInt(_jump_of_ext.size()), &_v_ext), "VecCreateSeq");
  check(VecDuplicate(_v_ext, &_Tv_ext), "VecDuplicate");
  check(VecDuplicate(_g, &_Zr), "VecDuplicate");
  _u.assign(std::size_t(3) * n_blocks, 0.0);
  _f.assign(_u.size(), 0.0);
}

Condensation::~Condensation()
{
  release();
}

void Condensation::release() noexcept
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
} // namespace pushout::solver

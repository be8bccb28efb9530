#include "Condensation.h"
#include <algorithm>
#include <cmath>
#include <dolfinx/common/IndexMap.h>
#include <stdexcept>

namespace pushout::solver
{
namespace
{
/// Load directions kept before the basis starts again.
constexpr std::size_t max_basis = 6;

/// Interface node pairs of this process: (steel block, concrete block),
/// sorted by concrete block.
std::vector<std::pair<std::int32_t, std::int32_t>> node_pairs(const model::Model& model)
{
  const auto b = model.interface->pair_blocks();
  const int n = model.interface->nodes_per_side();
  std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
  for (std::size_t p = 0; p < model.interface->num_pairs(); ++p)
    for (int a = 0; a < n; ++a)
      pairs.emplace_back(b[2 * n * p + n + a], b[2 * n * p + a]);
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  for (std::size_t k = 1; k < pairs.size(); ++k)
    if (pairs[k].first == pairs[k - 1].first)
      throw std::logic_error("condensation: a concrete interface node has two steel partners");
  for (auto& [concrete, steel] : pairs)
    std::swap(concrete, steel);
  return pairs;
}

/// Column-major dense array of a SEQDENSE matrix and its leading dimension.
struct Dense
{
  Mat A;
  double* a = nullptr;
  PetscInt lda = 0;
  explicit Dense(Mat M) : A(M)
  {
    MatDenseGetLDA(A, &lda);
    MatDenseGetArray(A, &a);
  }
  ~Dense() { MatDenseRestoreArray(A, &a); }
  double& operator()(PetscInt i, PetscInt j) { return a[i + j * lda]; }
};
} // namespace

std::int64_t Condensation::interface_dofs(const model::Model& model)
{
  return 6 * std::int64_t(node_pairs(model).size());
}

bool Condensation::possible(const Equilibrium& eq, std::string& why)
{
  int size = 1;
  MPI_Comm_size(PetscObjectComm(reinterpret_cast<PetscObject>(eq.model().K)), &size);
  return possible(size, interface_dofs(eq.model()), why);
}

bool Condensation::possible(int processes, std::int64_t n_interface, std::string& why)
{
  char pc_type[64] = "";
  PetscBool pc_set = PETSC_FALSE;
  PetscOptionsGetString(nullptr, nullptr, "-pc_type", pc_type, sizeof(pc_type), &pc_set);
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
  std::string why;
  if (!possible(eq, why))
    throw std::runtime_error("cannot condense the bulk: " + why);
  const model::Model& model = eq.model();
  const auto& map = *model.V->dofmap()->index_map;
  const std::int32_t n_blocks = map.size_local() + map.num_ghosts();
  const auto pairs = node_pairs(model);
  std::vector<std::int32_t> pair_of_block(n_blocks, -1); // concrete block -> node pair
  for (std::size_t k = 0; k < pairs.size(); ++k)
  {
    pair_of_block[pairs[k].second] = std::int32_t(k);
    for (int c = 0; c < 3; ++c)
    {
      _steel.push_back(3 * pairs[k].first + c);
      _concrete.push_back(3 * pairs[k].second + c);
    }
  }
  const PetscInt n = PetscInt(_steel.size());

  const Constraints& bc = eq.constraints();
  _constraint_version = eq.constraint_version();
  std::vector<std::uint8_t> constrained(std::size_t(3) * n_blocks, 0);
  for (std::int32_t d : bc.dofs)
    constrained[d] = 1;
  for (PetscInt j = 0; j < n; ++j)
  {
    _steel_free.push_back(!constrained[_steel[j]]);
    _concrete_free.push_back(!constrained[_concrete[j]]);
  }

  // J0: K with unit constrained rows, plus eps G^T G on the free interface
  // rows; eps a hundredth of K's mean diagonal there.
  MatDuplicate(model.K, MAT_COPY_VALUES, &_J0);
  MatZeroRowsLocal(_J0, PetscInt(bc.dofs.size()), bc.dofs.data(), 1.0, nullptr, nullptr);
  {
    Vec diag;
    MatCreateVecs(model.K, &diag, nullptr);
    MatGetDiagonal(model.K, diag);
    const double* dg;
    VecGetArrayRead(diag, &dg);
    double sum = 0;
    for (PetscInt j = 0; j < n; ++j)
      sum += std::abs(dg[_steel[j]]) + std::abs(dg[_concrete[j]]);
    VecRestoreArrayRead(diag, &dg);
    VecDestroy(&diag);
    _eps = 1e-2 * sum / double(2 * n);
  }
  for (PetscInt j = 0; j < n; ++j)
  {
    const PetscInt s = _steel[j], c = _concrete[j];
    if (_steel_free[j])
    {
      MatSetValueLocal(_J0, s, s, _eps, ADD_VALUES);
      MatSetValueLocal(_J0, s, c, -_eps, ADD_VALUES);
    }
    if (_concrete_free[j])
    {
      MatSetValueLocal(_J0, c, c, _eps, ADD_VALUES);
      MatSetValueLocal(_J0, c, s, -_eps, ADD_VALUES);
    }
  }
  MatAssemblyBegin(_J0, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(_J0, MAT_FINAL_ASSEMBLY);

  // One MUMPS factorisation with the interface dofs (steel, then concrete)
  // last; their Schur complement S comes out of it.
  MatGetFactor(_J0, MATSOLVERMUMPS, MAT_FACTOR_LU, &_factor);
  {
    std::vector<PetscInt> gamma(_steel.begin(), _steel.end());
    gamma.insert(gamma.end(), _concrete.begin(), _concrete.end());
    IS is;
    ISCreateGeneral(PETSC_COMM_SELF, PetscInt(gamma.size()), gamma.data(), PETSC_COPY_VALUES, &is);
    MatFactorSetSchurIS(_factor, is);
    ISDestroy(&is);
  }
  MatFactorInfo info;
  MatFactorInfoInitialize(&info);
  MatLUFactorSymbolic(_factor, _J0, nullptr, nullptr, &info);
  MatLUFactorNumeric(_factor, _J0, &info);
  MatFactorFactorizeSchurComplement(_factor); // dense LU of S, kept in the factor

  // Z on the interface = S^-1 E_I G_I^T; column j: -1 at the steel dof of
  // jump j, +1 at its concrete dof (free ones only).
  Mat B;
  MatCreateSeqDense(PETSC_COMM_SELF, 2 * n, n, nullptr, &B);
  {
    Dense Bd(B);
    for (PetscInt j = 0; j < n; ++j)
    {
      Bd(j, j) = _steel_free[j] ? -1.0 : 0.0;
      Bd(n + j, j) = _concrete_free[j] ? 1.0 : 0.0;
    }
  }
  Mat S;
  MatFactorSchurStatus status;
  MatFactorGetSchurComplement(_factor, &S, &status); // factored; the factor owns it
  MatCreateSeqDense(PETSC_COMM_SELF, 2 * n, n, nullptr, &_Z);
  MatMatSolve(S, B, _Z);
  MatFactorRestoreSchurComplement(_factor, &S, status);
  MatDestroy(&B);

  // C = G Z, E = I - eps C, k = 1 / mean diag(C).
  MatCreateSeqDense(PETSC_COMM_SELF, n, n, nullptr, &_C);
  MatCreateSeqDense(PETSC_COMM_SELF, n, n, nullptr, &_E);
  {
    Dense Z(_Z), C(_C), E(_E);
    double trace = 0;
    int counted = 0;
    for (PetscInt col = 0; col < n; ++col)
      for (PetscInt j = 0; j < n; ++j)
      {
        C(j, col) = Z(n + j, col) - Z(j, col);
        E(j, col) = (j == col ? 1.0 : 0.0) - _eps * C(j, col);
      }
    for (PetscInt j = 0; j < n; ++j)
      if (C(j, j) > 0)
      {
        trace += C(j, j);
        ++counted;
      }
    _k = counted > 0 ? double(counted) / trace : 1.0;
  }

  // dF/dd: 3 x 3 blocks of node pairs; the steel blocks map to nothing.
  ISLocalToGlobalMappingCreate(PETSC_COMM_SELF, 3, n_blocks, pair_of_block.data(),
                               PETSC_COPY_VALUES, &_l2g);
  MatCreate(PETSC_COMM_SELF, &_T);
  MatSetSizes(_T, n, n, n, n);
  MatSetType(_T, MATSEQBAIJ);
  MatSetBlockSize(_T, 3);
  MatSeqBAIJSetPreallocation(_T, 3, 9, nullptr);
  MatSetOption(_T, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE);
  MatSetLocalToGlobalMapping(_T, _l2g, _l2g);

  MatCreateVecs(_J0, &_b, nullptr);
  _r = create_vector();
  _d_b = create_vector();
  VecCreateSeq(PETSC_COMM_SELF, 2 * n, &_g);
  VecDuplicate(_b, &_rest);
  _Tv = create_vector();
  VecDuplicate(_g, &_Zr);
  _u.assign(std::size_t(3) * n_blocks, 0.0);
  _f.assign(_u.size(), 0.0);
}

Condensation::~Condensation()
{
  for (Vec* v : {&_b, &_r, &_d_b, &_g, &_rest, &_Tv, &_Zr})
    VecDestroy(v);
  for (auto* list : {&_basis, &_basis_g, &_basis_d})
    for (Vec& v : *list)
      VecDestroy(&v);
  for (Mat* m : {&_Z, &_C, &_E, &_T, &_factor, &_J0})
    MatDestroy(m);
  ISLocalToGlobalMappingDestroy(&_l2g);
}

Mat Condensation::create_matrix() const
{
  Mat J;
  MatCreateSeqDense(PETSC_COMM_SELF, size(), size(), nullptr, &J);
  MatCopy(_E, J, SAME_NONZERO_PATTERN);
  return J;
}

Vec Condensation::create_vector() const
{
  Vec v;
  VecCreateSeq(PETSC_COMM_SELF, size(), &v);
  return v;
}

void Condensation::configure(KSP ksp) const
{
  PC pc;
  KSPGetPC(ksp, &pc);
  PCFactorSetMatSolverType(pc, MATSOLVERPETSC);
  PCFactorSetMatOrderingType(pc, MATORDERINGNATURAL);
}

void Condensation::restrict_to(Vec x, Vec d) const
{
  const double* a;
  double* g;
  VecGetArrayRead(x, &a);
  VecGetArray(d, &g);
  for (std::size_t j = 0; j < _steel.size(); ++j)
    g[j] = a[_concrete[j]] - a[_steel[j]];
  VecRestoreArray(d, &g);
  VecRestoreArrayRead(x, &a);
}

void Condensation::restrict_functional(Vec a, Vec a_d) const
{
  const double* aa;
  double* g;
  VecGetArrayRead(a, &aa);
  VecGetArray(a_d, &g);
  double scale = 0, mismatch = 0;
  for (std::size_t j = 0; j < _steel.size(); ++j)
  {
    g[j] = aa[_concrete[j]];
    scale = std::max(scale, std::abs(g[j]));
    mismatch = std::max(mismatch, std::abs(aa[_steel[j]] + aa[_concrete[j]]));
  }
  VecRestoreArray(a_d, &g);
  VecRestoreArrayRead(a, &aa);
  if (mismatch > 1e-12 * scale)
    throw std::logic_error("condensation: the functional is not one of the jumps");
}

void Condensation::combine(const std::vector<double>& c, const std::vector<Vec>& v, Vec y)
{
  VecSet(y, 0.0);
  for (std::size_t k = 0; k < c.size(); ++k)
    VecAXPY(y, c[k], v[k]);
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
  VecNorm(_b, NORM_2, &b_norm);
  // Project b on the basis (classical Gram-Schmidt, twice).
  Vec rest = _rest;
  VecCopy(_b, rest);
  std::vector<double>& c = _load_c;
  c.assign(_basis.size(), 0.0);
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t k = 0; k < _basis.size(); ++k)
    {
      double ck;
      VecDot(_basis[k], rest, &ck);
      VecAXPY(rest, -ck, _basis[k]);
      c[k] += ck;
    }
  double r_norm;
  VecNorm(rest, NORM_2, &r_norm);
  if (r_norm > 1e-12 * b_norm)
  {
    if (_basis.size() == max_basis) // start again from b
    {
      for (auto* list : {&_basis, &_basis_g, &_basis_d})
      {
        for (Vec& v : *list)
          VecDestroy(&v);
        list->clear();
      }
      c.clear();
      VecCopy(_b, rest);
      r_norm = b_norm;
    }
    // The new direction q = rest / |rest|: J0^-1 q on the interface, and
    // its jumps.
    VecDuplicate(_b, &rest);
    VecCopy(_rest, rest);
    VecScale(rest, 1.0 / r_norm);
    Vec y, g, d;
    VecDuplicate(_b, &y);
    MatSolve(_factor, rest, y);
    VecDuplicate(_g, &g);
    d = create_vector();
    const double* ya;
    double *ga, *da;
    VecGetArrayRead(y, &ya);
    VecGetArray(g, &ga);
    VecGetArray(d, &da);
    const std::size_t n = _steel.size();
    for (std::size_t j = 0; j < n; ++j)
    {
      ga[j] = ya[_steel[j]];
      ga[n + j] = ya[_concrete[j]];
      da[j] = ga[n + j] - ga[j];
    }
    VecRestoreArray(d, &da);
    VecRestoreArray(g, &ga);
    VecRestoreArrayRead(y, &ya);
    VecDestroy(&y);
    _basis.push_back(rest);
    _basis_g.push_back(g);
    _basis_d.push_back(d);
    c.push_back(r_norm);
  }
  return c;
}

bool Condensation::interface_forces(Vec d, bool tangent, double* force_norm)
{
  const double* da;
  VecGetArrayRead(d, &da);
  for (std::size_t j = 0; j < _steel.size(); ++j)
  {
    _u[_steel[j]] = 0.0;
    _u[_concrete[j]] = da[j];
    _f[_steel[j]] = _f[_concrete[j]] = 0.0;
  }
  if (tangent)
    MatZeroEntries(_T);
  const bool ok = _eq.model().interface->assemble(_u, _f, tangent ? _T : nullptr);
  if (tangent)
  {
    MatAssemblyBegin(_T, MAT_FINAL_ASSEMBLY);
    MatAssemblyEnd(_T, MAT_FINAL_ASSEMBLY);
  }
  double* r;
  VecGetArray(_r, &r);
  double f2 = 0;
  for (std::size_t j = 0; j < _steel.size(); ++j)
  {
    const double F = _f[_concrete[j]];
    f2 += F * F;
    r[j] = F - _eps * da[j];
  }
  VecRestoreArray(_r, &r);
  VecRestoreArrayRead(d, &da);
  if (force_norm)
    *force_norm = std::sqrt(f2);
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
  MatMult(_C, _r, R);
  VecAXPY(R, 1.0, d);
  VecAXPY(R, -1.0, _d_b);
  VecScale(R, _k);
  return ok;
}

bool Condensation::jacobian(Vec d, Mat J)
{
  const bool ok = interface_forces(d, true); // dF/dd into _T
  PetscBool shell;
  PetscObjectTypeCompare(reinterpret_cast<PetscObject>(J), MATSHELL, &shell);
  if (!shell)
    form_jacobian(J);
  return ok;
}

void Condensation::form_jacobian(Mat J) const
{
  MatCopy(_E, J, SAME_NONZERO_PATTERN);
  {
    // J += C dF/dd, column by column: J(:, j) += T(i, j) C(:, i).
    Dense Jd(J), C(_C);
    const PetscInt n = size();
    for (PetscInt i = 0; i < n; ++i)
    {
      PetscInt ncols;
      const PetscInt* cols;
      const double* vals;
      MatGetRow(_T, i, &ncols, &cols, &vals);
      for (PetscInt c = 0; c < ncols; ++c)
      {
        const double t = vals[c];
        if (t == 0.0)
          continue;
        double* Jj = &Jd(0, cols[c]);
        const double* Ci = &C(0, i);
        for (PetscInt r = 0; r < n; ++r)
          Jj[r] += t * Ci[r];
      }
      MatRestoreRow(_T, i, &ncols, &cols, &vals);
    }
  }
  MatScale(J, _k);
}

Mat Condensation::create_operator() const
{
  Mat J;
  MatCreateShell(PETSC_COMM_SELF, size(), size(), size(), size(), const_cast<Condensation*>(this),
                 &J);
  MatShellSetOperation(J, MATOP_MULT, reinterpret_cast<void (*)(void)>(operator_mult));
  return J;
}

PetscErrorCode Condensation::operator_mult(Mat J, Vec v, Vec y)
{
  // y = k (v + C (dF/dd - eps) v).
  Condensation* self;
  MatShellGetContext(J, &self);
  MatMult(self->_T, v, self->_Tv);
  VecAXPY(self->_Tv, -self->_eps, v);
  MatMult(self->_C, self->_Tv, y);
  VecAXPY(y, 1.0, v);
  VecScale(y, self->_k);
  return 0;
}

void Condensation::copy_jacobian(Mat J, Mat P) const
{
  PetscBool shell;
  PetscObjectTypeCompare(reinterpret_cast<PetscObject>(J), MATSHELL, &shell);
  if (shell)
    form_jacobian(P);
  else
    MatCopy(J, P, SAME_NONZERO_PATTERN);
}

void Condensation::expand_interface(Vec d, Vec x)
{
  combine(load_coefficients(), _basis_g, _g);
  interface_forces(d, false);
  MatMult(_Z, _r, _Zr);
  VecAXPY(_g, -1.0, _Zr);
  const double* g;
  double* xa;
  VecGetArrayRead(_g, &g);
  VecGetArray(x, &xa);
  const std::size_t n = _steel.size();
  for (std::size_t j = 0; j < n; ++j)
  {
    xa[_steel[j]] = g[j];
    xa[_concrete[j]] = g[n + j];
  }
  VecRestoreArray(x, &xa);
  VecRestoreArrayRead(_g, &g);
  _eq.apply_constraints(x);
}

void Condensation::expand(Vec d, Vec x)
{
  load_coefficients(); // _b: the current loads
  interface_forces(d, false);
  // x = J0^-1 (b - E_I G_I^T r).
  Vec rhs = _rest;
  VecCopy(_b, rhs);
  double* ra;
  const double* r;
  VecGetArray(rhs, &ra);
  VecGetArrayRead(_r, &r);
  for (std::size_t j = 0; j < _steel.size(); ++j)
  {
    if (_steel_free[j])
      ra[_steel[j]] += r[j];
    if (_concrete_free[j])
      ra[_concrete[j]] -= r[j];
  }
  VecRestoreArrayRead(_r, &r);
  VecRestoreArray(rhs, &ra);
  MatSolve(_factor, rhs, x);
  VecGhostUpdateBegin(x, INSERT_VALUES, SCATTER_FORWARD);
  VecGhostUpdateEnd(x, INSERT_VALUES, SCATTER_FORWARD);
}
} // namespace pushout::solver

// The condensed system per Newton iteration (Condensation.h): the joints'
// forces at the jumps, the residual R(d) = k (d + C r - d_b) and its floor,
// the Jacobian k (I - eps C + C dF/dd) formed densely or applied
// matrix-free, the energy release of the joints, and the linear solver's
// set-up (dense LU, in single precision under GMRES).
#include "../common/petsc_check.h"
#include "Condensation.h"
#include "DenseArray.h"
#include "ShellPreconditioner.h"
#include "Vector.h"
#include <algorithm>
#include <cmath>
#include <limits>

namespace pushout::solver
{
using petsc::check;

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
      make_gmres_flexible(ksp);
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
    DenseArray Jd(J), C(_C);
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

} // namespace pushout::solver

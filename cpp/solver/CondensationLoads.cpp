// The loads and the whole model on the condensed system (Condensation.h):
// d_b from an orthonormal basis of the load directions solved so far (a
// solve with J0 only when the loads leave their span), whole-model vectors
// and functionals restricted to the jumps, and the jumps expanded to the
// whole model's displacements (the interface alone, or all by one solve).
#include "../common/petsc_check.h"
#include "Condensation.h"
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pushout::solver
{
using petsc::check;

namespace
{
/// Load directions kept before the basis starts again.
constexpr std::size_t max_basis = 6;
} // namespace

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

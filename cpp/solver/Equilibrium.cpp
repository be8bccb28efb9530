#include "Equilibrium.h"
#include "RigidBodyModes.h"
#include <cmath>
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/la/petsc.h>

namespace pushout::solver
{
Equilibrium::Equilibrium(model::Model& model)
    : _model(model), _f_interface(model.V->dofmap()->index_map, model.V->dofmap()->index_map_bs())
{
  _f_external = dolfinx::la::petsc::create_vector(*model.V->dofmap()->index_map,
                                                  model.V->dofmap()->index_map_bs());
  VecSet(_f_external, 0.0);
}

Equilibrium::~Equilibrium()
{
  if (_f_thermal)
    VecDestroy(&_f_thermal);
  VecDestroy(&_f_external);
}

void Equilibrium::set_temperature_change(double dT)
{
  if (dT == _dT)
    return; // the thermal load is assembled once per temperature change
  _dT = dT;
  ++_load_version;
  if (_f_thermal)
    VecDestroy(&_f_thermal);
  _f_thermal = dT != 0.0 ? _model.thermal_load(dT) : nullptr;
}

void Equilibrium::set_external_forces(const std::vector<std::pair<std::int32_t, double>>& forces)
{
  ++_load_version;
  VecSet(_f_external, 0.0);
  double* f;
  VecGetArray(_f_external, &f);
  for (const auto& [dof, value] : forces)
    f[dof] += value;
  VecRestoreArray(_f_external, &f);
}

void Equilibrium::apply_constraints(Vec x) const
{
  double* a;
  VecGetArray(x, &a);
  for (std::size_t i = 0; i < _bc.dofs.size(); ++i)
    a[_bc.dofs[i]] = _bc.values[i];
  VecRestoreArray(x, &a);
}

void Equilibrium::update_displacement(Vec x)
{
  const double* a;
  VecGetArrayRead(x, &a);
  std::span<double> u = _model.u->x()->mutable_array();
  const std::size_t n_owned =
      _model.V->dofmap()->index_map->size_local() * _model.V->dofmap()->index_map_bs();
  std::copy_n(a, n_owned, u.begin());
  VecRestoreArrayRead(x, &a);
  _model.u->x()->scatter_fwd();
}

bool Equilibrium::internal_forces(Vec x, Vec F)
{
  update_displacement(x);
  std::span<double> fi = _f_interface.mutable_array();
  std::fill(fi.begin(), fi.end(), 0.0);
  const bool ok = _model.interface->assemble(_model.u->x()->array(), fi, nullptr);
  _f_interface.scatter_rev(std::plus<double>());

  MatMult(_model.K, x, F);
  if (_f_thermal)
    VecAXPY(F, -1.0, _f_thermal);
  VecAXPY(F, -1.0, _f_external);
  double* f;
  VecGetArray(F, &f);
  PetscInt n_owned;
  VecGetLocalSize(F, &n_owned);
  for (PetscInt i = 0; i < n_owned; ++i)
    f[i] += fi[i];
  VecRestoreArray(F, &f);
  return ok;
}

bool Equilibrium::residual(Vec x, Vec F)
{
  double reaction_norm;
  return residual(x, F, reaction_norm);
}

bool Equilibrium::residual(Vec x, Vec F, double& reaction_norm)
{
  const bool ok = internal_forces(x, F);
  double* f;
  const double* a;
  VecGetArray(F, &f);
  VecGetArrayRead(x, &a);
  double r2 = 0;
  for (std::size_t i = 0; i < _bc.dofs.size(); ++i)
  {
    r2 += f[_bc.dofs[i]] * f[_bc.dofs[i]];
    f[_bc.dofs[i]] = a[_bc.dofs[i]] - _bc.values[i];
  }
  VecRestoreArrayRead(x, &a);
  VecRestoreArray(F, &f);
  MPI_Allreduce(MPI_IN_PLACE, &r2, 1, MPI_DOUBLE, MPI_SUM,
                PetscObjectComm(reinterpret_cast<PetscObject>(x)));
  reaction_norm = std::sqrt(r2);
  return ok;
}

void Equilibrium::linear_rhs(Vec b) const
{
  VecCopy(_f_external, b);
  if (_f_thermal)
    VecAXPY(b, 1.0, _f_thermal);
  double* a;
  VecGetArray(b, &a);
  for (std::size_t i = 0; i < _bc.dofs.size(); ++i)
    a[_bc.dofs[i]] = _bc.values[i];
  VecRestoreArray(b, &a);
}

Mat Equilibrium::create_matrix() const
{
  Mat J;
  MatDuplicate(_model.K, MAT_COPY_VALUES, &J);
  MatSetOption(J, MAT_KEEP_NONZERO_PATTERN, PETSC_TRUE);
  set_rigid_body_modes(_model, J); // for algebraic multigrid (-pc_type gamg)
  return J;
}

Vec Equilibrium::create_vector() const
{
  Vec v;
  MatCreateVecs(_model.K, nullptr, &v);
  return v;
}

bool Equilibrium::jacobian(Vec x, Mat J)
{
  update_displacement(x);
  MatCopy(_model.K, J, SAME_NONZERO_PATTERN);
  std::span<double> fi = _f_interface.mutable_array();
  std::fill(fi.begin(), fi.end(), 0.0);
  const bool ok = _model.interface->assemble(_model.u->x()->array(), fi, J);
  MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY);
  static_assert(sizeof(PetscInt) == sizeof(std::int32_t), "PETSc with 32-bit indices expected");
  MatZeroRowsLocal(J, PetscInt(_bc.dofs.size()), _bc.dofs.data(), 1.0, nullptr, nullptr);
  return ok;
}
} // namespace pushout::solver

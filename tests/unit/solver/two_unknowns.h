// A nonlinear problem of two unknowns on one process, for the solver's unit
// tests: the PETSc objects (a 2 x 2 AIJ matrix, LU), F and J from the
// derived class as plain arrays. No reactions (norm 1), no round-off floor,
// no energy release, no trial state.
#pragma once

#include "common/petsc_check.h"
#include "solver/NonlinearProblem.h"
#include <array>

namespace pushout::unit
{
class TwoUnknowns : public solver::NonlinearProblem
{
public:
  /// F(x) for the two unknowns.
  virtual std::array<double, 2> F(const std::array<double, 2>& x) = 0;
  /// The Jacobian given at x, row by row.
  virtual std::array<double, 4> J(const std::array<double, 2>& x) = 0;

  Mat create_matrix() const override
  {
    Mat J;
    petsc::check(MatCreateSeqAIJ(PETSC_COMM_SELF, 2, 2, 2, nullptr, &J), "MatCreateSeqAIJ");
    return J;
  }
  Vec create_vector() const override
  {
    Vec v;
    petsc::check(VecCreateSeq(PETSC_COMM_SELF, 2, &v), "VecCreateSeq");
    return v;
  }
  bool residual(Vec x, Vec F_out) override
  {
    const std::array<double, 2> f = F(values(x));
    PetscScalar* Fa;
    petsc::check(VecGetArray(F_out, &Fa), "VecGetArray");
    Fa[0] = f[0];
    Fa[1] = f[1];
    petsc::check(VecRestoreArray(F_out, &Fa), "VecRestoreArray");
    return true;
  }
  bool residual(Vec x, Vec F_out, double& reaction_norm) override
  {
    reaction_norm = 1.0;
    return residual(x, F_out);
  }
  bool jacobian(Vec x, Mat J_out) override
  {
    const std::array<double, 4> j = J(values(x));
    const PetscInt rows[2] = {0, 1};
    petsc::check(MatZeroEntries(J_out), "MatZeroEntries");
    petsc::check(MatSetValues(J_out, 2, rows, 2, rows, j.data(), INSERT_VALUES), "MatSetValues");
    petsc::check(MatAssemblyBegin(J_out, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    petsc::check(MatAssemblyEnd(J_out, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    return true;
  }
  bool energy_release(Vec, double&, Vec) override { return false; }
  double residual_floor(Vec) override { return 0.0; }
  void configure(KSP ksp) const override
  {
    PC pc;
    petsc::check(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
    petsc::check(KSPGetPC(ksp, &pc), "KSPGetPC");
    petsc::check(PCSetType(pc, PCLU), "PCSetType");
  }
  void forget_trial_state() override {}

  /// The two entries of x.
  static std::array<double, 2> values(Vec x)
  {
    const PetscScalar* a;
    petsc::check(VecGetArrayRead(x, &a), "VecGetArrayRead");
    const std::array<double, 2> v = {a[0], a[1]};
    petsc::check(VecRestoreArrayRead(x, &a), "VecRestoreArrayRead");
    return v;
  }
};
} // namespace pushout::unit

// The push force P of curve.csv is the axial resultant of the interface
// tractions (specimen/PushOut.h); paper eq. (1) and the README define it as the
// sum of the support reactions. At equilibrium the two are the same: check
// it after the thermal step and a push step on a coarse quarter model, with
// friction + exponential softening, trilinear and triquadratic bulk.
#include "mesh/generate.h"
#include "model/Model.h"
#include "scene/Scene.h"
#include "solver/Equilibrium.h"
#include "solver/NewtonSolver.h"
#include "specimen/PushOut.h"
#include <cmath>
#include <dolfinx/la/petsc.h>
#include <gtest/gtest.h>

namespace
{
using namespace pushout;

/// |P_interface - P_supports| / |P_supports| after one push step, over
/// the bound Newton's tolerance sets on it: the two differ by the sum of the
/// free rows' residual in z, at most sqrt(N) |F| <= sqrt(N) (snes_rtol |F0|
/// + snes_atol) over N dofs, and the step's initial out-of-balance |F0| is
/// at most the forces it changes, P (as common.newton_bound reasons).
double push_force_mismatch_over_bound(int degree)
{
  const Scene scene =
      Scene::parse("[mesh]\nelements_per_quarter = 4\nelements_through_thickness = 2\n"
                   "[[interface]]\nlaw = \"friction\"\nk = 1000.0\nmu = 0.4\n"
                   "[[interface]]\nlaw = \"exponential_softening\"\nk = 1000.0\nf_t = 3.0\n"
                   "c = 25.0\n[loading]\ntemperature_change = -25.0\n"
                   "push_displacement = 0.005\nsteps = 1\n",
                   {{"mesh.degree", std::to_string(degree)}});
  bool reused = false;
  const pushout::mesh::MeshData data = pushout::mesh::generate(
      pushout::mesh::MeshInput::of(scene), pushout::mesh::default_cache_dir(), reused);
  model::Model model(MPI_COMM_WORLD, data, model::ModelInput::of(scene));
  specimen::PushOut pushout(pushout::mesh::MeshInput::of(scene), scene.loading(),
                            scene.layers().size(), data, model);
  solver::Equilibrium eq(model);
  solver::NewtonSolver::set_default_options(solver::NewtonSolver::Preconditioner::jacobian);
  solver::NewtonSolver newton(eq, solver::NewtonSolver::Preconditioner::jacobian);
  Vec x = model.create_vector();
  VecSet(x, 0.0);
  pushout.apply_load(0.0, eq);
  eq.apply_constraints(x);
  EXPECT_TRUE(newton.solve(x).converged);
  model.interface().state().commit();
  PetscInt n;
  VecGetLocalSize(x, &n);
  const double* xa;
  VecGetArrayRead(x, &xa);
  pushout.start_loading(std::span<const double>(xa, n));
  VecRestoreArrayRead(x, &xa);
  pushout.apply_load(1.0, eq);
  eq.apply_constraints(x);
  EXPECT_TRUE(newton.solve(x).converged);

  // Support reactions: the constrained z dofs of the concrete at z = 0
  // (the tube top is at z = L; the symmetry planes hold x and y).
  Vec reactions;
  VecDuplicate(x, &reactions);
  eq.internal_forces(x, reactions);
  const std::vector<double> X = model.space()->tabulate_dof_coordinates(false);
  const double* r;
  VecGetArrayRead(reactions, &r);
  double P_supports = 0;
  for (std::int32_t d : eq.constraints().dofs)
    if (d % 3 == 2 && std::abs(X[d]) < 1e-9) // X[3 block + 2] = z of the block
      P_supports += r[d];
  VecRestoreArrayRead(reactions, &r);
  const double P_interface = model.interface().resultant()[2];
  VecDestroy(&reactions);
  PetscInt N = 0;
  VecGetSize(x, &N);
  VecDestroy(&x);
  EXPECT_GT(std::abs(P_supports), 10.0); // N: a real push, not a trivial zero
  PetscReal rtol = 0, atol = 0;          // as set_default_options() set them
  PetscBool set = PETSC_FALSE;
  PetscOptionsGetReal(nullptr, nullptr, "-snes_rtol", &rtol, &set);
  PetscOptionsGetReal(nullptr, nullptr, "-snes_atol", &atol, &set);
  const double bound = std::sqrt(double(N)) * (rtol + atol / std::abs(P_supports));
  return std::abs(P_interface - P_supports) / std::abs(P_supports) / bound;
}
} // namespace

TEST(PushForce, InterfaceResultantEqualsSupportReactions)
{
  EXPECT_LE(push_force_mismatch_over_bound(1), 1.0);
}

TEST(PushForce, InterfaceResultantEqualsSupportReactionsQuadratic)
{
  EXPECT_LE(push_force_mismatch_over_bound(2), 1.0);
}

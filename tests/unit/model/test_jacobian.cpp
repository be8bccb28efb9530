// The consistent tangent in the assembled system: on a coarse push-out with
// a sliding friction interface, J v equals the central finite difference of
// the assembled residual F along random directions v.
#include "mesh/generate.h"
#include "model/Model.h"
#include "scene/Scene.h"
#include "solver/Equilibrium.h"
#include "solver/NewtonSolver.h"
#include <cmath>
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/la/petsc.h>
#include <gtest/gtest.h>
#include <random>

namespace
{
using namespace pushout;

double jacobian_error(const std::string& quadrature, int degree = 1)
{
  const Scene scene = Scene::parse(
      "[mesh]\nelements_per_quarter = 4\n"
      "elements_through_thickness = 2\n"
      "[[interface]]\nlaw = \"friction\"\nk = 1000.0\nmu = 0.4\n",
      {{"mesh.interface_quadrature", quadrature}, {"mesh.degree", std::to_string(degree)}});
  bool reused = false;
  const pushout::mesh::MeshData data = pushout::mesh::generate(
      pushout::mesh::MeshInput::of(scene), pushout::mesh::default_cache_dir(), reused);
  model::Model model(MPI_COMM_WORLD, data, model::ModelInput::of(scene));
  solver::Equilibrium eq(model);
  solver::NewtonSolver::set_default_options(solver::NewtonSolver::Preconditioner::jacobian);

  // A loaded state: shrinkage presses the interface; then give the whole
  // concrete a vertical shift so that every point slides, plus noise.
  eq.set_temperature_change(-25.0);
  Vec x = model.create_vector();
  VecSet(x, 0.0);
  {
    solver::NewtonSolver newton(eq, solver::NewtonSolver::Preconditioner::jacobian);
    EXPECT_TRUE(newton.solve(x).converged);
  }
  model.interface().state().commit();
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> U(-1, 1);
  PetscInt n;
  VecGetLocalSize(x, &n);
  double* xa;
  VecGetArray(x, &xa);
  for (PetscInt i = 0; i < n; ++i)
    xa[i] += 1e-4 * U(gen) + (i % 3 == 2 ? 2e-3 : 0.0);
  VecRestoreArray(x, &xa);

  Mat J;
  MatDuplicate(model.stiffness(), MAT_COPY_VALUES, &J);
  EXPECT_TRUE(eq.jacobian(x, J));
  Vec v, Jv, Fp, Fm, xp, xm;
  for (Vec* w : {&v, &Jv, &Fp, &Fm, &xp, &xm})
    VecDuplicate(x, w);
  double worst = 0;
  // A central difference errs by its truncation (~h^2, large where a step
  // crosses a stick/slip kink) and by the residual's round-off (~eps |F| /
  // h, whose size depends on the state's cancellations, and so on the BLAS
  // threads and the generated forms' last digits): each direction takes the
  // best of three steps, where one of the two is small. A wrong tangent is
  // wrong at every step.
  for (int trial = 0; trial < 3; ++trial)
  {
    double* va;
    VecGetArray(v, &va);
    for (PetscInt i = 0; i < n; ++i)
      va[i] = U(gen);
    VecRestoreArray(v, &va);
    MatMult(J, v, Jv);
    double norm_Jv;
    VecNorm(Jv, NORM_INFINITY, &norm_Jv);
    double best = INFINITY;
    for (const double h : {1e-6, 1e-7, 1e-8}) // mm
    {
      VecWAXPY(xp, h, v, x);
      VecWAXPY(xm, -h, v, x);
      eq.internal_forces(xp, Fp);
      eq.internal_forces(xm, Fm);
      VecAXPY(Fp, -1.0, Fm);
      VecScale(Fp, 1.0 / (2 * h));
      // Free rows only: J's constrained rows are identity; there are no
      // constraints set here, so all rows are compared.
      VecAXPY(Fp, -1.0, Jv);
      double diff;
      VecNorm(Fp, NORM_INFINITY, &diff);
      best = std::min(best, diff / norm_Jv);
    }
    worst = std::max(worst, best);
  }
  for (Vec* w : {&v, &Jv, &Fp, &Fm, &xp, &xm, &x})
    VecDestroy(w);
  MatDestroy(&J);
  return worst;
}
} // namespace

TEST(Jacobian, AssembledTangentMatchesFiniteDifferencesGauss)
{
  EXPECT_LT(jacobian_error("gauss"), 1e-6);
}

TEST(Jacobian, AssembledTangentMatchesFiniteDifferencesNodal)
{
  EXPECT_LT(jacobian_error("nodal"), 1e-6);
}

// The triquadratic bulk (mesh.degree = 2): 9-node joint elements.
TEST(Jacobian, AssembledTangentMatchesFiniteDifferencesQuadraticGauss)
{
  EXPECT_LT(jacobian_error("gauss", 2), 1e-6);
}

TEST(Jacobian, AssembledTangentMatchesFiniteDifferencesQuadraticNodal)
{
  EXPECT_LT(jacobian_error("nodal", 2), 1e-6);
}

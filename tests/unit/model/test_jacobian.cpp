// The consistent tangent in the assembled system: on a coarse push-out with
// a sliding friction interface, J v equals the central finite difference of
// the assembled residual F along random directions v.
#include "central_difference.h"
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
  // Directions of unit size per dof, steps where one of the two errors is
  // small (unit::worst_relative_error). No constraints are set here: J has
  // no identity rows, and every row is compared.
  const double worst = unit::tangent_error(eq, J, x, gen, 1.0, {1e-6, 1e-7, 1e-8});
  VecDestroy(&x);
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

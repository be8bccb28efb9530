// The cracking cells' elasticity at the crack band's points
// (forms/cracking.py, a_rule; BulkCracking::add_elastic_rule):
// K (forms/elasticity.py, FFCx's 3 x 3 x 3 points) plus a_rule, with the
// cracks' tangent C_t - C = -C at every point (a crack band that lost all
// its stiffness), leaves no stiffness at all; without a_rule, on hexahedra
// that are not parallelepipeds, more than 1e-5 of K is left. The thermal load
// (FFCx's 3 x 3 x 3 points too) balances the cracks' forces at u = 0
// (sigma = 0 there) without such a change: both rules integrate it
// exactly. On PETSC_COMM_WORLD (unit_two_processes runs it on two).
#include "bulk/Voigt.h"
#include "common/petsc_check.h"
#include "cracking.h"
#include "elasticity.h"
#include "mesh/generate.h"
#include "model/Model.h"
#include "scene/Scene.h"
#include "uniform_materials.h"
#include <cmath>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/fem/utils.h>
#include <dolfinx/la/petsc.h>
#include <dolfinx/mesh/generation.h>
#include <gtest/gtest.h>
#include <numeric>
#include <petscmat.h>
#include <petscvec.h>

using namespace pushout;
namespace fem = dolfinx::fem;
using petsc::check;

namespace
{
constexpr double E = 30000.0, nu = 0.2, alpha = 1e-5, dT = -25.0; // MPa, -, 1/degC, degC

/// A box of 3 x 2 x 2 hexahedra [mm], its inner nodes moved so that no cell
/// is a parallelepiped.
std::shared_ptr<dolfinx::mesh::Mesh> distorted_box()
{
  auto mesh = std::make_shared<dolfinx::mesh::Mesh>(dolfinx::mesh::create_box(
      PETSC_COMM_WORLD, {{{0, 0, 0}, {3, 2, 2}}}, {3, 2, 2}, dolfinx::mesh::CellType::hexahedron,
      dolfinx::mesh::GhostMode::none));
  std::span<double> x = mesh->geometry().x();
  for (std::size_t i = 0; i < x.size() / 3; ++i)
  {
    double* p = x.data() + 3 * i;
    const double bump = p[0] * (3 - p[0]) * p[1] * (2 - p[1]) * p[2] * (2 - p[2]); // 0 on the faces
    p[0] += 0.15 * bump;
    p[1] -= 0.1 * bump;
  }
  return mesh;
}

struct Forms
{
  std::shared_ptr<fem::FunctionSpace> V;
  std::shared_ptr<fem::Form<double>> K, a_rule, a_crack, L_thermal, L_crack;
};

/// Every cell cracking (the region all of the mesh), each point's crack
/// without stiffness: C_t - C = -C, and sigma - C : eps_e = C : alpha dT I
/// at u = 0.
Forms forms(std::shared_ptr<dolfinx::mesh::Mesh> mesh)
{
  Forms f;
  f.V = std::make_shared<fem::FunctionSpace>(
      fem::create_functionspace(functionspace_form_elasticity_a, "u", mesh));
  const auto materials = unit::uniform_materials(mesh, E, nu, alpha);
  auto temperature = std::make_shared<fem::Constant<double>>(dT);
  const std::map<std::string, std::shared_ptr<const fem::Constant<double>>> none;
  f.K = std::make_shared<fem::Form<double>>(
      fem::create_form<double>(*form_elasticity_a, {f.V, f.V}, materials, none, {}));
  f.L_thermal = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      *form_elasticity_L_thermal, {f.V}, materials, {{"dT", temperature}}, {}));

  const int tdim = mesh->topology().dim();
  const std::int32_t n_cells = mesh->topology().index_map(tdim)->size_local() +
                               mesh->topology().index_map(tdim)->num_ghosts();
  std::vector<std::int32_t> cells(n_cells);
  std::iota(cells.begin(), cells.end(), 0);
  auto region = std::make_shared<dolfinx::mesh::MeshTags<std::int32_t>>(
      mesh, tdim, std::vector<std::int32_t>(cells), std::vector<std::int32_t>(cells.size(), 1));
  const std::map<fem::IntegralType, const dolfinx::mesh::MeshTags<int>*> subdomains = {
      {fem::IntegralType::cell, region.get()}};
  const std::map<std::string, std::shared_ptr<const fem::Constant<double>>> stiffness = {
      {"E_c", std::make_shared<fem::Constant<double>>(E)},
      {"nu_c", std::make_shared<fem::Constant<double>>(nu)}};
  const std::map<std::string, std::shared_ptr<const fem::Function<double>>> no_coefficients;
  f.a_rule = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      *form_cracking_a_rule, {f.V, f.V}, no_coefficients, stiffness, subdomains));

  auto d_C = std::make_shared<fem::Function<double>>(std::make_shared<fem::FunctionSpace>(
      fem::create_functionspace(functionspace_form_cracking_a_crack, "d_C", mesh)));
  auto d_sigma = std::make_shared<fem::Function<double>>(std::make_shared<fem::FunctionSpace>(
      fem::create_functionspace(functionspace_form_cracking_L_crack, "d_sigma", mesh)));
  const bulk::Voigt66 C = bulk::isotropic_stiffness(E, nu);
  const bulk::Voigt free = bulk::multiply(C, {alpha * dT, alpha * dT, alpha * dT, 0, 0, 0});
  std::span<double> c = d_C->x()->mutable_array(), s = d_sigma->x()->mutable_array();
  for (std::size_t i = 0; i < c.size(); ++i)
    c[i] = -C[i % 36];
  for (std::size_t i = 0; i < s.size(); ++i)
    s[i] = free[i % 6];
  f.a_crack = std::make_shared<fem::Form<double>>(
      fem::create_form<double>(*form_cracking_a_crack, {f.V, f.V}, {{"d_C", d_C}}, {}, subdomains));
  f.L_crack = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      *form_cracking_L_crack, {f.V}, {{"d_sigma", d_sigma}}, {}, subdomains));
  return f;
}

/// The Frobenius norm of the sum of the forms' matrices [N/mm].
double norm_of_sum(const std::vector<const fem::Form<double>*>& a)
{
  Mat A = dolfinx::fem::petsc::create_matrix(*a.front());
  check(MatZeroEntries(A), "MatZeroEntries");
  for (const fem::Form<double>* form : a)
    fem::assemble_matrix(dolfinx::la::petsc::Matrix::set_block_fn(A, ADD_VALUES), *form, {});
  check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  double norm = 0;
  check(MatNorm(A, NORM_FROBENIUS, &norm), "MatNorm");
  check(MatDestroy(&A), "MatDestroy");
  return norm;
}

/// The norm of sum_i sign_i L_i over all processes' local (unsummed) parts
/// [N]: each cell's contributions cancel or not whatever the ghosts.
double norm_of_sum(const fem::FunctionSpace& V,
                   const std::vector<std::pair<double, const fem::Form<double>*>>& L)
{
  const std::size_t n =
      std::size_t(V.dofmap()->index_map->size_local() + V.dofmap()->index_map->num_ghosts()) *
      std::size_t(V.dofmap()->index_map_bs());
  std::vector<double> sum(n, 0.0);
  for (const auto& [sign, form] : L)
  {
    std::vector<double> b(n, 0.0);
    fem::assemble_vector(std::span<double>(b), *form);
    for (std::size_t i = 0; i < n; ++i)
      sum[i] += sign * b[i];
  }
  double squares = 0;
  for (double v : sum)
    squares += v * v;
  MPI_Allreduce(MPI_IN_PLACE, &squares, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  return std::sqrt(squares);
}
} // namespace

TEST(CrackingRule, ACrackWithoutStiffnessKeepsNoneOfK)
{
  const Forms f = forms(distorted_box());
  const double K = norm_of_sum({f.K.get()});
  // Round-off of sums of entries of the order of E h (1e4 N/mm).
  EXPECT_LT(norm_of_sum({f.K.get(), f.a_rule.get(), f.a_crack.get()}), 1e-12 * K);
  EXPECT_GT(norm_of_sum({f.K.get(), f.a_crack.get()}), 1e-5 * K); // without a_rule
}

TEST(CrackingRule, ACrackWithoutStiffnessFeelsNoThermalLoad)
{
  const Forms f = forms(distorted_box());
  const double L = norm_of_sum(*f.V, {{1.0, f.L_thermal.get()}});
  // f(u = 0) = K 0 - f_thermal + f_crack: zero to round-off.
  EXPECT_LT(norm_of_sum(*f.V, {{-1.0, f.L_thermal.get()}, {1.0, f.L_crack.get()}}), 1e-12 * L);
}

// The model's K takes its cracking cells at the crack band's points once,
// with the concrete's E and nu (Model's constructor): K v equals forms/
// elasticity.py's a plus forms/cracking.py's a_rule on the concrete (all of
// it may crack here) applied to a random v, to round-off; a_rule itself is
// far from round-off there.
TEST(CrackingRule, TheModelsStiffnessTakesItOnce)
{
  const Scene scene = Scene::parse("[mesh]\nelements_per_quarter = 4\n"
                                   "elements_through_thickness = 2\n"
                                   "[[interface]]\nlaw = \"elastic\"\nk = 1000.0\n"
                                   "[cracking]\nmodel = \"embedded\"\n");
  bool reused = false;
  const pushout::mesh::MeshData data = pushout::mesh::generate(
      pushout::mesh::MeshInput::of(scene), pushout::mesh::default_cache_dir(), reused);
  const model::Model model(PETSC_COMM_WORLD, data, model::ModelInput::of(scene));
  auto V = std::const_pointer_cast<fem::FunctionSpace>(model.space());
  auto mesh = model.mesh();
  const model::Materials& m = model.materials();
  const std::map<std::string, std::shared_ptr<const fem::Function<double>>> materials = {
      {"E", m.E}, {"nu", m.nu}, {"alpha", m.alpha}};
  const std::map<std::string, std::shared_ptr<const fem::Constant<double>>> none;
  const fem::Form<double> a =
      fem::create_form<double>(*form_elasticity_a, {V, V}, materials, none, {});
  // The concrete's cells: those of its E (the steel's is another).
  const int tdim = mesh->topology().dim();
  const std::int32_t n_cells = mesh->topology().index_map(tdim)->size_local();
  const std::span<const double> E = m.E->x()->array();
  std::vector<std::int32_t> concrete;
  for (std::int32_t c = 0; c < n_cells; ++c)
    if (E[m.E->function_space()->dofmap()->cell_dofs(c)[0]] == scene.concrete().E)
      concrete.push_back(c);
  const dolfinx::mesh::MeshTags<std::int32_t> region(mesh, tdim,
                                                     std::vector<std::int32_t>(concrete),
                                                     std::vector<std::int32_t>(concrete.size(), 1));
  const std::map<fem::IntegralType, const dolfinx::mesh::MeshTags<int>*> subdomains = {
      {fem::IntegralType::cell, &region}};
  const std::map<std::string, std::shared_ptr<const fem::Function<double>>> no_coefficients;
  const fem::Form<double> a_rule = fem::create_form<double>(
      *form_cracking_a_rule, {V, V}, no_coefficients,
      {{"E_c", std::make_shared<fem::Constant<double>>(scene.concrete().E)},
       {"nu_c", std::make_shared<fem::Constant<double>>(scene.concrete().nu)}},
      subdomains);

  const auto matrix = [](const fem::Form<double>& form)
  {
    Mat A = dolfinx::fem::petsc::create_matrix(form);
    check(MatZeroEntries(A), "MatZeroEntries");
    fem::assemble_matrix(dolfinx::la::petsc::Matrix::set_block_fn(A, ADD_VALUES), form, {});
    check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    return A;
  };
  Mat A = matrix(a), R = matrix(a_rule);
  Vec v = model.create_vector(), Kv = model.create_vector(), Av = model.create_vector(),
      Rv = model.create_vector();
  PetscRandom random;
  check(PetscRandomCreate(PETSC_COMM_WORLD, &random), "PetscRandomCreate");
  check(VecSetRandom(v, random), "VecSetRandom"); // [mm]
  check(MatMult(model.stiffness(), v, Kv), "MatMult");
  check(MatMult(A, v, Av), "MatMult");
  check(MatMult(R, v, Rv), "MatMult");
  double norms[2];
  check(VecNorm(Kv, NORM_2, &norms[0]), "VecNorm");
  check(VecNorm(Rv, NORM_2, &norms[1]), "VecNorm");
  check(VecAXPY(Kv, -1.0, Av), "VecAXPY");
  check(VecAXPY(Kv, -1.0, Rv), "VecAXPY");
  double left = 0;
  check(VecNorm(Kv, NORM_2, &left), "VecNorm");
  EXPECT_LT(left, 1e-12 * norms[0]); // round-off of sums of entries of E h
  EXPECT_GT(norms[1], 1e-6 * norms[0]);
  for (Mat* M : {&A, &R})
    check(MatDestroy(M), "MatDestroy");
  for (Vec* w : {&v, &Kv, &Av, &Rv})
    check(VecDestroy(w), "VecDestroy");
  check(PetscRandomDestroy(&random), "PetscRandomDestroy");
}

// Mesh objectivity of the concrete's cracks (model/BulkCracking.h) over the
// whole softening branch: a concrete prism 100 x 10 x 10 mm pulled apart
// along its axis, with a shallow waist at its middle (its side 2 % less
// there, over some 15 mm: the same on every mesh), on three meshes refined
// in every direction (5 x 1 x 1, 11 x 2 x 2 and 21 x 4 x 4 cells: 20, 9.1
// and 4.8 mm along the prism). One crack opens through the middle row of
// cells (odd n: a row at the waist; on the finest mesh 4 points of its
// neighbours crack too and unload), the rest of the prism unloads, and
//
// - the energy the cracks dissipate is G_F per unit of crack area, G_F
//   times the middle row's section A_n, within 1 % (measured -0.16, -0.24
//   and -0.21 %; the prism is pulled to an opening where exp(-c w) is
//   1e-4);
// - the force-elongation curve past the peak, F(delta), follows the bar's
//   closed form delta = F C + w(F / A_n) within 3 % (measured 0.75 %), C
//   the prism's elastic compliance by the bar's one-dimensional formula and
//   w the law's opening at the stress f_t exp(-c w); the gap grows with w,
//   as from a band a little wider than the cell's length (the waist tilts
//   the cracks' normals: the band is the cell's extent along the normal);
// - each mesh's F over its own closed form agrees with the finest mesh's
//   within 1 % (measured 0.3 %): the closed forms themselves differ by
//   1.4 to 1.7 % from mesh to mesh (A_n and C), so this is the objectivity
//   check; F itself agrees with the finest mesh's within 5 % (measured
//   1.8 %).
//
// With a crack band 10 mm wide on every mesh instead of the element's
// projected size the coarsest mesh dissipates 18.94 N mm against G_F A_n =
// 9.75 and the curves part by far more than 5 % (checked): the band's
// regularisation is what holds them. The normal runs along the prism, so
// the band is the cells' length along it; a fourth mesh, 21 x 1 x 1 (cells
// 4.8 x 10 x 10 mm, wider than long), checks that it is not their largest
// extent (which would halve the energy there): its energy within 1 %
// (measured -0.7 %) and its curve within 3 % of the closed form (measured
// 2.2 %: the tilt above, across cells twice as wide). A band by the
// cells' length along x would pass these too: the last two tests shear the
// cells, so that the crack crosses their faces obliquely, where the
// projected extent is too wide and cracking.band_width = "row" holds.
// The uniform ring and cover of the push-out bifurcate past their peak
// (docs/cracking.md, "Still to come"); the prism's waist leaves it one
// crack to open, so this checks the regularisation alone. Newton on the
// implicit cracks with their consistent tangent, one process, a direct
// solve, to 1e-9 of the peak force: far below the bounds above.
//
// The same with IMPL-EX cracks (the default integration; the strain
// predictor, each step committing the crack band's own update, the steps'
// error not checked): energy -0.16, -0.24 and -0.12 % (21 x 1 x 1: -0.56
// %, its F within 2.2 %), F within 1.1 % of the closed form (IMPL-EX lags just past the peak:
// 0.99 at delta = 0.02 mm), each mesh's ratio within 0.2 % of the finest
// mesh's, under the same bounds.
#include "common/petsc_check.h"
#include "elasticity.h"
#include "mesh/MeshData.h"
#include "model/BulkCracking.h"
#include "model/CellWidth.h"
#include "uniform_materials.h"
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/fem/utils.h>
#include <dolfinx/la/petsc.h>
#include <dolfinx/mesh/generation.h>
#include <gtest/gtest.h>
#include <memory>
#include <petscksp.h>
#include <span>
#include <stdexcept>
#include <vector>

using namespace pushout;
namespace fem = dolfinx::fem;
using petsc::check;

namespace
{
constexpr double E = 30000.0, nu = 0.2, alpha = 1e-5;     // MPa, -, 1/degC
constexpr double f_t = 3.0, c = 30.0;                     // MPa, 1/mm: G_F = f_t / c = 0.1 N/mm
constexpr double L = 100.0, side = 10.0;                  // prism length and square side [mm]
constexpr double waist_depth = 0.02, waist_length = 15.0; // -, mm: see waist()
constexpr double G_F = f_t / c;                           // N/mm
constexpr double A = side * side;                         // mm^2

/// How a prism is meshed and its cracks integrated.
struct Setup
{
  bool implex = false;   ///< IMPL-EX cracks (else implicit)
  double shear = 0;      ///< the inner node planes' shear, x moved by shear (y - side / 2) [-]
  bool row_band = false; ///< cracking.band_width = "row" (else projected)
};

/// One prism's run: its elongation [mm] and force [N] at each converged
/// step, the energy its cracks dissipated [N mm], the middle cell's length
/// [mm] and how many points cracked.
struct Pull
{
  std::vector<double> delta, force;
  double dissipated = 0;
  double h = 0;
  std::int64_t cracked = 0; ///< points cracked at the end
};

/// The prism's side at x over `side` [-]: a shallow waist at the middle,
/// so that the crack opens there, the same on every mesh (a notch of one
/// cell would steepen with the mesh and tilt the stress).
double waist(double x)
{
  const double s = (x - L / 2) / waist_length;
  return 1 - waist_depth * std::exp(-s * s);
}

/// Where a node of the box [0, L] x [0, side]^2 goes [mm]: its node plane
/// scaled to waist(x) about the edge y = z = 0, then sheared in x by
/// `shear` (y - side / 2) sin(pi x / L): the same prism (its ends and sides
/// stay), its cells round the middle parallelepipeds whose x faces lean by
/// atan(shear).
bulk::Vec3 prism_node(const bulk::Vec3& box, double shear)
{
  const double y = box[1] * waist(box[0]), z = box[2] * waist(box[0]);
  return {box[0] + shear * (y - side / 2) * std::sin(M_PI * box[0] / L), y, z};
}

/// The prism on n cells along x (n odd: a cell at the middle) and m across
/// (prism_node).
std::shared_ptr<dolfinx::mesh::Mesh> waisted_prism(int n, int m, double shear)
{
  auto mesh = std::make_shared<dolfinx::mesh::Mesh>(dolfinx::mesh::create_box(
      MPI_COMM_SELF, {{{0, 0, 0}, {L, side, side}}},
      {std::size_t(n), std::size_t(m), std::size_t(m)}, dolfinx::mesh::CellType::hexahedron,
      dolfinx::mesh::GhostMode::none));
  std::span<double> x = mesh->geometry().x();
  for (std::size_t i = 0; i < x.size() / 3; ++i)
  {
    const bulk::Vec3 p = prism_node({x[3 * i], x[3 * i + 1], x[3 * i + 2]}, shear);
    std::copy(p.begin(), p.end(), x.begin() + std::ptrdiff_t(3 * i));
  }
  return mesh;
}

/// The middle cell's section on n cells along x [mm^2]: where the crack
/// opens.
double middle_section(int n)
{
  const double s = waist(L / 2 + L / (2 * n));
  return s * s * A;
}

/// The prism's elastic compliance on n cells by the bar's formula, the sum
/// over its cells of int dx / (E A(x)), the side linear in x within a cell
/// from s0 to s1 (so the integral h / (E A s0 s1)) [mm/N].
double compliance(int n)
{
  const double h = L / n;
  double C = 0;
  for (int i = 0; i < n; ++i)
    C += h / (E * A * waist(i * h) * waist((i + 1) * h));
  return C;
}

/// The closed form's force at elongation `delta` past the peak [N]: the
/// root of delta = F C + w(F / A_n), w(sigma) = ln(f_t / sigma) / c.
double closed_form_force(double delta, double C, double A_n)
{
  double lo = 1e-12, hi = f_t * A_n; // delta(F) falls with F past the peak
  for (int k = 0; k < 200; ++k)
  {
    const double F = 0.5 * (lo + hi);
    (F * C + std::log(f_t * A_n / F) / c > delta ? lo : hi) = F;
  }
  return 0.5 * (lo + hi);
}

/// The prism on n x m x m cells with its concrete's cracks, its stiffness
/// K (the cracking cells at the crack band's points, as Model makes it) and
/// its supports: u_x = 0 at x = 0 and the elongation at x = L, u_y = 0 on
/// y = 0, u_z = 0 on z = 0 (rollers: the section contracts freely).
class PulledPrism
{
public:
  PulledPrism(int n, int m, const Setup& setup) : _mesh(waisted_prism(n, m, setup.shear))
  {
    _V = std::make_shared<fem::FunctionSpace>(
        fem::create_functionspace(functionspace_form_elasticity_a, "u", _mesh));
    const auto materials = unit::uniform_materials(_mesh, E, nu, alpha); // no dT here
    const fem::Form<double> a =
        fem::create_form<double>(*form_elasticity_a, {_V, _V}, materials, {}, {});
    _u = std::make_shared<fem::Function<double>>(_V);

    const std::int32_t n_cells = _mesh->topology().index_map(3)->size_local();
    const std::vector<std::int32_t> material(std::size_t(n_cells), pushout::mesh::concrete);
    CrackingPart part; // implicit cracks, uniform strength, all the concrete
    part.embedded = true;
    part.f_t = f_t;
    part.c = c;
    part.correlation_length = 5.0;
    part.seed = 1;
    part.visible_width = 0.05;
    part.implex = setup.implex;
    part.row_band = setup.row_band;
    part.predict_strain = true; // IMPL-EX's default predictor
    part.implex_tolerance = 1;  // unused: the test does not check the steps' error
    // The cracking region's centre, the surface readings' faces and the
    // nominal fracture energy of dissipation control: none of them used here.
    Geometry slice;
    slice.width = L;
    slice.thickness = side;
    slice.tube_center = {L / 2, L / 2};
    _cracking = std::make_unique<model::BulkCracking>(
        _mesh, _V, _u, materials.at("alpha"), material, Material{E, nu, alpha}, part, slice);

    _K = fem::petsc::create_matrix(a);
    check(MatZeroEntries(_K), "MatZeroEntries");
    fem::assemble_matrix(dolfinx::la::petsc::Matrix::set_block_fn(_K, ADD_VALUES), a, {});
    check(MatAssemblyBegin(_K, MAT_FLUSH_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(_K, MAT_FLUSH_ASSEMBLY), "MatAssemblyEnd");
    _cracking->add_elastic_rule(_K);
    check(MatAssemblyBegin(_K, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(_K, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    check(MatDuplicate(_K, MAT_COPY_VALUES, &_J), "MatDuplicate");
    check(MatCreateVecs(_K, &_du, &_r), "MatCreateVecs");
    check(KSPCreate(PETSC_COMM_SELF, &_ksp), "KSPCreate");
    check(KSPSetType(_ksp, KSPPREONLY), "KSPSetType");
    PC pc;
    check(KSPGetPC(_ksp, &pc), "KSPGetPC");
    check(PCSetType(pc, PCLU), "PCSetType");

    _X = _V->tabulate_dof_coordinates(false);
    for (std::size_t node = 0; node < _X.size() / 3; ++node)
    {
      const double* p = _X.data() + 3 * node;
      const PetscInt d = PetscInt(3 * node);
      if (p[0] < 1e-9 * L)
        _held.push_back(d);
      if (p[0] > L * (1 - 1e-9))
        _pulled.push_back(d);
      if (std::abs(p[1]) < 1e-9 * L)
        _held.push_back(d + 1);
      if (std::abs(p[2]) < 1e-9 * L)
        _held.push_back(d + 2);
    }
    _held.insert(_held.end(), _pulled.begin(), _pulled.end());
    _f.resize(_X.size());
  }

  ~PulledPrism()
  {
    KSPDestroy(&_ksp);
    VecDestroy(&_r);
    VecDestroy(&_du);
    MatDestroy(&_J);
    MatDestroy(&_K);
  }
  PulledPrism(const PulledPrism&) = delete;
  PulledPrism& operator=(const PulledPrism&) = delete;

  /// The dofs' coordinates, node by node [mm].
  const std::vector<double>& coordinates() const { return _X; }
  /// The displacement [mm].
  std::span<double> displacement() { return _u->x()->mutable_array(); }
  model::BulkCracking& cracking() { return *_cracking; }

  /// Newton from the displacement as it is, the pulled face at `delta`
  /// [mm], to |f| below `tolerance` [N] on the free dofs, with the cracks'
  /// consistent tangent; false if it does not get there in 50 iterations.
  bool solve(double delta, double tolerance)
  {
    std::span<double> U = displacement();
    for (PetscInt d : _pulled)
      U[std::size_t(d)] = delta;
    for (int it = 0; it < 50; ++it)
    {
      if (!forces())
        return false;
      std::vector<double> free_f = _f;
      for (PetscInt d : _held)
        free_f[std::size_t(d)] = 0;
      double norm = 0;
      for (double v : free_f)
        norm += v * v;
      if (std::sqrt(norm) < tolerance)
        return true;
      check(MatCopy(_K, _J, SAME_NONZERO_PATTERN), "MatCopy");
      _cracking->add_tangent(_J);
      check(MatAssemblyBegin(_J, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
      check(MatAssemblyEnd(_J, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
      check(MatZeroRowsColumns(_J, PetscInt(_held.size()), _held.data(), 1.0, nullptr, nullptr),
            "MatZeroRowsColumns");
      double* r;
      check(VecGetArray(_r, &r), "VecGetArray");
      for (std::size_t i = 0; i < free_f.size(); ++i)
        r[i] = -free_f[i];
      check(VecRestoreArray(_r, &r), "VecRestoreArray");
      check(KSPSetOperators(_ksp, _J, _J), "KSPSetOperators");
      check(KSPSolve(_ksp, _r, _du), "KSPSolve");
      const double* du;
      check(VecGetArrayRead(_du, &du), "VecGetArrayRead");
      for (std::size_t i = 0; i < U.size(); ++i)
        U[i] += du[i];
      check(VecRestoreArrayRead(_du, &du), "VecRestoreArrayRead");
    }
    return false;
  }

  /// The force on the pulled face at the last solve [N].
  double force() const
  {
    double F = 0;
    for (PetscInt d : _pulled)
      F += _f[std::size_t(d)];
    return F;
  }

private:
  /// _f = K u + the cracks' forces [N]; false if a crack failed.
  bool forces()
  {
    if (!_cracking->evaluate())
      return false;
    std::span<double> U = displacement();
    Vec u;
    check(VecCreateSeqWithArray(PETSC_COMM_SELF, 3, PetscInt(U.size()), U.data(), &u),
          "VecCreateSeqWithArray");
    check(MatMult(_K, u, _r), "MatMult");
    check(VecDestroy(&u), "VecDestroy");
    const double* r;
    check(VecGetArrayRead(_r, &r), "VecGetArrayRead");
    std::copy(r, r + U.size(), _f.begin());
    check(VecRestoreArrayRead(_r, &r), "VecRestoreArrayRead");
    _cracking->add_forces(_f);
    return true;
  }

  std::shared_ptr<dolfinx::mesh::Mesh> _mesh;
  std::shared_ptr<fem::FunctionSpace> _V;
  std::shared_ptr<fem::Function<double>> _u;
  std::unique_ptr<model::BulkCracking> _cracking;
  Mat _K = nullptr, _J = nullptr;
  Vec _r = nullptr, _du = nullptr;
  KSP _ksp = nullptr;
  std::vector<double> _X, _f;
  std::vector<PetscInt> _held, _pulled; // _held includes _pulled
};

/// Pulls the prism on n x m x m cells to `delta_end` [mm] (see Pull).
Pull pull(int n, int m, double delta_end, const Setup& setup)
{
  const bool implex = setup.implex;
  PulledPrism prism(n, m, setup);
  const std::vector<double>& X = prism.coordinates();
  std::span<double> U = prism.displacement();
  Pull run;
  run.h = L / n;
  // Elastic to 0.9 of the peak's elongation in 3 steps, through the peak in
  // steps of 1/500 of it (0.2 % of f_t; on the finest mesh the neighbours'
  // points nearest the middle row have 0.15 % more section), then 2 um
  // steps. Each
  // step starts from the last converged one plus its increment scaled to
  // the step's (the first from a uniform stretch): from the pulled face
  // alone moved the cells beside it cracked, and Newton on the cracks'
  // kinks wandered.
  const double peak = f_t * L / E; // about the elongation at the peak [mm]
  std::vector<double> last(U.size(), 0.0), increment(U.size(), 0.0);
  for (std::size_t node = 0; node < X.size() / 3; ++node)
    increment[3 * node] = X[3 * node] / L;
  double delta = 0, last_step = 1;
  while (delta < delta_end)
  {
    const double step = delta < 0.85 * peak  ? 0.3 * peak
                        : delta < 1.2 * peak ? 2e-3 * peak
                                             : 2e-3; // mm
    delta += step;
    for (std::size_t i = 0; i < U.size(); ++i)
      U[i] = last[i] + increment[i] * step / last_step;
    // IMPL-EX: the step's cracks extrapolated from the last step's by the
    // ratio of the increments (none in the first step), as the step loop
    // does (stepping/DisplacementControl.cpp).
    if (implex)
      prism.cracking().set_extrapolation(run.delta.empty() ? 0.0 : step / last_step);
    if (!prism.solve(delta, 1e-9 * f_t * A))
    {
      ADD_FAILURE() << "Newton did not converge at delta = " << delta << " mm on " << n << " cells";
      break;
    }
    // IMPL-EX: the crack band's own update at the converged strain, what
    // the step commits (its error not checked: the steps are small).
    std::int64_t failed_points = 0;
    if (implex && (prism.cracking().implex_error(failed_points), failed_points > 0))
    {
      ADD_FAILURE() << "the crack band's update failed at delta = " << delta << " mm";
      break;
    }
    for (std::size_t i = 0; i < U.size(); ++i)
    {
      increment[i] = U[i] - last[i];
      last[i] = U[i];
    }
    last_step = step;
    run.delta.push_back(delta);
    run.force.push_back(prism.force());
    run.dissipated += prism.cracking().dissipation();
    prism.cracking().commit();
  }
  run.cracked = prism.cracking().totals().cracked_points;
  return run;
}

/// F at elongation `delta` by linear interpolation of the run's curve [N];
/// `delta` within the run's first and last step.
double force_at(const Pull& run, double delta)
{
  if (run.delta.size() < 2 || delta < run.delta.front() || delta > run.delta.back())
    throw std::out_of_range("force_at: an elongation outside the run");
  auto it = std::lower_bound(run.delta.begin(), run.delta.end(), delta);
  const std::size_t i = std::size_t(std::max<std::ptrdiff_t>(1, it - run.delta.begin()));
  const double t = (delta - run.delta[i - 1]) / (run.delta[i] - run.delta[i - 1]);
  return run.force[i - 1] + t * (run.force[i] - run.force[i - 1]);
}
} // namespace

/// How far each mesh's force may lie from its closed form [-], and its
/// ratio to the closed form from the finest mesh's [-].
struct Bounds
{
  double closed_form = 0.03;
  double closed_form_vs_finest = 0.01;
};

/// The checks of the file's head, on the meshes and with the cracks of
/// `setup`.
static void check_objectivity(const Setup& setup, const Bounds& bounds = {})
{
  const double delta_end = 0.32; // mm: the crack's exp(-c w) about 1e-4 at the end
  // n cells along the prism, m across: 20, 9.1 and 4.8 mm along it.
  const std::vector<std::array<int, 2>> meshes = {{5, 1}, {11, 2}, {21, 4}};
  const std::vector<double> post_peak = {0.015, 0.02, 0.03, 0.05, 0.08, 0.12}; // mm
  std::vector<Pull> runs;
  for (const auto& [n, m] : meshes)
  {
    runs.push_back(pull(n, m, delta_end, setup));
    ASSERT_GE(runs.back().delta.size(), 2u) << n << " cells";
    ASSERT_GE(runs.back().delta.back(), post_peak.back()) << n << " cells";
  }
  // Cells wider than long: the band is not the cell's largest extent.
  {
    const Pull wide = pull(21, 1, delta_end, setup);
    ASSERT_GE(wide.delta.size(), 2u);
    ASSERT_GE(wide.delta.back(), post_peak.back());
    const double A_n = middle_section(21); // mm^2
    std::printf("21 x 1 x 1 cells: dissipated %.4f N mm (G_F A_n %.4f)\n", wide.dissipated,
                G_F * A_n);
    EXPECT_NEAR(wide.dissipated, G_F * A_n, 0.01 * G_F * A_n);
    for (double d : post_peak)
    {
      const double ratio = force_at(wide, d) / closed_form_force(d, compliance(21), A_n);
      std::printf("  delta %.3f mm: / closed form %.4f\n", d, ratio);
      EXPECT_NEAR(ratio, 1.0, bounds.closed_form) << "21 x 1 x 1 cells, delta " << d << " mm";
    }
  }
  // Each mesh's force over its own closed form at each post_peak point.
  auto to_closed_form = [&](std::size_t k, double d)
  {
    const int n = meshes[k][0];
    return force_at(runs[k], d) / closed_form_force(d, compliance(n), middle_section(n));
  };
  for (std::size_t k = 0; k < runs.size(); ++k)
  {
    const Pull& run = runs[k];
    const int n = meshes[k][0];
    const double A_n = middle_section(n); // mm^2
    std::printf("%d x %d x %d cells: peak %.2f N (f_t A_n %.2f), dissipated %.4f N mm "
                "(G_F A_n %.4f), %ld points cracked\n",
                n, meshes[k][1], meshes[k][1],
                *std::max_element(run.force.begin(), run.force.end()), f_t * A_n, run.dissipated,
                G_F * A_n, long(run.cracked));
    EXPECT_NEAR(run.dissipated, G_F * A_n, 0.01 * G_F * A_n) << n << " cells";
    for (double d : post_peak)
    {
      const double F = force_at(run, d), F_fine = force_at(runs.back(), d);
      std::printf("  delta %.3f mm: F %.3f N, / closed form %.4f, / finest %.4f\n", d, F,
                  to_closed_form(k, d), F / F_fine);
      EXPECT_NEAR(F, F_fine, 0.05 * F_fine) << n << " cells, delta " << d << " mm";
      EXPECT_NEAR(to_closed_form(k, d), 1.0, bounds.closed_form)
          << n << " cells, delta " << d << " mm";
      EXPECT_NEAR(to_closed_form(k, d), to_closed_form(runs.size() - 1, d),
                  bounds.closed_form_vs_finest)
          << n << " cells, delta " << d << " mm";
    }
  }
}

TEST(PrismObjectivity, OneCrackDissipatesGfAndThePostPeakCurveIsTheMeshes)
{
  check_objectivity({.implex = false});
}

TEST(PrismObjectivity, TheSameWithImplexCracks)
{
  check_objectivity({.implex = true});
}

// Cells that the crack crosses obliquely: the meshes sheared by 0.3 (their
// x faces lean by 16.7 deg round the middle), the crack's normal still along
// the prism. It runs along the middle row of cells, whose width along x is
// the cells' spacing L / n, while the cells' extent along x is L / n +
// 0.3 side / m. With the row band (cracking.band_width = "row") the cracks
// dissipate G_F A_n within 1 % (measured -0.01, +0.07, +0.24 and +0.31 %
// on 5 x 1 x 1, 11 x 2 x 2, 21 x 4 x 4 and 21 x 1 x 1 cells) and the
// curves agree within 2.1 % of the finest mesh's (asserted 5 %). The
// curve's shape is not mode I's: the row, leaning, opens by a jump along
// the prism that the crack's frame sees partly as sliding, and the
// crack's law (a central force) softens on the sliding too, so F lies
// above the closed form by up to 5.5 % just past the peak and below it by
// up to 10.5 % at delta = 0.12 mm, the same on every mesh (the shear is);
// asserted 12 %, and each mesh's ratio to the closed form within 3 % of
// the finest mesh's (measured 2.0 %). With the projected band on the same
// cells the force falls to 0.50 of the closed form at 0.12 mm (0.09 on
// 21 x 1 x 1) and the energy is 12 to 38 % short (the next test).
TEST(PrismObjectivity, OnShearedCellsTheRowBandHolds)
{
  check_objectivity({.implex = false, .shear = 0.3, .row_band = true},
                    {.closed_form = 0.12, .closed_form_vs_finest = 0.03});
}

// The projected band on the same sheared cells dissipates G_F A_n times
// the row's width over the extent (measured: 0.876, 0.862, 0.868 and 0.620
// of G_F A_n on 5 x 1 x 1, 11 x 2 x 2, 21 x 4 x 4 and 21 x 1 x 1 cells,
// against ratios of 0.877, 0.862, 0.867 and 0.619):
// a bias that does not fall with the cells' size, which the row band
// removes (docs/cracking.md, "The band's width").
TEST(PrismObjectivity, OnShearedCellsTheProjectedBandIsTooWide)
{
  const double shear = 0.3;
  for (const auto& [n, m] : std::vector<std::array<int, 2>>{{5, 1}, {11, 2}, {21, 4}, {21, 1}})
  {
    const Pull run = pull(n, m, 0.32, {.implex = false, .shear = shear});
    ASSERT_GE(run.delta.size(), 2u) << n << " cells";
    // The middle cell at y, z in [0, side / m], placed as waisted_prism
    // places it.
    model::CellVertices x;
    const double dx = L / n, dy = side / m;
    for (int v = 0; v < 8; ++v)
      x[std::size_t(v)] =
          prism_node({(n / 2 + (v & 1)) * dx, ((v >> 1) & 1) * dy, ((v >> 2) & 1) * dy}, shear);
    const double ratio = model::row_width(x, {1, 0, 0}) / model::projected_width(x, {1, 0, 0}); // -
    const double A_n = middle_section(n); // mm^2
    std::printf("%d x %d x %d cells sheared by %.1f, projected band: dissipated %.4f N mm, "
                "G_F A_n %.4f, times the row's width over the extent %.4f\n",
                n, m, m, shear, run.dissipated, G_F * A_n, G_F * A_n * ratio);
    EXPECT_LT(ratio, 0.9) << n << " cells"; // the cells are sheared
    EXPECT_NEAR(run.dissipated, G_F * A_n * ratio, 0.01 * G_F * A_n) << n << " cells";
  }
}

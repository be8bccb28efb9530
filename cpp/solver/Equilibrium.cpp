#include "Equilibrium.h"
#include "../common/mpi_errors.h"
#include "../common/petsc_check.h"
#include "RigidBodyModes.h"
#include "ShellPreconditioner.h"
#include "SinglePrecisionSparse.h"
#include <cmath>
#include <cstdlib>
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/la/petsc.h>
#include <limits>
#include <petscksp.h>
#include <stdexcept>
#include <string>

namespace pushout::solver
{
using petsc::check;

namespace
{
/// Test hook, not a scene key (tests/e2e/test_implex_tends_to_implicit.py):
/// with PUSHOUT_TEST_NO_TANGENT_CACHE set, IMPL-EX cracks' tangent is
/// assembled afresh at every Newton iteration, and their forces from the
/// crack band's stresses at every residual, as for implicit cracks.
bool test_no_tangent_cache()
{
  static const bool set = std::getenv("PUSHOUT_TEST_NO_TANGENT_CACHE") != nullptr;
  return set;
}
} // namespace

Equilibrium::Equilibrium(model::Model& model)
    : _model(model), _f_interface(model.space()->dofmap()->index_map, model.block_size()),
      _g_energy(model.space()->dofmap()->index_map, model.block_size())
{
  _f_external = model.create_vector();
  check(VecSet(_f_external, 0.0), "VecSet");
}

Equilibrium::~Equilibrium()
{
  if (_bulk_tangent)
    petsc::check_nothrow(MatDestroy(&_bulk_tangent), "MatDestroy");
  if (_f_thermal)
    petsc::check_nothrow(VecDestroy(&_f_thermal), "VecDestroy");
  for (Vec* v : {&_free_expansion, &_expansion_load, &_shifted})
    if (*v)
      petsc::check_nothrow(VecDestroy(v), "VecDestroy");
  petsc::check_nothrow(VecDestroy(&_f_external), "VecDestroy");
}

void Equilibrium::set_temperature_change(double dT)
{
  // The model's (the stress output reads it) and the crack band's, also
  // where another Equilibrium on the model (an earlier run's, on a set-up
  // reused) set them.
  _model.set_temperature_change(dT);
  model::BulkCracking* cracking = _model.bulk_cracking();
  if (cracking && cracking->temperature_change() != dT)
    cracking->set_temperature_change(dT, {});
  if (dT == _dT)
    return; // the thermal load is assembled once per temperature change
  _dT = dT;
  ++_load_version;
  if (_f_thermal)
    check(VecDestroy(&_f_thermal), "VecDestroy");
  _f_thermal = dT != 0.0 ? _model.thermal_load() : nullptr;
  make_free_expansion();
}

void Equilibrium::set_constraints(Constraints c)
{
  // Each process holds its own dofs: the tube's top, say, on some of them
  // only. A version that moved on those alone would send the others down
  // another path through the solver's collectives (a lagged LU refreshed
  // here and reused there), so all of them agree.
  if (!mpi::all(_model.comm(), c.dofs == _bc.dofs))
    ++_constraint_version;
  _bc = std::move(c);
  ++_load_version;
}

bool Equilibrium::kept_tangent() const
{
  const model::BulkCracking* cracking = _model.bulk_cracking();
  return cracking && cracking->implex() && !test_no_tangent_cache();
}

void Equilibrium::make_free_expansion()
{
  for (Vec* v : {&_free_expansion, &_expansion_load, &_shifted})
    if (*v)
      check(VecDestroy(v), "VecDestroy");
  if (_dT == 0.0 || !kept_tangent())
    return;
  for (Vec* v : {&_free_expansion, &_expansion_load, &_shifted})
    *v = create_vector();
  // u_T = alpha dT X at the nodes: its strain is alpha dT I on every
  // cracking cell (all of one concrete).
  const double scale = _model.bulk_cracking()->thermal_expansion() * _dT;        // strain [-]
  const std::vector<double> X = _model.space()->tabulate_dof_coordinates(false); // [node][3] mm
  double* a;
  check(VecGetArray(_free_expansion, &a), "VecGetArray");
  PetscInt n_owned;
  check(VecGetLocalSize(_free_expansion, &n_owned), "VecGetLocalSize");
  for (PetscInt i = 0; i < n_owned; ++i)
    a[i] = scale * X[i];
  check(VecRestoreArray(_free_expansion, &a), "VecRestoreArray");
  check(MatMult(_model.stiffness(), _free_expansion, _expansion_load), "MatMult");
  check(VecAXPY(_expansion_load, -1.0, _f_thermal), "VecAXPY");
}

void Equilibrium::set_external_forces(const std::vector<std::pair<std::int32_t, double>>& forces)
{
  ++_load_version;
  check(VecSet(_f_external, 0.0), "VecSet");
  double* f;
  check(VecGetArray(_f_external, &f), "VecGetArray");
  for (const auto& [dof, value] : forces)
    f[dof] += value;
  check(VecRestoreArray(_f_external, &f), "VecRestoreArray");
}

void Equilibrium::apply_constraints(Vec x) const
{
  double* a;
  check(VecGetArray(x, &a), "VecGetArray");
  for (std::size_t i = 0; i < _bc.dofs.size(); ++i)
    a[_bc.dofs[i]] = _bc.values[i];
  check(VecRestoreArray(x, &a), "VecRestoreArray");
}

void Equilibrium::update_displacement(Vec x)
{
  const double* a;
  check(VecGetArrayRead(x, &a), "VecGetArrayRead");
  std::span<double> u = _model.displacement().x()->mutable_array();
  const std::size_t n_owned = _model.index_map().size_local() * _model.block_size();
  std::copy_n(a, n_owned, u.begin());
  check(VecRestoreArrayRead(x, &a), "VecRestoreArrayRead");
  _model.displacement().x()->scatter_fwd();
}

bool Equilibrium::assemble_interfaces(std::span<double> f, Mat A)
{
  bool ok = true;
  for (interface::Interface* joints : _model.joints())
    ok = joints->assemble(_model.displacement().x()->array(), f, A) && ok;
  return ok;
}

bool Equilibrium::assemble_joints(std::span<double> f, Mat A)
{
  bool ok = assemble_interfaces(f, A);
  if (model::BulkCracking* cracking = _model.bulk_cracking())
  {
    ok = cracking->evaluate() && ok;
    cracking->add_forces(f);
    if (A)
      cracking->add_tangent(A);
  }
  return ok;
}

void Equilibrium::restart()
{
  if (_bulk_tangent)
    check(MatDestroy(&_bulk_tangent), "MatDestroy");
  _bulk_assembled.clear();
  _bulk_tangent_version = 0;
}

Mat Equilibrium::bulk_tangent()
{
  model::BulkCracking* cracking = _model.bulk_cracking();
  // Stale on one process, rebuilt on all: the assembly is collective.
  int stale = !_bulk_tangent || cracking->tangent_version() != _bulk_tangent_version;
  MPI_Allreduce(MPI_IN_PLACE, &stale, 1, MPI_INT, MPI_MAX, _model.comm());
  if (!stale)
    return _bulk_tangent;
  if (!_bulk_tangent)
  {
    _bulk_tangent = create_matrix(); // K
    _bulk_assembled.clear();
  }
  cracking->add_tangent_change(_bulk_tangent, _bulk_assembled);
  check(MatAssemblyBegin(_bulk_tangent, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(_bulk_tangent, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  _bulk_tangent_version = cracking->tangent_version();
  return _bulk_tangent;
}

void Equilibrium::kept_tangent_forces(Vec x, Vec F)
{
  const Mat M = bulk_tangent();
  // Made where first needed at this dT: the cracks' integration may have
  // turned to IMPL-EX since dT was set (an implicit run's IMPL-EX rescue,
  // BulkCracking::set_implex_rescue).
  if (_dT != 0.0 && !_free_expansion)
    make_free_expansion();
  if (!_free_expansion) // dT = 0: no free strain
  {
    check(MatMult(M, x, F), "MatMult");
    return;
  }
  check(VecWAXPY(_shifted, -1.0, _free_expansion, x), "VecWAXPY");
  check(MatMult(M, _shifted, F), "MatMult");
  check(VecAXPY(F, 1.0, _expansion_load), "VecAXPY");
}

bool Equilibrium::internal_forces(Vec x, Vec F)
{
  // The kept residual's shift by u_T is of this object's dT; the crack
  // band's strains must be of the same (set_temperature_change sets both,
  // and only an Equilibrium can set the crack band's: another one on the
  // same model may have set it since).
  if (kept_tangent() && _model.bulk_cracking()->temperature_change() != _dT)
    throw std::logic_error("Equilibrium: the crack band's temperature change was set by another "
                           "Equilibrium on the same model since this one's");
  update_displacement(x);
  std::span<double> fi = _f_interface.mutable_array();
  std::fill(fi.begin(), fi.end(), 0.0);
  bool ok = true;
  if (kept_tangent())
  {
    // The cracks' forces by the kept tangent, brought up to where a crack
    // opens or closes; the Jacobian at this iterate then finds it current.
    ok = assemble_interfaces(fi, nullptr);
    ok = _model.bulk_cracking()->evaluate_tangent() && ok;
    kept_tangent_forces(x, F);
  }
  else
  {
    ok = assemble_joints(fi, nullptr);
    check(MatMult(_model.stiffness(), x, F), "MatMult");
    if (_f_thermal)
      check(VecAXPY(F, -1.0, _f_thermal), "VecAXPY");
  }
  _f_interface.scatter_rev(std::plus<double>());
  check(VecAXPY(F, -1.0, _f_external), "VecAXPY");
  double* f;
  check(VecGetArray(F, &f), "VecGetArray");
  PetscInt n_owned;
  check(VecGetLocalSize(F, &n_owned), "VecGetLocalSize");
  for (PetscInt i = 0; i < n_owned; ++i)
    f[i] += fi[i];
  check(VecRestoreArray(F, &f), "VecRestoreArray");
  return ok;
}

bool Equilibrium::energy_release(Vec x, double& G, Vec gradient)
{
  update_displacement(x);
  std::span<double> g = _g_energy.mutable_array();
  std::fill(g.begin(), g.end(), 0.0);
  bool ok = true;
  G = 0;
  for (interface::Interface* joints : _model.joints())
  {
    double G_set;
    ok = joints->energy_release(_model.displacement().x()->array(), g, G_set) && ok;
    G += G_set;
  }
  if (model::BulkCracking* cracking = _model.bulk_cracking())
  {
    double G_bulk;
    ok = cracking->energy_release(g, G_bulk) && ok;
    G += G_bulk;
  }
  _g_energy.scatter_rev(std::plus<double>());
  double* a;
  check(VecGetArray(gradient, &a), "VecGetArray");
  PetscInt n_owned;
  check(VecGetLocalSize(gradient, &n_owned), "VecGetLocalSize");
  std::copy_n(g.begin(), n_owned, a);
  check(VecRestoreArray(gradient, &a), "VecRestoreArray");
  MPI_Allreduce(MPI_IN_PLACE, &G, 1, MPI_DOUBLE, MPI_SUM,
                PetscObjectComm(reinterpret_cast<PetscObject>(x)));
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
  check(VecGetArray(F, &f), "VecGetArray");
  check(VecGetArrayRead(x, &a), "VecGetArrayRead");
  double r2 = 0;
  for (std::size_t i = 0; i < _bc.dofs.size(); ++i)
  {
    r2 += f[_bc.dofs[i]] * f[_bc.dofs[i]];
    f[_bc.dofs[i]] = a[_bc.dofs[i]] - _bc.values[i];
  }
  check(VecRestoreArrayRead(x, &a), "VecRestoreArrayRead");
  check(VecRestoreArray(F, &f), "VecRestoreArray");
  MPI_Allreduce(MPI_IN_PLACE, &r2, 1, MPI_DOUBLE, MPI_SUM,
                PetscObjectComm(reinterpret_cast<PetscObject>(x)));
  reaction_norm = std::sqrt(r2);
  return ok;
}

// F = K x + f_int - f_thermal - f_external: floor = C eps (||K||_inf ||x||
// + ||f_thermal|| + ||f_external|| + ||f_int||), C = residual_floor_factor
// (NonlinearProblem.h). The term of K x dominates when the tube moves as a
// body: K x is then a sum of large terms that cancel. With IMPL-EX cracks
// the cracks' forces are in K x's product (kept_tangent_forces: (K + A)
// (x - u_T), A softer than K where it is not zero), and K u_T - f_thermal
// cancels to the size of f_thermal's term.
double Equilibrium::residual_floor(Vec x)
{
  if (_K_norm < 0)
    check(MatNorm(_model.stiffness(), NORM_INFINITY, &_K_norm), "MatNorm");
  double x_norm;
  check(VecNorm(x, NORM_2, &x_norm), "VecNorm");
  double squares[3] = {0, 0, 0}; // thermal, external, interface forces
  PetscInt n;
  check(VecGetLocalSize(x, &n), "VecGetLocalSize");
  const std::span<const double> fi = _f_interface.array();
  for (PetscInt i = 0; i < n; ++i)
    squares[2] += fi[i] * fi[i];
  int k = 0;
  for (Vec f : {_f_thermal, _f_external})
  {
    if (f)
    {
      const double* a;
      check(VecGetArrayRead(f, &a), "VecGetArrayRead");
      for (PetscInt i = 0; i < n; ++i)
        squares[k] += a[i] * a[i];
      check(VecRestoreArrayRead(f, &a), "VecRestoreArrayRead");
    }
    ++k;
  }
  MPI_Allreduce(MPI_IN_PLACE, squares, 3, MPI_DOUBLE, MPI_SUM,
                PetscObjectComm(reinterpret_cast<PetscObject>(x)));
  const double scale =
      _K_norm * x_norm + std::sqrt(squares[0]) + std::sqrt(squares[1]) + std::sqrt(squares[2]);
  return residual_floor_factor * std::numeric_limits<double>::epsilon() * scale;
}

void Equilibrium::linear_rhs(Vec b) const
{
  check(VecCopy(_f_external, b), "VecCopy");
  if (_f_thermal)
    check(VecAXPY(b, 1.0, _f_thermal), "VecAXPY");
  double* a;
  check(VecGetArray(b, &a), "VecGetArray");
  for (std::size_t i = 0; i < _bc.dofs.size(); ++i)
    a[_bc.dofs[i]] = _bc.values[i];
  check(VecRestoreArray(b, &a), "VecRestoreArray");
}

Mat Equilibrium::create_matrix() const
{
  Mat J;
  check(MatDuplicate(_model.stiffness(), MAT_COPY_VALUES, &J), "MatDuplicate");
  check(MatSetOption(J, MAT_KEEP_NONZERO_PATTERN, PETSC_TRUE), "MatSetOption");
  set_rigid_body_modes(_model, J); // for algebraic multigrid (-pc_type gamg)
  return J;
}

Vec Equilibrium::create_vector() const
{
  Vec v;
  check(MatCreateVecs(_model.stiffness(), nullptr, &v), "MatCreateVecs");
  return v;
}

bool Equilibrium::jacobian(Vec x, Mat J)
{
  count_tangent();
  update_displacement(x);
  std::span<double> fi = _f_interface.mutable_array();
  std::fill(fi.begin(), fi.end(), 0.0);
  bool ok = true;
  if (kept_tangent())
  {
    // The cracks' secant tangent is the step's at every iteration but where
    // a crack opens or closes (BulkCracking::tangent_version): K plus it is
    // kept, and only the joints' tangent is added afresh. The crack band is
    // evaluated first (it may open or close a crack), as far as the tangent
    // goes: the residual at this iterate has done it.
    ok = _model.bulk_cracking()->evaluate_tangent();
    check(MatCopy(bulk_tangent(), J, SAME_NONZERO_PATTERN), "MatCopy");
    ok = assemble_interfaces(fi, J) && ok;
  }
  else
  {
    check(MatCopy(_model.stiffness(), J, SAME_NONZERO_PATTERN), "MatCopy");
    ok = assemble_joints(fi, J);
  }
  check(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  static_assert(sizeof(PetscInt) == sizeof(std::int32_t), "PETSc with 32-bit indices expected");
  check(MatZeroRowsLocal(J, PetscInt(_bc.dofs.size()), _bc.dofs.data(), 1.0, nullptr, nullptr),
        "MatZeroRowsLocal");
  return ok;
}

void Equilibrium::configure(KSP ksp) const
{
  if (!_single_precision)
    return;
  KSPType type;
  check(KSPGetType(ksp, &type), "KSPGetType");
  PC pc;
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  PCType pc_type;
  check(PCGetType(pc, &pc_type), "PCGetType");
  if (!type || std::string(type) != KSPGMRES || !pc_type || std::string(pc_type) != PCLU)
    return;
  MatSolverType factor_type = nullptr;
  check(PCFactorGetMatSolverType(pc, &factor_type), "PCFactorGetMatSolverType");
  if (!factor_type || std::string(factor_type) != MATSOLVERMUMPS)
    return; // another LU the user asked for
  // GMRES on a lagged LU (solver.preconditioner = "lagged"), or on the LU of
  // every Jacobian of implicit cracks (NewtonSolver::set_default_options):
  // the LU only steers it. Flexible GMRES: its residual is the Jacobian's own, whatever
  // the rounding of the preconditioner (SinglePrecisionSparse.h); the
  // tolerance stays.
  // On several processes, the numbering MUMPS's ordering is made in.
  int processes = 1;
  MPI_Comm_size(_model.comm(), &processes);
  use_single_precision_sparse_lu(
      pc, processes > 1 ? _model.input_numbering() : std::vector<std::int64_t>{},
      _model.block_size());
  make_gmres_flexible(ksp);
}
} // namespace pushout::solver

#include "LoadStepSolver.h"
#include "../common/mpi_errors.h"
#include "../common/petsc_check.h"
#include "../scene/SceneError.h"
#include "ShellPreconditioner.h"
#include "Vector.h"
#include <cmath>
#include <iostream>

namespace pushout::solver
{
using petsc::check;

namespace
{
/// Newton on concrete that cracks keeps the factorisation at hand once two
/// iterations in a row cut ||F|| by this ratio or better
/// (NewtonSolver::set_tail_reuse).
constexpr double tail_reuse_ratio = 0.3;
} // namespace

LoadStepSolver::LoadStepSolver(Equilibrium& eq, bool condense, NewtonSolver::Preconditioner pc,
                               int refactor_iterations, std::string description)
    : _eq(eq), _condense(condense), _pc(pc), _refactor_iterations(refactor_iterations),
      _description(std::move(description)), _whole(eq, pc, refactor_iterations)
{
}

NewtonSolver::Preconditioner LoadStepSolver::preconditioner(const SolverPart& part,
                                                            NewtonSolver::Concrete concrete)
{
  // Concrete that cracks softens at many points at once, and GMRES on a
  // lagged LU then needs many iterations or fails: on the corroded demo
  // with cracks (paper's mesh, to x = 10 um) it took 74 factorisations
  // instead of 288 but 6 cuts and twice the time (docs/cracking.md, "Newton").
  // It takes the Jacobian's LU whatever solver.preconditioner says.
  // IMPL-EX cracks leave a step's bulk linear but for closure
  // (BulkCracking::implex): the solver of a linear bulk.
  return part.lagged_preconditioner && concrete != NewtonSolver::Concrete::cracks
             ? NewtonSolver::Preconditioner::lagged
             : NewtonSolver::Preconditioner::jacobian;
}

bool LoadStepSolver::single_precision_lu(const SolverPart& part, NewtonSolver::Concrete concrete)
{
  // GMRES runs on a lagged LU, and on the implicit cracks' LU of every
  // Jacobian in mixed precision (NewtonSolver::set_default_options);
  // Equilibrium::configure then factors it in single precision.
  return part.mixed_precision &&
         (preconditioner(part, concrete) == NewtonSolver::Preconditioner::lagged ||
          concrete == NewtonSolver::Concrete::cracks);
}

void LoadStepSolver::check_options(const SolverPart& part, NewtonSolver::Concrete concrete,
                                   int processes)
{
  std::string why;
  if (part.condensation == SolverPart::Condensation::on &&
      !Condensation::possible(processes, 1, concrete != NewtonSolver::Concrete::linear, why))
    throw SceneError("solver.condensation = \"on\" is not possible here: " + why);
  // GMRES on MUMPS's LU in mixed precision is flexible (Equilibrium::
  // configure, CondensationNewton::configure): the KSP, PC and factor the
  // user's options choose, else the defaults set_default_options() sets.
  const auto chosen = [](const char* name, const char* ours)
  {
    const std::string given = NewtonSolver::user_option(name);
    return given.empty() ? std::string(ours) : given;
  };
  if (part.mixed_precision &&
      chosen("-ksp_type", NewtonSolver::gmres_by_default(preconditioner(part, concrete), concrete,
                                                         part.mixed_precision)
                              ? "gmres"
                              : "preonly") == "gmres" &&
      chosen("-pc_type", "lu") == "lu" && chosen("-pc_factor_mat_solver_type", "mumps") == "mumps")
    refuse_side_flexible_gmres_lacks(nullptr);
}

std::unique_ptr<LoadStepSolver> LoadStepSolver::make(Equilibrium& eq, const SolverPart& part)
{
  using Concrete = NewtonSolver::Concrete;
  const model::BulkCracking* bulk = eq.model().bulk_cracking();
  const Concrete concrete = LoadStepSolver::concrete(bulk != nullptr, bulk && bulk->implex());
  const auto pc = preconditioner(part, concrete);
  const bool lagged = pc == NewtonSolver::Preconditioner::lagged;
  int processes = 1;
  MPI_Comm_size(eq.model().comm(), &processes);
  NewtonSolver::set_default_options(pc, concrete, part.mixed_precision);
  const std::int64_t interface_dofs = Condensation::interface_dofs(eq.model());
  std::string why;
  const bool condense =
      Condensation::chosen(part.condensation, processes, interface_dofs, bulk != nullptr, why);
  const bool required = part.condensation == SolverPart::Condensation::on;
  if (!condense && required)
    throw SceneError("solver.condensation = \"on\" is not possible here: " + why);
  const std::string cracks = concrete == Concrete::linear ? ""
                             : concrete == Concrete::implex_cracks
                                 ? "; IMPL-EX cracks (cracking.integration)"
                                 : "; implicit cracks (cracking.integration)";
  // The whole model's linear solver as NewtonSolver::set_default_options
  // and Equilibrium::configure make it (the LU in single precision under
  // GMRES), unless the user's PETSc options chose another.
  const bool single = single_precision_lu(part, concrete);
  const std::string whole_linear =
      NewtonSolver::linear_solver_from_options() ? ", the linear solver of the PETSc options"
      : lagged ? std::string(", GMRES on a lagged LU") + (single ? " in single precision" : "")
      : single ? ", GMRES on the single-precision LU of every Jacobian"
               : ", the LU of every Jacobian";
  const std::string description =
      condense ? "the " + std::to_string(Condensation::unknowns(eq.model())) +
                     " interface jumps (bulk condensed)" + cracks
               : "the whole model" + (why.empty() ? "" : " (not condensed: " + why + ")") + cracks +
                     whole_linear;
  eq.set_single_precision(part.mixed_precision); // before the solvers configure their KSP
  auto solver = std::make_unique<LoadStepSolver>(eq, condense, pc, int(part.refactor_iterations),
                                                 description);
  // IMPL-EX: a step's secant tangent is known at its start (the cracks'
  // extrapolated damage), and the last step's is not it; from it a step
  // without a crack that closes converges in one iteration (the bench's
  // corroded demo: 342 iterations against 412, docs/cracking-speed.md).
  solver->set_first_tangent(part.first_tangent_converged && concrete != Concrete::implex_cracks);
  solver->_inexact = part.inexact_newton;
  solver->_whole.set_inexact(part.inexact_newton);
  solver->_whole.set_fallback_line_search(NewtonSolver::fallback_line_search(concrete));
  if (concrete == Concrete::cracks)
  {
    // Linear tails keep their factorisation: the bench's corroded demo with
    // cracks, on its mesh of 8e10d4d, 150 s against 185 s without (334
    // against 471 factorisations; docs/cracking.md, "Newton"). A stalled
    // solve stops early and is not tried again (NewtonSolver.h).
    solver->_whole.set_tail_reuse(tail_reuse_ratio);
    solver->_whole.set_stop_when_stalled(true);
  }
  solver->_whole_linear = whole_linear;
  solver->_single_precision = part.mixed_precision;
  solver->_condense_required = required;
  return solver;
}

void LoadStepSolver::set_first_tangent(bool converged)
{
  _first_tangent_converged = converged;
  _whole.set_first_tangent(converged);
  if (_newton)
    _newton->set_first_tangent(converged);
}

LoadStepSolver::~LoadStepSolver()
{
  if (_x)
    petsc::check_nothrow(VecDestroy(&_x), "VecDestroy");
}

void LoadStepSolver::update()
{
  if (!_condense || (_condensation && _eq.constraint_version() == _constraint_version))
    return;
  if (_condensation)
  {
    _retired_factorizations += 1 + _newton->factorizations();
    _retired_linear_iterations += _newton->linear_iterations();
  }
  _newton.reset();
  _condensation.reset();
  if (_x)
    check(VecDestroy(&_x), "VecDestroy");
  _condensation = std::make_unique<Condensation>(_eq);
  _asymmetry = _condensation->asymmetry();
  if (const std::string why = _condensation->untrusted(); !why.empty())
  {
    // "on" asked for the condensed system; "auto" never fails where the
    // whole model runs.
    if (_condense_required)
      throw std::runtime_error("condensation: " + why +
                               "; solver.condensation = \"off\" (or \"auto\") solves the "
                               "whole model");
    ++_retired_factorizations;
    _condensation.reset();
    _condense = false;
    _description = "the whole model (not condensed: " + why + ")" + _whole_linear;
    if (_talk)
      std::cout << "pushout: " << why << "; Newton on the whole model" << _whole_linear
                << std::endl;
    return;
  }
  _condensation->set_single_precision(_single_precision);
  _newton = std::make_unique<NewtonSolver>(*_condensation, _pc, _refactor_iterations);
  _newton->set_first_tangent(_first_tangent_converged);
  _newton->set_inexact(_inexact);
  _constraint_version = _eq.constraint_version();
  _x = _condensation->create_vector();
}

NonlinearProblem& LoadStepSolver::problem()
{
  update();
  if (_condensation)
    return *_condensation;
  return _eq;
}

Vec LoadStepSolver::to_problem(Vec x)
{
  update();
  if (!_condensation)
    return x;
  _condensation->restrict_to(x, _x);
  return _x;
}

void LoadStepSolver::from_problem(Vec x)
{
  if (!_condensation)
    return;
  if (_bulk_needed)
    _condensation->expand(_x, x);
  else
    _condensation->expand_interface(_x, x);
}

Vec LoadStepSolver::functional(Vec a)
{
  update();
  Vec v;
  if (!_condensation)
  {
    check(VecDuplicate(a, &v), "VecDuplicate");
    check(VecCopy(a, v), "VecCopy");
    return v;
  }
  v = _condensation->create_vector();
  _condensation->restrict_functional(a, v);
  return v;
}

SolveReport LoadStepSolver::solve(Vec x, Vec unpredicted)
{
  update(); // may find the condensation untrusted, and turn it off
  // The reference is the residual with new cracks allowed, for the
  // crack-free predictor's first solve too (solve_whole: step 0, whose
  // parts after a cut are predicted).
  if (!_condense)
    return solve_whole(x, unpredicted ? residual_norm(unpredicted) : 0.0);
  Vec xp = to_problem(x);
  SolveReport r = _newton->solve(xp);
  if (r.converged)
  {
    from_problem(x);
    if (!finite(x)) // the bulk recovered from the jumps
    {
      r.converged = false;
      r.reason = "DIVERGED_NONFINITE_SOLUTION (the displacement recovered from the jumps is not a "
                 "number)";
    }
  }
  return r;
}

double LoadStepSolver::residual_norm(Vec unpredicted)
{
  if (!_residual_work.get()) // the whole model's layout, once
    _residual_work = Vector(_eq.create_vector());
  Vec F = _residual_work;
  const MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(unpredicted));
  const bool ok =
      mpi::all(comm, mpi::collectively(comm, [&] { return _eq.residual(unpredicted, F); }));
  PetscReal norm = 0;
  check(VecNorm(F, NORM_2, &norm), "VecNorm");
  return ok && std::isfinite(norm) ? double(norm) : 0.0;
}

SolveReport LoadStepSolver::solve_whole(Vec x, double reference)
{
  // IMPL-EX cracks are the step's secant maps, fixed through it: nothing
  // to hold back.
  model::BulkCracking* bulk = _eq.model().bulk_cracking();
  if (!bulk || !_crack_free_predictor || bulk->implex())
    return _whole.solve(x, reference);
  Vec copy;
  check(VecDuplicate(x, &copy), "VecDuplicate");
  const Vector start(copy); // destroyed on every way out
  check(VecCopy(x, start), "VecCopy");
  bulk->allow_new_cracks(false);
  SolveReport first;
  try
  {
    first = _whole.solve(x, reference);
  }
  catch (...) // the concrete may crack again whatever happens next
  {
    bulk->allow_new_cracks(true);
    throw;
  }
  bulk->allow_new_cracks(true);
  if (!first.converged) // from the step's start, as without the predictor
  {
    check(VecCopy(start, x), "VecCopy");
    _whole.forget_tangent();
  }
  SolveReport r = _whole.solve(x, reference);
  r.iterations += first.iterations;
  return r;
}

std::int64_t LoadStepSolver::linear_iterations() const
{
  return _whole.linear_iterations() + _retired_linear_iterations +
         (_newton ? _newton->linear_iterations() : 0);
}

int LoadStepSolver::factorizations() const
{
  int n = _whole.factorizations() + _retired_factorizations;
  if (_condensation)
    n += 1 + _newton->factorizations();
  return n;
}
} // namespace pushout::solver

// The least-squares solver of a fit (TaoFit.h): TAO's set-up, its callbacks
// (the objective, its gradient by the forward-difference Jacobian, the
// Gauss-Newton Hessian, the convergence test) and the progress line of each
// iteration.
#include "TaoFit.h"
#include "../common/Interrupt.h"
#include "../common/petsc_check.h"
#include "../solver/FitTao.h"
#include "FitStatistics.h"
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace pushout::study
{
namespace
{
using petsc::check;

PetscErrorCode objective_callback(Tao, Vec X, PetscReal* f, void* ctx)
{
  return petsc::callback(
      [&]
      {
        Problem& p = *static_cast<Problem*>(ctx);
        p.evaluate(p.values(X), false);
        *f = p.objective();
      });
}

/// f and its gradient J^T r.
PetscErrorCode objective_gradient_callback(Tao, Vec X, PetscReal* f, Vec G, void* ctx)
{
  return petsc::callback(
      [&]
      {
        Problem& p = *static_cast<Problem*>(ctx);
        p.evaluate(p.values(X), true);
        *f = p.objective();
        const std::vector<double> gradient = transpose_times(p.jacobian, p.r_last);
        PetscScalar* g;
        check(VecGetArray(G, &g), "VecGetArray");
        std::copy(gradient.begin(), gradient.end(), g);
        check(VecRestoreArray(G, &g), "VecRestoreArray");
      });
}

/// Gauss-Newton's Hessian J^T J.
PetscErrorCode hessian_callback(Tao, Vec X, Mat H, Mat, void* ctx)
{
  return petsc::callback(
      [&]
      {
        Problem& p = *static_cast<Problem*>(ctx);
        p.evaluate(p.values(X), true);
        const std::size_t n = p.free.size();
        const auto JtJ = normal_matrix(p.jacobian.data(), p.r_last.size(), n);
        for (std::size_t j = 0; j < n; ++j)
          for (std::size_t k = 0; k < n; ++k)
            check(MatSetValue(H, PetscInt(j), PetscInt(k), JtJ[j][k], INSERT_VALUES),
                  "MatSetValue");
        check(MatAssemblyBegin(H, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
        check(MatAssemblyEnd(H, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
      });
}

/// TAO's own test (its gradient's tolerances, its iteration limit), then the
/// relative offset's (Resolution::offset_tolerance), which also ends a fit
/// at its iteration limit as converged where it is met, and its floor
/// (Resolution::stall_ratio); the progress line.
PetscErrorCode convergence_test(Tao tao, void* ctx)
{
  return petsc::callback(
      [&]
      {
        Problem& p = *static_cast<Problem*>(ctx);
        check(TaoDefaultConvergenceTest(tao, nullptr), "TaoDefaultConvergenceTest");
        if (tao != p.tao) // a solver BNLS runs inside (-tao_bnk_max_cg_its)
          return;
        Vec X;
        check(TaoGetSolution(tao, &X), "TaoGetSolution");
        PetscInt iteration;
        check(TaoGetIterationNumber(tao, &iteration), "TaoGetIterationNumber");
        const std::vector<double> x = p.values(X);
        const double offset = p.offset_at(x);
        p.report(int(iteration), x, offset);
        TaoConvergedReason reason;
        check(TaoGetConvergedReason(tao, &reason), "TaoGetConvergedReason");
        const bool going = reason == TAO_CONTINUE_ITERATING || reason == TAO_DIVERGED_MAXITS;
        // Settled: inside the confidence region, the offset fell by less
        // than the ratio asks in two iterations running, each on a Jacobian
        // of its own (the steps left are the curve's jumps). Counted once
        // per iteration (BNLS may test its start twice).
        if (iteration != p.last_iteration)
        {
          const bool stalled = p.resolution.stall_ratio > 0 && offset < 1 &&
                               offset > p.resolution.stall_ratio * p.last_offset;
          p.stalls = stalled ? p.stalls + 1 : 0;
          // Met refused values and did not halve the offset: creeping
          // towards a relation, not overshooting it on the way to an
          // optimum inside (whose Gauss-Newton steps shrink fast).
          const bool blocked = p.failed_in_search && !(offset < 0.5 * p.last_offset);
          p.searches_failed = blocked ? p.searches_failed + 1 : 0;
          p.failed_in_search = false;
          p.last_iteration = iteration;
        }
        // Or its line search met the model's resolution: what is left of
        // the step is below the curve's jumps (Problem::search_at_resolution).
        const bool settled = p.stalls >= 2 || p.search_at_resolution;
        if (going && (offset < p.resolution.offset_tolerance || settled))
        {
          p.at_resolution = offset >= p.resolution.offset_tolerance;
          check(TaoSetConvergedReason(tao, TAO_CONVERGED_USER), "TaoSetConvergedReason");
        }
        else if (going && p.searches_failed >= Problem::searches_failed_to_stop)
          check(TaoSetConvergedReason(tao, TAO_DIVERGED_USER), "TaoSetConvergedReason");
        if (!std::isnan(offset))
          p.last_offset = offset;
      });
}
} // namespace

std::vector<double> Problem::values(Vec X) const
{
  const PetscScalar* a;
  check(VecGetArrayRead(X, &a), "VecGetArrayRead");
  std::vector<double> x(a, a + free.size());
  check(VecRestoreArrayRead(X, &a), "VecRestoreArrayRead");
  return x;
}

double Problem::half_square(const std::vector<double>& r)
{
  double s = 0;
  for (double v : r)
    s += v * v;
  return s / 2;
}

double Problem::rms() const
{
  return std::sqrt(2 * objective() / double(r_last.size()));
}

double Problem::offset_at(const std::vector<double>& x) const
{
  if (x != x_jacobian || x != x_last)
    return NAN;
  // The step still to go is along the values free to move: one on a bound
  // that the gradient pushes beyond it stays there (TAO's bounded step).
  const std::size_t m = r_last.size();
  const std::vector<double> g = transpose_times(jacobian, r_last); // d(|r|^2 / 2) / dx
  std::vector<double> columns;
  for (std::size_t j = 0; j < free.size(); ++j)
  {
    if ((free[j].on_lo(x[j]) && g[j] > 0) || (free[j].on_hi(x[j]) && g[j] < 0))
      continue;
    if (j < difference_failed.size() && difference_failed[j])
      continue; // no derivative: the step cannot be told along it
    columns.insert(columns.end(), jacobian.begin() + std::ptrdiff_t(j * m),
                   jacobian.begin() + std::ptrdiff_t((j + 1) * m));
  }
  return columns.empty() ? 0.0 : relative_offset(columns, r_last);
}

bool Problem::nothing_to_judge(const std::vector<double>& x) const
{
  if (x != x_jacobian || difference_failed.size() < free.size())
    return false;
  const std::size_t m = r_last.size();
  for (std::size_t j = 0; j < free.size(); ++j)
  {
    // A column of zeros is no derivative either: the runs beside x gave the
    // same curve (a value the curve no longer depends on, such as mu where
    // the tube no longer slips; TAO's gradient test then ends at zero).
    const auto column = jacobian.begin() + std::ptrdiff_t(j * m);
    const bool flat =
        std::all_of(column, column + std::ptrdiff_t(m), [](double d) { return d == 0.0; });
    if (!difference_failed[j] && !flat)
      return false;
  }
  return true;
}

void Problem::report(int iteration, const std::vector<double>& x, double offset) const
{
  if (!talk)
    return;
  std::ostringstream s;
  s << "fit: iteration " << iteration;
  if (std::isnan(offset)) // x is not the last point tried: TAO went back to it
    s << ": the line search found no step; back at";
  else
    s << ", rms " << std::setprecision(6) << rms() << " MPa, offset " << std::setprecision(3)
      << offset << " at";
  for (std::size_t j = 0; j < x.size(); ++j)
    s << " " << free[j].key << " = " << std::setprecision(8) << x[j] * free[j].scale;
  s << " (" << evaluator.evaluations() << " runs, " << std::fixed << std::setprecision(1)
    << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() << " s)";
  std::cout << s.str() << std::endl;
}

namespace
{
/// Whether a and b are the same point, to the round-off of a line search's
/// x0 + t s against ours.
bool same_point(const std::vector<double>& a, const std::vector<double>& b)
{
  for (std::size_t j = 0; j < a.size(); ++j)
    if (std::abs(a[j] - b[j]) > 1e-14 * std::max(1.0, std::abs(a[j])))
      return false;
  return true;
}
} // namespace

void Problem::evaluate(const std::vector<double>& x, bool with_jacobian)
{
  if (search_at_resolution && !with_jacobian && x != x_jacobian)
  {
    x_last = x; // not run: x_jacobian's misfit (search_at_resolution)
    r_last = known_points.front().r;
    last_failed = false;
    return;
  }
  if (x != x_last)
    for (const KnownPoint& k : known_points)
      if (same_point(k.x, x))
      {
        x_last = x;
        r_last = k.r;
        last_failed = k.failed;
        failed_in_search = failed_in_search || (k.failed && !with_jacobian);
        evaluator.count(k.x); // a run ahead, used
        break;
      }
  const bool known = x == x_last;
  if (known && (!with_jacobian || x == x_jacobian)) // TAO asks again at the same point
    return;
  std::vector<std::vector<double>> points;
  if (!known)
    points.push_back(x);
  // A point tried alone (Armijo's backtracking from x_jacobian): the other
  // groups run the points it would try next, halfway back again and again
  // (the same to round-off: same_point).
  const std::size_t ahead =
      known || with_jacobian || x_jacobian.empty() ? 0 : std::size_t(evaluator.groups() - 1);
  for (std::size_t k = 1; k <= ahead; ++k)
  {
    points.push_back(x);
    for (std::size_t j = 0; j < x.size(); ++j)
      points.back()[j] = x_jacobian[j] + std::ldexp(x[j] - x_jacobian[j], -int(k));
  }
  std::vector<double> h(x.size());
  if (with_jacobian)
    for (std::size_t j = 0; j < x.size(); ++j)
    {
      h[j] = resolution.difference_step * std::max(std::abs(x[j]), 1e-3);
      if (x[j] + h[j] > free[j].tao_hi() / free[j].scale)
        h[j] = -h[j]; // backwards at the upper bound
      points.push_back(x);
      points.back()[j] += h[j];
    }
  std::vector<bool> failed;
  auto r = evaluator.residuals(points, &failed, points.size() - ahead);
  if (!known)
  {
    x_last = x;
    r_last = r[0];
    last_failed = failed[0];
    failed_in_search = failed_in_search || (last_failed && !with_jacobian);
    // The line search's whole step (its first point) raised the misfit at
    // the model's resolution: no point after it is run.
    if (!with_jacobian && ++search_points == 1 && resolution.stall_ratio > 0 &&
        !x_jacobian.empty() && last_offset < search_resolution_offset() && !last_failed)
    {
      search_at_resolution = objective() > half_square(known_points.front().r);
      at_resolution = at_resolution || search_at_resolution; // the warning says so
    }
  }
  for (std::size_t k = 1; k <= ahead; ++k)
    known_points.push_back({points[k], r[k], failed[k]});
  if (!with_jacobian)
    return;
  const std::size_t first = known ? 0 : 1, m = r_last.size();
  // A difference whose run failed outright (x + h beyond a relation between
  // keys, such as f_fr = f_t) is taken backwards where the base run did not
  // fail and the bound leaves room; else its column holds the failure.
  std::vector<std::size_t> again;
  points.clear();
  for (std::size_t j = 0; j < x.size(); ++j)
    if (failed[first + j] && !last_failed && h[j] > 0 &&
        x[j] - h[j] >= free[j].tao_lo() / free[j].scale)
    {
      h[j] = -h[j];
      points.push_back(x);
      points.back()[j] += h[j];
      again.push_back(j);
    }
  if (!again.empty())
  {
    std::vector<bool> back_failed;
    const auto back = evaluator.residuals(points, &back_failed);
    for (std::size_t k = 0; k < again.size(); ++k)
      if (back_failed[k]) // both ways fail: the forward failure stays
        h[again[k]] = -h[again[k]];
      else
        r[first + again[k]] = back[k];
  }
  difference_failed.assign(x.size(), false);
  for (std::size_t j = 0; j < x.size(); ++j)
  {
    const bool taken_back = std::find(again.begin(), again.end(), j) != again.end() && h[j] < 0;
    difference_failed[j] = failed[first + j] && !taken_back;
  }
  x_jacobian = x;
  search_points = 0;
  known_points = {{x, r_last, last_failed}};
  jacobian.assign(m * x.size(), 0.0);
  for (std::size_t j = 0; j < x.size(); ++j)
    for (std::size_t i = 0; i < m; ++i)
      jacobian[j * m + i] = (r[first + j][i] - r_last[i]) / h[j];
}

void Problem::fill(Mat J) const
{
  const std::size_t m = r_last.size();
  for (std::size_t j = 0; j < free.size(); ++j)
    for (std::size_t i = 0; i < m; ++i)
      check(MatSetValue(J, PetscInt(i), PetscInt(j), jacobian[j * m + i], INSERT_VALUES),
            "MatSetValue");
  check(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
}

TaoFit::TaoFit(const std::vector<Free>& free, PetscInt m, Problem& problem) : _problem(problem)
{
  const PetscInt n = PetscInt(free.size());
  check(TaoCreate(PETSC_COMM_SELF, &tao), "TaoCreate");
  problem.tao = tao;
  check(TaoSetType(tao, TAOBNLS), "TaoSetType");
  check(VecCreateSeq(PETSC_COMM_SELF, n, &X), "VecCreateSeq");
  check(VecDuplicate(X, &lo), "VecDuplicate");
  check(VecDuplicate(X, &hi), "VecDuplicate");
  check(MatCreateSeqDense(PETSC_COMM_SELF, m, n, nullptr, &J), "MatCreateSeqDense");
  check(MatCreateSeqDense(PETSC_COMM_SELF, n, n, nullptr, &H), "MatCreateSeqDense");
  for (PetscInt j = 0; j < n; ++j)
  {
    const Free& f = free[std::size_t(j)];
    check(VecSetValue(X, j, f.start / f.scale, INSERT_VALUES), "VecSetValue");
    check(VecSetValue(lo, j, std::isfinite(f.lo) ? f.tao_lo() / f.scale : PETSC_NINFINITY,
                      INSERT_VALUES),
          "VecSetValue");
    check(VecSetValue(hi, j, std::isfinite(f.hi) ? f.tao_hi() / f.scale : PETSC_INFINITY,
                      INSERT_VALUES),
          "VecSetValue");
  }
  for (Vec v : {X, lo, hi})
  {
    check(VecAssemblyBegin(v), "VecAssemblyBegin");
    check(VecAssemblyEnd(v), "VecAssemblyEnd");
  }
  check(TaoSetSolution(tao, X), "TaoSetSolution");
  check(TaoSetVariableBounds(tao, lo, hi), "TaoSetVariableBounds");
  check(TaoSetObjective(tao, objective_callback, &problem), "TaoSetObjective");
  check(TaoSetObjectiveAndGradient(tao, nullptr, objective_gradient_callback, &problem),
        "TaoSetObjectiveAndGradient");
  check(TaoSetHessian(tao, H, H, hessian_callback, &problem), "TaoSetHessian");
  check(TaoSetConvergenceTest(tao, convergence_test, &problem), "TaoSetConvergenceTest");
  // Its type already (a set-up of the same type leaves the callbacks).
  solver::set_up_fit_tao(tao, problem.resolution.line_search);
}

TaoFit::~TaoFit()
{
  petsc::check_nothrow(TaoDestroy(&tao), "TaoDestroy");
  for (Vec* v : {&X, &lo, &hi})
    petsc::check_nothrow(VecDestroy(v), "VecDestroy");
  for (Mat* a : {&J, &H})
    petsc::check_nothrow(MatDestroy(a), "MatDestroy");
}

std::vector<double> TaoFit::solve()
{
  const interrupt::Phase phase("fit", interrupt::stop_grace_s);
  check(TaoSolve(tao), "TaoSolve");
  // At the optimum: residuals and the Jacobian (of the scaled values).
  std::vector<double> x = _problem.values(X);
  _problem.evaluate(x, true);
  _problem.fill(J);
  no_derivative = _problem.nothing_to_judge(x);
  final_offset = no_derivative ? NAN : _problem.offset_at(x); // NaN: none to take
  return x;
}

bool TaoFit::converged() const
{
  TaoConvergedReason reason;
  check(TaoGetConvergedReason(tao, &reason), "TaoGetConvergedReason");
  return !no_derivative && (reason > 0 || at_resolution_by_search(reason));
}

bool TaoFit::at_resolution_by_search(TaoConvergedReason reason) const
{
  // The line search given x_jacobian's misfit at every point it tried
  // found none better (Problem::search_at_resolution): TAO ends so.
  return reason == TAO_DIVERGED_LS_FAILURE && _problem.search_at_resolution;
}

std::string TaoFit::reason() const
{
  TaoConvergedReason reason;
  check(TaoGetConvergedReason(tao, &reason), "TaoGetConvergedReason");
  if (no_derivative)
    return "DIVERGED_NO_DERIVATIVE";
  if (reason == TAO_CONVERGED_USER) // the tests of ours (convergence_test)
    return _problem.at_resolution ? "CONVERGED_MODEL_RESOLUTION" : "CONVERGED_RELATIVE_OFFSET";
  if (at_resolution_by_search(reason))
    return "CONVERGED_MODEL_RESOLUTION";
  if (reason == TAO_DIVERGED_USER) // our test's only divergence (convergence_test)
    return "DIVERGED_REFUSED_VALUES";
  return TaoConvergedReasons[reason];
}

int TaoFit::iterations() const
{
  PetscInt n;
  check(TaoGetIterationNumber(tao, &n), "TaoGetIterationNumber");
  return int(n);
}
} // namespace pushout::study

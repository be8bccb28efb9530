#include "Fit.h"
#include "../common/Interrupt.h"
#include "../common/exit_codes.h"
#include "../common/mpi_errors.h"
#include "../common/petsc_check.h"
#include "../driver/Run.h"
#include "../driver/exit_on_error.h"
#include "../laws/LawRegistry.h"
#include "../output/OutputFiles.h"
#include "../output/plot.h"
#include "../scene/SceneError.h"
#include "../specimen/Scenario.h"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <petsctao.h>
#include <sstream>

namespace pushout::study
{
using driver::run_case;
using driver::RunOptions;
using driver::RunOutcome;
using driver::Simulation;
namespace
{
using petsc::check;

/// The relative step of the forward differences of the Jacobian (of the
/// scaled values, which start at 1).
constexpr double difference_step = 1e-4;
/// Two values whose correlation exceeds this are not separately
/// identifiable from the data.
constexpr double identifiable_correlation = 0.95;

/// A signal stopped the fit (thrown on every process at once).
class Interrupted : public std::runtime_error
{
public:
  explicit Interrupted(int signal)
      : std::runtime_error("interrupted by " + interrupt::signal_name(signal)), signal(signal)
  {
  }
  int signal;
};

/// A free value: its key, start, bounds and the scale TAO divides it by.
struct Free
{
  std::string key;
  double start = 0, lo = -INFINITY, hi = INFINITY, scale = 1;
  bool lo_exclusive = false; ///< lo itself is not allowed (a law's positive parameter)
  /// The lower bound given to TAO: lo, or the next number above it.
  double tao_lo() const { return lo_exclusive ? std::nextafter(lo, INFINITY) : lo; }
};

std::vector<std::string> split(const std::string& s, char by)
{
  std::vector<std::string> parts;
  std::stringstream in(s);
  for (std::string part; std::getline(in, part, by);)
    parts.push_back(part);
  return parts;
}

std::string number_text(double v)
{
  std::ostringstream s;
  s << std::setprecision(17) << v;
  return s.str();
}

/// The value of `key` in `scene` and the lower bound of its range (from the
/// law's parameter declaration, and whether it is exclusive; -inf for other
/// keys); throws SceneError if the key is not a number of the scene.
double value_of(const Scene& scene, const std::string& key, double& minimum, bool& exclusive)
{
  minimum = -INFINITY;
  exclusive = false;
  const std::vector<std::string> parts = split(key, '.');
  if (parts.size() == 3 && (parts[0] == "interface" || parts[0] == "crack") && !parts[1].empty() &&
      std::all_of(parts[1].begin(), parts[1].end(), ::isdigit))
  {
    const std::size_t i = std::stoul(parts[1]);
    const bool itf = parts[0] == "interface";
    if (i >= (itf ? scene.layers().size() : scene.cracks().size()))
      throw SceneError("--free '" + key + "': the scene has no " + parts[0] + " " + parts[1]);
    const LayerSpec& layer = itf ? scene.layers()[i] : scene.cracks()[i].layer;
    const laws::LawInfo* law = laws::find_law(layer.law);
    const auto def = std::find_if(law->params.begin(), law->params.end(),
                                  [&](const laws::ParamDef& p) { return p.name == parts[2]; });
    if (def == law->params.end())
    {
      std::string names;
      for (const auto& p : law->params)
        names += (names.empty() ? "" : ", ") + p.name;
      throw SceneError("--free '" + key + "': law '" + layer.law + "' has no parameter '" +
                       parts[2] + "' (it has " + names + ")");
    }
    const auto it = layer.params.find(parts[2]);
    if (it == layer.params.end())
      throw SceneError("--free '" + key + "' has no value in the scene (an optional parameter): " +
                       "give it a start with --set " + key + "=...");
    minimum = def->min;
    exclusive = def->min_exclusive;
    return it->second;
  }
  const Value* v = scene.find(key);
  if (!v)
    throw SceneError("--free '" + key + "': no such key (pushout keys lists them)");
  if (const double* d = std::get_if<double>(v))
    return *d;
  throw SceneError("--free '" + key + "': not a number key (" + to_toml(*v) + ")");
}

/// The message of the lowest-ranked process of `comm` that has one ("" if
/// none has). Collective.
std::string first_message(const std::string& mine, MPI_Comm comm)
{
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  int first = size;
  const int have = mine.empty() ? size : rank;
  MPI_Allreduce(&have, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == size)
    return "";
  long long length = rank == first ? static_cast<long long>(mine.size()) : 0;
  MPI_Bcast(&length, 1, MPI_LONG_LONG, first, comm);
  std::string message = rank == first ? mine : std::string(std::size_t(length), ' ');
  MPI_Bcast(message.data(), int(length), MPI_CHAR, first, comm);
  return message;
}

/// The free values with their starts and bounds; throws SceneError.
std::vector<Free> free_values(const Scene& scene, const FitOptions& opt)
{
  if (opt.free.empty())
    throw SceneError("pushout fit needs at least one --free key");
  std::vector<Free> free;
  for (const std::string& key : opt.free)
  {
    if (std::any_of(free.begin(), free.end(), [&](const Free& f) { return f.key == key; }))
      throw SceneError("--free '" + key + "' is given twice");
    Free f{key};
    f.start = value_of(scene, key, f.lo, f.lo_exclusive);
    f.scale = f.start != 0 ? std::abs(f.start) : 1.0;
    free.push_back(f);
  }
  for (const std::string& b : opt.bounds)
  {
    const auto eq = b.find('='), colon = b.find(':', eq == std::string::npos ? 0 : eq);
    if (eq == std::string::npos || colon == std::string::npos)
      throw SceneError("--bounds '" + b + "': expected key=lo:hi (either may be empty)");
    const std::string key = b.substr(0, eq);
    const auto f =
        std::find_if(free.begin(), free.end(), [&](const Free& x) { return x.key == key; });
    if (f == free.end())
      throw SceneError("--bounds '" + b + "': '" + key + "' is not a --free key");
    try
    {
      const std::string lo = b.substr(eq + 1, colon - eq - 1), hi = b.substr(colon + 1);
      if (!lo.empty() && std::stod(lo) > f->lo)
      {
        f->lo = std::stod(lo);
        f->lo_exclusive = false;
      }
      if (!hi.empty())
        f->hi = std::stod(hi);
    }
    catch (const std::exception&)
    {
      throw SceneError("--bounds '" + b + "': the bounds must be numbers");
    }
  }
  for (const Free& f : free)
    if (!(f.tao_lo() <= f.start && f.start <= f.hi))
      throw SceneError("the bounds of '" + f.key + "' " + (f.lo_exclusive ? "(" : "[") +
                       number_text(f.lo) + ", " + number_text(f.hi) + "] exclude its start " +
                       number_text(f.start));
  return free;
}

/// The model runs of the fit, spread over the groups of processes.
class Evaluator
{
public:
  Evaluator(const FitOptions& opt, const std::vector<Free>& free, const MeasuredCurve& data,
            MPI_Comm group, int groups, int group_index)
      : _opt(opt), _free(free), _data(data), _group(group), _groups(groups),
        _group_index(group_index)
  {
    int rank = 0;
    MPI_Comm_rank(group, &rank);
    _leader = rank == 0;
  }

  /// The residuals at each of `points` (scaled values); every process gets
  /// them all. Collective on MPI_COMM_WORLD.
  std::vector<std::vector<double>> residuals(const std::vector<std::vector<double>>& points)
  {
    const std::size_t m = _data.delta.size();
    std::vector<double> all(points.size() * m, 0.0);
    for (std::size_t k = 0; k < points.size(); ++k)
      if (int(k % std::size_t(_groups)) == _group_index)
      {
        const std::vector<double> r =
            run(points[k], _opt.out / ".runs" / ("group_" + std::to_string(_group_index)));
        if (_leader)
          std::copy(r.begin(), r.end(), all.begin() + std::ptrdiff_t(k * m));
      }
    MPI_Allreduce(MPI_IN_PLACE, all.data(), int(all.size()), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    int signal = std::max(interrupt::received(), _signal);
    MPI_Allreduce(MPI_IN_PLACE, &signal, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    if (signal != 0) // on every process alike: TaoSolve ends with it
    {
      interrupt::acknowledge();
      throw Interrupted(signal);
    }
    int failed = _failed;
    MPI_Allreduce(&failed, &_failed_total, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
    _evaluations += int(points.size());
    std::vector<std::vector<double>> out;
    for (std::size_t k = 0; k < points.size(); ++k)
      out.emplace_back(all.begin() + std::ptrdiff_t(k * m),
                       all.begin() + std::ptrdiff_t((k + 1) * m));
    return out;
  }

  /// The --set overrides of the scene at scaled values x.
  std::vector<std::string> sets_at(const std::vector<double>& x) const
  {
    std::vector<std::string> sets = _opt.sets;
    sets.push_back("loading.push_displacement=" + number_text(_data.delta.back()));
    for (std::size_t j = 0; j < _free.size(); ++j)
      sets.push_back(_free[j].key + "=" + number_text(x[j] * _free[j].scale));
    return sets;
  }

  /// One run at scaled values x into `out` on this group; its residuals
  /// (leader), the curve held flat after its last row if it stopped short.
  std::vector<double> run(const std::vector<double>& x, const std::filesystem::path& out,
                          bool plot = false)
  {
    const RunOutcome o =
        run_case(_opt.scene_file, sets_at(x),
                 {out, _opt.mesh_cache, true, _opt.force, _group, plot}, _simulation);
    std::vector<double> r(_data.delta.size(), 0.0);
    _last_exit_code = o.exit_code;
    if (o.exit_code > exit_code::signal(0))
      _signal = o.exit_code - exit_code::signal(0);
    if (o.exit_code != 0 && _leader) // once per group: the count is summed over processes
    {
      ++_failed;
      _last_failure = o.message;
    }
    if (!_leader)
      return r;
    std::vector<double> delta, tau;
    std::ifstream in(out / "curve.csv");
    std::string line;
    std::getline(in, line);
    const std::vector<std::string> header = split(line, ',');
    const auto column = [&](const std::string& name)
    { return std::size_t(std::find(header.begin(), header.end(), name) - header.begin()); };
    const std::size_t cd = column("delta_mm"), ct = column("tau_MPa");
    while (std::getline(in, line)) // our own file: a row that does not parse ends it
    {
      const std::vector<std::string> cells = split(line, ',');
      if (cd >= cells.size() || ct >= cells.size())
        break;
      char *end_d = nullptr, *end_t = nullptr;
      const double d = std::strtod(cells[cd].c_str(), &end_d);
      const double t = std::strtod(cells[ct].c_str(), &end_t);
      if (end_d == cells[cd].c_str() || end_t == cells[ct].c_str())
        break;
      delta.push_back(d);
      tau.push_back(t);
    }
    for (std::size_t i = 0; i < r.size(); ++i)
      r[i] = (delta.empty() ? 0.0 : interpolate(delta, tau, _data.delta[i])) - _data.tau[i];
    return r;
  }

  int evaluations() const { return _evaluations; }
  /// The exit code of this group's last run.
  int last_exit_code() const { return _last_exit_code; }
  /// A signal that stopped a run of any process, or came here (collective
  /// on MPI_COMM_WORLD).
  int signal_anywhere() const
  {
    int signal = std::max(interrupt::received(), _signal);
    MPI_Allreduce(MPI_IN_PLACE, &signal, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    return signal;
  }
  int failed() const { return _failed_total; }
  const std::string& last_failure() const { return _last_failure; }
  void release() { _simulation.reset(); }

private:
  const FitOptions& _opt;
  const std::vector<Free>& _free;
  const MeasuredCurve& _data;
  MPI_Comm _group;
  int _groups, _group_index;
  bool _leader = false;
  std::unique_ptr<Simulation> _simulation; ///< the group's set-up, reused
  int _evaluations = 0, _failed = 0, _failed_total = 0;
  int _signal = 0; ///< a run stopped by this signal
  int _last_exit_code = exit_code::done;
  std::string _last_failure;
};

/// What TAO's callbacks share.
struct Problem
{
  Evaluator& evaluator;
  const std::vector<Free>& free;
  bool talk = false;
  std::vector<double> x_last, r_last; ///< the last base point and its residuals
  std::vector<double> x_jacobian;     ///< where the last Jacobian was formed
  std::vector<double> jacobian;       ///< its entries, column-major (m x n)
  int iterations = 0;
  std::chrono::steady_clock::time_point t0;

  std::vector<double> values(Vec X) const
  {
    const PetscScalar* a;
    check(VecGetArrayRead(X, &a), "VecGetArrayRead");
    std::vector<double> x(a, a + free.size());
    check(VecRestoreArrayRead(X, &a), "VecRestoreArrayRead");
    return x;
  }

  double rms() const
  {
    double s = 0;
    for (double r : r_last)
      s += r * r;
    return std::sqrt(s / double(r_last.size()));
  }

  /// The stored Jacobian into J.
  void fill(Mat J) const;

  /// The residuals at x and, if `J`, the forward-difference Jacobian there
  /// (one batch of runs over the groups).
  void evaluate(const std::vector<double>& x, Mat J)
  {
    if (J && x == x_jacobian && x == x_last) // TAO asks again at the same point
    {
      fill(J);
      return;
    }
    std::vector<std::vector<double>> points;
    const bool known = x == x_last;
    if (!known)
      points.push_back(x);
    std::vector<double> h(x.size());
    if (J)
      for (std::size_t j = 0; j < x.size(); ++j)
      {
        h[j] = difference_step * std::max(std::abs(x[j]), 1e-3);
        if (x[j] + h[j] > free[j].hi / free[j].scale)
          h[j] = -h[j]; // backwards at the upper bound
        points.push_back(x);
        points.back()[j] += h[j];
      }
    const auto r = evaluator.residuals(points);
    if (!known)
    {
      x_last = x;
      r_last = r[0];
    }
    if (!J)
      return;
    const std::size_t first = known ? 0 : 1, m = r_last.size();
    x_jacobian = x;
    jacobian.assign(m * x.size(), 0.0);
    for (std::size_t j = 0; j < x.size(); ++j)
      for (std::size_t i = 0; i < m; ++i)
        jacobian[j * m + i] = (r[first + j][i] - r_last[i]) / h[j];
    fill(J);
    ++iterations;
    if (talk)
    {
      std::ostringstream s;
      s << "fit: iteration " << iterations << ", rms " << std::setprecision(6) << rms()
        << " MPa at";
      for (std::size_t j = 0; j < x.size(); ++j)
        s << " " << free[j].key << " = " << std::setprecision(8) << x[j] * free[j].scale;
      s << " (" << evaluator.evaluations() << " runs, " << std::fixed << std::setprecision(1)
        << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() << " s)";
      std::cout << s.str() << std::endl;
    }
  }
};

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

PetscErrorCode residual_callback(Tao, Vec X, Vec F, void* ctx)
{
  return petsc::callback(
      [&]
      {
        Problem& p = *static_cast<Problem*>(ctx);
        p.evaluate(p.values(X), nullptr);
        PetscScalar* f;
        check(VecGetArray(F, &f), "VecGetArray");
        std::copy(p.r_last.begin(), p.r_last.end(), f);
        check(VecRestoreArray(F, &f), "VecRestoreArray");
      });
}

PetscErrorCode jacobian_callback(Tao, Vec X, Mat J, Mat, void* ctx)
{
  return petsc::callback(
      [&]
      {
        Problem& p = *static_cast<Problem*>(ctx);
        p.evaluate(p.values(X), J);
      });
}

/// Solves the n x n system A y = b (A symmetric positive definite, small)
/// by Gauss-Jordan with partial pivoting; false if A is singular.
bool invert(std::vector<std::vector<double>> a, std::vector<std::vector<double>>& inverse)
{
  const std::size_t n = a.size();
  inverse.assign(n, std::vector<double>(n, 0.0));
  for (std::size_t i = 0; i < n; ++i)
    inverse[i][i] = 1;
  for (std::size_t c = 0; c < n; ++c)
  {
    std::size_t p = c;
    for (std::size_t r = c + 1; r < n; ++r)
      if (std::abs(a[r][c]) > std::abs(a[p][c]))
        p = r;
    if (!(std::abs(a[p][c]) > 1e-300))
      return false;
    std::swap(a[p], a[c]);
    std::swap(inverse[p], inverse[c]);
    const double d = a[c][c];
    for (std::size_t k = 0; k < n; ++k)
    {
      a[c][k] /= d;
      inverse[c][k] /= d;
    }
    for (std::size_t r = 0; r < n; ++r)
      if (r != c)
      {
        const double f = a[r][c];
        for (std::size_t k = 0; k < n; ++k)
        {
          a[r][k] -= f * a[c][k];
          inverse[r][k] -= f * inverse[c][k];
        }
      }
  }
  return true;
}
} // namespace

MeasuredCurve read_measured(const std::filesystem::path& file)
{
  std::ifstream in(file);
  if (!in)
    throw SceneError("--data '" + file.string() + "': cannot read it");
  std::string line;
  if (!std::getline(in, line))
    throw SceneError("--data '" + file.string() + "' is empty");
  if (!line.empty() && line.back() == '\r')
    line.pop_back();
  const std::vector<std::string> header = split(line, ',');
  const auto find = [&](const std::string& name)
  {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end())
      throw SceneError("--data '" + file.string() + "': no column '" + name + "' in its header '" +
                       line + "' (delta_mm and tau_MPa are needed)");
    return std::size_t(it - header.begin());
  };
  const std::size_t cd = find("delta_mm"), ct = find("tau_MPa");
  MeasuredCurve c;
  for (int row = 2; std::getline(in, line); ++row)
  {
    if (!line.empty() && line.back() == '\r')
      line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos)
      continue;
    const std::vector<std::string> cells = split(line, ',');
    double v[2];
    for (int k = 0; k < 2; ++k)
    {
      const std::size_t col = k == 0 ? cd : ct;
      std::size_t used = 0;
      try
      {
        if (col >= cells.size())
          throw std::invalid_argument("missing");
        v[k] = std::stod(cells[col], &used);
      }
      catch (const std::exception&)
      {
        used = 0;
      }
      if (used == 0 || cells[col].find_first_not_of(" \t", used) != std::string::npos ||
          !std::isfinite(v[k]))
        throw SceneError("--data '" + file.string() + "' line " + std::to_string(row) + ": " +
                         header[col] + " '" + (col < cells.size() ? cells[col] : "") +
                         "' is not a number");
    }
    if (!c.delta.empty() && !(v[0] > c.delta.back()))
      throw SceneError("--data '" + file.string() + "' line " + std::to_string(row) +
                       ": delta_mm must increase (a monotonic push; unload and reload "
                       "branches are not fitted)");
    c.delta.push_back(v[0]);
    c.tau.push_back(v[1]);
  }
  if (c.delta.empty())
    throw SceneError("--data '" + file.string() + "' has no rows");
  if (std::none_of(c.tau.begin(), c.tau.end(), [](double t) { return t > 0; }))
    throw SceneError("--data '" + file.string() +
                     "': no tau_MPa above 0: a push-out's bond stress is positive (the push "
                     "force resists the push); a curve of the opposite sign needs its sign "
                     "changed");
  if (!(c.delta.back() > 0))
    throw SceneError("--data '" + file.string() + "': the largest delta_mm must be > 0");
  return c;
}

double interpolate(const std::vector<double>& delta, const std::vector<double>& tau, double d)
{
  if (d <= delta.front())
    return tau.front();
  for (std::size_t i = 1; i < delta.size(); ++i)
    if (d <= delta[i])
    {
      const double t = (d - delta[i - 1]) / (delta[i] - delta[i - 1]);
      return tau[i - 1] + t * (tau[i] - tau[i - 1]);
    }
  return tau.back();
}

namespace
{
/// The TAO solver of a fit (bounded regularised Gauss-Newton, TAOBRGN) on
/// the scaled values x = value / scale, with its vectors: the start and the
/// bounds of `free`, the m residuals and their Jacobian; freed when it goes.
struct TaoFit
{
  Tao tao = nullptr;
  Vec X = nullptr, F = nullptr, lo = nullptr, hi = nullptr;
  Mat J = nullptr;

  TaoFit(const std::vector<Free>& free, PetscInt m, Problem& problem)
  {
    const PetscInt n = PetscInt(free.size());
    check(TaoCreate(PETSC_COMM_SELF, &tao), "TaoCreate");
    check(TaoSetType(tao, TAOBRGN), "TaoSetType");
    check(VecCreateSeq(PETSC_COMM_SELF, n, &X), "VecCreateSeq");
    check(VecDuplicate(X, &lo), "VecDuplicate");
    check(VecDuplicate(X, &hi), "VecDuplicate");
    check(VecCreateSeq(PETSC_COMM_SELF, m, &F), "VecCreateSeq");
    check(MatCreateSeqDense(PETSC_COMM_SELF, m, n, nullptr, &J), "MatCreateSeqDense");
    for (PetscInt j = 0; j < n; ++j)
    {
      const Free& f = free[std::size_t(j)];
      check(VecSetValue(X, j, f.start / f.scale, INSERT_VALUES), "VecSetValue");
      check(VecSetValue(lo, j, std::isfinite(f.lo) ? f.tao_lo() / f.scale : PETSC_NINFINITY,
                        INSERT_VALUES),
            "VecSetValue");
      check(
          VecSetValue(hi, j, std::isfinite(f.hi) ? f.hi / f.scale : PETSC_INFINITY, INSERT_VALUES),
          "VecSetValue");
    }
    for (Vec v : {X, lo, hi})
    {
      check(VecAssemblyBegin(v), "VecAssemblyBegin");
      check(VecAssemblyEnd(v), "VecAssemblyEnd");
    }
    check(TaoSetSolution(tao, X), "TaoSetSolution");
    check(TaoSetVariableBounds(tao, lo, hi), "TaoSetVariableBounds");
    check(TaoSetResidualRoutine(tao, F, residual_callback, &problem), "TaoSetResidualRoutine");
    check(TaoSetJacobianResidualRoutine(tao, J, J, jacobian_callback, &problem),
          "TaoSetJacobianResidualRoutine");
    // Converged when the gradient fell by 1e6 from the start (the
    // differences' noise floor is near 1e-10 of it) or below 1e-12 [MPa^2].
    check(TaoSetTolerances(tao, 1e-12, 0.0, 1e-6), "TaoSetTolerances");
    check(TaoSetMaximumIterations(tao, 50), "TaoSetMaximumIterations");
    check(TaoSetFromOptions(tao), "TaoSetFromOptions");
  }
  ~TaoFit()
  {
    petsc::check_nothrow(TaoDestroy(&tao), "TaoDestroy");
    for (Vec* v : {&X, &F, &lo, &hi})
      petsc::check_nothrow(VecDestroy(v), "VecDestroy");
    petsc::check_nothrow(MatDestroy(&J), "MatDestroy");
  }
  TaoFit(const TaoFit&) = delete;
  TaoFit& operator=(const TaoFit&) = delete;
};

/// What the fit found beyond its values: their standard errors and
/// correlations, the residual sum of squares, and what the user should know.
struct FitStatistics
{
  std::vector<double> se;                ///< standard errors, the keys' units
  std::vector<std::vector<double>> corr; ///< correlations (NaN: undetermined)
  std::vector<std::string> warnings;
  double rss = 0; ///< |r|^2 [MPa^2]
};

/// The statistics at the optimum x (scaled values) from the Jacobian J (m x
/// n, dense, of the scaled values) and the residuals r [MPa]: s^2 = |r|^2 /
/// (m - n), cov = s^2 (J^T J)^-1 in the keys' units (docs/fitting.md).
FitStatistics statistics(Mat J, const std::vector<double>& r, const std::vector<Free>& free,
                         const std::vector<double>& x)
{
  const std::size_t n = free.size(), m = r.size();
  FitStatistics st;
  std::vector<std::vector<double>> JtJ(n, std::vector<double>(n, 0.0));
  {
    const PetscScalar* a;
    check(MatDenseGetArrayRead(J, &a), "MatDenseGetArrayRead");
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t k = 0; k < n; ++k)
        for (std::size_t i = 0; i < m; ++i)
          JtJ[j][k] += a[j * m + i] / free[j].scale * a[k * m + i] / free[k].scale;
    check(MatDenseRestoreArrayRead(J, &a), "MatDenseRestoreArrayRead");
  }
  for (double v : r)
    st.rss += v * v;
  const double s2 = st.rss / double(m > n ? m - n : 1);
  std::vector<std::vector<double>> cov;
  st.se.assign(n, INFINITY);
  st.corr.assign(n, std::vector<double>(n, NAN));
  if (invert(JtJ, cov))
  {
    for (std::size_t j = 0; j < n; ++j)
      st.se[j] = std::sqrt(std::max(s2 * cov[j][j], 0.0));
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t k = 0; k < n; ++k)
        st.corr[j][k] = s2 * cov[j][k] / (st.se[j] * st.se[k]);
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t k = j + 1; k < n; ++k)
        if (std::abs(st.corr[j][k]) > identifiable_correlation)
          st.warnings.push_back(free[j].key + " and " + free[k].key + " are correlated (" +
                                number_text(std::round(st.corr[j][k] * 1000) / 1000) +
                                "): the data do not determine them separately");
  }
  else
    st.warnings.push_back("J^T J is singular at the optimum: some values do not change the curve");
  // A value the optimum pushes onto a bound is not a fit of it: the data
  // want it beyond (a different model, or data the model cannot make).
  for (std::size_t k = 0; k < n; ++k)
  {
    const double v = x[k] * free[k].scale, tol = 1e-6 * free[k].scale;
    for (const double bound : {free[k].lo, free[k].hi})
      if (std::isfinite(bound) && std::abs(v - bound) <= tol)
        st.warnings.push_back(free[k].key + " = " + number_text(v) +
                              " sits on its bound: the best fit would take it beyond, so the "
                              "model does not describe these data well there");
  }
  return st;
}

/// fit.json's part on the values: `parameters`, `standard_errors`,
/// `correlation`, `start`, `bounds`, `bounds_exclusive`.
nlohmann::json fitted_values(const std::vector<Free>& free, const std::vector<double>& x,
                             const FitStatistics& st)
{
  const auto number_or_null = [](double v)
  { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
  nlohmann::json params = nlohmann::json::object(), errors = nlohmann::json::object(),
                 starts = nlohmann::json::object(), bounds = nlohmann::json::object(),
                 exclusive = nlohmann::json::array(), correlation = nlohmann::json::array();
  std::vector<std::string> keys;
  for (std::size_t k = 0; k < free.size(); ++k)
  {
    keys.push_back(free[k].key);
    params[free[k].key] = x[k] * free[k].scale;
    errors[free[k].key] = number_or_null(st.se[k]);
    starts[free[k].key] = free[k].start;
    // [lo, hi], null where unbounded; lo itself excluded where the law says
    // so (bounds_exclusive).
    bounds[free[k].key] = {number_or_null(free[k].lo), number_or_null(free[k].hi)};
    if (free[k].lo_exclusive)
      exclusive.push_back(free[k].key);
    nlohmann::json row = nlohmann::json::array();
    for (double c : st.corr[k])
      row.push_back(number_or_null(c));
    correlation.push_back(row);
  }
  nlohmann::json j;
  j["parameters"] = params;
  j["standard_errors"] = errors;
  j["correlation"] = {{"keys", keys}, {"matrix", correlation}};
  j["start"] = starts;
  j["bounds"] = bounds;
  j["bounds_exclusive"] = exclusive;
  return j;
}
} // namespace

int fit(const FitOptions& opt)
{
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const bool talk = rank == 0 && !opt.quiet;
  const auto t0 = std::chrono::steady_clock::now();
  MeasuredCurve data;
  std::vector<Free> free;
  const int set_up = driver::exit_code_of(
      "pushout fit", "error",
      [&]
      {
        mpi::collectively<SceneError>(
            MPI_COMM_WORLD,
            [&]
            {
              ProcessGroups::check(opt.ranks_per_case);
              data = read_measured(opt.data);
              const Scene scene = Scene::load(opt.scene_file, parse_overrides(opt.sets));
              if (scene.string("model.type") != "pushout")
                throw SceneError("pushout fit fits push-out curves (model.type = \"pushout\")");
              if (!scene.numbers("loading.push_path").empty())
                throw SceneError(
                    "pushout fit runs a monotonic push: leave 'loading.push_path' empty");
              free = free_values(scene, opt);
              if (data.delta.size() <= free.size())
                throw SceneError("--data '" + opt.data.string() + "' has " +
                                 std::to_string(data.delta.size()) + " rows: more than the " +
                                 std::to_string(free.size()) + " free values are needed");
              // The start must be a valid scene with the push to the data's end.
              std::vector<std::string> sets = opt.sets;
              sets.push_back("loading.push_displacement=" + number_text(data.delta.back()));
              specimen::check_scene(Scene::load(opt.scene_file, parse_overrides(sets)));
            });
        // The folder is this fit's alone, without an earlier run's outputs
        // (output/OutputFiles.h); neither the scene nor the data may be
        // among them.
        mpi::collectively<output::FolderError>(
            MPI_COMM_WORLD,
            [&]
            {
              if (rank == 0)
                output::claim(opt.out, {opt.scene_file, opt.data});
            });
        return exit_code::done;
      });
  if (set_up != exit_code::done)
    return set_up;

  ProcessGroups groups(opt.ranks_per_case);
  Evaluator evaluator(opt, free, data, groups.comm(), groups.count(), groups.index());
  Problem problem{evaluator, free, talk, {}, {}, {}, {}, 0, t0};
  if (talk)
    std::cout << "pushout fit: " << free.size() << " values to " << data.delta.size()
              << " points of " << opt.data.string() << "; " << groups.count()
              << (groups.count() == 1 ? " group" : " groups") << " of " << opt.ranks_per_case
              << (opt.ranks_per_case == 1 ? " process" : " processes") << std::endl;

  // TAO on each process alike (PETSC_COMM_SELF), on the scaled values.
  const PetscInt m = PetscInt(data.delta.size());
  TaoFit solver(free, m, problem);
  Tao tao = solver.tao;
  Mat J = solver.J;
  std::vector<double> x;
  try
  {
    const interrupt::Phase phase("fit", interrupt::stop_grace_s);
    check(TaoSolve(tao), "TaoSolve");
    // At the optimum: residuals and the Jacobian (in the keys' units below).
    x = problem.values(solver.X);
    problem.evaluate(x, J);
  }
  catch (const Interrupted& e)
  {
    evaluator.release();
    groups.close();
    if (rank == 0)
      std::cerr << "pushout: " << e.what() << " after " << evaluator.evaluations()
                << " runs; no fit written" << std::endl;
    return exit_code::signal(e.signal);
  }
  TaoConvergedReason reason;
  check(TaoGetConvergedReason(tao, &reason), "TaoGetConvergedReason");

  const std::vector<double> r = problem.r_last;
  const FitStatistics stats = statistics(J, r, free, x);
  const std::vector<double>& se = stats.se;
  const double rss = stats.rss;

  // The fitted run, with its outputs, in DIR/best (group 0; rank 0 leads
  // it).
  if (groups.index() == 0)
    evaluator.run(x, opt.out / "best", true);
  const int best_exit_code = evaluator.last_exit_code();
  evaluator.release();
  groups.close();
  // A stopped fitted run leaves no best/ (it would hold a part of the
  // curve) and no fit.json.
  if (const int signal = evaluator.signal_anywhere(); signal != 0)
  {
    interrupt::acknowledge();
    if (rank == 0)
    {
      output::remove_outputs(opt.out / "best");
      std::cerr << "pushout: interrupted by " << interrupt::signal_name(signal)
                << " during the fitted run after " << evaluator.evaluations()
                << " runs; no fit written" << std::endl;
    }
    return exit_code::signal(signal);
  }
  const bool converged = reason > 0 && evaluator.failed() == 0 && best_exit_code == exit_code::done;
  // Why a run failed, from any process (the failure may have been another
  // group's).
  const std::string failure = first_message(evaluator.last_failure(), MPI_COMM_WORLD);
  int code = converged ? exit_code::done : exit_code::not_converged;
  if (rank == 0)
  {
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    nlohmann::json j = fitted_values(free, x, stats);
    j["rms_MPa"] = std::sqrt(rss / double(m));
    j["points"] = m;
    j["evaluations"] = evaluator.evaluations();
    j["failed_runs"] = evaluator.failed();
    j["iterations"] = problem.iterations;
    j["converged"] = converged;
    j["reason"] = TaoConvergedReasons[reason];
    j["warnings"] = stats.warnings;
    j["data"] = opt.data.string();
    j["wall_s"] = wall;
    try
    {
      output::write_file(opt.out / "fit.json", j.dump(2) + "\n");
      // The fitted scene, rerunnable.
      std::vector<std::string> sets = evaluator.sets_at(x);
      output::write_file(opt.out / "scene.toml",
                         Scene::load(opt.scene_file, parse_overrides(sets)).to_toml());
      std::ostringstream csv;
      csv << "delta_mm,tau_data_MPa,tau_model_MPa\n" << std::setprecision(12);
      for (std::size_t i = 0; i < std::size_t(m); ++i)
        csv << data.delta[i] << "," << data.tau[i] << "," << data.tau[i] + r[i] << "\n";
      output::write_file(opt.out / "fit.csv", csv.str());
    }
    catch (const std::exception& e)
    {
      std::cerr << "pushout: error: " << e.what() << std::endl;
      code = exit_code::failure;
    }
    std::string why;
    if (!output::plot_fit(opt.out, opt.out / "fit.png", why))
      std::cerr << "pushout: warning: no fit.png: " << why << std::endl;
    for (const std::string& w : stats.warnings)
      std::cerr << "pushout: warning: " << w << std::endl;
    if (!converged)
      std::cerr << "pushout: error: the fit did not converge (" << TaoConvergedReasons[reason]
                << (evaluator.failed() ? "; " + std::to_string(evaluator.failed()) +
                                             " runs did not converge: " + failure
                                       : std::string())
                << "); " << (opt.out / "fit.json").string() << " has where it stopped" << std::endl;
    if (talk)
    {
      std::cout << "pushout fit: rms " << std::setprecision(6) << std::sqrt(rss / double(m))
                << " MPa after " << evaluator.evaluations() << " runs, " << std::fixed
                << std::setprecision(1) << wall << " s:" << std::defaultfloat << std::endl;
      for (std::size_t k = 0; k < free.size(); ++k)
        std::cout << "  " << free[k].key << " = " << std::setprecision(6) << x[k] * free[k].scale
                  << " +- " << se[k] << std::endl;
      std::cout << "results: " << (opt.out / "fit.json").string() << ", fitted scene "
                << (opt.out / "scene.toml").string() << std::endl;
    }
  }
  MPI_Bcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return code;
}
} // namespace pushout::study

// IMPL-EX cracks (BulkCracking.h, docs/cracking.md "IMPL-EX"): a step's
// secant maps from the committed state and the last step's growth, the
// step's evaluations by them, and after the step the crack band's own
// update and the step's error against it; and the implicit cracks' step
// error, against the same prediction (docs/cracking.md, "The implicit
// cracks' step error").
#include "BulkCrackingPoints.h"
#include <cmath>
#include <mpi.h>

namespace pushout::model
{
using namespace points;

void BulkCracking::make_secants()
{
  std::vector<double> scratch(state);
  const std::size_t n_points = std::size_t(expression_cracking_strain->num_points);
  for (std::size_t i = 0; i < _secant.size(); ++i)
    predict_secant(i / n_points, i, scratch, _secant[i]);
  _secant_current = true;
}

void BulkCracking::predict_secant(std::size_t c, std::size_t i, std::vector<double>& scratch,
                                  bulk::SecantOperator& op) const
{
  // The strain predictor: the point's state is the crack band's own update
  // from the committed state to the strain extrapolated from the last
  // step, as the history predictor extrapolates the history: a point may
  // crack there, and a crack that stops growing holds its history.
  const std::span<const double> old(_committed.data() + state * i, state);
  if (_predict_strain && _extrapolation > 0 && !_strain_step.empty())
  {
    bulk::Voigt strain;
    for (int k = 0; k < voigt; ++k)
      strain[k] = _strain_committed[voigt * i + k] + _extrapolation * _strain_step[voigt * i + k];
    const bulk::CrackBandResult r = update_point(c, i, strain, scratch, bulk::Tangent::skip);
    // Uncracked there, or its update failed: the history predictor's map.
    if (r.status == bulk::CrackBandResult::Status::ok && crack_of(scratch, 0).cracked())
    {
      _band.secant_operator(scratch, kappa_of(scratch, 0), _strength[i], op);
      return;
    }
  }
  _band.secant_operator(old, kappa_of(_committed, i) + _extrapolation * _kappa_step[i],
                        _strength[i], op);
}

namespace
{
/// How many points ahead apply_sides() asks for a point's secant maps.
constexpr std::size_t prefetch_ahead = 8;

/// The map of `op` that answers `strain`: its open or closed side's, or
/// none, C (uncracked, or the map failed); `side` secant_side()'s.
const bulk::Voigt66* secant_map(const bulk::SecantOperator& op, int side)
{
  return side == bulk::CrackBand::secant_open || side == bulk::CrackBand::secant_closed
             ? &op.tangent[side]
             : nullptr;
}
} // namespace

bool BulkCracking::apply_sides(bool& tangent_changed)
{
  // The step's maps, made at its first evaluation: each point's tangent
  // (d_C) is written then, and afterwards only where its crack opens or
  // closes.
  const bool new_secants = !_secant_current;
  if (new_secants)
    make_secants();
  tangent_changed = new_secants;
  const bulk::Voigt66& C = _band.stiffness();
  bool ok = true;
  for_each_point(
      [&](std::size_t c, std::size_t i, const bulk::Voigt& strain, std::span<double>, auto d_C_at)
      {
        // What picks the side, a few points ahead: the points' maps lie
        // sizeof(SecantOperator), 704 bytes, apart, too far for the
        // processor to fetch them ahead by itself, and this loop does
        // little else (a builtin of GCC and Clang).
        if (i + prefetch_ahead < _secant.size())
          __builtin_prefetch(&_secant[i + prefetch_ahead]);
        const bulk::SecantOperator& op = _secant[i];
        const int side = bulk::CrackBand::secant_side(op, strain);
        ok = ok && side != bulk::CrackBand::secant_failed;
        // The side of closure as _closed keeps it (a failed map answers C,
        // and so does an uncracked point, on the open side).
        const std::uint8_t closed = side == bulk::CrackBand::secant_elastic ? 0 : side;
        const bool write_tangent = new_secants || closed != _closed[i];
        if (closed != _closed[i])
        {
          _closed[i] = closed;
          tangent_changed = true;
        }
        if (write_tangent)
        {
          // A step's new maps are mostly last step's (a crack that unloads
          // keeps its history): the cell is marked where a value changed.
          const bulk::Voigt66* T = secant_map(op, side);
          const std::span<double> d_C = d_C_at();
          bool changed = false;
          for (int k = 0; k < voigt_sq; ++k)
          {
            const double value = T ? (*T)[k] - C[k] : 0.0;
            changed = changed || d_C[k] != value;
            d_C[k] = value;
          }
          if (changed)
            _tangent_written[c] = 1;
        }
      });
  return ok;
}

void BulkCracking::apply_stresses()
{
  const bulk::Voigt66& C = _band.stiffness();
  for_each_point(
      [&](std::size_t, std::size_t i, const bulk::Voigt& strain, std::span<double> d_sigma, auto)
      {
        const bulk::SecantOperator& op = _secant[i];
        const bulk::Voigt66* T = secant_map(op, bulk::CrackBand::secant_side(op, strain));
        double* stress = _stress_trial.data() + voigt * i;
        const bulk::Voigt elastic = bulk::multiply(C, strain);
        if (T)
        {
          const bulk::Voigt s = bulk::multiply(*T, strain);
          for (int k = 0; k < voigt; ++k)
          {
            stress[k] = s[k];
            d_sigma[k] = s[k] - elastic[k];
          }
        }
        else
        {
          std::copy(elastic.begin(), elastic.end(), stress);
          std::fill(d_sigma.begin(), d_sigma.end(), 0.0);
        }
      });
}

void BulkCracking::implicit_update()
{
  if (_trial_implicit) // since the last evaluate(): the same displacement
    return;
  // The strains of the last evaluation where it stands (the converged
  // iterate's residual made it), else made again.
  if (!evaluated_here())
    evaluate_strains();
  _trial_implicit = true;
  ++_trial_version;
  _implicit_failures = 0;
  const int n_points = expression_cracking_strain->num_points;
  for (std::size_t c = 0; c < _cells.size(); ++c)
    for (int q = 0; q < n_points; ++q)
    {
      const std::size_t i = c * std::size_t(n_points) + q;
      // The state, stress and dissipation; the step's tangent is its maps'.
      const bulk::CrackBandResult r =
          update_point(c, i, voigt_at(_strain_values, i),
                       std::span<double>(_trial.data() + state * i, state), bulk::Tangent::skip);
      // A point whose crack's equilibrium fails keeps its committed state,
      // stress, opening and dissipation (none of the last evaluation's),
      // counted: implex_error() says so, and the step is cut.
      if (r.status != bulk::CrackBandResult::Status::ok)
      {
        std::copy_n(_committed.begin() + state * i, state, _trial.begin() + state * i);
        std::copy_n(_stress_committed.begin() + voigt * i, voigt,
                    _stress_trial.begin() + voigt * i);
        std::copy_n(_opening.begin() + 3 * i, 3, _opening_trial.begin() + 3 * i);
        _dissipated_step[i] = 0;
        _dissipated_trial[i] = _dissipated[i];
        ++_implicit_failures;
        continue;
      }
      _dissipated_step[i] = r.dissipation;
      _dissipated_trial[i] = _dissipated[i] + r.dissipation;
      std::copy(r.stress.begin(), r.stress.end(), _stress_trial.begin() + voigt * i);
      std::copy(r.opening.begin(), r.opening.end(), _opening_trial.begin() + 3 * i);
    }
}

double BulkCracking::error_against_trial(const std::function<bulk::Voigt(std::size_t)>& other)
{
  double sums[2] = {
      integrate(
          [&](std::size_t i)
          {
            bulk::Voigt d = voigt_at(_stress_trial, i);
            const bulk::Voigt e = other(i);
            for (int k = 0; k < voigt; ++k)
              d[k] -= e[k];
            return bulk::complementary_energy(d, _E, _nu);
          }),
      integrate([&](std::size_t i)
                { return bulk::complementary_energy(voigt_at(_stress_trial, i), _E, _nu); })};
  MPI_Allreduce(MPI_IN_PLACE, sums, 2, MPI_DOUBLE, MPI_SUM, _mesh->comm());
  return sums[1] > 0 ? std::sqrt(sums[0] / sums[1]) : 0.0;
}

double BulkCracking::implicit_error()
{
  // The step's own stress (the crack band's update at the converged strain)
  // against what the step's IMPL-EX maps would answer there.
  evaluate();
  const bulk::Voigt66& C = _band.stiffness();
  std::vector<double> scratch(state);
  bulk::SecantOperator op;
  const std::size_t n_points = std::size_t(expression_cracking_strain->num_points);
  return error_against_trial(
      [&](std::size_t i)
      {
        predict_secant(i / n_points, i, scratch, op);
        const bulk::Voigt strain = voigt_at(_strain_values, i);
        const bulk::Voigt66* T = secant_map(op, bulk::CrackBand::secant_side(op, strain));
        return bulk::multiply(T ? *T : C, strain);
      });
}

double BulkCracking::implex_error(std::int64_t& failed_points)
{
  // The stress the step converged with, before the update replaces it (its
  // last evaluation may have been evaluate_tangent()'s).
  evaluate();
  const std::vector<double> stepped = _stress_trial;
  implicit_update();
  const double error = error_against_trial([&](std::size_t i) { return voigt_at(stepped, i); });
  MPI_Allreduce(&_implicit_failures, &failed_points, 1, MPI_INT64_T, MPI_SUM, _mesh->comm());
  return error;
}
} // namespace pushout::model

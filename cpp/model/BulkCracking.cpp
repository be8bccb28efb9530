#include "BulkCracking.h"
#include "../bulk/StrengthField.h"
#include "../common/BlockAdd.h"
#include "../scene/SceneError.h"
#include "BulkCrackingPoints.h"
#include "CrackBandCheck.h"
#include "CrackingCells.h"
#include "cracking.h"
#include <algorithm>
#include <cmath>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/fem/utils.h>
#include <dolfinx/la/petsc.h>
#include <functional>
#include <sstream>
#include <stdexcept>

namespace pushout::model
{
using namespace points;
namespace
{
namespace fem = dolfinx::fem;
constexpr int region_tag = 1; ///< REGION of forms/cracking.py
/// The relative size of the step beyond the committed strain at which a
/// crack's loading tangent is taken where the strain has not moved
/// (BulkCracking::loading_tangent; as interface::Interface::loading_probe).
constexpr double probe = 1e-9;

/// A function on the Quadrature space that `form`'s coefficient `name`
/// lives on (forms/cracking.py).
std::shared_ptr<fem::Function<double>>
quadrature_function(ufcx_function_space* (*form)(const char*), const char* name,
                    std::shared_ptr<dolfinx::mesh::Mesh> mesh)
{
  return std::make_shared<fem::Function<double>>(
      std::make_shared<fem::FunctionSpace>(fem::create_functionspace(form, name, mesh)));
}

/// A row-major 2D view for Expression::eval.
struct Rows
{
  double* data;
  std::size_t columns;
  double& operator()(std::size_t row, std::size_t column) { return data[row * columns + column]; }
};

} // namespace

BulkCracking::BulkCracking(std::shared_ptr<dolfinx::mesh::Mesh> mesh,
                           std::shared_ptr<const fem::FunctionSpace> V,
                           std::shared_ptr<const fem::Function<double>> u,
                           std::shared_ptr<const fem::Function<double>> alpha,
                           const std::vector<std::int32_t>& material, const Material& concrete,
                           const CrackingPart& part, const Geometry& slice, int copies)
    : _mesh(mesh), _u(u), _band(concrete.E, concrete.nu, envelope_of(part), part.viscosity),
      _cells(cracking_cells(*mesh, material, part.radius, slice.tube_center)),
      _axis(slice.tube_center), _tube_radius(slice.tube_radius()),
      _visible_width(part.visible_width), _copies(copies), _row_band(part.row_band),
      _implex(part.implex), _implex_tolerance(part.implex_tolerance),
      _implicit_tolerance(part.implicit_tolerance),
      _step_error_unheld(part.implicit_step_error_read() && !part.implicit_steps_held()),
      _predict_strain(part.predict_strain), _rescue_allowed(part.implex_rescue), _E(concrete.E),
      _nu(concrete.nu), _alpha(concrete.alpha), _dT(std::make_shared<fem::Constant<double>>(0.0))
{
  // A radius that takes in no concrete would leave it linear without a
  // word: refused, the same on every process (the count is summed, the
  // nearest centre the least of the processes').
  std::int64_t n_cells = std::int64_t(_cells.size());
  MPI_Allreduce(MPI_IN_PLACE, &n_cells, 1, MPI_INT64_T, MPI_SUM, mesh->comm());
  if (n_cells == 0)
  {
    double nearest = nearest_concrete_centre(*mesh, material, slice.tube_center); // [mm]
    MPI_Allreduce(MPI_IN_PLACE, &nearest, 1, MPI_DOUBLE, MPI_MIN, mesh->comm());
    throw SceneError(takes_no_concrete(part.radius, nearest));
  }
  // A radius that takes in all the concrete leaves no edge: as radius 0
  // (the count agreed, so every process says the same).
  if (part.radius > 0)
    _edge = region_edge(*mesh, material, _cells);
  std::int64_t n_edge = std::int64_t(_edge.size());
  MPI_Allreduce(MPI_IN_PLACE, &n_edge, 1, MPI_INT64_T, MPI_SUM, mesh->comm());
  _radius = n_edge > 0 ? part.radius : 0.0;
  _d_sigma = quadrature_function(functionspace_form_cracking_L_crack, "d_sigma", mesh);
  _d_C = quadrature_function(functionspace_form_cracking_a_crack, "d_C", mesh);
  _d_C_change = quadrature_function(functionspace_form_cracking_a_crack, "d_C", mesh);
  _release_gradient = quadrature_function(functionspace_form_cracking_L_crack, "d_sigma", mesh);
  _point_value = quadrature_function(functionspace_form_cracking_M_points, "point_value", mesh);
  _stress_share = quadrature_function(functionspace_form_cracking_L_crack, "d_sigma", mesh);
  _region = std::make_shared<dolfinx::mesh::MeshTags<std::int32_t>>(
      mesh, 3, std::vector<std::int32_t>(_cells),
      std::vector<std::int32_t>(_cells.size(), region_tag));
  const std::map<fem::IntegralType, const dolfinx::mesh::MeshTags<int>*> subdomains = {
      {fem::IntegralType::cell, _region.get()}};
  _L = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      *form_cracking_L_crack, {V}, {{"d_sigma", _d_sigma}}, {}, subdomains));
  _a = std::make_shared<fem::Form<double>>(
      fem::create_form<double>(*form_cracking_a_crack, {V, V}, {{"d_C", _d_C}}, {}, subdomains));
  _L_release = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      *form_cracking_L_crack, {V}, {{"d_sigma", _release_gradient}}, {}, subdomains));
  _M = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      *form_cracking_M_points, {}, {{"point_value", _point_value}}, {}, subdomains, mesh));
  _strain = std::make_unique<fem::Expression<double>>(fem::create_expression<double>(
      *expression_cracking_strain, {{"u_h", u}, {"alpha", alpha}}, {{"dT", _dT}}, mesh));

  // The strength at each point, from the field at its position.
  const int n_points = expression_cracking_position->num_points;
  std::vector<double> positions(_cells.size() * n_points * 3);
  {
    const fem::Expression<double> position = fem::create_expression<double>(
        *expression_cracking_position,
        std::map<std::string, std::shared_ptr<const fem::Function<double>>>{},
        std::map<std::string, std::shared_ptr<const fem::Constant<double>>>{}, mesh);
    Rows rows{positions.data(), std::size_t(n_points) * 3};
    position.eval(std::span<const std::int32_t>(_cells), rows);
  }
  const bulk::StrengthField field(part.strength_cov, part.correlation_length,
                                  std::uint64_t(part.seed));
  _strength.resize(_cells.size() * n_points);
  for (std::size_t i = 0; i < _strength.size(); ++i)
    _strength[i] = field.factor({positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]});
  _committed.assign(_strength.size() * state, 0.0);
  _trial = _committed;
  _dissipated.assign(_strength.size(), 0.0);
  _dissipated_trial = _dissipated;
  _dissipated_step = _dissipated;
  _opening.assign(_strength.size() * 3, 0.0);
  _opening_trial = _opening;
  _strain_values.resize(_strength.size() * voigt);
  _loading.assign(_strength.size(), false);
  _kappa_step.assign(_strength.size(), 0.0);
  _closed.assign(_strength.size(), 0);
  _tangent_written.assign(_cells.size(), 1);
  if (_implex)
    _secant.resize(_strength.size());
  _stress_trial.assign(_strength.size() * voigt, 0.0);
  _stress_committed = _stress_trial;
  _strain_committed = _stress_trial;
  place_cells(slice, positions);
  double cover = slice.nearest_face_distance() - _tube_radius;
  if (part.radius > 0)
    cover = std::min(cover, part.radius - _tube_radius);
  _nominal_fracture_energy = _band.envelope().softening_energy() * slice.thickness * cover;

  // The crack band's size condition on this process's cells, agreed by all.
  BandSizeCheck check(_band, part);
  for (std::size_t c = 0; c < _cells.size(); ++c)
  {
    const double diagonal =
        std::hypot(extent(c, {1, 0, 0}), extent(c, {0, 1, 0}), extent(c, {0, 0, 1}));
    for (int q = 0; q < n_points; ++q)
      check.add(diagonal, {_places[c].x, _places[c].y}, _strength[c * n_points + q]);
  }
  check.agree(_mesh->comm());
  check.refuse_if_too_wide(_axis);
}

CellVertices BulkCracking::vertices(std::size_t cell) const
{
  const auto nodes = _mesh->geometry().dofmap().links(_cells[cell]);
  const std::span<const double> x = _mesh->geometry().x();
  CellVertices vertices;
  for (std::size_t v = 0; v < vertices.size(); ++v)
    for (std::size_t a = 0; a < 3; ++a)
      vertices[v][a] = x[3 * std::size_t(nodes[v]) + a];
  return vertices;
}

double BulkCracking::extent(std::size_t cell, const bulk::Vec3& n) const
{
  return projected_width(vertices(cell), n);
}

double BulkCracking::crack_band_width(std::size_t cell, const bulk::Vec3& n) const
{
  return _row_band ? row_width(vertices(cell), n) : extent(cell, n);
}

bulk::CrackBandResult BulkCracking::update_point(std::size_t c, std::size_t i,
                                                 const bulk::Voigt& strain, std::span<double> now,
                                                 bulk::Tangent tangent) const
{
  return _band.update(
      std::span<const double>(_committed.data() + state * i, state), strain, now,
      [&](const bulk::Vec3& n) { return crack_band_width(c, n); }, _strength[i], _dt, tangent);
}

void BulkCracking::set_implex_rescue(bool on)
{
  if (on == _rescue)
    return;
  if (on && !may_rescue())
    throw std::logic_error("BulkCracking::set_implex_rescue: only the implicit cracks without a "
                           "viscosity are rescued by an IMPL-EX step, with "
                           "cracking.implex_rescue");
  _rescue = _implex = on;
  if (on)
    _secant.resize(_strength.size());
  else // for the rescue's steps only
    std::vector<bulk::SecantOperator>().swap(_secant);
  history_changed();
  ++_tangent_version; // the tangent's kind changes
  _trial_implicit = false;
}

void BulkCracking::commit()
{
  history_changed();
  // What the step's cracks did at its converged strain: IMPL-EX's crack
  // band's own update (onset, the history), and the growth of the history
  // that the next step extrapolates (IMPL-EX's, the implicit cracks'
  // predictor for their step's error, and an IMPL-EX step that stands in
  // for one of theirs: set_implex_rescue).
  if (_implex)
    implicit_update();
  for (std::size_t i = 0; i < _kappa_step.size(); ++i)
    _kappa_step[i] = kappa_of(_trial, i) - kappa_of(_committed, i);
  if (_predict_strain)
  {
    _strain_step.resize(_strain_values.size());
    for (std::size_t j = 0; j < _strain_values.size(); ++j)
      _strain_step[j] = _strain_values[j] - _strain_committed[j];
  }
  for (std::size_t i = 0; i < _loading.size(); ++i)
    _loading[i] = kappa_of(_trial, i) > kappa_of(_committed, i);
  _trial_implicit = false;
  ++_trial_version;
  _committed = _trial;
  _stress_committed = _stress_trial;
  _strain_committed = _strain_values;
  _dissipated = _dissipated_trial;
  _opening = _opening_trial;
}

void BulkCracking::revert()
{
  _trial_implicit = false;
  ++_trial_version;
  _trial = _committed;
  _dissipated_trial = _dissipated;
  _opening_trial = _opening;
}

void BulkCracking::reset()
{
  set_implex_rescue(false); // one a stopped run left on
  std::fill(_committed.begin(), _committed.end(), 0.0);
  std::fill(_dissipated.begin(), _dissipated.end(), 0.0);
  std::fill(_opening.begin(), _opening.end(), 0.0);
  std::fill(_loading.begin(), _loading.end(), false);
  std::fill(_kappa_step.begin(), _kappa_step.end(), 0.0);
  _strain_step.clear();
  history_changed();
  std::fill(_stress_committed.begin(), _stress_committed.end(), 0.0);
  std::fill(_strain_committed.begin(), _strain_committed.end(), 0.0);
  revert();
}

void BulkCracking::set_temperature_change(double dT, TemperatureKey)
{
  _dT->value = {dT};
  ++_trial_version;
}

void BulkCracking::evaluate_strains()
{
  Rows rows{_strain_values.data(), std::size_t(expression_cracking_strain->num_points) * voigt};
  _strain->eval(std::span<const std::int32_t>(_cells), rows);
}

bool BulkCracking::evaluated_here() const
{
  const std::span<const double> u = _u->x()->array();
  return _evaluated.valid && _evaluated.trial_version == _trial_version &&
         std::equal(u.begin(), u.end(), _evaluated.u.begin(), _evaluated.u.end());
}

bool BulkCracking::evaluate_points(bool stresses)
{
  // The last evaluation stands where nothing it read has changed since: the
  // displacement, bit for bit, and the state and settings (trial_version).
  // The Jacobian at the residual's iterate asks for it again.
  if (evaluated_here())
  {
    if (stresses && !_evaluated.stresses)
    {
      apply_stresses(); // the same evaluation, completed
      _evaluated.stresses = true;
    }
    return _evaluated.ok;
  }
  const std::span<const double> u = _u->x()->array();
  _trial_implicit = false;
  evaluate_strains();
  bool tangent_changed = true;
  bool ok = true;
  if (_implex)
  {
    ok = apply_sides(tangent_changed);
    if (stresses)
      apply_stresses();
  }
  else
  {
    ok = update_points();
    stresses = true;
  }
  if (tangent_changed)
    ++_tangent_version;
  _evaluated = {true, ++_trial_version, {u.begin(), u.end()}, ok, stresses};
  return ok;
}

bool BulkCracking::update_points()
{
  const bulk::Voigt66& C = _band.stiffness();
  bool ok = true;
  for_each_point(
      [&](std::size_t c, std::size_t i, const bulk::Voigt& strain, std::span<double> d_sigma,
          auto d_C_at)
      {
        const std::span<const double> old(_committed.data() + state * i, state);
        const std::span<double> now(_trial.data() + state * i, state);
        // Initialised in place (not assigned): the result is 50 numbers, and
        // zeroing and copying a second one cost a tenth of the loop.
        bulk::CrackBandResult r = _new_cracks || bulk::CrackState<const double>(old).cracked()
                                      ? update_point(c, i, strain, now)
                                      : _band.held_uncracked(old, strain, now);
        if (_loading[i] && at_committed_strain(i, strain))
          loading_tangent(c, i, strain, r.tangent);
        ok = ok && r.status == bulk::CrackBandResult::Status::ok;
        std::copy(r.stress.begin(), r.stress.end(), _stress_trial.begin() + voigt * i);
        _dissipated_step[i] = r.dissipation;
        _dissipated_trial[i] = _dissipated[i] + r.dissipation;
        std::copy(r.opening.begin(), r.opening.end(), _opening_trial.begin() + 3 * i);
        const bulk::Voigt elastic = bulk::multiply(C, strain);
        for (int k = 0; k < voigt; ++k)
          d_sigma[k] = r.stress[k] - elastic[k];
        const std::span<double> d_C = d_C_at();
        for (int k = 0; k < voigt_sq; ++k)
          d_C[k] = r.tangent[k] - C[k];
      });
  std::fill(_tangent_written.begin(), _tangent_written.end(), 1);
  return ok;
}

bool BulkCracking::at_committed_strain(std::size_t i, const bulk::Voigt& strain) const
{
  const double* eps0 = _strain_committed.data() + voigt * i;
  double change = 0, size = 0;
  for (int k = 0; k < voigt; ++k)
  {
    change = std::max(change, std::abs(strain[k] - eps0[k]));
    size = std::max(size, std::abs(eps0[k]));
  }
  return change <= probe * size;
}

void BulkCracking::loading_tangent(std::size_t c, std::size_t i, const bulk::Voigt& strain,
                                   bulk::Voigt66& tangent) const
{
  bulk::Voigt probed;
  for (int k = 0; k < voigt; ++k)
    probed[k] = strain[k] * (1 + probe);
  std::array<double, state> scratch;
  const bulk::CrackBandResult r = update_point(c, i, probed, scratch);
  if (r.status == bulk::CrackBandResult::Status::ok) // else its tangent is not one
    tangent = r.tangent;
}

bool BulkCracking::energy_release(std::span<double> gradient, double& G)
{
  const bool ok = evaluate();
  const int n_points = expression_cracking_strain->num_points;
  const bulk::Voigt66& C = _band.stiffness();
  std::vector<double> release(_strength.size());
  const PointValues d_C_at(*_d_C, voigt_sq), gradient_at(*_release_gradient, voigt);
  for (std::size_t c = 0; c < _cells.size(); ++c)
    for (int q = 0; q < n_points; ++q)
    {
      const std::size_t i = c * std::size_t(n_points) + q;
      const double* eps = _strain_values.data() + voigt * i;
      const double* eps0 = _strain_committed.data() + voigt * i;
      const double* sigma = _stress_trial.data() + voigt * i;
      const double* sigma0 = _stress_committed.data() + voigt * i;
      release[i] = 0;
      for (int k = 0; k < voigt; ++k)
        release[i] += 0.5 * (sigma0[k] * eps[k] - sigma[k] * eps0[k]);
      const std::span<const double> d_C = d_C_at(_cells[c], q);
      // dG/d eps_e = 1/2 (sigma_0 - C_t^T eps_e0)
      const std::span<double> g = gradient_at(_cells[c], q);
      for (int k = 0; k < voigt; ++k)
      {
        g[k] = 0.5 * sigma0[k];
        for (int j = 0; j < voigt; ++j)
          g[k] -= 0.5 * (C[voigt * j + k] + d_C[voigt * j + k]) * eps0[j];
      }
    }
  G = integrate([&](std::size_t i) { return release[i]; });
  fem::assemble_vector(gradient, *_L_release);
  return ok;
}

double BulkCracking::dissipation()
{
  return integrate([&](std::size_t i) { return _dissipated_step[i]; });
}

double BulkCracking::integrate(const std::function<double(std::size_t)>& value_at_point)
{
  const int n_points = expression_cracking_strain->num_points;
  const PointValues value_at(*_point_value, 1);
  for (std::size_t c = 0; c < _cells.size(); ++c)
    for (int q = 0; q < n_points; ++q)
      value_at(_cells[c], q)[0] = value_at_point(c * std::size_t(n_points) + q);
  return fem::assemble_scalar(*_M);
}

void BulkCracking::add_forces(std::span<double> f) const
{
  if (_evaluated.valid && !_evaluated.stresses)
    throw std::logic_error("BulkCracking::add_forces after evaluate_tangent(): evaluate() first");
  fem::assemble_vector(f, *_L);
}

void BulkCracking::add_tangent(Mat A) const
{
  petsc::BlockAdd add(A);
  fem::assemble_matrix(std::ref(add), *_a, {});
}

void BulkCracking::add_elastic_rule(Mat K) const
{
  // Once per model: the form made here, on a_crack's spaces and cells.
  const std::map<fem::IntegralType, const dolfinx::mesh::MeshTags<int>*> subdomains = {
      {fem::IntegralType::cell, _region.get()}};
  const fem::Form<double> a_rule = fem::create_form<double>(
      *form_cracking_a_rule, _a->function_spaces(),
      std::map<std::string, std::shared_ptr<const fem::Function<double>>>{},
      {{"E_c", std::make_shared<fem::Constant<double>>(_E)},
       {"nu_c", std::make_shared<fem::Constant<double>>(_nu)}},
      subdomains);
  petsc::BlockAdd add(K);
  fem::assemble_matrix(std::ref(add), a_rule, {});
}

void BulkCracking::add_tangent_change(Mat A, std::vector<double>& assembled)
{
  const std::span<const double> now = _d_C->x()->array();
  if (assembled.empty())
  {
    add_tangent(A);
    assembled.assign(now.begin(), now.end());
    std::fill(_tangent_written.begin(), _tangent_written.end(), 0);
    _tangent_written_for = &assembled;
    return;
  }
  // Another sum than the last call's: its values may differ anywhere.
  if (&assembled != _tangent_written_for)
    std::fill(_tangent_written.begin(), _tangent_written.end(), 1);
  _tangent_written_for = &assembled;
  // The cells with a point whose tangent changed, and the change there:
  // among those whose tangent an evaluation wrote since the last call.
  const int n_points = expression_cracking_strain->num_points;
  std::vector<std::int32_t> changed;
  const PointValues d_C_at(*_d_C, voigt_sq), change_at(*_d_C_change, voigt_sq);
  for (std::size_t c = 0; c < _cells.size(); ++c)
  {
    if (!_tangent_written[c])
      continue;
    _tangent_written[c] = 0;
    const std::int32_t cell = _cells[c];
    bool differs = false;
    for (int q = 0; q < n_points; ++q)
    {
      const std::span<const double> point = d_C_at(cell, q);
      const std::size_t first = std::size_t(point.data() - now.data()); // in d_C's array
      const std::span<double> change = change_at(cell, q);
      for (int k = 0; k < voigt_sq; ++k)
      {
        change[k] = point[k] - assembled[first + k];
        differs = differs || change[k] != 0.0;
        assembled[first + k] = point[k];
      }
    }
    if (differs)
      changed.push_back(cell);
  }
  if (changed.empty())
    return;
  // The tangent's form on those cells (_cells is sorted, so is `changed`).
  std::vector<std::int32_t> tag_values(changed.size(), region_tag);
  const dolfinx::mesh::MeshTags<std::int32_t> tags(_mesh, 3, std::move(changed),
                                                   std::move(tag_values));
  const fem::Form<double> form =
      fem::create_form<double>(*form_cracking_a_crack, _a->function_spaces(),
                               {{"d_C", _d_C_change}}, {}, {{fem::IntegralType::cell, &tags}});
  petsc::BlockAdd add(A);
  fem::assemble_matrix(std::ref(add), form, {});
}
} // namespace pushout::model

#include "StressProjection.h"
#include "elasticity.h"
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/utils.h>

namespace pushout::output
{
using dolfinx::fem::Function;

StressProjection::StressProjection(const model::Model& model) : _cracking(model.bulk_cracking())
{
  namespace fem = dolfinx::fem;
  auto S = std::make_shared<fem::FunctionSpace>(
      fem::create_functionspace(functionspace_form_elasticity_L_stress, "tau", model.mesh()));
  const model::Materials& m = model.materials();
  auto Q = m.E->function_space();
  const std::map<std::string, std::shared_ptr<const Function<double>>> coeffs = {
      {"E", m.E},
      {"nu", m.nu},
      {"alpha", m.alpha},
      {model.degree() == 2 ? "u_h2" : "u_h", model.displacement_ptr()}};
  _L_stress = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      model.degree() == 2 ? *form_elasticity_L_stress_q2 : *form_elasticity_L_stress, {S}, coeffs,
      {{"dT", m.dT}}, {}));
  _sigma = std::make_shared<Function<double>>(S);
  _sigma->name = "stress";

  // Cell volumes, once: DG0 on both spaces, one dof (block) per cell.
  const auto L_volume = fem::create_form<double>(
      *form_elasticity_L_volume, {Q},
      std::map<std::string, std::shared_ptr<const Function<double>>>{},
      std::map<std::string, std::shared_ptr<const fem::Constant<double>>>{}, {});
  std::vector<double> volume(
      Q->dofmap()->index_map->size_local() + Q->dofmap()->index_map->num_ghosts(), 0.0);
  fem::assemble_vector(std::span<double>(volume), L_volume);
  const std::int32_t n_cells = model.mesh()->topology().index_map(3)->size_local();
  for (std::int32_t c = 0; c < n_cells; ++c)
    _inverse_volume.emplace_back(S->dofmap()->cell_dofs(c)[0],
                                 1.0 / volume[Q->dofmap()->cell_dofs(c)[0]]);
}

const Function<double>& StressProjection::update()
{
  std::span<double> s = _sigma->x()->mutable_array();
  std::fill(s.begin(), s.end(), 0.0);
  dolfinx::fem::assemble_vector(s, *_L_stress);
  if (_cracking) // cracked concrete: the crack band's stress, not the elastic one
    _cracking->add_stress_share(s, _sigma->function_space());
  for (const auto& [block, inv] : _inverse_volume)
    for (int i = 0; i < 9; ++i)
      s[9 * block + i] *= inv;
  _sigma->x()->scatter_fwd();
  return *_sigma;
}
} // namespace pushout::output

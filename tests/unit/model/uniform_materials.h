// A concrete of uniform E, nu and alpha over a mesh, as forms/elasticity.py
// takes them (DG0 coefficients "E", "nu", "alpha"), for the model's unit
// tests that build their forms on a box instead of a push-out's Model.
#pragma once

#include "elasticity.h"
#include <algorithm>
#include <dolfinx/fem/Function.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/fem/utils.h>
#include <dolfinx/mesh/Mesh.h>
#include <map>
#include <memory>
#include <string>

namespace pushout::unit
{
/// E [MPa], nu [-] and alpha [1/degC] on every cell of `mesh`, by
/// forms/elasticity.py's coefficient names.
inline std::map<std::string, std::shared_ptr<const dolfinx::fem::Function<double>>>
uniform_materials(std::shared_ptr<dolfinx::mesh::Mesh> mesh, double E, double nu, double alpha)
{
  auto Q = std::make_shared<dolfinx::fem::FunctionSpace>(
      dolfinx::fem::create_functionspace(functionspace_form_elasticity_a, "E", mesh));
  auto cellwise = [&](double v)
  {
    auto f = std::make_shared<dolfinx::fem::Function<double>>(Q);
    std::fill(f->x()->mutable_array().begin(), f->x()->mutable_array().end(), v);
    return std::shared_ptr<const dolfinx::fem::Function<double>>(f);
  };
  return {{"E", cellwise(E)}, {"nu", cellwise(nu)}, {"alpha", cellwise(alpha)}};
}
} // namespace pushout::unit

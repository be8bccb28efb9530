// Cell-averaged stress [MPa] for output: the DG0 projection of the stress of
// forms/elasticity.py (L_stress divided by the cell volumes), and in
// cracking concrete the crack band's share of it (forms/cracking.py's
// L_stress_crack). Built once; update() reassembles it from the model's
// current displacement and cracks.
#pragma once

#include "../model/Model.h"
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <memory>
#include <vector>

namespace pushout::output
{
class StressProjection
{
public:
  explicit StressProjection(const model::Model& model);
  const dolfinx::fem::Function<double>& update();

private:
  std::shared_ptr<dolfinx::fem::Form<double>> _L_stress;
  std::shared_ptr<dolfinx::fem::Function<double>> _sigma;
  std::vector<std::pair<std::int32_t, double>> _inverse_volume; ///< (DG0 block, 1/volume)
  const model::BulkCracking* _cracking = nullptr; ///< the concrete's cracks (none: linear)
};
} // namespace pushout::output

// One line per law: this is where laws are registered.
#include "LawRegistry.h"
#include "CohesiveFriction.h"
#include "Elastic.h"
#include "ExponentialSoftening.h"
#include "Friction.h"
#include "LinearSoftening.h"
#include "LinearSofteningFriction.h"
#include "OxideFriction.h"

namespace pushout::laws
{
const std::vector<LawInfo>& registered_laws()
{
  static const std::vector<LawInfo> laws = {
      describe<Elastic>(),
      describe<Friction>(),
      describe<LinearSoftening>(),
      describe<LinearSofteningFriction>(),
      describe<ExponentialSoftening>(),
      describe<CohesiveFriction>(),
      describe<OxideFriction>(),
  };
  return laws;
}

const LawInfo* find_law(const std::string& name)
{
  for (const LawInfo& law : registered_laws())
    if (law.name == name)
      return &law;
  return nullptr;
}
} // namespace pushout::laws

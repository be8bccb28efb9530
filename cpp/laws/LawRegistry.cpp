// One line per law: this is where laws are registered.
#include "LawRegistry.h"
#include "Elastic.h"
#include "Friction.h"

namespace pushout::laws
{
const std::vector<LawInfo>& registered_laws()
{
  static const std::vector<LawInfo> laws = {
      describe<Elastic>(),
      describe<Friction>(),
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

// The resolved scene (Scene::to_toml): every key with its value, defaults
// and --set overrides applied, as a run writes it to its scene.toml; read
// back, it gives the same scene.
#include "../laws/LawRegistry.h"
#include "Scene.h"
#include <sstream>

namespace pushout
{
std::string Scene::to_toml() const
{
  std::ostringstream out;
  out << "# Resolved scene: every key with its value (defaults and --set "
         "overrides applied).\n";
  std::string section;
  for (const KeyDef& def : scene_keys())
  {
    const auto it = _values.find(def.path);
    if (it == _values.end())
      continue;
    const auto dot = def.path.find('.');
    const std::string sec = def.path.substr(0, dot);
    if (sec != section)
    {
      out << "\n[" << sec << "]\n";
      section = sec;
    }
    out << def.path.substr(dot + 1) << " = " << pushout::to_toml(it->second);
    if (!def.unit.empty() && def.unit != "-")
      out << "  # " << def.unit;
    out << "\n";
  }
  const auto write_law = [&out](const LayerSpec& layer)
  {
    out << "law = \"" << layer.law << "\"\n";
    for (const auto& p : laws::find_law(layer.law)->params)
      if (layer.params.count(p.name))
        out << p.name << " = " << pushout::to_toml(layer.params.at(p.name)) << "  # " << p.unit
            << "\n";
  };
  for (const LayerSpec& layer : _layers)
  {
    out << "\n[[interface]]\n";
    write_law(layer);
  }
  for (const CrackSpec& crack : _cracks)
  {
    out << "\n[[crack]]\nangle = "
        << (crack.angle_deg ? pushout::to_toml(*crack.angle_deg) + "  # deg" : "\"nearest_face\"")
        << "\n";
    write_law(crack.layer);
  }
  return out.str();
}
} // namespace pushout

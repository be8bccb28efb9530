#include "Scenario.h"
#include "PushOut.h"
#include "SingleJoint.h"

namespace pushout::specimen
{
void check_scene(const Scene& scene)
{
  if (!scene.model().pushout())
    SingleJoint::check_scene(scene);
  else
    PushOut::check_scene(scene);
}

std::vector<std::string> scene_notes(const Scene& scene)
{
  return scene.model().pushout() ? PushOut::scene_notes(scene) : std::vector<std::string>{};
}

std::unique_ptr<Scenario> make_scenario(const Scene& scene, const mesh::MeshData& mesh,
                                        const model::Model& model)
{
  if (!scene.model().pushout())
    return std::make_unique<SingleJoint>(scene.loading(), mesh, model);
  return std::make_unique<PushOut>(mesh::MeshInput::of(scene), scene.loading(),
                                   scene.layers().size(), mesh, model);
}
} // namespace pushout::specimen

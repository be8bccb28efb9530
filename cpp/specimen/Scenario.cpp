#include "Scenario.h"
#include "PushOut.h"
#include "SingleJoint.h"

namespace pushout::specimen
{
void check_scene(const Scene& scene)
{
  if (scene.string("model.type") == "single_joint")
    SingleJoint::check_scene(scene);
  else
    PushOut::check_scene(scene);
}

std::unique_ptr<Scenario> make_scenario(const Scene& scene, const mesh::MeshData& mesh,
                                        const model::Model& model)
{
  if (scene.string("model.type") == "single_joint")
    return std::make_unique<SingleJoint>(scene, mesh, model);
  return std::make_unique<PushOut>(scene, mesh, model);
}
} // namespace pushout::specimen

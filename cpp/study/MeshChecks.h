// The checks of a sweep's cases, or a fit's start, with cracks anywhere that
// need the mesh (model::check_cracking_mesh: the crack band against its
// elements, the cracking region against the concrete), made before any run
// so that such a scene is refused at once (exit 2) in the words a run
// refuses it in.
#pragma once

#include "../mesh/MeshData.h"
#include "../mesh/MeshInput.h"
#include "../scene/Scene.h"
#include "ManyRuns.h"
#include <optional>
#include <utility>

namespace pushout::study
{
/// The mesh checks of scenes with cracks anywhere: each scene's mesh made
/// here, or read from the cache (which then serves its run), unless the size
/// guard refuses it on all the processes together (the run's own guard,
/// when it starts, counts the other groups' processes too), or it cannot be
/// made (its run then stops as without this check). One mesh is kept, for
/// the next scenes that share it.
class MeshChecks
{
public:
  explicit MeshChecks(const ManyRunsOptions& opt) : _opt(opt) {}

  /// Throws SceneError where `scene`'s mesh does not suit its cracks.
  /// Collective on MPI_COMM_WORLD.
  void operator()(const Scene& scene);

private:
  const ManyRunsOptions& _opt;
  std::optional<std::pair<mesh::MeshInput, mesh::MeshData>> _mesh;
};
} // namespace pushout::study

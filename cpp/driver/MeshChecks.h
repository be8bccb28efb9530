// The checks of a scene with cracks anywhere that need the mesh
// (model::check_cracking_mesh: the crack band against its elements, the
// cracking region against the concrete), made before a run touches its
// output folder, and before any case of a sweep or the start of a fit runs,
// so that such a scene is refused at once (exit 2) in the words a run
// refuses it in, an earlier run's outputs left where they are.
#pragma once

#include "../mesh/MeshData.h"
#include "../mesh/MeshInput.h"
#include "../scene/Scene.h"
#include <filesystem>
#include <optional>
#include <utility>

namespace pushout::driver
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
  /// `mesh_cache`: the mesh cache's folder; `force`: past the size guard
  /// (--force).
  MeshChecks(std::filesystem::path mesh_cache, bool force)
      : _mesh_cache(std::move(mesh_cache)), _force(force)
  {
  }

  /// Throws SceneError where `scene`'s mesh does not suit its cracks.
  /// Collective on MPI_COMM_WORLD.
  void operator()(const Scene& scene);

private:
  std::filesystem::path _mesh_cache;
  bool _force;
  std::optional<std::pair<mesh::MeshInput, mesh::MeshData>> _mesh;
};
} // namespace pushout::driver

// The mesh checks of scenes with cracks anywhere before a run (MeshChecks.h).
#include "MeshChecks.h"
#include "../mesh/generate.h"
#include "../model/CrackBandCheck.h"
#include "../record/ResourceGuard.h"
#include <stdexcept>

namespace pushout::driver
{
void MeshChecks::operator()(const Scene& scene)
{
  if (!scene.cracking().embedded)
    return;
  const mesh::MeshInput shape = mesh::MeshInput::of(scene);
  if (!_mesh || _mesh->first != shape)
  {
    _mesh.reset(); // one mesh in memory at a time
    try            // the whole run's estimate, which meshing alone is far below
    {
      record::check_fits(
          record::estimate_resources(shape, scene.solver(), scene.cracking(), MPI_COMM_WORLD),
          shape, _force);
    }
    catch (const record::TooLarge&)
    {
      return; // its run is refused when it starts, with the guard's words
    }
    bool reused = false;
    try
    {
      _mesh.emplace(shape, mesh::generate(shape, _mesh_cache, reused, MPI_COMM_WORLD));
    }
    catch (const std::runtime_error&) // on every process (mesh::generate)
    {
      return; // its run fails when it starts
    }
  }
  model::check_cracking_mesh(_mesh->second, scene.concrete(), scene.cracking(), scene.geometry());
}
} // namespace pushout::driver

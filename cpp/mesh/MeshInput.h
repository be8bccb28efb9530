// What the mesh is made from: the scene's model type, geometry, mesh keys,
// crack planes, and what decides the symmetry cut (mesh/symmetry.h).
#pragma once

#include "../scene/Scene.h"

namespace pushout::mesh
{
struct MeshInput
{
  bool pushout = true; ///< model.type: pushout (else the single joint)
  Geometry geometry;
  MeshPart mesh;
  CrackDirections cracks;         ///< the crack planes' directions (none: uncracked)
  ModelPart::Symmetry symmetry{}; ///< model.symmetry
  bool fields = false;        ///< output.xdmf (model.symmetry "auto" then takes the whole slice)
  bool bulk_cracking = false; ///< cracking.model = "embedded": cracks anywhere in the concrete
  bool cracked() const { return !cracks.angles.empty(); }
  bool operator==(const MeshInput&) const = default; ///< the same mesh

  static MeshInput of(const Scene& scene)
  {
    return {scene.model().pushout(),  scene.geometry(),       scene.mesh(),
            scene.crack_directions(), scene.model().symmetry, scene.output().xdmf,
            scene.cracking().embedded};
  }
};
} // namespace pushout::mesh

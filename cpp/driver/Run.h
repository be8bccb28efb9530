// One simulation: scene -> mesh -> model -> step loop -> outputs.
#pragma once

#include "../output/Summary.h"
#include "../scene/Scene.h"
#include <filesystem>
#include <mpi.h>

namespace pushout::driver
{
struct RunOptions
{
  std::filesystem::path out;        ///< output folder
  std::filesystem::path mesh_cache; ///< gmsh mesh cache folder
  bool quiet = false;               ///< no progress lines
  bool force = false;               ///< run even if the size guard says it cannot fit
  MPI_Comm comm = MPI_COMM_WORLD;   ///< the processes that run it (pushout sweep: a group)
  bool plot = true;                 ///< curve.png if output.plot (a sweep draws sweep.png)
};

/// Runs the scene on options.comm; writes curve.csv, summary.json,
/// scene.toml (and curve.png, XDMF) into options.out. Returns the summary; a step that
/// cannot converge ends the run with summary.converged = false.
output::Summary run(const Scene& scene, const RunOptions& options);
} // namespace pushout::driver

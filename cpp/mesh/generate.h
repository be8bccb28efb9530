// Meshes from the scene: gmsh runs meshes/*.geo with the scene's constants,
// and the result is cached by parameters (reused when they come again).
// gmsh lives in a module of its own (gmsh_mesher.cpp), loaded only when a
// mesh is not in the cache: a run from the cache does not load gmsh and the
// 70 libraries it brings.
#pragma once

#include "MeshData.h"
#include "MeshInput.h"
#include <filesystem>
#include <string_view>

namespace pushout::mesh
{
/// The mesh `in` describes, with its interface inserted. Rank 0 of
/// `comm` runs gmsh and every process receives the whole mesh. The gmsh mesh
/// is cached in `cache_dir` (*.mesh: its nodes, hexahedra and materials)
/// under a hash of the .geo text and constants.
/// `reused` reports whether the cache served it. Collective.
MeshData generate(const MeshInput& in, const std::filesystem::path& cache_dir, bool& reused,
                  MPI_Comm comm = MPI_COMM_WORLD);

/// Whether the cache holds a file of the mesh `in` describes (generate()
/// then reads it, unless it is found unreadable). On this process alone.
bool in_cache(const MeshInput& in, const std::filesystem::path& cache_dir);

/// Default cache folder: $PUSHOUT_CACHE_DIR, else $XDG_CACHE_HOME/pushout
/// (an absolute path: a relative one is ignored), else ~/.cache/pushout.
std::filesystem::path default_cache_dir();

/// The extension of the cache's mesh files.
constexpr std::string_view cache_extension = ".mesh";

/// The cache keeps at most this many MB of meshes by default; the least
/// recently used go first. $PUSHOUT_CACHE_MAX_MB sets another bound (0: no
/// cache: every run meshes, nothing is stored).
constexpr double default_cache_limit_mb = 1024;

/// The bound in force [MB]: $PUSHOUT_CACHE_MAX_MB or the default.
double cache_limit_mb();

/// Removes the least recently used meshes (*.mesh, by modification time, which
/// a reuse renews) of `cache_dir` until they and `keep` take at most
/// `limit_mb`; `keep` (the mesh just written) always stays.
void prune_cache(const std::filesystem::path& cache_dir, double limit_mb,
                 const std::filesystem::path& keep);
} // namespace pushout::mesh

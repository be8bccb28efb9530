#include "generate.h"
#include "../scene/CrackPlanes.h"
#include "../scene/SceneError.h"
#include "cracks.h"
#include "size.h"
#include "symmetry.h"
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <dlfcn.h>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <unistd.h>

#ifndef PUSHOUT_MESH_DIR
#error "PUSHOUT_MESH_DIR must point to the meshes/ folder"
#endif
#ifndef PUSHOUT_GMSH_MESHER
#error "PUSHOUT_GMSH_MESHER must be the path of the gmsh mesher module"
#endif

namespace pushout::mesh
{
namespace
{
/// The .geo file and its constants for this scene.
std::pair<std::filesystem::path, std::vector<std::pair<std::string, double>>>
geo_for(const MeshInput& in)
{
  const Geometry& g = in.geometry;
  const std::filesystem::path dir(PUSHOUT_MESH_DIR);
  if (!in.pushout)
    return {dir / "single_joint.geo", {{"a", std::sqrt(g.area)}}};
  const auto& c = g.tube_center;
  std::vector<std::pair<std::string, double>> sectors; // slice_cracked.geo's (cracks.h)
  if (in.cracked())
  {
    const SliceSectors sec = slice_sectors(in);
    sectors.push_back({"nb", double(sec.angles.size())});
    for (std::size_t i = 0; i < sec.angles.size(); ++i)
    {
      const std::string k = std::to_string(i);
      sectors.insert(sectors.end(), {{"a_" + k, sec.angles[i]},
                                     {"ox_" + k, sec.outer[i][0]},
                                     {"oy_" + k, sec.outer[i][1]},
                                     {"n_" + k, double(sec.elements[i])}});
    }
  }
  std::vector<std::pair<std::string, double>> constants = {
      {"shape", g.circle ? 1.0 : 0.0},
      {"W", g.width},
      {"L", g.thickness},
      {"D", g.tube_outer_diameter},
      {"Di", g.tube_inner_diameter},
      {"cx", c[0]},
      {"cy", c[1]},
      {"Ds", g.support_inner_diameter},
      {"nq", double(in.mesh.elements_per_quarter)},
      {"nz", double(in.mesh.elements_through_thickness)},
      {"ns", double(in.mesh.steel_layers)}};
  const SliceDivisions d = slice_divisions(in); // the radial divisions (mesh/size.h)
  constants.insert(constants.end(),
                   {{"nr1", double(d.ring)}, {"nr2", double(d.graded)}, {"q", d.growth}});
  if (sectors.empty())
  {
    const auto corners = block_corners(g); // the graded block's outer ends
    for (std::size_t k = 0; k < corners.size(); ++k)
      constants.insert(constants.end(), {{"ox_" + std::to_string(k), corners[k][0]},
                                         {"oy_" + std::to_string(k), corners[k][1]}});
    // Always given: gmsh keeps a constant that an earlier mesh of this
    // process set when this one does not set it.
    const bool radial = in.mesh.radial_lines && !g.circle; // (a circle's are radial already)
    constants.push_back({"radial", radial ? 1.0 : 0.0});
    if (radial)
    {
      const auto ends = radial_line_ends(g, in.mesh.elements_per_quarter);
      for (std::size_t j = 0; j < ends.size(); ++j)
        constants.insert(constants.end(), {{"bx_" + std::to_string(j), ends[j][0]},
                                           {"by_" + std::to_string(j), ends[j][1]}});
    }
    return {dir / "slice.geo", constants};
  }
  constants.insert(constants.end(), sectors.begin(), sectors.end());
  return {dir / "slice_cracked.geo", constants};
}

std::string read_file(const std::filesystem::path& p)
{
  std::ifstream in(p);
  if (!in)
    throw std::runtime_error("cannot read mesh geometry " + p.string());
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The mesher module (gmsh_mesher.cpp), loaded at its first use.
using MeshFunction = int (*)(const char*, const char* const*, const double*, std::size_t, MeshData*,
                             char*, std::size_t);
MeshFunction mesher()
{
  static const MeshFunction f = []
  {
    void* module = dlopen(PUSHOUT_GMSH_MESHER, RTLD_NOW | RTLD_LOCAL);
    if (!module)
      throw std::runtime_error(std::string("cannot load the gmsh mesher: ") + dlerror());
    void* entry = dlsym(module, "pushout_gmsh_mesh");
    if (!entry)
    {
      const std::string why = dlerror();
      dlclose(module);
      throw std::runtime_error("the gmsh mesher has no entry point: " + why);
    }
    return reinterpret_cast<MeshFunction>(entry);
  }();
  return f;
}

/// gmsh's mesh of `geo` with its constants.
MeshData mesh_with_gmsh(const std::filesystem::path& geo,
                        const std::vector<std::pair<std::string, double>>& constants)
{
  std::vector<const char*> names;
  std::vector<double> values;
  for (const auto& [name, value] : constants)
  {
    names.push_back(name.c_str());
    values.push_back(value);
  }
  MeshData m;
  std::array<char, 1024> error{};
  if (mesher()(geo.c_str(), names.data(), values.data(), names.size(), &m, error.data(),
               error.size()) != 0)
    throw std::runtime_error(error.data());
  return m;
}

/// The cache file: a header line (the format's version), the hash of what
/// made the mesh, the counts, the arrays as they are in memory (the cache is
/// this machine's), then the checksum of counts and arrays. A file that
/// fails any check is meshed again.
constexpr std::string_view cache_header = "pushout mesh cache 2\n";

/// The version of what the mesher makes of a .geo file and its constants:
/// raise it when gmsh_mesher.cpp (or what it is given) changes the mesh, and
/// every cached mesh is made again.
constexpr std::uint64_t mesher_version = 1;

/// FNV-1a, 64 bits: the checksum of the cache's content and of the mesher's
/// inputs (a hash that is the same in every build, unlike std::hash).
class Fnv1a
{
public:
  void add(const void* data, std::size_t bytes)
  {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i)
      _h = (_h ^ p[i]) * 0x100000001b3ULL;
  }
  std::uint64_t value() const { return _h; }

private:
  std::uint64_t _h = 0xcbf29ce484222325ULL;
};

/// The checksum of a mesh's counts and arrays.
std::uint64_t content_checksum(const std::uint64_t (&counts)[2], const MeshData& m)
{
  Fnv1a h;
  h.add(counts, sizeof(counts));
  h.add(m.x.data(), m.x.size() * sizeof(double));
  h.add(m.cells.data(), m.cells.size() * sizeof(std::int64_t));
  h.add(m.material.data(), m.material.size() * sizeof(std::int32_t));
  return h.value();
}

void write_cached(const std::filesystem::path& path, const MeshData& m, std::uint64_t inputs)
{
  std::ofstream out(path, std::ios::binary);
  const std::uint64_t counts[2] = {m.num_nodes(), m.num_cells()};
  const std::uint64_t checksum = content_checksum(counts, m);
  out.write(cache_header.data(), std::streamsize(cache_header.size()));
  out.write(reinterpret_cast<const char*>(&inputs), sizeof(inputs));
  out.write(reinterpret_cast<const char*>(counts), sizeof(counts));
  out.write(reinterpret_cast<const char*>(m.x.data()),
            std::streamsize(m.x.size() * sizeof(double)));
  out.write(reinterpret_cast<const char*>(m.cells.data()),
            std::streamsize(m.cells.size() * sizeof(std::int64_t)));
  out.write(reinterpret_cast<const char*>(m.material.data()),
            std::streamsize(m.material.size() * sizeof(std::int32_t)));
  out.write(reinterpret_cast<const char*>(&checksum), sizeof(checksum));
  if (!out)
    throw std::runtime_error("cannot write the mesh cache file " + path.string());
}

/// The cached mesh made from `inputs` (the hash of the mesher's inputs),
/// or false with the reason in `why` if the file is not one (then it is
/// meshed again).
bool read_cached(const std::filesystem::path& path, std::uint64_t inputs, MeshData& m,
                 std::string& why)
{
  std::ifstream in(path, std::ios::binary);
  std::string header(cache_header.size(), '\0');
  std::uint64_t stored_inputs = 0, counts[2] = {0, 0}, checksum = 0;
  in.read(header.data(), std::streamsize(header.size()));
  in.read(reinterpret_cast<char*>(&stored_inputs), sizeof(stored_inputs));
  in.read(reinterpret_cast<char*>(counts), sizeof(counts));
  if (!in || header != cache_header)
  {
    why = "not a mesh of this version of pushout";
    return false;
  }
  if (stored_inputs != inputs)
  {
    why = "made by another mesher version or from other inputs";
    return false;
  }
  // The counts must account for the file's size exactly (a damaged header
  // is not an allocation of 100 GB).
  std::error_code ec;
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  const double expected =
      double(cache_header.size() + sizeof(stored_inputs) + sizeof(counts) + sizeof(checksum)) +
      double(counts[0]) * 3 * sizeof(double) +
      double(counts[1]) * (8 * sizeof(std::int64_t) + sizeof(std::int32_t));
  if (ec || double(bytes) != expected)
  {
    why = "its size does not match its counts (cut short?)";
    return false;
  }
  m.x.resize(3 * counts[0]);
  m.cells.resize(8 * counts[1]);
  m.material.resize(counts[1]);
  in.read(reinterpret_cast<char*>(m.x.data()), std::streamsize(m.x.size() * sizeof(double)));
  in.read(reinterpret_cast<char*>(m.cells.data()),
          std::streamsize(m.cells.size() * sizeof(std::int64_t)));
  in.read(reinterpret_cast<char*>(m.material.data()),
          std::streamsize(m.material.size() * sizeof(std::int32_t)));
  in.read(reinterpret_cast<char*>(&checksum), sizeof(checksum));
  if (!in || in.peek() != std::ifstream::traits_type::eof())
  {
    why = "it cannot be read whole";
    return false;
  }
  if (checksum != content_checksum(counts, m))
  {
    why = "its checksum does not match its content (damaged)";
    return false;
  }
  const std::int64_t n = std::int64_t(counts[0]);
  if (!std::all_of(m.cells.begin(), m.cells.end(),
                   [n](std::int64_t v) { return v >= 0 && v < n; }) ||
      !std::all_of(m.x.begin(), m.x.end(), [](double v) { return std::isfinite(v); }))
  {
    why = "its cells or coordinates are out of range";
    return false;
  }
  return true;
}
} // namespace

std::filesystem::path default_cache_dir()
{
  if (const char* d = std::getenv("PUSHOUT_CACHE_DIR"); d && *d)
    return d;
  // A relative XDG_CACHE_HOME is not one (the XDG base directory spec).
  if (const char* d = std::getenv("XDG_CACHE_HOME"); d && std::filesystem::path(d).is_absolute())
    return std::filesystem::path(d) / "pushout";
  if (const char* d = std::getenv("HOME"); d && *d)
    return std::filesystem::path(d) / ".cache" / "pushout";
  return std::filesystem::temp_directory_path() / "pushout-cache";
}

double cache_limit_mb()
{
  if (const char* v = std::getenv("PUSHOUT_CACHE_MAX_MB"); v && *v)
  {
    char* end = nullptr;
    const double mb = std::strtod(v, &end);
    if (end == v || *end != '\0' || !(mb >= 0))
      throw OptionError(std::string("PUSHOUT_CACHE_MAX_MB = '") + v +
                        "': a size in MB (>= 0) is needed");
    return mb;
  }
  return default_cache_limit_mb;
}

void prune_cache(const std::filesystem::path& cache_dir, double limit_mb,
                 const std::filesystem::path& keep)
{
  namespace fs = std::filesystem;
  struct Entry
  {
    fs::path path;
    fs::file_time_type used;
    std::uintmax_t bytes;
  };
  std::vector<Entry> entries;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(cache_dir, ec))
  {
    // (*.msh: meshes of pushout before its own format, which nothing reads.)
    if ((e.path().extension() != cache_extension && e.path().extension() != ".msh") ||
        e.path() == keep)
      continue;
    std::error_code ec_entry;
    const auto used = fs::last_write_time(e.path(), ec_entry);
    // Another run's mesh being written (generate_here's private name) is
    // left alone for a day.
    const bool being_written = e.path().stem().extension().string().starts_with(".tmp");
    if (being_written && fs::file_time_type::clock::now() - used < std::chrono::hours(24))
      continue;
    const auto bytes = fs::file_size(e.path(), ec_entry);
    if (!ec_entry)
      entries.push_back({e.path(), used, bytes});
  }
  std::sort(entries.begin(), entries.end(),
            [](const Entry& a, const Entry& b) { return a.used > b.used; });
  std::error_code ec_keep;
  double total_mb = fs::exists(keep, ec_keep) ? double(fs::file_size(keep, ec_keep)) / 1048576 : 0;
  for (const Entry& e : entries) // newest first: the oldest go
  {
    total_mb += double(e.bytes) / 1048576;
    if (total_mb > limit_mb)
      fs::remove(e.path, ec); // another run may have removed it: no error
  }
}

namespace
{
/// The cache's file of the mesh of `geo` with its `constants`, and the
/// hash of its inputs (the mesher's version, the .geo text and the
/// constants) that the file holds.
std::filesystem::path cache_file(const std::filesystem::path& geo,
                                 const std::vector<std::pair<std::string, double>>& constants,
                                 const std::filesystem::path& cache_dir, std::uint64_t& inputs)
{
  std::ostringstream key;
  key << "mesher " << mesher_version << ";" << read_file(geo);
  for (const auto& [name, value] : constants)
    key << name << "=" << std::setprecision(17) << value << ";";
  Fnv1a inputs_hash;
  inputs_hash.add(key.str().data(), key.str().size());
  inputs = inputs_hash.value();
  std::ostringstream hex;
  hex << std::hex << std::setw(16) << std::setfill('0') << inputs;
  return cache_dir / (geo.stem().string() + "-" + hex.str() + std::string(cache_extension));
}

/// gmsh on this process: the cached or a new mesh.
MeshData generate_here(const MeshInput& in, const std::filesystem::path& cache_dir, bool& reused)
{
  const auto [geo, constants] = geo_for(in);
  std::uint64_t inputs;
  const std::filesystem::path cached = cache_file(geo, constants, cache_dir, inputs);

  MeshData m;
  const double limit_mb = cache_limit_mb();
  std::string why;
  reused = limit_mb > 0 && std::filesystem::exists(cached) && read_cached(cached, inputs, m, why);
  if (!why.empty())
    std::cerr << "pushout: note: the cached mesh " << cached.string() << " is not used (" << why
              << "); meshing again" << std::endl;
  if (reused)
  {
    // Marks it used: the cache forgets the least recently used first.
    std::error_code ec;
    std::filesystem::last_write_time(cached, std::filesystem::file_time_type::clock::now(), ec);
  }
  else
  {
    m = mesh_with_gmsh(geo, constants);
    if (limit_mb > 0)
    {
      // Write to a private name, then rename: concurrent runs never read a
      // half-written file (and prune_cache leaves *.tmpPID.* alone).
      std::filesystem::path tmp = cached;
      tmp.replace_extension(".tmp" + std::to_string(::getpid()) + std::string(cache_extension));
      // A cache that cannot be written costs the next run a meshing, not
      // this run its mesh.
      try
      {
        std::filesystem::create_directories(cache_dir);
        write_cached(tmp, m, inputs);
        std::filesystem::rename(tmp, cached);
        prune_cache(cache_dir, limit_mb, cached);
      }
      catch (const std::exception& e)
      {
        std::error_code ec;
        std::filesystem::remove(tmp, ec);
        std::cerr << "pushout: warning: the mesh was not cached: " << e.what() << std::endl;
      }
    }
  }
  insert_interface(m);
  if (in.cracked())
    insert_cracks(m, in.geometry.tube_center, in.geometry.tube_radius(), in.cracks.angles);
  return m;
}
} // namespace

bool in_cache(const MeshInput& in, const std::filesystem::path& cache_dir)
{
  if (!(cache_limit_mb() > 0))
    return false;
  const auto [geo, constants] = geo_for(in);
  std::uint64_t inputs;
  std::error_code ec;
  return std::filesystem::exists(cache_file(geo, constants, cache_dir, inputs), ec);
}

MeshData generate(const MeshInput& in, const std::filesystem::path& cache_dir, bool& reused,
                  MPI_Comm comm)
{
  int rank;
  MPI_Comm_rank(comm, &rank);
  MeshData m;
  std::string error;
  int flags[2] = {0, 0}; // failed, reused
  if (rank == 0)
  {
    try
    {
      m = generate_here(in, cache_dir, reused);
      flags[1] = reused;
    }
    catch (const std::exception& e)
    {
      error = e.what();
      flags[0] = 1;
    }
    catch (const std::string& e) // gmsh's errors
    {
      error = e;
      flags[0] = 1;
    }
    catch (...)
    {
      error = "an unknown error";
      flags[0] = 1;
    }
  }
  // Every process learns of a failure and throws: none waits in a
  // collective that the others skipped.
  MPI_Bcast(flags, 2, MPI_INT, 0, comm);
  if (flags[0])
  {
    std::uint64_t n = error.size();
    MPI_Bcast(&n, 1, MPI_UINT64_T, 0, comm);
    error.resize(n);
    MPI_Bcast(error.data(), int(n), MPI_CHAR, 0, comm);
    throw std::runtime_error("mesh generation failed: " + error);
  }
  reused = flags[1];
  broadcast(m, comm, 0);
  std::string why;
  if (const Symmetry symmetry = model_symmetry(in, why); symmetry.copies() > 1)
    keep_symmetric_part(m, symmetry, in.geometry.tube_center);
  return m;
}
} // namespace pushout::mesh

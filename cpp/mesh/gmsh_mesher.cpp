// The gmsh mesher, a module that pushout loads only when it meshes (a mesh
// not in the cache; mesh/generate.cpp). gmsh brings some 70 libraries of
// its own (OpenCASCADE, FLTK, ...): linked into pushout, loading them took
// a third of every run's start, cached mesh or not.
//
// One entry point, with C linkage so that dlsym finds it by name:
// pushout_gmsh_mesh meshes a .geo file with its constants (-setnumber) and
// returns the hexahedra, their nodes and materials.
#include "MeshData.h"
#include <cstring>
#include <dolfinx/io/cells.h>
#include <exception>
#include <gmsh.h>
#include <iomanip>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using namespace pushout::mesh;

/// Hexahedra and nodes of the current gmsh model.
MeshData read_gmsh_model()
{
  MeshData m;
  std::vector<std::size_t> tags;
  std::vector<double> coords, param;
  gmsh::model::mesh::getNodes(tags, coords, param, -1, -1, false, false);
  std::map<std::size_t, std::size_t> gmsh_node; // gmsh tag -> coords index
  for (std::size_t i = 0; i < tags.size(); ++i)
    gmsh_node[tags[i]] = i;

  const std::vector<std::uint8_t> perm =
      dolfinx::io::cells::perm_gmsh(dolfinx::mesh::CellType::hexahedron, 8);
  std::vector<std::int64_t> index(tags.size(), -1); // coords index -> node id
  for (const Material mat : {steel, concrete})
  {
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(3, mat, entities);
    for (int e : entities)
    {
      std::vector<std::size_t> elements, nodes;
      gmsh::model::mesh::getElementsByType(5, elements, nodes, e);
      for (std::size_t c = 0; c < elements.size(); ++c)
      {
        for (int i = 0; i < 8; ++i)
        {
          const std::size_t k = gmsh_node.at(nodes[8 * c + perm[i]]);
          if (index[k] < 0)
          {
            index[k] = std::int64_t(m.x.size() / 3);
            m.x.insert(m.x.end(), coords.begin() + 3 * k, coords.begin() + 3 * k + 3);
          }
          m.cells.push_back(index[k]);
        }
        m.material.push_back(mat);
      }
    }
  }
  if (m.material.empty())
    throw std::runtime_error("gmsh produced no hexahedra");
  return m;
}

void copy_message(const std::string& what, char* error, std::size_t size)
{
  if (size == 0)
    return;
  std::strncpy(error, what.c_str(), size - 1);
  error[size - 1] = '\0';
}
} // namespace

/// Meshes `geo` with the constants names[i] = values[i] into *out. Returns
/// 0, or 1 with gmsh's message in `error` (at most error_size bytes).
extern "C" int pushout_gmsh_mesh(const char* geo, const char* const* names, const double* values,
                                 std::size_t count, MeshData* out, char* error,
                                 std::size_t error_size)
{
  std::vector<std::string> args = {"pushout"};
  for (std::size_t i = 0; i < count; ++i)
  {
    std::ostringstream v;
    v << std::setprecision(17) << values[i];
    args.insert(args.end(), {"-setnumber", names[i], v.str()});
  }
  std::vector<char*> argv;
  for (auto& a : args)
    argv.push_back(a.data());
  bool initialized = false;
  try
  {
    gmsh::initialize(int(argv.size()), argv.data(), false);
    initialized = true;
    gmsh::option::setNumber("General.Terminal", 0);
    // No question on stdin (a mesh gmsh finds large asked one, and waited
    // for its answer past Ctrl-C): its default answer.
    gmsh::option::setNumber("General.NoPopup", 1);
    gmsh::open(geo);
    gmsh::model::mesh::generate(3);
    *out = read_gmsh_model();
    gmsh::finalize();
    return 0;
  }
  catch (const std::exception& e)
  {
    copy_message(e.what(), error, error_size);
  }
  catch (const std::string& e) // gmsh's errors
  {
    copy_message(e, error, error_size);
  }
  catch (...)
  {
    copy_message("unknown error in gmsh", error, error_size);
  }
  if (initialized)
    try
    {
      gmsh::finalize();
    }
    catch (...) // the error above is the one to report
    {
    }
  return 1;
}

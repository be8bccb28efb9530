// XdmfSeries (output/XdmfSeries.h) writes the files dolfinx::io::XDMFFile
// writes, the way ParaView reads them: the same XML, and in the HDF5 file a
// displacement's value at each node it lists (the dof there: an affine field
// of the node's coordinates) and a cell field per cell. On
// PETSC_COMM_WORLD: unit_two_processes runs it on two processes, where each
// writes its own nodes' and cells' rows.
#include "elasticity.h"
#include "output/XdmfSeries.h"
#include <array>
#include <cmath>
#include <dolfinx/fem/utils.h>
#include <dolfinx/io/HDF5Interface.h>
#include <dolfinx/io/XDMFFile.h>
#include <dolfinx/mesh/generation.h>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <petscsys.h>
#include <sstream>
#include <string>
#include <unistd.h>

using namespace pushout;
namespace fem = dolfinx::fem;

namespace
{
/// The affine displacement written at a point x [mm].
std::array<double, 3> affine(const double* x)
{
  return {0.5 + x[0] - 2 * x[1], 3 * x[2] - 1, x[0] + x[1] + x[2]};
}

std::string text_of(const std::filesystem::path& file)
{
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A folder of the first process's, shared by the processes of
/// PETSC_COMM_WORLD, removed with the object.
struct Scratch
{
  std::filesystem::path dir;
  Scratch()
  {
    long pid = long(getpid());
    MPI_Bcast(&pid, 1, MPI_LONG, 0, PETSC_COMM_WORLD);
    dir = std::filesystem::temp_directory_path() / ("xdmf_series_" + std::to_string(pid));
    for (const char* d : {"ours", "theirs"})
      std::filesystem::create_directories(dir / d);
    MPI_Barrier(PETSC_COMM_WORLD);
  }
  ~Scratch()
  {
    MPI_Barrier(PETSC_COMM_WORLD);
    int rank = 0;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    if (rank == 0)
      std::filesystem::remove_all(dir);
  }
};

struct Fields
{
  std::shared_ptr<dolfinx::mesh::Mesh> mesh;
  std::shared_ptr<fem::Function<double>> u, sigma;
};

/// The model's displacement and stress spaces on a box of hexahedra, the
/// displacement affine, the stress a different tensor per cell.
Fields fields()
{
  Fields f;
  f.mesh = std::make_shared<dolfinx::mesh::Mesh>(dolfinx::mesh::create_box(
      PETSC_COMM_WORLD, {{{0, 0, 0}, {3, 2, 1}}}, {3, 4, 2}, dolfinx::mesh::CellType::hexahedron,
      dolfinx::mesh::GhostMode::none));
  f.mesh->name = "mesh";
  auto V = std::make_shared<fem::FunctionSpace>(
      fem::create_functionspace(functionspace_form_elasticity_a, "u", f.mesh));
  auto S = std::make_shared<fem::FunctionSpace>(
      fem::create_functionspace(functionspace_form_elasticity_L_stress, "tau", f.mesh));
  f.u = std::make_shared<fem::Function<double>>(V);
  f.u->name = "displacement";
  const std::vector<double> x = V->tabulate_dof_coordinates(false);
  std::span<double> u = f.u->x()->mutable_array();
  for (std::size_t b = 0; b < u.size() / 3; ++b)
  {
    const std::array<double, 3> v = affine(x.data() + 3 * b);
    std::copy(v.begin(), v.end(), u.begin() + 3 * b);
  }
  f.sigma = std::make_shared<fem::Function<double>>(S);
  f.sigma->name = "stress";
  const std::vector<double> c = S->tabulate_dof_coordinates(false); // the cells' centres
  std::span<double> s = f.sigma->x()->mutable_array();
  for (std::size_t d = 0; d < s.size() / 9; ++d)
    for (int k = 0; k < 9; ++k)
      s[9 * d + k] = c[3 * d] + 10 * c[3 * d + 1] + 100 * c[3 * d + 2] + 1000 * k;
  return f;
}

std::vector<double> dataset(const std::filesystem::path& h5, const std::string& path)
{
  const hid_t file = dolfinx::io::HDF5Interface::open_file(MPI_COMM_SELF, h5, "r", false);
  const std::vector<std::int64_t> shape = dolfinx::io::HDF5Interface::get_dataset_shape(file, path);
  std::vector<double> v = dolfinx::io::HDF5Interface::read_dataset<double>(
      file, path, {0, shape.empty() ? 0 : shape[0]});
  dolfinx::io::HDF5Interface::close_file(file);
  return v;
}
} // namespace

TEST(XdmfSeries, WritesWhatXdmfFileWrites)
{
  const Fields f = fields();
  const Scratch scratch;
  const std::filesystem::path ours = scratch.dir / "ours" / "fields.xdmf",
                              theirs = scratch.dir / "theirs" / "fields.xdmf";
  {
    output::XdmfSeries series(PETSC_COMM_WORLD, ours);
    series.write_mesh(*f.mesh);
    dolfinx::io::XDMFFile file(PETSC_COMM_WORLD, theirs, "w");
    file.write_mesh(*f.mesh);
    for (double t : {0.0, 1.0, 2.5})
    {
      series.write(*f.u, t);
      series.write(*f.sigma, t);
      series.save();
      file.write_function(*f.u, t);
      file.write_function(*f.sigma, t);
    }
    series.close();
    file.close();
  }
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank == 0)
  {
    EXPECT_EQ(text_of(ours), text_of(theirs));
    const std::filesystem::path ours_h5 = ours.parent_path() / "fields.h5",
                                theirs_h5 = theirs.parent_path() / "fields.h5";
    const std::vector<double> X = dataset(ours_h5, "/Mesh/mesh/geometry");
    EXPECT_EQ(X, dataset(theirs_h5, "/Mesh/mesh/geometry"));
    for (const char* t : {"0", "1", "2_5"})
    {
      // At each node the displacement's dof there, written as the node's
      // (the dofs' coordinates, pushed forward from the reference cell,
      // differ from the nodes' by round-off; 1e-12 of a field of 10 mm).
      const std::vector<double> u = dataset(ours_h5, std::string("/Function/displacement/") + t);
      const std::vector<double> u_theirs =
          dataset(theirs_h5, std::string("/Function/displacement/") + t);
      ASSERT_EQ(u.size(), X.size());
      ASSERT_EQ(u_theirs.size(), X.size());
      for (std::size_t i = 0; i < X.size() / 3; ++i)
        for (int k = 0; k < 3; ++k)
        {
          EXPECT_NEAR(u[3 * i + k], affine(X.data() + 3 * i)[k], 1e-12) << "node " << i;
          // XDMFFile evaluates the field in a cell at the node: round-off.
          EXPECT_NEAR(u_theirs[3 * i + k], u[3 * i + k], 1e-12) << "node " << i;
        }
      EXPECT_EQ(dataset(ours_h5, std::string("/Function/stress/") + t),
                dataset(theirs_h5, std::string("/Function/stress/") + t));
    }
  }
}

#include "FieldWriter.h"
#include "../common/mpi_errors.h"
#include "elasticity.h"
#include "xdmf_checked.h"
#include <basix/finite-element.h>
#include <dolfinx/fem/utils.h>
#include <exception>
#include <functional>
#include <sys/statvfs.h>

namespace pushout::output
{
FieldWriter::FieldWriter(const model::Model& model, const std::filesystem::path& dir,
                         const std::string& prefix)
    : _model(model), _dir(dir),
      _fields_file(dir / (prefix + "fields.xdmf")), _h5{dir / (prefix + "fields.h5"),
                                                        dir / (prefix + "interface.h5")},
      _stress(model)
{
  try
  {
    open(prefix);
  }
  catch (...)
  {
    remove_files(prefix);
    throw;
  }
}

void FieldWriter::remove_files(const std::string& prefix) const noexcept
{
  int rank = 0;
  MPI_Comm_rank(_model.comm(), &rank);
  if (rank != 0)
    return;
  // Those of its names only: cracks.* is a run's with crack planes (a
  // file of that name is the user's else).
  std::vector<const char*> names = {"fields", "interface"};
  if (_model.num_cracks() > 0)
    names.push_back("cracks");
  for (const char* name : names)
    for (const char* ext : {".xdmf", ".h5"})
    {
      const std::filesystem::path f = _dir / (prefix + name + ext);
      std::error_code ec;
      if (std::filesystem::is_regular_file(f, ec))
        std::filesystem::remove(f, ec);
    }
}

void FieldWriter::open(const std::string& prefix)
{
  const model::Model& model = _model;
  const std::filesystem::path& dir = _dir;
  namespace fem = dolfinx::fem;
  MPI_Comm comm = model.comm();
  silence_hdf5();
  try
  {
    _fields = std::make_unique<XdmfSeries>(comm, _fields_file);
  }
  catch (...)
  {
    throw std::runtime_error(cannot_write_xdmf(_fields_file));
  }
  xdmf_checked(_fields, _fields_file, [&](XdmfSeries& f) { f.write_mesh(*model.mesh()); });
  if (model.degree() == 2)
  {
    _u1 = std::make_shared<fem::Function<double>>(std::make_shared<fem::FunctionSpace>(
        fem::create_functionspace(functionspace_form_elasticity_a, "u", model.mesh())));
    _u1->name = "displacement";
  }

  if (model.bulk_cracking())
  {
    auto cells = [&](int bs, const char* name)
    {
      auto f = std::make_shared<fem::Function<double>>(std::make_shared<fem::FunctionSpace>(
          fem::create_functionspace(model.mesh(),
                                    basix::create_element(basix::element::family::P,
                                                          basix::cell::type::hexahedron, 0, true),
                                    bs)));
      f->name = name;
      return f;
    };
    _crack_opening = cells(1, "crack_opening");
    _crack_normal = cells(3, "crack_normal");
    _crack_damage = cells(1, "crack_damage");
  }

  // The joint elements: interface.xdmf has the interface and the crack
  // planes (so that one file shows every joint element: `crack`
  // -1 on the interface, the plane's index on a plane); cracks.xdmf has the
  // planes alone, with their own fields.
  const std::vector<double> dof_x = model.space()->tabulate_dof_coordinates(false);
  const auto& itf = model.interface();
  const std::size_t layers = itf.num_layers();
  std::vector<std::string> names = {"t_n", "t_s1", "t_s2", "w_n", "w_s1"};
  for (std::size_t l = 0; l < layers; ++l)
    for (const char* n : {"slip_s1_", "slip_s2_", "damage_"})
      names.push_back(n + std::to_string(l));
  std::vector<const interface::Interface*> sets = {&itf}, cracks;
  for (std::size_t i = 0; i < model.num_cracks(); ++i)
    cracks.push_back(&model.crack(i));
  if (!cracks.empty())
  {
    sets.insert(sets.end(), cracks.begin(), cracks.end());
    names.insert(names.end(), {"w_s2", "crack", "crack_damage"});
  }
  const bool with_cracks = !cracks.empty();
  _interface = std::make_unique<JointWriter>(
      comm, sets, dof_x, names,
      [layers, with_cracks](const interface::PointOutput& o, std::size_t set)
      {
        std::vector<double> v = {o.t[0], o.t[1], o.t[2], o.w[0], o.w[1]};
        for (std::size_t l = 0; l < layers; ++l)
          if (set == 0)
            v.insert(v.end(), {o.slip[l][0], o.slip[l][1], o.damage[l]});
          else // a crack plane: no interface layers
            v.insert(v.end(), {0.0, 0.0, 0.0});
        if (with_cracks)
          v.insert(v.end(), {o.w[2], double(set) - 1, set == 0 ? 0.0 : o.damage[0]});
        return v;
      },
      dir / (prefix + "interface.xdmf"));
  if (cracks.empty())
    return;
  _h5.push_back(dir / (prefix + "cracks.h5"));
  // n is the crack's normal (opening), s1 axial, s2 radial.
  _cracks = std::make_unique<JointWriter>(
      comm, cracks, dof_x,
      std::vector<std::string>{"t_n", "t_s1", "t_s2", "w_n", "w_s1", "w_s2", "damage", "crack"},
      [](const interface::PointOutput& o, std::size_t crack)
      {
        return std::vector<double>{o.t[0], o.t[1], o.t[2],      o.w[0],
                                   o.w[1], o.w[2], o.damage[0], double(crack)};
      },
      dir / (prefix + "cracks.xdmf"));
}

FieldWriter::~FieldWriter()
{
  if (_open)
    try
    {
      close();
    }
    catch (const std::exception&) // an error on the way out, reported before
    {
    }
}

namespace
{
/// Runs every step (each a collective HDF5 call on all processes, so none
/// may be skipped because another failed), then rethrows the first error.
void all_of(std::initializer_list<std::function<void()>> steps)
{
  std::exception_ptr first;
  for (const auto& step : steps)
    try
    {
      step();
    }
    catch (...)
    {
      if (!first)
        first = std::current_exception();
    }
  if (first)
    std::rethrow_exception(first);
}
} // namespace

void FieldWriter::close()
{
  _open = false;
  all_of({[&] { xdmf_close(_fields, _fields_file); }, [&] { _interface->close(); },
          [&]
          {
            if (_cracks)
              _cracks->close();
          }});
}

std::uintmax_t FieldWriter::data_bytes() const
{
  std::uintmax_t total = 0;
  for (const std::filesystem::path& f : _h5)
  {
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(f, ec);
    total += ec ? 0 : size;
  }
  return total;
}

void FieldWriter::check_room()
{
  // HDF5 that meets a full disk leaves its files in a state that cannot be
  // closed (nor ended at MPI_Finalize): a step is written only where it
  // fits, with room to close the files after it. A step takes about what
  // the last one took; the first, about the mesh (the nodes' displacement
  // as their coordinates, the cells' stress as their connectivity).
  constexpr std::uintmax_t margin = 128 * 1024; // closing, the XML files [B]
  int rank = 0;
  MPI_Comm_rank(_model.comm(), &rank);
  bool full = false;
  std::uintmax_t now = 0;
  if (rank == 0)
  {
    now = data_bytes();
    const std::uintmax_t step = _bytes_before > 0 ? now - std::min(now, _bytes_before) : now;
    struct statvfs fs;
    if (::statvfs(_dir.c_str(), &fs) == 0)
      full = std::uintmax_t(fs.f_bavail) * fs.f_frsize < 2 * step + margin;
  }
  _bytes_before = now;
  mpi::throw_if_any(_model.comm(), full, cannot_write(_fields_file));
}

void FieldWriter::write(double t)
{
  check_room();
  if (_u1)
    _u1->interpolate(_model.displacement());
  const auto& stress = _stress.update();
  if (const model::BulkCracking* cracking = _model.bulk_cracking())
    cracking->cell_fields(*_crack_opening, *_crack_normal, *_crack_damage);
  const std::span<const double> u = _model.displacement().x()->array();
  all_of({[&]
          {
            xdmf_checked(
                _fields, _fields_file,
                [&](XdmfSeries& f)
                {
                  f.write(_u1 ? *_u1 : _model.displacement(), t);
                  f.write(stress, t);
                  if (_crack_opening)
                    for (const auto& field : {_crack_opening, _crack_normal, _crack_damage})
                      f.write(*field, t);
                  f.save();
                });
          },
          [&] { _interface->write(u, t); },
          [&]
          {
            if (_cracks)
              _cracks->write(u, t);
          }});
  // The step on disk: readable if the run is killed before it closes them.
  mpi::throw_if_any(_model.comm(), !flush_hdf5_files(_h5), cannot_write(_fields_file));
}
} // namespace pushout::output

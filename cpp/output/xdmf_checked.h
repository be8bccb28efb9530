// Writing XDMF files (XdmfSeries, HDF5) with a failure, such as a full disk,
// as one clear error ("cannot write DIR/fields.xdmf (disk full?)"): HDF5
// prints no error stack, and a file that failed is given up (never closed
// again: its HDF5 handle is broken).
#pragma once

#include "../common/mpi_errors.h"
#include "OutputFiles.h"
#include "XdmfSeries.h"
#include <algorithm>
#include <cerrno>
#include <filesystem>
#include <hdf5.h>
#include <memory>
#include <stdexcept>
#include <vector>

namespace pushout::output
{
/// HDF5 reports errors through return codes alone (dolfinx turns them
/// into exceptions), without printing its error stack.
inline void silence_hdf5()
{
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

/// cannot_write() of the XDMF file `xdmf` or of its data (the .h5 beside
/// it), naming the one a folder stands in the way of; else a full disk.
inline std::string cannot_write_xdmf(const std::filesystem::path& xdmf)
{
  for (const std::filesystem::path& f :
       {xdmf, std::filesystem::path(xdmf).replace_extension(".h5")})
    if (std::filesystem::is_directory(f))
      return cannot_write(f, EISDIR);
  return cannot_write(xdmf);
}

/// Runs f(*file) and agrees on its outcome over the file's processes: if it
/// threw on any, the file is given up there and the error is
/// cannot_write_xdmf(`name`) on all; so it is if the XML the first process
/// wrote is no file there. Collective where f
/// is.
template <class F>
void xdmf_checked(std::unique_ptr<XdmfSeries>& file, const std::filesystem::path& name, F&& f)
{
  if (!file) // given up before, on every process (agreed then)
    throw std::runtime_error(cannot_write_xdmf(name));
  const MPI_Comm comm = file->comm();
  bool failed = false;
  try
  {
    f(*file);
  }
  catch (...)
  {
    (void)file.release(); // its HDF5 handle is broken: never closed again
    failed = true;
  }
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  failed = failed || (rank == 0 && !std::filesystem::is_regular_file(name));
  mpi::throw_if_any(comm, failed, failed ? cannot_write_xdmf(name) : "");
}

/// Flushes the HDF5 files `h5` (an XDMF file's data, by path), so that the
/// steps written so far can be read whatever ends the run: one killed under
/// mpirun gets no time to close its files, and HDF5 files never flushed
/// could not be opened at all. Only these: a file given up after an error
/// (xdmf_checked) stays open in the process, and must not be flushed again.
/// False if one failed. Collective: each process flushes the same files in
/// `h5`'s order.
inline bool flush_hdf5_files(const std::vector<std::filesystem::path>& h5)
{
  const ssize_t n = H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_FILE);
  std::vector<hid_t> ids(static_cast<std::size_t>(std::max<ssize_t>(n, 0)));
  if (n > 0 &&
      H5Fget_obj_ids(H5F_OBJ_ALL, H5F_OBJ_FILE, static_cast<std::size_t>(n), ids.data()) != n)
    ids.clear();
  bool ok = true;
  for (const std::filesystem::path& file : h5)
  {
    bool found = false;
    for (const hid_t id : ids)
    {
      char name[4096] = {};
      if (H5Fget_name(id, name, sizeof name) > 0 &&
          std::filesystem::path(name).lexically_normal() == file.lexically_normal())
      {
        ok = H5Fflush(id, H5F_SCOPE_LOCAL) >= 0 && ok;
        found = true;
        break;
      }
    }
    ok = ok && found;
  }
  return ok;
}

/// Closes the file (collective); an error as xdmf_checked. A file given up
/// before is an error too.
inline void xdmf_close(std::unique_ptr<XdmfSeries>& file, const std::filesystem::path& name)
{
  xdmf_checked(file, name, [](XdmfSeries& f) { f.close(); });
  file.reset();
}
} // namespace pushout::output

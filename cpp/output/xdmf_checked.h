// Writing XDMF files (dolfinx::io::XDMFFile, HDF5) with a failure, such as a
// full disk, as one clear error ("cannot write DIR/fields.xdmf (disk
// full?)"): HDF5 prints no error stack, and a file that failed is given up
// (never closed again: XDMFFile's destructor would throw from its close,
// which ends the process).
#pragma once

#include "OutputFiles.h"
#include <dolfinx/io/XDMFFile.h>
#include <filesystem>
#include <hdf5.h>
#include <memory>
#include <stdexcept>

namespace pushout::output
{
/// HDF5 reports errors through return codes alone (dolfinx turns them
/// into exceptions), without printing its error stack.
inline void silence_hdf5()
{
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

/// Runs f(*file); if it throws, the file is given up and the error is
/// cannot_write(`name`). Collective where f is.
template <class F>
void xdmf_checked(std::unique_ptr<dolfinx::io::XDMFFile>& file, const std::filesystem::path& name,
                  F&& f)
{
  if (!file)
    throw std::runtime_error(cannot_write(name));
  try
  {
    f(*file);
  }
  catch (...)
  {
    (void)file.release(); // its HDF5 handle is broken: never closed again
    throw std::runtime_error(cannot_write(name));
  }
}

/// Closes the file (collective); an error as xdmf_checked. A file given up
/// before is an error too.
inline void xdmf_close(std::unique_ptr<dolfinx::io::XDMFFile>& file,
                       const std::filesystem::path& name)
{
  xdmf_checked(file, name, [](dolfinx::io::XDMFFile& f) { f.close(); });
  file.reset();
}
} // namespace pushout::output

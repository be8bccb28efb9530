// curve.csv (and corrosion.csv): a header, then one row per converged load
// step, written at once (one write(2) per row, no buffer) so that a run that
// stops later keeps every step it finished. A row is written whole or not at
// all: one that could not be (a full disk) is cut off the file again and is
// an error. One process writes it (rank 0, stepping/StepRecorder.cpp); the
// error is thrown there and the run agrees on it (common/mpi_errors.h).
#pragma once

#include "OutputFiles.h"
#include <cerrno>
#include <cmath>
#include <fcntl.h>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unistd.h>
#include <vector>

namespace pushout::output
{
class CurveWriter
{
public:
  CurveWriter(const std::filesystem::path& file, const std::vector<std::string>& columns)
      : _file(file)
  {
    _fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (_fd < 0)
      throw std::runtime_error(cannot_write(file, errno));
    std::string header = "step";
    for (const std::string& c : columns)
      header += "," + c;
    try
    {
      append(header + "\n");
    }
    catch (...)
    {
      ::close(_fd); // no destructor for a writer not made
      throw;
    }
  }
  ~CurveWriter()
  {
    if (_fd >= 0)
      ::close(_fd);
  }
  CurveWriter(const CurveWriter&) = delete;
  CurveWriter& operator=(const CurveWriter&) = delete;

  /// Writes a converged step's row; refuses a value that is not finite (a
  /// run stops before it writes one: record/NonFinite.h).
  void row(int step, const std::vector<double>& values)
  {
    for (double v : values)
      if (!std::isfinite(v))
        throw std::runtime_error("refusing to write a non-finite value to " + _file.string() +
                                 " as step " + std::to_string(step) + " of the curve");
    std::ostringstream line;
    line.precision(12);
    line << step;
    for (double v : values)
      line << "," << v;
    line << "\n";
    append(line.str());
  }

private:
  /// Appends `text` whole, or throws with the file as it was.
  void append(const std::string& text)
  {
    for (std::size_t done = 0; done < text.size();)
    {
      const ssize_t n = ::write(_fd, text.data() + done, text.size() - done);
      if (n < 0 && errno == EINTR)
        continue;
      if (n <= 0)
      {
        const int error = n < 0 ? errno : ENOSPC;
        if (::ftruncate(_fd, off_t(_size)) == 0) // the rows before stay whole
          ::lseek(_fd, off_t(_size), SEEK_SET);
        throw std::runtime_error(cannot_write(_file, error));
      }
      done += std::size_t(n);
    }
    _size += text.size();
  }

  std::filesystem::path _file;
  int _fd = -1;
  std::size_t _size = 0; ///< bytes of whole rows written [B]
};
} // namespace pushout::output

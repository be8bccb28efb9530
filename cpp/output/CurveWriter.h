// curve.csv: a header, then one row per converged load step, flushed at once
// so that a run that stops later keeps every step it finished. One process
// writes it (rank 0, driver/StepRecorder.cpp); a failure to write throws there and
// the run agrees on it (common/mpi_errors.h).
#pragma once

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <stdexcept>
#include <string>
#include <vector>

namespace pushout::output
{
class CurveWriter
{
public:
  CurveWriter(const std::filesystem::path& file, const std::vector<std::string>& columns)
      : _file(file)
  {
    _out.open(file);
    if (!_out)
      throw std::runtime_error("cannot write " + file.string());
    _out << "step";
    for (const std::string& c : columns)
      _out << "," << c;
    _out << "\n" << std::flush;
    _out << std::setprecision(12);
    if (!_out)
      throw std::runtime_error("cannot write " + file.string());
  }

  /// Writes a converged step's row; refuses a value that is not finite (a
  /// run stops before it writes one: driver/NonFinite.h).
  void row(int step, const std::vector<double>& values)
  {
    for (double v : values)
      if (!std::isfinite(v))
        throw std::runtime_error("refusing to write a non-finite value to " + _file.string() +
                                 " as step " + std::to_string(step) + " of the curve");
    _out << step;
    for (double v : values)
      _out << "," << v;
    _out << "\n" << std::flush;
    if (!_out)
      throw std::runtime_error("cannot write " + _file.string() + " (disk full?)");
  }

private:
  std::filesystem::path _file;
  std::ofstream _out;
};
} // namespace pushout::output

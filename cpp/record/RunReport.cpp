#include "RunReport.h"
#include "../common/mpi_errors.h"
#include "../output/OutputFiles.h"
#include "../output/plot.h"
#include <fstream>
#include <iostream>
#include <iterator>
#include <mpi.h>
#include <sys/resource.h>
#include <thread>

namespace pushout::record
{
std::string stage_progress(const std::string& stage, const output::Summary& s)
{
  if (stage == "step 0")
    return "in step 0";
  if (stage == "corrosion steps")
    return "after " + std::to_string(s.corrosion_steps) + " corrosion steps";
  if (stage == "meshing" || stage == "set-up")
    return ""; // no step yet
  // The load steps, or a later phase ("writing outputs"): after the
  // corrosion steps where no load step was taken.
  if (s.steps == 0 && s.corrosion_steps > 0)
    return "after " + std::to_string(s.corrosion_steps) + " corrosion steps";
  return "after " + std::to_string(s.steps) + " load steps";
}

double peak_memory_here_mb()
{
  rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;
}

namespace
{
/// Where a process other than rank 0 leaves the error it ends the run with
/// (RunReport::abandoned) for rank 0's stop report, which removes it; an
/// output of the folder (output::remove_outputs).
constexpr const char* process_error_file = ".process-error";

int rank_in(MPI_Comm comm)
{
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  return rank;
}
} // namespace

RunReport::RunReport(const Scene& scene, const std::filesystem::path& out, bool quiet,
                     MPI_Comm comm, bool plot)
    : _out(out), _comm(comm), _rank(rank_in(comm)), _talk(_rank == 0 && !quiet),
      _on_stop(
          [this](int sig, const std::string& phase)
          {
            std::lock_guard lock(_published_mutex);
            output::Summary s = _published;
            s.interrupted = true;
            s.converged = false;
            s.signal = sig;
            s.stopped_in = phase;
            std::string where = " during " + phase;
            if (const std::string progress = stage_progress(phase, s);
                phase != "step 0" && !progress.empty())
              where += ' ' + progress;
            s.message = "interrupted by " + interrupt::signal_name(sig) + where;
            stamp(s);
            if (_rank == 0 && take_process_error(s))
            {
              // (the failing process printed it: one message on stderr)
              try
              {
                s.write(_out / "summary.json");
              }
              catch (...)
              {
              }
              return;
            }
            if (_rank != 0)
            {
              // mpirun ends every process as soon as one has ended with an
              // error: rank 0, which writes summary.json, ends first.
              std::this_thread::sleep_for(std::chrono::milliseconds(300));
              return;
            }
            try
            {
              s.write(_out / "summary.json");
              std::cerr << "pushout: " << s.message << "; " << (_out / "summary.json").string()
                        << " says so" << std::endl;
            }
            catch (const std::exception& e)
            {
              std::cerr << "pushout: " << s.message << "; error: " << e.what() << std::endl;
            }
          }),
      _on_abandon([this](const std::string& message) { abandoned(message); })
{
  int size = 1;
  MPI_Comm_size(comm, &size);
  _summary.model_type = scene.model().name();
  if (scene.cracking().embedded)
  {
    _summary.cracking_integration = scene.cracking().implex ? "implex" : "implicit";
    _summary.implicit_step_error = scene.cracking().implicit_step_error_read();
    _summary.implicit_steps_held = scene.cracking().implicit_steps_held();
  }
  _summary.processes = size;
  _summary.run_id = output::run_id();
  // Agreed here: a failure on the first process alone would leave the
  // others in the run's collectives while it waits to agree.
  mpi::collectively(comm,
                    [&]
                    {
                      if (_rank == 0)
                        output::write_file(_out / "scene.toml", scene.to_toml());
                      if (_rank == 0 && plot && scene.output().plot)
                        _plotter.emplace();
                    });
  publish();
}

void RunReport::publish()
{
  output::Summary s = _summary;
  if (_counters)
    _counters(s);
  std::lock_guard lock(_published_mutex);
  _published = std::move(s);
}

double RunReport::seconds() const
{
  return std::chrono::duration<double>(Clock::now() - _start).count();
}

void RunReport::plot_also(const std::string& stem, const std::string& kind)
{
  _more_plots.push_back({stem, kind});
}

output::Summary RunReport::finish()
{
  // A stopped run draws nothing: it stops within the time a launcher gives
  // it (mpirun: 1 s before its SIGKILL), and curve.csv has the curve.
  if (_plotter && _summary.interrupted)
    _plotter.reset();
  if (_plotter)
  {
    _plotter->draw(_out / "curve.csv", _out / "curve.png", _summary.model_type);
    if (_summary.corrosion_steps > 0)
      _plotter->draw(_out / "corrosion.csv", _out / "corrosion.png", "corrosion");
    for (const auto& [stem, kind] : _more_plots)
      _plotter->draw(_out / (stem + ".csv"), _out / (stem + ".png"), kind);
    std::string why;
    if (!_plotter->finish(why))
      std::cerr << "pushout: warning: no curve.png"
                << (_summary.corrosion_steps > 0 ? " or corrosion.png" : "")
                << (_more_plots.empty() ? "" : " or " + _more_plots[0][0] + ".png") << ": " << why
                << std::endl;
    _plotter.reset();
  }
  _summary.wall_s = seconds();
  double peak_mb = peak_memory_here_mb();
  MPI_Allreduce(MPI_IN_PLACE, &peak_mb, 1, MPI_DOUBLE, MPI_MAX, _comm);
  _summary.peak_memory_mb = peak_mb;
  if (_rank == 0)
    _summary.write(_out / "summary.json");
  return _summary;
}

void RunReport::stamp(output::Summary& s) const
{
  s.wall_s = seconds();
  s.peak_memory_mb = peak_memory_here_mb();
}

void RunReport::save_stop() noexcept
{
  publish();
  if (_rank != 0)
    return;
  try
  {
    output::Summary s = _summary;
    if (_counters)
      _counters(s);
    stamp(s);
    s.write(_out / "summary.json");
  }
  catch (...) // finish() writes it again, and reports an error there
  {
  }
}

void RunReport::fail(const std::string& message) noexcept
{
  if (_rank != 0)
    return;
  try
  {
    _plotter.reset();
    output::Summary s = _summary;
    s.converged = false;
    s.message = message;
    stamp(s);
    s.write(_out / "summary.json");
  }
  catch (...) // no room for it either: the error line is what the user gets
  {
  }
}

void RunReport::abandoned(const std::string& message) noexcept
{
  // The run ends next (MPI_Abort): a SIGTERM from mpirun meanwhile must not
  // have the watcher write the signal over the error.
  interrupt::acknowledge();
  try
  {
    if (_rank != 0)
    {
      output::write_file(_out / process_error_file, message);
      return;
    }
    std::lock_guard lock(_published_mutex);
    output::Summary s = _published;
    s.converged = false;
    s.message = message;
    stamp(s);
    s.write(_out / "summary.json");
  }
  catch (...) // the error line on stderr is what the user gets
  {
  }
}

bool RunReport::take_process_error(output::Summary& s) const noexcept
{
  try
  {
    const std::filesystem::path file = _out / process_error_file;
    std::ifstream in(file);
    if (!in)
      return false;
    s.message.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    s.interrupted = false;
    s.signal = 0;
    s.stopped_in.clear();
    std::error_code ignored;
    std::filesystem::remove(file, ignored);
    return true;
  }
  catch (...) // (on the watcher's thread: the signal is reported instead)
  {
    return false;
  }
}
} // namespace pushout::record

#include "OutputFiles.h"
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <iomanip>
#include <random>
#include <regex>
#include <sstream>
#include <sys/file.h>
#include <unistd.h>

namespace pushout::output
{
namespace
{
namespace fs = std::filesystem;

/// The files pushout writes in an output folder (and in the folders below
/// it that it makes: a sweep's cases, a fit's runs).
/// (.process-error: record/RunReport.cpp's hand-over of an error between
/// processes.)
bool is_output_file(const std::string& name)
{
  static const char* const names[] = {
      "curve.csv",         "curve.png",         "corrosion.csv",       "corrosion.png",
      "summary.json",      "scene.toml",        "fields.xdmf",         "fields.h5",
      "interface.xdmf",    "interface.h5",      "cracks.xdmf",         "cracks.h5",
      "sweep.csv",         "sweep.png",         "sweep_seeds.csv",     "fit.json",
      "fit.csv",           "fit.png",           ".pushout-write-test", "summary.json.tmp",
      "crack_pattern.csv", "crack_pattern.png", "crack_planes.csv",    ".process-error"};
  for (const char* n : names)
    if (name == n)
      return true;
  // The corrosion stage's fields (output::FieldWriter's "corrosion_" files).
  for (const char* n : {"fields", "interface", "cracks"})
    for (const char* ext : {".xdmf", ".h5"})
      if (name == std::string("corrosion_") + n + ext)
        return true;
  return name.starts_with(".") && name.ends_with(".pushout-tmp"); // write_file's
}

/// The folders pushout makes below an output folder.
bool is_output_folder(const std::string& name, bool top)
{
  static const std::regex case_folder("case_[0-9]{3,}"), group_folder("group_[0-9]+");
  if (top)
    return std::regex_match(name, case_folder) || name == "best" || name == ".runs";
  return std::regex_match(name, group_folder);
}

/// Removes pushout's outputs from `dir`, and the folders it made there once
/// nothing else is left in them.
void clean(const fs::path& dir, bool top)
{
  std::vector<fs::path> files, folders;
  for (const fs::directory_entry& e : fs::directory_iterator(dir))
  {
    const std::string name = e.path().filename().string();
    if (e.is_directory() && !e.is_symlink() && is_output_folder(name, top))
      folders.push_back(e.path());
    else if (!e.is_directory() && is_output_file(name))
      files.push_back(e.path());
  }
  for (const fs::path& f : files)
    fs::remove(f);
  for (const fs::path& f : folders)
  {
    clean(f, false);
    if (fs::is_empty(f))
      fs::remove(f);
  }
}

/// Whether `rel` (a path inside an output folder) names a file pushout
/// writes there.
bool is_output_path(const fs::path& rel)
{
  std::vector<std::string> parts;
  for (const fs::path& p : rel)
    parts.push_back(p.string());
  if (parts.empty() || parts.front() == ".." || !is_output_file(parts.back()))
    return false;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i)
    if (!is_output_folder(parts[i], i == 0))
      return false;
  return true;
}

/// Takes the folder's lock for the rest of the process (its descriptor is
/// never closed); throws FolderError if another process holds it.
void lock(const fs::path& dir)
{
  const fs::path file = dir / ".pushout.lock";
  const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  if (fd < 0)
    throw FolderError("--out '" + dir.string() + "': cannot create or write this folder (" +
                      file.filename().string() + ": " + std::strerror(errno) + ")");
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0)
  {
    if (errno != EWOULDBLOCK)
    {
      ::close(fd);
      return; // a file system without locks: the folder is not guarded
    }
    char pid[32] = {};
    const ssize_t n = ::pread(fd, pid, sizeof(pid) - 1, 0);
    ::close(fd);
    std::string holder = n > 0 ? std::string(pid, std::size_t(n)) : "";
    while (!holder.empty() && (holder.back() == '\n' || holder.back() == ' '))
      holder.pop_back();
    throw FolderError(dir.string() + " is in use by another pushout run (pid " +
                      (holder.empty() ? "unknown" : holder) + ")");
  }
  const std::string pid = std::to_string(::getpid()) + "\n";
  // The pid only names the holder in the message above: not writing it
  // (a full disk) leaves the lock held all the same.
  if (::ftruncate(fd, 0) == 0 && ::pwrite(fd, pid.data(), pid.size(), 0) < 0)
    errno = 0;
}
} // namespace

std::string cannot_write(const fs::path& file, int error)
{
  const bool full = error == ENOSPC || error == EDQUOT;
  return "cannot write " + file.string() + " (" + (full ? "disk full?" : std::strerror(error)) +
         ")";
}

void write_file(const fs::path& file, const std::string& text)
{
  // A name of this writer's own: two threads (the stop report of
  // common/Interrupt.h and the step loop) may write one file at once.
  static std::atomic<unsigned> writes{0};
  std::ostringstream name;
  name << "." << file.filename().string() << "." << ::getpid() << "." << writes++ << ".pushout-tmp";
  const fs::path tmp = file.parent_path() / name.str();
  int error = 0; // errno of the first call that failed
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0)
    error = errno;
  for (std::size_t done = 0; error == 0 && done < text.size();)
  {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR)
      continue;
    if (n <= 0)
      error = n < 0 ? errno : ENOSPC; // a write of nothing: no room
    done += n > 0 ? std::size_t(n) : 0;
  }
  if (fd >= 0 && ::close(fd) != 0 && error == 0)
    error = errno;
  if (error == 0 && ::rename(tmp.c_str(), file.c_str()) == 0)
    return;
  if (error == 0)
    error = errno; // the rename's (the name is a folder, say)
  ::unlink(tmp.c_str());
  throw std::runtime_error(cannot_write(file, error));
}

void claim(const fs::path& dir, const std::vector<fs::path>& inputs)
{
  std::error_code ec;
  fs::create_directories(dir, ec);
  std::error_code status;
  if (fs::exists(dir, status) && !fs::is_directory(dir, status))
    throw FolderError("--out '" + dir.string() + "' is a file, not a folder: name another");
  // A symbolic link to nothing: create_directories says the name exists.
  if (fs::is_symlink(fs::symlink_status(dir, status)) && !fs::exists(dir, status))
    throw FolderError("--out '" + dir.string() + "' is a symbolic link to nothing (" +
                      fs::read_symlink(dir, status).string() +
                      "): name another, or make its target");
  if (ec || !fs::is_directory(dir, status))
    throw FolderError("--out '" + dir.string() + "': cannot create or write this folder (" +
                      (ec ? ec.message() : std::string("not a folder")) + ")");
  // Only a folder that a run of pushout has used (it leaves its lock file)
  // holds outputs to remove: a folder of the user's own keeps its files,
  // whatever their names.
  const bool used_before = fs::exists(dir / ".pushout.lock");
  const fs::path home = fs::canonical(dir);
  for (const fs::path& input : inputs)
    if (!input.empty() && fs::exists(input) &&
        is_output_path(fs::weakly_canonical(input).lexically_relative(home)))
      throw FolderError(input.string() + " is an output of pushout in " + dir.string() +
                        " and would be overwritten: copy it elsewhere, or choose another --out");
  lock(dir);
  if (used_before)
    clean(dir, true);
}

void remove_outputs(const fs::path& dir)
{
  if (!fs::is_directory(dir))
    return;
  clean(dir, false);
  if (fs::is_empty(dir))
    fs::remove(dir);
}

namespace
{
std::string& the_run_id()
{
  static std::string id = []
  {
    std::random_device random;
    std::ostringstream s;
    s << std::hex << std::setfill('0') << std::setw(8) << random() << std::setw(8) << random();
    return s.str();
  }();
  return id;
}
} // namespace

const std::string& run_id()
{
  return the_run_id();
}

void share_run_id(MPI_Comm comm)
{
  std::string& id = the_run_id();
  int length = int(id.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, comm);
  id.resize(std::size_t(length));
  MPI_Bcast(id.data(), length, MPI_CHAR, 0, comm);
}
} // namespace pushout::output

// Errors under MPI: a condition found on one process becomes the
// same clear error on every process (agree, then throw), so that no process
// is left waiting in a collective that the failing one skipped, and rank 0
// alone prints it.
//
// Every agreement is the same two steps on a channel of its own (a
// duplicate of the run's processes, MPI_COMM_WORLD unless `pushout sweep`
// split them into groups: set_run_processes): MPI_Iallreduce of the lowest
// failing rank, then, if one failed, MPI_Bcast of its message and kind from
// it. An agreement therefore never matches another collective of the
// program, and a process that failed meets the others at their next
// agreement, wherever in the code that is:
//  - collectively(f) runs f on every process and agrees after it (a phase);
//    main() runs the whole run in one, so any exception anywhere is agreed;
//  - throw_if_any(comm, failed_here, message) agrees on a condition every
//    process checks at the same point; checkpoint() is the same with no
//    failure here (the step loop passes one per try).
// All processes then throw the same exception: an AgreedError, or the type
// collectively<Known...>() was told to keep (SceneError: exit code 2).
//
// A process that failed while the others wait in some other collective
// (one it skipped) would wait forever: it waits at most abandon_after_s
// for them, then reports its error (abandon_report: summary.json), prints
// it itself and ends the run with MPI_Abort. A failed process must reach
// its agreement before it destroys an object whose destruction is
// collective (a MUMPS factor: MUMPS ends with a broadcast), or it waits
// there instead: a phase that owns such objects agrees inside
// (driver/Run.cpp: the load steps; the SNES callbacks), and the run's
// errors are agreed on while its report lives (driver/Run.cpp,
// reporting_errors).
#pragma once

#include <chrono>
#include <cstdlib>
#include <exception>
#include <functional>
#include <iostream>
#include <mpi.h>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <type_traits>

namespace pushout::mpi
{
/// Marks an exception that every process threw together: it is not agreed
/// on again on its way up.
class Agreed
{
public:
  virtual ~Agreed() = default;
};

/// An agreed error: the message of the lowest failing rank. `kind` (0: an
/// error of no particular type) is the index + 1 of the exception type in
/// the Known list of the collectively() that classified it.
class AgreedError : public std::runtime_error, public Agreed
{
public:
  AgreedError(const std::string& message, int kind = 0) : std::runtime_error(message), _kind(kind)
  {
  }
  int kind() const { return _kind; }

private:
  int _kind;
};

/// An agreed exception of type T (constructible from its message).
template <class T> class AgreedAs : public T, public Agreed
{
public:
  explicit AgreedAs(const std::string& message) : T(message) {}
};

/// How long a process that failed waits for the others to come to agree on
/// it before it ends the run (they may be waiting in a collective it
/// skipped) [s].
constexpr double abandon_after_s = 10;

/// What abandon() calls on the failing process before it ends the run,
/// with the error as it prints it (without "pushout: error: "); none if
/// empty. record::RunReport sets it, so that summary.json says the error
/// and not the SIGTERM that mpirun then sends the others.
using AbandonReport = std::function<void(const std::string& message)>;
inline AbandonReport& abandon_report()
{
  static AbandonReport report;
  return report;
}

/// Sets the abandon report until destroyed (then none).
class ReportOnAbandon
{
public:
  explicit ReportOnAbandon(AbandonReport report) { abandon_report() = std::move(report); }
  ~ReportOnAbandon() { abandon_report() = nullptr; }
  ReportOnAbandon(const ReportOnAbandon&) = delete;
  ReportOnAbandon& operator=(const ReportOnAbandon&) = delete;
};

namespace detail
{
/// The run's processes and the agreement channel, a duplicate of them
/// (made at the first agreement: main() makes it before the run).
struct Channel
{
  MPI_Comm processes = MPI_COMM_WORLD;
  MPI_Comm dup = MPI_COMM_NULL;
};
inline Channel& channel_state()
{
  static Channel c;
  return c;
}
inline MPI_Comm channel()
{
  Channel& c = channel_state();
  if (c.dup == MPI_COMM_NULL)
    MPI_Comm_dup(c.processes, &c.dup);
  return c.dup;
}

/// Whether `comm` has one process.
inline bool alone(MPI_Comm comm)
{
  int size = 1;
  MPI_Comm_size(comm, &size);
  return size == 1;
}

/// Ends the whole run from a process whose error the others did not come
/// to agree on.
[[noreturn]] inline void abandon(const std::string& message, int rank)
{
  std::ostringstream said;
  said << message << " (process " << rank
       << "; the other processes did not come to agree on it within " << abandon_after_s
       << " s, so the run is ended)";
  if (const AbandonReport& report = abandon_report())
    try
    {
      report(said.str());
    }
    catch (...) // the line on stderr is what the user gets
    {
    }
  // One write: mpirun prints its abort banner on the same stderr, and a
  // line written in pieces (std::cerr is unbuffered) was cut by it.
  std::cerr << "pushout: error: " + said.str() + "\n" << std::flush;
  MPI_Abort(MPI_COMM_WORLD, 1);
  std::abort();
}

/// The agreement: whether any process of `comm` failed. Returns -1 if none;
/// else the failing process's kind, with its message in `message`.
inline int agree(MPI_Comm comm, bool failed_here, int kind, std::string& message)
{
  if (alone(comm))
    return failed_here ? kind : -1;
  int result = MPI_UNEQUAL;
  MPI_Comm_compare(comm, channel_state().processes, &result);
  if (result != MPI_IDENT && result != MPI_CONGRUENT)
    throw std::logic_error("error agreement on a communicator of other processes than the run's");
  const MPI_Comm ch = channel();
  int rank = 0, size = 1;
  MPI_Comm_rank(ch, &rank);
  MPI_Comm_size(ch, &size);
  int mine = failed_here ? rank : size, first = size;
  MPI_Request request;
  MPI_Iallreduce(&mine, &first, 1, MPI_INT, MPI_MIN, ch, &request);
  if (!failed_here)
    MPI_Wait(&request, MPI_STATUS_IGNORE);
  else
  {
    const auto t0 = std::chrono::steady_clock::now();
    for (int done = 0; !done;)
    {
      MPI_Test(&request, &done, MPI_STATUS_IGNORE);
      if (!done && std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() >
                       abandon_after_s)
        abandon(message, rank);
      if (!done)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }
  if (first == size)
    return -1;
  long long header[2] = {kind, static_cast<long long>(message.size())};
  MPI_Bcast(header, 2, MPI_LONG_LONG, first, ch);
  message.resize(std::size_t(header[1]));
  MPI_Bcast(message.data(), int(header[1]), MPI_CHAR, first, ch);
  return int(header[0]);
}

/// The message of any exception.
inline std::string describe(const std::exception_ptr& e)
{
  try
  {
    std::rethrow_exception(e);
  }
  catch (const std::exception& x)
  {
    return x.what();
  }
  catch (const std::string& s) // gmsh reports errors this way
  {
    return s;
  }
  catch (const char* s)
  {
    return s;
  }
  catch (...)
  {
    return "unknown error";
  }
}

template <class T> bool is_a(const std::exception_ptr& e)
{
  try
  {
    std::rethrow_exception(e);
  }
  catch (const T&)
  {
    return true;
  }
  catch (...)
  {
    return false;
  }
}

/// Index + 1 of the first of Known that `e` is (0: none).
template <class... Known> int kind_of(const std::exception_ptr& e)
{
  int kind = 0;
  [[maybe_unused]] int i = 0;
  ((++i, kind = kind == 0 && is_a<Known>(e) ? i : kind), ...);
  return kind;
}

/// Throws the agreed exception of `kind` (as kind_of<Known...>).
template <class... Known> [[noreturn]] void throw_agreed(int kind, const std::string& message)
{
  [[maybe_unused]] int i = 0;
  ((++i == kind ? throw AgreedAs<Known>(message) : void()), ...);
  throw AgreedError(message, kind);
}
} // namespace detail

/// The processes the runs of this process agree with from now on (a group
/// of `pushout sweep`; collective on them): agreements on communicators of
/// other processes are a logic error. `processes` must outlive them.
inline void set_run_processes(MPI_Comm processes)
{
  detail::Channel& c = detail::channel_state();
  if (c.dup != MPI_COMM_NULL)
    MPI_Comm_free(&c.dup);
  c.processes = processes;
  MPI_Comm_dup(processes, &c.dup);
}

/// Collective on comm: if `failed_here` on any process, every process
/// throws AgreedError with the message of the lowest failing rank.
inline void throw_if_any(MPI_Comm comm, bool failed_here, const std::string& message)
{
  std::string m = message;
  if (const int kind = detail::agree(comm, failed_here, 0, m); kind >= 0)
    throw AgreedError(m, kind);
}

/// Collective on comm: throws here the error of a process that failed since
/// the last agreement (and is waiting in collectively() to agree on it).
inline void checkpoint(MPI_Comm comm)
{
  throw_if_any(comm, false, "");
}

/// Whether `ok` holds on every process of comm (collective; not an
/// agreement on errors).
inline bool all(MPI_Comm comm, bool ok)
{
  int local = ok ? 1 : 0, global = 0;
  MPI_Allreduce(&local, &global, 1, MPI_INT, MPI_MIN, comm);
  return global == 1;
}

/// Runs f() on every process of comm and agrees on the outcome: if it threw
/// anywhere, every process throws the same exception (the lowest failing
/// rank's message) as AgreedAs<T> for the first T of Known it is, else as
/// AgreedError. Use the same Known list at every level of nesting.
template <class... Known, class F> auto collectively(MPI_Comm comm, F&& f) -> decltype(f())
{
  using R = decltype(f());
  detail::channel(); // made here, where every process is
  std::conditional_t<std::is_void_v<R>, bool, std::optional<R>> result{};
  std::string message;
  int kind = 0;
  bool failed = false;
  try
  {
    if constexpr (std::is_void_v<R>)
      f();
    else
      result.emplace(f());
  }
  catch (const AgreedError& e) // agreed in f, where its type was not known
  {
    detail::throw_agreed<Known...>(e.kind(), e.what());
  }
  catch (const Agreed&)
  {
    throw;
  }
  catch (...)
  {
    failed = true;
    message = detail::describe(std::current_exception());
    kind = detail::kind_of<Known...>(std::current_exception());
  }
  if (const int k = detail::agree(comm, failed, kind, message); k >= 0)
    detail::throw_agreed<Known...>(k, message);
  if constexpr (!std::is_void_v<R>)
    return std::move(*result);
}
} // namespace pushout::mpi

// Checked PETSc calls: every PETSc call in pushout goes through
// check(), which turns a non-zero PETSc error code into a C++ exception that
// names the call, PETSc's error text and where the call is:
//
//   check(MatLUFactorNumeric(F, A, &info), "MatLUFactorNumeric");
//   -> "PETSc: MatLUFactorNumeric failed: <PETSc's message> (<error class>,
//       error 71) [solver/Condensation.cpp:180]"
//
// PETSc itself prints nothing (main() installs PetscReturnErrorHandler): the
// message reaches the user once, through the exception, on rank 0.
//
// C++ exceptions must never cross PETSc's C frames. The body of every
// callback PETSc calls (SNES function and Jacobian, convergence tests,
// MatShell operations) runs inside callback(): an exception there is kept,
// PETSc unwinds with an error code, and the exception resumes, unchanged, at
// the check() of the PETSc call that ran the callback (SNESSolve, KSPSolve,
// MatMult, ...).
#pragma once

#include <exception>
#include <iostream>
#include <petscsys.h>
#include <source_location>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

namespace pushout::petsc
{
/// A PETSc call that returned an error code.
class Error : public std::runtime_error
{
public:
  Error(PetscErrorCode code, const std::string& message) : std::runtime_error(message), _code(code)
  {
  }
  /// PETSc's error code (PETSC_ERR_MAT_LU_ZRPVT, ...).
  PetscErrorCode code() const { return _code; }

private:
  PetscErrorCode _code;
};

namespace detail
{
/// The exception a callback caught while PETSc was running it (one thread
/// runs PETSc); check() throws it again.
inline thread_local std::exception_ptr pending;

/// A path from "cpp/" on ("solver/Condensation.cpp"), else as given.
inline std::string_view short_path(std::string_view file)
{
  const std::size_t at = file.rfind("cpp/");
  return at == std::string_view::npos ? file : file.substr(at + 4);
}

/// PETSc's specific message of the last error, on one line ("" if none).
inline std::string one_line(const char* text)
{
  std::string s = text ? text : "";
  for (char& c : s)
    if (c == '\n' || c == '\r')
      c = ' ';
  const std::size_t first = s.find_first_not_of(' ');
  if (first == std::string::npos)
    return "";
  return s.substr(first, s.find_last_not_of(' ') - first + 1);
}
} // namespace detail

/// The message of a failed PETSc call (what check() throws).
inline std::string error_message(PetscErrorCode code, std::string_view call,
                                 const std::source_location& where)
{
  const char* text = nullptr;
  char* specific = nullptr;
  PetscErrorMessage(int(code), &text, &specific);
  std::string m = "PETSc: " + std::string(call) + " failed";
  if (const std::string s = detail::one_line(specific); !s.empty())
    m += ": " + s;
  m += " (";
  if (const std::string t = detail::one_line(text); !t.empty())
    m += t + ", ";
  m += "error " + std::to_string(int(code)) + ") [" +
       std::string(detail::short_path(where.file_name())) + ":" + std::to_string(where.line()) +
       "]";
  return m;
}

/// Throws petsc::Error naming `call` unless `code` is 0; if a callback run
/// by the call threw (callback()), that exception instead.
inline void check(PetscErrorCode code, std::string_view call,
                  const std::source_location& where = std::source_location::current())
{
  if (code == 0)
    return;
  if (detail::pending)
    std::rethrow_exception(std::exchange(detail::pending, nullptr));
  throw Error(code, error_message(code, call, where));
}

/// For destructors (and PetscFinalize), which must not throw: a failed call
/// is reported on stderr as a warning (a failed destroy means corrupted
/// memory; the run goes on to its end or its error).
inline void check_nothrow(PetscErrorCode code, std::string_view call,
                          const std::source_location& where = std::source_location::current())
{
  if (code != 0)
    std::cerr << "pushout: warning: " << error_message(code, call, where) << std::endl;
}

/// Whether a callback threw in the PETSc call that just returned (its
/// exception waits for check()).
inline bool callback_failed()
{
  return bool(detail::pending);
}

/// Runs the body `f` of a PETSc callback: returns 0, or, if f threw, a
/// PETSc error code (PETSC_ERR_LIB) after keeping the exception for the
/// check() of the PETSc call that ran the callback.
template <class F> PetscErrorCode callback(F&& f) noexcept
{
  try
  {
    f();
    return 0;
  }
  catch (...)
  {
    detail::pending = std::current_exception();
    return PetscError(PETSC_COMM_SELF, __LINE__, "pushout callback", __FILE__, PETSC_ERR_LIB,
                      PETSC_ERROR_INITIAL, "an exception in a pushout callback");
  }
}
} // namespace pushout::petsc

// Test hooks (TestHooks.h): environment variables read once, on first use.
#include "TestHooks.h"
#include <chrono>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <thread>

namespace pushout::stepping
{
namespace
{
/// From the third load step on (`steps` >= 2 done), each step spends
/// PUSHOUT_TEST_SLOW_STEP_S seconds.
void test_slow_step(int steps)
{
  static const char* slow_s = std::getenv("PUSHOUT_TEST_SLOW_STEP_S");
  if (slow_s && steps >= 2)
    std::this_thread::sleep_for(std::chrono::duration<double>(std::atof(slow_s)));
}

/// Throws on process PUSHOUT_TEST_FAIL_RANK alone if PUSHOUT_TEST_FAIL_AT
/// is `at`.
void test_failure(const char* at, MPI_Comm comm)
{
  static const char* fail_rank = std::getenv("PUSHOUT_TEST_FAIL_RANK");
  static const char* fail_at = std::getenv("PUSHOUT_TEST_FAIL_AT");
  if (!fail_rank || !fail_at || std::string(fail_at) != at)
    return;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == std::atoi(fail_rank))
    throw std::runtime_error(std::string("test failure on process ") + fail_rank + " at " + at +
                             " (PUSHOUT_TEST_FAIL_AT)");
}
} // namespace

void test_failure_at_setup(MPI_Comm comm)
{
  test_failure("setup", comm);
}

void test_failure_in_setup(MPI_Comm comm)
{
  test_failure("setup_collective", comm);
}

void test_hooks_before_agreement(int steps, MPI_Comm comm)
{
  test_slow_step(steps);
  if (steps == 2)
    test_failure("step", comm);
}

void test_hooks_after_agreement(int steps, MPI_Comm comm)
{
  if (steps == 2)
    test_failure("collective", comm);
}

bool test_no_prediction_reference()
{
  static const bool set = std::getenv("PUSHOUT_TEST_NO_PREDICTION_REFERENCE") != nullptr;
  return set;
}

bool test_no_step_prediction()
{
  static const bool set = std::getenv("PUSHOUT_TEST_NO_STEP_PREDICTION") != nullptr;
  return set;
}

bool test_fail_step_to_final()
{
  static const char* n = std::getenv("PUSHOUT_TEST_FAIL_TO_FINAL");
  static long failed = 0;
  if (!n || failed >= std::atol(n))
    return false;
  ++failed;
  return true;
}

bool test_fail_crack_band_update()
{
  static const bool set = std::getenv("PUSHOUT_TEST_FAIL_CRACK_BAND_UPDATE") != nullptr;
  return set;
}

bool test_fail_implicit_row(int rows)
{
  static const char* n = std::getenv("PUSHOUT_TEST_FAIL_IMPLICIT_ROW");
  return n && std::atoi(n) == rows;
}

bool test_energy_overshoots()
{
  static const bool set = std::getenv("PUSHOUT_TEST_ENERGY_OVERSHOOTS") != nullptr;
  return set;
}
} // namespace pushout::stepping

// GoogleTest main with PETSc/MPI initialised (the Jacobian test assembles).
#include <cstdio>
#include <dolfinx/common/log.h>
#include <gtest/gtest.h>
#include <mpi.h>
#include <petscsys.h>

namespace
{
/// On several processes, a fatal failure (ASSERT_*) ends the whole run at
/// once. The failing process leaves its test while the others wait in that
/// test's next collective call, which would hang the run instead of failing
/// it. A non-fatal failure (EXPECT_*) does not change the control flow, and
/// is reported as usual.
class AbortOnFatalFailure : public ::testing::EmptyTestEventListener
{
  void OnTestPartResult(const ::testing::TestPartResult& result) override
  {
    if (!result.fatally_failed())
      return;
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    std::fprintf(stderr,
                 "[rank %d] fatal failure at %s:%d; aborting every process, as the others would "
                 "wait for this one:\n%s\n",
                 rank, result.file_name() ? result.file_name() : "?", result.line_number(),
                 result.summary());
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
};
} // namespace

int main(int argc, char** argv)
{
  ::testing::InitGoogleTest(&argc, argv);
  PetscInitializeNoArguments();
  loguru::g_stderr_verbosity = loguru::Verbosity_WARNING;
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size > 1) // GoogleTest owns the listener
    ::testing::UnitTest::GetInstance()->listeners().Append(new AbortOnFatalFailure);
  const int rc = RUN_ALL_TESTS();
  PetscFinalize();
  return rc;
}

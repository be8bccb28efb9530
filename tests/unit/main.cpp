// GoogleTest main with PETSc/MPI initialised (the Jacobian test assembles).
#include <dolfinx/common/log.h>
#include <gtest/gtest.h>
#include <petscsys.h>

int main(int argc, char** argv)
{
  ::testing::InitGoogleTest(&argc, argv);
  PetscInitializeNoArguments();
  loguru::g_stderr_verbosity = loguru::Verbosity_WARNING;
  const int rc = RUN_ALL_TESTS();
  PetscFinalize();
  return rc;
}

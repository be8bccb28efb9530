// How a command ends when its work throws: one line on rank 0 and the exit
// code of the table (common/exit_codes.h). Used by run, sweep and fit alike.
#pragma once

#include "../common/exit_codes.h"
#include "../output/OutputFiles.h"
#include "../record/ResourceGuard.h"
#include "../scene/SceneError.h"
#include <iostream>
#include <mpi.h>
#include <string>

namespace pushout::driver
{
/// Runs `f` (returns an exit code; collective, its errors agreed on every
/// process: common/mpi_errors.h) and, if it throws, prints one line on rank
/// 0, `who: error: ...`, and returns exit_code::bad_input for a bad scene or
/// option (SceneError), a run the machine cannot hold (TooLarge) or an
/// output folder that cannot be used (FolderError), else exit_code::failure.
/// `scene_label`: how a SceneError is named ("error in scene" where the
/// scene is the command's only input; "error" where its options throw it
/// too); an OptionError is an "error" always.
template <class F> int exit_code_of(const std::string& who, const std::string& scene_label, F&& f)
{
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const auto say = [&](const std::string& label, const std::string& what, int code)
  {
    if (rank == 0)
      std::cerr << who << ": " << label << ": " << what << std::endl;
    return code;
  };
  try
  {
    return f();
  }
  catch (const OptionError& e) // before SceneError, which it is
  {
    return say("error", e.what(), exit_code::bad_input);
  }
  catch (const SceneError& e)
  {
    return say(scene_label, e.what(), exit_code::bad_input);
  }
  catch (const record::TooLarge& e)
  {
    return say("error", e.what(), exit_code::bad_input);
  }
  catch (const output::FolderError& e)
  {
    return say("error", e.what(), exit_code::bad_input);
  }
  catch (const std::exception& e)
  {
    return say("error", e.what(), exit_code::failure);
  }
  catch (const std::string& e) // gmsh reports errors this way
  {
    return say("error", e, exit_code::failure);
  }
}
} // namespace pushout::driver

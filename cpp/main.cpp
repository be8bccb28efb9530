// pushout: push-out tests of reinforced-concrete slices with cohesive-
// frictional interface elements (Sanz, Planas, Sancho).
//
//   pushout run SCENE.toml --out DIR [--set key=value]... [PETSc options]
//   pushout fit SCENE.toml --data measured.csv --free key [--free ...] --out DIR
//              [--bounds key=lo:hi]... [--set key=value]... [--ranks-per-case N]
//   pushout sweep SCENE.toml --vary key=v1,v2,... [--vary ...] --out DIR
//                [--set key=value]... [--ranks-per-case N] [PETSc options]
//   pushout keys        # the scene keys, with defaults, units and docs
//   pushout laws        # the interface laws and their parameters
#include "common/Interrupt.h"
#include "common/exit_codes.h"
#include "common/mpi_errors.h"
#include "common/mpi_start.h"
#include "common/petsc_check.h"
#include "driver/Fit.h"
#include "driver/ResourceGuard.h"
#include "driver/Run.h"
#include "driver/Sweep.h"
#include "mesh/generate.h"
#include "output/OutputFiles.h"
#include "scene/SceneError.h"
#include <CLI/CLI.hpp>
#include <dolfinx/common/log.h>
#include <filesystem>
#include <iostream>
#include <petscsys.h>

namespace
{
void print_keys()
{
  using namespace pushout;
  std::cout << "| key | type | default | unit | meaning |\n|---|---|---|---|---|\n";
  for (const KeyDef& k : scene_keys())
  {
    std::string doc = k.doc;
    if (!k.choices.empty())
    {
      doc += " (";
      for (std::size_t i = 0; i < k.choices.size(); ++i)
        doc += (i ? ", " : "") + k.choices[i];
      doc += ")";
    }
    std::cout << "| `" << k.path << "` | " << type_name(k.type) << " | `"
              << to_toml(k.default_value) << "` | " << k.unit << " | " << doc << " |\n";
  }
}

void print_laws()
{
  for (const auto& law : pushout::laws::registered_laws())
  {
    std::cout << "law = \"" << law.name << "\": " << law.doc << "\n";
    for (const auto& p : law.params)
    {
      std::cout << "    " << p.name << " [" << p.unit << "] " << p.doc;
      if (p.default_value)
        std::cout << " (default " << *p.default_value << ")";
      else if (!p.default_from.empty())
        std::cout << " (default: " << p.default_from << ")";
      else if (p.optional)
        std::cout << " (optional)";
      else
        std::cout << " (required)";
      std::cout << "\n";
    }
  }
}

/// The scene file with the --set overrides applied.
pushout::Scene load_scene(const std::string& scene_file, const std::vector<std::string>& sets)
{
  return pushout::Scene::load(scene_file, pushout::parse_overrides(sets));
}

/// Creates the output folder and writes a file there (rank 0 only: the
/// others learn the outcome collectively).
void probe_output_folder(const std::string& out)
{
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  const std::filesystem::path probe = std::filesystem::path(out) / ".pushout-write-test";
  if (ec || !std::ofstream(probe))
    throw pushout::SceneError("--out '" + out + "': cannot create or write this folder");
  std::filesystem::remove(probe);
}

/// Runs a scene; returns the process exit code.
int run_scene(const std::string& scene_file, const std::string& out,
              const std::vector<std::string>& sets, bool quiet, bool force)
{
  using namespace pushout;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  try
  {
    // Each phase is agreed on by all processes (common/mpi_errors.h): an
    // error on any one is the same error on all, printed once (rank 0).
    const Scene scene =
        mpi::collectively<SceneError>(MPI_COMM_WORLD, [&] { return load_scene(scene_file, sets); });
    // The folder is this run's alone, without an earlier run's outputs
    // (output/OutputFiles.h).
    mpi::collectively<SceneError, output::FolderError>(MPI_COMM_WORLD,
                                                       [&]
                                                       {
                                                         if (rank != 0)
                                                           return;
                                                         probe_output_folder(out);
                                                         output::claim(out, {scene_file});
                                                       });
    const driver::RunOptions options{out, pushout::mesh::default_cache_dir(), quiet, force};
    const output::Summary s = mpi::collectively<SceneError, driver::TooLarge>(
        MPI_COMM_WORLD, [&] { return driver::run(scene, options); });
    if (s.interrupted)
    {
      if (rank == 0)
        std::cerr << "pushout: " << s.message << "; " << out << "/curve.csv keeps them"
                  << std::endl;
      return exit_code::signal(s.signal);
    }
    if (!s.converged)
    {
      if (rank == 0)
        std::cerr << "pushout: error: " << s.message << "; " << out << "/curve.csv keeps the "
                  << s.steps << " converged steps" << std::endl;
      return exit_code::not_converged;
    }
    if (rank == 0 && !quiet)
      std::cout << "pushout: done in " << std::fixed << std::setprecision(2) << s.wall_s << " s, "
                << s.newton_iterations << " Newton iterations; curve: " << out << "/curve.csv"
                << (scene.boolean("output.plot") ? ", plot: " + out + "/curve.png" : "")
                << std::endl;
    return exit_code::done;
  }
  catch (const driver::TooLarge& e)
  {
    if (rank == 0)
      std::cerr << "pushout: error: " << e.what() << std::endl;
    return exit_code::bad_input;
  }
  catch (const output::FolderError& e)
  {
    if (rank == 0)
      std::cerr << "pushout: error: " << e.what() << std::endl;
    return exit_code::bad_input;
  }
  catch (const SceneError& e)
  {
    if (rank == 0)
      std::cerr << "pushout: error in scene: " << e.what() << std::endl;
    return exit_code::bad_input;
  }
  catch (const std::exception& e)
  {
    if (rank == 0)
      std::cerr << "pushout: error: " << e.what() << std::endl;
    return exit_code::failure;
  }
  catch (const std::string& e) // gmsh reports errors this way
  {
    if (rank == 0)
      std::cerr << "pushout: error: " << e << std::endl;
    return exit_code::failure;
  }
}
} // namespace

int main(int argc, char* argv[])
{
  CLI::App app{"pushout: push-out tests of RC slices with cohesive-frictional interfaces"};
  app.require_subcommand(1);
  app.allow_extras(); // the rest goes to PETSc
  std::string scene_file, out;
  std::vector<std::string> sets;
  bool quiet = false, force = false;
  // The scene, the output folder, the overrides and the flags every command
  // that runs takes; `ranks`: --ranks-per-case, for those that make many runs.
  const auto common = [&](CLI::App* cmd, const std::string& scene_doc, int* ranks)
  {
    cmd->add_option("scene", scene_file, scene_doc)->required();
    cmd->add_option("--out", out, "output folder")->required();
    cmd->add_option("--set", sets, "override a scene key: key=value (repeatable)");
    if (ranks)
      cmd->add_option("--ranks-per-case", *ranks,
                      "processes that run each model run together (default 1)");
    cmd->add_flag("--quiet", quiet, "no progress lines");
    cmd->add_flag("--force", force,
                  "run even if the size guard estimates a run cannot fit in memory");
    cmd->allow_extras();
  };
  CLI::App* run = app.add_subcommand("run", "run a scene");
  common(run, "scene file (TOML)", nullptr);
  pushout::driver::SweepOptions sweep_options;
  CLI::App* sweep = app.add_subcommand(
      "sweep", "run the Cartesian product of scene values, each case in DIR/case_NNN; under "
               "mpirun the processes share the cases (docs/sweeps.md)");
  common(sweep, "scene file (TOML)", &sweep_options.ranks_per_case);
  sweep
      ->add_option("--vary", sweep_options.vary, "a key and its values: key=v1,v2,... (repeatable)")
      ->required();
  pushout::driver::FitOptions fit_options;
  CLI::App* fit = app.add_subcommand(
      "fit", "fit scene values (law parameters, loads) to a measured push-out curve by least "
             "squares (PETSc TAO); DIR/fit.json has them with their standard errors "
             "(docs/fitting.md)");
  common(fit, "scene file (TOML): the start values", &fit_options.ranks_per_case);
  fit->add_option("--data", fit_options.data, "measured curve: CSV with delta_mm, tau_MPa")
      ->required();
  fit->add_option("--free", fit_options.free, "a scene key to fit (repeatable)")->required();
  fit->add_option("--bounds", fit_options.bounds,
                  "bounds of a free key: key=lo:hi (either may be empty; repeatable)");
  app.add_subcommand("keys", "print the scene keys (Markdown table)");
  app.add_subcommand("laws", "print the interface laws and their parameters");
  try
  {
    app.parse(argc, argv);
  }
  catch (const CLI::ParseError& e)
  {
    return app.exit(e);
  }
  if (app.got_subcommand("keys"))
  {
    print_keys();
    return 0;
  }
  if (app.got_subcommand("laws"))
  {
    print_laws();
    return 0;
  }

  // PETSc sees only the options CLI11 did not consume.
  std::vector<std::string> extras = app.got_subcommand("sweep") ? sweep->remaining()
                                    : app.got_subcommand("fit") ? fit->remaining()
                                                                : run->remaining();
  std::vector<char*> petsc_argv = {argv[0]};
  for (std::string& e : extras)
    petsc_argv.push_back(e.data());
  petsc_argv.push_back(nullptr);
  int petsc_argc = int(petsc_argv.size()) - 1;
  char** petsc_args = petsc_argv.data();
  pushout::mpi::prepare_singleton_start();
  try
  {
    pushout::petsc::check(PetscInitialize(&petsc_argc, &petsc_args, nullptr, nullptr),
                          "PetscInitialize");
    // PETSc prints nothing of an error: it reaches the user once, as the
    // exception of the checked call (common/petsc_check.h).
    pushout::petsc::check(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr),
                          "PetscPushErrorHandler");
  }
  catch (const std::exception& e)
  {
    std::cerr << "pushout: error: " << e.what() << std::endl;
    return 1;
  }
  // After PETSc, whose own handlers would otherwise abort on SIGTERM.
  pushout::interrupt::install();
  dolfinx::init_logging(1, argv);
  loguru::g_stderr_verbosity = loguru::Verbosity_WARNING;
  // What sweep and fit share, from the command line.
  const auto fill = [&](pushout::driver::ManyRunsOptions& o)
  {
    o.scene_file = scene_file;
    o.sets = sets;
    o.out = out;
    o.mesh_cache = pushout::mesh::default_cache_dir();
    o.quiet = quiet;
    o.force = force;
  };
  int rc = 0;
  try
  {
    if (app.got_subcommand("fit"))
    {
      fill(fit_options);
      rc = pushout::driver::fit(fit_options);
    }
    else if (app.got_subcommand("sweep"))
    {
      fill(sweep_options);
      rc = pushout::driver::sweep(sweep_options);
    }
    else
      rc = run_scene(scene_file, out, sets, quiet, force);
  }
  catch (const std::exception& e) // an error outside the runs of a sweep or fit
  {
    std::cerr << "pushout: error: " << e.what() << std::endl;
    MPI_Abort(MPI_COMM_WORLD, 1); // the other processes may wait in a collective
  }
  // The command has said how it ended: a signal that came meanwhile ends
  // nothing more.
  const pushout::interrupt::Phase ending("ending", -1);
  pushout::petsc::check_nothrow(PetscFinalize(), "PetscFinalize");
  return rc;
}

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
#include "common/mpi_gather.h"
#include "common/petsc_check.h"
#include "driver/MeshChecks.h"
#include "driver/PetscOptions.h"
#include "driver/Run.h"
#include "driver/exit_on_error.h"
#include "mesh/generate.h"
#include "output/OutputFiles.h"
#include "output/Summary.h"
#include "record/ResourceGuard.h"
#include "scene/SceneError.h"
#include "study/Fit.h"
#include "study/Sweep.h"
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <dolfinx/common/log.h>
#include <exception>
#include <filesystem>
#include <iostream>
#include <optional>
#include <petscsys.h>

namespace
{
/// The exit code of a command that printed its answer: 1, said, if
/// standard output did not take it all (a full disk; a closed pipe ends
/// the process with SIGPIPE first).
int printed()
{
  if (std::cout.flush())
    return pushout::exit_code::done;
  std::cerr << "pushout: error: cannot write to standard output (disk full?)" << std::endl;
  return pushout::exit_code::failure;
}

void print_keys()
{
  using namespace pushout;
  std::cout << "| key | type | default | unit | meaning |\n|---|---|---|---|---|\n";
  for (const KeyDef& k : scene_keys())
  {
    std::string doc = k.doc;
    if (std::isfinite(k.min) || std::isfinite(k.max))
      doc += " (" + range_text(k.min, k.max, k.open, k.type == KeyType::integer) + ")";
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
      if (std::isfinite(p.max))
        std::cout << " (at most " << p.max << ")";
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

/// Runs a scene; returns the process exit code.
int run_scene(const std::string& scene_file, const std::string& out,
              const std::vector<std::string>& sets, bool quiet, bool force)
{
  using namespace pushout;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return driver::exit_code_of(
      "pushout", "error in scene",
      [&]
      {
        // Each phase is agreed on by all processes (common/mpi_errors.h): an
        // error on any one is the same error on all, printed once (rank 0).
        const Scene scene = mpi::collectively<SceneError>(MPI_COMM_WORLD, [&]
                                                          { return load_scene(scene_file, sets); });
        const driver::RunOptions options{out, pushout::mesh::default_cache_dir(), quiet, force};
        // What refuses the run before its folder is touched: an earlier
        // run's outputs there stay (a typo in a mesh key deleted them).
        mpi::collectively<OptionError, SceneError, record::TooLarge>(
            MPI_COMM_WORLD, [&] { driver::check_before_run(scene, options); });
        // With cracks anywhere, what needs the mesh too (a cracking.radius
        // that takes in no element, a crack band too wide for one): the
        // mesh made, or read from the cache, which then serves the run.
        mpi::collectively<SceneError>(MPI_COMM_WORLD,
                                      [&] {
                                        driver::MeshChecks{options.mesh_cache, force}(scene);
                                      });
        // The folder is this run's alone, without an earlier run's outputs
        // (output/OutputFiles.h).
        mpi::collectively<SceneError, output::FolderError>(MPI_COMM_WORLD,
                                                           [&]
                                                           {
                                                             if (rank == 0)
                                                               output::claim(out, {scene_file});
                                                           });
        const output::Summary s = mpi::collectively<OptionError, SceneError, record::TooLarge>(
            MPI_COMM_WORLD, [&] { return driver::run(scene, options); });
        if (s.interrupted)
        {
          if (rank == 0)
          {
            // What keeps the finished steps: none in step 0.
            std::cerr << "pushout: " << s.message;
            if (s.stopped_in != "step 0")
              std::cerr << "; " << out
                        << (s.stopped_in == "corrosion steps" ? "/corrosion.csv" : "/curve.csv")
                        << " keeps them";
            std::cerr << std::endl;
          }
          return exit_code::signal(s.signal);
        }
        if (!s.converged)
        {
          if (rank == 0)
          {
            std::cerr << "pushout: error: " << s.message << "; " << out << "/curve.csv keeps the "
                      << s.steps << " converged steps";
            if (s.corrosion_steps > 0)
              std::cerr << ", " << out << "/corrosion.csv the " << s.corrosion_steps
                        << " converged corrosion steps";
            std::cerr << std::endl;
          }
          return exit_code::not_converged;
        }
        if (rank == 0 && !quiet)
          std::cout << "pushout: done in " << std::fixed << std::setprecision(2) << s.wall_s
                    << " s, " << s.newton_iterations << " Newton iterations; curve: " << out
                    << "/curve.csv" << (scene.output().plot ? ", plot: " + out + "/curve.png" : "")
                    << std::endl;
        return exit_code::done;
      });
}

/// Whether this process prints what every process would (before MPI is
/// started: the launcher's rank, if any, is 0).
bool first_process()
{
  const char* rank = std::getenv("OMPI_COMM_WORLD_RANK");
  return !rank || std::string(rank) == "0";
}

/// An exception nothing can catch (one thrown inside gmsh's OpenMP regions
/// ends there): one line and exit_code::failure, not an abort.
[[noreturn]] void on_terminate()
{
  std::string what = "an internal error";
  try
  {
    if (const std::exception_ptr e = std::current_exception())
      std::rethrow_exception(e);
  }
  catch (const std::exception& e)
  {
    what = e.what();
  }
  catch (const std::string& e) // gmsh's errors
  {
    what = e;
  }
  catch (...)
  {
  }
  std::replace(what.begin(), what.end(), '\n', ' ');
  std::cerr << "pushout: error: " << what << " (uncaught)" << std::endl;
  int started = 0, size = 1;
  MPI_Initialized(&started);
  if (started)
    MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size > 1)
    MPI_Abort(MPI_COMM_WORLD, pushout::exit_code::failure);
  std::_Exit(pushout::exit_code::failure);
}

/// The command line: the commands, their options and what they were given.
/// Built in place (its options write into its members).
struct CommandLine
{
  CLI::App app{"pushout: push-out tests of RC slices with cohesive-frictional interfaces"};
  std::string scene_file, out;
  std::vector<std::string> sets;
  bool quiet = false, force = false, allow_unused = false;
  pushout::study::SweepOptions sweep_options;
  pushout::study::FitOptions fit_options;
  CLI::App* run = nullptr;
  CLI::App* sweep = nullptr;
  CLI::App* fit = nullptr;

  CommandLine()
  {
    app.require_subcommand(1);
    app.allow_extras(); // the rest goes to PETSc
    run = app.add_subcommand("run", "run a scene");
    common(run, "scene file (TOML)", nullptr);
    sweep = app.add_subcommand(
        "sweep", "run the Cartesian product of scene values, each case in DIR/case_NNN; under "
                 "mpirun the processes share the cases (docs/sweeps.md)");
    common(sweep, "scene file (TOML)", &sweep_options.ranks_per_case);
    sweep
        ->add_option("--vary", sweep_options.vary,
                     "a key and its values: key=v1,v2,... (repeatable)")
        ->allow_extra_args(false) // one value per flag (as --set): the scene may follow
        ->required();
    sweep // from 1: a negative count would wrap round
        ->add_option("--max-cases", sweep_options.max_cases,
                     "the most cases the sweep runs; more is refused (default " +
                         std::to_string(pushout::study::SweepOptions::default_max_cases) + ")")
        ->check(CLI::Range(std::size_t(1), pushout::study::SweepOptions::largest_max_cases));
    fit = app.add_subcommand(
        "fit", "fit scene values (law parameters, loads) to a measured push-out curve by least "
               "squares (PETSc TAO); DIR/fit.json has them with their standard errors "
               "(docs/fitting.md)");
    common(fit, "scene file (TOML): the start values", &fit_options.ranks_per_case);
    fit->add_option("--data", fit_options.data, "measured curve: CSV with delta_mm, tau_MPa")
        ->required();
    fit->add_option("--free", fit_options.free, "a scene key to fit (repeatable)")
        ->allow_extra_args(false)
        ->required();
    fit->add_option("--bounds", fit_options.bounds,
                    "bounds of a free key: key=lo:hi (either may be empty; repeatable)")
        ->allow_extra_args(false);
    app.add_subcommand("keys", "print the scene keys (Markdown table)");
    app.add_subcommand("laws", "print the interface laws and their parameters");
  }

  /// Parses the command line: an exit code to end with (a usage error: one
  /// line naming the option, with where help is; --help), or none.
  std::optional<int> parse(int argc, char* argv[])
  {
    std::string command;
    for (int i = 1; i < argc && command.empty(); ++i)
      for (const char* name : {"run", "sweep", "fit", "keys", "laws"})
        if (std::string(argv[i]) == name)
          command = name;
    const std::string help = command.empty() ? "pushout --help" : "pushout " + command + " --help";
    const auto usage_error = [&](std::string message)
    {
      std::replace(message.begin(), message.end(), '\n', ' ');
      if (first_process())
        std::cerr << "pushout: error: " << message << " (" << help << ")" << std::endl;
      return pushout::exit_code::bad_input;
    };
    try
    {
      app.parse(argc, argv);
    }
    catch (const CLI::ParseError& e)
    {
      if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) // --help
      {
        const int code = app.exit(e);
        return code == pushout::exit_code::done ? printed() : code;
      }
      if (command.empty() && argc > 1 && argv[1][0] != '-')
        return usage_error(std::string("unknown command '") + argv[1] +
                           "'; commands: run, sweep, fit, keys, laws");
      return usage_error(e.what());
    }
    // Options with two dashes are pushout's: one it does not know is a
    // typo, not a PETSc option (those have one dash, each with at most one
    // value after it). A word after no option is an argument too many.
    bool after_option = false; // the last word was a PETSc option's name
    for (const std::string& extra : app.remaining(true))
    {
      if (extra.rfind("--", 0) == 0)
        return usage_error("unknown option '" + extra.substr(0, extra.find('=')) + "'");
      if (command == "keys" || command == "laws") // nothing to solve
        return usage_error("unexpected argument '" + extra + "' (" + command +
                           " takes no arguments)");
      const bool name = extra.size() > 1 && extra[0] == '-' &&
                        !(std::isdigit(static_cast<unsigned char>(extra[1])) || extra[1] == '.');
      if (!name && !after_option)
        return usage_error("unexpected argument '" + extra + "'");
      after_option = name;
    }
    return std::nullopt;
  }

  /// The options CLI11 did not consume: PETSc's.
  std::vector<std::string> petsc_options() const
  {
    return app.got_subcommand("sweep") ? sweep->remaining()
           : app.got_subcommand("fit") ? fit->remaining()
                                       : run->remaining();
  }

  /// Runs the command (run, sweep or fit); returns its exit code.
  int run_command()
  {
    // What sweep and fit share, from the command line.
    const auto fill = [&](pushout::study::ManyRunsOptions& o)
    {
      o.scene_file = scene_file;
      o.sets = sets;
      o.out = out;
      o.mesh_cache = pushout::mesh::default_cache_dir();
      o.quiet = quiet;
      o.force = force;
      o.petsc_options = pushout::driver::option_names(petsc_options());
      o.allow_unused = allow_unused;
    };
    if (app.got_subcommand("fit"))
    {
      fill(fit_options);
      return pushout::study::fit(fit_options);
    }
    if (app.got_subcommand("sweep"))
    {
      fill(sweep_options);
      return pushout::study::sweep(sweep_options);
    }
    return run_scene(scene_file, out, sets, quiet, force);
  }

  /// The summary.json that `pushout run` writes (empty for sweep and fit).
  std::filesystem::path run_summary() const
  {
    return app.got_subcommand("run") ? std::filesystem::path(out) / "summary.json"
                                     : std::filesystem::path();
  }

private:
  /// The scene, the output folder, the overrides and the flags every
  /// command that runs takes; `ranks`: --ranks-per-case, for those that
  /// make many runs.
  void common(CLI::App* cmd, const std::string& scene_doc, int* ranks)
  {
    cmd->add_option("scene", scene_file, scene_doc)->required();
    cmd->add_option("--out", out, "output folder")->required();
    cmd->add_option("--set", sets, "override a scene key: key=value (repeatable)")
        ->allow_extra_args(false);
    if (ranks)
      cmd->add_option("--ranks-per-case", *ranks,
                      "processes that run each model run together (default 1)");
    cmd->add_flag("--quiet", quiet, "no progress lines");
    cmd->add_flag("--force", force,
                  "run even if the size guard estimates a run cannot fit in memory");
    cmd->add_flag("--allow-unused-petsc-options", allow_unused,
                  "a PETSc option that nothing read is a warning, not an error (exit 2)");
    cmd->footer("Options with one dash go to PETSc (-snes_monitor, -ksp_type gmres); one that "
                "no solver of the run (nor of the default solver path) read is an error, "
                "reported at the end of the run, unless --allow-unused-petsc-options.");
    cmd->allow_extras();
  }
};

} // namespace

int main(int argc, char* argv[])
{
  std::set_terminate(on_terminate);
  CommandLine cli;
  if (const std::optional<int> end = cli.parse(argc, argv))
    return *end;
  if (cli.app.got_subcommand("keys"))
  {
    print_keys();
    return printed();
  }
  if (cli.app.got_subcommand("laws"))
  {
    print_laws();
    return printed();
  }
  std::vector<std::string> petsc_options = cli.petsc_options();
  if (!pushout::driver::start_petsc(argv[0], petsc_options))
    return pushout::exit_code::failure;
  // Agreed: an option naming a file (-tao_monitor FILE) may open on some
  // processes only, and the command either runs on all of them or on none.
  if (const std::string bad =
          pushout::mpi::first_message(pushout::driver::petsc_option_error(), MPI_COMM_WORLD);
      !bad.empty())
  {
    if (first_process())
      std::cerr << "pushout: error: a PETSc option: " << bad << std::endl;
    pushout::petsc::check_nothrow(PetscFinalize(), "PetscFinalize");
    return pushout::exit_code::bad_input;
  }
  pushout::output::share_run_id(MPI_COMM_WORLD);
  // After PETSc, whose own handlers would otherwise abort on SIGTERM.
  pushout::interrupt::install();
  dolfinx::init_logging(1, argv);
  loguru::g_stderr_verbosity = loguru::Verbosity_WARNING;
  int rc = pushout::exit_code::done;
  try
  {
    rc = cli.run_command();
    rc = pushout::driver::check_petsc_options(pushout::driver::option_names(petsc_options),
                                              cli.allow_unused, rc, cli.run_summary());
  }
  catch (const std::exception& e) // an error outside the runs of a sweep or fit
  {
    std::cerr << "pushout: error: " << e.what() << std::endl;
    MPI_Abort(MPI_COMM_WORLD, pushout::exit_code::failure); // others may wait in a collective
  }
  // The command has said how it ended: a signal that came meanwhile ends
  // nothing more.
  const pushout::interrupt::Phase ending("ending", -1);
  pushout::petsc::check_nothrow(PetscFinalize(), "PetscFinalize");
  return rc;
}

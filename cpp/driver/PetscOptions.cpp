#include "PetscOptions.h"
#include "../common/exit_codes.h"
#include "../common/mpi_start.h"
#include "../common/petsc_check.h"
#include "../output/Summary.h"
#include "../solver/FitTao.h"
#include <cctype>
#include <iostream>
#include <mpi.h>
#include <petscmat.h>
#include <petscsnes.h>
#include <petscsys.h>
#include <petsctao.h>
#include <sstream>

namespace pushout::driver
{
std::vector<std::string> unused_petsc_options(const std::set<std::string>& given, MPI_Comm comm)
{
  using pushout::petsc::check;
  PetscInt left = 0;
  check(PetscOptionsLeftGet(nullptr, &left, nullptr, nullptr), "PetscOptionsLeftGet");
  if (left > 0)
  {
    // The SNES, its KSP and PC and a fit's TAO read theirs in
    // petsc_option_error(), which every command passed before it ran; made
    // again here they would open again, and empty, the files that options
    // such as -snes_monitor FILE name. MUMPS reads its own at a factor.
    Mat A, F;
    check(MatCreateSeqAIJ(PETSC_COMM_SELF, 1, 1, 1, nullptr, &A), "MatCreateSeqAIJ");
    check(MatSetValue(A, 0, 0, 1.0, INSERT_VALUES), "MatSetValue");
    check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    if (MatGetFactor(A, MATSOLVERMUMPS, MAT_FACTOR_LU, &F) == 0)
    {
      // Only for the options it reads: a value this 1 x 1 probe cannot
      // take (-mat_mumps_icntl_7 1, an order the run's own LU gives MUMPS)
      // is no error of the run's, which has ended. Not checked, alike on
      // every process.
      MatFactorInfo info;
      check(MatFactorInfoInitialize(&info), "MatFactorInfoInitialize");
      (void)MatLUFactorSymbolic(F, A, nullptr, nullptr, &info);
      check(MatDestroy(&F), "MatDestroy");
    }
    check(MatDestroy(&A), "MatDestroy");
    for (const char* own : {"-arc_monitor", "-options_left"}) // read by pushout, or at the end
    {
      PetscBool set;
      check(PetscOptionsHasName(nullptr, nullptr, own, &set), "PetscOptionsHasName");
    }
  }
  // The first process's list; each is unused where no process read it.
  char** names = nullptr;
  char** values = nullptr;
  check(PetscOptionsLeftGet(nullptr, &left, &names, &values), "PetscOptionsLeftGet");
  std::string list;
  for (PetscInt i = 0; i < left; ++i)
    list += std::string("-") + names[i] + "\n";
  check(PetscOptionsLeftRestore(nullptr, &left, &names, &values), "PetscOptionsLeftRestore");
  int length = int(list.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, comm);
  list.resize(std::size_t(length));
  MPI_Bcast(list.data(), length, MPI_CHAR, 0, comm);
  std::vector<std::string> candidates;
  std::istringstream in(list);
  for (std::string name; std::getline(in, name);)
    candidates.push_back(name);
  std::vector<int> used(candidates.size(), 0);
  for (std::size_t i = 0; i < candidates.size(); ++i)
  {
    PetscBool u = PETSC_FALSE;
    check(PetscOptionsUsed(nullptr, candidates[i].c_str(), &u), "PetscOptionsUsed");
    used[i] = u ? 1 : 0;
  }
  MPI_Allreduce(MPI_IN_PLACE, used.data(), int(used.size()), MPI_INT, MPI_MAX, comm);
  std::vector<std::string> unused;
  for (std::size_t i = 0; i < candidates.size(); ++i)
    if (!used[i] && given.count(candidates[i]))
      unused.push_back(candidates[i]);
  return unused;
}

std::set<std::string> option_names(const std::vector<std::string>& words)
{
  std::set<std::string> names;
  for (const std::string& w : words)
    if (w.size() > 1 && w[0] == '-' && std::isalpha(static_cast<unsigned char>(w[1])))
      names.insert(w);
  return names;
}

bool start_petsc(char* program, std::vector<std::string>& options)
{
  std::vector<char*> petsc_argv = {program};
  for (std::string& o : options)
    petsc_argv.push_back(o.data());
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
    return false;
  }
  return true;
}

namespace
{
/// "OPTION TYPE: WHY" where a solver's `type` is not pushout's `ours`, else "".
std::string another_type(const char* option, const char* type, const char* ours, const char* why)
{
  return type && std::string(type) != ours ? std::string(option) + " " + type + ": " + why : "";
}
} // namespace

std::string petsc_option_error()
{
  using pushout::petsc::check;
  SNES snes;
  check(SNESCreate(PETSC_COMM_SELF, &snes), "SNESCreate");
  std::string error;
  try
  {
    check(SNESSetFromOptions(snes), "SNESSetFromOptions");
    // The load steps are Newton's method with a line search on the laws'
    // consistent tangents, and their stop tests and cuts read its
    // iterations: another SNES (ksponly took one linear solve and said it
    // converged; qn failed inside) is no solver of pushout's.
    SNESType type = nullptr;
    check(SNESGetType(snes, &type), "SNESGetType");
    error = another_type("-snes_type", type, SNESNEWTONLS,
                         "pushout's load steps run Newton's method with a line search "
                         "(newtonls, the default; -snes_linesearch_type chooses the line search)");
    KSP ksp;
    check(SNESGetKSP(snes, &ksp), "SNESGetKSP");
    check(KSPSetFromOptions(ksp), "KSPSetFromOptions");
  }
  catch (const pushout::petsc::Error& e)
  {
    error = e.what();
  }
  check(SNESDestroy(&snes), "SNESDestroy");
  if (!error.empty())
    return error;
  // A fit's solver with each line search it may use (its options are read
  // by type): a value it cannot take is refused before any command, a
  // fit's before its runs (and another command's TAO options count as
  // read, as the default solver path's do: unused_petsc_options).
  for (TaoLineSearchType line_search : pushout::solver::fit_line_searches)
  {
    Tao tao;
    check(TaoCreate(PETSC_COMM_SELF, &tao), "TaoCreate");
    try
    {
      pushout::solver::set_up_fit_tao(tao, line_search);
      // A fit's stop tests, its refused values' stop and its counts of
      // runs read BNLS's iterations and line search, as the load steps
      // read Newton's.
      TaoType type = nullptr;
      check(TaoGetType(tao, &type), "TaoGetType");
      error = another_type("-tao_type", type, TAOBNLS,
                           "a fit is Gauss-Newton as TAO's bnls (the default; -tao_ls_type "
                           "chooses its line search)");
    }
    catch (const pushout::petsc::Error& e)
    {
      error = e.what();
    }
    check(TaoDestroy(&tao), "TaoDestroy");
    if (!error.empty())
      break;
  }
  return error;
}

namespace
{
/// "-a, -b".
std::string listed(const std::vector<std::string>& names)
{
  std::string list;
  for (const std::string& n : names)
    list += (list.empty() ? "" : ", ") + n;
  return list;
}
} // namespace

void warn_unread_options(const std::set<std::string>& given, bool allow_unused, MPI_Comm comm,
                         bool say, const std::string& first_runs, const std::string& command)
{
  if (allow_unused || given.empty())
    return;
  const std::vector<std::string> unused = unused_petsc_options(given, comm);
  if (!say || unused.empty())
    return;
  const bool many = unused.size() > 1;
  std::cerr << "pushout: warning: PETSc option" << (many ? "s " : " ") << listed(unused)
            << " not read by " << first_runs << " (a typo?); the " << command
            << " goes on (an option that no run reads fails it at the end, exit 2; "
               "--allow-unused-petsc-options accepts "
            << (many ? "them" : "it") << ")" << std::endl;
}

int check_petsc_options(const std::set<std::string>& given, bool allow_unused, int rc,
                        const std::filesystem::path& summary)
{
  const std::vector<std::string> unused = unused_petsc_options(given, MPI_COMM_WORLD);
  if (unused.empty())
    return rc;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const std::string list = listed(unused);
  const bool error = !allow_unused && rc == pushout::exit_code::done;
  if (rank == 0)
    std::cerr << "pushout: " << (error ? "error" : "warning") << ": PETSc option"
              << (unused.size() > 1 ? "s " : " ") << list
              << " not read by any solver (a typo?); --allow-unused-petsc-options accepts "
              << (unused.size() > 1 ? "them" : "it") << std::endl;
  // Said above whatever comes of it: a summary that cannot be written again
  // (the disk full since) changes no exit code.
  if (rank == 0 && !summary.empty())
    try
    {
      pushout::output::add_unused_petsc_options(summary, unused);
    }
    catch (const std::exception& e)
    {
      std::cerr << "pushout: warning: summary.json does not list them: " << e.what() << std::endl;
    }
  return error ? pushout::exit_code::bad_input : rc;
}
} // namespace pushout::driver

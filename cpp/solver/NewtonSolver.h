// Thin layer over PETSc SNES: Newton with line search (PETSc's newtonls/bt
// by default) on an Equilibrium. Every PETSc option from the command line
// reaches SNES, KSP and PC (-snes_monitor, -ksp_type, -pc_type, ...); the
// defaults below apply only where the user gave none.
#pragma once

#include "Equilibrium.h"
#include <petscsnes.h>
#include <string>

namespace pushout::solver
{
struct SolveReport
{
  bool converged = false;
  int iterations = 0;
  std::string reason; ///< PETSc's converged/diverged reason
};

class NewtonSolver
{
public:
  explicit NewtonSolver(Equilibrium& problem);
  ~NewtonSolver();
  NewtonSolver(const NewtonSolver&) = delete;
  NewtonSolver& operator=(const NewtonSolver&) = delete;

  /// Solves F(x) = 0 from the initial guess x (constraints already in x).
  SolveReport solve(Vec x);

  /// Sets PETSc's options database defaults for pushout (MUMPS LU, tight
  /// tolerances) where the user did not set them. Call before NewtonSolver.
  static void set_default_options();

private:
  Equilibrium& _problem;
  SNES _snes = nullptr;
  Mat _J = nullptr;
  Vec _F = nullptr;
};
} // namespace pushout::solver

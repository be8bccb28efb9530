#!/usr/bin/python3
"""Linear solvers, and the whole curve against its floor.

Each run also times one linear solve of its first load step with MUMPS LU
on the whole model (solver.time_linear_solve), in the same process, so
    floor ratio = T(whole curve) / T(one linear solve),
with T(whole curve) the run's wall time less that probe. Scenes (quarter
model by symmetry, the paper's mesh 16/8, one thread):

  fig7:  demo/pushout_friction.toml (friction, dT -25, 10 um in 9 steps);
  fig10: demo/pushout_friction_adhesion.toml pushed to 1 mm in 120 steps
         (growth 1.07^(80/120)), through the adhesion peak.

Solvers (all one option away from the default):
  condensed-lagged  default: Newton on the interface jumps after condensing
                    the bulk (solver.condensation), GMRES preconditioned by
                    a lagged dense LU;
  condensed-newton  the same with a dense LU of every Jacobian;
  mumps-lagged      solver.condensation=off: GMRES on the whole model,
                    preconditioned by the MUMPS LU of an earlier Jacobian,
                    refreshed when GMRES needs > 10 iterations;
  mumps-newton      ... and solver.preconditioner=jacobian: MUMPS LU of
                    every whole-model Jacobian (plain Newton);
  gamg-once         GMRES + GAMG (rigid-body near-nullspace) built once on
                    the elastic tangent (solver.refactor_iterations=1000);
  gamg-newton       GMRES + GAMG rebuilt for every Jacobian;
  hypre-newton      GMRES + hypre BoomerAMG rebuilt for every Jacobian.
(Iterative preconditioners run on the whole model: condensation is dense LU.)

Writes bench/results/solvers.csv and solvers.md.

  bench/solvers.py [--only fig7 fig10] [--solvers ...] [--reuse]
"""
import argparse
import os
import time

from common import PUSHOUT, ROOT, curve, markdown_table, run, summary, write_csv

KRYLOV = ["-ksp_type", "gmres", "-ksp_rtol", "1e-10", "-ksp_max_it", "5000", "-ksp_gmres_restart", "200"]
OFF = ["--set", "solver.condensation=off"]
SOLVERS = {
    "condensed-lagged": [],
    "condensed-newton": ["--set", "solver.preconditioner=jacobian"],
    "mumps-lagged": OFF,
    "mumps-newton": OFF + ["--set", "solver.preconditioner=jacobian"],
    "gamg-once": ["--set", "solver.refactor_iterations=1000", "-pc_type", "gamg"] + KRYLOV,
    "gamg-newton": ["--set", "solver.preconditioner=jacobian", "-pc_type", "gamg"] + KRYLOV,
    "hypre-newton": ["--set", "solver.preconditioner=jacobian", "-pc_type", "hypre",
                     "-pc_hypre_type", "boomeramg"] + KRYLOV,
}
SCENES = {
    "fig7": ("pushout_friction.toml", []),
    "fig10": ("pushout_friction_adhesion.toml",
              ["loading.push_displacement=1.0", "loading.steps=120", f"loading.step_growth={1.07 ** (80 / 120):.6f}"]),
}


# The table's columns (a row's keys, in order).
COLUMNS = ["scene", "solver", "dofs", "linear_solve_s", "curve_s", "solve_s", "floor_ratio",
           "newton_unknowns", "steps", "newton_iterations", "factorizations", "peak_memory_mb",
           "tau_end_MPa", "status"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pushout", default=PUSHOUT)
    ap.add_argument("--only", nargs="+", default=list(SCENES), choices=list(SCENES))
    ap.add_argument("--solvers", nargs="+", default=list(SOLVERS), choices=list(SOLVERS))
    ap.add_argument("--timeout", type=float, default=3600, help="per run [s]")
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results"),
                    help="the folder of the tables (the runs go to --work)")
    ap.add_argument("--work", default=os.path.join(ROOT, "results", "solvers"))
    ap.add_argument("--reuse", action="store_true")
    args = ap.parse_args()
    rows = []
    for scene_name in args.only:
        scene, sets = SCENES[scene_name]
        for solver in args.solvers:
            out = os.path.join(args.work, scene_name, solver)
            started = time.time()
            code = run(args.pushout, os.path.join(ROOT, "demo", scene), out,
                       ["output.plot=false", "solver.time_linear_solve=true"] + sets, SOLVERS[solver],
                       reuse=args.reuse, timeout=args.timeout, check=False)
            stopped = f"stopped after {args.timeout:.0f} s"
            written = os.path.join(out, "summary.json")
            if code is None and not (os.path.exists(written) and
                                     os.path.getmtime(written) >= started):
                # Killed before it wrote a summary: an earlier run's in the
                # folder is not this one's.
                rows.append(dict({k: "" for k in COLUMNS}, scene=scene_name, solver=solver,
                                 status=stopped))
                print(rows[-1], flush=True)
                continue
            s, c = summary(out), curve(out)
            status = "ok" if s["converged"] else s["message"]
            if code is None:
                status = stopped
            rows.append({"scene": scene_name, "solver": solver, "dofs": s["dofs"],
                         "linear_solve_s": round(s["linear_solve_s"], 3),
                         "curve_s": round(s["wall_s"] - s["linear_solve_s"], 2),
                         "solve_s": round(s["time_s"]["solve"], 2),
                         "floor_ratio": round((s["wall_s"] - s["linear_solve_s"]) / s["linear_solve_s"], 1),
                         "newton_unknowns": s["condensed_dofs"] or s["dofs"],
                         "steps": s["steps"], "newton_iterations": s["newton_iterations"],
                         "factorizations": s["factorizations"],
                         "peak_memory_mb": round(s["peak_memory_mb"]),
                         "tau_end_MPa": c[-1]["tau_MPa"], "status": status})
            assert list(rows[-1]) == COLUMNS
            print(rows[-1], flush=True)
    write_csv(os.path.join(args.out, "solvers.csv"), rows)
    with open(os.path.join(args.out, "solvers.md"), "w") as f:
        f.write(markdown_table(["scene", "solver", "dofs", "one linear solve [s]", "whole curve [s]",
                                "of which solving [s]", "curve / linear solve", "Newton unknowns",
                                "steps", "Newton its",
                                "preconditioner set-ups", "peak memory [MB]", "tau at the end [MPa]",
                                "status"], rows))


if __name__ == "__main__":
    main()

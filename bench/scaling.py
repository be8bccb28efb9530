#!/usr/bin/python3
"""Strong scaling on this machine: the friction push-out (Fig. 7 scene,
dT -25 degC, 10 um, in --steps push steps) on a fine mesh, on 1 and 2 MPI
processes. At >= 500 k dofs MUMPS LU needs > 20 GB on this 24 GB machine, so
the linear solver here is GMRES + algebraic multigrid (GAMG with the
rigid-body near-nullspace) on the elastic tangent, set up once
(--set solver.refactor_iterations=1000); --petsc changes that.
Reports the dofs, the time of the setup, of the thermal step, of one push
step (the median) and of the whole curve, Newton iterations,
factorisations and the peak memory per process; writes
bench/results/scaling.csv and scaling.md.

  bench/scaling.py [--quarter 40 --layers 26] [--procs 1 2]
"""
import argparse
import csv
import json
import os
import statistics
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
from common import write_csv  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pushout", default=os.path.join(ROOT, "build", "pushout"))
    ap.add_argument("--quarter", type=int, default=40, help="mesh.elements_per_quarter")
    ap.add_argument("--layers", type=int, default=26, help="mesh.elements_through_thickness")
    ap.add_argument("--procs", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--steps", type=int, default=3)
    ap.add_argument("--petsc", default="-ksp_type gmres -pc_type gamg -ksp_rtol 1e-9 -ksp_max_it 2000",
                    help="PETSc options for the linear solver")
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results"),
                    help="the folder of the tables (the runs go to --work)")
    ap.add_argument("--work", default=os.path.join(ROOT, "results", "scaling"))
    args = ap.parse_args()
    rows = []
    for n in args.procs:
        out = os.path.join(args.work, f"np{n}")
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-n", str(n), args.pushout, "run",
               os.path.join(ROOT, "demo", "pushout_friction.toml"), "--out", out, "--quiet",
               "--set", f"mesh.elements_per_quarter={args.quarter}",
               "--set", f"mesh.elements_through_thickness={args.layers}", "--set", "output.plot=false",
               "--set", f"loading.steps={args.steps}", "--set", "solver.refactor_iterations=1000",
               "--set", "model.symmetry=full"]
        cmd += args.petsc.split()
        subprocess.run(cmd, check=True, env=dict(os.environ, OPENBLAS_NUM_THREADS="1"))
        with open(os.path.join(out, "summary.json")) as f:
            s = json.load(f)
        with open(os.path.join(out, "curve.csv"), newline="") as f:
            curve = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
        push = [b["wall_s"] - a["wall_s"] for a, b in zip(curve, curve[1:])]
        rows.append({"processes": n, "dofs": s["dofs"], "setup_s": round(s["time_s"]["mesh"] + s["time_s"]["setup"], 2),
                     "thermal_step_s": round(curve[0]["wall_s"] - s["time_s"]["mesh"] - s["time_s"]["setup"], 2),
                     "push_step_median_s": round(statistics.median(push), 2),
                     "curve_s": round(s["wall_s"], 2), "newton_iterations": s["newton_iterations"],
                     "factorizations": s["factorizations"], "peak_memory_mb_per_process": round(s["peak_memory_mb"]),
                     "tau_end_MPa": curve[-1]["tau_MPa"], "petsc": args.petsc})
        print(rows[-1], flush=True)
    os.makedirs(args.out, exist_ok=True)
    write_csv(os.path.join(args.out, "scaling.csv"), rows)
    with open(os.path.join(args.out, "scaling.md"), "w") as f:
        f.write("| processes | dofs | setup [s] | thermal step [s] | push step (median) [s] | whole curve [s] | "
                "Newton its | preconditioner set-ups | peak memory / process [MB] | tau at 10 um [MPa] | solver |\n")
        f.write("|---|---|---|---|---|---|---|---|---|---|---|\n")
        for r in rows:
            f.write("| " + " | ".join(str(v) for v in r.values()) + " |\n")


if __name__ == "__main__":
    main()

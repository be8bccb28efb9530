#!/usr/bin/python3
"""Cost against problem size: the friction push-out (Fig. 7 scene,
dT -25 degC, two push steps of 1.1 um after the thermal step) on the full
slice (model.symmetry = "full", so the dofs are the specimen's) from the
paper's mesh up to > 1 M dofs, on one process. For each size and solver:
the time of one linear solve of the first step (solver.time_linear_solve),
of the thermal step and of a push step (the median), and the peak memory.
Fits time ~ dofs^p and memory ~ dofs^q by least squares in log-log.

Solvers: "gamg" (GMRES + GAMG with the rigid-body near-nullspace, built on
the elastic tangent once: solver.refactor_iterations = 1000) at every size;
"mumps" (GMRES + lagged MUMPS LU on the whole model, solver.condensation =
off: the condensed interface system is a different cost model, measured in
bench/solvers.py) up to --mumps-max dofs, above which its memory does not
fit beside the rest on this 24 GB machine.

Writes bench/results/dofs_scaling.csv, dofs_scaling.md, dofs_scaling.png.

  bench/dofs_scaling.py [--sizes 16x8 24x12 32x16 40x20 52x32] [--reuse]
"""
import argparse
import math
import os
import statistics

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from common import PUSHOUT, ROOT, curve, markdown_table, run, summary, write_csv  # noqa: E402
import argument_types  # noqa: E402  (common puts scripts/ on the path)

SOLVERS = {  # gamg first: its runs tell which sizes MUMPS can take
    "gamg": ["--set", "solver.refactor_iterations=1000", "-ksp_type", "gmres", "-pc_type", "gamg",
             "-ksp_rtol", "1e-9", "-ksp_max_it", "2000"],
    "mumps": ["--set", "solver.preconditioner=lagged", "--set", "solver.condensation=off"],
}


def fit(xs, ys):
    """Least-squares slope and intercept of log y against log x."""
    lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    p = sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)
    return p, math.exp(my - p * mx)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pushout", default=PUSHOUT)
    ap.add_argument("--sizes", nargs="+", type=argument_types.mesh_size, default=["16x8", "24x12", "32x16", "40x20", "52x32"])
    ap.add_argument("--mumps-max", type=int, default=300000, help="largest dofs run with MUMPS")
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results"),
                    help="the folder of the tables (the runs go to --work)")
    ap.add_argument("--work", default=os.path.join(ROOT, "results", "dofs_scaling"))
    ap.add_argument("--reuse", action="store_true")
    args = ap.parse_args()
    rows = []
    for solver, options in SOLVERS.items():
        for size in args.sizes:
            nq, nz = (int(v) for v in size.split("x"))
            out = os.path.join(args.work, f"{solver}_{size}")
            if solver == "mumps":  # skip sizes whose gamg run shows too many dofs
                big = [r for r in rows if r["solver"] == "gamg" and r["size"] == size]
                if big and big[0]["dofs"] > args.mumps_max:
                    continue
            run(args.pushout, os.path.join(ROOT, "demo", "pushout_friction.toml"), out,
                [f"mesh.elements_per_quarter={nq}", f"mesh.elements_through_thickness={nz}",
                 "model.symmetry=full", "output.plot=false", "loading.steps=2",
                 "loading.push_displacement=0.0022", "solver.time_linear_solve=true"], options,
                reuse=args.reuse)
            s, c = summary(out), curve(out)
            setup = s["time_s"]["mesh"] + s["time_s"]["setup"] + s["linear_solve_s"]
            push = [b["wall_s"] - a["wall_s"] for a, b in zip(c, c[1:])]
            rows.append({"solver": solver, "size": size, "dofs": s["dofs"],
                         "linear_solve_s": round(s["linear_solve_s"], 3),
                         "thermal_step_s": round(c[0]["wall_s"] - setup, 2),
                         "push_step_s": round(statistics.median(push), 2),
                         "newton_iterations": s["newton_iterations"],
                         "peak_memory_mb": round(s["peak_memory_mb"]),
                         "tau_end_MPa": round(c[-1]["tau_MPa"], 6)})
            print(rows[-1], flush=True)
    write_csv(os.path.join(args.out, "dofs_scaling.csv"), rows)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), dpi=110)
    lines = ["| solver | quantity | exponent p (~ dofs^p) | dofs range |", "|---|---|---|---|"]
    for solver, color in (("mumps", "tab:blue"), ("gamg", "tab:orange")):
        rs = [r for r in rows if r["solver"] == solver]
        if len(rs) < 2:
            continue
        dofs = [r["dofs"] for r in rs]
        for key, ax, marker in (("push_step_s", axes[0], "o"), ("linear_solve_s", axes[0], "s"),
                                ("peak_memory_mb", axes[1], "o")):
            ys = [r[key] for r in rs]
            p, c = fit(dofs, ys)
            ax.loglog(dofs, ys, marker=marker, color=color, ls="-" if marker == "o" else ":",
                      label=f"{solver} {key.replace('_', ' ')}: ~ dofs^{p:.2f}")
            lines.append(f"| {solver} | {key} | {p:.2f} | {min(dofs)}–{max(dofs)} |")
    axes[0].set(xlabel="dofs", ylabel="time [s]", title="Per push step and per linear solve (1 process)")
    axes[1].set(xlabel="dofs", ylabel="peak memory [MB]", title="Peak resident memory")
    for ax in axes:
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "dofs_scaling.png"))
    with open(os.path.join(args.out, "dofs_scaling.md"), "w") as f:
        f.write(markdown_table(["solver", "mesh", "dofs", "one linear solve [s]", "thermal step [s]",
                                "push step [s]", "Newton its", "peak memory [MB]", "tau at 2.2 um [MPa]"],
                               rows))
        f.write("\n" + "\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()

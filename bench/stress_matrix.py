#!/usr/bin/python3
"""Stress matrix of numerical stability.

Runs the friction + exponential-softening push-out (Friction 2 + Exp. soft.
of Table 1 with both penalties set to k; dT = -25 degC; pushed to 0.1 mm,
through the peak and the drop) over
    k in {1e2, 1e4, 1e6} N/mm^3  x  steps in {1, 9, 100, 1000}
    x  mu in {0, 0.2, 1.0}  x  interface quadrature in {gauss, nodal}
on a coarse mesh (4 per quarter, 2 through the thickness) and writes
bench/results/stress_matrix.csv and .md: converged, cuts, Newton iterations,
wall time, and max |tau - tau_ref| with tau_ref the 1000-step run of the same
k, mu and quadrature (interpolated at each run's delta).

With --brittle, brittle adhesion under each push control instead (issue 16):
demo/pushout_friction_adhesion.toml (paper mesh, quarter model) with
    c in {100, 400, 2000} 1/mm  x  f_t in {3, 6} MPa  x  k in {1e3, 1e5} N/mm^3
(k of both layers), dT = -25 degC, 0.5 mm in 10 steps, under displacement,
dissipation and arc-length control (arc length with 200 steps: the
reference), into bench/results/brittle_matrix.csv and .md: exit, Newton
iterations, steps (by energy), cuts, wall time, peak tau, and max |tau -
tau_arc| at the same mean slip (the arc-length rows interpolated).

  bench/stress_matrix.py [--pushout build/pushout] [--jobs 2] [--brittle]
"""
import argparse
import concurrent.futures
import csv
import itertools
import json
import math
import os
import subprocess
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
from common import curve, markdown_table, summary, write_csv  # noqa: E402
from common import run as bench_run  # noqa: E402
import argument_types  # noqa: E402  (common puts scripts/ on the path)
SCENE = """
[mesh]
elements_per_quarter = 4
elements_through_thickness = 2
interface_quadrature = "{quad}"
[[interface]]
law = "friction"
k = {k}
mu = {mu}
[[interface]]
law = "exponential_softening"
k = {k}
f_t = 3.0
c = 25.0
f_fr = 0.0
[loading]
temperature_change = -25.0
push_displacement = 0.1
steps = {steps}
[output]
plot = false
"""


def run(pushout, out, k, steps, mu, quad):
    os.makedirs(out, exist_ok=True)
    scene = os.path.join(out, "scene_in.toml")
    with open(scene, "w") as f:
        f.write(SCENE.format(k=float(k), steps=steps, mu=mu, quad=quad))
    t0 = time.time()
    p = subprocess.run([pushout, "run", scene, "--out", out, "--quiet"], capture_output=True, text=True,
                       env=dict(os.environ, OPENBLAS_NUM_THREADS="1"), timeout=3600)
    wall = time.time() - t0
    rows = []
    if os.path.exists(os.path.join(out, "curve.csv")):
        with open(os.path.join(out, "curve.csv"), newline="") as f:
            rows = [{k2: float(v) for k2, v in r.items()} for r in csv.DictReader(f)]
    summary = {}
    if os.path.exists(os.path.join(out, "summary.json")):
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
    return {"rc": p.returncode, "signal": p.returncode < 0, "wall_s": wall, "rows": rows,
            "summary": summary, "stderr": p.stderr.strip().splitlines()[-1:] if p.stderr else []}


def interp(xs, ys, x):
    for i in range(1, len(xs)):
        if xs[i] >= x:
            t = (x - xs[i - 1]) / (xs[i] - xs[i - 1]) if xs[i] > xs[i - 1] else 0.0
            return ys[i - 1] + t * (ys[i] - ys[i - 1])
    return ys[-1]


BRITTLE_CONTROLS = {"displacement": [], "dissipation": ["loading.control=dissipation"],
                    "arc_length": ["loading.control=arc_length", "loading.steps=200"]}


def run_brittle(pushout, out, c, f_t, k, control):
    """One brittle case under one control: its curve, summary and wall time."""
    sets = [f"interface.1.c={c}", f"interface.1.f_t={f_t}", f"interface.0.k={k}", f"interface.1.k={k}",
            "loading.push_displacement=0.5", "loading.steps=10", "output.plot=false"]
    t0 = time.time()
    p = bench_run(pushout, os.path.join(ROOT, "demo", "pushout_friction_adhesion.toml"), out,
                  sets + BRITTLE_CONTROLS[control], timeout=3600, check=False)
    wall = time.time() - t0
    rows = curve(out) if os.path.exists(os.path.join(out, "curve.csv")) else []
    s = summary(out) if os.path.exists(os.path.join(out, "summary.json")) else {}
    return {"rc": p, "wall_s": wall, "rows": rows, "summary": s}


def brittle(args):
    grid = list(itertools.product([100, 400, 2000], [3.0, 6.0], [1e3, 1e5], BRITTLE_CONTROLS))
    results = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futs = {pool.submit(run_brittle, args.pushout, os.path.join(args.work, f"brittle_c{c}_ft{f_t:g}_k{k:g}_{ctl}"),
                            c, f_t, k, ctl): (c, f_t, k, ctl) for c, f_t, k, ctl in grid}
        for f in concurrent.futures.as_completed(futs):
            results[futs[f]] = f.result()
            print(futs[f], results[futs[f]]["rc"], f"{results[futs[f]]['wall_s']:.1f} s", flush=True)
    table = []
    for c, f_t, k, ctl in grid:
        r, ref = results[(c, f_t, k, ctl)], results[(c, f_t, k, "arc_length")]
        rows, s = r["rows"], r["summary"]
        err = float("nan")
        if ctl != "arc_length" and len(rows) > 1 and ref["summary"].get("converged"):
            xs = [x["slip_mm"] for x in ref["rows"][1:]]
            ys = [x["tau_MPa"] for x in ref["rows"][1:]]
            inside = [x for x in rows[1:] if xs[0] <= x["slip_mm"] <= xs[-1]]
            if inside:
                err = round(max(abs(x["tau_MPa"] - interp(xs, ys, x["slip_mm"])) for x in inside), 4)
        table.append({"c_1_mm": c, "f_t_MPa": f_t, "k_N_mm3": k, "control": ctl, "exit": r["rc"],
                      "newton_iterations": s.get("newton_iterations", ""), "steps": s.get("steps", ""),
                      "energy_steps": s.get("dissipation_steps", ""), "cuts": s.get("cuts", ""),
                      "wall_s": round(r["wall_s"], 1),
                      "peak_tau_MPa": round(max((x["tau_MPa"] for x in rows), default=float("nan")), 4),
                      "max_err_tau_vs_arc_MPa": err, "message": s.get("message", "")})
    os.makedirs(args.out, exist_ok=True)
    write_csv(os.path.join(args.out, "brittle_matrix.csv"), table)
    with open(os.path.join(args.out, "brittle_matrix.md"), "w") as f:
        f.write("Made by `bench/stress_matrix.py --brittle` (see its docstring).\n\n")
        f.write(markdown_table(["c [1/mm]", "f_t [MPa]", "k [N/mm³]", "control", "exit", "Newton its", "steps",
                                "by energy", "cuts", "wall [s]", "peak τ [MPa]", "max \\|τ − τ_arc\\| [MPa]",
                                "message"], table))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pushout", default=os.path.join(ROOT, "build", "pushout"))
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results"),
                    help="the folder of the tables (the runs go to --work)")
    ap.add_argument("--work", default=os.path.join(ROOT, "results", "stress_matrix"))
    ap.add_argument("--jobs", type=argument_types.positive_int, default=os.cpu_count() or 1)
    ap.add_argument("--brittle", action="store_true", help="the brittle-adhesion matrix of the push controls")
    args = ap.parse_args()
    if args.brittle:
        return brittle(args)
    ks, stepss, mus, quads = [1e2, 1e4, 1e6], [1, 9, 100, 1000], [0.0, 0.2, 1.0], ["gauss", "nodal"]
    grid = list(itertools.product(ks, stepss, mus, quads))
    results = {}
    t0 = time.time()
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futs = {pool.submit(run, args.pushout, os.path.join(args.work, f"k{k:g}_n{n}_mu{mu}_{q}"), k, n, mu, q):
                (k, n, mu, q) for k, n, mu, q in grid}
        for f in concurrent.futures.as_completed(futs):
            results[futs[f]] = f.result()
            print(futs[f], results[futs[f]]["rc"], f"{results[futs[f]]['wall_s']:.1f} s", flush=True)

    table = []
    for k, n, mu, q in grid:
        r = results[(k, n, mu, q)]
        ref = results[(k, 1000, mu, q)]
        rows, s = r["rows"], r["summary"]
        err = float("nan")
        if rows and ref["rows"] and ref["summary"].get("converged"):
            xs = [x["delta_mm"] for x in ref["rows"]]
            ys = [x["tau_MPa"] for x in ref["rows"]]
            err = max(abs(x["tau_MPa"] - interp(xs, ys, x["delta_mm"])) for x in rows[1:]) if len(rows) > 1 else float("nan")
        nan = any(math.isnan(v) for x in rows for v in x.values())
        table.append({"k_N_mm3": k, "steps": n, "mu": mu, "quadrature": q, "exit": r["rc"],
                      "converged": bool(s.get("converged")), "rows": len(rows), "cuts": s.get("cuts", ""),
                      "newton_iterations": s.get("newton_iterations", ""), "wall_s": round(r["wall_s"], 2),
                      "peak_tau_MPa": round(max((x["tau_MPa"] for x in rows), default=float("nan")), 4),
                      "max_err_tau_MPa": err if math.isnan(err) else round(err, 5),
                      "nan_in_output": nan, "message": s.get("message", "") or " ".join(r["stderr"])})
    os.makedirs(args.out, exist_ok=True)
    write_csv(os.path.join(args.out, "stress_matrix.csv"), table)
    with open(os.path.join(args.out, "stress_matrix.md"), "w") as f:
        f.write("| k [N/mm³] | steps | μ | quadrature | converged | cuts | Newton its | wall [s] | peak τ [MPa] | max \\|τ − τ_ref\\| [MPa] | note |\n")
        f.write("|---|---|---|---|---|---|---|---|---|---|---|\n")
        for t in table:
            f.write(f"| {t['k_N_mm3']:g} | {t['steps']} | {t['mu']} | {t['quadrature']} | "
                    f"{'yes' if t['converged'] else 'NO'} | {t['cuts']} | {t['newton_iterations']} | {t['wall_s']} | "
                    f"{t['peak_tau_MPa']} | {t['max_err_tau_MPa']} | {t['message']} |\n")
    crashes = sum(1 for t in table if t["exit"] < 0 or t["exit"] >= 128)
    print(f"{len(table)} runs in {time.time() - t0:.0f} s: {sum(t['converged'] for t in table)} converged, "
          f"{crashes} crashes, {sum(t['nan_in_output'] for t in table)} with NaN")


if __name__ == "__main__":
    main()

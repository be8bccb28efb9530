#!/usr/bin/python3
"""The cost of `pushout fit` (issue 15): a 3-parameter fit of a Fig. 10
curve on the paper's mesh.

The measured curve is the model's own Fig. 10 curve (friction 2 + exp. soft.,
mu 0.4, f_t 3 MPa, c 25 1/mm, dT -25 degC; 1 mm in 80 steps growing by 1.07,
as scripts/studies.py) plus Gaussian noise of 1 % of its peak (seed 7); the
fit starts 30 % off (mu 0.52, f_t 3.9, c 17.5) with the same steps. Cases:
one process, and two (the Jacobian's runs shared by two groups). Also the
time of one run of the same scene as `pushout run` (process start, set-up,
plot) for comparison with the runs inside the fit, which reuse the set-up.

Writes bench/results/fit.csv and fit.md.

  bench/fit.py [--pushout build/pushout]
"""
import argparse
import json
import os
import random
import shutil
import subprocess
import time

from common import PUSHOUT, ROOT, curve, markdown_table, run, write_csv

SCENE = os.path.join(ROOT, "demo", "pushout_friction_adhesion.toml")
FIG10 = ["loading.push_displacement=1.0", "loading.steps=80", "loading.step_growth=1.07"]
TRUTH = {"interface.0.mu": 0.4, "interface.1.f_t": 3.0, "interface.1.c": 25.0}
START = {"interface.0.mu": 0.52, "interface.1.f_t": 3.9, "interface.1.c": 17.5}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pushout", default=PUSHOUT)
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "bench_fit"),
                    help="the folder of the runs; the tables go to bench/results")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    truth = os.path.join(args.out, "truth")
    t0 = time.time()
    run(args.pushout, SCENE, truth, FIG10 + [f"{k}={v}" for k, v in TRUTH.items()])
    one_run_s = time.time() - t0
    rows = curve(truth)[1:]
    peak = max(r["tau_MPa"] for r in rows)
    random.seed(7)
    data = os.path.join(args.out, "measured.csv")
    with open(data, "w") as f:
        f.write("delta_mm,tau_MPa\n")
        for r in rows:
            f.write(f"{r['delta_mm']!r},{r['tau_MPa'] + random.gauss(0.0, 0.01 * peak)!r}\n")
    table = []
    for processes in (1, 2):
        out = os.path.join(args.out, f"fit_{processes}")
        cmd = [args.pushout, "fit", SCENE, "--data", data, "--out", out, "--quiet"]
        for s in FIG10 + [f"{k}={v}" for k, v in START.items()]:
            cmd += ["--set", s]
        for k in TRUTH:
            cmd += ["--free", k]
        if processes > 1:
            cmd = [shutil.which("mpirun"), "--allow-run-as-root", "--oversubscribe", "-n", str(processes)] + cmd
        t0 = time.time()
        p = subprocess.run(cmd, capture_output=True, text=True)
        wall = time.time() - t0
        with open(os.path.join(out, "fit.json")) as f:
            r = json.load(f)
        row = {"processes": processes, "exit": p.returncode, "wall_s": round(wall, 2),
               "evaluations": r["evaluations"], "iterations": r["iterations"],
               "s_per_run": round(r["wall_s"] / r["evaluations"], 3), "rms_MPa": round(r["rms_MPa"], 4)}
        for k, v in TRUTH.items():
            row[k.split(".")[-1]] = f"{r['parameters'][k]:.4f} ± {r['standard_errors'][k]:.2g} ({v})"
        table.append(row)
        print(row, flush=True)
    results = os.path.join(ROOT, "bench", "results")
    write_csv(os.path.join(results, "fit.csv"), table)
    with open(os.path.join(results, "fit.md"), "w") as f:
        f.write("# A 3-parameter fit of a Fig. 10 curve (paper's mesh)\n\n"
                "Made by `bench/fit.py` (see its docstring; this 2-core machine). Values: "
                "fitted ± standard error (truth).\n"
                f"One `pushout run` of the scene (process start, set-up, 80 steps, plot): "
                f"{one_run_s:.2f} s.\n\n")
        f.write(markdown_table(list(table[0]), table))


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""The whole process of one `pushout run` of the default scene
(demo/pushout_friction.toml), as a user starts it, and where its time goes
(issue 15: <= 1 s with the plot).

Each case runs --repeat times, one after the other (this machine's timing
noise is +-20 %): the whole process with the plot, without it, and `pushout
keys` (the process with its libraries loaded and nothing run); the run's own
phases come from summary.json (its wall_s starts after the libraries, MPI
and PETSc). The mesh comes from the cache, as in any run after the first.
Default threads (OpenBLAS on both cores), as a user runs it.

Writes bench/results/demo_time.csv and demo_time.md.

  bench/demo_time.py [--repeat N]
"""
import argparse
import json
import os
import statistics
import subprocess
import time

from common import PUSHOUT, ROOT, markdown_table, write_csv

SCENE = os.path.join(ROOT, "demo", "pushout_friction.toml")


def timed(cmd):
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - t0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pushout", default=PUSHOUT)
    ap.add_argument("--repeat", type=int, default=10)
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "bench_demo_time"),
                    help="the folder of the runs; the tables go to bench/results")
    args = ap.parse_args()
    run = [args.pushout, "run", SCENE, "--out", args.out, "--quiet"]
    subprocess.run(run, check=True, stdout=subprocess.DEVNULL)  # the mesh into the cache
    cases = {
        "whole process, plot included": run,
        "whole process, no plot": run + ["--set", "output.plot=false"],
        "libraries only (pushout keys)": [args.pushout, "keys"],
    }
    rows, phases = [], {"mesh": [], "setup": [], "solve": [], "wall_s": []}
    for name, cmd in cases.items():
        times = []
        for _ in range(args.repeat):
            times.append(timed(cmd))
            if "no plot" in name:
                with open(os.path.join(args.out, "summary.json")) as f:
                    s = json.load(f)
                for k in ("mesh", "setup", "solve"):
                    phases[k].append(s["time_s"][k])
                phases["wall_s"].append(s["wall_s"])
        rows.append({"case": name, "min_s": round(min(times), 3),
                     "median_s": round(statistics.median(times), 3), "max_s": round(max(times), 3),
                     "runs": len(times)})
        print(rows[-1], flush=True)
    for k, label in (("wall_s", "run (summary wall_s: after libraries, MPI, PETSc)"),
                     ("mesh", "  mesh (from the cache)"),
                     ("setup", "  set-up (factorisation, condensed flexibility)"),
                     ("solve", "  load steps")):
        v = phases[k]
        rows.append({"case": label, "min_s": round(min(v), 3), "median_s": round(statistics.median(v), 3),
                     "max_s": round(max(v), 3), "runs": len(v)})
    results = os.path.join(ROOT, "bench", "results")
    write_csv(os.path.join(results, "demo_time.csv"), rows)
    with open(os.path.join(results, "demo_time.md"), "w") as f:
        f.write("# The default scene's whole process\n\n"
                f"Made by `bench/demo_time.py --repeat {args.repeat}` (this machine, default "
                "threads, mesh from the cache).\n\n")
        f.write(markdown_table(list(rows[0]), rows))


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""The size guard's peak-memory estimate (record/ResourceGuard.h) against the
measured peak resident memory, over mesh sizes and solver paths: the
friction push-out (demo scene, 1 push step) on the quarter model condensed
and whole, the full model, the triquadratic bulk, 2 MPI processes and an
iterative preconditioner; and the corroded demo with cracks anywhere in the
concrete (one corrosion step of 1 um, 1 push step), on 1 and 2 processes.
Each case meshes afresh (an empty mesh cache). Writes
bench/results/memory_estimate.csv and .md (with --quick
memory_estimate_quick.csv and .md).

  bench/memory_estimate.py [--pushout build/pushout] [--quick]
"""
import argparse
import atexit
import os
import shutil
import tempfile
import time

from common import ROOT, markdown_table, pushout_runs, summary, write_csv

SCENE = os.path.join(ROOT, "demo", "pushout_friction.toml")
CRACKING = os.path.join(ROOT, "demo", "pushout_corroded_cracking.toml")
SHORT_CORROSION = ["corrosion.steps=1", "corrosion.penetration=0.001"]
WHOLE = ['solver.condensation="off"']
FULL = ['model.symmetry="full"'] + WHOLE
P2 = ["mesh.degree=2"]
GAMG = ["-pc_type", "gamg", "-ksp_type", "gmres", "-ksp_rtol", "1e-9"]
# (path, elements per quarter, through thickness, --set overrides, processes, PETSc options)
CASES = [("condensed", nq, 8, [], 1, []) for nq in (8, 16, 32, 48, 64)] + \
        [("condensed", 32, nz, [], 1, []) for nz in (4, 16)] + \
        [("whole", nq, 8, WHOLE, 1, []) for nq in (16, 32, 48, 64, 96)] + \
        [("whole", 16, nz, WHOLE, 1, []) for nz in (4, 16, 32)] + \
        [("whole", 32, 32, WHOLE, 1, [])] + \
        [("full", nq, 8, FULL, 1, []) for nq in (16, 32, 48)] + \
        [("degree 2", nq, 8, P2, 1, []) for nq in (8, 16, 24)] + \
        [("degree 2 whole", nq, 8, P2 + WHOLE, 1, []) for nq in (8, 16)] + \
        [("2 processes", nq, 8, [], 2, []) for nq in (32, 48, 64)] + \
        [("gamg", nq, 8, WHOLE, 1, GAMG) for nq in (32, 64)] + \
        [("cracking", nq, 8, SHORT_CORROSION, 1, [], CRACKING) for nq in (8, 16, 24, 32)] + \
        [("cracking", 16, nz, SHORT_CORROSION, 1, [], CRACKING) for nz in (4, 16)] + \
        [("cracking 2 processes", nq, 8, SHORT_CORROSION, 2, [], CRACKING) for nq in (16, 32)]
QUICK = [c for c in CASES if c[1] * c[2] <= 32 * 8]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pushout", default=os.path.join(ROOT, "build", "pushout"))
    ap.add_argument("--out", default=os.path.join(tempfile.gettempdir(), "pushout-bench-memory"),
                    help="the folder of the runs; the tables go to bench/results")
    ap.add_argument("--quick", action="store_true", help="the smaller cases only")
    args = ap.parse_args()
    # Every case meshes, gmsh loaded: the peak of a mesh's first run, which
    # the guard must cover (a run whose mesh is in the cache does not load
    # gmsh, some 40 MB less).
    cache = tempfile.mkdtemp(prefix="pushout-bench-memory-cache-")
    atexit.register(shutil.rmtree, cache, ignore_errors=True)
    os.environ["PUSHOUT_CACHE_DIR"] = cache
    rows = []
    for path, nq, nz, sets, procs, petsc, *scene in (QUICK if args.quick else CASES):
        out = os.path.join(args.out, f"{path.replace(' ', '_')}_{nq}x{nz}")
        sets = sets + [f"mesh.elements_per_quarter={nq}", f"mesh.elements_through_thickness={nz}",
                       "loading.steps=1", "output.plot=false"]
        t0 = time.time()
        pushout_runs.run(args.pushout, scene[0] if scene else SCENE, out, sets, petsc,
                         one_thread=True, check=True,
                         mpirun=procs if procs > 1 else None)
        s = summary(out)
        est, meas = s["estimate"]["peak_memory_mb"], s["peak_memory_mb"]
        rows.append({"path": path, "mesh": f"{nq}x{nz}", "processes": procs, "dofs": s["dofs"],
                     "joint elements": s["interface_pairs"], "condensed dofs": s["condensed_dofs"],
                     "estimated peak [MB]": round(est), "measured peak [MB]": round(meas),
                     "estimate / measured": round(est / meas, 2), "wall [s]": round(time.time() - t0, 1)})
        print(rows[-1], flush=True)
    name = "memory_estimate_quick" if args.quick else "memory_estimate"
    write_csv(os.path.join(ROOT, "bench", "results", name + ".csv"), rows)
    ratios = [r["estimate / measured"] for r in rows]
    with open(os.path.join(ROOT, "bench", "results", name + ".md"), "w") as f:
        f.write(f"Made by `bench/memory_estimate.py{' --quick' if args.quick else ''}`. Peak memory is "
                "the largest resident set of a process (summary.json peak_memory_mb); the estimate is "
                "made from the mesh keys before meshing (summary.json estimate.peak_memory_mb). "
                f"Estimate / measured over all rows: {min(ratios):.2f} to {max(ratios):.2f}.\n\n")
        f.write(markdown_table(list(rows[0].keys()), rows))


if __name__ == "__main__":
    main()

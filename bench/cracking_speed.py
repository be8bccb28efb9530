#!/usr/bin/python3
"""The cost of cracks anywhere in the concrete against the one-plane
corroded demo, side by side in one run (docs/cracking-speed.md).

Cases (the paper's mesh 16/8, one thread per process, one after the
other):

  plane           demo/pushout_corroded.toml as it is: one crack plane to the
                  nearest face, 25 corrosion steps to x = 50 um, a 40-step
                  push (half model, bulk condensed: the defaults);
  plane_2proc     plane on two processes (mpirun -n 2, one thread each):
                  the like-for-like cost of the two-process rows;
  plane_full      the same on the whole slice (model.symmetry = "full"):
                  the model the cracks need, as a random field is not
                  symmetric (the like-for-like cost; ratio_to_plane_full);
  embedded        demo/pushout_corroded_cracking.toml: the same specimen
                  with [cracking] model = "embedded" instead of its crack
                  plane (f_t 3 MPa, c 30 1/mm as the plane's; strength_cov
                  0.15, seed 1: the whole slice),
                  displacement control (the default), the implicit cracks
                  (cracking.integration = "implicit"; since the IMPL-EX
                  rescue, cracking.implex_rescue, it completes, with two
                  of its steps taken as IMPL-EX steps: 2026-12-06);
  embedded_auto   the same specimen at the scene's integration ("auto":
                  IMPL-EX under every control) under loading.control =
                  "auto" (dissipation control where the cracks snap back);
  embedded_implex the same with IMPL-EX cracks (cracking.integration =
                  "implex", what its default "auto" takes under displacement
                  control; cracking.implex_tolerance at its default 0.0025,
                  the strain predictor, the default);
  embedded_implex_0.01
                  the same at implex_tolerance 0.01 (the default until
                  docs/cracking.md "Accuracy and the tolerance" made it
                  0.0025): about half the time, less accurate;
  embedded_implex_2proc
                  embedded_implex on two processes (mpirun -n 2, one
                  thread each: the LU in single precision across the two);
  embedded_implex_history
                  embedded_implex with the history predictor
                  (cracking.implex_predictor = "history": each crack's
                  damage extrapolated from the last steps, the default
                  until the strain predictor's);
  embedded_implex_radial_whole
                  embedded_implex with radial graded lines refined whole
                  (mesh.graded_lines = "radial", mesh.graded_refinement =
                  "whole": 38 016 dofs against 31 104), the layout whose
                  residual bond does not drift with the mesh
                  (docs/cracking.md, "Radial graded lines"; no error
                  columns: another mesh than the reference's);
  embedded_implex_radial_whole_2proc
                  embedded_implex_radial_whole on two processes (where
                  the LU takes SCOTCH's order: docs/performance.md, "The
                  cheaper of PORD's order and SCOTCH's");
  embedded_fine   the implicit cracks at four times the steps (100 corrosion,
                  160 push), not held to their step error (cracking.
                  implicit_tolerance = 0: 45 of its steps read above 0.0025,
                  the largest 0.22): the error columns' reference where
                  embedded_held did not run;
  embedded_held   the same steps, each held to its step error
                  (cracking.implicit_tolerance = 0.0025, IMPL-EX's
                  tolerance: a step above it is cut): the reference of the
                  error columns, converged in its steps (held to 0.001 it
                  moves by 0.04 %: bench/cracking_reference.py).

For each: wall time (with --repeat N, the median of N runs made in
interleaved rounds, every timed case once a round, so that each case's
runs sample the machine's speed at the same hours; wall_s_min and
wall_s_max beside it; embedded, embedded_fine and embedded_held, whose
times are not the target's, run once), dofs, Newton iterations, factorizations, GMRES iterations
(linear_iterations: one LU application each; blank for a run made before it
was counted), cuts, and the
seconds of each phase (step 0 with the retraction, the corrosion stage, the
push) from the wall_s columns of corrosion.csv and curve.csv; the ratio of
wall times to the plane's (and to plane_full's, and to the plane's on as
many processes as the row: plane or plane_2proc); the peak pressure and the pressure after the
corrosion stage, the residual bond stress at 0.2 mm, and, where
embedded_held (else embedded_fine) ran, the relative error of those three
against it; and when
each run was made (--reuse keeps the runs already in the folder). Writes
bench/results/cracking_speed.csv and .md.

  bench/cracking_speed.py [--reuse] [--only CASE ...] [--repeat N]
"""
import os
import statistics
import sys
import time

from common import (ROOT, arguments, check_only, curve, markdown_table, pushout_runs, ran_utc, run,
                    summary, write_csv)

RESULTS = os.path.join(ROOT, "bench", "results")


def phases(out):
    """Seconds of step 0, the corrosion stage and the push (empty: a run that
    stopped before it)."""
    corr = pushout_runs.corrosion(out)
    push = curve(out)
    t0, t_corr = corr[0]["wall_s"], corr[-1]["wall_s"]
    return round(t0, 2), round(t_corr - t0, 2), round(push[-1]["wall_s"] - t_corr, 2) if push else ""


# Run once whatever --repeat says: the implicit cracks and the fine
# reference take minutes, and neither time is the target's.
ONCE = ("embedded", "embedded_fine", "embedded_held")
# Cases on another mesh than the reference's: no error columns.
OTHER_MESH = ("embedded_implex_radial_whole", "embedded_implex_radial_whole_2proc")


def main():
    args = arguments(__doc__, "bench_cracking_speed", repeat=True)
    embedded = pushout_runs.embedded_corroded_demo(
        os.path.join(args.out, "pushout_corroded_embedded.toml"))
    # name: (scene, --set values, processes)
    cases = {
        "plane": (os.path.join(ROOT, "demo", "pushout_corroded.toml"), [], 1),
        "plane_2proc": (os.path.join(ROOT, "demo", "pushout_corroded.toml"), [], 2),
        "plane_full": (os.path.join(ROOT, "demo", "pushout_corroded.toml"),
                       ["model.symmetry=full"], 1),
        "embedded": (embedded, ["cracking.integration=implicit"], 1),
        "embedded_auto": (embedded, ["loading.control=auto"], 1),
        "embedded_implex": (embedded, ["cracking.integration=implex"], 1),
        "embedded_implex_0.01": (embedded, ["cracking.integration=implex",
                                            "cracking.implex_tolerance=0.01"], 1),
        "embedded_implex_2proc": (embedded, ["cracking.integration=implex"], 2),
        "embedded_implex_history": (embedded, ["cracking.integration=implex",
                                               "cracking.implex_predictor=history"], 1),
        "embedded_implex_radial_whole": (embedded, ["cracking.integration=implex",
                                                    "mesh.graded_lines=radial",
                                                    "mesh.graded_refinement=whole"], 1),
        "embedded_implex_radial_whole_2proc": (embedded, ["cracking.integration=implex",
                                                          "mesh.graded_lines=radial",
                                                          "mesh.graded_refinement=whole"], 2),
        "embedded_fine": (embedded, ["cracking.integration=implicit", "corrosion.steps=100",
                                     "loading.steps=160"], 1),
        "embedded_held": (embedded, ["cracking.integration=implicit", "corrosion.steps=100",
                                     "loading.steps=160", "cracking.implicit_tolerance=0.0025"],
                          1),
    }
    check_only(args, list(cases))
    chosen = [name for name in cases if not args.only or name in args.only]
    walls = {name: [] for name in chosen}  # [s] of each round's run
    for round_ in range(args.repeat):
        for name in chosen:
            if round_ > 0 and name in ONCE:
                continue
            scene, sets, processes = cases[name]
            out = os.path.join(args.out, name if round_ == 0 else f"{name}_round{round_ + 1}")
            start = time.time()
            code = run(args.pushout, scene, out, sets, reuse=args.reuse, check=False,
                       mpirun=processes if processes > 1 else None)
            print(f"{name} (round {round_ + 1}): exit {code}, {time.time() - start:.1f} s",
                  flush=True)
            walls[name].append(summary(out)["wall_s"])
    rows = []
    for name in chosen:
        out = os.path.join(args.out, name)
        s = summary(out)
        step0, corrosion, push = phases(out)
        corrosion_rows, push_rows = pushout_runs.corrosion(out), curve(out)
        rows.append({"case": name, "wall_s": round(statistics.median(walls[name]), 2),
                     "wall_s_min": round(min(walls[name]), 2),
                     "wall_s_max": round(max(walls[name]), 2), "runs": len(walls[name]),
                     "converged": s["converged"],
                     "processes": s["processes"], "symmetry": s["symmetry"],
                     "dofs": s["dofs"],
                     "condensed_dofs": s["condensed_dofs"],
                     "newton_iterations": s["newton_iterations"],
                     "factorizations": s["factorizations"],
                     "linear_iterations": s.get("linear_iterations", ""), "cuts": s["cuts"],
                     "dissipation_steps": s["dissipation_steps"], "step0_s": step0,
                     "corrosion_s": corrosion, "push_s": push,
                     "s_per_iteration": round(statistics.median(walls[name]) /
                                              max(s["newton_iterations"], 1), 3),
                     "p_peak_MPa": round(max(r["p_MPa"] for r in corrosion_rows), 4),
                     "p_corroded_MPa": round(corrosion_rows[-1]["p_MPa"], 4),
                     "tau_last_MPa": round(push_rows[-1]["tau_MPa"], 4) if push_rows else "",
                     "ran_utc": ran_utc(out)})
    plane = next((r["wall_s"] for r in rows if r["case"] == "plane"), None)
    plane_full = next((r["wall_s"] for r in rows if r["case"] == "plane_full"), None)
    # The reference: the implicit cracks held to their step error, else
    # only at fine steps.
    fine = next((r for name in ("embedded_held", "embedded_fine") for r in rows
                 if r["case"] == name and r["converged"]), None)
    # The plane on as many processes as the row: plane or plane_2proc.
    plane_on = {r["processes"]: r["wall_s"] for r in rows if r["case"] in ("plane", "plane_2proc")}
    for r in rows:
        r["ratio_to_plane"] = round(r["wall_s"] / plane, 1) if plane else ""
        same = plane_on.get(r["processes"])
        r["ratio_to_plane_same_processes"] = round(r["wall_s"] / same, 1) if same else ""
        r["ratio_to_plane_full"] = round(r["wall_s"] / plane_full, 1) if plane_full else ""
        # Errors of the runs that finished, against the reference.
        for key in ("p_peak_MPa", "p_corroded_MPa", "tau_last_MPa"):
            r[key.replace("_MPa", "_error_pct")] = (
                round(100 * (r[key] / fine[key] - 1), 2)
                if fine and r["converged"] and r["case"].startswith("embedded")
                and r["case"] not in OTHER_MESH else "")
    os.makedirs(RESULTS, exist_ok=True)
    write_csv(os.path.join(RESULTS, "cracking_speed.csv"), rows)
    with open(os.path.join(RESULTS, "cracking_speed.md"), "w") as f:
        f.write("# Cracks anywhere: cost against the one-plane corroded demo\n\n"
                "Made by `bench/cracking_speed.py " + " ".join(sys.argv[1:]) +
                "` (one thread per process, this machine; wall_s the median of the row's "
                "runs, made in interleaved rounds, the other columns of its first run; the "
                "error columns against " + (fine["case"] if fine else "(no reference ran)") +
                "; ran_utc: when each row's first run was "
                "made, as --reuse keeps earlier runs).\n\n")
        f.write(markdown_table(list(rows[0].keys()), rows))
    print(markdown_table(list(rows[0].keys()), rows))


if __name__ == "__main__":
    main()

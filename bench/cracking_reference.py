#!/usr/bin/python3
"""How the two integrations of the cracks in the concrete converge with
their steps on the bench's corroded scene (docs/cracking-speed.md, "The
reference held to its step error"): which reference the error columns of
bench/cracking_speed.py may trust, and how far IMPL-EX lies from it.

The scene is bench/cracking_speed.py's (demo/pushout_corroded_cracking.toml:
cover 15 mm, x = 50 um in 25 corrosion steps, a 0.2 mm push in 40, the
paper's mesh, seed 1). Cases (one thread, one after the other):

  implicit_25     the implicit cracks at the scene's steps, not held to
                  their step error (cracking_speed.py's embedded);
  implicit_100    at four times the steps, 100 + 160 (embedded_fine);
  implicit_400    at 400 corrosion steps, 160 push steps;
  held_25         at the scene's steps, each held to its step error
                  (cracking.implicit_tolerance = 0.0025, IMPL-EX's default);
  held_0.0025     100 + 160, held to 0.0025 (cracking_speed.py's
                  embedded_held, its error columns' reference);
  held_0.001      100 + 160, held to 0.001: the reference of this table;
  implex_0.0025   IMPL-EX at its defaults (embedded_implex);
  implex_0.001, implex_0.0005
                  IMPL-EX at cracking.implex_tolerance 0.001 and 0.0005;
  implex_0.0005_history
                  at 0.0005 with the history predictor
                  (cracking.implex_predictor = "history");
  implex_0.0005_push640
                  at 0.0005 with 640 push steps instead of 40.

For each: the corrosion stage's rows and the push's, Newton iterations,
factorisations, wall time, the peak pressure, the pressure at x = 30 um
and after the corrosion stage, the residual bond stress at 0.2 mm, by how
much the push lowers the pressure on the tube (push_p_drop: p after the
corrosion stage less p at the push's end), the cracked points and the
concrete's dissipation after the corrosion stage, the widest surface
crack, and the relative error of p at 30 um, p after the corrosion
stage, the bond and the drop against held_0.001 (of the unrounded
values). About two hours on one core (held_0.001 alone 25 min); --reuse
keeps the converged runs already in the folder (a run that stopped is
made again). Writes bench/results/cracking_reference.csv and .md.

  bench/cracking_reference.py [--pushout PATH] [--out DIR] [--reuse] [--only CASE ...]
"""
import os
import sys
import time

from common import (ROOT, arguments, check_only, curve, markdown_table, pushout_runs, ran_utc, run,
                    summary, write_csv)

RESULTS = os.path.join(ROOT, "bench", "results")
REFERENCE = "held_0.001"

IMPLICIT = ["cracking.integration=implicit"]
FOUR_TIMES = ["corrosion.steps=100", "loading.steps=160"]
IMPLEX = ["cracking.integration=implex"]

# name: --set values
CASES = {
    "implicit_25": IMPLICIT,
    "implicit_100": IMPLICIT + FOUR_TIMES,
    "implicit_400": IMPLICIT + ["corrosion.steps=400", "loading.steps=160"],
    "held_25": IMPLICIT + ["cracking.implicit_tolerance=0.0025"],
    "held_0.0025": IMPLICIT + FOUR_TIMES + ["cracking.implicit_tolerance=0.0025"],
    "held_0.001": IMPLICIT + FOUR_TIMES + ["cracking.implicit_tolerance=0.001"],
    "implex_0.0025": IMPLEX,
    "implex_0.001": IMPLEX + ["cracking.implex_tolerance=0.001"],
    "implex_0.0005": IMPLEX + ["cracking.implex_tolerance=0.0005"],
    "implex_0.0005_history": IMPLEX + ["cracking.implex_tolerance=0.0005",
                                       "cracking.implex_predictor=history"],
    "implex_0.0005_push640": IMPLEX + ["cracking.implex_tolerance=0.0005", "loading.steps=640"],
}


def p_at(corrosion, x_mm):
    """The pressure on the tube at penetration x_mm, linear between rows [MPa]."""
    for a, b in zip(corrosion, corrosion[1:]):
        if a["penetration_mm"] <= x_mm <= b["penetration_mm"]:
            dx = b["penetration_mm"] - a["penetration_mm"]
            t = (x_mm - a["penetration_mm"]) / dx if dx > 0 else 0.0
            return a["p_MPa"] + t * (b["p_MPa"] - a["p_MPa"])
    return float("nan")


def row(name, out):
    """The case's row of the table, and the values compared with the
    reference's, unrounded (None where the run has no push)."""
    s = summary(out)
    corrosion = pushout_runs.corrosion(out)
    push = curve(out)
    last = corrosion[-1]
    compared = {"p_30um_MPa": p_at(corrosion, 0.030), "p_corroded_MPa": last["p_MPa"],
                "tau_last_MPa": push[-1]["tau_MPa"] if push else None,
                "push_p_drop_MPa": last["p_MPa"] - push[-1]["p_MPa"] if push else None}
    return {"case": name, "converged": s["converged"], "corrosion_rows": len(corrosion),
            "push_rows": len(push), "newton_iterations": s["newton_iterations"],
            "factorizations": s["factorizations"], "wall_s": round(s["wall_s"], 1),
            "p_peak_MPa": round(max(r["p_MPa"] for r in corrosion), 4),
            **{key: "" if v is None else round(v, 4) for key, v in compared.items()},
            "cracked_points": int(last["cracked_points"]),
            "dissipation_Nmm": round(last["concrete_dissipation_Nmm"], 3),
            "crack_width_um": round(1e3 * last["crack_width_mm"], 2),
            "ran_utc": ran_utc(out)}, compared


def main():
    args = arguments(__doc__, "bench_cracking_reference")
    check_only(args, list(CASES))
    scene = pushout_runs.embedded_corroded_demo(
        os.path.join(args.out, "pushout_corroded_embedded.toml"))
    rows, compared = [], {}  # compared: the case's unrounded values (row())
    for name, sets in CASES.items():
        out = os.path.join(args.out, name)
        if not args.only or name in args.only:
            start = time.time()
            reuse = args.reuse and pushout_runs.converged_before(out)
            code = run(args.pushout, scene, out, sets, reuse=reuse, check=False)
            print(f"{name}: exit {code}, {time.time() - start:.1f} s", flush=True)
        if os.path.exists(os.path.join(out, "summary.json")):
            r, compared[name] = row(name, out)
            rows.append(r)
    if not rows:
        raise SystemExit("cracking_reference.py: no run to tabulate in " + args.out)
    reference = next((r for r in rows if r["case"] == REFERENCE and r["converged"]), None)
    for r in rows:
        for key, value in compared[r["case"]].items():
            r[key.replace("_MPa", "_error_pct")] = (
                round(100 * (value / compared[REFERENCE][key] - 1), 2)
                if reference and r["converged"] and value is not None else "")
    os.makedirs(RESULTS, exist_ok=True)
    write_csv(os.path.join(RESULTS, "cracking_reference.csv"), rows)
    with open(os.path.join(RESULTS, "cracking_reference.md"), "w") as f:
        f.write("# The cracks' two integrations against their steps\n\n"
                "Made by `bench/cracking_reference.py " + " ".join(sys.argv[1:]) +
                "` (one thread, this machine; the error columns against " +
                (REFERENCE if reference else "(no reference ran)") +
                "; ran_utc: when each run was made, as --reuse keeps earlier runs).\n\n")
        f.write(markdown_table(list(rows[0].keys()), rows))
    print(markdown_table(list(rows[0].keys()), rows))


if __name__ == "__main__":
    main()

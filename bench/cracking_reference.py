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
  implex_0.001, implex_0.0005, implex_0.00025, implex_0.0001
                  IMPL-EX at cracking.implex_tolerance 0.001 to 0.0001;
  implex_0.0005_history
                  at 0.0005 with the history predictor
                  (cracking.implex_predictor = "history");
  implex_0.0005_push640
                  at 0.0005 with 640 push steps instead of 40;
  seedN_held_25, seedN_implex_0.0025, seedN_implex_0.0001 (N = 2 to 5)
                  held_25, implex_0.0025 and implex_0.0001 on the field of
                  cracking.seed N: whether IMPL-EX's distance from the
                  implicit cracks' converged path on seed 1 holds on other
                  fields, and whether a tighter tolerance closes it there;
  seedN_held_0.001 (N = 2 to 5)
                  held_0.001 on the other fields: whether held_25 is
                  converged there too;
  seedN_held_25_covC, seedN_implex_0.0025_covC (N = 1 to 5, C = 0.1485
                  and 0.1515)
                  held_25 and implex_0.0025 on the field of seed N with
                  its scatter (cracking.strength_cov, 0.15 in the scene)
                  changed by 1 %: where the two integrations' crack
                  patterns differ, whether each keeps its own under a
                  change of the field far below what is known of any
                  concrete (IMPL-EX's error) or the implicit cracks then
                  take IMPL-EX's (two branches near to equally likely).

For each: the corrosion stage's rows and the push's, Newton iterations,
factorisations, wall time, the peak pressure, the pressure at x = 30 um
and after the corrosion stage, the residual bond stress at 0.2 mm, by how
much the push lowers the pressure on the tube (push_p_drop: p after the
corrosion stage less p at the push's end), the cracked points and the
concrete's dissipation after the corrosion stage, the widest surface
crack, and the relative error of p at 30 um, p after the corrosion
stage, the bond and the drop against held_0.001 (of the unrounded
values). Writes bench/results/cracking_reference.csv and .md (seed 1's
cases) and cracking_reference_seeds.csv and .md, a row per seed: the held
implicit cracks at the scene's steps (held_25; on seed 1 within 0.03 % of
held_0.001 on p and tau): their wall time, steps taken above the tolerance
and largest step error, IMPL-EX rescues, p after the corrosion stage, the
bond at 0.2 mm and the push's drop of p; and for IMPL-EX at 0.0025 and at
0.0001 (columns suffixed by the tolerance): how far its corrosion stage
got (x_reached_um, 50 when complete), its wall time and jumps
(implex_jumps), the relative error of those three values against
held_25, and opening_not_shared_pct, the share of the two runs' crack
opening after corrosion that is not common to both (crack_pattern.csv:
the sum over columns of |w - w_held| over that of w + w_held); and where
held_0.001 ran on the seed (seedN_held_0.001), held_25's relative error
against it (the _error_pct_held_0.001 columns) and the two's opening not
shared. And cracking_reference_perturbed.csv and .md, a row per seed and
changed scatter: the held run's bond against the seed's held_25
(tau_change_pct_held) and the share of its opening not shared with
held_25 and with implex_0.0025 of the unchanged field (which pattern it
took: pattern_held, "held_25's" or "IMPL-EX's", the one it shares more
with), and IMPL-EX's on the changed field against the held run on it
(tau_error_pct_implex, opening_not_shared_pct_implex) and against its
own run on the unchanged field (opening_not_shared_pct_implex_unchanged).

The seeds' runs at 0.0001 are stopped after an hour (TIGHT_SECONDS, as by
Ctrl-C: their summary.json says interrupted): on some fields that
tolerance meets the floor of IMPL-EX's error and takes its smallest steps
for hours. --reuse keeps the converged runs already in the folder and
those stopped runs (any other run that stopped is made again). Run times
on one core: seed 1's cases some 2.6 hours (held_0.001 alone 25 min,
implex_0.00025 23 min), the seeds' about 6.5 hours (each held_25 22 to
29 min, each held_0.001 25 to 30 min, each IMPL-EX run at 0.0001 10 min
to the hour's stop), the changed fields' about 3 hours (each held run 15
to 17 min, each IMPL-EX run 1 to 2 min).

  bench/cracking_reference.py [--pushout PATH] [--out DIR] [--reuse] [--only CASE ...]
"""
import csv
import functools
import os
import sys
import time

from common import (ROOT, arguments, check_only, curve, markdown_table, pushout_runs, ran_utc, run,
                    summary, write_csv)

RESULTS = os.path.join(ROOT, "bench", "results")
REFERENCE = "held_0.001"
# The values compared between runs (row()'s second answer) on each seed.
COMPARED = ("p_corroded_MPa", "tau_last_MPa", "push_p_drop_MPa")

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
    "implex_0.00025": IMPLEX + ["cracking.implex_tolerance=0.00025"],
    "implex_0.0001": IMPLEX + ["cracking.implex_tolerance=0.0001"],
    "implex_0.0005_history": IMPLEX + ["cracking.implex_tolerance=0.0005",
                                       "cracking.implex_predictor=history"],
    "implex_0.0005_push640": IMPLEX + ["cracking.implex_tolerance=0.0005", "loading.steps=640"],
}
# Seed 1's runs are the cases above of these names; the other seeds':
SEEDS = (2, 3, 4, 5)
ON_EACH_SEED = ("held_25", "implex_0.0025", "implex_0.0001")
# The seeds whose held runs are checked against held_0.001, as seed 1's
# are (all of them; 3 and 5 first, where IMPL-EX at 0.0001 met the floor
# of its error and nothing else checked them).
CROSS_CHECKED = SEEDS
SEED_CASES = {f"seed{seed}_{name}": CASES[name] + [f"cracking.seed={seed}"]
              for seed in SEEDS for name in ON_EACH_SEED}
SEED_CASES.update({f"seed{seed}_held_0.001": CASES["held_0.001"] + [f"cracking.seed={seed}"]
                   for seed in CROSS_CHECKED})
# The fields changed by 1 % of their scatter (the scene's strength_cov 0.15):
# each seed's held_25 and implex_0.0025 again on each.
PERTURBED_COVS = ("0.1485", "0.1515")
PERTURBED = ("held_25", "implex_0.0025")
SEED_CASES.update({f"seed{seed}_{name}_cov{cov}": CASES[name] + [f"cracking.seed={seed}",
                                                                   f"cracking.strength_cov={cov}"]
                   for seed in (1,) + SEEDS for cov in PERTURBED_COVS for name in PERTURBED})
# The seeds' runs at 0.0001 are stopped after TIGHT_SECONDS (the docstring
# says why); --reuse keeps them stopped.
CAPPED = {f"seed{seed}_implex_0.0001" for seed in SEEDS}
TIGHT_SECONDS = 3600
# Each IMPL-EX run's columns in the seeds' table (suffixed by its tolerance).
SEED_COLUMNS = ("x_reached_um", "wall_s", "implex_jumps", "p_corroded_error_pct",
                "tau_last_error_pct", "push_p_drop_error_pct", "opening_not_shared_pct")


def p_at(corrosion, x_mm):
    """The pressure on the tube at penetration x_mm, linear between rows [MPa]."""
    for a, b in zip(corrosion, corrosion[1:]):
        if a["penetration_mm"] <= x_mm <= b["penetration_mm"]:
            dx = b["penetration_mm"] - a["penetration_mm"]
            t = (x_mm - a["penetration_mm"]) / dx if dx > 0 else 0.0
            return a["p_MPa"] + t * (b["p_MPa"] - a["p_MPa"])
    return float("nan")


@functools.lru_cache(maxsize=None)
def tables(out):
    """out/'s summary.json, corrosion.csv and curve.csv, each read once."""
    return summary(out), pushout_runs.corrosion(out), curve(out)


def row(name, out):
    """The case's row of the table, and the values compared with the
    reference's, unrounded (None where the run has no push)."""
    s, corrosion, push = tables(out)
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


def error_pct(value, reference):
    """value's relative error against reference [%], to 0.01."""
    return round(100 * (value / reference - 1), 2)


def column_openings(out):
    """crack_pattern.csv: each column's crack opening after the corrosion
    stage [mm], by the column's centre."""
    with open(os.path.join(out, "crack_pattern.csv")) as f:
        return {(r["x_mm"], r["y_mm"]): float(r["opening_mm"]) for r in csv.DictReader(f)}


def opening_not_shared(held, other):
    """The share of two runs' crack opening after corrosion that is not
    common to both [%]: the sum over columns of |w - w_held| over the sum
    of w + w_held (0: the same openings in the same columns; 100: no
    column open in both)."""
    a, b = column_openings(held), column_openings(other)
    columns = set(a) | set(b)
    differ = sum(abs(b.get(c, 0.0) - a.get(c, 0.0)) for c in columns)
    total = sum(a.get(c, 0.0) + b.get(c, 0.0) for c in columns)
    return round(100 * differ / total, 1) if total > 0 else 0.0


def against_finer_held(held_25, held, finer):
    """The seeds' table's columns of held_25 against the same field's
    held_0.001 in folder `finer` (blank where it did not run): the
    relative errors of the COMPARED values (held: held_25's) and the
    opening not shared."""
    columns = {key.replace("_MPa", "_error_pct_held_0.001"): "" for key in COMPARED}
    columns["opening_not_shared_pct_held_0.001"] = ""
    if pushout_runs.converged_before(finer):
        _, values = row(REFERENCE, finer)
        for key in COMPARED:
            columns[key.replace("_MPa", "_error_pct_held_0.001")] = error_pct(held[key], values[key])
        columns["opening_not_shared_pct_held_0.001"] = opening_not_shared(finer, held_25)
    return columns


def seed_rows(out):
    """Each seed's runs (ON_EACH_SEED, from out/): the held implicit
    cracks' values, and each IMPL-EX run's beside them (SEED_COLUMNS)."""
    rows = []
    for seed in (1,) + SEEDS:
        runs = {name: seed_run(out, seed, name) for name in ON_EACH_SEED}
        if not pushout_runs.converged_before(runs["held_25"]):
            continue
        _, held = row("held_25", runs["held_25"])
        s = tables(runs["held_25"])[0]
        r = {"seed": seed, "wall_s_held": round(s["wall_s"], 1),
             "implicit_jumps_held": s["implicit_jumps"],
             "implicit_error_max_held": round(s["implicit_error_max"], 4),
             "implex_rescues_held": s["implex_rescues"],
             **{key + "_held": round(held[key], 4) for key in COMPARED}}
        r.update(against_finer_held(runs["held_25"], held,
                                    seed_run(out, seed, REFERENCE)))
        for name in ON_EACH_SEED[1:]:
            tolerance = name.split("_")[1]
            columns = {f"{c}_{tolerance}": "" for c in SEED_COLUMNS}
            o = runs[name]
            converged = pushout_runs.converged_before(o)
            if (converged or pushout_runs.summary_says(o, "interrupted")) and tables(o)[1]:
                s, corrosion, _ = tables(o)
                columns.update({f"x_reached_um_{tolerance}":
                                round(1e3 * corrosion[-1]["penetration_mm"], 2),
                                f"wall_s_{tolerance}": round(s["wall_s"], 1),
                                f"implex_jumps_{tolerance}": s["implex_jumps"]})
            if converged:
                _, values = row(name, o)
                for key in COMPARED:
                    columns[key.replace("_MPa", f"_error_pct_{tolerance}")] = error_pct(values[key],
                                                                                        held[key])
                columns[f"opening_not_shared_pct_{tolerance}"] = opening_not_shared(
                    runs["held_25"], o)
            r.update(columns)
        rows.append(r)
    return rows


def seed_run(out, seed, name):
    """The folder of case `name` (a name of CASES, perhaps with a suffix)
    on seed `seed` in out/ (seed 1's unchanged field: the name alone)."""
    return os.path.join(out, name if seed == 1 and not name.endswith(PERTURBED_COVS)
                        else f"seed{seed}_{name}")


def perturbed_rows(out):
    """A row per seed and changed scatter whose held run converged: which
    crack pattern the held implicit cracks take there, and IMPL-EX's
    distance from them on the same changed field (the module's docstring)."""
    rows = []
    for seed in (1,) + SEEDS:
        held, implex = seed_run(out, seed, "held_25"), seed_run(out, seed, "implex_0.0025")
        if not (pushout_runs.converged_before(held) and pushout_runs.converged_before(implex)):
            continue
        tau_held = row("held_25", held)[1]["tau_last_MPa"]
        for cov in PERTURBED_COVS:
            held_c = seed_run(out, seed, f"held_25_cov{cov}")
            implex_c = seed_run(out, seed, f"implex_0.0025_cov{cov}")
            if not pushout_runs.converged_before(held_c):
                continue
            s, values = tables(held_c)[0], row("held_25", held_c)[1]
            with_held, with_implex = opening_not_shared(held, held_c), opening_not_shared(implex, held_c)
            r = {"seed": seed, "strength_cov": cov, "wall_s_held": round(s["wall_s"], 1),
                 "tau_last_MPa_held": round(values["tau_last_MPa"], 4),
                 "tau_change_pct_held": error_pct(values["tau_last_MPa"], tau_held),
                 "opening_not_shared_pct_with_held_25": with_held,
                 "opening_not_shared_pct_with_implex_0.0025": with_implex,
                 "pattern_held": "held_25's" if with_held <= with_implex else "IMPL-EX's",
                 "tau_error_pct_implex": "", "opening_not_shared_pct_implex": "",
                 "opening_not_shared_pct_implex_unchanged": ""}
            if pushout_runs.converged_before(implex_c):
                r.update({"tau_error_pct_implex": error_pct(row("implex", implex_c)[1]["tau_last_MPa"],
                                                            values["tau_last_MPa"]),
                          "opening_not_shared_pct_implex": opening_not_shared(held_c, implex_c),
                          "opening_not_shared_pct_implex_unchanged": opening_not_shared(implex,
                                                                                        implex_c)})
            rows.append(r)
    return rows


def write_table(name, title, made_by, rows):
    """bench/results/NAME.csv and NAME.md (a title, how it was made, the table)."""
    os.makedirs(RESULTS, exist_ok=True)
    write_csv(os.path.join(RESULTS, name + ".csv"), rows)
    with open(os.path.join(RESULTS, name + ".md"), "w") as f:
        f.write(f"# {title}\n\n{made_by}\n\n")
        f.write(markdown_table(list(rows[0].keys()), rows))
    print(markdown_table(list(rows[0].keys()), rows))


def main():
    args = arguments(__doc__, "bench_cracking_reference")
    every_case = {**CASES, **SEED_CASES}
    check_only(args, list(every_case))
    scene = pushout_runs.embedded_corroded_demo(
        os.path.join(args.out, "pushout_corroded_embedded.toml"))
    for name, sets in every_case.items():
        if not args.only or name in args.only:
            out = os.path.join(args.out, name)
            start = time.time()
            capped = name in CAPPED
            reuse = args.reuse and (pushout_runs.converged_before(out) or
                                    capped and pushout_runs.summary_says(out, "interrupted"))
            code = run(args.pushout, scene, out, sets, reuse=reuse, check=False,
                       stop_after=TIGHT_SECONDS if capped else None)
            print(f"{name}: exit {code}, {time.time() - start:.1f} s", flush=True)
    rows, compared = [], {}  # compared: the case's unrounded values (row())
    for name in CASES:
        out = os.path.join(args.out, name)
        if os.path.exists(os.path.join(out, "summary.json")):
            if not tables(out)[1]:
                print(f"{name}: stopped before its first corrosion row, left out of the table")
                continue
            r, compared[name] = row(name, out)
            rows.append(r)
    if not rows:
        raise SystemExit("cracking_reference.py: no run to tabulate in " + args.out)
    reference = next((r for r in rows if r["case"] == REFERENCE and r["converged"]), None)
    for r in rows:
        for key, value in compared[r["case"]].items():
            r[key.replace("_MPa", "_error_pct")] = (
                error_pct(value, compared[REFERENCE][key])
                if reference and r["converged"] and value is not None else "")
    command = "Made by `bench/cracking_reference.py " + " ".join(sys.argv[1:]) + "` (one thread, this machine"
    write_table("cracking_reference", "The cracks' two integrations against their steps",
                command + "; the error columns against " +
                (REFERENCE if reference else "(no reference ran)") +
                "; ran_utc: when each run was made, as --reuse keeps earlier runs).", rows)
    seeds = seed_rows(args.out)
    if seeds:
        write_table("cracking_reference_seeds", "IMPL-EX against the held implicit cracks on five fields",
                    command + "; on each seed the held implicit cracks at the scene's steps "
                    "(held_25) and IMPL-EX at its tolerance 0.0025 and 0.0001: its relative "
                    "error against held_25 in the _error_pct columns, and opening_not_shared_pct "
                    "the share of the two runs' crack opening after corrosion not common to "
                    "both, sum |w - w_held| / sum (w + w_held) over crack_pattern.csv's "
                    "columns); the _held_0.001 columns: held_25 against the same field's "
                    "held_0.001, where it ran).", seeds)
    perturbed = perturbed_rows(args.out)
    if perturbed:
        write_table("cracking_reference_perturbed",
                    "The held implicit cracks and IMPL-EX on fields changed by 1 % of their scatter",
                    command + "; each seed's field with cracking.strength_cov 0.1485 and 0.1515 "
                    "instead of 0.15: the held run's bond against the seed's held_25 and the share "
                    "of its crack opening after corrosion not shared with held_25 and with "
                    "implex_0.0025 of the unchanged field (pattern_held: the one it shares more "
                    "with); IMPL-EX on the changed field against the held run on it, and its "
                    "opening not shared with its own run on the unchanged field).", perturbed)


if __name__ == "__main__":
    main()

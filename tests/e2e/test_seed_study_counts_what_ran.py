"""The corroded seed study's tables and figures (scripts/embedded_study.py,
docs/corrosion.md) count what ran and what converged: built here from run
folders written by hand (no pushout run), so every number is known.

Three seeds per case, x = 0 and 50 um; one run fails (cover15, beta 3,
seed 3, x = 50 um). Checked: the per-run table leaves it out and names it;
its group has seeds 2 of seeds_run 3, and the figure's title says so; the
groups' mean, min and max are those of the converged seeds; the first
visible crack is the first corrosion row with a surface crack; the widest
surface crack's angle is the widest concrete crack's; both figures are
written.
"""
import contextlib
import csv
import io
import json
import os
import statistics
import sys

from common import SOURCE, check, out_dir

sys.path.insert(0, os.path.join(SOURCE, "scripts"))
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import embedded_study  # noqa: E402

STUDY = "corroded_embedded_implex_strain"
SEEDS = (1, 2, 3)
FAILED = "cover15_beta3_seed3_x50"
out = out_dir("seed_study_counts")


def write_csv(path, header, rows):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(rows)


def tau_residual(where, beta, seed, x_um):
    """A number distinct for every run [MPa]."""
    return 0.6 + 0.01 * x_um / beta + 0.05 * seed + (0.3 if where == "centred" else 0.0)


def write_run(where, beta, seed, x_um):
    name = f"{where}_beta{beta:g}_seed{seed}_x{x_um:g}"
    folder = os.path.join(out, STUDY, name)
    os.makedirs(folder, exist_ok=True)
    converged = name != FAILED
    tau = tau_residual(where, beta, seed, x_um)
    rows = [] if not converged else [[0.0, 2.0 + seed, 0.0], [0.1, 2.5, tau + 0.2], [0.2, 2.4, tau]]
    write_csv(os.path.join(folder, "curve.csv"), ["delta_mm", "p_MPa", "tau_MPa"], rows)
    cracks = []
    if x_um > 0:
        # The surface crack reads visible (>= 1) from x = 10 + seed um on.
        corr = [[1e-3 * x, 0.01 * x, int(x >= 10 + seed)] for x in (0.0, 5.0, 10.0 + seed, x_um)]
        write_csv(os.path.join(folder, "corrosion.csv"),
                  ["penetration_mm", "crack_width_mm", "cracks_at_surface"], corr)
        cracks = [{"source": "plane", "angle_deg": 90.0, "width_mm": 9.0, "length_mm": 15.0},
                  {"source": "concrete", "angle_deg": 270.0 + seed, "width_mm": 0.2, "length_mm": 15.0},
                  {"source": "concrete", "angle_deg": 10.0, "width_mm": 0.1, "length_mm": 5.0}]
        corners = [0, 0, 1, 0, 1, 1, 0, 1]
        write_csv(os.path.join(folder, "crack_pattern.csv"),
                  ["x_mm", "y_mm", "opening_mm", "size_mm"] +
                  [f"corner_{k}_{a}_mm" for k in range(4) for a in "xy"],
                  [[0.5, 0.5, 0.01 * seed, 1.0] + corners])
    with open(os.path.join(folder, "summary.json"), "w") as f:
        json.dump({"converged": converged, "message": "" if converged else "did not converge (test)",
                   "cracks": cracks, "newton_iterations": 10}, f)
    return name, rows


runs = {}
for where, _ in embedded_study.WHERE:
    for beta in embedded_study.BETAS:
        for seed in SEEDS:
            for x_um in (0.0, 50.0):
                name, rows = write_run(where, beta, seed, x_um)
                runs[(STUDY, name)] = [{"delta_mm": r[0], "p_MPa": r[1], "tau_MPa": r[2]} for r in rows]

said = io.StringIO()
with contextlib.redirect_stdout(said):
    groups = embedded_study.report(plt, out, runs, STUDY)
check(FAILED in said.getvalue(), f"the failed run is named: {said.getvalue()!r}")

with open(os.path.join(out, f"{STUDY}.csv"), newline="") as f:
    table = list(csv.DictReader(f))
check(len(table) == len(runs) - 1 and FAILED not in {r["case"] for r in table},
      f"the per-run table has the {len(runs) - 1} converged runs: {len(table)}")
for r in table:
    where, beta, seed, x = embedded_study.parse(r["case"])
    check(abs(float(r["tau_residual_MPa"]) - tau_residual(where, beta, seed, x)) < 1e-12,
          f"{r['case']}: the residual is the curve's last tau")
    check(abs(float(r["tau_peak_MPa"]) - (tau_residual(where, beta, seed, x) + 0.2)) < 1e-12,
          f"{r['case']}: the peak is the curve's largest tau")
    if x > 0:
        # The depth goes through mm and back: equal to round-off.
        check(abs(float(r["first_visible_x_um"]) - (10.0 + seed)) < 1e-9,
              f"{r['case']}: first visible at {r['first_visible_x_um']} um, written {10 + seed}")
        check(float(r["widest_angle_deg"]) == 270.0 + seed,
              f"{r['case']}: the widest concrete crack's angle, {r['widest_angle_deg']}")
        check(abs(float(r["surface_crack_um"]) - 10 * x) < 1e-9,
              f"{r['case']}: the last corrosion row's crack, {r['surface_crack_um']} um")

by_group = {(g["tube"], g["beta"], g["x_um"]): g for g in groups}
for (where, beta, x), g in by_group.items():
    ran = [s for s in SEEDS if f"{where}_beta{beta:g}_seed{s}_x{x:g}" != FAILED]
    taus = [tau_residual(where, beta, s, x) for s in ran]
    check(g["seeds"] == len(ran) and g["seeds_run"] == len(SEEDS),
          f"{where} beta {beta:g} x {x:g}: {g['seeds']} of {g['seeds_run']} seeds, "
          f"{len(ran)} of {len(SEEDS)} converged")
    check(abs(g["tau_residual_MPa_mean"] - statistics.mean(taus)) < 1e-12 and
          g["tau_residual_MPa_min"] == min(taus) and g["tau_residual_MPa_max"] == max(taus),
          f"{where} beta {beta:g} x {x:g}: mean and range of the converged seeds")
title = embedded_study.seed_count(groups)
check(title == "3 seeds, 2 converged in 1 group", f"the figure's seed count: {title!r}")
for figure in ("residual_bond", "patterns"):
    path = os.path.join(out, f"{STUDY}_{figure}.png")
    check(os.path.getsize(path) > 0, f"{path} written")
print("seed study tables: ok")

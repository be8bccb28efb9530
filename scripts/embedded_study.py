"""The corroded study on cracks anywhere in the concrete (scripts/studies.py
--only corroded_embedded; docs/corrosion.md).

demo/pushout_corroded.toml with [cracking] model = "embedded" instead of its
crack plane (f_t 3 MPa, c 30 1/mm as the plane's: G_F 0.1 N/mm; a random
strength field of cov 0.15 and correlation length 5 mm): the tube centred
or 15 mm from a face, beta 2 or 3, seeds 1-5, corroded to x = 0, 12.5, 25,
50 um in steps of 2.5 um, then pushed 0.2 mm; the implicit cracks under
loading.control = "auto" (dissipation control where a crack snaps back),
IMPL-EX's under displacement control. Run it through scripts/studies.py
(--only STUDY, STUDIES below), which imports it. Per run: the pressure and the
widest surface crack after corrosion, the bond's peak and the residual at
0.2 mm; per group of seeds: their mean and range (the error bars); the
crack patterns after corrosion to 50 um, one per seed.
"""
import collections
import csv
import os
import statistics
import sys

import plot_curve
import pushout_runs

SEEDS = (1, 2, 3, 4, 5)
DEPTHS_UM = (0.0, 12.5, 25.0, 50.0)
WHERE = (("centred", "[50.0, 50.0]"), ("cover15", "[50.0, 25.0]"))
BETAS = (2.0, 3.0)
SCENE = "pushout_corroded_embedded.toml"
# Each study's integration of the cracks (cracking.integration), whether it
# runs on the paper's mesh (16 per quarter, 8 through the thickness) instead
# of the crack-plane series' 12 / 4 (scripts/studies.py mesh_sets), and its
# cracking.implex_tolerance (None: the default, 0.0025, where the centred
# tube's cover picks the main crack of a converged integration;
# docs/cracking.md, "Accuracy and the tolerance"), and its
# cracking.implex_predictor (None: the default, "strain"; the series run
# before it became the default name "history", so that they rerun with the
# predictor they ran with, though not bit for bit: step 0 extrapolates its
# parts since de9cf8a; the paper's-mesh series ran with "history" until its
# rerun after a2cc244; docs/corrosion.md), and its cracking.band_width (None:
# the default, "projected"; docs/cracking.md, "The band's width"), and its
# mesh.graded_lines and mesh.graded_refinement (docs/cracking.md, "Radial
# graded lines"), both always set, so that a study reruns on the mesh it ran
# on whatever the demo's [mesh] says.
Study = collections.namedtuple("Study",
                               "integration paper_mesh tolerance predictor band lines refinement",
                               defaults=("blocks", "near_tube"))
STUDIES = {
    "corroded_embedded": Study("implicit", False, None, None, None),
    "corroded_embedded_implex": Study("implex", False, None, "history", None),
    "corroded_embedded_paper_mesh": Study("implex", True, None, "strain", None),
    "corroded_embedded_implex_strain": Study("implex", False, None, "strain", None),
    "corroded_embedded_row_band": Study("implex", False, None, "strain", "row"),
    "corroded_embedded_row_band_paper_mesh": Study("implex", True, None, "strain", "row"),
    "corroded_embedded_radial": Study("implex", False, None, "strain", None, "radial"),
    "corroded_embedded_radial_paper_mesh": Study("implex", True, None, "strain", None, "radial"),
    "corroded_embedded_radial_whole_paper_mesh": Study("implex", True, None, "strain", None,
                                                       "radial", "whole"),
}
VISIBLE_UM = 50.0  # the [cracking] visible_width default: a surface crack counts from here


def on_paper_mesh(study):
    """Whether `study` (STUDIES) runs on the paper's mesh."""
    return STUDIES[study].paper_mesh


def write_scene(out):
    """OUT/pushout_corroded_embedded.toml: the corroded demo, [cracking] for its plane."""
    return pushout_runs.embedded_corroded_demo(os.path.join(out, SCENE))


def cases(quick, study="corroded_embedded"):
    """(name, scene, --set list) of every run of `study` (STUDIES); --quick:
    seeds 1 and 2 only."""
    out = []
    for where, centre in WHERE:
        for beta in BETAS:
            for seed in SEEDS[:2] if quick else SEEDS:
                for x_um in DEPTHS_UM:
                    sets = [f"geometry.tube_center={centre}", f"corrosion.beta={beta}",
                            f"corrosion.penetration={x_um / 1e3}",
                            f"corrosion.steps={max(1, round(x_um / 2.5))}",
                            f"loading.steps={10 if quick else 20}", f"cracking.seed={seed}"]
                    if STUDIES[study].integration == "implex":  # its steps jump where the cover snaps back
                        sets.append("cracking.integration=implex")
                        if STUDIES[study].tolerance is not None:
                            sets.append(f"cracking.implex_tolerance={STUDIES[study].tolerance}")
                        if STUDIES[study].predictor is not None:
                            sets.append(f"cracking.implex_predictor={STUDIES[study].predictor}")
                    else:
                        # The centred tube's cover snaps back past the peak
                        # pressure, which control of x alone cannot pass.
                        sets += ["loading.control=auto", "cracking.integration=implicit"]
                    if STUDIES[study].band is not None:
                        sets.append(f"cracking.band_width={STUDIES[study].band}")
                    sets += [f"mesh.graded_lines={STUDIES[study].lines}",
                             f"mesh.graded_refinement={STUDIES[study].refinement}"]
                    out.append((f"{where}_beta{beta:g}_seed{seed}_x{x_um:g}", SCENE, sets))
    return out


def parse(name):
    where, beta, seed, x = name.split("_")
    return where, float(beta[4:]), int(seed[4:]), float(x[1:])


def first_visible_um(corr):
    """The corrosion depth [um] at which a surface crack first reads
    visible_width (None: not within the run)."""
    for r in corr:
        if r["cracks_at_surface"] >= 1:
            return 1e3 * r["penetration_mm"]
    return None


def run_table(out, runs, study):
    """One row per converged run of `study`; the failed ones are named on stdout."""
    table = []
    for name in sorted(n for (s_, n) in runs if s_ == study):
        folder = os.path.join(out, study, name)
        rows = runs[(study, name)]
        try:
            s = pushout_runs.summary(folder)
        except (OSError, ValueError):  # refused before it wrote one
            print(f"{study} {name}: no summary.json (the run's words are its stderr)")
            continue
        if not s["converged"] or not rows:
            print(f"{study} {name}: did not converge: {s['message']}")
            continue
        where, beta, seed, x = parse(name)
        # x = 0: no corrosion stage, no corrosion.csv; the push starts uncracked.
        has_corrosion = os.path.exists(os.path.join(folder, "corrosion.csv"))
        corr = pushout_runs.corrosion(folder) if has_corrosion else []
        concrete = [c for c in s.get("cracks", []) if c["source"] == "concrete"]
        widest = max(concrete, key=lambda c: c["width_mm"]) if concrete else None
        table.append({"case": name, "tube": where, "beta": beta, "seed": seed, "x_um": x,
                      "p_after_corrosion_MPa": rows[0]["p_MPa"],
                      "surface_crack_um": 1e3 * corr[-1]["crack_width_mm"] if corr else 0.0,
                      "cracks_at_surface": int(corr[-1]["cracks_at_surface"]) if corr else 0,
                      "widest_angle_deg": widest["angle_deg"] if widest else None,
                      "first_visible_x_um": first_visible_um(corr),
                      "tau_peak_MPa": max(r["tau_MPa"] for r in rows),
                      "tau_residual_MPa": rows[-1]["tau_MPa"],
                      "newton_iterations": s.get("newton_iterations")})
    return table


def spread(values):
    return statistics.mean(values), min(values), max(values)


def group_table(table, runs, study):
    """Per tube, beta and x: the converged seeds' mean, min and max; `seeds`
    counts the converged ones, `seeds_run` every one run (as sweep_seeds.csv's
    converged and seeds). A group none of whose seeds converged has a row
    too, with `seeds` 0 and no values (it is not left out of the table)."""
    groups = {}
    for r in table:
        groups.setdefault((r["tube"], r["beta"], r["x_um"]), []).append(r)
    ran = {}
    for (s_, name) in runs:
        if s_ == study:
            where, beta, _, x = parse(name)
            ran[(where, beta, x)] = ran.get((where, beta, x), 0) + 1
    out = []
    for (tube, beta, x) in sorted(set(groups) | set(ran)):
        rs = groups.get((tube, beta, x), [])
        row = {"tube": tube, "beta": beta, "x_um": x, "seeds": len(rs),
               "seeds_run": ran.get((tube, beta, x), len(rs))}
        for key in ("p_after_corrosion_MPa", "surface_crack_um", "tau_peak_MPa", "tau_residual_MPa"):
            mean, lo, hi = spread([r[key] for r in rs]) if rs else (None, None, None)
            row.update({f"{key}_mean": mean, f"{key}_min": lo, f"{key}_max": hi})
        row["cover_crack_seeds"] = sum(r["cracks_at_surface"] >= 1 for r in rs)
        out.append(row)
    return out


def seed_count(groups):
    """'5 seeds', or where a group lost some: '5 seeds, 4 converged in 1 group'."""
    run = max(g["seeds_run"] for g in groups)
    short = [g for g in groups if g["seeds"] < g["seeds_run"]]
    if not short:
        return f"{run} seeds"
    fewest = min(g["seeds"] for g in short)
    if len(short) == 1:
        return f"{run} seeds, {fewest} converged in 1 group"
    return f"{run} seeds, as few as {fewest} converged in {len(short)} groups"


def plot_bond(plt, out, groups, table, study):
    """Residual bond stress against x and against the surface crack width,
    the seeds' mean with their range as error bars (and each seed)."""
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), dpi=120, sharey=True)
    for (where, _), style in zip(WHERE, ("o-", "s--")):
        for beta, color in zip(BETAS, ("tab:blue", "tab:red")):
            sel = [g for g in groups if g["tube"] == where and g["beta"] == beta and g["seeds"]]
            mean = [g["tau_residual_MPa_mean"] for g in sel]
            err = [[m - g["tau_residual_MPa_min"] for m, g in zip(mean, sel)],
                   [g["tau_residual_MPa_max"] - m for m, g in zip(mean, sel)]]
            axes[0].errorbar([g["x_um"] for g in sel], mean, yerr=err, fmt=style, color=color,
                             ms=4, capsize=3, label=f"{where}, $\\beta$ {beta:g}")
            seeds = [r for r in table if r["tube"] == where and r["beta"] == beta]
            axes[1].plot([r["surface_crack_um"] for r in seeds],
                         [r["tau_residual_MPa"] for r in seeds], style[0], color=color, ms=4,
                         mfc="none" if where == "centred" else color)
    axes[0].set(xlabel="corrosion depth $x$ [µm]", ylabel="residual bond stress at 0.2 mm [MPa]")
    axes[1].set(xlabel="widest surface crack after corrosion [µm] (each seed; open: centred)")
    axes[1].axvline(VISIBLE_UM, color="0.5", lw=0.8, ls=":")
    for ax in axes:
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    title = ("Corroded push-out, cracks anywhere" +
             (" (IMPL-EX)" if STUDIES[study].integration == "implex" else "") +
             (", the strain predictor" if STUDIES[study].predictor == "strain" else "") +
             (", the paper's mesh" if on_paper_mesh(study) else "") +
             (f", the {STUDIES[study].band} band" if STUDIES[study].band else "") +
             (f", {STUDIES[study].lines} graded lines"
              if STUDIES[study].lines != Study._field_defaults["lines"] else "") +
             (f", {STUDIES[study].refinement} refinement"
              if STUDIES[study].refinement != Study._field_defaults["refinement"] else ""))
    seeds = f"({seed_count(groups)} of a cov 0.15 strength field: mean and range)"
    # One line while it fits the figure's width.
    fig.suptitle(title + ("\n" if len(title) + len(seeds) > 110 else " ") + seeds)
    fig.tight_layout()
    fig.savefig(os.path.join(out, f"{study}_residual_bond.png"))
    plt.close(fig)


def plot_patterns(plt, out, table, seeds, study):
    """The crack patterns after corrosion to the largest x: a row per tube
    and beta, a column per seed (a run that did not converge: its title
    says so), one colour scale."""
    x = max(DEPTHS_UM)
    done = {(r["tube"], r["beta"], r["seed"]) for r in table if r["x_um"] == x}
    rows = [(w, b) for w, _ in WHERE for b in BETAS]
    fig, axes = plt.subplots(len(rows), len(seeds), figsize=(2.2 * len(seeds) + 1.5, 2.3 * len(rows) + 0.6),
                             dpi=110, squeeze=False, layout="constrained")
    cells = None
    for i, (where, beta) in enumerate(rows):
        for j, seed in enumerate(seeds):
            ax = axes[i][j]
            ax.set_xticks([])
            ax.set_yticks([])
            if (where, beta, seed) not in done:
                ax.set_title(f"{where}, β {beta:g}, seed {seed}: did not converge", fontsize=7)
                continue
            name = f"{where}_beta{beta:g}_seed{seed}_x{x:g}"
            data = plot_curve.read(os.path.join(out, study, name, "crack_pattern.csv"))
            cells = plot_curve.draw_crack_pattern(ax, data, top=0.5)
            ax.set_title(f"{where}, β {beta:g}, seed {seed}", fontsize=8)
    if cells is not None:
        fig.colorbar(cells, ax=axes, shrink=0.6, label="crack opening [mm]")
    fig.suptitle(f"Crack patterns at x = {x:g} µm, seen along the tube", fontsize=10)
    fig.savefig(os.path.join(out, f"{study}_patterns.png"))
    plt.close(fig)


def report(plt, out, runs, study="corroded_embedded"):
    """Writes OUT/<study>.csv (per run), OUT/<study>_groups.csv (per group of
    seeds) and the two figures; returns the group rows."""
    table = run_table(out, runs, study)
    if not table:
        print(f"{study}: no run converged: no table, no figure", file=sys.stderr)
        return []
    seeds = sorted({parse(n)[2] for (s_, n) in runs if s_ == study})
    groups = group_table(table, runs, study)
    for path, rows in ((f"{study}.csv", table), (f"{study}_groups.csv", groups)):
        with open(os.path.join(out, path), "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)
    plot_bond(plt, out, groups, table, study)
    plot_patterns(plt, out, table, seeds, study)
    return groups

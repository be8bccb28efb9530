#!/usr/bin/python3
"""Path following through the snap-back after the adhesion peak:

  1. bench/scenes/snap_back.toml (80 mm slice, brittle adhesion) with
     loading.control = "arc_length", "displacement" (stops at the peak), and
     displacement control with viscous damage (eta = 1e-3 mm, the other way
     through the drop);
  2. the Fig. 10 scene (20 mm slice, c = 25 1/mm, mesh 8/4, 0.1 mm), where
     both controls must trace the same curve.

Writes bench/results/snap_back.png (tau against delta, and against the mean
slip, the control variable) and snap_back.csv (one row per run).

  bench/snap_back.py [--pushout build/pushout] [--reuse]

Timings in snap_back.csv: wall_s of each run alone on the 2-core reference
machine (one run at a time).
"""
import argparse
import os
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from common import PUSHOUT, ROOT, curve, run, save_figure_and_table, summary  # noqa: E402

SNAP = os.path.join(ROOT, "bench", "scenes", "snap_back.toml")
FIG10 = os.path.join(ROOT, "demo", "pushout_friction_adhesion.toml")
FIG10_SETS = ["mesh.elements_per_quarter=8", "mesh.elements_through_thickness=4",
              "loading.push_displacement=0.1", "loading.steps=80", "output.plot=false"]

RUNS = [  # name, scene, --set list
    ("snap_arc_length", SNAP, []),
    ("snap_displacement", SNAP, ["loading.control=displacement"]),
    ("snap_viscous_eta1e-3", SNAP, ["loading.control=displacement", "interface.1.eta=1e-3"]),
    ("fig10_arc_length", FIG10, FIG10_SETS + ["loading.control=arc_length"]),
    ("fig10_displacement", FIG10, FIG10_SETS),
]


def run_case(pushout, name, scene, sets, reuse):
    out = os.path.join(ROOT, "results", "snap_back", name)
    t0 = time.time()
    code = run(pushout, scene, out, sets, reuse=reuse, check=False)
    wall = time.time() - t0
    rows, s = curve(out), summary(out)
    if reuse:
        code, wall = (0 if s["converged"] else 3), s["wall_s"]
    return rows, {"run": name, "exit": code, "converged": s["converged"],
                  "points": len(rows), "newton_iterations": s["newton_iterations"],
                  "cuts": s["cuts"], "wall_s": round(wall, 1),
                  "peak_tau_MPa": round(max(r["tau_MPa"] for r in rows), 4),
                  "final_delta_mm": round(rows[-1]["delta_mm"], 6),
                  "final_tau_MPa": round(rows[-1]["tau_MPa"], 6),
                  "delta_decrease_um": round(1e3 * sum(max(0.0, a["delta_mm"] - b["delta_mm"])
                                                       for a, b in zip(rows, rows[1:])), 3),
                  "message": s.get("message", "")}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pushout", default=PUSHOUT)
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results"),
                    help="the folder of the tables (the runs go to results/snap_back)")
    ap.add_argument("--reuse", action="store_true", help="replot the runs in results/snap_back/")
    args = ap.parse_args()
    curves, table = {}, []
    for name, scene, sets in RUNS:
        curves[name], row = run_case(args.pushout, name, scene, sets, args.reuse)
        table.append(row)
        print(row)

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.4), dpi=110)
    style = {"snap_arc_length": ("tab:blue", "-", "arc length (mean slip control)"),
             "snap_displacement": ("tab:red", "none", "displacement control"),
             "snap_viscous_eta1e-3": ("tab:green", "--", "displacement control, viscous $\\eta$ = 1e-3 mm")}
    for name, (color, ls, label) in style.items():
        c = curves[name]
        kw = dict(color=color, label=label, ls=ls if ls != "none" else "-")
        if name == "snap_displacement":
            kw.update(marker="o", ms=3, lw=0)
        axes[0].plot([r["delta_mm"] * 1e3 for r in c], [r["tau_MPa"] for r in c], **kw)
        axes[1].plot([r["slip_mm"] * 1e3 for r in c], [r["tau_MPa"] for r in c], **kw)
    last = curves["snap_displacement"][-1]
    axes[0].annotate("displacement control\nstops here", (last["delta_mm"] * 1e3, last["tau_MPa"]),
                     xytext=(last["delta_mm"] * 1e3 + 8, last["tau_MPa"] + 0.1),
                     arrowprops=dict(arrowstyle="->", color="tab:red"), color="tab:red", fontsize=8)
    axes[0].set(xlabel="tube displacement $\\delta$ [µm]", ylabel="nominal bond stress $\\tau$ [MPa]",
                title="Snap-back: 80 mm slice, exp. soft. c = 100 1/mm")
    axes[1].set(xlabel="mean axial slip s [µm] (the control variable)",
                ylabel="$\\tau$ [MPa]", title="The same runs against the mean slip")
    for name, color, label in (("fig10_displacement", "tab:red", "displacement control, 80 steps"),
                               ("fig10_arc_length", "tab:blue", "arc length")):
        c = curves[name]
        axes[2].plot([r["delta_mm"] * 1e3 for r in c], [r["tau_MPa"] for r in c], color=color,
                     label=label, marker="." if "arc" in name else None, ms=3,
                     ls="-" if "arc" not in name else "none")
    axes[2].set(xlabel="$\\delta$ [µm]", ylabel="$\\tau$ [MPa]",
                title="Fig. 10 scene (20 mm, c = 25): no snap-back")
    # The inset: the snap-back itself.
    inset = axes[0].inset_axes([0.6, 0.08, 0.38, 0.42])
    c = curves["snap_arc_length"]
    peak = max(range(len(c)), key=lambda i: c[i]["tau_MPa"])
    sel = c[max(0, peak - 6): peak + 25]
    inset.plot([r["delta_mm"] * 1e3 for r in sel], [r["tau_MPa"] for r in sel], color="tab:blue",
               marker=".", ms=3)
    inset.set_title("around the peak", fontsize=7)
    inset.tick_params(labelsize=6)
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="upper left" if ax is axes[0] else "lower right")
    save_figure_and_table(fig, args.out, "snap_back", table)


if __name__ == "__main__":
    main()

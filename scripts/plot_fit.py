#!/usr/bin/python3
"""Draw a `pushout fit`: the measured points (DIR/fit.csv) and the fitted
model's curve (DIR/best/curve.csv), with the fitted values (DIR/fit.json).

Usage: plot_fit.py DIR OUT.png
"""
import argparse
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pushout_runs  # noqa: E402  (beside this script)


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("folder")
    ap.add_argument("png")
    args = ap.parse_args()
    with open(os.path.join(args.folder, "fit.csv"), newline="") as f:
        data = list(csv.DictReader(f))
    if not data:
        raise ValueError(f"{os.path.join(args.folder, 'fit.csv')} has no rows: not a fit's table")
    fig, ax = plt.subplots(figsize=(7, 4.5), dpi=120)
    ax.plot([float(r["delta_mm"]) * 1e3 for r in data], [float(r["tau_data_MPa"]) for r in data],
            "o", ms=3, color="0.4", label="measured")
    best = os.path.join(args.folder, "best", "curve.csv")
    if os.path.exists(best):
        with open(best, newline="") as f:
            curve = list(csv.DictReader(f))
        ax.plot([float(r["delta_mm"]) * 1e3 for r in curve], [float(r["tau_MPa"]) for r in curve],
                "-", color="C3", lw=1.5, label="fitted model")
    title = "fit"
    fit_json = os.path.join(args.folder, "fit.json")
    if os.path.exists(fit_json):
        with open(fit_json) as f:
            fit = json.load(f)
        short = pushout_runs.short_key_names(list(fit["parameters"]))
        title = ", ".join(
            f"{short[k]} = {v:.4g}" + (f" ± {fit['standard_errors'][k]:.2g}"
                                       if fit["standard_errors"].get(k) is not None else "")
            for k, v in fit["parameters"].items())
        if fit.get("rms_MPa") is not None:
            title += f"  (rms {fit['rms_MPa']:.3g} MPa)"
    ax.axhline(0, color="0.6", lw=0.5)
    ax.set(xlabel="tube displacement $\\delta$ [µm]", ylabel="nominal bond stress $\\tau$ [MPa]")
    ax.set_title(title, fontsize=8)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.png)


if __name__ == "__main__":
    # A file that cannot be read or written, or is not the table it should
    # be: one line, exit 1 (not a traceback).
    try:
        main()
    except (OSError, ValueError, KeyError) as e:
        sys.exit(f"plot_fit.py: error: {e}")

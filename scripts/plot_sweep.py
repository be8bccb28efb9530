#!/usr/bin/python3
"""Draw the curves of a `pushout sweep` overlaid: DIR/sweep.csv names the
cases and their varied values; each DIR/case_NNN/curve.csv is one curve
(push-out: tau against delta; single joint: F_s against u_s).

Usage: plot_sweep.py DIR OUT.png
"""
import argparse
import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# The first columns of sweep.csv after `case` are the varied keys, up to the
# first of the computed ones.
COMPUTED = ("peak_",)


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("folder")
    ap.add_argument("png")
    args = ap.parse_args()
    with open(os.path.join(args.folder, "sweep.csv"), newline="") as f:
        reader = csv.DictReader(f)
        rows = list(reader)
        keys = []
        for k in reader.fieldnames[1:]:
            if k.startswith(COMPUTED):
                break
            keys.append(k)
    fig, ax = plt.subplots(figsize=(7.5, 4.8), dpi=120)
    for i, row in enumerate(rows):
        path = os.path.join(args.folder, row["case"], "curve.csv")
        if not os.path.exists(path):
            continue
        with open(path, newline="") as f:
            curve = list(csv.DictReader(f))
        if not curve:
            continue
        if "delta_mm" in curve[0]:
            x = [float(r["delta_mm"]) * 1e3 for r in curve]
            y = [float(r["tau_MPa"]) for r in curve]
            ax.set(xlabel="tube displacement $\\delta$ [µm]", ylabel="nominal bond stress $\\tau$ [MPa]")
        else:
            x = [float(r["u_s_mm"]) for r in curve]
            y = [float(r["F_s_N"]) for r in curve]
            ax.set(xlabel="shear displacement $u_s$ [mm]", ylabel="shear force $F_s$ [N]")
        label = ", ".join(f"{k.split('.')[-1]} {row[k]}" for k in keys)
        if row.get("converged") == "0":
            label += " (stopped)"
        ax.plot(x, y, "-", lw=1.2, color=plt.cm.viridis(i / max(1, len(rows) - 1)), label=label)
    ax.axhline(0, color="0.6", lw=0.5)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, ncol=2 if len(rows) > 8 else 1)
    ax.set_title(f"sweep: {len(rows)} cases ({', '.join(keys)})", fontsize=9)
    fig.tight_layout()
    fig.savefig(args.png)


if __name__ == "__main__":
    main()

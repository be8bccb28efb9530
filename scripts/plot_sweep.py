#!/usr/bin/python3
"""Draw the curves of a `pushout sweep` overlaid: DIR/sweep.csv names the
cases and their varied values; each DIR/case_NNN/curve.csv is one curve
(push-out: tau against delta; single joint: F_s against u_s). When the sweep
varies cracking.seed (the random strength field's), the cases that differ
only in the seed are one group, one colour: each seed's curve thin, and
where every converged seed's delta only grows, their mean (thick) and the
band between the lowest and highest (docs/sweeps.md).

Usage: plot_sweep.py DIR OUT.png
"""
import argparse
import csv
import os
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pushout_runs  # noqa: E402  (beside this script)

# The first columns of sweep.csv after `case` are the varied keys, up to the
# first of the computed ones.
COMPUTED = ("peak_",)
SEED = "cracking.seed"


def read_curve(folder, row):
    """(x, y) of a case's curve.csv, and the axis labels; None if it has none."""
    path = os.path.join(folder, row["case"], "curve.csv")
    if not os.path.exists(path):
        return None
    with open(path, newline="") as f:
        curve = list(csv.DictReader(f))
    if not curve:
        return None
    try:
        if "delta_mm" in curve[0]:
            return ([float(r["delta_mm"]) * 1e3 for r in curve], [float(r["tau_MPa"]) for r in curve],
                    ("tube displacement $\\delta$ [µm]", "nominal bond stress $\\tau$ [MPa]"))
        return ([float(r["u_s_mm"]) for r in curve], [float(r["F_s_N"]) for r in curve],
                ("shear displacement $u_s$ [mm]", "shear force $F_s$ [N]"))
    except KeyError as e:
        raise ValueError(f"{path} has no column {e}: not a curve.csv of pushout") from None
    except (TypeError, ValueError):
        raise ValueError(f"{path} is not a table of numbers: not a curve.csv of pushout") from None


def draw_group(ax, curves, color, label):
    """A seed group: each converged seed thin, and their mean and range where
    every x only grows (else the thin curves alone); a group with no
    converged seed is named in the legend all the same."""
    for x, y in curves:
        ax.plot(x, y, "-", lw=0.7, alpha=0.45, color=color)
    if len(curves) >= 2 and all(np.all(np.diff(x) > 0) for x, _ in curves):
        lo, hi = max(x[0] for x, _ in curves), min(x[-1] for x, _ in curves)
        grid = np.unique(np.concatenate([x for x, _ in curves]))
        grid = grid[(grid >= lo) & (grid <= hi)]
        ys = np.array([np.interp(grid, x, y) for x, y in curves])
        ax.fill_between(grid, ys.min(axis=0), ys.max(axis=0), color=color, alpha=0.2, lw=0)
        ax.plot(grid, ys.mean(axis=0), "-", lw=1.8, color=color, label=label + ": mean, range")
    elif curves:
        ax.plot([], [], "-", lw=1.2, color=color, label=label)
    else:  # no seed converged: the group is still named, so that it is seen
        ax.plot([], [], ":", lw=1.2, color=color, label=label + ": none converged")


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("folder")
    ap.add_argument("png")
    args = ap.parse_args()
    with open(os.path.join(args.folder, "sweep.csv"), newline="") as f:
        reader = csv.DictReader(f)
        rows = list(reader)
        if not reader.fieldnames or not rows:
            raise ValueError(f"{f.name} has no cases: not a sweep's table")
        if reader.fieldnames[0] != "case":
            raise ValueError(f"{f.name} has no column case first: not a sweep's table")
        keys = []
        for k in reader.fieldnames[1:]:
            if k.startswith(COMPUTED):
                break
            keys.append(k)
    fig, ax = plt.subplots(figsize=(7.5, 4.8), dpi=120)
    seeded = SEED in keys and len({r[SEED] for r in rows}) >= 2
    others = [k for k in keys if k != SEED] if seeded else keys
    short = pushout_runs.short_key_names(others)
    groups = {}  # the other keys' values -> the group's rows, in order
    for row in rows:
        groups.setdefault(tuple(row[k] for k in others), []).append(row)
    for i, (values, members) in enumerate(groups.items()):
        # A seed group's band needs a colour that stands out on white.
        color = (plt.cm.tab10(i) if seeded and len(groups) <= 10
                 else plt.cm.viridis(i / max(1, len(groups) - 1)))
        label = ", ".join(f"{short[k]} {v}" for k, v in zip(others, values))
        curves = []
        for row in members:
            read = read_curve(args.folder, row)
            if read is None:
                if not seeded:  # failed before its curve's first row: named all the same
                    ax.plot([], [], ":", lw=1.2, color=color, label=label + " (no curve)")
                continue
            x, y, labels = read
            ax.set(xlabel=labels[0], ylabel=labels[1])
            if not seeded:
                stopped = " (stopped)" if row.get("converged") == "0" else ""
                ax.plot(x, y, "-", lw=1.2, color=color, label=label + stopped)
            elif row.get("converged") == "0":
                ax.plot(x, y, ":", lw=0.7, color=color)
            else:
                curves.append((np.array(x), np.array(y)))
        if seeded:
            seeds = f"{len(curves)} of {len(members)} seeds" if len(curves) < len(members) \
                else f"{len(members)} seeds"
            draw_group(ax, curves, color, (label + ", " if label else "") + seeds)
    ax.axhline(0, color="0.6", lw=0.5)
    ax.grid(alpha=0.3)
    if ax.get_legend_handles_labels()[0]:  # a case without a curve draws nothing
        ax.legend(fontsize=7, ncol=2 if len(groups) > 8 else 1)
    ax.set_title(f"sweep: {len(rows)} cases ({', '.join(keys)})"
                 + ("; the seeds of a case as its range" if seeded else ""), fontsize=9)
    fig.tight_layout()
    fig.savefig(args.png)


if __name__ == "__main__":
    # A file that cannot be read or written, or is not the table it should
    # be: one line, exit 1 (not a traceback).
    try:
        main()
    except UnicodeDecodeError:
        sys.exit("plot_sweep.py: error: sweep.csv is not text: not a sweep's table")
    except (OSError, ValueError, KeyError) as e:
        sys.exit(f"plot_sweep.py: error: {e}")

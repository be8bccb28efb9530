#!/usr/bin/python3
"""Regenerates the single-joint figures (paper Figs. 6 and 9, and the coupled
cohesive-friction law against the superposition) with the analytic answers
overlaid, into docs/figures/.

Usage: scripts/figures_single_joint.py [--pushout build/pushout] [--out docs/figures]
"""
import argparse
import os
import shutil
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
import analytic  # noqa: E402  (beside this script)
import pushout_runs  # noqa: E402


def run(pushout, scene, out, sets=()):
    """The single joint's (u_s, F_s) curve of a scene."""
    pushout_runs.run(pushout, scene, out, ["output.plot=false"] + list(sets), check=True)
    rows = pushout_runs.curve(out)
    return [r["u_s_mm"] for r in rows], [r["F_s_N"] for r in rows]


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--pushout", default=os.path.join(ROOT, "build", "pushout"))
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "figures"))
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    demo = os.path.join(ROOT, "demo")
    tmp = tempfile.mkdtemp(prefix="pushout-figs-")
    try:
        draw(args, demo, tmp)
    except (OSError, pushout_runs.RunError) as e:
        sys.exit(f"figures_single_joint.py: error: {e}")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def draw(args, demo, tmp):
    """The figures, from runs in `tmp`."""

    # Fig. 6: friction 1, -0.1 N per node.
    u, F = run(args.pushout, os.path.join(demo, "single_joint_fig6.toml"), os.path.join(tmp, "fig6"))
    fig, ax = plt.subplots(figsize=(6, 4), dpi=120)
    ax.plot(u, analytic.coulomb(u, 100, 0.4, 0.4), "k-", lw=3, alpha=0.3, label="analytic")
    ax.plot(u, F, "o", ms=3, label="pushout")
    ax.set(xlabel="shear displacement $u_s$ [mm]", ylabel="shear force $F_s$ [N]",
           title="Fig. 6: friction (k 100, $\\mu$ 0.4), 4 x -0.1 N")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "fig6_single_joint_friction.png"))

    # Fig. 9: friction 1 + lin. soft. superposed, and each layer alone.
    single = os.path.join(tmp, "single.toml")
    u, F = run(args.pushout, os.path.join(demo, "single_joint_fig9.toml"), os.path.join(tmp, "fig9"))
    fig, ax = plt.subplots(figsize=(6, 4), dpi=120)
    fr = analytic.coulomb(u, 100, 0.4, 0.4)
    ls = analytic.linear_softening(u, 100, 1.0, 0.3)
    ax.plot(u, [a + b for a, b in zip(fr, ls)], "k-", lw=3, alpha=0.3, label="analytic sum")
    ax.plot(u, F, "o", ms=3, label="superposed layers (-0.2 N/node)")
    for law, label in [('law = "friction"\nk = 100.0\nmu = 0.4', "friction 1 alone"),
                       ('law = "linear_softening"\nk = 100.0\nf_t = 1.0\nw_c2 = 0.3', "lin. soft. alone")]:
        with open(single, "w") as f:
            f.write(f'[model]\ntype = "single_joint"\n[[interface]]\n{law}\n')
        uu, FF = run(args.pushout, single, os.path.join(tmp, label.replace(" ", "_")))
        ax.plot(uu, FF, "-", label=label + " (-0.1 N/node)")
    ax.set(xlabel="shear displacement $u_s$ [mm]", ylabel="shear force $F_s$ [N]",
           title="Fig. 9: superposition of friction 1 and lin. soft.")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "fig9_superposition.png"))

    # Coupled law vs superposition on the Fig. 9 path extended to full damage.
    path = "loading.shear_path=[0.0, 0.02, 0.01, 0.025, 0.4]"
    uc, Fc = run(args.pushout, os.path.join(demo, "single_joint_cohesive_friction.toml"),
                 os.path.join(tmp, "cf"))
    us, Fs = run(args.pushout, os.path.join(demo, "single_joint_fig9.toml"), os.path.join(tmp, "sup"),
                 sets=[path])
    fig, ax = plt.subplots(figsize=(6, 4), dpi=120)
    ax.plot(us, Fs, "-", label="superposition: friction 1 + lin. soft.")
    ax.plot(uc, Fc, "-", label="cohesive_friction (Alfano & Sacco)")
    ax.plot(us, analytic.coulomb(us, 100, 0.4, 0.4), ":", label="friction alone")
    ax.set(xlabel="shear displacement $u_s$ [mm]", ylabel="shear force $F_s$ [N]",
           title="Coupled law vs superposition (k 100, $\\mu$ 0.4, $f_t$ 1, $w_{c2}$ 0.3)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "cohesive_friction_vs_superposition.png"))
    print("figures in", args.out)


if __name__ == "__main__":
    main()

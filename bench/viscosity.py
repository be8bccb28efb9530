#!/usr/bin/python3
"""How the viscous regularisation of the damage changes the push-out curve:
Friction 2 + Exp. soft. (Table 1), dT -25 degC, 0.1 mm in 80 steps, mesh
8/4, with eta in {0, 1e-4, 1e-3, 1e-2} mm (pseudo-time = push). Writes
bench/results/viscosity.png and viscosity.csv (max |tau_eta - tau_0|).

  bench/viscosity.py [--pushout build/pushout]
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from common import PUSHOUT, ROOT, curve, run, save_figure_and_table  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pushout", default=PUSHOUT)
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results"),
                    help="the folder of the tables (the runs go to results/viscosity)")
    args = ap.parse_args()
    etas = [0.0, 1e-4, 1e-3, 1e-2]
    curves = {}
    for eta in etas:
        out = os.path.join(ROOT, "results", "viscosity", f"eta{eta:g}")
        run(args.pushout, os.path.join(ROOT, "demo", "pushout_friction_adhesion.toml"), out,
            [f"interface.1.eta={eta}", "loading.push_displacement=0.1", "loading.steps=80",
             "mesh.elements_per_quarter=8", "mesh.elements_through_thickness=4", "output.plot=false"])
        curves[eta] = curve(out)
    fig, ax = plt.subplots(figsize=(6.5, 4.2), dpi=120)
    rows = []
    for eta in etas:
        c = curves[eta]
        ax.plot([r["delta_mm"] * 1e3 for r in c], [r["tau_MPa"] for r in c],
                label="rate independent" if eta == 0 else f"$\\eta$ = {eta:g} mm")
        err = max(abs(a["tau_MPa"] - b["tau_MPa"]) for a, b in zip(c, curves[0.0]))
        rows.append({"eta_mm": eta, "max_abs_tau_diff_MPa": round(err, 5),
                     "peak_tau_MPa": round(max(r["tau_MPa"] for r in c), 4)})
    ax.set(xlabel="tube displacement $\\delta$ [µm]", ylabel="nominal bond stress $\\tau$ [MPa]",
           title="Viscous damage: friction 2 + exp. soft., $\\Delta T$ -25 °C")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    save_figure_and_table(fig, args.out, "viscosity", rows)
    for r in rows:
        print(r)


if __name__ == "__main__":
    main()

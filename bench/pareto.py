#!/usr/bin/python3
"""Run time against error on the paper's two push-out scenes:

  fig10: Friction 2 + Exp. soft. (c 25 1/mm), dT -25 degC, pushed to 1 mm
         (demo/pushout_friction_adhesion.toml), steps growing geometrically
         (80 steps with growth 1.07, N steps with growth 1.07^(80/N));
  fig7:  Friction 2 (mu 0.4), dT -25 degC, 10 um in 9 steps
         (demo/pushout_friction.toml).

Swept: mesh resolution (elements per quarter 4..32, through the thickness
2..16), steel layers, grading of the outer block, interface quadrature
(gauss/nodal), the number of steps and the bulk's degree (1: trilinear; 2:
triquadratic displacement on the same trilinear hexahedra, "P2" runs). Each curve is compared with the reference (the
finest run, 32/16 with twice the steps for fig10 and three times the
default 9 for fig7; its own convergence is in the table): relative L2 error of tau(delta) over the curve (the run interpolated
at the reference's delta), and the relative errors of the peak tau and of
tau at the end (the residual at 1 mm for fig10). Runs use the defaults
otherwise (quarter model by symmetry, condensed bulk), one at a time, one
thread (OPENBLAS_NUM_THREADS=1).

Writes bench/results/pareto.csv and pareto.png (error against wall time,
the Pareto front marked).

  bench/pareto.py [--only fig10 fig7] [--reuse]
"""
import argparse
import os

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from common import PUSHOUT, ROOT, curve, run, save_figure_and_table, summary  # noqa: E402



def mesh(nq, nz, **kw):
    s = [f"mesh.elements_per_quarter={nq}", f"mesh.elements_through_thickness={nz}"]
    return s + [f"mesh.{k}={v}" for k, v in kw.items()]


def fig10_steps(n):
    return ["loading.push_displacement=1.0", f"loading.steps={n}",
            f"loading.step_growth={1.07 ** (80 / n):.6f}"]


def cases(study):
    """(name, --set list); the first is the reference."""
    if study == "fig10":
        base = ["output.plot=false"]
        out = [("ref 32/16 160 steps", mesh(32, 16) + fig10_steps(160))]
        for nq, nz in ((4, 2), (8, 4), (16, 8), (24, 12), (32, 16)):
            out.append((f"{nq}/{nz}", mesh(nq, nz) + fig10_steps(80)))
        out.append(("24/12 160 steps", mesh(24, 12) + fig10_steps(160)))
        for nq, nz in ((16, 4), (16, 16), (8, 8), (32, 8)):
            out.append((f"{nq}/{nz}", mesh(nq, nz) + fig10_steps(80)))
        out.append(("16/8 steel 1", mesh(16, 8, steel_layers=1) + fig10_steps(80)))
        out.append(("16/8 steel 6", mesh(16, 8, steel_layers=6) + fig10_steps(80)))
        out.append(("16/8 ratio 5", mesh(16, 8, outer_size_ratio=5) + fig10_steps(80)))
        out.append(("16/8 ratio 20", mesh(16, 8, outer_size_ratio=20) + fig10_steps(80)))
        for nq, nz in ((8, 4), (16, 8)):
            out.append((f"{nq}/{nz} nodal", mesh(nq, nz, interface_quadrature="nodal") + fig10_steps(80)))
        for n in (20, 40, 160):
            out.append((f"16/8 {n} steps", mesh(16, 8) + fig10_steps(n)))
        for n in (20, 40):
            out.append((f"8/4 {n} steps", mesh(8, 4) + fig10_steps(n)))
        for nq, nz in ((4, 2), (8, 4), (16, 8)):
            out.append((f"{nq}/{nz} P2", mesh(nq, nz, degree=2) + fig10_steps(80)))
        return "pushout_friction_adhesion.toml", [(n, s + base) for n, s in out]
    base = ["output.plot=false", "loading.temperature_change=-25"]
    out = [("ref 32/16 27 steps", mesh(32, 16) + ["loading.steps=27"])]
    for nq, nz in ((4, 2), (8, 4), (16, 8), (24, 12), (32, 16)):
        out.append((f"{nq}/{nz}", mesh(nq, nz)))
    out.append(("16/8 nodal", mesh(16, 8, interface_quadrature="nodal")))
    out.append(("16/4", mesh(16, 4)))
    out.append(("8/8", mesh(8, 8)))
    for n in (3, 27):
        out.append((f"16/8 {n} steps", mesh(16, 8) + [f"loading.steps={n}"]))
    for nq, nz in ((4, 2), (8, 4), (16, 8)):
        out.append((f"{nq}/{nz} P2", mesh(nq, nz, degree=2)))
    return "pushout_friction.toml", [(n, s + base) for n, s in out]


def run_case(pushout, scene, folder, sets, reuse):
    run(pushout, os.path.join(ROOT, "demo", scene), folder, sets, reuse=reuse)
    c = curve(folder)
    return summary(folder), np.array([r["delta_mm"] for r in c]), np.array([r["tau_MPa"] for r in c])


def errors(d, t, dr, tr):
    ti = np.interp(dr, d, t)
    l2 = np.sqrt(np.trapz((ti - tr) ** 2, dr) / np.trapz(tr ** 2, dr))
    peak = abs(t.max() - tr.max()) / abs(tr.max())
    end = abs(t[-1] - tr[-1]) / abs(tr[-1])
    return l2, peak, end


def pareto(points):
    """Indices of the points no other point beats in both time and error."""
    return [i for i, (t, e) in enumerate(points)
            if not any(t2 <= t and e2 <= e and (t2, e2) != (t, e) for t2, e2 in points)]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pushout", default=PUSHOUT)
    ap.add_argument("--only", nargs="+", default=["fig10", "fig7"], choices=["fig10", "fig7"])
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results"),
                    help="the folder of the tables (the runs go to --work)")
    ap.add_argument("--work", default=os.path.join(ROOT, "results", "pareto"))
    ap.add_argument("--reuse", action="store_true")
    args = ap.parse_args()
    table = []
    fig, axes = plt.subplots(1, len(args.only) + 1, figsize=(6 * (len(args.only) + 1), 4.8), dpi=110)
    for k, study in enumerate(args.only):
        scene, runs = cases(study)
        results = []
        for name, sets in runs:
            folder = os.path.join(args.work, study, name.replace(" ", "_").replace("/", "x"))
            s, d, t = run_case(args.pushout, scene, folder, sets, args.reuse)
            results.append((name, s, d, t))
            print(study, name, f"{s['wall_s']:.1f} s", flush=True)
        _, _, dr, tr = results[0]
        pts = []
        for name, s, d, t in results:
            l2, peak, end = errors(d, t, dr, tr)
            row = {"study": study, "run": name, "dofs": s["dofs"], "steps": s["steps"],
                   "newton_iterations": s["newton_iterations"], "wall_s": round(s["wall_s"], 2),
                   "l2_rel": float(f"{l2:.3e}"), "peak_tau_MPa": round(float(t.max()), 5),
                   "peak_rel": float(f"{peak:.3e}"), "end_tau_MPa": round(float(t[-1]), 5),
                   "end_rel": float(f"{end:.3e}")}
            table.append(row)
            pts.append((s["wall_s"], max(l2, 1e-7)))
        front = pareto(pts[1:])  # without the reference itself
        ax = axes[k]
        for i, ((wt, e), (name, *_)) in enumerate(zip(pts[1:], results[1:])):
            on = i in front
            ax.loglog(wt, e, "o", color="tab:red" if on else "tab:gray", ms=6 if on else 4)
            ax.annotate(name, (wt, e), fontsize=6, xytext=(3, 2), textcoords="offset points",
                        color="black" if on else "dimgray")
        f_sorted = sorted((pts[1:][i] for i in front))
        ax.loglog([p[0] for p in f_sorted], [p[1] for p in f_sorted], "-", color="tab:red", lw=1,
                  label="Pareto front")
        ax.set(xlabel="wall time [s] (1 core)", ylabel="relative L2 error of tau(delta)",
               title=f"{study}: reference {results[0][0]} ({results[0][1]['wall_s']:.0f} s)")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
        if study == "fig10":
            ax2 = axes[-1]
            for (name, s, d, t) in results:
                if name in ("4/2", "8/4", "16/8", "32/16") or name.startswith("ref"):
                    ax2.plot(d * 1e3, t, label=name, lw=1)
            ax2.set(xlim=(0, 100), xlabel="delta [um]", ylabel="tau [MPa]",
                    title="fig10: mesh convergence (first 100 um)")
            ax2.grid(alpha=0.3)
            ax2.legend(fontsize=7)
    save_figure_and_table(fig, args.out, "pareto", table)
    for r in table:
        print(r)


if __name__ == "__main__":
    main()

"""Elastic interface, no retraction: the whole problem is linear, so P is
proportional to delta (P/delta the same at every step), and there is no
thermal step (step 0 takes no Newton iteration)."""
from common import check, curve, out_dir, run, summary

scene = """
[mesh]
elements_per_quarter = 4
elements_through_thickness = 2
[[interface]]
law = "elastic"
k = 100.0
[loading]
temperature_change = 0.0
push_displacement = 0.01
steps = 4
"""
out = out_dir("pushout_elastic")
run(scene, out)
rows = curve(out)
check(rows[0]["P_N"] == 0 and rows[0]["newton_iterations"] == 0, "no thermal step when dT = 0")
stiff = [r["P_N"] / r["delta_mm"] for r in rows[1:]]
spread = max(stiff) / min(stiff) - 1
check(min(stiff) > 0, f"P > 0 for a push (P/delta = {stiff[0]:.1f} N/mm)")
check(spread < 1e-8, f"P proportional to delta (spread {spread:.1e})")
check(all(r["newton_iterations"] <= 2 for r in rows[1:]), "linear problem: at most 2 Newton iterations per step")
check(summary(out)["converged"], "summary says converged")

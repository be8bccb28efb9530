"""Friction interface, no retraction: nothing presses the concrete on the
tube, so Coulomb friction transmits nothing and tau stays 0."""
from common import COARSE_MESH, FRICTION_2, check, curve, out_dir, run

scene = COARSE_MESH + FRICTION_2 + """
[loading]
temperature_change = 0.0
push_displacement = 0.01
steps = 3
"""
out = out_dir("pushout_no_pressure")
run(scene, out)
rows = curve(out)
check(len(rows) == 4, "step 0 + 3 steps")
worst = max(abs(r["tau_MPa"]) for r in rows)
check(worst < 1e-9, f"max |tau| = {worst:.2e} MPa (no pressure, no friction)")
check(abs(rows[-1]["delta_mm"] - 0.01) < 1e-12, "the tube moved 10 um")

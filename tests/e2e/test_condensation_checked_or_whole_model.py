"""solver.condensation = "auto" never fails where "off" runs.

1. A circular slice with four crack planes (0, 90, 180, 270 degrees, the
   default crack law), everything else default but a coarser mesh (8 elements
   per quarter: condensed, 1 836 jumps), at steel.E = 3e5 and 2e6 MPa (moduli
   whose condensed flexibility C a fixed round-off threshold of 1e-9 would
   refuse on some machines): exit 0, condensed, and the curve equals the whole
   model's (solver.condensation = "off") to the bound of Newton's tolerance
   on the two runs (common.newton_bound) plus C's own round-off (the
   asymmetry measured, summary.json condensation_asymmetry: symmetrising
   moves C's products by half of it, and its symmetric part carries about
   as much).
   And a corroded ring with a rigid tube (steel.E 2e8 MPa, 16 elements per
   quarter, one through the thickness, oxide_friction, x = 20 um), whose C
   measured max|C - C^T| = 4.4e-9 max|C| on this stack, which the old
   threshold refused ("solver.condensation = off solves the whole model"):
   the corrosion curve equals the whole model's to the same bound.
2. Where C is not trusted (a test hook, PUSHOUT_TEST_TRUSTED_ASYMMETRY,
   sets a limit below the asymmetry measured), "auto" says so in one
   progress line and solves the whole model: exit 0, not condensed, the
   "off" curve to the same bound; "on" is an error that names the
   asymmetry."""
import os
import subprocess

from common import (OUT_ROOT, PUSHOUT, check, corrosion, curve, newton_bound, out_dir, run,
                    solved_unknowns, summary)

scene = """
[geometry]
outer_shape = "circle"
[mesh]
elements_per_quarter = 8
[[crack]]
angle = 0.0
[[crack]]
angle = 90.0
[[crack]]
angle = 180.0
[[crack]]
angle = 270.0
"""
COLUMNS = ("P_N", "tau_MPa", "p_MPa", "slip_mm")


def largest_difference(a, b):
    """Largest difference of COLUMNS relative to each column's largest |value|."""
    if len(a) != len(b):
        return float("inf")
    worst = 0.0
    for c in COLUMNS:
        scale = max(abs(r[c]) for r in b) or 1.0
        worst = max(worst, max(abs(x[c] - y[c]) for x, y in zip(a, b)) / scale)
    return worst


def bound(a, b):
    sa, sb = summary(a), summary(b)
    steps = len(curve(b))  # step 0 and the load steps
    return (newton_bound(steps, max(solved_unknowns(sa), solved_unknowns(sb)))
            + 2 * max(sa["condensation_asymmetry"], sb["condensation_asymmetry"]))


for E in ("3e5", "2e6"):
    auto, off = out_dir(f"trust_auto_E{E}"), out_dir(f"trust_off_E{E}")
    run(scene, auto, sets=[f"steel.E={E}"])
    run(scene, off, sets=[f"steel.E={E}", "solver.condensation=off"])
    s = summary(auto)
    check(s["converged"] and s["condensed_dofs"] > 0,
          f"E = {E}: auto condensed {s['condensed_dofs']} jumps, "
          f"max|C - C^T| = {s['condensation_asymmetry']:.2e} max|C|")
    d, tol = largest_difference(curve(auto), curve(off)), bound(auto, off)
    check(d <= tol, f"E = {E}: the whole model's curve to {d:.1e} <= {tol:.1e}")

RING = """
[geometry]
outer_shape = "circle"
[mesh]
elements_per_quarter = 16
elements_through_thickness = 1
[steel]
E = 2.0e8
[[interface]]
law = "oxide_friction"
mu = 0.4
[loading]
temperature_change = 0.0
push_displacement = 0.0001
steps = 1
[corrosion]
penetration = 0.02
steps = 40
oxide_bulk = 2.0e8
""" + "".join(f"[[crack]]\nangle = {a}\nk = 100000.0\nc = 30.0\n" for a in (0, 90, 180, 270))
auto, off = out_dir("trust_ring_auto"), out_dir("trust_ring_off")
run(RING, auto)
run(RING, off, sets=["solver.condensation=off"])
s = summary(auto)
check(s["converged"] and s["condensed_dofs"] > 0,
      f"rigid-tube ring: auto condensed {s['condensed_dofs']} jumps, "
      f"max|C - C^T| = {s['condensation_asymmetry']:.2e} max|C|")
rows_auto, rows_off = corrosion(auto), corrosion(off)
tol = (newton_bound(len(rows_off), max(solved_unknowns(s), solved_unknowns(summary(off))))
       + 2 * s["condensation_asymmetry"])
d = max(abs(a["p_MPa"] - b["p_MPa"]) for a, b in zip(rows_auto, rows_off)) / max(
    abs(b["p_MPa"]) for b in rows_off)
check(len(rows_auto) == len(rows_off) and d <= tol,
      f"rigid-tube ring: the whole model's corrosion curve to {d:.1e} <= {tol:.1e}")

# 2. An untrusted C: the whole model instead (auto), an error (on).
E = "3e5"
env = dict(os.environ, PUSHOUT_TEST_TRUSTED_ASYMMETRY="1e-30")
fallback = out_dir("trust_fallback")
toml = os.path.join(OUT_ROOT, "trust_auto_E3e5.toml")  # the scene run() wrote above
p = subprocess.run([PUSHOUT, "run", toml, "--out", fallback, "--set", f"steel.E={E}",
                    "--set", "output.plot=false"],
                   capture_output=True, text=True, env=env, timeout=900)
said = [line for line in p.stdout.splitlines() if "not accurate enough" in line]
s = summary(fallback)
check(p.returncode == 0 and s["converged"] and s["condensed_dofs"] == 0
      and s["condensation_asymmetry"] > 0 and len(said) == 1 and "whole model" in said[0],
      f"untrusted C, auto: exit {p.returncode}, the whole model: {said}")
off = os.path.join(OUT_ROOT, f"trust_off_E{E}")
d, tol = largest_difference(curve(fallback), curve(off)), bound(fallback, off)
check(d <= tol, f"untrusted C, auto: the 'off' curve to {d:.1e} <= {tol:.1e}")
p = subprocess.run([PUSHOUT, "run", toml, "--out", out_dir("trust_on"), "--quiet",
                    "--set", f"steel.E={E}", "--set", "solver.condensation=on"],
                   capture_output=True, text=True, env=env, timeout=900)
lines = [line for line in p.stderr.splitlines() if line.startswith("pushout")]
check(p.returncode != 0 and len(lines) == 1 and "max|C - C^T|" in lines[0],
      f"untrusted C, on: exit {p.returncode}, {lines[0] if lines else p.stderr[-300:]}")

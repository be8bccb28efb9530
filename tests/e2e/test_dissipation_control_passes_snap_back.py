"""Dissipation control (loading.control = "dissipation"; "auto" is the same):

1. Snap-back (the 80 mm slice with brittle adhesion of test_arc_length_follows_snap_back.py):
   displacement control stops at the peak; dissipation control goes through
   the snap-back (delta decreases after the peak), reaches the final delta,
   and traces the arc-length path: tau within 2 % of the peak at the same
   mean slip (the arc-length rows interpolated linearly: their spacing near
   the peak is most of it), on the condensed system and on the whole model
   (which take different steps near the peak: a step of delta converges on
   one and not on the other). An energy step that overshoots, replaced by
   steps of delta that fail, is cut, not tried again for ever (a test hook
   makes every energy step overshoot and those steps fail: exit 3, saying
   so, within the timeout).
2. Brittle adhesion on the demo slice (pushout_friction_adhesion, c = 400
   1/mm, f_t = 6 MPa, k = 1e5 N/mm^3 for both layers, 0.5 mm in 10 steps):
   displacement control converges across the peak (its curve never rises
   above the friction plateau) or stops at it, as the round-off goes;
   dissipation control traces the peak (more than 3x the plateau) and the
   softening (its Newton iterations are printed: 347 with threaded BLAS,
   589 with one thread when this was written; a cost, which bench/ measures,
   not a correctness test).
3. Without a softening layer there is nothing to control by: the push runs
   under displacement control.
4. The corrosion stage (the corroded demo, coarse, with a brittle crack
   through the cover: c = 100 1/mm, G_F = 0.03 N/mm; x to 20 um in 10
   steps): control by x stops where the crack snaps (exit 3, its message
   naming loading.control = "auto"); dissipation
   control passes it, x decreasing in at least one step, and reaches x =
   20 um, where p and the crack width equal those of the same crack made
   slightly viscous (eta = 1e-5: x-control passes the snap dynamically) to
   1e-4 relative (measured: 2e-5 and 3e-5; the viscous runs tend to it as
   eta falls: p 8.55561, 8.55526, 8.55519, 8.55516 MPa for eta 3e-4 to
   1e-5, dissipation control 8.55532; the damage the snap leaves differs a
   little between the two paths); the whole model on 2 processes reaches
   the same p at 20 um as the condensed system on one, to Newton's bound
   on the two runs (common.newton_bound over both stages' steps)."""
import os
import subprocess

from common import (COARSE_MESH, FRICTION_2, OUT_ROOT, PUSHOUT, SNAP_BACK_LOADING, check, corrosion,
                    curve, newton_bound, out_dir, run, solved_unknowns, summary)

EXP = '[[interface]]\nlaw = "exponential_softening"\nk = {k}\nf_t = {f_t}\nc = {c}\n'


def tau_at_slip(rows, slip):
    """tau of a curve at mean slip `slip` (linear between rows; the mean
    slip grows along both paths)."""
    for a, b in zip(rows, rows[1:]):
        if a["slip_mm"] <= slip <= b["slip_mm"]:
            t = (slip - a["slip_mm"]) / (b["slip_mm"] - a["slip_mm"])
            return a["tau_MPa"] + t * (b["tau_MPa"] - a["tau_MPa"])
    return None


# 1. Snap-back, against arc length.
snap = COARSE_MESH + FRICTION_2 + EXP.format(k=1000.0, f_t=3.0, c=100.0) + SNAP_BACK_LOADING
arc, diss = out_dir("dissipation_snap_arc_length"), out_dir("dissipation_snap_dissipation")
run(snap, arc, sets=["loading.control=arc_length"])
run(snap, diss, sets=["loading.control=dissipation"])
a, d = curve(arc), curve(diss)
s = summary(diss)
delta = [r["delta_mm"] for r in d]
tau = [r["tau_MPa"] for r in d]
i_peak = tau.index(max(tau))
check(s["converged"] and abs(delta[-1] - 0.04) < 1e-12,
      f"dissipation control reaches delta = {delta[-1]} mm")
back = [i for i in range(i_peak + 1, len(d)) if delta[i] < delta[i - 1]]
check(len(back) >= 1 and s["dissipation_steps"] > 0,
      f"snap-back: delta decreases in {len(back)} steps after the peak; "
      f"{s['dissipation_steps']} of {s['steps']} steps controlled by the energy released")
peak_a = max(r["tau_MPa"] for r in a)
print(f"peak tau: dissipation {max(tau):.4f} MPa, arc length {peak_a:.4f} MPa")
whole = out_dir("dissipation_snap_whole_model")
run(snap, whole, sets=["loading.control=dissipation", "solver.condensation=off"])
for name, out in (("condensed", diss), ("whole model", whole)):
    rows = curve(out)
    diffs = [abs(r["tau_MPa"] - t) for r in rows if (t := tau_at_slip(a, r["slip_mm"])) is not None]
    check(len(diffs) > 10 and max(diffs) < 0.02 * peak_a,
          f"{name}: tau at the same mean slip: max |dissipation - arc length| = {max(diffs):.4f} MPa "
          f"over {len(diffs)} points (peak {peak_a:.3f} MPa); Newton iterations: dissipation "
          f"{summary(out)['newton_iterations']}, arc length {summary(arc)['newton_iterations']}")

# 1b. An energy step that would move delta by more than a step is replaced by
# steps of delta; where those fail back to energy steps, the energy step is
# cut (it was tried again from the same state: the same overshoot, for
# ever). With PUSHOUT_TEST_ENERGY_OVERSHOOTS every energy step overshoots and
# the steps of delta after it fail: the energy steps are cut to the smallest
# loading.max_cuts allows, and the run stops there saying why (exit 3), in
# seconds (a run that hands back and forth for ever meets the timeout).
hooked = out_dir("dissipation_overshoot_hook")
os.makedirs(OUT_ROOT, exist_ok=True)
hooked_scene = os.path.join(OUT_ROOT, "dissipation_overshoot_hook.toml")
with open(hooked_scene, "w") as f:
    f.write(snap)
try:
    p = subprocess.run([PUSHOUT, "run", hooked_scene, "--out", hooked, "--quiet", "--set",
                        "loading.control=dissipation"], capture_output=True, text=True,
                       timeout=120, env=dict(os.environ, PUSHOUT_TEST_ENERGY_OVERSHOOTS="1"))
    code, err = p.returncode, p.stderr.strip()
except subprocess.TimeoutExpired:
    code, err = None, "still handing back and forth after 120 s"
check(code == 3 and "the smallest step of energy would move it by more than a step" in err
      and not summary(hooked)["converged"],
      f"energy steps that overshoot, steps of delta that fail: exit {code}, {err[-250:]!r}")

# 2. Brittle adhesion on the demo slice.
brittle = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "demo",
                       "pushout_friction_adhesion.toml")
BRITTLE = ["interface.1.c=400", "interface.1.f_t=6", "interface.0.k=1e5", "interface.1.k=1e5",
           "loading.push_displacement=0.5", "loading.steps=10"]
disp, diss = out_dir("dissipation_brittle_displacement"), out_dir("dissipation_brittle_dissipation")
# Which of the two displacement control does depends on the round-off of
# the Newton iterates near the peak (BLAS threads).
p = run(brittle, disp, sets=BRITTLE, check=False)
if p.returncode == 0:
    c = curve(disp)
    check(max(r["tau_MPa"] for r in c) < 1.1 * c[-1]["tau_MPa"],
          f"displacement control jumps over the peak: its largest tau "
          f"{max(r['tau_MPa'] for r in c):.3f} MPa, plateau {c[-1]['tau_MPa']:.3f} MPa")
else:
    check(p.returncode == 3, f"displacement control stops at the peak: exit {p.returncode}")
run(brittle, diss, sets=BRITTLE + ["loading.control=auto"])
d, s = curve(diss), summary(diss)
plateau = d[-1]["tau_MPa"]
check(s["converged"] and abs(d[-1]["delta_mm"] - 0.5) < 1e-12,
      f"dissipation control reaches delta = {d[-1]['delta_mm']} mm")
check(max(r["tau_MPa"] for r in d) > 3 * plateau,
      f"the peak is traced: tau {max(r['tau_MPa'] for r in d):.3f} MPa, plateau {plateau:.3f} MPa")
print(f"{s['newton_iterations']} Newton iterations, {s['steps']} steps "
      f"({s['dissipation_steps']} by energy), {s['cuts']} cuts")

# 3. Nothing softens.
friction = COARSE_MESH + FRICTION_2 + """
[loading]
temperature_change = -25.0
push_displacement = 0.05
steps = 5
"""
plain, diss = out_dir("dissipation_friction_displacement"), out_dir("dissipation_friction")
run(friction, plain)
run(friction, diss, sets=["loading.control=dissipation"])
check(summary(diss)["dissipation_steps"] == 0, "no step controlled by the energy released")
a, b = curve(plain), curve(diss)
# Another solver (the path follower's, steps of delta) on the same steps:
# to Newton's bound on the two runs.
tol = newton_bound(len(a), max(solved_unknowns(summary(o)) for o in (plain, diss)))
scale = max(abs(r["P_N"]) for r in a)
check(len(a) == len(b) and all(abs(x["P_N"] - y["P_N"]) <= tol * scale for x, y in zip(a, b)),
      f"the same curve as displacement control (to {tol:.1e} x {scale:.4g} N)")

# 4. A brittle crack in the corrosion stage.
corroded = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "demo",
                        "pushout_corroded.toml")
CRACK = ["crack.0.c=100", "mesh.elements_per_quarter=8", "mesh.elements_through_thickness=2",
         "corrosion.penetration=0.02", "corrosion.steps=10", "loading.push_displacement=0.01",
         "loading.steps=2"]
by_x, diss = out_dir("dissipation_crack_x"), out_dir("dissipation_crack_dissipation")
p = run(corroded, by_x, sets=CRACK, check=False)
check(p.returncode == 3 and 'loading.control = "auto"' in p.stderr,
      f"control by x stops where the crack snaps, and says what follows it: exit {p.returncode}, "
      f"{p.stderr.strip()[-300:]!r}")
run(corroded, diss, sets=CRACK + ["loading.control=dissipation"])
c, s = corrosion(diss), summary(diss)
x = [r["penetration_mm"] for r in c]
back = [i for i in range(1, len(c)) if x[i] < x[i - 1]]
check(s["converged"] and abs(x[-1] - 0.02) < 1e-15 and back and s["dissipation_steps"] > 0,
      f"dissipation control reaches x = {x[-1] * 1e3} um; x decreases in {len(back)} steps "
      f"(the snap-back); {s['dissipation_steps']} of {len(c) - 1} corrosion steps by energy; "
      f"{s['newton_iterations']} Newton iterations")
viscous = out_dir("dissipation_crack_viscous")
run(corroded, viscous, sets=CRACK + ["crack.0.eta=1e-5"])
v = corrosion(viscous)[-1]
for col in ("p_MPa", "crack_width_mm"):
    check(abs(c[-1][col] - v[col]) < 1e-4 * v[col],
          f"at x = 20 um {col} {c[-1][col]:.7g} against {v[col]:.7g} with the viscous crack")
whole = out_dir("dissipation_crack_whole_2")
run(corroded, whole, sets=CRACK + ["loading.control=dissipation"], mpirun=2)
w = corrosion(whole)
check(summary(whole)["condensed_dofs"] == 0 and summary(whole)["processes"] == 2,
      "the whole model on 2 processes")
tol = newton_bound(max(summary(o)["steps"] + summary(o)["corrosion_steps"] + 1 for o in (diss, whole)),
                   max(solved_unknowns(summary(o)) for o in (diss, whole)))
check(abs(w[-1]["p_MPa"] - c[-1]["p_MPa"]) <= tol * max(abs(r["p_MPa"]) for r in c),
      f"whole model, 2 processes: p {w[-1]['p_MPa']:.9g} MPa at 20 um, condensed {c[-1]['p_MPa']:.9g} "
      f"(to {tol:.1e} of the largest p)")

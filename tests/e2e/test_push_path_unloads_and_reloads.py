"""Push paths with unload and reload (loading.push_path, loading.unload_to):

1. Elastic joints (thermal step, top held: P < 0 at delta = 0), pushed to
   4 um and back with unload_to = "zero_force": the unloading rows equal
   the loading rows at the same delta to 1e-8 of the largest force, and the
   unloading ends where P = 0, at the delta where the loading passed P = 0
   (linear between its rows: exact, the model is linear) to 1e-9 mm, with
   |P| below 1e-6 of the largest force; summary.json lists it.
2. Friction (Table 1) past its plateau, unloaded to zero force and reloaded:
   the permanent displacement is > 0 and within 10 % of the mean slip the
   push left at P = 0 (measured: 8.68 against 8.22 um; with one friction
   layer the mean traction, hence the mean elastic slip, is zero at P = 0,
   so this is the mean plastic slip added by the push: the difference is
   the elastic strain of tube and concrete locked in by the friction
   tractions and by the thermal step). Reloading rejoins the monotonic
   curve (tau at 20 um to 1e-6 relative). The whole model gives the same
   permanent displacement as the condensed system (1e-8 mm).
3. Friction + adhesion (Fig. 10 layers) with an unloading before and one
   after the peak: both end at zero force with a growing permanent
   displacement, and reloading rejoins the monotonic curve after the peak
   (tau at 80 um within 1 %); with viscous adhesion (eta = 1e-3 mm) the
   loops run too.
4. Scene errors: a path that does not start at 0, push_path with step
   growth or with dissipation control: exit 2 and a message naming the key.
5. A path within a thin slice's small-displacement range runs, whatever
   the (unread) push_displacement, and the unread keys are noted.
6. IMPL-EX cracks in the concrete (the coarse corroded slice with cracks
   anywhere): pushed to 10 um and unloaded, the unloading ends at zero force
   (|P| within the search's 1e-6 of the largest force) with a permanent
   displacement. A try at the zero force is taken without IMPL-EX's error
   check (its size is the force's), but not where the crack band's own
   update failed: with a test hook that fails it at one point, the run stops
   there, exit 3, and says so; nothing of that try is committed.
7. An unloading ended at zero force skips the unloadings right after it
   (they would pull); one that reaches zero force at its own vertex lists
   no permanent displacement."""
import os

from common import (COARSE_MESH, EXP_SOFT, FRICTION_2, OUT_ROOT, check, cracking_corroded_demo, curve,
                    newton_bound, out_dir, run, solved_unknowns, summary)

THERMAL = "[loading]\ntemperature_change = -25.0\nsteps_per_segment = {n}\npush_path = {path}\n"
ZERO = 'unload_to = "zero_force"\n'
ELASTIC = '[[interface]]\nlaw = "elastic"\nk = 1000.0\n'

# 1. Elastic: reversible.
out = out_dir("push_path_elastic")
run(COARSE_MESH + ELASTIC + THERMAL.format(n=8, path="[0.0, 0.004, 0.0]") + ZERO, out)
c, s = curve(out), summary(out)
P_max = max(abs(r["P_N"]) for r in c)
load, unload = c[1:9], c[9:-1]
pairs = [(u, next(r for r in load if abs(r["delta_mm"] - u["delta_mm"]) < 1e-15)) for u in unload]
# Every unloading row before the zero-force end has its loading row (how
# many there are depends on where P crosses 0: the thermal force over the
# slice's stiffness, so on the mesh).
check(len(pairs) == len(unload) >= 2 and all(abs(u["P_N"] - l["P_N"]) < 1e-8 * P_max for u, l in pairs),
      f"elastic: the {len(pairs)} unloading rows equal the loading rows at the same delta "
      f"(largest difference {max(abs(u['P_N'] - l['P_N']) for u, l in pairs):.1e} N)")
i = next(i for i in range(len(c) - 1) if c[i]["P_N"] < 0 <= c[i + 1]["P_N"])
a, b = c[i], c[i + 1]
delta0 = a["delta_mm"] + (b["delta_mm"] - a["delta_mm"]) * (-a["P_N"]) / (b["P_N"] - a["P_N"])
end = c[-1]
check(abs(end["delta_mm"] - delta0) < 1e-9 and abs(end["P_N"]) < 1e-6 * P_max
      and len(s["permanent_displacements_mm"]) == 1
      and abs(s["permanent_displacements_mm"][0] - end["delta_mm"]) < 1e-13,
      f"elastic: the unloading ends at delta = {end['delta_mm'] * 1e3:.6f} um, P = {end['P_N']:.2e} N; "
      f"the loading passed P = 0 at {delta0 * 1e3:.6f} um")

# 2. Friction: permanent displacement, reload, whole model.
friction = COARSE_MESH + FRICTION_2 + THERMAL.format(n=10, path="[0.0, 0.01, 0.0, 0.02]") + ZERO
mono = out_dir("push_path_friction_monotonic")
run(COARSE_MESH + FRICTION_2 + "[loading]\ntemperature_change = -25.0\n"
    "push_displacement = 0.02\nsteps = 20\n", mono)
for name, sets in (("condensed", []), ("whole", ["solver.condensation=off"])):
    out = out_dir(f"push_path_friction_{name}")
    run(friction, out, sets=sets)
    c, s = curve(out), summary(out)
    perm = s["permanent_displacements_mm"]
    zero = next(r for r in c if abs(r["delta_mm"] - perm[0]) < 1e-13)
    slip_added = zero["slip_mm"] - c[0]["slip_mm"]
    if name == "condensed":
        check(len(perm) == 1 and perm[0] > 0 and abs(perm[0] - slip_added) < 0.1 * perm[0],
              f"friction: permanent displacement {perm[0] * 1e3:.3f} um, mean slip added by the push "
              f"{slip_added * 1e3:.3f} um")
        # The plateau of friction (perfectly plastic) is the same however it
        # was reached: the two runs' to Newton's bound.
        tau, tau_mono = c[-1]["tau_MPa"], curve(mono)[-1]["tau_MPa"]
        tol = newton_bound(s["steps"] + 1, max(solved_unknowns(s), solved_unknowns(summary(mono))))
        check(abs(c[-1]["delta_mm"] - 0.02) < 1e-15 and abs(tau - tau_mono) <= tol * tau_mono,
              f"friction: reloaded to 20 um, tau {tau:.9f} MPa, monotonic {tau_mono:.9f} MPa "
              f"(to {tol:.1e})")
        perm_condensed, s_condensed = perm[0], s
    else:
        # Each run finds the zero to |P| <= 1e-6 of the peak force (the search's
        # tolerance, DisplacementControl.cpp), on forces that are exact to
        # Newton's bound: the zeros' positions differ by those forces over the
        # unloading branch's slope at the zero.
        i = c.index(zero)
        slope = abs((c[i - 1]["P_N"] - zero["P_N"]) / (c[i - 1]["delta_mm"] - zero["delta_mm"]))  # [N/mm]
        P_peak = max(r["P_N"] for r in c)
        tol = (2 * 1e-6 + newton_bound(s["steps"] + 1, max(solved_unknowns(s), solved_unknowns(s_condensed)))) \
            * P_peak / slope  # [mm]
        check(abs(perm[0] - perm_condensed) <= tol,
              f"whole model: permanent displacement {perm[0] * 1e3:.6f} um, "
              f"condensed {perm_condensed * 1e3:.6f} um (to {tol * 1e3:.1e} um)")

# 3. Friction + adhesion: unload before and after the peak.
fig10 = COARSE_MESH + FRICTION_2 + EXP_SOFT
path = "[0.0, 0.006, 0.0, 0.03, 0.0, 0.08]"
loops, mono = out_dir("push_path_fig10"), out_dir("push_path_fig10_monotonic")
run(fig10 + THERMAL.format(n=12, path=path) + ZERO, loops)
run(fig10 + "[loading]\ntemperature_change = -25.0\npush_displacement = 0.08\nsteps = 48\n", mono)
c, s, m = curve(loops), summary(loops), curve(mono)
perm = s["permanent_displacements_mm"]
peak = max(m, key=lambda r: r["tau_MPa"])
check(len(perm) == 2 and 0 < perm[0] < perm[1] and 0.006 < peak["delta_mm"] < 0.03,
      f"fig10 layers: unloaded at 6 and 30 um (peak at {peak['delta_mm'] * 1e3:.1f} um): "
      f"permanent displacements {[round(p * 1e3, 3) for p in perm]} um")
check(abs(c[-1]["tau_MPa"] - m[-1]["tau_MPa"]) < 0.01 * m[-1]["tau_MPa"],
      f"fig10 layers: reloaded to 80 um, tau {c[-1]['tau_MPa']:.5f} MPa, monotonic "
      f"{m[-1]['tau_MPa']:.5f} MPa")
viscous = out_dir("push_path_fig10_viscous")
run(fig10 + THERMAL.format(n=12, path=path) + ZERO, viscous, sets=["interface.1.eta=1e-3"])
check(len(summary(viscous)["permanent_displacements_mm"]) == 2,
      f"viscous adhesion: permanent displacements "
      f"{[round(p * 1e3, 3) for p in summary(viscous)['permanent_displacements_mm']]} um")

# 4. Scene errors.
for what, scene, key in (
        ("a path not starting at 0", THERMAL.format(n=4, path="[0.01, 0.02]"), "loading.push_path"),
        ("a path of one point", THERMAL.format(n=4, path="[0.0]"), "no segment"),
        ("step growth", THERMAL.format(n=4, path="[0.0, 0.02]") + "step_growth = 1.1\n",
         "loading.step_growth"),
        ("dissipation control", THERMAL.format(n=4, path="[0.0, 0.02]") + 'control = "dissipation"\n',
         "loading.push_path")):
    out = out_dir("push_path_error")
    p = run(COARSE_MESH + FRICTION_2 + scene, out, check=False)
    check(p.returncode == 2 and key in p.stderr, f"{what}: exit {p.returncode}, {p.stderr.strip()}")

# A path within the slice's small-displacement range runs whatever the
# monotonic push's push_displacement (not read with a path: 0.01 mm, more
# than 10 % of this 0.08 mm slice, was refused), and the run notes the
# monotonic push's keys as not read.
out = out_dir("push_path_thin_slice")
scene = os.path.join(OUT_ROOT, "push_path_thin_slice.toml")
with open(scene, "w") as f:
    f.write(COARSE_MESH + FRICTION_2 + THERMAL.format(n=2, path="[0.0, 0.005]"))
p = run(scene, out, ["geometry.thickness=0.08", "loading.steps=7"], check=False, quiet=False)
check(p.returncode == 0 and "loading.steps not read: loading.push_path sets the push" in p.stdout,
      f"a thin slice with a push path: exit {p.returncode}, {p.stderr.strip()[-300:]!r}")
notes = summary(out)["notes"]
check(len(notes) == 1 and notes[0].startswith("loading.steps not read"),
      f"summary.json keeps the note: {notes}")

# 6. IMPL-EX cracks: the zero force found, and a failed crack band update
# there stops the run.
cracked = cracking_corroded_demo(0.012, 6, seed=1).replace(
    "[loading]\n", "[loading]\npush_path = [0.0, 0.01, 0.0]\nsteps_per_segment = 4\n" + ZERO)
out = out_dir("push_path_implex_cracks")
run(cracked, out)
c, s = curve(out), summary(out)
P_max = max(abs(r["P_N"]) for r in c)
check(len(s["permanent_displacements_mm"]) == 1 and abs(c[-1]["P_N"]) < 1e-6 * P_max
      and 0 < c[-1]["delta_mm"] < 0.01,
      f"IMPL-EX cracks: the unloading ends at P = {c[-1]['P_N']:.2e} N (largest {P_max:.0f} N), "
      f"delta = {c[-1]['delta_mm'] * 1e3:.3f} um")
failed = out_dir("push_path_implex_cracks_failed_update")
os.environ["PUSHOUT_TEST_FAIL_CRACK_BAND_UPDATE"] = "1"
try:
    p = run(cracked, failed, check=False)
finally:
    del os.environ["PUSHOUT_TEST_FAIL_CRACK_BAND_UPDATE"]
f = curve(failed)
check(p.returncode == 3 and "zero force of the unloading failed" in p.stderr
      and "crack band's update failed at 1 point" in p.stderr and len(f) == len(c) - 1
      and summary(failed)["permanent_displacements_mm"] == [],
      f"a failed crack band update at the zero force: exit {p.returncode}, {len(f)} rows against "
      f"{len(c) - 1} before it, {p.stderr.strip()[-300:]!r}")

# 7. An unloading ended at zero force skips the unloadings right after it
# (they would pull): one permanent displacement and one row at it (the next
# segment searched a zero again 1e-12 mm further: two of each); and an
# unloading that reaches zero force at its own vertex, as an elastic joint's
# at delta = 0 with no thermal step, lists none whatever the sign of P's
# round-off there (it listed [5.2e-18, 0.0]).
out = out_dir("push_path_unloadings_in_a_row")
run(COARSE_MESH + FRICTION_2 + EXP_SOFT + THERMAL.format(n=10, path="[0.0, 0.03, 0.005, 0.0, 0.05]")
    + ZERO, out)
c, s = curve(out), summary(out)
at_zero = [r for r in c if abs(r["P_N"]) < 1e-6 * max(abs(r["P_N"]) for r in c)]
check(len(s["permanent_displacements_mm"]) == 1 and len(at_zero) == 1,
      f"unloadings in a row: permanent displacements {s['permanent_displacements_mm']}, "
      f"{len(at_zero)} row(s) at zero force")
out = out_dir("push_path_elastic_back_to_zero")
run(COARSE_MESH + '[[interface]]\nlaw = "elastic"\nk = 1000.0\n'
    + THERMAL.replace("-25.0", "0.0").format(n=5, path="[0.0, 0.01, 0.0, 0.01, 0.0]") + ZERO, out)
check(summary(out)["permanent_displacements_mm"] == [],
      f"elastic, back to delta = 0: no permanent displacement: "
      f"{summary(out)['permanent_displacements_mm']}")

"""The implicit cracks' step error (cracking.implicit_tolerance,
docs/cracking.md "The implicit cracks' step error"): after each converged
step of the implicit cracks, the stress the crack band's own update gives
at the step's strain is compared with what IMPL-EX's prediction from the
last steps answers there (the predictor-corrector difference of a
first-order integration), and a step further from it than the tolerance is
cut. The cracks are path dependent, so the implicit cracks at the scene's
steps carry a step error of their own. On the corroded demo's specimen
(coarse mesh, random field, tube 15 mm from a face), corroded to x = 30 um
in 15 steps and pushed 5 um:

1. At the scene's 15 steps with the tolerance at 0.005, p(x) is within
   1.5 % (of the peak) of the implicit cracks at four times the steps at
   every nominal x, with the same surface crack within 1.5 % (the bound of
   test_implex_tends_to_implicit 1: the reference's own step error, 1 %
   between 30 and 60 steps, plus the controlled run's), where the same 15
   steps without it are further off than that (3.9 % measured; 0.65 % with
   it). Its steps were cut for the error (more corrosion rows than the
   scene's), and every step met the tolerance or was taken at the smallest
   size the error may cut to (summary.json implicit_error_max,
   implicit_jumps).
2. The readings are the implicit cracks': implicit_error_max and
   implicit_jumps set, implex_error_max and implex_jumps null. Without the
   tolerance the steps are not held, but their error is read all the same:
   implicit_error_max set (above the 0.005 that the controlled run cut
   these steps for), implicit_jumps null, and a note (printed, and in
   summary.json) says how many steps went above IMPL-EX's tolerance and
   which key holds them; the controlled run has no such note.
3. With IMPL-EX cracks the key is not read, and the run says so (a note, in
   summary.json too).
4. Refused with a damage viscosity (exit 2, the scene's error names both
   keys): the prediction takes no viscosity, so the error would not fall
   with the step.
5. The same steps, cracked points and p(x) on 1 and 2 processes, to
   Newton's tolerance (both at SNES_RTOL, common.TIGHT_NEWTON): a step's
   error is a sum over the processes' points, so its cut or not could
   differ only if it landed within round-off of the tolerance."""

from common import (check, check_one_and_two_processes, corrosion, cracking_corroded_demo, out_dir,
                    run, summary)

scene = cracking_corroded_demo(0.03, 15, seed=1)
reference, plain, controlled = out_dir("implicit_ref"), out_dir("implicit_plain"), \
    out_dir("implicit_controlled")
run(scene, reference, sets=["corrosion.steps=60", "cracking.integration=implicit"])
run(scene, plain, sets=["cracking.integration=implicit"])
run(scene, controlled, sets=["cracking.integration=implicit", "cracking.implicit_tolerance=0.005"])

ref = corrosion(reference)
peak = max(r["p_MPa"] for r in ref)
ref_at = {round(r["penetration_mm"], 9): r["p_MPa"] for r in ref}
grid = {round(0.002 * k, 9) for k in range(16)}  # the 15 nominal steps' x [mm]


def off(out):
    """The largest difference of p at the nominal x from the reference's,
    over its peak, and the number of nominal x compared."""
    at = {round(r["penetration_mm"], 9): r["p_MPa"] for r in corrosion(out)}
    common = grid & at.keys() & ref_at.keys()
    return max(abs(at[x] - ref_at[x]) for x in common) / peak, len(common)


# 1. Within the bound with the tolerance, outside it without.
dp, n = off(controlled)
dp_plain, n_plain = off(plain)
rows = corrosion(controlled)
w, w_ref = rows[-1]["crack_width_mm"], ref[-1]["crack_width_mm"]
check(n == n_plain == 16 and dp < 0.015 < dp_plain and w_ref > 0.05 and abs(w - w_ref) < 0.015 * w_ref,
      f"implicit cracks at the scene's 15 steps: p(x) within {100 * dp:.2f} % of 60 steps' with "
      f"implicit_tolerance 0.005, {100 * dp_plain:.2f} % without; the surface crack at 30 um "
      f"{1e3 * w:.1f} um against {1e3 * w_ref:.1f} um")
s = summary(controlled)
check(len(rows) > len(corrosion(plain)) and
      (s["implicit_error_max"] <= 0.005 * (1 + 1e-12) or s["implicit_jumps"] > 0),
      f"the steps cut for their error: {len(rows)} corrosion rows against "
      f"{len(corrosion(plain))}, the largest error {s['implicit_error_max']:.4f}, "
      f"{s['implicit_jumps']} taken above it")

# 2. Which readings are set.
s_plain = summary(plain)
check(s["cracking_integration"] == "implicit" and s["implex_error_max"] is None and
      s["implex_jumps"] is None and s["implicit_jumps"] is not None and
      all(s_plain[k] is None for k in ("implicit_jumps", "implex_error_max", "implex_jumps")),
      f"readings: implicit_error_max {s['implicit_error_max']}, implex_error_max "
      f"{s['implex_error_max']}; without the tolerance implicit_jumps {s_plain['implicit_jumps']}")
# Up to the controlled run's first cut its steps are the plain run's (the
# scene's, from the same state, on one process), and the try it cut had
# converged (the plain run took it): it was cut for its error, so that
# plain step erred above 0.005.
unheld = [n for n in s_plain["notes"] if "were not held to their error" in n]
check(s_plain["implicit_error_max"] is not None and s_plain["implicit_error_max"] > 0.005 and
      len(unheld) == 1 and "cracking.implicit_tolerance = 0.0025 holds them" in unheld[0] and
      not any("were not held to their error" in n for n in s["notes"]),
      f"without the tolerance the error is read: implicit_error_max "
      f"{s_plain['implicit_error_max']}, noted: {unheld}")

# 3. Not read with IMPL-EX cracks.
unread = out_dir("implicit_tolerance_unread")
run(scene, unread, sets=["corrosion.penetration=0.002", "corrosion.steps=1",
                         "cracking.implicit_tolerance=0.005"])
notes = summary(unread)["notes"]
check(any("cracking.implicit_tolerance" in note for note in notes),
      f"cracking.implicit_tolerance with IMPL-EX cracks noted: {notes}")

# 4. Refused with a damage viscosity, which IMPL-EX's prediction does not
#    take (measured: the error stayed near 0.2 at every step size, so every
#    step was cut to 2^-6 of a nominal one).
#    Explicitly implicit, and "auto", which a viscosity makes implicit.
for integration in ("implicit", "auto"):
    p = run(scene, out_dir("implicit_tolerance_viscosity"),
            sets=[f"cracking.integration={integration}", "cracking.implicit_tolerance=0.005",
                  "cracking.viscosity=0.001"], check=False)
    check(p.returncode == 2 and "measures a step against IMPL-EX's prediction" in p.stderr,
          f"implicit_tolerance with a damage viscosity, integration {integration}: exit "
          f"{p.returncode} ({p.stderr.strip()[:120]})")

# 5. One and two processes, with steps cut for their error.
sets = ["cracking.integration=implicit", "cracking.implicit_tolerance=0.005",
        "corrosion.penetration=0.016", "corrosion.steps=8"]
_, one = check_one_and_two_processes(scene, "implicit_step_error", sets)
check(len(corrosion(one)) > 9, f"steps cut there: {len(corrosion(one))} corrosion rows for 8 steps")

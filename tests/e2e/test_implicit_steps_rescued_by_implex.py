"""The IMPL-EX rescue of the implicit cracks (cracking.implex_rescue,
docs/cracking.md "The IMPL-EX rescue"): where the implicit cracks' Newton
fails at every cut down to the smallest step (2^-10 of a step or less), that
step is tried once more as one IMPL-EX step, whose bulk is linear but for
closure; its crack band's own update at its strain is committed, and the
implicit steps go on from it. On the corroded demo's specimen (coarse mesh,
random field, tube 15 mm from a face), corroded to x = 30 um in 15 steps,
the implicit cracks' every try of the sixth corrosion step is made to fail
(test hook PUSHOUT_TEST_FAIL_IMPLICIT_ROW=5, as Newton cycling there would):

1. Under displacement control the run goes on: one rescue (summary.json
   implex_rescues), after the ten cuts to 2^-10 of a step, at x = 10 um +
   2 um / 1024, its IMPL-EX error reported (implex_rescue_error_max) and
   below cracking.implex_tolerance: IMPL-EX itself takes steps of 1/16 of
   a step there with errors just below it (0.0029 at 1/8 is cut), and its
   error does not grow as the step shrinks, so a step 64 times smaller
   stays below it (measured 1.7e-5); the rows before it are the plain run's
   (the same steps of the same binary on one process, to round-off), and
   p at the nominal x after it is the plain run's within 3.9 % of the peak,
   the implicit cracks' own step error at these 15 steps
   (test_implicit_step_error: the steps after the rescue are the plain
   run's or finer, so the two differ by at most that).
2. The same under loading.control = "auto", where the failure hands the
   step to energy steps and the rescue is one IMPL-EX energy step of the
   smallest release, 2^-10 of the energy steps' nominal one (the first
   cut's release is half of that). And in the push (every implicit try of
   the first push step failing): under displacement control one rescue, a
   load step of 2^-10 of the push's first step, and the push goes on to
   its end; under arc length (loading.control = "arc_length") one rescue,
   a path-following step.
3. With cracking.implex_rescue = false the run stops there, as before,
   and says to take IMPL-EX or to let the rescue take the step.
4. A rescue that fails too (test hook PUSHOUT_TEST_FAIL_CRACK_BAND_UPDATE:
   its crack band's update fails at a point) stops the run, which says so.
5. No rescue where the smallest step is larger than 2^-10 of a step
   (loading.max_cuts = 9; the message says what would let it), nor with a
   damage viscosity (which IMPL-EX does not take).
6. With a viscosity, or with IMPL-EX cracks, the key is not read, and a run
   that sets it says so (a note); with IMPL-EX cracks summary.json's
   implex_rescues is null; with a viscosity the implicit cracks' step
   error is not read either (implicit_error_max null: the prediction takes
   no viscosity).
7. The rescued run on 1 and 2 processes: the same rows, cracked points and
   p(x) to Newton's bound (the rescue is agreed: Newton's outcome is the
   same on every process)."""

import os
import re

from common import (check, check_one_and_two_processes, corrosion, cracking_corroded_demo, curve,
                    out_dir, run, summary)

scene = cracking_corroded_demo(0.03, 15, seed=1)
IMPLICIT = ["cracking.integration=implicit"]
DISPLACEMENT = IMPLICIT + ["loading.control=displacement"]
ROW = "5"  # corrosion rows after step 0 before the step whose tries fail
RESCUE_LINE = "as one IMPL-EX step (cracking.implex_rescue)"


def hooked(name, sets, check_exit=True, fail_update=False, row=ROW):
    """The scene with every implicit try after `row` committed rows (corrosion
    step 6 by default) failing."""
    os.environ["PUSHOUT_TEST_FAIL_IMPLICIT_ROW"] = row
    if fail_update:
        os.environ["PUSHOUT_TEST_FAIL_CRACK_BAND_UPDATE"] = "1"
    try:
        out = out_dir(name)
        return out, run(scene, out, sets=sets, check=check_exit, quiet=False)
    finally:
        del os.environ["PUSHOUT_TEST_FAIL_IMPLICIT_ROW"]
        os.environ.pop("PUSHOUT_TEST_FAIL_CRACK_BAND_UPDATE", None)


# 1. Displacement control.
plain = out_dir("rescue_plain")
run(scene, plain, sets=DISPLACEMENT)
rescued, p = hooked("rescue_displacement", DISPLACEMENT)
s, s_plain = summary(rescued), summary(plain)
check(s_plain["converged"] and s_plain["implex_rescues"] == 0 and
      s_plain["implex_rescue_error_max"] == 0,
      f"the plain implicit run: no rescue ({s_plain['implex_rescues']})")
check(s["converged"] and s["implex_rescues"] == 1 and s["cuts"] == 10 and
      RESCUE_LINE in p.stdout and "implicit cracks again" in p.stdout,
      f"every implicit try of step 6 failing: the run went on after {s['cuts']} cuts and "
      f"{s['implex_rescues']} IMPL-EX rescue")
rows, rows_plain = corrosion(rescued), corrosion(plain)
x_rescue = 0.010 + 0.002 / 1024  # [mm]
check(abs(rows[int(ROW) + 1]["penetration_mm"] - x_rescue) < 1e-12,
      f"the rescue is the smallest step, to x = {rows[int(ROW) + 1]['penetration_mm'] * 1e3:.6f} um")
error = s["implex_rescue_error_max"]
check(0 < error <= 0.0025, f"its IMPL-EX error {error:.2e} is reported, below the tolerance")
same = all(abs(a["p_MPa"] - b["p_MPa"]) <= 1e-12 * abs(b["p_MPa"]) and
           a["cracked_points"] == b["cracked_points"]
           for a, b in zip(rows[:int(ROW) + 1], rows_plain[:int(ROW) + 1]))
check(same, "the rows before it are the plain run's")
peak = max(r["p_MPa"] for r in rows_plain)
nominal = {round(0.002 * k, 9) for k in range(int(ROW) + 2, 16)}
at = {round(r["penetration_mm"], 9): r["p_MPa"] for r in rows}
at_plain = {round(r["penetration_mm"], 9): r["p_MPa"] for r in rows_plain}
dp = max(abs(at[x] - at_plain[x]) for x in nominal) / peak
check(nominal <= at.keys() and dp <= 0.039,
      f"p after it within {dp:.2%} of the peak of the plain run's at the nominal x (<= 3.9 %)")

# 2. Dissipation control.
out, p = hooked("rescue_auto", IMPLICIT + ["loading.control=auto"])
s = summary(out)
releases = [float(r) for r in re.findall(r"retrying with a release of ([0-9.e+-]+) N mm", p.stdout)]
rescue_release = re.search(r"the step of a release of ([0-9.e+-]+) N mm " + re.escape(RESCUE_LINE),
                           p.stdout)
check(s["converged"] and s["implex_rescues"] == 1 and
      "dissipation-controlled corrosion step 6" in p.stdout and rescue_release is not None and
      releases and float(rescue_release.group(1)) <= 2 * releases[0] / 1024 * (1 + 1e-5),
      f"under loading.control = \"auto\": {s['implex_rescues']} rescue, an energy step of "
      f"{rescue_release.group(1) if rescue_release else '?'} N mm (nominal "
      f"{2 * releases[0] if releases else '?'} N mm)")

# ... and in the push, under displacement control: after the 15 corrosion
# rows, the first load step's tries fail.
out, p = hooked("rescue_push_displacement", DISPLACEMENT, row="15")
s = summary(out)
push = curve(out)
check(s["converged"] and s["implex_rescues"] == 1 and s["cuts"] == 10 and
      # (the push of one step is "load step", as a stage of one step)
      re.search(r"load step: .*" + re.escape(RESCUE_LINE), p.stdout) is not None and
      push[-1]["delta_mm"] == curve(plain)[-1]["delta_mm"],
      f"in the push under displacement control: {s['implex_rescues']} rescue after {s['cuts']} "
      f"cuts, the push to delta = {push[-1]['delta_mm']} mm")

# ... and in the push under arc length: after the 15 corrosion rows.
out, p = hooked("rescue_arc_length", IMPLICIT + ["loading.control=arc_length"], row="15")
s = summary(out)
check(s["converged"] and s["implex_rescues"] == 1 and
      re.search(r"path-following step 1: .*" + re.escape(RESCUE_LINE), p.stdout) is not None,
      f"under loading.control = \"arc_length\", in the push: {s['implex_rescues']} rescue, a "
      "path-following step")

# 3. Off.
out, p = hooked("rescue_off", DISPLACEMENT + ["cracking.implex_rescue=false"], check_exit=False)
s = summary(out)
check(p.returncode == 3 and "did not converge with 10 cuts" in p.stderr and
      'cracking.integration = "implex"' in p.stderr and RESCUE_LINE not in p.stdout and
      "cracking.implex_rescue = true" in p.stderr and s["implex_rescues"] == 0,
      f"cracking.implex_rescue = false: exit {p.returncode}, stopped at step 6")

# 4. A rescue that fails.
out, p = hooked("rescue_fails", DISPLACEMENT, check_exit=False, fail_update=True)
s = summary(out)
check(p.returncode == 3 and RESCUE_LINE in p.stdout and "nor as one IMPL-EX step" in p.stderr and
      "failed as one IMPL-EX step too" in p.stderr and s["implex_rescues"] == 0,
      f"a rescue that fails: exit {p.returncode} ({p.stderr.strip()[-200:]!r})")

# 5. Where no rescue is tried.
out, p = hooked("rescue_max_cuts", DISPLACEMENT + ["loading.max_cuts=9"], check_exit=False)
check(p.returncode == 3 and "did not converge with 9 cuts" in p.stderr and
      RESCUE_LINE not in p.stdout and "loading.max_cuts >= 10" in p.stderr,
      f"loading.max_cuts = 9 (smallest step 2^-9): no rescue, exit {p.returncode}")
out, p = hooked("rescue_viscous", DISPLACEMENT + ["cracking.viscosity=0.001"], check_exit=False)
check(p.returncode == 3 and RESCUE_LINE not in p.stdout and "viscosity" in p.stderr,
      f"with a viscosity: no rescue, exit {p.returncode}")

# 6. Where the key is not read, a run that sets it says so (a note).
SHORT = ["corrosion.penetration=0.002", "corrosion.steps=1", "cracking.implex_rescue=false"]
for name, sets in (("rescue_note_viscous", IMPLICIT + ["cracking.viscosity=0.001"]),
                   ("rescue_note_implex", ["cracking.integration=implex"])):
    out = out_dir(name)
    run(scene, out, sets=sets + SHORT)
    s = summary(out)
    nulls = s["implex_rescues"] is None and s["implex_rescue_error_max"] is None
    check(any("cracking.implex_rescue" in n for n in s["notes"]) and
          nulls == (s["cracking_integration"] == "implex") and s["implicit_error_max"] is None,
          f"{' '.join(sets)}: a note on cracking.implex_rescue (implex_rescues "
          f"{s['implex_rescues']})")

# 7. One and two processes.
os.environ["PUSHOUT_TEST_FAIL_IMPLICIT_ROW"] = ROW
try:
    p_one, one = check_one_and_two_processes(scene, "rescue", DISPLACEMENT)
finally:
    del os.environ["PUSHOUT_TEST_FAIL_IMPLICIT_ROW"]
check(summary(one)["implex_rescues"] == 1, "the two-process comparison ran through a rescue")

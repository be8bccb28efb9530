"""Newton at the round-off floor: tolerances below what
floating point can reach (-snes_atol 1e-30 -snes_rtol 1e-30) converge once
||F|| is at the floor of the residual (NonlinearProblem::residual_floor),
instead of failing the line search there and cutting the step back to
max_cuts. The full model (tube off-centre, held only by the interface: its
floor is the highest) on the whole model, factored and lagged, with path
following, and condensed: every step converges with no cut and few Newton
iterations, on the curve of the default tolerances."""
from common import (COARSE_MESH, EXP_SOFT, FRICTION_2, check, curve, newton_bound, out_dir, run,
                    solved_unknowns, summary)

scene = (COARSE_MESH + FRICTION_2 + EXP_SOFT + "[geometry]\ntube_center = [45.0, 50.0]\n"
         "[loading]\ntemperature_change = -25.0\npush_displacement = 0.05\nsteps = 5\n")
tiny = ["-snes_atol", "1e-30", "-snes_rtol", "1e-30"]
ref_out = out_dir("floor_reference")
run(scene, ref_out, sets=["solver.condensation=off"])
ref = curve(ref_out)
scale = max(abs(r["P_N"]) for r in ref)
# The reference converged each step to -snes_rtol alone, the others to the
# round-off floor: half Newton's bound on two runs.
tol = newton_bound(len(ref), solved_unknowns(summary(ref_out))) / 2
for name, sets in (("whole, factored", ["solver.condensation=off", "solver.preconditioner=jacobian"]),
                   ("whole, lagged", ["solver.condensation=off"]),
                   ("whole, path following", ["solver.condensation=off", "loading.control=arc_length"]),
                   ("condensed", ["solver.condensation=on"])):
    out = out_dir("floor_" + name.replace(", ", "_").replace(" ", "_"))
    p = run(scene, out, sets=sets, extra=tiny, check=False)
    check(p.returncode == 0, f"{name}: -snes_atol 1e-30 -snes_rtol 1e-30 converges "
                             f"(exit {p.returncode}) {p.stderr.strip()[-300:]}")
    rows = curve(out)
    check(all(r["cuts"] == 0 for r in rows), f"{name}: no step cut back")
    its = [int(r["newton_iterations"]) for r in rows]
    check(max(its) <= 8, f"{name}: Newton iterations per step {its} <= 8")
    if "path" not in name:
        diff = max(abs(a["P_N"] - b["P_N"]) for a, b in zip(rows, ref))
        check(len(rows) == len(ref) and diff <= tol * scale,
              f"{name}: the curve of the default tolerances (max |dP| = {diff:.1e} N <= {tol:.1e} x "
              f"{scale:.4g})")

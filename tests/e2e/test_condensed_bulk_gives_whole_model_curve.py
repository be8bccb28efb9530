"""Condensation of the linear bulk (solver.condensation, solver/
Condensation.h): Newton on the interface jumps gives the plain full-Newton
whole-model curve (LU of every whole-model Jacobian) to Newton's bound in each
situation that changes how it works:
 - the full model: its tube is held in x only by the interface, so J0 needs
   its eps joint to be regular;
 - the tube top free in the thermal step: the constrained dofs change after
   step 0 and the condensation is built again;
 - path following (arc length) through the adhesion peak, also with the
   tube top free in the thermal step;
 - a single joint, whose curve reads reactions, and output.xdmf: the bulk is
   recovered after every step.
It is the default where possible, and solver.condensation = "on" is refused
with a clear error where it is not."""
import os
import re

from common import (COARSE_MESH, EXP_SOFT, FRICTION_2, SOURCE, THROUGH_PEAK, check, curve, newton_bound, out_dir, run,
                    solved_unknowns, summary)

adhesion = COARSE_MESH + FRICTION_2 + EXP_SOFT + THROUGH_PEAK
single_joint = os.path.join(SOURCE, "demo", "single_joint_cohesive_friction.toml")
cases = {
    "full_model": (adhesion, ["model.symmetry=full"]),
    "top_free": (adhesion, ["loading.thermal_tube_top=free"]),
    "arc_length": (adhesion, ["loading.control=arc_length"]),
    "arc_length_top_free": (adhesion, ["loading.control=arc_length", "loading.thermal_tube_top=free"]),
    "single_joint": (single_joint, []),
    "fields": (COARSE_MESH + FRICTION_2, ["loading.steps=3", "output.xdmf=true"]),
}
PLAIN = ["solver.preconditioner=jacobian", "solver.condensation=off"]
for name, (scene, sets) in cases.items():
    condensed, plain = out_dir(f"condensation_{name}"), out_dir(f"condensation_{name}_plain")
    run(scene, condensed, sets=sets + ["output.plot=false"])
    run(scene, plain, sets=sets + PLAIN + ["output.plot=false"])
    sc, sp = summary(condensed), summary(plain)
    check(sc["condensed_dofs"] > 0 and sp["condensed_dofs"] == 0,
          f"{name}: Newton on {sc['condensed_dofs']} jumps instead of {sp['dofs']} dofs")
    a, b = curve(condensed), curve(plain)
    check(len(a) == len(b) and sc["converged"], f"{name}: both converged, {len(a)} rows")
    columns = [c for c in b[0] if c not in ("step", "newton_iterations", "cuts", "wall_s")]
    # Each run converged every step (the corrosion stage's too) to Newton's
    # tolerance, summing in its own order: that bounds the sums of nodal
    # forces (P, tau, the mean pressures). Not the displacements, slips,
    # damage and pointwise tractions: their error is the residual over the
    # softening joints' tangent, which Newton's test does not bound: 1e-6
    # there.
    bound = newton_bound(max(s["steps"] + s.get("corrosion_steps", 0) + 1 for s in (sc, sp)),
                         max(solved_unknowns(sc), solved_unknowns(sp)))
    for c in columns:
        summed = c in ("P_N", "tau_MPa", "p_MPa") or re.fullmatch(r"p_\d+_MPa", c)
        tol = bound if summed else max(bound, 1e-6)
        scale = max(abs(r[c]) for r in b) or 1.0
        diff = max(abs(x[c] - y[c]) for x, y in zip(a, b)) / scale
        check(diff <= tol, f"{name}: {c}: relative difference {diff:.1e} <= {tol:.1e}")

# The whole model's lagged preconditioner is refreshed when the constrained
# dofs change (tube top free in the thermal step, held in the push): no cut.
out = out_dir("condensation_arc_length_top_free_lagged")
run(adhesion, out, sets=cases["arc_length_top_free"][1] + ["solver.condensation=off", "output.plot=false"])
check(summary(out)["cuts"] == 0, f"whole model, lagged, top free: {summary(out)['cuts']} cuts")

# Where it cannot work: a clear error for "on", the whole model for "auto".
out = out_dir("condensation_refused")
p = run(adhesion, out, sets=["solver.condensation=on"], extra=["-pc_type", "gamg"], check=False)
check(p.returncode == 2 and "solver.condensation" in p.stderr and "gamg" in p.stderr,
      f"on with -pc_type gamg: exit {p.returncode}, {p.stderr.strip()}")
out = out_dir("condensation_auto_gamg")
run(adhesion, out, sets=["loading.steps=2", "loading.push_displacement=0.01"],
    extra=["-pc_type", "gamg", "-ksp_type", "gmres", "-ksp_rtol", "1e-10"])
check(summary(out)["condensed_dofs"] == 0, "auto with -pc_type gamg: Newton on the whole model")

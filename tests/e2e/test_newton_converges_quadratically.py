"""Newton converges quadratically on a friction + exponential softening
push-out (the consistent tangent is right in the assembled system, not only
at the material point): in the step with the longest residual history, each
residual above the round-off floor is below C r^2 of the previous one, i.e.
the observed order log(r2/r1)/log(r1/r0) of the last contraction is >= 1.8.
Checked for both linear solvers (exact LU, and GMRES with the lagged LU), on
the whole model and on the condensed interface system."""
import math
import re

from common import COARSE_MESH, EXP_SOFT, FRICTION_2, check, out_dir, run

scene = COARSE_MESH + FRICTION_2 + EXP_SOFT + """
[loading]
temperature_change = -25.0
push_displacement = 0.03
steps = 6
"""
for pc, condensation in (("jacobian", "off"), ("lagged", "off"), ("jacobian", "on"), ("lagged", "on")):
    name = f"{pc}, condensation {condensation}"
    out = out_dir(f"quadratic_{pc}_{condensation}")
    p = run(scene, out, sets=[f"solver.preconditioner={pc}", f"solver.condensation={condensation}"],
            extra=["-snes_monitor"])
    histories, current = [], []
    for line in p.stdout.splitlines():
        m = re.match(r"\s*(\d+) SNES Function norm ([0-9.eE+-]+)", line)
        if m:
            if int(m.group(1)) == 0 and current:
                histories.append(current)
                current = []
            current.append(float(m.group(2)))
    histories.append(current)
    floor = 1e-6  # N: 1e-9 of the forces (~1e3 N); round-off pollutes what is below
    best = None
    for h in histories:
        r = [x for x in h if x > floor]
        if len(r) >= 3 and (best is None or len(r) > len(best)):
            best = r
    check(best is not None, f"{name}: a step with at least 3 residuals above the floor")

    order = math.log(best[-1] / best[-2]) / math.log(best[-2] / best[-3])
    history = ", ".join(f"{x:.2e}" for x in best)
    check(order >= 1.8, f"{name}: residual history [{history}] N, observed order {order:.2f} >= 1.8")

"""Correctness guard for the lagged preconditioner: the default (GMRES with a
lagged LU) and the plain Newton (LU of every Jacobian) give the same curve to
1e-6 relative on a friction + adhesion push-out through the peak."""
from common import COARSE_MESH, EXP_SOFT, FRICTION_2, check, curve, out_dir, run, summary

scene = COARSE_MESH + FRICTION_2 + EXP_SOFT + """
[loading]
temperature_change = -25.0
push_displacement = 0.05
steps = 10
"""
lag, lu = out_dir("solver_lagged"), out_dir("solver_jacobian")
run(scene, lag, sets=["solver.preconditioner=lagged"])
run(scene, lu, sets=["solver.preconditioner=jacobian"])
a, b = curve(lag), curve(lu)
scale = max(abs(r["P_N"]) for r in b)
diff = max(abs(x["P_N"] - y["P_N"]) for x, y in zip(a, b))
check(len(a) == len(b) == 11, "both converged through 10 steps")
check(diff <= 1e-6 * scale, f"max |P_lagged - P_jacobian| = {diff:.2e} N <= 1e-6 x {scale:.0f} N")
check(summary(lag)["factorizations"] < summary(lu)["factorizations"],
      f"lagged factorised {summary(lag)['factorizations']} times, plain Newton {summary(lu)['factorizations']}")

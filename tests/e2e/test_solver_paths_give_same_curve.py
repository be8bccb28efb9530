"""Correctness guard for the solvers that reuse work: GMRES with a lagged LU
(the default), Newton on the interface jumps after condensing the bulk
(solver.condensation), and both together, in single-precision GMRES
(solver.precision = mixed, the default; on the whole model, the sparse LU
in single precision) or in double, and with a step's first
iteration on the step's own tangent (solver.first_tangent = current) give the
plain full-Newton curve (LU of every whole-model Jacobian) to the bound of
Newton's tolerance on the two runs (common.newton_bound) on a friction +
adhesion push-out through the peak; mixed and double
precision agree to the bound of Newton's tolerance on the two runs
(common.newton_bound: single precision changes the iterates, and each run
is exact only to Newton's tolerance). A stiff stick-slip push (k = 1e6 N/mm^3, mu = 1,
nodal quadrature, 1000 steps) needs no cut: a step that fails from the last
converged tangent is retried from the current one. Implicit cracks in the
concrete (the LU of every Jacobian, GMRES on it) factor in single precision
too, and their corrosion curve is the double-precision one to the bound of
Newton's tolerance, with the same cracked points. GMRES stopped at what
Newton's test needs (solver.inexact_newton, the default) gives the curve of
every solve to -ksp_rtol, to the bound of Newton's tolerance, in fewer
GMRES iterations: on the lagged whole model (its LU in single precision
and in double, on one process and on two) and with IMPL-EX cracks. On two
processes the whole model's LU is in single precision too, and its curve
the one-process double-precision one to the bound of Newton's tolerance. Where
a step starts from a prediction (cracking concrete), Newton's relative
test of the step's own residual gives the curve of the test of the
prediction's, to the same bound, and lets Newton stop where the
prediction's own test would not."""
import os
import re

from common import (COARSE_MESH, EXP_SOFT, FRICTION_2, SNES_RTOL, THROUGH_PEAK, TIGHT_NEWTON,
                    check, corrosion, cracking_corroded_demo, curve, newton_bound, out_dir, run,
                    solved_unknowns, summary)

scene = COARSE_MESH + FRICTION_2 + EXP_SOFT + THROUGH_PEAK
plain = out_dir("solver_plain")
run(scene, plain, sets=["solver.preconditioner=jacobian", "solver.condensation=off"])
ref = curve(plain)
check(len(ref) == 11, "plain Newton converged through 10 steps")
scale = max(abs(r["P_N"]) for r in ref)
outs = {}
for name, sets in (("lagged", ["solver.condensation=off"]),
                   ("lagged double", ["solver.condensation=off", "solver.precision=double"]),
                   ("condensed", ["solver.preconditioner=jacobian", "solver.condensation=on"]),
                   ("condensed lagged (default)", []),
                   ("condensed lagged double", ["solver.precision=double"]),
                   ("condensed lagged current tangent", ["solver.first_tangent=current"])):
    out = out_dir("solver_" + name.replace(" (default)", "").replace(" ", "_"))
    # -ksp_view: which preconditioner the whole model's GMRES had.
    p = run(scene, out, sets=sets, extra=["-ksp_view"] if "condensed" not in name else [])
    if "condensed" not in name:
        single = "sparse LU in single precision" in p.stdout
        check(single == ("double" not in name),
              f"{name}: the whole model's LU {'in single' if single else 'in double'} precision")
    a = curve(out)
    check(len(a) == 11, f"{name}: converged through 10 steps")
    bound = newton_bound(len(ref), max(solved_unknowns(summary(out)), solved_unknowns(summary(plain))))
    # Newton's test bounds the forces; the slip's error is the residual over
    # the softening joints' tangent, which it does not bound: 1e-6 there.
    for key, tol in (("P_N", bound), ("p_MPa", bound), ("slip_mm", max(bound, 1e-6))):
        s = max(abs(r[key]) for r in ref)
        diff = max(abs(x[key] - y[key]) for x, y in zip(a, ref))
        check(diff <= tol * s, f"{name}: max |{key} - plain| = {diff:.2e} <= {tol:.1e} x {s:.4g}")
    condensed = summary(out)["condensed_dofs"]
    check((condensed > 0) == ("condensed" in name), f"{name}: condensed_dofs = {condensed}")
    if name == "lagged":
        check(summary(out)["factorizations"] < summary(plain)["factorizations"],
              f"lagged factorised {summary(out)['factorizations']} times, plain Newton "
              f"{summary(plain)['factorizations']}")
    outs[name] = out

# Single precision (the condensed systems' LU and C, or the whole model's
# sparse LU) changes the iterates, not the solution.
for m, d in (("condensed lagged (default)", "condensed lagged double"), ("lagged", "lagged double")):
    mixed, double = curve(outs[m]), curve(outs[d])
    tol = newton_bound(len(double), max(solved_unknowns(summary(outs[k])) for k in (m, d)))
    for key in ("P_N", "p_MPa", "slip_mm"):
        s = max(abs(r[key]) for r in double)
        diff = max(abs(x[key] - y[key]) for x, y in zip(mixed, double))
        check(diff <= tol * s, f"{m}: mixed against double precision: max |{key}| difference "
              f"{diff:.2e} <= {tol:.1e} x {s:.4g}")

# Stiff stick-slip (k = 1e6 N/mm^3 both layers, mu = 1, nodal quadrature,
# 1000 steps: bench/stress_matrix.py's hardest friction case). A step whose
# first iteration on the last converged tangent fails is tried again from
# the current tangent before it is cut: no cut (78 without the retry), and
# the curve of solver.first_tangent = current to Newton's tolerance.
stiff = COARSE_MESH + """interface_quadrature = "nodal"
[[interface]]
law = "friction"
k = 1000000.0
mu = 1.0
[[interface]]
law = "exponential_softening"
k = 1000000.0
f_t = 3.0
c = 25.0
f_fr = 0.0
[loading]
temperature_change = -25.0
push_displacement = 0.1
steps = 1000
"""
conv, curr = out_dir("solver_stiff_converged"), out_dir("solver_stiff_current")
run(stiff, conv)
run(stiff, curr, sets=["solver.first_tangent=current"])
sc, su = summary(conv), summary(curr)
check(sc["cuts"] == 0 and sc["newton_iterations"] < su["newton_iterations"],
      f"stiff stick-slip: no cut, {sc['newton_iterations']} Newton iterations "
      f"(current tangent: {su['newton_iterations']}, {su['cuts']} cuts)")
a, b = curve(conv), curve(curr)
s = max(abs(r["P_N"]) for r in b)
diff = max(abs(x["P_N"] - y["P_N"]) for x, y in zip(a, b))
tol = newton_bound(len(b), max(solved_unknowns(sc), solved_unknowns(su)))
check(len(a) == len(b) == 1001 and diff <= tol * s,
      f"stiff stick-slip: converged against current tangent: max |P difference| {diff:.2e} <= {tol:.1e} x {s:.4g}")

# Implicit cracks: the LU of every Jacobian, in single precision (mixed)
# or in double, under GMRES.
cracks = cracking_corroded_demo(0.012, 6, seed=2)
rows = {}
for precision in ("mixed", "double"):
    out = out_dir("solver_cracks_" + precision)
    p = run(cracks, out, sets=[f"solver.precision={precision}", "cracking.integration=implicit"],
            extra=["-ksp_view"])
    single = "sparse LU in single precision" in p.stdout
    check(single == (precision == "mixed"),
          f"implicit cracks, {precision}: the LU {'in single' if single else 'in double'} precision")
    rows[precision] = corrosion(out)
mixed, double = rows["mixed"], rows["double"]
tol = newton_bound(len(double), summary(out)["dofs"])
s = max(abs(r["p_MPa"]) for r in double)
diff = max(abs(x["p_MPa"] - y["p_MPa"]) for x, y in zip(mixed, double))
check(len(mixed) == len(double) and diff <= tol * s and double[-1]["cracked_points"] > 0 and
      all(x["cracked_points"] == y["cracked_points"] for x, y in zip(mixed, double)),
      f"implicit cracks: mixed against double precision: max |p difference| {diff:.2e} <= "
      f"{tol:.1e} x {s:.4g} MPa, the same cracked points ({int(double[-1]['cracked_points'])} "
      f"at the end)")

# Inexact Newton (solver.inexact_newton, the default): from a step's second
# iteration on, GMRES on the lagged LU stops at half the residual Newton's
# test still asks for. Each run's curve is exact to Newton's tolerance only,
# so the two agree to newton_bound; the default must take fewer GMRES
# iterations (summary.json linear_iterations), or the option did nothing.
def inexact_against_exact(name, scene, out, sets, key, table, rtol, extra=(), mpirun=None):
    exact = out_dir(os.path.basename(out) + "_exact")
    run(scene, exact, sets=sets + ["solver.inexact_newton=false"], extra=list(extra),
        mpirun=mpirun)
    a, b = table(out), table(exact)
    tol = newton_bound(len(b), solved_unknowns(summary(exact)), rtol)
    s = max(abs(r[key]) for r in b)
    diff = max(abs(x[key] - y[key]) for x, y in zip(a, b))
    fewer, all_its = summary(out)["linear_iterations"], summary(exact)["linear_iterations"]
    check(len(a) == len(b) and diff <= tol * s and 0 < fewer < all_its and
          summary(out)["cuts"] == summary(exact)["cuts"],
          f"{name}: inexact against exact linear solves: max |{key} difference| {diff:.2e} <= "
          f"{tol:.1e} x {s:.4g}; {fewer} GMRES iterations against {all_its}")


inexact_against_exact("lagged whole model", scene, outs["lagged"], ["solver.condensation=off"],
                      "P_N", curve, SNES_RTOL)
inexact_against_exact("condensed lagged", scene, outs["condensed lagged (default)"], [], "P_N",
                      curve, SNES_RTOL)
# GMRES on the LU in double (solver.precision = "double") is
# right-preconditioned by default, so that it measures the true residual
# and stops early too (left, its norm would be the preconditioned
# residual's, and every solve would go to -ksp_rtol).
inexact_against_exact("lagged whole model, LU in double", scene, outs["lagged double"],
                      ["solver.condensation=off", "solver.precision=double"], "P_N", curve,
                      SNES_RTOL)
# Two processes: the whole model's LU in single precision too (MUMPS given
# each process's rows, the right-hand side gathered on the first), its curve
# the double-precision one's to the bound of Newton's tolerance, as on one
# process; inexact Newton fewer GMRES iterations there, and with the LU in
# double on two processes.
two = out_dir("solver_lagged_two_processes")
p = run(scene, two, sets=["solver.condensation=off"], mpirun=2, extra=["-ksp_view"])
check("sparse LU in single precision" in p.stdout,
      "two processes: the whole model's LU in single precision")
mixed, double = curve(two), curve(outs["lagged double"])
tol = newton_bound(len(double), max(solved_unknowns(summary(d)) for d in (two, outs["lagged double"])))
for key in ("P_N", "p_MPa", "slip_mm"):
    s = max(abs(r[key]) for r in double)
    diff = max(abs(x[key] - y[key]) for x, y in zip(mixed, double))
    check(len(mixed) == len(double) and diff <= tol * s,
          f"two processes, single-precision LU: against one process in double: max |{key}| "
          f"difference {diff:.2e} <= {tol:.1e} x {s:.4g}")
inexact_against_exact("lagged whole model on two processes", scene, two,
                      ["solver.condensation=off"], "P_N", curve, SNES_RTOL, mpirun=2)
two_double = out_dir("solver_lagged_double_two_processes")
p = run(scene, two_double, sets=["solver.condensation=off", "solver.precision=double"], mpirun=2,
        extra=["-ksp_view"])
check("sparse LU in single precision" not in p.stdout,
      "two processes, solver.precision = double: the whole model's LU in double")
inexact_against_exact("lagged whole model, LU in double, on two processes", scene, two_double,
                      ["solver.condensation=off", "solver.precision=double"], "P_N", curve,
                      SNES_RTOL, mpirun=2)
# IMPL-EX at Newton's tight tolerance: at its own (IMPLEX_RTOL) a point
# whose stress is within the tolerance of its strength may crack in one run
# and not the other, and a step be cut in one only (common.TIGHT_NEWTON).
# -snes_monitor and -snes_converged_reason: for the test of the reference
# below.
MONITOR = ["-snes_monitor", "-snes_converged_reason"]
implex = out_dir("solver_implex")
p_implex = run(cracks, implex, extra=TIGHT_NEWTON + MONITOR)
check(summary(implex)["cracking_integration"] == "implex", "the cracks run IMPL-EX by default")
inexact_against_exact("IMPL-EX cracks", cracks, implex, [], "p_MPa", corrosion, SNES_RTOL,
                      TIGHT_NEWTON)

# Newton's relative test of the step's own residual (LoadStepSolver::solve):
# a corrosion step starts from a prediction (the last increment
# extrapolated), and -snes_rtol is of the residual the step's loads make at
# the committed state, not of the prediction's own, which is smaller.
# Against the test of the prediction's residual (a test hook): the curve to
# newton_bound and the same cuts; and Newton's own record (-snes_monitor,
# -snes_converged_reason) shows the reference reaching it: a solve that
# converged by the relative test with ||F|| above -snes_rtol x ||F_0|| (F_0
# the prediction's residual) is one that only the reference lets stop
# (NewtonSolver::convergence_test). The hook's run can have none (PETSc's
# own test is ||F|| <= rtol ||F_0||); the default's has one in most predicted
# steps (24 of 64 solves here). Counts of iterations are not compared: they
# differ by about 1 % (713 against 723 GMRES iterations), which another
# machine's rounding of the single-precision LU could tie.


def stopped_by_reference(stdout):
    """The solves in a run's -snes_monitor / -snes_converged_reason output
    that converged by the relative test with ||F|| > SNES_RTOL ||F_0||, and
    the number of solves."""
    norms, above, solves = [], 0, 0
    for line in stdout.splitlines():
        m = re.match(r"\s*(\d+) SNES Function norm (\S+)", line)
        if m:
            norms = [] if m.group(1) == "0" else norms
            norms.append(float(m.group(2)))
        elif "Nonlinear solve" in line:
            solves += 1
            # 1e-9: the monitor prints 13 digits
            above += ("CONVERGED_FNORM_RELATIVE" in line and
                      norms[-1] > SNES_RTOL * norms[0] * (1 + 1e-9))
    return above, solves


referred, p_referred = implex, p_implex
os.environ["PUSHOUT_TEST_NO_PREDICTION_REFERENCE"] = "1"
try:
    unreferred = out_dir("solver_implex_no_reference")
    p_unreferred = run(cracks, unreferred, extra=TIGHT_NEWTON + MONITOR)
finally:
    del os.environ["PUSHOUT_TEST_NO_PREDICTION_REFERENCE"]
a, b = corrosion(referred), corrosion(unreferred)
tol = newton_bound(len(b), solved_unknowns(summary(unreferred)), SNES_RTOL)
s = max(abs(r["p_MPa"]) for r in b)
diff = max(abs(x["p_MPa"] - y["p_MPa"]) for x, y in zip(a, b))
check(len(a) == len(b) and diff <= tol * s and summary(referred)["cuts"] == summary(unreferred)["cuts"],
      f"IMPL-EX cracks: Newton's test of the step's residual against the prediction's: max |p "
      f"difference| {diff:.2e} <= {tol:.1e} x {s:.4g} MPa, the same cuts")
(by_reference, solves), (without, solves_without) = (stopped_by_reference(p.stdout)
                                                     for p in (p_referred, p_unreferred))
check(solves > 0 and by_reference > 0 and solves_without > 0 and without == 0,
      f"IMPL-EX cracks: {by_reference} of {solves} solves stopped above -snes_rtol x ||F_0|| by "
      f"the step's own residual; {without} of {solves_without} without it")

# solver.time_linear_solve (a factorisation and a solve at the first step's
# load before the run) leaves the curve as it is: with no thermal step (dT =
# 0) step 0's row and commit are the unloaded start's, all zeros (they were
# the timing's evaluation: P 1244 N in row 0 of this scene); the
# steps after it differ by Newton's tolerance at most (the lagged LU may be
# the timing's Jacobian's).
untimed, timed = out_dir("solver_untimed"), out_dir("solver_timed")
no_dT = ["loading.temperature_change=0"]
run(scene, untimed, sets=no_dT)
run(scene, timed, sets=no_dT + ["solver.time_linear_solve=true"])
a, b = curve(untimed), curve(timed)
tol = newton_bound(len(b), solved_unknowns(summary(timed)))
s = max(abs(r["P_N"]) for r in a)
diff = max(abs(x["P_N"] - y["P_N"]) for x, y in zip(a, b))
check(summary(timed)["linear_solve_s"] > 0 and len(a) == len(b)
      and all(b[0][k] == 0 for k in ("P_N", "tau_MPa", "p_MPa", "slip_mm", "t_s1_max_MPa"))
      and diff <= tol * s,
      f"solver.time_linear_solve: row 0 {b[0]['P_N']} N, max |P difference| {diff:.2e} <= "
      f"{tol:.1e} x {s:.4g} N")

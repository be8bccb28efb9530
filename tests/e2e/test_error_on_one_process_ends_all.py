"""Errors that reach everyone: an error found on one process of
an `mpirun -n 2` run ends the whole run within seconds, non-zero, with one
message on stderr (rank 0's, or the failing process's own when the other
waits in a collective it skipped), never a hang. The failures on one
process come from a run folder whose scene.toml cannot be written (the
first process writes it) and from test hooks (PUSHOUT_TEST_FAIL_RANK,
PUSHOUT_TEST_FAIL_AT: stepping/TestHooks.h), during the set-up and during the
load steps. A PETSc error (a solver type that does not exist) is one clear
message too, without PETSc's traceback, on 1 and 2 processes. A process that waited in a
collective is ended by mpirun's SIGTERM, but summary.json says the error,
whichever process failed. mpirun adds
its own notice that a process ended non-zero; only pushout's lines count.
A folder where the fields' XML or curve.csv goes is one agreed error that
names the cause."""
import json
import os
import signal
import subprocess
import sys
import time

from common import COARSE_MESH, EXP_SOFT, FRICTION_2, OUT_ROOT, check, curve, mpi_env, mpirun, out_dir

PUSHOUT = sys.argv[1]
MPIRUN = mpirun()
scene = os.path.join(OUT_ROOT, "mpi_errors.toml")
os.makedirs(OUT_ROOT, exist_ok=True)
with open(scene, "w") as f:
    f.write(COARSE_MESH + FRICTION_2 + EXP_SOFT +
            "[loading]\ntemperature_change = -25.0\npush_displacement = 0.05\nsteps = 5\n")


# A failed process waits at most abandon_after_s (10 s, common/mpi_errors.h)
# for the others to agree, then ends the run: a run that ends, its set-up
# included, within three times that has not hung.
ENDS_WITHIN_S = 30


def run(name, processes, extra=(), env=None, prepare=None):
    """Runs the scene (`prepare(out)` first, if given); returns (exit code,
    stderr, wall time [s]); a run still going after 60 s is killed (with its
    processes) and fails."""
    out = out_dir("mpi_errors_" + name)
    if prepare:
        prepare(out)
    cmd = [PUSHOUT, "run", scene, "--out", out, "--quiet", "--set", "output.plot=false", *extra]
    if processes > 1:
        cmd = [MPIRUN, "--allow-run-as-root", "--oversubscribe", "-n", str(processes)] + cmd
    t0 = time.time()
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         start_new_session=True,
                         env=dict(mpi_env(processes), **(env or {})))
    try:
        _, err = p.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        p.communicate()
        check(False, f"{name}: still running after 60 s (a process waits for one that failed)")
    return p.returncode, err, time.time() - t0, out


def one_message(name, err, words):
    # (a process that waited in a collective is ended by mpirun's SIGTERM
    # after the failing one's MPI_Abort, and says nothing of it: the error
    # is the failing one's line)
    ours = [line for line in err.splitlines() if line.startswith("pushout:")]
    check(len(ours) == 1, f"{name}: one message from pushout: {ours}")
    check(all(w in ours[0] for w in words), f"{name}: it says {words}: {ours[0]!r}")
    check("PETSC ERROR" not in err, f"{name}: no PETSc traceback")


for rank, at, words in ((1, "setup", ["error:", "test failure on process 1 at setup"]),
                        (1, "step", ["error:", "test failure on process 1 at step"]),
                        (1, "collective", ["error:", "test failure on process 1 at collective",
                                           "did not come to agree"]),
                        (0, "collective", ["error:", "test failure on process 0 at collective",
                                           "did not come to agree"]),
                        (1, "setup_collective", ["error:",
                                                 "test failure on process 1 at setup_collective",
                                                 "did not come to agree"])):
    name = f"fail_{at}_{rank}"
    rc, err, wall, out = run(name, 2, env={"PUSHOUT_TEST_FAIL_RANK": str(rank),
                                           "PUSHOUT_TEST_FAIL_AT": at})
    check(rc != 0, f"{name}: exit {rc} (non-zero)")
    check(wall < ENDS_WITHIN_S, f"{name}: ended {wall:.1f} s after the start")
    one_message(name, err, words)
    if at == "step":  # the load steps before the failure stay in curve.csv
        check(len(curve(out)) == 3, f"{name}: curve.csv keeps step 0 and the 2 load steps")
        # summary.json, written for the error, has the solver's counts and
        # time so far (zeros before: they were added at the steps' end only).
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        check(summary["factorizations"] > 0 and summary["linear_iterations"] > 0
              and summary["time_s"]["solve"] > 0,
              f"{name}: summary.json has the solver's counts so far: "
              f"{summary['factorizations']} factorisations, {summary['linear_iterations']} "
              f"linear iterations, {summary['time_s']['solve']:.3f} s")
    if at.endswith("collective"):
        # summary.json says the error, not the SIGTERM that mpirun sends the
        # waiting process once the failing one ends the run: written by the
        # failing process itself (rank 0) or by rank 0 from what the failing
        # one left it (rank 1; RunReport::abandoned), which is then gone.
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        said = summary.get("message", "")
        check(all(w in said for w in words[1:]), f"{name}: summary.json says the error: {said!r}")
        check(summary.get("interrupted") is False and summary.get("converged") is False,
              f"{name}: summary.json: not interrupted, not converged: {summary.get('interrupted')}, "
              f"{summary.get('converged')}")
        steps = 0 if at.startswith("setup") else 2
        check(summary.get("steps") == steps, f"{name}: summary.json keeps the {steps} load steps")
        check(not os.path.exists(os.path.join(out, ".process-error")),
              f"{name}: the hand-over of the error is removed")

# A file that only the first process writes, and cannot (scene.toml is a
# folder there): the others must not go on into the run's collectives.
name = "scene_toml_unwritable"
rc, err, wall, _ = run(name, 2, prepare=lambda out: os.makedirs(os.path.join(out, "scene.toml")))
check(rc != 0, f"{name}: exit {rc} (non-zero)")
check(wall < ENDS_WITHIN_S, f"{name}: ended {wall:.1f} s after the start")
one_message(name, err, ["error:", "cannot write", "scene.toml", "Is a directory"])
check("did not come to agree" not in err, f"{name}: the processes agreed on it")

# A folder where an output goes: the fields' XML (dolfinx writes it on the
# first process and does not check it: the run ended with exit 0 and no
# fields.xdmf) and curve.csv (said to be a full disk) name the cause.
for name, blocked, extra in (("fields_xdmf_folder", "fields.xdmf", ["--set", "output.xdmf=true"]),
                             ("curve_csv_folder", "curve.csv", [])):
    rc, err, wall, _ = run(name, 2, extra=extra,
                           prepare=lambda out, f=blocked: os.makedirs(os.path.join(out, f, "x")))
    check(rc == 1, f"{name}: exit {rc} (1)")
    one_message(name, err, ["error:", "cannot write", blocked, "Is a directory"])
    check("did not come to agree" not in err, f"{name}: the processes agreed on it")

bad_solver = ["-pc_type", "lu", "-pc_factor_mat_solver_type", "nonexistent"]
for processes, sets in ((1, ["--set", "solver.condensation=off"]), (2, [])):
    name = f"petsc_error_{processes}"
    rc, err, wall, _ = run(name, processes, extra=sets + bad_solver)
    check(0 < rc < 128, f"{name}: exit {rc} (non-zero, no signal)")
    check(wall < ENDS_WITHIN_S, f"{name}: ended {wall:.1f} s after the start")
    one_message(name, err, ["error: PETSc:", "SNESSolve", "nonexistent"])
    if processes == 1:
        check(len(err.strip().splitlines()) == 1, f"{name}: nothing else on stderr: {err!r}")

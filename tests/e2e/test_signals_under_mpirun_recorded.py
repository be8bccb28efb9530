"""Stopping a run under mpirun the ways users do: Ctrl-C (SIGINT to the
whole process group), `kill -TERM <mpirun pid>` (mpirun sends SIGTERM to
every process, then SIGKILL odls_base_sigkill_timeout later, 1 s) and
SIGTERM to every process (Slurm's scancel). Every way, summary.json says
interrupted, by which signal, in the load steps, and curve.csv keeps whole
rows, at least as many as summary.json counts. The exit code is mpirun's
own (docs/running.md, "Under mpirun"). After Ctrl-C or a SIGTERM to mpirun,
its SIGKILL comes a second after its SIGTERM: summary.json, naming the
phase, must be written before it, with the solver's counts so far."""
import json
import os
import signal
import subprocess
import sys
import time

from common import COARSE_MESH, FRICTION_2, check, mpirun, out_dir

PUSHOUT = sys.argv[1]
mpirun()
ROOT = out_dir("mpi_signals")
os.makedirs(ROOT)
scene = os.path.join(ROOT, "scene.toml")
with open(scene, "w") as f:
    f.write(COARSE_MESH + FRICTION_2 + "[loading]\ntemperature_change = -25.0\n"
            "push_displacement = 0.01\nsteps = 100000\n")


def ranks(mpirun_pid):
    """The pids of the pushout processes mpirun started."""
    p = subprocess.run(["ps", "-o", "pid=,comm=", "--ppid", str(mpirun_pid)], capture_output=True,
                       text=True)
    return [int(l.split()[0]) for l in p.stdout.splitlines() if "pushout" in l]


def stop(name, how, mca=(), env=None):
    out = os.path.join(ROOT, name)
    p = subprocess.Popen(["mpirun", "--allow-run-as-root", "--oversubscribe", "-n", "2"] + list(mca)
                         + [PUSHOUT, "run", scene, "--out", out, "--quiet"], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True, start_new_session=True,
                         env=dict(os.environ, **(env or {})))
    csv = os.path.join(out, "curve.csv")
    deadline = time.time() + 180
    while time.time() < deadline and (not os.path.exists(csv) or len(open(csv).readlines()) < 4):
        time.sleep(0.1)
    check(p.poll() is None, f"{name}: running")
    sig = how(p)
    try:
        _, err = p.communicate(timeout=120)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        raise SystemExit(f"FAILED: {name}: still running 120 s after the signal")
    print(f"{name}: mpirun exit {p.returncode}; stderr {err.strip()[-300:]!r}")
    path = os.path.join(out, "summary.json")
    check(os.path.exists(path), f"{name}: summary.json written")
    s = json.load(open(path))
    check(s["interrupted"] and not s["converged"] and s["signal"] in sig
          and s["stopped_in"] == "load steps",
          f"{name}: summary.json says interrupted by {s['signal']} in {s['stopped_in']!r}: "
          f"{s['message']!r}")
    rows = open(csv).read().splitlines()
    check(all(len(r.split(",")) == len(rows[0].split(",")) for r in rows) and len(rows) >= s["steps"] + 1,
          f"{name}: curve.csv has {len(rows) - 1} whole rows ({s['steps']} steps in summary.json)")
    return s


def ctrl_c(p):
    os.killpg(p.pid, signal.SIGINT)
    return (signal.SIGINT, signal.SIGTERM)


def term_mpirun(p):
    p.send_signal(signal.SIGTERM)
    return (signal.SIGTERM,)


def term_every_process(p):
    pids = ranks(p.pid)
    check(len(pids) == 2, f"two processes: {pids}")
    for pid in pids:
        os.kill(pid, signal.SIGTERM)
    return (signal.SIGTERM,)


stop("ctrl_c", ctrl_c)
stop("term_mpirun", term_mpirun)
stop("term_every_process", term_every_process)

# Load steps that do not look at signals for 2 s (a test hook standing for
# a long factorisation): mpirun's SIGKILL comes 1 s after its SIGTERM, so
# the processes end where they are after 0.5 s, summary.json written first.
# With more time from mpirun (odls_base_sigkill_timeout 4: the SIGTERM 4 s
# after mpirun's, the SIGKILL 4 s later) the run stops after the step, by
# itself.
slow = {"PUSHOUT_TEST_SLOW_STEP_S": "2"}
s = stop("slow_step", term_mpirun, env=slow)
check("during load steps" in s["message"], f"slow_step: ended where it was: {s['message']!r}")
# Its summary.json (published at the last committed step) has the solver's
# counts and time so far, not the zeros the run's end would have filled in.
check(s["factorizations"] > 0 and s["linear_iterations"] > 0 and s["time_s"]["solve"] > 0,
      f"slow_step: the solver's counts so far: {s['factorizations']} factorisations, "
      f"{s['linear_iterations']} linear iterations, {s['time_s']['solve']:.3f} s")
s = stop("slow_step_sigkill_4", term_mpirun, ["--mca", "odls_base_sigkill_timeout", "4"], slow)
check("during" not in s["message"], f"slow_step_sigkill_4: stopped by itself: {s['message']!r}")

# A sweep of two groups of one process, SIGTERM to one process alone: its
# group stops, and the other takes no new case after the one it runs (it ran
# every case left). Eight cases, each 2.1 s at least (a test hook: 0.3 s a
# step from the third); the signal once both groups run their first.
out = os.path.join(ROOT, "sweep_one_process")
p = subprocess.Popen(["mpirun", "--allow-run-as-root", "--oversubscribe", "-n", "2", PUSHOUT, "sweep", scene,
                      "--out", out, "--quiet", "--set", "loading.steps=8", "--vary",
                      "interface.0.mu=" + ",".join(str(0.1 * i) for i in range(1, 9))],
                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True,
                     env=dict(os.environ, PUSHOUT_TEST_SLOW_STEP_S="0.3"))
firsts = [os.path.join(out, f"case_00{i}", "curve.csv") for i in (0, 1)]
deadline = time.time() + 180
while time.time() < deadline and not all(os.path.exists(c) and len(open(c).readlines()) >= 3 for c in firsts):
    time.sleep(0.05)
pids = ranks(p.pid)
check(len(pids) == 2 and p.poll() is None, f"sweep: two processes running: {pids}")
os.kill(pids[1], signal.SIGTERM)
try:
    _, err = p.communicate(timeout=120)
except subprocess.TimeoutExpired:
    os.killpg(p.pid, signal.SIGKILL)
    raise SystemExit("FAILED: sweep: still running 120 s after the signal")
ran = [d for d in os.listdir(out) if d.startswith("case_")]
check(p.returncode != 0 and len(ran) <= 4,
      f"sweep: SIGTERM to one process stops both groups (mpirun exit {p.returncode}, cases begun {sorted(ran)})")

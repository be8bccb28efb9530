"""An output folder holds one run's outputs: a second run into a folder in
use is refused (exit 2, naming the pid of the one using it); a run removes
what an earlier run of pushout left there (so a stale summary.json cannot
outlive a run killed with SIGKILL, and a smaller sweep leaves no old case
folders), but no file of another name, and nothing from a folder no run of
pushout used; summary.json has a run id of its own;
an input that is one of the outputs (the scene DIR/scene.toml with --out DIR)
is refused (exit 2) and left as it was."""
import json
import os
import signal
import subprocess
import sys
import time

from common import COARSE_MESH, FRICTION_2, check, out_dir

PUSHOUT = sys.argv[1]
ROOT = out_dir("output_folder")
os.makedirs(ROOT)
scene = os.path.join(ROOT, "scene_in.toml")
with open(scene, "w") as f:
    f.write(COARSE_MESH + FRICTION_2 + "[loading]\ntemperature_change = -25.0\n"
            "push_displacement = 0.01\nsteps = 4\n[output]\nplot = false\n")


def run(out, *args, scene=scene):
    return subprocess.run([PUSHOUT, "run", scene, "--out", out, "--quiet"] + list(args),
                          capture_output=True, text=True, timeout=300)


def start_long(out):
    """A run of 100000 steps into out, once it has written a few rows."""
    p = subprocess.Popen([PUSHOUT, "run", scene, "--out", out, "--quiet", "--set",
                          "loading.steps=100000"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         text=True)
    csv = os.path.join(out, "curve.csv")
    deadline = time.time() + 120
    while time.time() < deadline and (not os.path.exists(csv) or len(open(csv).readlines()) < 10):
        time.sleep(0.1)
    check(p.poll() is None, "the long run is running")
    return p


def summary(out):
    return json.load(open(os.path.join(out, "summary.json")))


# A folder in use: a second run is refused (the two would interleave outputs).
out = os.path.join(ROOT, "in_use")
first = start_long(out)
try:
    p = run(out)
    check(p.returncode == 2, f"a second run into the folder: exit {p.returncode} (2)")
    want = f"pushout: error: {out} is in use by another pushout run (pid {first.pid})"
    check(p.stderr.strip() == want, f"says so: {p.stderr.strip()!r}")
finally:
    first.send_signal(signal.SIGTERM)
    first.communicate(timeout=120)
check(first.returncode == 143 and summary(out)["interrupted"], "the first run went on (stopped by SIGTERM)")
p = run(out)
check(p.returncode == 0, f"the folder is free again once it ended: exit {p.returncode}")

# Outputs of an earlier run never survive a later one, even one killed with
# SIGKILL (the earlier summary.json would say converged for it).
out = os.path.join(ROOT, "stale")
p = run(out, "--set", "output.xdmf=true")
check(p.returncode == 0, f"a first run: exit {p.returncode}")
first_id = summary(out)["run_id"]
os.makedirs(os.path.join(out, "case_003"))
with open(os.path.join(out, "case_003", "curve.csv"), "w") as f:
    f.write("step\n")
with open(os.path.join(out, "notes.txt"), "w") as f:
    f.write("the user's own file\n")
with open(os.path.join(out, "sweep.csv"), "w") as f:
    f.write("case\n")
p = start_long(out)
p.send_signal(signal.SIGKILL)
p.communicate(timeout=60)
left = sorted(os.listdir(out))
check("summary.json" not in left, f"no summary.json after the killed run: {left}")
check(not any(f.startswith(("fields.", "interface.", "case_", "sweep.")) for f in left),
      f"the earlier run's fields, case folders and sweep.csv are gone: {left}")
check("notes.txt" in left, "a file pushout did not write is kept")
p = run(out)
check(p.returncode == 0 and summary(out)["run_id"] not in ("", first_id),
      f"each run has its own run id: {first_id} then {summary(out)['run_id']}")

# A folder no run of pushout used (no lock file) keeps its files, whatever
# their names: they are the user's (here a measured fit.csv and a folder
# case_001 of notes), not an earlier run's.
out = os.path.join(ROOT, "users_own")
os.makedirs(os.path.join(out, "case_001"))
for name in ("fit.csv", os.path.join("case_001", "curve.csv")):
    with open(os.path.join(out, name), "w") as f:
        f.write("the user's\n")
p = run(out)
check(p.returncode == 0 and os.path.exists(os.path.join(out, "fit.csv"))
      and os.path.exists(os.path.join(out, "case_001", "curve.csv")),
      f"a folder pushout never used keeps its files: exit {p.returncode}, {sorted(os.listdir(out))}")

# The scene is DIR/scene.toml, which the run into DIR would overwrite.
before = open(os.path.join(out, "scene.toml")).read()
with open(os.path.join(out, "scene.toml"), "a") as f:
    f.write("# the user's edit\n")
p = run(out, scene=os.path.join(out, "scene.toml"))
check(p.returncode == 2 and "would be overwritten" in p.stderr,
      f"a scene among the outputs is refused: exit {p.returncode}, {p.stderr.strip()!r}")
check(open(os.path.join(out, "scene.toml")).read() == before + "# the user's edit\n",
      "the scene is left as it was")

# A smaller sweep into the folder of a larger one: no case folder of the
# larger one stays beside the new sweep.csv.
out = os.path.join(ROOT, "sweep")
cmd = [PUSHOUT, "sweep", scene, "--out", out, "--quiet"]
p = subprocess.run(cmd + ["--vary", "interface.0.mu=0.3,0.4,0.5"], capture_output=True, text=True,
                   timeout=300)
check(p.returncode == 0 and os.path.isdir(os.path.join(out, "case_002")), "a sweep of 3 cases")
p = subprocess.run(cmd + ["--vary", "interface.0.mu=0.3"], capture_output=True, text=True,
                   timeout=300)
cases = sorted(f for f in os.listdir(out) if f.startswith("case_"))
check(p.returncode == 0 and cases == ["case_000"], f"then one of 1 case leaves only its own: {cases}")

# Folders that cannot be used, each said with its reason: a symbolic link to
# nothing (it was "File exists"), a lock that is a folder (no reason given).
dangling = os.path.join(ROOT, "dangling")
os.symlink(os.path.join(ROOT, "nowhere", "x"), dangling)
p = run(dangling)
check(p.returncode == 2 and "symbolic link to nothing" in p.stderr and not os.path.exists(dangling),
      f"--out a symbolic link to nothing: exit {p.returncode}, {p.stderr.strip()!r}")
locked = os.path.join(ROOT, "lock_folder")
os.makedirs(os.path.join(locked, ".pushout.lock"))
p = run(locked)
check(p.returncode == 2 and ".pushout.lock: Is a directory" in p.stderr,
      f"a lock that is a folder: exit {p.returncode}, {p.stderr.strip()!r}")

"""A process that no launcher started (an Open MPI singleton,
common/mpi_start.h):

1. makes no session directory: nothing appears in TMPDIR (an empty folder)
   while a run lasts (every isolated singleton would use the same one, and
   one that ends would remove it under another that starts);
2. runs side by side with others: 3 rounds of 8 runs at once all converge
   (with a shared session directory about one in 24 runs of
   scripts/studies.py on a fresh Debian root fails: "orte_session_dir
   failed");
3. keeps the user's own Open MPI settings: OMPI_MCA_btl=self,vader given
   runs as well."""
import os
import subprocess
import sys
import tempfile
import time

from common import SOURCE, check, out_dir

PUSHOUT = sys.argv[1]
SCENE = os.path.join(SOURCE, "demo", "single_joint_elastic.toml")
FRICTION = os.path.join(SOURCE, "demo", "pushout_friction.toml")  # ~0.5 s


def start(out, env, scene=SCENE):
    return subprocess.Popen([PUSHOUT, "run", scene, "--out", out, "--quiet"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)


def clean_env(**extra):
    """The environment without launcher or Open MPI settings, plus `extra`."""
    env = {k: v for k, v in os.environ.items() if not k.startswith(("OMPI_", "PMIX_", "PMI_"))}
    env.update(extra)
    return env


# 1. No session directory (Open MPI would make it in TMPDIR at MPI_Init and
# remove it at the end: TMPDIR is watched while the run lasts).
with tempfile.TemporaryDirectory() as tmp:
    p = start(out_dir("singleton_tmpdir"), clean_env(TMPDIR=tmp), FRICTION)
    seen = set()
    while p.poll() is None:
        seen.update(os.listdir(tmp))
        time.sleep(0.005)
    err = p.stderr.read()
    check(p.returncode == 0 and not seen,
          f"a singleton run makes nothing in TMPDIR: exit {p.returncode}, {sorted(seen)} {err[-300:]}")

# 2. Side by side.
failed = []
for round_ in range(3):
    runs = [start(out_dir(f"singleton_side_by_side_{round_}_{i}"), clean_env()) for i in range(8)]
    for i, p in enumerate(runs):
        _, err = p.communicate(timeout=300)
        if p.returncode != 0:
            failed.append(f"round {round_} run {i}: exit {p.returncode} {err[-300:]}")
check(not failed, f"24 runs, 8 at a time, all converge {failed[:1]}")

# 3. The user's settings stay.
p = start(out_dir("singleton_user_btl"), clean_env(OMPI_MCA_btl="self,vader"))
_, err = p.communicate(timeout=300)
check(p.returncode == 0, f"OMPI_MCA_btl=self,vader given: exit {p.returncode} {err[-300:]}")

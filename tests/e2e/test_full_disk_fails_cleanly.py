"""A full disk is one clear error, never an abort or a cut file: on a small
tmpfs (mounted here; skipped where mounting is not allowed) a run whose
fields.xdmf fills it, one whose curve.csv does, one with no room for
summary.json and one with no room for scene.toml each exit with code 1 and
one line `pushout: error: cannot write FILE (disk full?)`; curve.csv keeps
every row it has, each whole, and no row for a step the fields had no room
for (its rows are the steps summary.json counts), nor corrosion.csv for a
corrosion step its fields had no room for; summary.json is whole or absent."""
import os
import shutil
import subprocess
import sys
import tempfile

from common import COARSE_MESH, FRICTION_2, check, out_dir

PUSHOUT = sys.argv[1]
if os.geteuid() != 0:
    print("SKIPPED: mounting a tmpfs needs root")
    sys.exit(77)
if not shutil.which("mount"):
    print("SKIPPED: no mount command (scripts/setup.sh installs it)")
    sys.exit(77)
PAGE = 4096  # tmpfs allocates whole pages [B]
ROOT = out_dir("full_disk")
os.makedirs(ROOT)
CACHE = os.path.join(ROOT, "cache")  # the mesh cache is not on the small disk
scene = os.path.join(ROOT, "scene.toml")
with open(scene, "w") as f:
    f.write(COARSE_MESH + FRICTION_2 + "[loading]\ntemperature_change = -25.0\n"
            "push_displacement = 0.01\nsteps = 4\n[output]\nplot = false\n")


def mount(size):
    """A tmpfs of `size` (e.g. "256k"); exits 77 (skip) where mounting is not allowed."""
    d = tempfile.mkdtemp(prefix="pushout-full-disk-")
    p = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs", d],
                       capture_output=True, text=True)
    if p.returncode != 0:
        os.rmdir(d)
        print(f"SKIPPED: cannot mount a tmpfs here: {p.stderr.strip()}")
        sys.exit(77)
    return d


def unmount(d):
    subprocess.run(["umount", d], check=False)
    os.rmdir(d)


def fill(d, leave_pages):
    """Fills the tmpfs at d but `leave_pages` pages."""
    st = os.statvfs(d)
    free = st.f_bavail * st.f_frsize
    with open(os.path.join(d, "filler"), "wb") as f:
        f.write(b"x" * max(free - leave_pages * PAGE, 0))


def pages(path):
    return -(-os.path.getsize(path) // PAGE) if os.path.exists(path) else 0


def run(out, sets=(), mpirun=None):
    cmd = [PUSHOUT, "run", scene, "--out", out, "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    if mpirun:
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-n", str(mpirun)] + cmd
    return subprocess.run(cmd, capture_output=True, text=True, timeout=300,
                          env=dict(os.environ, PUSHOUT_CACHE_DIR=CACHE))


def check_outcome(name, p, out, files, mpirun=False):
    """`files`: the file the error may name (the first that found the disk full)."""
    err = p.stderr.strip()
    check(p.returncode == 1, f"{name}: exit {p.returncode} (1)")
    wanted = [f"pushout: error: cannot write {os.path.join(out, f)} (disk full?)"
              for f in files.split()]
    # (under mpirun, mpirun adds its own lines about the exit code)
    lines = [l for l in err.splitlines() if l.strip() and (not mpirun or "pushout" in l)]
    check(len(lines) == 1 and lines[0] in wanted, f"{name}: one error line {wanted[0]!r}: {err[-600:]!r}")
    csv = os.path.join(out, "curve.csv")
    if os.path.exists(csv):
        text = open(csv).read()
        rows = text.splitlines()
        check(text.endswith("\n") and all(len(r.split(",")) == len(rows[0].split(",")) for r in rows),
              f"{name}: curve.csv has {len(rows) - 1} rows, each whole")
    sj = os.path.join(out, "summary.json")
    if os.path.exists(sj):
        import json
        s = json.load(open(sj))
        check(not s["converged"] and "cannot write" in s["message"],
              f"{name}: summary.json says why: {s['message']!r}")
    else:
        print(f"ok: {name}: no summary.json (no room for it)")
    return lines


# The sizes of a run's files, on a disk with room.
ref = os.path.join(ROOT, "reference")
p = run(ref)
check(p.returncode == 0, f"the reference run: exit {p.returncode} {p.stderr[-300:]!r}")
lock = os.path.join(ref, ".pushout.lock")
base_pages = pages(os.path.join(ref, "scene.toml")) + max(pages(lock), 1)

# No room for summary.json: exit 1, and no summary.json, not an empty one.
d = mount("128k")
try:
    fill(d, base_pages + pages(os.path.join(ref, "curve.csv")))
    out = os.path.join(d, "out")
    p = run(out)
    check_outcome("no room for summary.json", p, out, "summary.json")
    check(not os.path.exists(os.path.join(out, "summary.json")), "no summary.json, not an empty one")
    check(len(open(os.path.join(out, "curve.csv")).read().splitlines()) == 6,
          "curve.csv has every step")
finally:
    unmount(d)

# curve.csv fills the disk: exit 1, and no row cut mid-line.
d = mount("128k")
try:
    fill(d, base_pages + 1)
    out = os.path.join(d, "out")
    p = run(out, ["loading.steps=200"])
    check_outcome("curve.csv fills the disk", p, out, "curve.csv")
finally:
    unmount(d)

# No room for scene.toml.
d = mount("128k")
try:
    fill(d, 0)
    out = os.path.join(d, "out")
    os.makedirs(out)
    p = run(out)
    check_outcome("no room for scene.toml", p, out, "scene.toml")
finally:
    unmount(d)

# No room for the fields' mesh: exit 1, and none of their files is left
# (they hold no step; a fields.h5 cut short was left).
d = mount("128k")
try:
    fill(d, base_pages + 4)
    out = os.path.join(d, "out")
    # A folder no run of pushout used, with a file of the user's named as
    # the crack planes' fields, which this run (no planes) never writes.
    os.makedirs(out)
    with open(os.path.join(out, "cracks.xdmf"), "w") as f:
        f.write("mine\n")
    p = run(out, ["output.xdmf=true"])
    check_outcome("no room for the fields' mesh", p, out, "fields.xdmf")
    left = [f for f in os.listdir(out) if f.split(".")[0] in ("fields", "interface")]
    check(not left, f"no room for the fields' mesh: none of their files left: {left}")
    check(os.path.exists(os.path.join(out, "cracks.xdmf")),
          "no room for the fields' mesh: the user's cracks.xdmf stays (the run has no planes)")
finally:
    unmount(d)

# fields.xdmf fills the disk: one line and exit 1, not HDF5's abort (SIGABRT,
# an HDF5 error stack, no summary.json; under mpirun exit 134 everywhere).
for n in (None, 2):
    name = f"fields.xdmf fills the disk ({n or 1} process{'es' if n else ''})"
    d = mount("512k")
    try:
        out = os.path.join(d, "out")
        p = run(out, ["output.xdmf=true", "loading.steps=100"], mpirun=n)
        check("HDF5" not in p.stderr and "Abort" not in p.stderr, f"{name}: no HDF5 error stack")
        check_outcome(name, p, out, "fields.xdmf", mpirun=bool(n))
        # The step the fields had no room for writes no row either: the rows
        # after step 0 are the steps summary.json counts (where it fitted).
        sj = os.path.join(out, "summary.json")
        if os.path.exists(sj):
            import json
            steps = json.load(open(sj))["steps"]
            rows = len(open(os.path.join(out, "curve.csv")).read().splitlines()) - 1
            check(rows == steps + 1, f"{name}: curve.csv's {rows - 1} rows after step 0 are "
                  f"summary.json's {steps} steps")
    finally:
        unmount(d)

# The corrosion stage's fields fill the disk: its rows after step 0 are the
# corrosion steps summary.json counts (a step its fields had no room for
# wrote a corrosion.csv row all the same).
corroded = os.path.join(ROOT, "corroded.toml")
with open(corroded, "w") as f:
    f.write(COARSE_MESH + '[[interface]]\nlaw = "oxide_friction"\nk = 1000.0\nmu = 0.4\n'
            "[corrosion]\npenetration = 0.02\nsteps = 200\n"
            "[loading]\ntemperature_change = -25.0\npush_displacement = 0.01\nsteps = 4\n"
            "[output]\nplot = false\nxdmf = true\n")
scene = corroded
d = mount("512k")
try:
    out = os.path.join(d, "out")
    name = "corrosion_fields.xdmf fills the disk"
    p = run(out)
    check_outcome(name, p, out, "corrosion_fields.xdmf fields.xdmf")
    # (the fields' writer stops a step before the disk is full, with room
    # to close its files: summary.json fits in it, as in the runs above)
    sj = os.path.join(out, "summary.json")
    check(os.path.exists(sj), f"{name}: summary.json written")
    if os.path.exists(sj):
        import json
        steps = json.load(open(sj))["corrosion_steps"]
        rows = len(open(os.path.join(out, "corrosion.csv")).read().splitlines()) - 1
        check(0 < steps < 200 and rows == steps + 1,
              f"{name}: corrosion.csv's {rows - 1} rows after step 0 are summary.json's "
              f"{steps} corrosion steps")
finally:
    unmount(d)

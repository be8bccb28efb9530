"""No silent wrong result.

1. A cached mesh whose coordinates were changed in place (the file keeps its
   size and header) is not used: the run says so in one line on stderr,
   meshes again (summary: mesh_reused false) and gives the clean run's curve
   (the same binary, process and mesh: bit for bit, wall_s aside). The same
   for a file whose checksum itself was changed.
2. A solve whose solution is not a number (a test hook,
   PUSHOUT_TEST_NONFINITE_FROM: every converged Newton solve from the 3rd on
   leaves a NaN in its solution) is a failed step: cut back, and, when the
   cuts run out, exit 3 with a message that says what was not a number;
   summary.json says not converged, and curve.csv holds only finite rows.
   (The curve writer's own refusal of a non-finite row: tests/unit/record/test_recorder.cpp.)
3. A step of energy under dissipation control that finds an equilibrium
   behind the push's start (the tube pulled back) is no state of the test:
   it is cut, never taken. The corroded demo (coarse) with its crack plane at
   a block corner of the mesh took one to delta = -2.47 mm, P = -5347 N, and
   pushed on from there to an exit 0; now no row lies behind the start.
4. An IMPL-EX step that misses its error tolerance at the smallest step
   loading.max_cuts allows, with nothing that shows the cracks snapping
   back (no smaller try whose error did not fall), stops the run (exit 3)
   and the message names max_cuts; it used to be taken as a "jump" (the
   coarse corroded cracking demo with max_cuts = 0: p after corrosion 12 %
   off, exit 0). Stopped so in the corrosion stage, the run leaves the
   cracks of its last finished step (crack_pattern.csv, summary.json's
   widest surface crack). With the default max_cuts the same scene runs
   through with no jump."""
import glob
import math
import os
import shutil
import struct
import subprocess

from common import (BLOCKS_MESH, OUT_ROOT, PUSHOUT, SOURCE, check, corrosion, curve, out_dir, run,
                    summary)

scene = """
[mesh]
elements_per_quarter = 4
elements_through_thickness = 2
[loading]
steps = 3
"""
cache = os.path.join(OUT_ROOT, "mesh-checksum-test")
shutil.rmtree(cache, ignore_errors=True)
os.environ["PUSHOUT_CACHE_DIR"] = cache
strip = lambda rows: [{k: v for k, v in r.items() if k != "wall_s"} for r in rows]  # noqa: E731

clean = out_dir("checksum_clean")
run(scene, clean)
files = glob.glob(os.path.join(cache, "*.mesh"))
check(len(files) == 1, f"one cached mesh: {files}")
path = files[0]
with open(path, "rb") as f:
    original = f.read()


def damaged(name, change):
    """Runs the scene from a cached mesh changed by change(bytearray)."""
    data = bytearray(original)
    change(data)
    with open(path, "wb") as f:
        f.write(data)
    out = out_dir(f"checksum_{name}")
    p = run(scene, out, check=False)
    notes = [line for line in p.stderr.splitlines() if "meshing again" in line]
    check(p.returncode == 0 and not summary(out)["mesh_reused"] and len(notes) == 1,
          f"{name}: exit {p.returncode}, meshed again, one note: {notes}")
    check(strip(curve(out)) == strip(curve(clean)), f"{name}: the clean run's curve")
    with open(path, "rb") as f:
        check(f.read() == original, f"{name}: the cache holds the mesh again")


def move_nodes(data):
    # The coordinates follow the header line, the hash of the mesher's
    # inputs and the two counts (cpp/mesh/generate.cpp); every 7th value of
    # the first 300 is moved by 1 mm, in place.
    start = data.index(b"\n") + 1 + 8 + 16
    for i in range(0, 300, 7):
        (v,) = struct.unpack_from("<d", data, start + 8 * i)
        struct.pack_into("<d", data, start + 8 * i, v + 1.0)


def flip_checksum(data):
    data[-1] ^= 0xFF


damaged("coordinates", move_nodes)
damaged("checksum", flip_checksum)

# 2. A non-finite solution: cut back, then exit 3, nothing non-finite written.
out = out_dir("nonfinite_solution")
env = dict(os.environ, PUSHOUT_TEST_NONFINITE_FROM="3")
p = subprocess.run([PUSHOUT, "run", os.path.join(OUT_ROOT, "checksum_clean.toml"), "--out", out, "--quiet", "--set", "loading.max_cuts=2"],
                   capture_output=True, text=True, env=env, timeout=600)
lines = [line for line in p.stderr.splitlines() if line.startswith("pushout")]
check(p.returncode == 3 and len(lines) == 1 and "not a number" in lines[0],
      f"a non-finite solution: exit {p.returncode}, {lines[0] if lines else p.stderr[-300:]}")
s = summary(out)
rows = curve(out)
check(not s["converged"] and s["cuts"] >= 1
      and all(math.isfinite(v) for r in rows for v in r.values()),
      f"not converged, {s['cuts']} cuts, {len(rows)} finite rows in curve.csv")

# 3. No step of energy behind the push's start.
corner = out_dir("energy_step_behind_start")
p = run(os.path.join(SOURCE, "demo", "pushout_corroded.toml"), corner, check=False,
        sets=["mesh.elements_per_quarter=4", "mesh.elements_through_thickness=2", "loading.steps=5",
              "crack.0.angle=56.309932", "loading.control=auto"])
rows = curve(corner)
check(p.returncode in (0, 3) and rows and min(r["delta_mm"] for r in rows) >= 0,
      f"dissipation control: exit {p.returncode}, {len(rows)} rows, delta from "
      f"{min(r['delta_mm'] for r in rows) * 1e3:.2f} um (never behind the start)")

# 4. An IMPL-EX miss that only max_cuts stops from being cut is no jump.
# On the mesh where this case misses in the corrosion stage (blocks: with
# radial lines refined whole, 8 / 2 misses in step 0 already, with no
# corrosion row to check below), whatever the demo's [mesh] says.
implex = ["mesh.elements_per_quarter=8", "mesh.elements_through_thickness=2", *BLOCKS_MESH,
          "corrosion.penetration=0.006", "corrosion.steps=2", "loading.push_displacement=0.01",
          "loading.steps=2"]
demo = os.path.join(SOURCE, "demo", "pushout_corroded_cracking.toml")
uncut = out_dir("implex_uncut")
p = run(demo, uncut, check=False, sets=implex + ["loading.max_cuts=0"])
lines = [line for line in p.stderr.splitlines() if line.startswith("pushout")]
check(p.returncode == 3 and lines and "IMPL-EX error" in lines[-1] and "max_cuts" in lines[-1]
      and summary(uncut)["implex_jumps"] == 0,
      f"IMPL-EX at max_cuts = 0: exit {p.returncode}, {lines[-1] if lines else p.stderr[-300:]}")
# Stopped in the corrosion stage, it describes the cracks of its last
# finished step: crack_pattern.csv, and summary.json's widest surface crack
# as corrosion.csv's last row reads it (12 digits printed there).
w, w_row = summary(uncut)["surface_crack_width_mm"], corrosion(uncut)[-1]["crack_width_mm"]
check(os.path.exists(os.path.join(uncut, "crack_pattern.csv")) and w is not None
      and abs(w - w_row) <= 1e-11 * max(abs(w_row), 1e-6),
      f"IMPL-EX at max_cuts = 0: crack_pattern.csv written, the widest surface crack {w} mm "
      f"against corrosion.csv's last row {w_row} mm")
cut = out_dir("implex_cut")
p = run(demo, cut, check=False, sets=implex)
check(p.returncode == 0 and summary(cut)["implex_jumps"] == 0,
      f"the same with the default max_cuts: exit {p.returncode}, "
      f"{summary(cut)['implex_jumps']} jumps")
# Its cut steps' parts are rows of corrosion.csv numbered as curve.csv's.
rows = corrosion(cut)
check(summary(cut)["cuts"] > 0 and [r["step"] for r in rows] == list(range(len(rows))),
      f"{summary(cut)['cuts']} cuts: corrosion.csv's step is the row's number ({len(rows)} rows)")
# (the one note is the blocks' layout's:
# SceneNotes.CorrodedCracksOnALayoutThatMovesTheResidualBond)
notes = [n for n in summary(cut)["notes"] if not n.startswith("cracks in the concrete on the blocks")]
check(summary(cut)["linear_solve_s"] is None and notes == [],
      f"summary.json: linear_solve_s null (not timed), no notes but the layout's: {notes}")

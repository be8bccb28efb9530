#!/usr/bin/python3
"""With cracking.radius > 0 the concrete beyond the radius stays linear, so a
crack that reaches the edge of the cracking region cannot run on there: the
run says so (a note on the progress line and in summary.json's notes) and
summary.json's cracking_edge counts the points of the region's outermost
elements and those cracked at the end, the widest opening there and the
corrosion step the cracks first reached them in, named as the progress line
numbers it and as corrosion.csv does (its row there has the x it names)
(model/CrackingCells.h region_edge, specimen/Corrosion.h note_edge_cracks).

The coarse corroded slice with cracks anywhere (common.cracking_corroded_demo:
cover 15 mm, 8 elements per quarter) corroded to x = 16 um:

1. radius 25 mm (10 mm of concrete round a 20 mm tube, the cover crack
   runs 15 mm to the face): cracks reach the edge, noted, with the counts;
   the same counts on 2 processes (the edge is the mesh's: its points
   exactly; the cracked points at Newton's tolerance, TIGHT_NEWTON, as
   common.check_one_and_two_processes compares them).
2. radius 0 (all the concrete): no edge, cracking_edge null, no note; the
   same with a radius beyond the slice's corners.
3. radius 70 mm and x = 2 um: the edge (round the far corners) exists
   and nothing cracks there: cracking_edge with no cracked point, no note.
4. No corrosion stage, the concrete cracked by a cooling of 300 degC
   (radius 11 mm, the tube's 10 mm and one ring of elements): reached, noted,
   and reached_in says so (it was "", as for none)."""

import re

from common import TIGHT_NEWTON, check, corrosion, cracking_corroded_demo, out_dir, run, summary

scene = cracking_corroded_demo(0.016, 8, seed=1)
IMPLEX = ["cracking.integration=implex"]


def edge_run(name, sets, mpirun=None):
    """The run's process (with its progress output), cracking_edge, the
    notes of the edge, and its output folder."""
    out = out_dir(name)
    p = run(scene, out, sets=IMPLEX + sets, extra=TIGHT_NEWTON, mpirun=mpirun, quiet=False)
    s = summary(out)
    noted = [n for n in s["notes"] if "edge of the cracking region" in n]
    return p, s["cracking_edge"], noted, out


# 1. Reached, noted, the same on 2 processes.
p1, e1, noted1, out1 = edge_run("edge_r25", ["cracking.radius=25"])
check(e1 is not None and e1["radius_mm"] == 25 and 0 < e1["cracked_points"] <= e1["points"]
      and e1["max_opening_mm"] > 0 and e1["reached_in"].startswith("corrosion step"),
      f"radius 25 mm: cracking_edge {e1}")
# "corrosion step k (x = X um; corrosion.csv step N)": row N has x = X (to
# the 4 digits printed).
m = re.fullmatch(r"corrosion step (\d+) \(x = ([0-9.e+-]+) um; corrosion.csv step (\d+)\)",
                 e1["reached_in"])
rows = corrosion(out1)
check(m is not None and abs(rows[int(m[3])]["penetration_mm"] * 1e3 - float(m[2])) <= 5e-4 * float(m[2])
      and f"corrosion {m[1]}/8  x = {m[2]} um" in p1.stdout,
      f"radius 25 mm: reached in {e1['reached_in']!r}, corrosion.csv's row there: "
      f"{rows[int(m[3])] if m else None}")
check(len(noted1) == 1 and f"{e1['cracked_points']} of the {e1['points']} points" in noted1[0]
      and "note: cracks reached the edge" in p1.stdout,
      f"radius 25 mm: noted in summary.json and on the progress line ({noted1})")
_, e2, noted2, _ = edge_run("edge_r25_np2", ["cracking.radius=25"], mpirun=2)
check(e2["points"] == e1["points"] and e2["cracked_points"] == e1["cracked_points"]
      and e2["reached_in"] == e1["reached_in"] and len(noted2) == 1,
      f"2 processes: {e2['points']} edge points ({e1['points']} on 1), "
      f"{e2['cracked_points']} cracked ({e1['cracked_points']}), in {e2['reached_in']}")

# 2. No radius: no edge.
p0, e0, noted0, _ = edge_run("edge_r0", ["corrosion.penetration=0.004", "corrosion.steps=2"])
check(e0 is None and not noted0 and "edge of the cracking region" not in p0.stdout,
      f"radius 0: cracking_edge {e0}, notes {noted0}")
# A radius beyond the slice's farthest corner (90 mm from the axis) takes in
# all the concrete: no edge either (it was a cracking_edge of zeros).
_, e200, noted200, _ = edge_run("edge_r200", ["cracking.radius=200", "corrosion.penetration=0.002",
                                            "corrosion.steps=1"])
check(e200 is None and not noted200, f"radius 200 mm: cracking_edge {e200}, notes {noted200}")

# 3. An edge that no crack reaches.
p70, e70, noted70, _ = edge_run("edge_r70", ["cracking.radius=70", "corrosion.penetration=0.002",
                                          "corrosion.steps=1"])
check(e70 is not None and e70["points"] > 0 and e70["cracked_points"] == 0
      and e70["reached_in"] == "" and not noted70,
      f"radius 70 mm at x = 2 um: cracking_edge {e70}, notes {noted70}")

# 4. Reached without a corrosion stage.
p4, e4, noted4, _ = edge_run("edge_no_corrosion", ["cracking.radius=11", "corrosion.penetration=0",
                                                   "loading.temperature_change=-300"])
check(e4 is not None and e4["cracked_points"] > 0 and len(noted4) == 1
      and e4["reached_in"] == "step 0 or the push (no corrosion stage)",
      f"no corrosion stage: cracking_edge {e4}, notes {noted4}")

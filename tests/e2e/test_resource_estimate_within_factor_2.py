"""The size guard (record/ResourceGuard.h): the mesh size predicted from the
mesh keys before meshing equals the mesh gmsh makes, the peak-memory
estimate is within a factor 2 of the measured peak, and a run that cannot
fit is refused at once with exit 2 and a message that says what to change;
--force runs it anyway."""
import os
import resource
import subprocess
import sys
import time

from common import check, out_dir, run, summary

PUSHOUT = sys.argv[1]
SCENE = os.path.join(os.environ.get("PUSHOUT_SOURCE_DIR", "."), "demo", "pushout_friction.toml")
SHORT = ["loading.steps=1", "output.plot=false"]

# Exact sizes: the counts of meshes/slice.geo in closed form (mesh/size.cpp).
cases = {
    "quarter": ["mesh.elements_per_quarter=6", "mesh.elements_through_thickness=3"],
    "full": ["mesh.elements_per_quarter=6", "mesh.elements_through_thickness=3",
             "model.symmetry=\"full\""],
    "odd": ["mesh.elements_per_quarter=5", "mesh.elements_through_thickness=2",
            "mesh.steel_layers=2"],
    "off_centre": ["mesh.elements_per_quarter=6", "mesh.elements_through_thickness=2",
                   "geometry.tube_center=[35.0, 50.0]"],
    "circle": ["mesh.elements_per_quarter=8", "mesh.elements_through_thickness=2",
               "geometry.outer_shape=\"circle\"", "mesh.outer_size_ratio=4.0"],
    "no_grading": ["mesh.elements_per_quarter=4", "mesh.elements_through_thickness=2",
                   "mesh.outer_size_ratio=1.0"],
    "degree2": ["mesh.elements_per_quarter=4", "mesh.elements_through_thickness=2",
                "mesh.degree=2"],
    "degree2_full": ["mesh.elements_per_quarter=4", "mesh.elements_through_thickness=2",
                     "mesh.degree=2", "model.symmetry=\"full\""],
}
for name, sets in cases.items():
    out = out_dir(f"guard_{name}")
    run(SCENE, out, sets=sets + SHORT)
    s = summary(out)
    e = s["estimate"]
    for key in ("dofs", "cells", "interface_pairs"):
        check(e[key] == s[key], f"{name}: predicted {key} {e[key]} = meshed {s[key]}")
# With crack planes the circumference is cut at the cracks (mesh/cracks.h).
CORRODED = os.path.join(os.environ.get("PUSHOUT_SOURCE_DIR", "."), "demo", "pushout_corroded.toml")
for name, sets in {"one_crack": [], "odd_crack": ["mesh.elements_per_quarter=5"]}.items():
    out = out_dir(f"guard_{name}")
    run(CORRODED, out, sets=sets + ["mesh.elements_through_thickness=2", "corrosion.steps=1",
                                    "corrosion.penetration=0.001"] + SHORT)
    s = summary(out)
    for key in ("dofs", "cells", "interface_pairs"):
        check(s["estimate"][key] == s[key], f"{name}: predicted {key} {s['estimate'][key]} = meshed {s[key]}")
four = open(CORRODED).read() + "".join(f"\n[[crack]]\nangle = {a}\n" for a in (0.0, 135.0, 180.0))
out = out_dir("guard_four_cracks")
run(four, out, sets=["mesh.elements_through_thickness=2", "corrosion.steps=1",
                     "corrosion.penetration=0.001"] + SHORT)
s = summary(out)
check(all(s["estimate"][k] == s[k] for k in ("dofs", "cells", "interface_pairs")),
      f"four cracks: predicted size = meshed ({s['dofs']} dofs, {s['interface_pairs']} joint elements)")
single = os.path.join(os.environ.get("PUSHOUT_SOURCE_DIR", "."), "demo", "single_joint_fig6.toml")
out = out_dir("guard_single_joint")
run(single, out, sets=["output.plot=false"])
s = summary(out)
check(all(s["estimate"][k] == s[k] for k in ("dofs", "cells", "interface_pairs")),
      f"single joint: predicted size = meshed ({s['dofs']} dofs)")

# Memory within a factor 2 of the measurement (bench/memory_estimate.py has
# the table over sizes), on the condensed and on the whole-model path, and
# with cracks anywhere in the concrete (the corroded demo with them, its
# first corrosion step: the whole slice, not condensed).
CRACKING = os.path.join(os.environ.get("PUSHOUT_SOURCE_DIR", "."), "demo",
                        "pushout_corroded_cracking.toml")
for name, scene, sets in [("condensed", SCENE, ["mesh.elements_per_quarter=24"]),
                          ("whole", SCENE, ["mesh.elements_per_quarter=24",
                                            "solver.condensation=\"off\""]),
                          ("cracking", CRACKING, ["corrosion.steps=1",
                                                  "corrosion.penetration=0.001"])]:
    out = out_dir(f"guard_memory_{name}")
    run(scene, out, sets=sets + SHORT)
    s = summary(out)
    ratio = s["estimate"]["peak_memory_mb"] / s["peak_memory_mb"]
    check(0.5 < ratio < 2, f"{name}: estimated {s['estimate']['peak_memory_mb']:.0f} MB vs measured "
                           f"{s['peak_memory_mb']:.0f} MB (ratio {ratio:.2f})")

# Too large (some 0.5 TB): refused before meshing, with exit 2 and what to
# change.
out = out_dir("guard_too_large")
t0 = time.time()
p = run(SCENE, out, sets=["mesh.elements_per_quarter=2000"], check=False, quiet=False)
wall = time.time() - t0
err = p.stderr.strip()
check(p.returncode == 2, f"elements_per_quarter = 2000: exit {p.returncode} = 2 ({wall:.1f} s)")
check("meshing" not in p.stdout and not os.path.exists(out),
      f"refused before meshing (no meshing line, no output folder): {p.stdout.strip()[:200]!r}")
check(len(err.splitlines()) == 1 and "GB" in err and "available" in err and "--force" in err
      and "mesh.elements_per_quarter (2000)" in err, f"one line that says why and what to change: {err!r}")
check(not os.path.exists(os.path.join(out, "curve.csv")), "no curve.csv from a refused run")

# A refused run leaves an earlier run's outputs in its folder as they were
# (it deleted them before it was refused).
kept = out_dir("guard_keeps_earlier_run")
run(SCENE, kept, sets=["mesh.elements_per_quarter=4", "mesh.elements_through_thickness=2"] + SHORT)
before = {f: os.path.getmtime(os.path.join(kept, f)) for f in ("curve.csv", "summary.json")}
# (With a PETSc option nothing reads: the earlier summary.json is not this
# run's to list it in.)
p = run(SCENE, kept, sets=["mesh.elements_per_quarter=2000"], extra=["-snes_monitr"], check=False)
check(p.returncode == 2 and all(os.path.getmtime(os.path.join(kept, f)) == t for f, t in before.items()),
      f"refused (exit {p.returncode}): the earlier run's curve.csv and summary.json stay")
# So does a fit whose start is too large (it claimed the folder first).
data = os.path.join(os.path.dirname(kept), "guard_fit_data.csv")
with open(data, "w") as f:
    f.write("delta_mm,tau_MPa\n" + "".join(f"{0.01 * i},{0.1 * i}\n" for i in range(1, 6)))
p = subprocess.run([PUSHOUT, "fit", SCENE, "--data", data, "--free", "interface.0.mu", "--out", kept,
                    "--quiet", "--set", "mesh.elements_per_quarter=2000"],
                   capture_output=True, text=True, timeout=120)
check(p.returncode == 2 and "mesh.elements_per_quarter (2000)" in p.stderr
      and all(os.path.getmtime(os.path.join(kept, f)) == t for f, t in before.items()),
      f"a fit refused (exit {p.returncode}, {p.stderr.strip()[:120]!r}): the earlier outputs stay")

# A limit of the address space (ulimit -v) bounds the run as the machine's
# memory does: a 5 GB run under a 2.5 GB limit is refused, not started.
limited = out_dir("guard_address_space")
p = subprocess.run([PUSHOUT, "run", SCENE, "--out", limited, "--quiet", "--set", "mesh.elements_per_quarter=32",
                    "--set", "mesh.elements_through_thickness=16", "--set", "model.symmetry=full"],
                   capture_output=True, text=True, timeout=120,
                   preexec_fn=lambda: resource.setrlimit(resource.RLIMIT_AS, (2500 << 20, 2500 << 20)))
check(p.returncode == 2 and "ulimit -v" in p.stderr,
      f"under ulimit -v 2.5 GB: exit {p.returncode}, {p.stderr.strip()[:120]!r}")
# --force runs it into the limit: the LU out of memory ends the run at once
# (exit 1, not retried in smaller steps and reported as non-convergence).
t0 = time.time()
p = subprocess.run([PUSHOUT, "run", SCENE, "--out", limited, "--quiet", "--force", "--set",
                    "mesh.elements_per_quarter=32", "--set", "mesh.elements_through_thickness=16",
                    "--set", "model.symmetry=full", "--set", "loading.steps=1"],
                   capture_output=True, text=True, timeout=300,
                   preexec_fn=lambda: resource.setrlimit(resource.RLIMIT_AS, (2500 << 20, 2500 << 20)))
check(p.returncode == 1 and "ran out of memory" in p.stderr and summary(limited)["cuts"] == 0,
      f"--force under the limit: exit {p.returncode} in {time.time() - t0:.1f} s, "
      f"{summary(limited)['cuts']} cuts: {p.stderr.strip()[:100]!r}")

# --force runs what the guard refuses (stopped once it is meshing). The run
# needs some 50 GB: under an address space of 20 GB it is refused on any
# machine, however much memory it has.
out = out_dir("guard_force")
big = ["mesh.elements_per_quarter=600", "mesh.elements_through_thickness=2", "output.plot=false"]
big_args = [PUSHOUT, "run", SCENE, "--out", out, "--quiet"] + [a for s in big for a in ("--set", s)]
limit_20_gb = lambda: resource.setrlimit(resource.RLIMIT_AS, (20 << 30, 20 << 30))  # noqa: E731
p = subprocess.run(big_args, capture_output=True, text=True, timeout=120, preexec_fn=limit_20_gb)
check(p.returncode == 2, f"600 elements per quarter are refused under 20 GB ({p.stderr.strip()[:90]}...)")
proc = subprocess.Popen(big_args + ["--force"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                        preexec_fn=limit_20_gb)
time.sleep(3)
check(proc.poll() is None, "--force: the same run starts meshing")
proc.terminate()
proc.communicate(timeout=30)

"""pushout sweep (the Cartesian product of scene values, study/Sweep.h):

1. Serial: 2 x 2 cases of the friction push-out (mu x dT, coarse mesh):
   sweep.csv has one row per case with the varied values, the peak and last
   tau; every case folder has its resolved scene.toml, curve.csv and
   summary.json; the set-up is built for the first case and reused by the
   others (they change laws and loads only), and a reused case's curve
   equals that of `pushout run` with the same --set values bit for bit
   (to 1e-10 asked); the plateau tau grows with mu and |dT|. With a mesh
   key varying fastest, the cases that share a set-up run together (two
   set-ups built for four cases).
2. MPI: the same sweep on 2 processes (two groups of one: the cases spread
   over them) gives the serial curves; with --ranks-per-case 2 (one group:
   each case on 2 processes, the whole model) a case equals `pushout run` on
   2 processes, and the serial (condensed) sweep. Each to the bound of
   Newton's tolerance on the two runs (common.newton_bound): under mpirun
   BLAS may run on other threads, and parallel MUMPS is not bitwise
   reproducible (measured 1e-11 to 2e-9), so only Newton's tolerance binds.
3. A case refused by the size guard (a 4000-per-quarter mesh) is a row with
   its exit code and message while the other case runs; the sweep exits 3.
4. Bad input exits 2 with one message: --vary without values, an unknown
   key (naming the case), a value that is not a number, --ranks-per-case
   that does not divide the processes.
5. SIGINT during a sweep (paper's mesh, 8 cases of 100 steps, the signal
   after the first cases): exit 130, and sweep.csv lists the cases that ran,
   the interrupted one with exit 130.
6. Seeds as error bars: beta x cracking.seed (2 x 2) on the coarse corroded
   slice with cracks anywhere: sweep.csv's p_before_push_MPa and
   crack_width_mm are each case's curve.csv (delta = 0) and corrosion.csv
   (last row) values, and sweep_seeds.csv has one row per beta with the two
   seeds' mean, min and max of sweep.csv's numbers (to the 12 digits both
   print); the seeds give different curves (the field is the seed's); a
   sweep that does not vary the seed writes no sweep_seeds.csv (1.), a
   sweep whose uniform-strength cases do not read the seed says which, and
   one into the same folder removes the earlier one. A case that reused
   another's set-up (another beta, the same seed) equals `pushout run` of
   its scene.toml, as in 1.
7. A scene file edited while the sweep runs (here made no TOML at all):
   the cases after it run the scene the sweep read and checked at its
   start (each case read the file again, and failed)."""
import csv
import os
import signal
import subprocess
import time

import h5py
import numpy as np

from common import (PUSHOUT, SOURCE, check, corrosion, cracking_corroded_demo, curve, mpi_env, mpirun,
                    newton_bound, out_dir, run, solved_unknowns, summary)

SCENE = os.path.join(SOURCE, "demo", "pushout_friction.toml")
COARSE = ["--set", "mesh.elements_per_quarter=4", "--set", "mesh.elements_through_thickness=2"]
VARY = ["--vary", "interface.0.mu=0.2,0.4", "--vary", "loading.temperature_change=-5,-25"]
MPI = [mpirun(), "--allow-run-as-root", "--oversubscribe"]
ENV = mpi_env(1)


def sweep(out, extra=(), processes=None, vary=VARY, env=None):
    cmd = [PUSHOUT, "sweep", SCENE, "--out", out, "--quiet"] + COARSE + list(vary) + list(extra)
    if processes:
        cmd = MPI + ["-n", str(processes)] + cmd
    return subprocess.run(cmd, capture_output=True, text=True, timeout=600,
                          env=dict(mpi_env(processes or 1), **(env or {})))


def table(out):
    with open(os.path.join(out, "sweep.csv"), newline="") as f:
        return list(csv.DictReader(f))


def same_curves(a, b):
    """Largest relative difference of the curve columns (not wall_s)."""
    worst = 0.0
    for ra, rb in zip(a, b):
        for k in ra:
            if k in ("wall_s", "newton_iterations", "cuts"):
                continue
            worst = max(worst, abs(ra[k] - rb[k]) / max(1.0, abs(ra[k])))
    return worst if len(a) == len(b) else float("inf")


def column_difference(a, b):
    """Largest difference of the curve columns (not wall_s) relative to each
    column's largest |value| (the measure of common.newton_bound)."""
    if len(a) != len(b):
        return float("inf")
    worst = 0.0
    for k in a[0]:
        if k in ("step", "wall_s", "newton_iterations", "cuts"):
            continue
        scale = max(abs(r[k]) for r in b) or 1.0
        worst = max(worst, max(abs(x[k] - y[k]) for x, y in zip(a, b)) / scale)
    return worst


def bound(a, b):
    """common.newton_bound for the runs in folders a and b."""
    return newton_bound(len(curve(b)), max(solved_unknowns(summary(a)), solved_unknowns(summary(b))))


# 1. Serial.
serial = out_dir("sweep_serial")
p = sweep(serial)
check(p.returncode == 0, f"serial sweep: exit {p.returncode} {p.stderr[-500:]}")
rows = table(serial)
check([(r["interface.0.mu"], r["loading.temperature_change"]) for r in rows] ==
      [("0.2", "-5"), ("0.2", "-25"), ("0.4", "-5"), ("0.4", "-25")]
      and all(r["converged"] == "1" for r in rows),
      "sweep.csv: 4 rows, mu varying slowest, all converged")
for r in rows:
    for f in ("scene.toml", "curve.csv", "summary.json"):
        check(os.path.exists(os.path.join(serial, r["case"], f)), f"{r['case']}/{f} written")
tau = {(r["interface.0.mu"], r["loading.temperature_change"]): float(r["tau_last_MPa"]) for r in rows}
check(tau[("0.4", "-25")] > tau[("0.2", "-25")] > tau[("0.2", "-5")] > 0
      and abs(tau[("0.4", "-25")] / tau[("0.2", "-25")] - 2) < 0.05,
      f"plateau tau grows with mu (x{tau[('0.4', '-25')] / tau[('0.2', '-25')]:.3f} for mu x2) and |dT|")
reused = [summary(os.path.join(serial, r["case"]))["setup_reused"] for r in rows]
check(reused == [False, True, True, True],
      f"the set-up (mesh, factorisation, condensed flexibility) built once, reused: {reused}")
# Cases that share a set-up run one after the other: with the mesh varying
# fastest (set-ups A, B, A, B) two are built, not four; the folders keep the
# cases' numbers.
grouped = out_dir("sweep_set_up_order")
p = sweep(grouped, vary=["--vary", "interface.0.mu=0.2,0.4",
                         "--vary", "mesh.elements_through_thickness=2,3"])
g = table(grouped) if p.returncode == 0 else []
built = [r["case"] for r in g if not summary(os.path.join(grouped, r["case"]))["setup_reused"]]
check(p.returncode == 0 and [r["mesh.elements_through_thickness"] for r in g] == ["2", "3", "2", "3"]
      and built == ["case_000", "case_001"],
      f"cases sharing a set-up run together: set-ups built for {built} of 4 cases")
direct = out_dir("sweep_direct_case_002")
run(SCENE, direct, sets=["mesh.elements_per_quarter=4", "mesh.elements_through_thickness=2",
                         "interface.0.mu=0.4", "loading.temperature_change=-5"])
d = same_curves(curve(direct), curve(os.path.join(serial, "case_002")))
check(d < 1e-10, f"case_002 equals pushout run with its values (largest difference {d:.1e})")
check(not os.path.exists(os.path.join(serial, "sweep_seeds.csv")),
      "no sweep_seeds.csv where the seed is not varied")
# A reused set-up's fields: a case without a temperature change after one
# with it writes the stress of its own (the stress output read the model's
# last temperature change, set only where one was loaded: 12.5 MPa of
# thermal stress in a case that has none). As the curves, to 1e-10.
fields = out_dir("sweep_fields_reused")
two_steps = ["--set", "loading.steps=2", "--set", "output.xdmf=true"]
p = sweep(fields, extra=two_steps, vary=["--vary", "loading.temperature_change=-25,0"])
alone = out_dir("sweep_fields_alone")
run(SCENE, alone, sets=["mesh.elements_per_quarter=4", "mesh.elements_through_thickness=2",
                        "loading.steps=2", "output.xdmf=true", "loading.temperature_change=0"])
with h5py.File(os.path.join(fields, "case_001", "fields.h5"), "r") as a, \
        h5py.File(os.path.join(alone, "fields.h5"), "r") as b:
    steps = sorted(b["Function/stress"])
    worst = max(float(np.abs(a["Function/stress"][t][()] - b["Function/stress"][t][()]).max())
                for t in steps)
    scale = max(1.0, max(float(np.abs(b["Function/stress"][t][()]).max()) for t in steps))
check(p.returncode == 0 and summary(os.path.join(fields, "case_001"))["setup_reused"] and
      len(steps) == 3 and worst <= 1e-10 * scale,
      f"a reused set-up's case without temperature change: its stress field within {worst:.1e} MPa "
      f"of pushout run's ({len(steps)} steps)")

# 2. MPI. Two groups of one process run what the serial sweep runs; a group
# of two runs the whole model (no condensation on 2 processes), which equals
# `pushout run` on 2 processes, and the condensed serial run. Processes,
# threads and MUMPS's order of sums differ: each run is exact only to
# Newton's tolerance, so each comparison is to newton_bound.
two = out_dir("sweep_direct_case_003_2_processes")
run(SCENE, two, sets=["mesh.elements_per_quarter=4", "mesh.elements_through_thickness=2",
                      "interface.0.mu=0.4", "loading.temperature_change=-25"], mpirun=2)
for name, extra in (("two_groups", []), ("ranks_per_case_2", ["--ranks-per-case", "2"])):
    out = out_dir(f"sweep_{name}")
    p = sweep(out, extra, processes=2)
    check(p.returncode == 0, f"{name}: exit {p.returncode} {p.stderr[-500:]}")
    for r in rows:
        a, b = os.path.join(serial, r["case"]), os.path.join(out, r["case"])
        d, tol = column_difference(curve(b), curve(a)), bound(a, b)
        check(d <= tol, f"{name}: {r['case']} equals the serial sweep's to {d:.1e} <= {tol:.1e}")
    if name == "ranks_per_case_2":
        b = os.path.join(out, "case_003")
        d, tol = column_difference(curve(b), curve(two)), bound(two, b)
        check(d <= tol, f"{name}: case_003 equals pushout run on 2 processes to {d:.1e} <= {tol:.1e}")

# 3. A case refused by the size guard. With two groups on this machine the
# guard counts the other group's process beside the case's own, and says so.
for name, processes, beside in (("sweep_refused", None, ""),
                                ("sweep_refused_two_groups", 2,
                                 "2 processes, 1 of them running other cases")):
    out = out_dir(name)
    p = sweep(out, processes=processes, vary=["--vary", "mesh.elements_per_quarter=4,4000"])
    rows = table(out)
    check(p.returncode == 3 and rows[0]["converged"] == "1" and rows[1]["exit_code"] == "2"
          and "memory" in rows[1]["message"] and beside in rows[1]["message"],
          f"{name}: the refused case is a row (exit {rows[1]['exit_code']}: "
          f"{rows[1]['message'][:120]}...), the other ran; the sweep exits {p.returncode}")

# Every case refused: sweep.csv has them, and no sweep.png is drawn (no
# curve to draw), which the sweep says.
out = out_dir("sweep_all_refused")
p = sweep(out, vary=["--vary", "mesh.elements_per_quarter=3000,4000"])
check(p.returncode == 3 and len(table(out)) == 2 and not os.path.exists(os.path.join(out, "sweep.png"))
      and "no case wrote a curve" in p.stderr and "plot:" not in p.stderr,
      f"every case refused: exit {p.returncode}, no sweep.png ({p.stderr.strip()[-160:]!r})")

# Every case failed at its first solve (a test hook: each solve's result is
# not a number), so each curve.csv is its header alone: no sweep.png either
# (an empty plot), and the sweep says so.
out = out_dir("sweep_all_failed_before_a_row")
p = sweep(out, vary=["--vary", "interface.0.mu=0.2,0.4"], env={"PUSHOUT_TEST_NONFINITE_FROM": "1"})
headers_only = all(len(open(os.path.join(out, f"case_{i:03d}", "curve.csv")).readlines()) == 1
                   for i in range(2))
check(p.returncode == 3 and headers_only and not os.path.exists(os.path.join(out, "sweep.png"))
      and "no case wrote a curve" in p.stderr,
      f"every case failed before a row: exit {p.returncode}, curves of their header alone "
      f"{headers_only}, no sweep.png ({p.stderr.strip()[-160:]!r})")

# 4. Bad input.
for what, vary, extra, n in (
        ("no values", ["--vary", "interface.0.mu="], [], None),
        ("unknown key", ["--vary", "interface.0.muu=0.2"], [], None),
        ("not a number", ["--vary", "interface.0.mu=0.2,abc"], [], None),
        # the second case's push is more than 10 % of the slice's thickness
        ("values run refuses together", ["--vary", "loading.push_displacement=0.01,5.0"], [], None),
        ("ranks per case", VARY, ["--ranks-per-case", "2"], 3)):
    p = sweep(out_dir("sweep_bad"), extra, processes=n, vary=vary)
    message = [line for line in p.stderr.splitlines() if line.startswith("pushout")]
    check(p.returncode == 2 and len(message) == 1,
          f"{what}: exit {p.returncode}, {message[0] if message else p.stderr[-300:]}")

# More cases than --max-cases can allow (500^3 > 1e8): the message does not
# offer a --max-cases that its range refuses.
many = []
for key, values in (("interface.0.mu", [0.001 * i for i in range(1, 501)]),
                    ("loading.temperature_change", [-0.1 * i for i in range(1, 501)]),
                    ("concrete.E", [20000 + i for i in range(1, 501)])):
    many += ["--vary", key + "=" + ",".join(str(v) for v in values)]
p = sweep(out_dir("sweep_bad"), vary=many)
check(p.returncode == 2 and "split the --vary values" in p.stderr and "--max-cases 1" not in p.stderr,
      f"125000000 cases: exit {p.returncode}, {p.stderr.strip()[:160]!r}")

# A --set (or --vary) before the scene takes one value: the scene follows.
p = subprocess.run([PUSHOUT, "run", "--set", "mesh.elements_per_quarter=4", SCENE, "--out",
                    out_dir("sweep_set_first"), "--quiet", "--set", "mesh.elements_through_thickness=2",
                    "--set", "loading.steps=2"], capture_output=True, text=True, timeout=300, env=ENV)
check(p.returncode == 0, f"pushout run --set KEY=VALUE SCENE: exit {p.returncode} {p.stderr[-200:]}")

# 5. A signal stops the sweep cleanly.
out = out_dir("sweep_interrupted")
cmd = [PUSHOUT, "sweep", os.path.join(SOURCE, "demo", "pushout_friction_adhesion.toml"), "--out", out,
       "--quiet", "--vary", "interface.1.c=10,15,20,25,30,35,40,45",
       "--set", "loading.push_displacement=0.5", "--set", "loading.steps=100"]
p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
while not os.path.exists(os.path.join(out, "case_001", "summary.json")) and p.poll() is None:
    time.sleep(0.05)
p.send_signal(signal.SIGINT)
_, err = p.communicate(timeout=120)
rows = table(out)
check(p.returncode == 130 and 1 <= len(rows) < 8 and rows[-1]["exit_code"] in ("0", "130"),
      f"SIGINT: exit {p.returncode}, sweep.csv with {len(rows)} of 8 cases "
      f"(last: exit {rows[-1]['exit_code']} {rows[-1]['message']})")

# 6. Seeds as error bars.
out = out_dir("sweep_seeds")
scene = os.path.join(out + "_scene.toml")
with open(scene, "w") as f:
    f.write(cracking_corroded_demo(0.012, 3))
p = subprocess.run([PUSHOUT, "sweep", scene, "--out", out, "--quiet", "--vary",
                    "corrosion.beta=2,3", "--vary", "cracking.seed=1,2",
                    "--set", "loading.push_displacement=0.02", "--set", "loading.steps=4"],
                   capture_output=True, text=True, timeout=600)
check(p.returncode == 0, f"seed sweep: exit {p.returncode} {p.stderr[-500:]}")
rows = table(out)
for r in rows:
    c, k = curve(os.path.join(out, r["case"])), corrosion(os.path.join(out, r["case"]))
    for name, x, y in (("p_before_push_MPa", float(r["p_before_push_MPa"]), c[0]["p_MPa"]),
                       ("crack_width_mm", float(r["crack_width_mm"]), k[-1]["crack_width_mm"])):
        check(abs(x - y) <= 1e-10 * abs(y), f"{r['case']}: sweep.csv {name} {x} is the run's {y}")
with open(os.path.join(out, "sweep_seeds.csv"), newline="") as f:
    groups = list(csv.DictReader(f))
check([(g["corrosion.beta"], g["seeds"], g["converged"]) for g in groups]
      == [("2", "2", "2"), ("3", "2", "2")], "sweep_seeds.csv: one row per beta, 2 seeds each")
for g in groups:
    seeds = [r for r in rows if r["corrosion.beta"] == g["corrosion.beta"]]
    for name in ("peak_tau_MPa", "tau_last_MPa", "p_before_push_MPa", "crack_width_mm"):
        v = [float(r[name]) for r in seeds]
        for stat, want in (("mean", sum(v) / len(v)), ("min", min(v)), ("max", max(v))):
            got = float(g[f"{name}_{stat}"])
            check(abs(got - want) <= 1e-10 * max(abs(want), 1e-12),
                  f"beta {g['corrosion.beta']}: {name}_{stat} {got} = {want} over the seeds")
    check(float(g["tau_last_MPa_min"]) < float(g["tau_last_MPa_max"]),
          f"beta {g['corrosion.beta']}: the seeds' fields differ: tau_last "
          f"{g['tau_last_MPa_min']} to {g['tau_last_MPa_max']} MPa")
check(os.path.getsize(os.path.join(out, "sweep.png")) > 0, "sweep.png drawn with the seed groups")
# A case that reused another's set-up (the same seed, another beta: the
# cracks' kept tangent built afresh, Equilibrium::restart) is the run of its
# scene.toml (to 1e-10 asked, as the friction cases, 1.); it differed by
# 4e-7 MPa in tau when the kept tangent carried the last case's round-off.
reused = [r["case"] for r in rows if summary(os.path.join(out, r["case"]))["setup_reused"]]
check(len(reused) == 2, f"the cracking cases of another beta reuse a set-up: {reused}")
alone = out_dir("sweep_seeds_case_alone")
run(os.path.join(out, reused[0], "scene.toml"), alone)
for name, read in (("curve.csv", curve), ("corrosion.csv", corrosion)):
    d = same_curves(read(os.path.join(out, reused[0])), read(alone))
    check(d < 1e-10, f"{reused[0]} (set-up reused) is pushout run's {name} (largest difference {d:.1e})")
# Into the same folder without the seed: the earlier sweep_seeds.csv goes.
p = subprocess.run([PUSHOUT, "sweep", scene, "--out", out, "--quiet", "--vary", "corrosion.beta=2",
                    "--set", "loading.push_displacement=0.02", "--set", "loading.steps=1"],
                   capture_output=True, text=True, timeout=600)
check(p.returncode == 0 and not os.path.exists(os.path.join(out, "sweep_seeds.csv")),
      f"a later sweep without the seed leaves no sweep_seeds.csv behind (exit {p.returncode})")
# The seed beside a uniform strength (strength_cov = 0), which does not read
# it: the sweep runs (the field's cases read it) and says, before the cases
# run, which cases' rows of sweep_seeds.csv are one specimen run per seed.
uniform = out_dir("sweep_seeds_uniform")
p = subprocess.run([PUSHOUT, "sweep", scene, "--out", uniform, "--quiet", "--vary",
                    "cracking.strength_cov=0,0.15", "--vary", "cracking.seed=1,2",
                    "--set", "loading.push_displacement=0.02", "--set", "loading.steps=1"],
                   capture_output=True, text=True, timeout=600)
note = [line for line in p.stdout.splitlines() if line.startswith("pushout sweep: note:")]
check(p.returncode == 0 and len(note) == 1 and "case_000, case_001" in note[0]
      and "cracking.seed is not read" in note[0] and "case_002" not in note[0],
      f"a seed beside a uniform strength: exit {p.returncode}, {note}")

# 7. The scene file edited while the sweep runs. The first case's steps are
# slowed (a test hook: 0.3 s a step from the third on), and the file is
# spoilt once its second step is in curve.csv.
edited = os.path.join(os.path.dirname(out_dir("sweep_scene_edited")), "sweep_scene_edited.toml")
with open(SCENE) as f:
    original = f.read()
with open(edited, "w") as f:
    f.write(original)
out = out_dir("sweep_scene_edited")
p = subprocess.Popen([PUSHOUT, "sweep", edited, "--out", out, "--quiet", "--vary", "loading.steps=6,3"] + COARSE,
                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                     env=dict(ENV, PUSHOUT_TEST_SLOW_STEP_S="0.3"))
first = os.path.join(out, "case_000", "curve.csv")
deadline = time.time() + 300
while p.poll() is None and time.time() < deadline and (
        not os.path.exists(first) or len(open(first).readlines()) < 4):
    time.sleep(0.02)
# (header, step 0 and 6 steps: 8 lines once the first case is done)
spoilt_while_running = p.poll() is None and len(open(first).readlines()) < 8
with open(edited, "w") as f:
    f.write("this is [ no TOML\n")
_, err = p.communicate(timeout=300)
rows = table(out)
check(spoilt_while_running and p.returncode == 0 and [r["converged"] for r in rows] == ["1", "1"],
      f"the scene spoilt during the first case: both cases run the scene read at the start "
      f"(exit {p.returncode}, {err.strip()[-200:]!r})")

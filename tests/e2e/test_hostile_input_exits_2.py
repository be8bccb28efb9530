"""Hostile input: scene files, --set values and command lines that could
crash, run until killed or run silently. Each must end at once with exit 2
and one line on stderr naming the key, option or file."""
import os
import subprocess
import time

from common import COARSE_MESH, FRICTION_2, OUT_ROOT, PUSHOUT, check, out_dir, summary

GOOD = COARSE_MESH + FRICTION_2
QUICK = ["--set", "loading.steps=1", "--set", "output.plot=false"]
os.makedirs(OUT_ROOT, exist_ok=True)


def scene(name, text):
    path = os.path.join(OUT_ROOT, "hostile_" + name + ".toml")
    with open(path, "w") as f:
        f.write(text)
    return path


GOOD_SCENE = scene("good", GOOD)


def pushout(args, timeout=60):
    t0 = time.monotonic()
    try:
        p = subprocess.run([PUSHOUT] + args, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        raise SystemExit(f"FAILED: pushout {' '.join(args)[:200]} still running after {timeout} s")
    return p, time.monotonic() - t0


# A refusal does no work: its time is the start of a run (libraries, MPI,
# PETSc) plus the checks. That start is measured here, on this machine
# under this load, by a run refused for a value out of range (the same path
# as the refusals below; `pushout keys` starts no MPI, and a fresh root's
# first MPI start has taken 10 s), the slower of two; a refusal may take
# `seconds` more: far more than any check needs, far less than a scan
# quadratic in a 50000-character key or a run of 1e7 steps.
START_S = max(pushout(["run", GOOD_SCENE, "--out", out_dir("hostile_start"), "--quiet",
                       "--set", "loading.steps=-1"])[1] for _ in range(2))


def refused(name, args, words, timeout=60, seconds=None):
    """`pushout args` must exit 2 with one stderr line holding every word."""
    p, wall = pushout(args, timeout)
    err = p.stderr.strip()
    check(p.returncode == 2, f"{name}: exit {p.returncode} (2 wanted): {err[:300]!r}")
    check(len(err.splitlines()) == 1, f"{name}: one line on stderr")
    check(all(w in err for w in words), f"{name}: message names {words}: {err[:300]!r}")
    if seconds:
        check(wall < START_S + seconds,
              f"{name}: refused in {wall:.1f} s (< {START_S:.1f} s to start + {seconds} s)")
    return err


def run_args(name, path, sets=(), extra=()):
    out = out_dir("hostile_" + name)
    args = ["run", path, "--out", out, "--quiet"]
    for s in sets:
        args += ["--set", s]
    return args + list(extra), out


def refused_run(name, text, sets, words, **kw):
    args, out = run_args(name.replace(" ", "_"), scene(name.replace(" ", "_"), text), sets)
    refused(name, args, words, **kw)
    check(not os.path.exists(os.path.join(out, "curve.csv")), f"{name}: no curve.csv")


# 1. Nesting that would exhaust the TOML parser's stack.
deep = ".".join(["a"] * 50000)
refused_run("deep dotted key", GOOD + "\n" + deep + " = 1\n", [], ["too deeply nested", "line"],
            timeout=30, seconds=10)
refused_run("deep arrays", GOOD + "\n[loading]\npush_path = " + "[" * 30000 + "]" * 30000 + "\n", [],
            ["too deeply nested"], timeout=30, seconds=10)
refused_run("deep inline tables", GOOD + "\nx = " + "{a=" * 30000 + "1" + "}" * 30000 + "\n", [],
            ["too deeply nested"], timeout=30, seconds=10)
refused_run("deep --set path", GOOD, ["loading." + ".".join(["a"] * 50000) + "=1"],
            ["--set", "too deeply nested"], timeout=30, seconds=10)
refused_run("deep --set value", GOOD, ["loading.push_path=" + "[" * 30000 + "]" * 30000],
            ["loading.push_path", "too deeply nested"], timeout=30, seconds=10)

# 2, 3. Scene paths that are not a scene file of reasonable size.
args, _ = run_args("dev_zero", "/dev/zero")
refused("/dev/zero as the scene", args, ["/dev/zero", "regular file"], timeout=30, seconds=10)
big = scene("big", GOOD + ("# padding\n" * 120000))  # 1.2 MB of comments
args, _ = run_args("big", big)
refused("scene over 1 MiB", args, ["hostile_big.toml", "MiB"], timeout=30, seconds=10)
args, _ = run_args("directory", "/tmp")
refused("directory as the scene", args, ["/tmp", "regular file"], timeout=30, seconds=10)
# Command lines with words nothing takes, or a count that would wrap round.
refused("a second scene", ["run", GOOD_SCENE, GOOD_SCENE, "--out", out_dir("hostile_two")],
        ["unexpected argument", GOOD_SCENE])
refused("a word after a command without arguments", ["keys", "extra"], ["unexpected argument", "extra"])
refused("a PETSc option to a command that solves nothing", ["laws", "-snes_monitor"],
        ["unexpected argument", "-snes_monitor", "laws takes no arguments"])
# A PETSc option whose value PETSc cannot take, or a nonlinear solver that is
# not Newton's (ksponly ran one linear solve a step and said it converged, 8 %
# off): refused before the run.
for option in (["-ksp_type", "bogus"], ["-snes_max_it", "abc"], ["-snes_type", "ksponly"],
               ["-snes_type", "qn"]):
    refused(f"PETSc option {' '.join(option)}",
            ["run", GOOD_SCENE, "--out", out_dir("hostile_petsc"), "--quiet"] + option,
            ["PETSc option", option[1]], seconds=10)
# A preconditioner side that the default solver's flexible GMRES has not:
# refused with the key that has it (PETSc's own error, exit 1, came in the
# first solve). It is an option's error, not the scene's (OptionError).
err = refused("-ksp_pc_side left on the single-precision LU",
              ["run", GOOD_SCENE, "--out", out_dir("hostile_pc_side"), "--quiet", "-ksp_pc_side", "left"],
              ["-ksp_pc_side left", "solver.precision"], seconds=10)
check(err.startswith("pushout: error: -ksp_pc_side"),
      f"-ksp_pc_side left: not called the scene's error: {err[:80]!r}")
# The solver's refusals come before the run touches its folder: an earlier
# run's outputs there stay (they were deleted, the refusal coming from the
# solver's set-up).
kept = out_dir("hostile_solver_refusal_keeps")
p, _ = pushout(["run", GOOD_SCENE, "--out", kept, "--quiet"] + QUICK)
before = {f: os.path.getmtime(os.path.join(kept, f)) for f in ("curve.csv", "summary.json")}
for name, extra in (("-ksp_pc_side left", ["-ksp_pc_side", "left"]),
                    ("-ksp_pc_side left with -pc_type lu", ["-pc_type", "lu", "-ksp_pc_side", "left"]),
                    ("-ksp_pc_side left with -ksp_type gmres", ["-ksp_type", "gmres", "-ksp_pc_side", "left"]),
                    ("condensation on with -pc_type jacobi",
                     ["--set", "solver.condensation=on", "-pc_type", "jacobi"])):
    refused(f"{name}: into an earlier run's folder", ["run", GOOD_SCENE, "--out", kept, "--quiet"] + extra,
            ["-ksp_pc_side left" if "side" in name else "solver.condensation"])
    check(p.returncode == 0 and all(os.path.getmtime(os.path.join(kept, f)) == t for f, t in before.items()),
          f"{name}: the earlier run's curve.csv and summary.json stay")
# So are the refusals of cracks anywhere that need the mesh (a
# cracking.radius that takes in no element, a crack band too wide for one):
# they took the folder first, and an earlier run's outputs there were gone.
for name, sets, words in (
        ("a cracking radius short of the concrete", ["cracking.radius=10.2"],
         ["cracking.radius", "takes in no concrete element"]),
        ("a crack band too wide", ["cracking.c=150", "mesh.elements_per_quarter=8"],
         ["mm across", "lower cracking.c"])):
    set_args = [a for s in ["cracking.model=embedded"] + sets for a in ("--set", s)]
    refused(f"{name}: into an earlier run's folder",
            ["run", GOOD_SCENE, "--out", kept, "--quiet"] + set_args, words, seconds=10)
    check(all(os.path.getmtime(os.path.join(kept, f)) == t for f, t in before.items()),
          f"{name}: the earlier run's curve.csv and summary.json stay")
# A sweep refuses them before any case, as other values a run refuses
# (each case failed with exit 2, the sweep exit 3).
refused("a sweep with -ksp_pc_side left", ["sweep", GOOD_SCENE, "--vary", "interface.0.mu=0.2,0.3", "--out",
                                           out_dir("hostile_sweep_side"), "-ksp_pc_side", "left"] + QUICK,
        ["-ksp_pc_side left"])
refused("a negative --max-cases", ["sweep", GOOD_SCENE, "--vary", "interface.0.mu=0.2,0.3",
                                   "--max-cases", "-5", "--out", out_dir("hostile_cases")],
        ["--max-cases", "-5"])

# 4. Step counts that would run for days.
refused_run("steps 1e7", GOOD, ["loading.steps=10000000"], ["loading.steps", "100000"], seconds=10)
refused_run("corrosion steps 1e7", GOOD, ["corrosion.steps=10000000"], ["corrosion.steps"], seconds=10)
refused_run("steps per segment 1e7", GOOD, ["loading.steps_per_segment=10000000"],
            ["loading.steps_per_segment"], seconds=10)
refused_run("dissipation steps 1e7", GOOD, ["loading.dissipation_steps=10000000"],
            ["loading.dissipation_steps"], seconds=10)
refused_run("path steps 1e6", GOOD, ["loading.push_path=[0.0,0.01,0.0,0.01,0.0,0.01,0.0,0.01,0.0,0.01,0.0,0.01]",
                                     "loading.steps_per_segment=100000"],
            ["loading.steps_per_segment", "loading.push_path"], seconds=10)

# 5. Every number of an array checked as a scalar is.
refused_run("nan in push_path", GOOD, ["loading.push_path=[0.0,nan]"], ["loading.push_path", "nan"],
            seconds=10)
refused_run("inf in tube_center", GOOD, ["geometry.tube_center=[50.0,inf]"],
            ["geometry.tube_center", "inf"], seconds=10)

# 6. Values far outside what the model means.
refused_run("penalty 1e300", GOOD, ["interface.0.k=1e300"], ["interface.0.k", "out of range"], seconds=10)
refused_run("crack penalty 1e300", GOOD + "\n[[crack]]\nangle = 90.0\nk = 1e300\n", [], ["crack.0.k"],
            seconds=10)
refused_run("step growth 1e300", GOOD, ["loading.step_growth=1e300"], ["loading.step_growth"], seconds=10)
refused_run("step growth 5 over 200 steps", GOOD, ["loading.step_growth=5", "loading.steps=200"],
            ["loading.step_growth", "loading.steps"], seconds=10)
refused_run("temperature 1e6", GOOD, ["loading.temperature_change=1e6"],
            ["loading.temperature_change", "out of range"], seconds=10)

# 7. The model is small-displacement: a push beyond 10 % of the thickness.
for push in ("10", "19", "19.999", "2.5"):
    refused_run(f"push {push} mm", GOOD, [f"loading.push_displacement={push}"],
                ["loading.push_displacement", "10 %", "geometry.thickness"], seconds=10)
refused_run("push path 5 mm", GOOD, ["loading.push_path=[0.0,0.01,-5.0]"],
            ["loading.push_path", "10 %"], seconds=10)

# 8. Degenerate geometry.
refused_run("tube wall 1e-7 mm", GOOD, ["geometry.tube_inner_diameter=19.9999999"],
            ["geometry.tube_inner_diameter"], seconds=10)
refused_run("support gap 1e-7 mm", GOOD, ["geometry.support_inner_diameter=20.0000001"],
            ["geometry.support_inner_diameter"], seconds=10)

# 9. Sweeps: a key varied twice, and more cases than the limit.
sweep = ["sweep", GOOD_SCENE, "--out", out_dir("hostile_sweep"), "--quiet"]
refused("sweep: key varied twice", sweep + ["--vary", "interface.0.mu=0.1,0.2", "--vary", "interface.0.mu=0.3"],
        ["interface.0.mu", "--vary"], seconds=10)
values = ",".join(str(0.1 + i / 1000) for i in range(200))
err = refused("sweep: 40 000 cases", sweep + ["--vary", f"interface.0.mu={values}", "--vary",
                                            f"interface.0.k={','.join(str(1000 + i) for i in range(200))}"],
              ["40000", "--max-cases"], seconds=10)

# A sweep whose cases would all give the same curve, or run one twice: a
# varied key that no case reads (the seed without [cracking]), a value
# given twice.
refused("sweep: a key no case reads", sweep + ["--vary", "cracking.seed=1,2"],
        ["cracking.seed", "no case reads cracking.seed", "the same cases again", "cracking.model"], seconds=10)
refused("sweep: a value twice", sweep + ["--vary", "interface.0.mu=0.3,0.2,0.30"],
        ["interface.0.mu", "0.30 twice"], seconds=10)
refused("sweep: an array value twice", sweep + ["--vary", "geometry.tube_center=[50,50],[50.0, 50.0]"],
        ["geometry.tube_center", "[50.0, 50.0] twice"], seconds=10)
# A case whose elements are too wide for its crack band (the square's
# corners at 8 elements per quarter, c 150 1/mm), which needs the mesh, is
# refused before any case runs (it used to run case_000 and refuse case_001
# in its row, exit 3), in the words and numbers a run of that case gives
# (the sweep checks the whole mesh, the run each process's elements).
too_wide = ["--set", "cracking.model=embedded", "--set", "mesh.elements_per_quarter=8"]
err = refused("sweep: a crack band too wide", sweep + too_wide + ["--vary", "cracking.c=30,150"],
              ["case_001 (cracking.c=150)", "mm across", "lower cracking.c"], seconds=10)
run_err = pushout(["run", GOOD_SCENE, "--out", out_dir("hostile_too_wide"), "--quiet"] + too_wide
                  + ["--set", "cracking.c=150"])[0].stderr.strip()
check(err.split("): ", 1)[1] == run_err.split("error in scene: ", 1)[1],
      f"sweep and run refuse alike: {run_err[:200]!r}")
# So is a cracking radius that takes in no concrete element (the nearest
# centre is 10.78 mm from the axis on this mesh).
refused("sweep: a cracking radius short of the concrete",
        sweep + too_wide + ["--vary", "cracking.radius=30,10.2"],
        ["case_001 (cracking.radius=10.2)", "takes in no concrete element"], seconds=10)

# 10. Command-line usage errors: one line, exit 2, a hint.
refused("run without --out", ["run", GOOD_SCENE], ["--out", "pushout run --help"])
refused("no command", [], ["pushout --help"])
refused("unknown command", ["frobnicate", GOOD_SCENE], ["frobnicate", "pushout --help"])
refused("fit without --free", ["fit", GOOD_SCENE, "--data", "x.csv", "--out", out_dir("hostile_fit")],
        ["--free", "pushout fit --help"])
# A fit of a key the scene does not read (no corrosion stage), or with
# bounds that leave no value.
fit_data = os.path.join(OUT_ROOT, "hostile_fit.csv")
with open(fit_data, "w") as f:
    f.write("delta_mm,tau_MPa\n0.002,1.0\n0.004,1.5\n0.006,1.7\n")
fit = ["fit", GOOD_SCENE, "--data", fit_data, "--out", out_dir("hostile_fit"), "--quiet"]
refused("fit: a free key not read", fit + ["--free", "corrosion.beta"],
        ["corrosion.beta", "does not read", "corrosion.penetration = 0"], seconds=10)
# A key read only once another free key leaves 0 (the strength field's
# correlation length, freed with its coefficient of variation that starts at
# 0) passes the check: the fit can make the scene read it. It is refused
# here by the next check, two rows for two free values, which runs nothing.
two_rows = os.path.join(OUT_ROOT, "hostile_fit_two_rows.csv")
with open(two_rows, "w") as f:
    f.write("delta_mm,tau_MPa\n0.002,1.0\n0.004,1.5\n")
fit_cracking = ["fit", GOOD_SCENE, "--data", two_rows, "--out", out_dir("hostile_fit"), "--quiet",
                "--set", "cracking.model=embedded"]
refused("fit: a free key alone not read", fit_cracking + ["--free", "cracking.correlation_length"],
        ["cracking.correlation_length", "does not read", "cracking.strength_cov = 0"], seconds=10)
refused("fit: a free key read once another leaves 0",
        fit_cracking + ["--free", "cracking.strength_cov", "--free", "cracking.correlation_length"],
        ["2 rows", "2 free values"], seconds=10)
# A fit whose start's crack band is too wide for its elements is refused
# before any run, in the run's words (it used to run two refused runs and
# exit 3 with CONVERGED_GATOL), and leaves no folder.
too_wide_out = out_dir("hostile_fit_too_wide")
fit_too_wide = ["fit", GOOD_SCENE, "--data", fit_data, "--out", too_wide_out, "--quiet",
                "--free", "cracking.f_t"] + too_wide
err = refused("fit: a crack band too wide", fit_too_wide + ["--set", "cracking.c=150"],
              ["mm across", "lower cracking.c"], seconds=10)
check(err.split("pushout fit: error: ", 1)[-1] == run_err.split("error in scene: ", 1)[1]
      and not os.path.exists(too_wide_out),
      f"fit and run refuse alike, no folder: {err[:200]!r}")
refused("fit: bounds with lo above hi", fit + ["--free", "interface.0.mu", "--bounds", "interface.0.mu=0.5:0.1"],
        ["interface.0.mu", "lo is not below hi"], seconds=10)
# A -tao_* option TAO cannot take (a line search it has not, a value that
# is no number) refuses the fit before any run, and leaves no folder.
tao_out = out_dir("hostile_fit_tao_option")
fit_tao = ["fit", GOOD_SCENE, "--data", fit_data, "--out", tao_out, "--quiet", "--free", "interface.0.mu"]
refused("fit: a line search TAO has not", fit_tao + ["-tao_ls_type", "mt"],
        ["a PETSc option", "TaoLineSearch type mt"], seconds=10)
refused("fit: a TAO option that is no number", fit_tao + ["-tao_max_it", "many"],
        ["a PETSc option", "many"], seconds=10)
# An option of Armijo's line search alone (the one of fits with cracks):
# checked on the solver as a fit with cracks sets it up.
refused("fit: an Armijo option that is no number", fit_tao + ["-tao_ls_armijo_beta", "half"],
        ["a PETSc option", "half"], seconds=10)
check(not os.path.exists(tao_out), "a fit refused for its TAO option leaves no folder")
# With another error of the fit's input, one of the two, exit 2 (it was both
# lines, then MPI_Abort and exit 1).
refused("fit: a TAO option beside a free key the scene lacks",
        fit_tao[:-1] + ["interface.0.muu", "-tao_ls_type", "foo"], ["a PETSc option"], seconds=10)
# Any command reads the -tao_* options (as a fit's solver would) once it
# ends: a run with one TAO cannot take is refused before it starts (it ran,
# then ended in MPI_Abort, exit 1).
args, out = run_args("tao_option", GOOD_SCENE, extra=["-tao_type", "nonesuch"])
refused("run: a TAO type PETSc has not", args, ["a PETSc option", "Tao type nonesuch"], seconds=10)
# A TAO of another type than a fit's (as another -snes_type): its stop
# tests and counts read BNLS's iterations.
args, out = run_args("tao_type_other", GOOD_SCENE, extra=["-tao_type", "lmvm"])
refused("run: a TAO type not a fit's", args, ["a PETSc option", "-tao_type lmvm", "bnls"], seconds=10)
for cmd in ([], ["run"], ["sweep"]):
    p, _ = pushout(cmd + ["--help"])
    # (the top level's help names the subcommands, not their options)
    said = "--out" if cmd else "SUBCOMMAND"
    check(p.returncode == 0 and said in p.stdout, f"pushout {' '.join(cmd)} --help: exit 0, help")
# An answer standard output cannot take (a full disk) is an I/O error,
# exit 1, said on stderr (it was exit 0).
if os.path.exists("/dev/full"):
    for cmd in ("keys", "laws"):
        with open("/dev/full", "w") as full:
            p = subprocess.run([PUSHOUT, cmd], stdout=full, stderr=subprocess.PIPE, text=True, timeout=60)
        check(p.returncode == 1 and "cannot write to standard output" in p.stderr,
              f"pushout {cmd} > /dev/full: exit {p.returncode}, {p.stderr.strip()[:100]!r}")
p, _ = pushout(["run", "--help"])
check("--allow-unused-petsc-options" in p.stdout, "run --help documents --allow-unused-petsc-options")

# 11. Typos: an unknown --option, and a PETSc option nothing read.
for typo in (["--sett", "loading.steps=3"], ["--froce"], ["--bogus"]):
    args, out = run_args("typo", GOOD_SCENE, extra=typo)
    refused(f"unknown option {typo[0]}", args, [typo[0], "pushout run --help"], seconds=10)
args, out = run_args("petsc_typo", GOOD_SCENE, extra=QUICK + ["-snes_monitr"])
refused("unused PETSc option", args, ["-snes_monitr", "--allow-unused-petsc-options"])
# summary.json says so beside how the run ended (converged: its curve is whole).
s = summary(out)
check(s["converged"] and s.get("unused_petsc_options") == ["-snes_monitr"],
      f"summary.json lists the unused option: {s.get('unused_petsc_options')!r}")
args, out = run_args("petsc_allowed", GOOD_SCENE,
                     extra=QUICK + ["-snes_monitr", "--allow-unused-petsc-options"])
p, _ = pushout(args)
check(p.returncode == 0 and "-snes_monitr" in p.stderr, "unused PETSc option allowed: exit 0, a warning")
check(summary(out).get("unused_petsc_options") == ["-snes_monitr"],
      "summary.json lists an allowed unused option too")
# The search for unused options at the end opens no file an option names:
# it made the solvers again, which emptied -snes_monitor's (and a fit's
# -tao_monitor's) file.
monitor = os.path.join(out_dir("hostile_monitor_file"), "snes.txt")
os.makedirs(os.path.dirname(monitor), exist_ok=True)
args, out = run_args("petsc_monitor_kept", GOOD_SCENE,
                     extra=QUICK + ["-snes_monitor", "ascii:" + monitor, "-snes_monitr",
                                    "--allow-unused-petsc-options"])
p, _ = pushout(args)
kept = open(monitor).read() if os.path.exists(monitor) else ""
check(p.returncode == 0 and "SNES Function norm" in kept,
      f"-snes_monitor's file kept beside an unused option: exit {p.returncode}, {len(kept)} bytes")
# In a sweep the typo is said after the first case, before the next runs
# (a long sweep need not run to its end to tell), and fails it at the end.
p = subprocess.run([PUSHOUT, "sweep", GOOD_SCENE, "--out", out_dir("hostile_sweep_typo"),
                    "--vary", "interface.0.mu=0.3,0.4", "-snes_monitr"] + QUICK,
                   stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=60)
lines = p.stdout.splitlines()
warned = [i for i, line in enumerate(lines) if "warning: PETSc option -snes_monitr not read by "
          "case_000" in line]
second = [i for i, line in enumerate(lines) if line.startswith("sweep: case_001")]
check(p.returncode == 2 and warned and second and warned[0] < second[0]
      and "-snes_monitr not read by any solver" in lines[-1],
      f"a sweep's PETSc typo said after its first case: exit {p.returncode}, {lines[-3:]!r}")
# Options of the default solver path pass, read or not by this scene's.
args, out = run_args("petsc_ok", GOOD_SCENE, extra=QUICK + ["-snes_monitor", "-ksp_type", "gmres",
                                                            "-pc_type", "lu", "-snes_rtol", "1e-9",
                                                            "-mat_mumps_icntl_14", "50"])
p, _ = pushout(args)
check(p.returncode == 0, f"PETSc options of the solver pass: exit {p.returncode} {p.stderr[-300:]!r}")
# An iterative solver leaves the program's own defaults for LU unread
# (-pc_factor_mat_solver_type mumps): not the user's, not reported.
args, out = run_args("petsc_gamg", GOOD_SCENE, extra=QUICK + ["-ksp_type", "gmres", "-pc_type", "gamg",
                                                              "--set", "solver.condensation=off"])
p, _ = pushout(args)
check(p.returncode == 0 and "not read" not in p.stderr,
      f"the program's own PETSc defaults are not reported: exit {p.returncode} {p.stderr[-300:]!r}")
print("hostile inputs refused")

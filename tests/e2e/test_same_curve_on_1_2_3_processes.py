"""The same executable under mpirun gives the same curve on 1, 2 and 3
processes (3: an uneven split; 1 process condenses the bulk, more do not) to
the bound of Newton's tolerance on the two runs (common.newton_bound: each
run is exact only to it, whatever order its processes sum in), for a friction push-out, a friction + exponential-softening
push-out (quarter model), the same with the tube's top free in the thermal
step, the same with path following (arc length), the
same with the triquadratic bulk, a corrosion stage before the push (its
corrosion.csv too), the corroded demo with a crack plane, the corroded demo
with cracks anywhere in the concrete (IMPL-EX, a random field), a push path that
unloads to zero force and reloads, and a single joint; the interface pressure
columns (global integrals of the interface traction field) agree too, and
the XDMF output is written once."""
import os
import subprocess
import sys

from common import (OUT_ROOT, TIGHT_NEWTON, check, corrosion, curve, mpi_env, mpirun, newton_bound, out_dir,
                    solved_unknowns, summary)

PUSHOUT = sys.argv[1]
MPIRUN = mpirun()
SOURCE = os.environ["PUSHOUT_SOURCE_DIR"]
coarse = ["mesh.elements_per_quarter=4", "mesh.elements_through_thickness=2"]
cases = {
    "friction": ("pushout_friction.toml", coarse + ["loading.steps=5", "output.xdmf=true"]),
    "friction_adhesion": ("pushout_friction_adhesion.toml",
                          coarse + ["loading.steps=12", "loading.push_displacement=0.06"]),
    # The tube's top free in the thermal step, held in the push: the push's
    # first step adds constraints on the processes that hold the top only
    # (this hung until every process agreed that the constraints changed).
    "top_free": ("pushout_friction_adhesion.toml",
                 coarse + ["loading.steps=12", "loading.push_displacement=0.06",
                           "loading.thermal_tube_top=free"]),
    "arc_length": ("pushout_friction_adhesion.toml",
                   coarse + ["loading.steps=10", "loading.push_displacement=0.05",
                             "loading.control=arc_length"]),
    "degree_2": ("pushout_friction_adhesion.toml",
                 coarse + ["mesh.degree=2", "loading.steps=6", "loading.push_displacement=0.03"]),
    "corrosion": ("pushout_friction.toml",
                  coarse + ["loading.steps=4", "interface.0.law=oxide_friction",
                            "corrosion.penetration=0.002", "corrosion.steps=4"]),
    "cracks": ("pushout_corroded.toml",
               coarse + ["loading.steps=3", "corrosion.steps=6", "corrosion.penetration=0.03"]),
    "push_path": ("pushout_friction.toml",
                  coarse + ["loading.push_path=[0.0,0.01,0.0,0.02]", "loading.steps_per_segment=4",
                            "loading.unload_to=zero_force"]),
    "single_joint": ("single_joint_fig9.toml", []),
    # Cracks anywhere in the concrete (IMPL-EX, the random field): at
    # TIGHT_NEWTON, so that no point's cracking hinges on the tolerance, and
    # its steps (cut by IMPL-EX's error) are the same.
    "embedded": ("pushout_corroded_cracking.toml",
                 ["mesh.elements_per_quarter=8", "mesh.elements_through_thickness=2",
                  "corrosion.penetration=0.012", "corrosion.steps=4", "loading.steps=2",
                  "loading.push_displacement=0.01"]),
}

# Options after the scene (PETSc's), per case.
petsc = {"embedded": TIGHT_NEWTON}
# The cases with a corrosion stage: their corrosion.csv is compared too.
corroded = ("corrosion", "cracks", "embedded")
for name, (scene, sets) in cases.items():
    curves, unknowns = {}, {}
    for n in (1, 2, 3):
        out = out_dir(f"mpi_{name}_{n}")
        cmd = [MPIRUN, "--allow-run-as-root", "--oversubscribe", "-n", str(n), PUSHOUT, "run",
               os.path.join(SOURCE, "demo", scene), "--out", out, "--quiet", "--set", "output.plot=false"]
        for s in sets:
            cmd += ["--set", s]
        cmd += petsc.get(name, [])
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=900, env=mpi_env(n))
        check(p.returncode == 0, f"{name} on {n} processes: exit {p.returncode} {p.stderr[-500:]}")
        check(summary(out)["processes"] == n, f"{name}: summary says {n} processes")
        # One process condenses the bulk (solver.condensation auto); more do
        # not, nor does cracking concrete, whose bulk is not linear.
        check((summary(out)["condensed_dofs"] > 0) == (n == 1 and name != "embedded"),
              f"{name}: {summary(out)['condensed_dofs']} condensed dofs on {n} processes")
        # The push, and the corrosion stage before it (if any), as one table.
        curves[n] = curve(out) + (corrosion(out) if name in corroded else [])
        unknowns[n] = solved_unknowns(summary(out))
    ref = curves[1]
    for n in (2, 3):
        check(len(curves[n]) == len(ref), f"{name}: {n} processes, same number of steps")
        worst, columns = 0.0, set()
        for c in ref[0].keys() | ref[-1].keys():
            if c in ("step", "newton_iterations", "cuts", "wall_s"):
                continue
            rows = [(a[c], b[c]) for a, b in zip(curves[n], ref) if c in b]
            columns.add(c)
            scale = max(abs(b) for _, b in rows) or 1.0
            worst = max(worst, max(abs(a - b) for a, b in rows) / scale)
        tol = newton_bound(len(ref), max(unknowns[1], unknowns[n]))
        check(worst <= tol, f"{name}: {n} vs 1 process, max relative difference {worst:.1e} <= "
                            f"{tol:.1e} over {', '.join(sorted(columns))}")
out = os.path.join(OUT_ROOT, "mpi_friction_3")
for f in ("fields.xdmf", "interface.xdmf"):
    text = open(os.path.join(out, f)).read()
    check(text.count("<Domain>") == 1 and "Grid" in text, f"{f} from 3 processes is one dataset")

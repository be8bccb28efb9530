"""Helpers for the whole-pipeline tests: the scene pieces they share, and
running build/pushout (scripts/pushout_runs.py) with a failure as a test
failure."""
import math
import os
import shutil
import sys

PUSHOUT = sys.argv[1] if len(sys.argv) > 1 else None
SOURCE = os.environ.get("PUSHOUT_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
OUT_ROOT = os.environ.get("PUSHOUT_TEST_OUT", "/tmp/pushout-test-output")
sys.path.insert(0, os.path.join(SOURCE, "scripts"))
import pushout_runs  # noqa: E402
from pushout_runs import corrosion, summary  # noqa: E402

# The tests read outputs through these.
curve = pushout_runs.curve


# Scene pieces the tests share (TOML text).
COARSE_MESH = "[mesh]\nelements_per_quarter = 4\nelements_through_thickness = 2\n"
FRICTION_2 = '[[interface]]\nlaw = "friction"\nk = 1000.0\nmu = 0.4\n'  # Table 1
EXP_SOFT = '[[interface]]\nlaw = "exponential_softening"\nk = 1000.0\nf_t = 3.0\nc = 25.0\n'
# Thermal step, then through the adhesion peak (with FRICTION_2 + EXP_SOFT).
THROUGH_PEAK = "[loading]\ntemperature_change = -25.0\npush_displacement = 0.05\nsteps = 10\n"
# Snap-back after the adhesion peak: an 80 mm slice (with FRICTION_2 and an
# exponential softening layer of c = 100 1/mm) pushed 0.04 mm in 20 steps.
SNAP_BACK_LOADING = """
[geometry]
thickness = 80.0
[loading]
temperature_change = -25.0
push_displacement = 0.04
steps = 20
"""
# Lame shrink fit: a circular slice (outer diameter 100 mm) shrinks onto the
# tube through a friction interface; its plateau is tau = mu p (test_friction_plateau_matches_lame).
LAME = """
[geometry]
outer_shape = "circle"
width = 100.0
[[interface]]
law = "friction"
k = 1000.0
mu = 0.4
[loading]
temperature_change = -25.0
push_displacement = 0.01
steps = 4
"""



def corroded_ring(mesh, x, steps, mu=0.4, push=0.01, push_steps=4, beta=2.0, oxide_bulk=2000.0):
    """The circular slice of LAME (outer diameter 100 mm) without the thermal
    step, an oxide_friction interface (k 1000 N/mm^3), corroded to x [mm] in
    `steps`, then pushed by `push` [mm] (TOML text; test_corrosion_matches_thick_cylinder,
    test_cover_cracks_match_closed_forms)."""
    return mesh + f"""
[geometry]
outer_shape = "circle"
width = 100.0
[[interface]]
law = "oxide_friction"
k = 1000.0
mu = {mu}
[loading]
temperature_change = 0.0
push_displacement = {push}
steps = {push_steps}
[corrosion]
penetration = {x}
steps = {steps}
beta = {beta}
oxide_bulk = {oxide_bulk}
"""


def cracking_corroded_demo(x, steps, f_t=3.0, cov=0.15, seed=None, xdmf=False):
    """demo/pushout_corroded.toml on a coarse mesh (8 per quarter, 2 through
    the thickness) with [cracking] model = "embedded" (f_t [MPa], c 30 1/mm,
    strength_cov `cov`, correlation length 5 mm) instead of its crack plane,
    corroded to x [mm] in `steps`, then pushed 5 um in one step (TOML text;
    test_cover_crack_read_at_the_face, test_corroded_slice_picks_its_cover_crack)."""
    with open(os.path.join(SOURCE, "demo", "pushout_corroded.toml")) as f:
        demo = f.read()
    scene = demo[:demo.index("[[crack]]")] + demo[demo.index("[loading]"):]
    scene = (scene.replace("elements_per_quarter = 16", "elements_per_quarter = 8")
             .replace("elements_through_thickness = 8", "elements_through_thickness = 2")
             .replace("penetration = 0.05", f"penetration = {x}")
             .replace("steps = 25", f"steps = {steps}").replace("steps = 40", "steps = 1")
             .replace("push_displacement = 0.2", "push_displacement = 0.005")
             .replace("xdmf = false", f"xdmf = {'true' if xdmf else 'false'}"))
    return scene + (f'\n[cracking]\nmodel = "embedded"\nf_t = {f_t}\nc = 30.0\n'
                    f"strength_cov = {cov}\ncorrelation_length = 5.0\n"
                    + (f"seed = {seed}\n" if seed is not None else ""))


# The slice's default layout of the graded concrete, for a check tuned on
# it that reads a demo whose [mesh] might one day say otherwise
# (docs/cracking.md, "Radial graded lines").
BLOCKS_MESH = ["mesh.graded_lines=blocks", "mesh.graded_refinement=near_tube"]


# Newton's tolerances (NewtonSolver::set_default_options): a step converges
# when |F|_2 <= snes_atol [N] or <= snes_rtol |F0|_2, F0 the residual the
# step started with.
SNES_RTOL = 1e-10
# ... and with IMPL-EX cracks ([cracking] integration = "implex"), whose
# Newton and GMRES stop there by default (NewtonSolver::implex_rtol).
IMPLEX_RTOL = 1e-6
# The options that put an IMPL-EX run back at SNES_RTOL: a comparison of its
# cracked points or step cuts across processes needs them, since a point
# whose stress is within the tolerance of its strength may crack in one run
# and not the other.
TIGHT_NEWTON = ["-snes_rtol", str(SNES_RTOL), "-ksp_rtol", str(SNES_RTOL)]


def newton_bound(steps, unknowns, rtol=SNES_RTOL):
    """The largest relative difference of a curve column (to its largest
    magnitude) that two runs may show when each converged every one of
    `steps` steps to Newton's tolerance on a system of `unknowns` (the
    jumps, condensed, or the whole model's dofs), in whatever order their
    processes, threads or precision summed: a residual F moves a sum of
    nodal forces (P, a reaction, the pressure's integral) by at most
    sqrt(unknowns) |F|_2 <= sqrt(unknowns) snes_rtol |F0|_2, and a step's
    initial out-of-balance |F0| is at most the forces it changes (the
    column's scale); a path-dependent law carries each step's error on to
    the next (at most `steps` of them), and each of the two runs has its
    own: 2 steps sqrt(unknowns) snes_rtol (`rtol`)."""
    return 2 * steps * math.sqrt(unknowns) * rtol


def solved_unknowns(s):
    """The size of the system Newton ran on, from a summary.json."""
    return s["condensed_dofs"] or s["dofs"]


def mpirun():
    """mpirun's path. Open MPI comes with libdolfinx-dev, which
    scripts/setup.sh installs, and the program is made for MPI: a machine
    without it fails the tests that need it rather than skipping them."""
    path = shutil.which("mpirun")
    if not path:
        raise SystemExit("FAILED: mpirun not found (Open MPI comes with libdolfinx-dev, which "
                         "scripts/setup.sh installs)")
    return path


def mpi_env(n):
    """The environment of a run on n processes under mpirun (shared memory
    without single-copy, which a container may refuse). More processes
    than cores (3 on a machine of two) wait for each other's messages by
    polling: without yielding the core to the process that has work, each
    exchange waits out a slice of the scheduler (the friction_adhesion
    case on 3 processes of 2 cores, machine otherwise idle: 84 s, against
    1.0 s when yielding)."""
    env = dict(os.environ, OMPI_MCA_btl_vader_single_copy_mechanism="none")
    if n > len(os.sched_getaffinity(0)):  # the cores it may use, as nproc counts them
        env["OMPI_MCA_mpi_yield_when_idle"] = "1"
    return env


def out_dir(name):
    d = os.path.join(OUT_ROOT, name)
    shutil.rmtree(d, ignore_errors=True)
    return d


def run(scene, out, sets=(), extra=(), check=True, mpirun=None, quiet=True):
    """Runs a scene (a path, or TOML text written to out/../NAME.toml);
    `mpirun`: on that many processes; `quiet` false: with the progress
    output (stdout)."""
    if "\n" in scene or "=" in scene:
        os.makedirs(OUT_ROOT, exist_ok=True)
        path = os.path.join(OUT_ROOT, os.path.basename(out.rstrip("/")) + ".toml")
        with open(path, "w") as f:
            f.write(scene)
        scene = path
    try:
        p = pushout_runs.run(PUSHOUT, scene, out, sets, extra, timeout=1200, check=check,
                             mpirun=mpirun, quiet=quiet)
    except pushout_runs.RunError as e:
        raise SystemExit(f"FAILED: {e}")
    if p is None:
        raise SystemExit(f"FAILED: {scene} did not finish in 1200 s")
    return p


def check(cond, message):
    if not cond:
        raise SystemExit("FAILED: " + message)
    print("ok: " + message)


def check_one_and_two_processes(scene, name, sets, extra=()):
    """Runs `scene` at SNES_RTOL (TIGHT_NEWTON) on 1 and 2 processes (into
    out_dir(NAME_np1) and out_dir(NAME_np2)) and checks that they give the
    same corrosion rows, cracked points and p(x), p to Newton's bound
    (newton_bound over the rows, of the largest p). `extra`: more options of
    the one-process run. Returns that run's process and folder."""
    one, two = out_dir(name + "_np1"), out_dir(name + "_np2")
    p_one = run(scene, one, sets=sets, extra=TIGHT_NEWTON + list(extra))
    run(scene, two, sets=sets, extra=TIGHT_NEWTON, mpirun=2)
    r1, r2 = corrosion(one), corrosion(two)
    dp = max(abs(a["p_MPa"] - b["p_MPa"]) for a, b in zip(r1, r2))
    bound = p_bound(r1, one)
    check(len(r1) == len(r2) and dp <= bound and
          all(a["cracked_points"] == b["cracked_points"] for a, b in zip(r1, r2)),
          f"1 and 2 processes: {len(r1)} and {len(r2)} rows, the same cracked points, p within "
          f"{dp:.1e} MPa (Newton's bound {bound:.1e})")
    return p_one, one


def p_bound(rows, out, rtol=SNES_RTOL):
    """Newton's bound [MPa] on the difference of corrosion.csv's p between
    two runs of `rows` (the rows of one of them, its folder `out`): each
    converged every step to `rtol`, so newton_bound over the rows, of the
    largest |p|."""
    return (newton_bound(len(rows), solved_unknowns(summary(out)), rtol)
            * max(abs(r["p_MPa"]) for r in rows))

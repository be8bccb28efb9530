"""Malformed scenes and command lines: each must exit non-zero (not by a
signal) with one message naming the problem, and leave no results behind."""
import os

from common import COARSE_MESH, FRICTION_2, SOURCE, check, out_dir, run

GOOD = COARSE_MESH + FRICTION_2
JOINT = open(os.path.join(SOURCE, "demo", "single_joint_fig6.toml")).read()

cases = [
    # (name, scene text, --set overrides, expected words in stderr)
    ("toml syntax", GOOD + "\n[loading\n", [], ["TOML syntax error", "line"]),
    ("unknown key", GOOD + "\n[geometry]\nwidht = 100.0\n", [], ["geometry.widht"]),
    ("unknown section", GOOD + "\n[geometri]\nwidth = 100.0\n", [], ["geometri"]),
    ("wrong type", GOOD + '\n[geometry]\nwidth = "wide"\n', [], ["geometry.width", "number"]),
    ("integer expected", GOOD + "\n[loading]\nsteps = 2.5\n", [], ["loading.steps", "integer"]),
    ("unknown law", GOOD.replace('"friction"', '"glue"'), [], ["interface.0.law", "glue"]),
    ("unknown law key", GOOD.replace("mu = 0.4", "mu = 0.4\nphi = 3.0"), [], ["interface.0.phi"]),
    ("negative k", GOOD.replace("k = 1000.0", "k = -1000.0"), [], ["interface.0.k", "out of range"]),
    ("zero k", GOOD.replace("k = 1000.0", "k = 0.0"), [], ["interface.0.k"]),
    ("negative mu", GOOD.replace("mu = 0.4", "mu = -0.1"), [], ["interface.0.mu"]),
    ("zero steps", GOOD + "\n[loading]\nsteps = 0\n", [], ["loading.steps"]),
    ("zero mesh count", GOOD.replace("elements_per_quarter = 4", "elements_per_quarter = 0"), [],
     ["mesh.elements_per_quarter"]),
    ("tube wall inverted", GOOD + "\n[geometry]\ntube_inner_diameter = 25.0\n", [], ["tube_inner_diameter"]),
    ("support hole smaller than tube", GOOD + "\n[geometry]\nsupport_inner_diameter = 15.0\n", [],
     ["support_inner_diameter"]),
    ("tube outside slice", GOOD + "\n[geometry]\ntube_center = [5.0, 50.0]\n", [], ["tube_center"]),
    ("negative E", GOOD + "\n[concrete]\nE = -3.0\n", [], ["concrete.E"]),
    ("poisson 0.5", GOOD + "\n[steel]\nnu = 0.5\n", [], ["steel.nu"]),
    ("unsupported degree", GOOD.replace("[mesh]", "[mesh]\ndegree = 3"), [], ["mesh.degree"]),
    ("degree 2 single joint", '[model]\ntype = "single_joint"\n[mesh]\ndegree = 2\n', [],
     ["mesh.degree", "pushout"]),
    ("bad choice", GOOD + '\n[geometry]\nouter_shape = "hexagon"\n', [], ["geometry.outer_shape", "square"]),
    ("key of the other model type", '[model]\ntype = "single_joint"\n[geometry]\nwidth = 3.0\n', [],
     ["geometry.width", "single_joint"]),
    ("corrosion without oxide law", GOOD + "\n[corrosion]\npenetration = 0.01\n", [],
     ["corrosion.penetration", "oxide_friction"]),
    ("beta below 1", GOOD + "\n[corrosion]\nbeta = 0.5\n", [], ["corrosion.beta"]),
    # A depth typed in um (50 for 0.05 mm): deeper than the tube's wall (2 mm).
    ("corrosion through the tube wall",
     GOOD.replace('"friction"', '"oxide_friction"') + "\n[corrosion]\npenetration = 50.0\n", [],
     ["corrosion.penetration", "tube's wall", "0.05"]),
    ("crack without angle", GOOD + "\n[[crack]]\nf_t = 3.0\n", [], ["crack.0.angle"]),
    ("crack angle word", GOOD + '\n[[crack]]\nangle = "cover"\n', [], ["crack.0.angle", "nearest_face"]),
    ("cracks too close", GOOD + "\n[[crack]]\nangle = 10.0\n[[crack]]\nangle = 12.0\n", [],
     ["crack.1.angle", "crack.0.angle"]),
    ("nearest_face in a circle", GOOD + '\n[geometry]\nouter_shape = "circle"\n[[crack]]\n'
     'angle = "nearest_face"\n', [], ["crack.0.angle", "circular"]),
    ("crack law parameter", GOOD + "\n[[crack]]\nangle = 90.0\nmu = 0.3\n", [], ["crack.0.mu"]),
    ("crack in a single joint", '[model]\ntype = "single_joint"\n[[crack]]\nangle = 0.0\n', [],
     ["crack", "single_joint"]),
    ("radial lines with crack planes", GOOD + "\n[[crack]]\nangle = 90.0\n",
     ["mesh.graded_lines=radial"], ["mesh.graded_lines", "[[crack]]"]),
    ("cracking radius in the tube", GOOD + '\n[cracking]\nmodel = "embedded"\nradius = 5.0\n', [],
     ["cracking.radius", "no concrete"]),
    ("cracking radius short of the concrete",
     GOOD + '\n[cracking]\nmodel = "embedded"\nradius = 10.01\n', [],
     ["cracking.radius", "nearest element centre"]),
    ("a section given a value", GOOD, ["cracking=embedded"], ["'cracking'", "[cracking]", "model"]),
    ("cracking seed beyond 2^53", GOOD + '\n[cracking]\nmodel = "embedded"\n',
     ["cracking.seed=9007199254740993"], ["cracking.seed", "9007199254740993", "out of range"]),
    # 1e-320 made the strength field NaN, and nothing cracked (exit 0).
    ("correlation length of nothing", GOOD + '\n[cracking]\nmodel = "embedded"\nstrength_cov = 0.1\n',
     ["cracking.correlation_length=1e-320"], ["cracking.correlation_length", ">= 0.001"]),
    # A corrosion step lasts the push's first step's pseudo-time: none
    # without a push, and viscous damage stayed 0 (the uncracked answer).
    ("viscous corrosion without a push",
     COARSE_MESH + '[[interface]]\nlaw = "oxide_friction"\nk = 1000.0\nmu = 0.4\n'
     '[corrosion]\npenetration = 0.01\n[cracking]\nmodel = "embedded"\nviscosity = 0.001\n',
     ["loading.push_displacement=0"],
     ["'cracking.viscosity'", "'loading.push_displacement' = 0", "corrosion step"]),
    ("viscous corrosion before a push path standing still",
     COARSE_MESH + '[[interface]]\nlaw = "oxide_friction"\nk = 1000.0\nmu = 0.4\n'
     '[corrosion]\npenetration = 0.01\n[cracking]\nmodel = "embedded"\nviscosity = 0.001\n',
     ["loading.push_path=[0.0, 0.0, 0.01]"],
     ["'cracking.viscosity'", "'loading.push_path''s first segment", "corrosion step"]),
    # A ring of concrete 1e-6 mm wide outside the support (the mesher
    # corrupted memory: a segfault and a hang), one outside the tube, a
    # slice typed in cm, a tube in um, a bore of nothing, a length beyond
    # any slice (gmsh asked on stdin), alpha typed in 1e-6/degC.
    ("support ring of nothing", GOOD, ["geometry.support_inner_diameter=99.999998"],
     ["'geometry.support_inner_diameter' = 99.999998", "'geometry.width' = 100"]),
    ("tube at the edge", GOOD, ["geometry.tube_center=[15.00001,50]"],
     ["'geometry.support_inner_diameter' = 30", "[15.00001, 50]"]),
    ("slice in cm", GOOD, ["geometry.width=10", "geometry.tube_center=[5.0,5.0]"],
     ["the tube", "'geometry.width' = 10", "in mm"]),
    ("tube in um", GOOD, ["geometry.tube_outer_diameter=0.02", "geometry.tube_inner_diameter=0.016",
                          "geometry.support_inner_diameter=0.03"],
     ["'geometry.width' = 100", "5000 times", "in mm"]),
    ("bore of nothing", GOOD, ["geometry.tube_inner_diameter=1e-7"],
     ["'geometry.tube_inner_diameter'", "at least 0.2 mm"]),
    ("slice beyond 10 m", GOOD, ["geometry.thickness=1e30"], ["'geometry.thickness'", "out of range"]),
    ("alpha in 1e-6/degC", GOOD, ["concrete.alpha=10"], ["'concrete.alpha'", "out of range"]),
    # An expansion no iron oxide has (reported 2 to 6.5).
    ("oxide beyond any iron oxide", GOOD, ["corrosion.beta=20"], ["corrosion.beta", "<= 7"]),
    # 2^-50 of a step vanished in the round-off of the step's position.
    ("cuts below round-off", GOOD, ["loading.max_cuts=50"], ["loading.max_cuts", "<= 40"]),
    # ... and at step 100000 below 2^-27 of a step (2^8 of its round-off).
    ("cuts below a long stage's round-off", GOOD, ["loading.steps=100000", "loading.max_cuts=30"],
     ["'loading.max_cuts' = 30", "100000 nominal steps", "at most 27"]),
    ("crack band too wide where the field raises f_t",
     GOOD.replace("elements_per_quarter = 4", "elements_per_quarter = 8") +
     '\n[cracking]\nmodel = "embedded"\nstrength_cov = 0.8\n', [],
     ["cracking.strength_cov", "raises f_t to", "times its mean", "mean f_t"]),
    # A softening so steep that the largest elements (the square's corners)
    # would snap back: where the element is and how large, and what helps.
    ("crack band too wide at the mean f_t",
     GOOD.replace("elements_per_quarter = 4", "elements_per_quarter = 8") +
     '\n[cracking]\nmodel = "embedded"\nc = 150.0\n', [],
     ["mm across", "lower cracking.c", "cracking.radius"]),
    # Steps that grow where the control takes equal steps of its own.
    ("step growth under arc length", GOOD, ["loading.control=arc_length", "loading.step_growth=2"],
     ["loading.step_growth", "arc_length"]),
    ("step growth where dissipation control runs", GOOD + '\n[cracking]\nmodel = "embedded"\n',
     ["loading.control=auto", "loading.step_growth=2"], ["loading.step_growth", "dissipation control"]),
    # A push the control cannot run, a path the device cannot follow.
    ("push to 0 under auto", GOOD, ["loading.control=auto", "loading.push_displacement=0.0"],
     ["'loading.control'", "loading.push_displacement"]),
    ("pull under arc length", GOOD, ["loading.control=arc_length", "loading.push_displacement=-0.01"],
     ["'loading.control'", "arc_length", "loading.push_displacement"]),
    ("device that cannot pull, pulled", GOOD,
     ["loading.push_path=[0.0, -0.01, 0.0]", "loading.unload_to=zero_force"],
     ["loading.unload_to", "cannot pull", "loading.push_path"]),
    ("circle with its tube off centre", GOOD,
     ["geometry.outer_shape=circle", "geometry.tube_center=[30.0, 50.0]"],
     ["geometry.tube_center", "concentric"]),
    # The single joint's shear path, checked as a push path is.
    ("shear path of one value", JOINT, ["loading.shear_path=[0.0]"],
     ["loading.shear_path", "no segment"]),
    ("shear path not from 0", JOINT, ["loading.shear_path=[0.1, 0.2]"],
     ["loading.shear_path", "must start at 0"]),
    ("shear path of too many steps", JOINT,
     ["loading.shear_path=[0.0, 0.01, 0.0, 0.01]", "loading.steps_per_segment=40000"],
     ["loading.steps_per_segment", "loading.shear_path", "120000 steps"]),
    ("--set missing layer", GOOD, ["interface.3.mu=0.2"], ["interface.3.mu"]),
    ("--set unknown key", GOOD, ["loading.stepz=3"], ["loading.stepz"]),
    ("--set malformed", GOOD, ["loading.steps"], ["loading.steps", "key=value"]),
    ("--set wrong type", GOOD, ["loading.steps=many"], ["loading.steps"]),
    ("--set integer beyond 64 bits", GOOD, ["loading.steps=99999999999999999999"],
     ["loading.steps", "99999999999999999999", "64 bits"]),
]

for name, text, sets, words in cases:
    out = out_dir("bad_" + name.replace(" ", "_").replace("-", ""))
    p = run(text, out, sets=sets, check=False)
    err = p.stderr.strip()
    check(0 < p.returncode < 128, f"{name}: exit {p.returncode} (non-zero, no signal)")
    check(all(w in err for w in words), f"{name}: message names {words}: {err!r}")
    check(len(err.splitlines()) == 1, f"{name}: one message line")
    check(not os.path.exists(os.path.join(out, "curve.csv")), f"{name}: no curve.csv")

# Missing scene file and an output folder that cannot be written.
p = run(os.path.join(SOURCE, "demo", "no_such_scene.toml"), out_dir("bad_missing"), check=False)
check(0 < p.returncode < 128 and "no_such_scene.toml" in p.stderr, "missing scene file named")
p = run(GOOD, "/proc/pushout-cannot-write-here", check=False)
check(0 < p.returncode < 128 and "--out" in p.stderr, "unwritable output folder named")
print(f"{len(cases) + 2} malformed inputs rejected")

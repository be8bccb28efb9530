"""Helpers for the whole-pipeline tests: run build/pushout, read its outputs."""
import csv
import json
import os
import shutil
import subprocess
import sys

PUSHOUT = sys.argv[1] if len(sys.argv) > 1 else None
SOURCE = os.environ.get("PUSHOUT_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
OUT_ROOT = os.environ.get("PUSHOUT_TEST_OUT", "/tmp/pushout-test-output")


# Scene pieces the tests share (TOML text).
COARSE_MESH = "[mesh]\nelements_per_quarter = 4\nelements_through_thickness = 2\n"
FRICTION_2 = '[[interface]]\nlaw = "friction"\nk = 1000.0\nmu = 0.4\n'  # Table 1
EXP_SOFT = '[[interface]]\nlaw = "exponential_softening"\nk = 1000.0\nf_t = 3.0\nc = 25.0\n'
# Thermal step, then through the adhesion peak (with FRICTION_2 + EXP_SOFT).
THROUGH_PEAK = "[loading]\ntemperature_change = -25.0\npush_displacement = 0.05\nsteps = 10\n"
# Lame shrink fit: a circular slice (outer diameter 100 mm) shrinks onto the
# tube through a friction interface; its plateau is tau = mu p (test_lame).
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


def out_dir(name):
    d = os.path.join(OUT_ROOT, name)
    shutil.rmtree(d, ignore_errors=True)
    return d


def run(scene, out, sets=(), extra=(), check=True):
    """Runs a scene (a path, or TOML text written to out/../NAME.toml)."""
    if "\n" in scene or "=" in scene:
        os.makedirs(OUT_ROOT, exist_ok=True)
        path = os.path.join(OUT_ROOT, os.path.basename(out.rstrip("/")) + ".toml")
        with open(path, "w") as f:
            f.write(scene)
        scene = path
    cmd = [PUSHOUT, "run", scene, "--out", out, "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    cmd += list(extra)
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=1200)
    if check and p.returncode != 0:
        raise SystemExit(f"FAILED: {' '.join(cmd)}\nexit {p.returncode}\n{p.stdout}\n{p.stderr}")
    return p


def curve(out):
    with open(os.path.join(out, "curve.csv"), newline="") as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def summary(out):
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


def check(cond, message):
    if not cond:
        raise SystemExit("FAILED: " + message)
    print("ok: " + message)

"""What the bench scripts share: running build/pushout on a scene, reading
its outputs, writing result tables."""
import csv
import json
import os
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PUSHOUT = os.path.join(ROOT, "build", "pushout")


def run(pushout, scene, out, sets=(), petsc=(), reuse=False, timeout=None, check=True):
    """Runs a scene (one thread, quiet) unless `reuse` and out/ has a summary.
    Returns the exit code (0 when reused) or None if it ran out of time."""
    if reuse and os.path.exists(os.path.join(out, "summary.json")):
        return 0
    cmd = [pushout, "run", scene, "--out", out, "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    cmd += list(petsc)
    try:
        p = subprocess.run(cmd, env=dict(os.environ, OPENBLAS_NUM_THREADS="1"), capture_output=True,
                           text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None
    if check and p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({p.returncode}):\n{p.stderr}")
    return p.returncode


def curve(out):
    with open(os.path.join(out, "curve.csv"), newline="") as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def summary(out):
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


def write_csv(path, rows):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


def save_figure_and_table(fig, out_dir, name, rows):
    """Writes out_dir/NAME.png (the figure, laid out) and NAME.csv (the rows)."""
    fig.tight_layout()
    os.makedirs(out_dir, exist_ok=True)
    fig.savefig(os.path.join(out_dir, name + ".png"))
    write_csv(os.path.join(out_dir, name + ".csv"), rows)


def markdown_table(header, rows):
    """A markdown table: header names, then one line per row (its values)."""
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(v) for v in r.values()) + " |" for r in rows]
    return "\n".join(lines) + "\n"

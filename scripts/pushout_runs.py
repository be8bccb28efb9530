"""Running build/pushout on a scene and reading what it writes: the one place
where the tests, the benches and the scripts do it (standard library only).

    import pushout_runs as pr
    p = pr.run("build/pushout", "demo/pushout_friction.toml", "out", sets=["loading.steps=4"])
    rows = pr.curve("out")        # curve.csv as a list of {column: float}
    s = pr.summary("out")         # summary.json as a dict
"""
import csv
import json
import os
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PUSHOUT = os.path.join(ROOT, "build", "pushout")


class RunError(RuntimeError):
    """A run that exited non-zero; the message has the command, its exit code and stderr."""


def corroded_demo(path, angles):
    """Writes demo/pushout_corroded.toml to `path` with its [[crack]] table
    copied to each of `angles` [deg] (none: no crack plane); returns path."""
    text = open(os.path.join(ROOT, "demo", "pushout_corroded.toml")).read()
    head, rest = text.split("[[crack]]", 1)
    crack, tail = rest.split("\n\n", 1)  # the table ends at the first blank line
    tables = "".join("[[crack]]" + crack.replace('"nearest_face"', f"{a:.1f}") + "\n\n"
                     for a in angles)
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    with open(path, "w") as f:
        f.write(head + tables + tail)
    return path


def embedded_corroded_demo(path):
    """Writes demo/pushout_corroded_cracking.toml (the corroded demo with
    cracks anywhere in the concrete instead of its crack plane) to `path`;
    returns path."""
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    shutil.copyfile(os.path.join(ROOT, "demo", "pushout_corroded_cracking.toml"), path)
    return path


def command(pushout, scene, out, sets=(), petsc=(), quiet=True):
    """The command line of `pushout run`: --set overrides, then PETSc options."""
    cmd = [pushout, "run", scene, "--out", out] + (["--quiet"] if quiet else [])
    for s in sets:
        cmd += ["--set", s]
    return cmd + list(petsc)


def run(pushout, scene, out, sets=(), petsc=(), one_thread=False, timeout=None, check=False,
        mpirun=None, quiet=True, stop_after=None):
    """Runs a scene; returns the CompletedProcess (output captured), or None if it ran
    out of `timeout` seconds (killed). `stop_after` (in place of `timeout`): seconds
    after which it is sent SIGTERM instead, so that it writes its summary.json as
    interrupted (and the CompletedProcess is returned). `one_thread`: BLAS on one
    core (runs side by side); `mpirun`: a number of processes; `check`: raise
    RunError on a non-zero exit; `quiet` false: with the progress output (in the
    CompletedProcess's stdout)."""
    cmd = command(pushout, scene, out, sets, petsc, quiet)
    if mpirun:
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-n", str(mpirun)] + cmd
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1") if one_thread else None
    try:
        if stop_after is None:
            p = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=timeout)
        else:
            p = stopped_after(cmd, env, stop_after)
    except subprocess.TimeoutExpired:
        return None
    if check and p.returncode != 0:
        raise RunError(f"{' '.join(cmd)}\nexit {p.returncode}\n{p.stdout}\n{p.stderr}")
    return p


def stopped_after(cmd, env, seconds):
    """Runs cmd; sends it SIGTERM if it is still running after `seconds`
    and waits for it to write its outputs (a minute, then SIGKILL). The
    CompletedProcess."""
    with subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                          env=env) as proc:
        try:
            stdout, stderr = proc.communicate(timeout=seconds)
        except subprocess.TimeoutExpired:
            proc.terminate()
            try:
                stdout, stderr = proc.communicate(timeout=60)  # it writes its outputs
            except subprocess.TimeoutExpired:
                proc.kill()
                stdout, stderr = proc.communicate()
    return subprocess.CompletedProcess(cmd, proc.returncode, stdout, stderr)


def curve(out, name="curve.csv"):
    """out/curve.csv (or another of the run's tables): one {column: float} per row."""
    with open(os.path.join(out, name), newline="") as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def corrosion(out):
    """out/corrosion.csv (the corrosion stage): one {column: float} per row."""
    return curve(out, "corrosion.csv")


def summary(out):
    """out/summary.json."""
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


def summary_says(out, key):
    """summary.json's `key` in out/ (false where there is no readable summary)."""
    try:
        return bool(summary(out).get(key, False))
    except (OSError, ValueError):
        return False


def converged_before(out):
    """Whether out/ already holds a converged run (to reuse it)."""
    return summary_says(out, "converged")


def short_key_names(keys):
    """Each scene key by its last parts, as few as tell it from the others
    (interface.0.k and interface.1.k: "0.k" and "1.k"; mu alone: "mu")."""
    names = {}
    for k in keys:
        parts = k.split(".")
        n = 1
        while n < len(parts) and sum(o.split(".")[-n:] == parts[-n:] for o in keys) > 1:
            n += 1
        names[k] = ".".join(parts[-n:])
    return names


def write_csv(path, rows):
    """Rows (dicts with the same keys) as a CSV file with a header. No rows
    is an error, before the file is touched (an earlier table there stays)."""
    if not rows:
        raise SystemExit(f"{os.path.basename(sys.argv[0])}: no rows for {path}: nothing ran")
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)

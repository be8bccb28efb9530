"""A run killed with SIGTERM, SIGINT or SIGHUP mid-way exits with 128 +
signal, keeps a valid curve.csv with every finished step, and its
summary.json says it was interrupted (and not converged). Stopped in the
corrosion stage, it says so (stopped_in "corrosion steps", the corrosion
steps it finished, corrosion.csv keeping them, and summary.json's cracks
and crack_pattern.csv those of the last finished one); in step 0, the set-up or
meshing, it names that alone. A closed pipe
(`pushout run ... | head -3`) does not stop it, nor does a signal once the
last step is done (the outputs are written, exit 0), sent to the whole
process group as Ctrl-C does too (the plotting child ignores it: the plot
is drawn). A sweep stops within a few
seconds, without plotting. A run killed outright (SIGKILL, as mpirun's kill
or an out-of-memory kill) leaves its fields (output.xdmf) readable with the
steps it wrote: the HDF5 files are flushed after each step (they could not
be opened at all before)."""
import csv as csv_module
import os
import signal
import subprocess
import sys
import time

import h5py

from common import OUT_ROOT, SOURCE, check, corrosion, cracking_corroded_demo, curve, out_dir, summary

PUSHOUT = sys.argv[1]


def wait_for_rows(csv, rows, seconds, poll):
    """Waits until the file `csv` has `rows` lines (its header one of them),
    at most `seconds`, looking every `poll` seconds."""
    def lines():
        if not os.path.exists(csv):
            return 0
        with open(csv) as f:
            return len(f.readlines())

    deadline = time.time() + seconds
    while time.time() < deadline and lines() < rows:
        time.sleep(poll)


os.makedirs(OUT_ROOT, exist_ok=True)
scene = os.path.join(OUT_ROOT, "interrupt.toml")
with open(scene, "w") as f:
    f.write("[mesh]\nelements_per_quarter = 4\nelements_through_thickness = 2\n"
            "[loading]\nsteps = 100000\n")
for sig in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
    out = out_dir(f"interrupt_{sig.name}")
    p = subprocess.Popen([PUSHOUT, "run", scene, "--out", out, "--quiet"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    csv = os.path.join(out, "curve.csv")
    wait_for_rows(csv, 4, 120, 0.1)
    p.send_signal(sig)
    _, err = p.communicate(timeout=120)
    check(p.returncode == 128 + sig, f"{sig.name}: exit {p.returncode} = 128 + {int(sig)}")
    check("interrupted" in err, f"{sig.name}: says so: {err.strip()!r}")
    s, rows = summary(out), curve(out)
    check(s["interrupted"] and not s["converged"], f"{sig.name}: summary.json says interrupted")
    check(len(rows) == s["steps"] + 1 >= 4, f"{sig.name}: curve.csv keeps all {len(rows)} rows")
    text = open(csv).read()  # (curve() would read a short row as a whole one)
    check(text.endswith("\n") and len({line.count(",") for line in text.splitlines()}) == 1,
          f"{sig.name}: every row of curve.csv complete")

# Stopped in the corrosion stage (the corroded demo, coarse, in many small
# corrosion steps): the stage and its finished steps named.
out = out_dir("interrupt_corrosion")
p = subprocess.Popen([PUSHOUT, "run", os.path.join(SOURCE, "demo", "pushout_corroded.toml"), "--out",
                      out, "--quiet", "--set", "mesh.elements_per_quarter=4", "--set",
                      "mesh.elements_through_thickness=2", "--set", "corrosion.steps=100000"],
                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
csv = os.path.join(out, "corrosion.csv")
wait_for_rows(csv, 5, 120, 0.1)
p.send_signal(signal.SIGINT)
_, err = p.communicate(timeout=120)
s, rows = summary(out), corrosion(out)
said = f"after {s['corrosion_steps']} corrosion steps"
check(p.returncode == 130 and s["interrupted"] and s["stopped_in"] == "corrosion steps" and
      s["steps"] == 0 and s["corrosion_steps"] == len(rows) - 1 >= 3 and said in s["message"] and
      said in err and "corrosion.csv keeps them" in err,
      f"SIGINT in the corrosion stage: exit {p.returncode}, stopped_in {s['stopped_in']!r}, "
      f"{s['message']!r}, corrosion.csv {len(rows)} rows; {err.strip()!r}")
# The cracks of its last finished step (summary.json cracks): the plane's
# mouth as corrosion.csv's last row has it (12 digits printed there).
w, w_row = (s["cracks"][0]["width_mm"] if s["cracks"] else None), rows[-1]["crack_width_mm"]
check(len(s["cracks"]) == 1 and abs(w - w_row) <= 1e-11 * max(abs(w_row), 1e-6),
      f"SIGINT in the corrosion stage: summary.json cracks at the last finished step, the "
      f"plane's mouth {w} mm against corrosion.csv's {w_row} mm")
# With cracks anywhere, crack_pattern.csv too (it was written at the push's
# start only, so a corrosion stage stopped left none).
out = out_dir("interrupt_corrosion_cracking")
cracking_scene = out + ".toml"
with open(cracking_scene, "w") as f:
    f.write(cracking_corroded_demo(0.05, 100))  # 0.5 um a step: cracked by the 8th row
p = subprocess.Popen([PUSHOUT, "run", cracking_scene, "--out", out, "--quiet"], stdout=subprocess.PIPE,
                     stderr=subprocess.PIPE, text=True)
wait_for_rows(os.path.join(out, "corrosion.csv"), 9, 120, 0.1)
p.send_signal(signal.SIGINT)
p.communicate(timeout=120)
pattern = os.path.join(out, "crack_pattern.csv")
cracked = 0
if os.path.exists(pattern):
    with open(pattern, newline="") as f:
        cracked = sum(float(r["opening_mm"]) > 0 for r in csv_module.DictReader(f))
rows = corrosion(out)
check(p.returncode == 130 and summary(out)["stopped_in"] == "corrosion steps" and
      rows[-1]["cracked_points"] > 0 and cracked > 0,
      f"SIGINT in the corrosion stage with cracks anywhere: exit {p.returncode}, crack_pattern.csv "
      f"with {cracked} cracked columns ({int(rows[-1]['cracked_points'])} cracked points in the "
      f"last row)")


# A signal once the last step is done stops nothing: the outputs are
# written whole (the plot too) and the run ends as it would have, exit 0.
# Whatever the timing, the exit code and summary.json agree (a signal during
# the writing was once forced as it ended: exit 143 beside "converged").
for attempt in range(3):
    out = out_dir(f"interrupt_after_last_step_{attempt}")
    p = subprocess.Popen([PUSHOUT, "run", scene, "--out", out, "--set", "loading.steps=4"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    while not (line := p.stdout.readline()).startswith("step 4/4") and line:
        pass
    p.send_signal(signal.SIGTERM)
    _, err = p.communicate(timeout=120)
    s = summary(out)
    finished = (p.returncode == 0 and s["converged"] and not s["interrupted"]
                and os.path.exists(os.path.join(out, "curve.png")))
    stopped = p.returncode == 143 and s["interrupted"] and not s["converged"]
    check(finished or stopped, f"SIGTERM after the last step ({attempt}): exit {p.returncode}, "
          f"converged {s['converged']}, interrupted {s['interrupted']}; {err.strip()!r}")


# Ctrl-C signals the whole foreground process group, the plotting child
# too: it ignores the signals that stop a run (SIGINT, SIGTERM, SIGHUP), so
# that the run decides; with SIGINT to the group after the last step the plot
# is drawn (it was lost: the child died of the signal, exit 0 without it).
def ignored_signals(pid):
    """The signals the process `pid` ignores (/proc's SigIgn mask)."""
    with open(f"/proc/{pid}/status") as f:
        mask = int(next(line for line in f if line.startswith("SigIgn:")).split()[1], 16)
    return {sig for sig in signal.Signals if mask >> (int(sig) - 1) & 1}


def plotting_child(pid):
    """The run's plotting child (scripts/plot_curve.py --serve), if any."""
    for entry in os.listdir("/proc"):
        try:
            with open(f"/proc/{entry}/stat") as f:
                parent = int(f.read().rsplit(")", 1)[1].split()[1])
            with open(f"/proc/{entry}/cmdline") as f:
                command = f.read()
        except (OSError, ValueError, IndexError):
            continue
        if parent == pid and "plot_curve.py" in command:
            return int(entry)
    return None


for attempt in range(3):
    out = out_dir(f"interrupt_group_after_last_step_{attempt}")
    p = subprocess.Popen([PUSHOUT, "run", scene, "--out", out, "--set", "loading.steps=4"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         start_new_session=True)
    while not (line := p.stdout.readline()).startswith("step 4/4") and line:
        pass
    child = plotting_child(p.pid)
    ignored = ignored_signals(child) if child else set()
    os.killpg(p.pid, signal.SIGINT)
    _, err = p.communicate(timeout=120)
    s = summary(out)
    check(child and {signal.SIGINT, signal.SIGTERM, signal.SIGHUP} <= ignored,
          f"the plotting child ({child}) ignores SIGINT, SIGTERM and SIGHUP: "
          f"{sorted(sig.name for sig in ignored)}")
    finished = (p.returncode == 0 and s["converged"] and not s["interrupted"]
                and os.path.exists(os.path.join(out, "curve.png")) and "Traceback" not in err
                and "no curve.png" not in err)
    stopped = p.returncode == 130 and s["interrupted"] and not s["converged"]
    check(finished or stopped, f"SIGINT to the process group after the last step ({attempt}): "
          f"exit {p.returncode}, converged {s['converged']}, curve.png "
          f"{os.path.exists(os.path.join(out, 'curve.png'))}; {err.strip()[-300:]!r}")


def interrupt_after_model_line(name, sets, in_newton=False):
    """Runs `scene` on a mesh large enough that the condensation (set-up)
    and Newton on the whole model (step 0) each take seconds (here 6.8 and
    3.3 s after the line that describes the model, which follows meshing),
    and sends SIGINT as soon as that line is read (it is printed in the
    set-up, before the condensation: the signal comes in the set-up however
    fast the machine), or (`in_newton`) as soon as Newton's first residual
    is printed (-snes_monitor: step 0 has begun, however long the set-up
    took on a loaded machine). Returns the exit code, stderr and the output
    folder."""
    out = out_dir(name)
    p = subprocess.Popen([PUSHOUT, "run", scene, "--out", out, "--set", "mesh.elements_per_quarter=40",
                          "--set", "mesh.elements_through_thickness=12", "--set", "loading.steps=3"] +
                         [a for s in sets for a in ("--set", s)] + (["-snes_monitor"] if in_newton else []),
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    while not (line := p.stdout.readline()).startswith("pushout: pushout") and line:
        pass
    if in_newton:
        while "SNES Function norm" not in (line := p.stdout.readline()) and line:
            pass
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=120)
    return p.returncode, err, out


# Stopped in step 0 (the thermal step; Newton on the whole model): said as
# such, no load step claimed, curve.csv has its header only. ("in step 0"
# where the run stops at a Newton iteration's end, "during step 0" where an
# iteration outlasts the grace period and the run is ended: a factorisation
# on a loaded machine.)
code, err, out = interrupt_after_model_line("interrupt_step0", ["solver.condensation=off"],
                                            in_newton=True)
s = summary(out)
check(code == 130 and s["interrupted"] and s["stopped_in"] == "step 0" and s["steps"] == 0 and
      s["message"].endswith("step 0") and "load steps" not in s["message"] and curve(out) == [],
      f"SIGINT in step 0: exit {code}, stopped_in {s['stopped_in']!r}, {s['message']!r}; {err.strip()!r}")

# Stopped in the set-up (the condensation): no steps named, and summary.json
# gives the model that was built.
code, err, out = interrupt_after_model_line("interrupt_setup", [])
s = summary(out)
check(code == 130 and s["stopped_in"] == "set-up" and s["message"] == "interrupted by SIGINT during set-up"
      and s["cells"] == s["estimate"]["cells"] > 0 and s["dofs"] == s["estimate"]["dofs"],
      f"SIGINT in the set-up: exit {code}, stopped_in {s['stopped_in']!r}, {s['message']!r}, "
      f"{s['cells']} cells, {s['dofs']} dofs; {err.strip()!r}")

# Under nohup (SIGHUP ignored from the start) SIGHUP does not stop the run.
out = out_dir("interrupt_nohup")
p = subprocess.Popen([PUSHOUT, "run", scene, "--out", out, "--quiet", "--set", "loading.steps=2000"],
                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                     preexec_fn=lambda: signal.signal(signal.SIGHUP, signal.SIG_IGN))
csv = os.path.join(out, "curve.csv")
wait_for_rows(csv, 4, 120, 0.05)
p.send_signal(signal.SIGHUP)
_, err = p.communicate(timeout=300)
check(p.returncode == 0 and summary(out)["converged"], f"nohup: SIGHUP ignored, exit {p.returncode}")

# A reader that closes the pipe (`| head -3`): the run goes on, writes its
# files, exit 0 (SIGPIPE would kill it: exit 141, no summary.json).
out = out_dir("interrupt_pipe")
p = subprocess.Popen([PUSHOUT, "run", scene, "--out", out, "--set", "loading.steps=30"],
                     stdout=subprocess.PIPE, stderr=subprocess.PIPE)
for _ in range(3):
    p.stdout.readline()
p.stdout.close()
err = p.stderr.read().decode()
p.wait(timeout=300)
check(p.returncode == 0, f"a closed stdout: exit {p.returncode} (0) {err.strip()[-300:]!r}")
s = summary(out)
check(s["converged"] and s["steps"] == 30 and len(curve(out)) == 31,
      "a closed stdout: every step in curve.csv, summary.json converged")

# A sweep stops within a few seconds of SIGTERM and draws no plot (plotting
# every finished curve takes 24 s here). Twenty short cases, then a long one.
out = out_dir("interrupt_sweep")
steps = ",".join([str(n) for n in range(2, 22)] + ["100000"])
p = subprocess.Popen([PUSHOUT, "sweep", scene, "--out", out, "--quiet", "--vary",
                      f"loading.steps={steps}"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                     text=True)
csv = os.path.join(out, "case_020", "curve.csv")
wait_for_rows(csv, 3, 300, 0.1)
t0 = time.time()
p.send_signal(signal.SIGTERM)
_, err = p.communicate(timeout=120)
waited = time.time() - t0
check(p.returncode == 143, f"sweep: exit {p.returncode} (143) {err.strip()[-300:]!r}")
# The program's own bound: a case's phases hold a signal at most
# stop_grace_s (5 s, common/Interrupt.h) before they are ended, then
# sweep.csv is written; twice that for a loaded machine.
check(waited < 10, f"sweep: stopped {waited:.1f} s after SIGTERM")
check(os.path.exists(os.path.join(out, "sweep.csv")) and not os.path.exists(os.path.join(out, "sweep.png")),
      "sweep: sweep.csv written, no sweep.png")
check(summary(os.path.join(out, "case_020"))["interrupted"], "sweep: the stopped case says so")

# Killed outright: the fields' HDF5 files hold the steps written.
out = out_dir("interrupt_sigkill_fields")
p = subprocess.Popen([PUSHOUT, "run", scene, "--out", out, "--quiet", "--set", "output.xdmf=true",
                      "--set", "output.plot=false"], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
wait_for_rows(os.path.join(out, "curve.csv"), 6, 120, 0.05)
p.kill()
p.communicate(timeout=60)
for name in ("fields.h5", "interface.h5"):
    with h5py.File(os.path.join(out, name), "r") as h5:
        steps = len(next(iter(h5["Function"].values())))
    # curve.csv had rows 0-4: a row is written before its fields, so the
    # last (row 4's) may have been cut short by the kill.
    check(steps >= 4, f"SIGKILL: {name} opens, {steps} steps in it")

# A fit stopped during its fitted run: exit 143, no fit.json, no best/ (a
# part of the curve in best/ and a fit.json saying converged would pass for
# a finished fit). The data: a friction curve (mu 0.4) of 5 points; each run takes
# 3000 steps, so the fitted run lasts long enough to be stopped.
out = out_dir("interrupt_fit")
data = os.path.join(out + "_data.csv")
with open(data, "w") as f:
    f.write("delta_mm,tau_MPa\n0.0,-0.42\n0.0025,0.5\n0.005,1.0\n0.0075,1.2\n0.01,1.3\n")
fit_scene = out + ".toml"
with open(fit_scene, "w") as f:
    f.write("[mesh]\nelements_per_quarter = 4\nelements_through_thickness = 2\n"
            '[[interface]]\nlaw = "friction"\nk = 1000.0\nmu = 0.4\n'
            "[loading]\ntemperature_change = -25.0\n")
p = subprocess.Popen([PUSHOUT, "fit", fit_scene, "--data", data, "--free", "interface.0.mu", "--out",
                      out, "--quiet", "--set", "loading.steps=3000", "--set", "output.plot=false"],
                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
csv = os.path.join(out, "best", "curve.csv")
deadline = time.time() + 300
while p.poll() is None and time.time() < deadline and (not os.path.exists(csv) or len(open(csv).readlines()) < 3):
    time.sleep(0.02)
check(p.poll() is None, "fit: stopped during the fitted run")
p.send_signal(signal.SIGTERM)
_, err = p.communicate(timeout=120)
check(p.returncode == 143, f"fit: exit {p.returncode} (143) {err.strip()[-300:]!r}")
check(not os.path.exists(os.path.join(out, "fit.json")), "fit: no fit.json")
check(not os.path.exists(os.path.join(out, "best")), "fit: no best/ with a part of a curve")

# A signal during meshing (gmsh cannot look at it): the run stops within a
# few seconds, with the same exit code, and summary.json says where. The
# mesh is large (gmsh needs about a minute) and never cached.
big = ["--set", "mesh.elements_per_quarter=500", "--set", "mesh.elements_through_thickness=4"]
for sig in (signal.SIGTERM, signal.SIGINT):
    out = out_dir(f"interrupt_meshing_{sig.name}")
    cache = out_dir(f"interrupt_meshing_cache_{sig.name}")
    os.makedirs(cache)  # (the run makes it only once its mesh is made)
    p = subprocess.Popen([PUSHOUT, "run", scene, "--out", out, "--force"] + big,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         env=dict(os.environ, PUSHOUT_CACHE_DIR=cache))
    line = p.stdout.readline()
    check(line.startswith("pushout: meshing"), f"{sig.name}: the run says it is meshing: {line.strip()!r}")
    time.sleep(2)
    check(p.poll() is None, f"{sig.name}: still meshing 2 s later")
    t0 = time.time()
    p.send_signal(sig)
    _, err = p.communicate(timeout=60)
    waited = time.time() - t0
    check(p.returncode == 128 + sig, f"{sig.name} during meshing: exit {p.returncode} = 128 + {int(sig)}")
    # Meshing's grace is 0 (common/Interrupt.h): the watcher ends it at its
    # next look, well within stop_grace_s (5 s), the longest any phase may
    # hold a signal.
    check(waited < 5, f"{sig.name} during meshing: stopped {waited:.2f} s after the signal")
    check("interrupted by " + sig.name + " during meshing" in err, f"{sig.name}: says where: {err.strip()!r}")
    s = summary(out)
    check(s["interrupted"] and not s["converged"] and s["stopped_in"] == "meshing"
          and s["signal"] == int(sig) and s["message"] == f"interrupted by {sig.name} during meshing",
          f"{sig.name}: summary.json says it stopped in meshing, and no steps: {s['message']!r}")
    check(os.listdir(cache) == [], f"{sig.name}: no mesh, whole or half-made, in the cache: "
          f"{os.listdir(cache)}")

#!/usr/bin/python3
"""Runs the paper's push-out studies (§4.2-4.4) and draws their figures.

  scripts/studies.py [--out results/studies] [--quick] [--jobs 2] [--only fig7 ...]

Studies (each run keeps its resolved scene.toml next to its curve.csv):
  fig7        Friction 2 (k 1000, mu 0.4 and 0.2) with retraction dT = -5, -10,
              -25, -50 degC, then 10 um in 9 steps (10 for dT = -5): tau-delta.
  fig8        mu 0.4, dT -5 at delta = 10 um: normal and shear traction maps
              over the interface, from interface.xdmf, rendered by ParaView.
  fig10       Friction 2 + Exp. soft. (k 1000, f_t 3, c 25 and 12.5, f_fr 0)
              superposed, and the single cohesive_friction law with the same
              parameters; dT = -5 ... -50; pushed to 1 mm.
  retraction  the tube's top nodes held (paper) or free during the thermal
              step, mu 0.4, dT -25.
  unload_reload  the Fig. 10 demo (c 25, dT -25) pushed along [0, 6, 0, 40, 0,
              200] um, each unloading ending at zero force (the device cannot
              pull; loading.unload_to), against the monotonic push to 200 um:
              the loops, one before and one after the peak, and the
              permanent displacements.
  laws        §2.3 rerun: the adhesion layer of the Fig. 10 demo as linear
              softening, linear softening with a residual (0.5 MPa),
              exponential, exponential with a residual (all k 1000, f_t 3,
              softening energy 0.12 N/mm: c 25, w_c2 0.08 mm), alone (the
              friction layer at mu 0: normal contact only) or with friction
              (mu 0.4); dT -25, pushed to 1 mm: peaks, residuals, and the
              spread of t_s1 over the interface after the peak; and the
              adhesion's damage after the thermal step, tube top held or
              free, dT -25 and -50.
  corroded    demo/pushout_corroded.toml (oxide_friction k 1000, mu 0.4; crack
              k 1e5, f_t 3, c 30: G_F 0.1 N/mm; dT -25): the tube centred or
              15 mm from a face, one crack to the nearest face or four (0, 90,
              180, 270 deg), beta 2 or 3, corroded to x = 0, 12.5, 25, 50 um,
              then pushed 0.2 mm: residual bond stress against x and against
              the crack width (not in the defaults: --only corroded).
  corroded_embedded  the same specimens with cracks anywhere in the concrete
              ([cracking] model = "embedded", f_t 3, c 30, strength cov 0.15,
              correlation length 5 mm) instead of crack planes, seeds 1-5:
              residual bond with the seeds' range as error bars, and the crack
              patterns at x = 50 um, the implicit cracks under
              loading.control = "auto" (scripts/embedded_study.py; not in the
              studies run by default: --only corroded_embedded).
  corroded_embedded_implex  the same with IMPL-EX cracks under displacement
              control (cracking.integration = "implex", what its default
              "auto" takes there) and the history predictor
              (cracking.implex_predictor = "history", the default when it
              ran; not in the studies run by default).
  corroded_embedded_paper_mesh  corroded_embedded_implex_strain on the
              paper's mesh (16 per quarter, 8 through the thickness) instead
              of 12 / 4 (the history predictor until the rerun after
              a2cc244; not in the studies run by default).
  corroded_embedded_implex_strain  corroded_embedded_implex with the strain
              predictor (cracking.implex_predictor = "strain", the default;
              not in the studies run by default).
  corroded_embedded_row_band  corroded_embedded_implex_strain with the
              cracks' band the width of the thinnest row of cells
              (cracking.band_width = "row"; not in the studies run by
              default).
  corroded_embedded_row_band_paper_mesh  corroded_embedded_row_band on the
              paper's mesh (not in the studies run by default).
  corroded_embedded_radial  corroded_embedded_implex_strain with the graded
              concrete's lines along rays from the tube axis
              (mesh.graded_lines = "radial"; not in the studies run by
              default).
  corroded_embedded_radial_paper_mesh  corroded_embedded_radial on the
              paper's mesh (not in the studies run by default).
  corroded_embedded_radial_whole_paper_mesh  corroded_embedded_radial_paper_mesh
              with every graded cell refined alike
              (mesh.graded_refinement = "whole", so that the cells keep
              their shape as the mesh is refined; not in the studies run
              by default).
--quick runs the same studies on a coarse mesh with few steps (the test
suite uses it). Writes OUT/<study>/<case>/ run folders, OUT/*.png figures,
OUT/plateaus.csv (friction plateau vs mu p) and OUT/timing.json.
"""
import argparse
import concurrent.futures
import csv
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import argument_types  # noqa: E402  (beside this script)
import embedded_study  # noqa: E402  (beside this script)
import pushout_runs  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEMO = os.path.join(ROOT, "demo")
DTS = [-5.0, -10.0, -25.0, -50.0]
CORROSION_DEPTHS_UM = [0.0, 12.5, 25.0, 50.0]
CRACK_ETA = 1e-3  # mm of pseudo-time (a push step is 0.01)
# The corroded demo with four crack planes instead of one (written to OUT).
FOUR_CRACKS = "pushout_corroded_four_cracks.toml"
# §2.3: the adhesion laws compared (the second [[interface]] table of
# demo/pushout_friction_adhesion.toml; scenes written to OUT/laws/).
ADHESION_LAWS = {
    "linear": 'law = "linear_softening"\nk = 1000.0\nf_t = 3.0\nw_c2 = 0.08\n',
    "linear_residual": 'law = "linear_softening_friction"\nk = 1000.0\nf_t = 3.0\nw_c2 = 0.08\nf_fr = 0.5\n',
    "exponential": 'law = "exponential_softening"\nk = 1000.0\nf_t = 3.0\nc = 25.0\nf_fr = 0.0\n',
    "exponential_residual": 'law = "exponential_softening"\nk = 1000.0\nf_t = 3.0\nc = 25.0\nf_fr = 0.5\n',
}
# delta after the peak where the spread of t_s1 is reported [mm].
SPREAD_AT_MM = (0.05, 0.2, 1.0)
# What --only takes (cases() knows each).
STUDIES = ["fig7", "fig8", "fig10", "retraction", "unload_reload", "laws", "corroded",
           *embedded_study.STUDIES]
COLORS = {-5.0: "tab:blue", -10.0: "tab:green", -25.0: "tab:orange", -50.0: "tab:red"}



def finish_pair(fig, axes, title, png):
    """Labels, legend and title of a figure of two τ(δ) panels side by side; saves it."""
    axes[0].set_ylabel("nominal bond stress $\\tau$ [MPa]")
    axes[1].legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(png)

def mesh_sets(study, quick):
    if quick and study in embedded_study.STUDIES:  # the crack band's size condition
        return ["mesh.elements_per_quarter=8", "mesh.elements_through_thickness=2"]
    if quick:
        return ["mesh.elements_per_quarter=4", "mesh.elements_through_thickness=2"]
    if study in embedded_study.STUDIES and embedded_study.on_paper_mesh(study):
        return []
    if study == "corroded" or study in embedded_study.STUDIES:  # the full model (no symmetry, no condensation)
        return ["mesh.elements_per_quarter=12", "mesh.elements_through_thickness=4"]
    return []  # the paper's mesh: 16 per quarter, 8 through the thickness


def cases(study, quick):
    """(name, scene, --set list) of every run of a study."""
    out = []
    if study == "fig7":
        for mu in (0.4, 0.2):
            for dT in DTS:
                steps = 10 if dT == -5 else 9
                out.append((f"mu{mu}_dT{dT:g}", "pushout_friction.toml",
                            [f"interface.0.mu={mu}", f"loading.temperature_change={dT}",
                             f"loading.steps={steps}"]))
    elif study == "fig8":
        out.append(("mu0.4_dT-5", "pushout_friction.toml",
                    ["interface.0.mu=0.4", "loading.temperature_change=-5", "loading.steps=10",
                     "output.xdmf=true"]))
    elif study == "fig10":
        steps = 30 if quick else 80
        push = ["loading.push_displacement=1.0", f"loading.steps={steps}",
                f"loading.step_growth={1.2 if quick else 1.07}"]
        for c in (25.0, 12.5):
            for dT in DTS:
                out.append((f"superposed_c{c:g}_dT{dT:g}", "pushout_friction_adhesion.toml",
                            [f"interface.1.c={c}", f"loading.temperature_change={dT}"] + push))
                out.append((f"coupled_c{c:g}_dT{dT:g}", "pushout_cohesive_friction.toml",
                            [f"interface.0.c={c}", f"loading.temperature_change={dT}"] + push))
        if quick:  # for the peak-vs-f_t trend
            out.append(("superposed_c25_dT-25_ft1.5", "pushout_friction_adhesion.toml",
                        ["interface.1.f_t=1.5", "loading.temperature_change=-25"] + push))
    elif study == "corroded":
        steps = 10 if quick else 20
        for where, centre in (("centred", "[50.0, 50.0]"), ("cover15", "[50.0, 25.0]")):
            for cracks in ("one", "four"):
                for beta in (2.0, 3.0):
                    for x_um in CORROSION_DEPTHS_UM:
                        sets = [f"geometry.tube_center={centre}", f"corrosion.beta={beta}",
                                f"corrosion.penetration={x_um / 1e3}",
                                f"corrosion.steps={max(1, round(x_um / 2.5))}",
                                f"loading.steps={steps}"]
                        # A small damage viscosity passes the cracks' snap-backs under
                        # control of x (docs/corrosion.md: 0.6 % on p at 12.5 um).
                        sets += [f"crack.{i}.eta={CRACK_ETA}" for i in range(1 if cracks == "one" else 4)]
                        scene = "pushout_corroded.toml" if cracks == "one" else FOUR_CRACKS
                        out.append((f"{where}_{cracks}_beta{beta:g}_x{x_um:g}", scene, sets))
    elif study in embedded_study.STUDIES:
        out = embedded_study.cases(quick, study)
    elif study == "unload_reload":
        per = 6 if quick else 20
        out.append(("loops", "pushout_friction_adhesion.toml",
                    ["loading.push_path=[0.0,0.006,0.0,0.04,0.0,0.2]",
                     f"loading.steps_per_segment={per}", "loading.unload_to=zero_force"]))
        out.append(("monotonic", "pushout_friction_adhesion.toml",
                    ["loading.push_displacement=0.2", f"loading.steps={3 * per}"]))
    elif study == "laws":
        steps = 30 if quick else 80
        push = ["loading.push_displacement=1.0", f"loading.steps={steps}",
                f"loading.step_growth={1.2 if quick else 1.07}", "loading.temperature_change=-25"]
        for law in ADHESION_LAWS:
            for mu in (0.0, 0.4):
                out.append((f"{law}_mu{mu:g}", f"laws/{law}.toml", push + [f"interface.0.mu={mu}"]))
        for top in ("held", "free"):
            for dT in (-25.0, -50.0):
                out.append((f"damage_{top}_dT{dT:g}", "pushout_friction_adhesion.toml",
                            [f"loading.thermal_tube_top={top}", f"loading.temperature_change={dT}",
                             "loading.push_displacement=0.1", "loading.steps=50"]))
    elif study == "retraction":
        for top in ("held", "free"):
            out.append((top, "pushout_friction.toml",
                        ["interface.0.mu=0.4", "loading.temperature_change=-25",
                         f"loading.thermal_tube_top={top}"]))
    return out


def law_scenes(out):
    """demo/pushout_friction_adhesion.toml with each of ADHESION_LAWS as its
    adhesion layer, into OUT/laws/<law>.toml."""
    text = open(os.path.join(DEMO, "pushout_friction_adhesion.toml")).read()
    head, rest = text.split("[[interface]]", 1)
    first, rest = rest.split("[[interface]]", 1)
    _, tail = rest.split("\n\n", 1)  # the table ends at the first blank line
    os.makedirs(os.path.join(out, "laws"), exist_ok=True)
    for law, table in ADHESION_LAWS.items():
        with open(os.path.join(out, "laws", law + ".toml"), "w") as f:
            f.write(head + "[[interface]]" + first + "[[interface]]\n" + table + "\n" + tail)


def four_cracks_scene(out):
    """demo/pushout_corroded.toml with four crack planes at 0, 90, 180, 270 deg."""
    return pushout_runs.corroded_demo(os.path.join(out, FOUR_CRACKS), (0.0, 90.0, 180.0, 270.0))


def run_case(pushout, study, folder, scene, sets, quick, reuse):
    path = os.path.join(DEMO, scene)
    if scene in (FOUR_CRACKS, embedded_study.SCENE) or scene.startswith("laws/"):
        path = os.path.join(os.path.dirname(os.path.dirname(folder)), scene)
    all_sets = ["output.plot=false"] + sets + mesh_sets(study, quick)
    # What made the run, beside it: --reuse keeps only a run of the same
    # scene and values (not a --quick run for a full set).
    made_by = os.path.join(folder, "studies_run.json")
    this_run = {"scene": path, "sets": all_sets}
    if reuse and pushout_runs.converged_before(folder):
        try:
            with open(made_by) as f:
                if json.load(f) == this_run:
                    return 0.0
        except (OSError, ValueError):
            pass
    t0 = time.time()
    # One core per run: the runs go side by side. A corroded case that does
    # not converge is reported, not fatal.
    pushout_runs.run(pushout, path, folder, all_sets, one_thread=True,
                     check=not study.startswith("corroded"))
    os.makedirs(folder, exist_ok=True)  # (a run refused before its folder)
    with open(made_by, "w") as f:
        json.dump(this_run, f)
    return time.time() - t0


def plot_fig7(out, runs):
    fig, ax = plt.subplots(figsize=(7, 4.5), dpi=120)
    for mu, style in ((0.4, "-"), (0.2, "--")):
        for dT in DTS:
            rows = runs[("fig7", f"mu{mu}_dT{dT:g}")]
            ax.plot([r["delta_mm"] * 1e3 for r in rows], [r["tau_MPa"] for r in rows], style,
                    marker="o", ms=3, color=COLORS[dT], label=f"$\\mu$ {mu}, $\\Delta T$ {dT:g} °C")
    ax.axhline(0, color="0.6", lw=0.5)
    ax.set(xlabel="tube displacement $\\delta$ [µm]", ylabel="nominal bond stress $\\tau$ [MPa]",
           title="Fig. 7: friction (k 1000) and retraction")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig7_friction_retraction.png"))


def plot_fig10(out, runs):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), dpi=120, sharey=True)
    for ax, c in zip(axes, (25.0, 12.5)):
        for dT in DTS:
            for kind, style in (("superposed", "-"), ("coupled", "--")):
                rows = runs[("fig10", f"{kind}_c{c:g}_dT{dT:g}")]
                label = f"$\\Delta T$ {dT:g}" + (" (cohesive_friction)" if kind == "coupled" else "")
                ax.plot([r["delta_mm"] * 1e3 for r in rows], [r["tau_MPa"] for r in rows], style,
                        color=COLORS[dT], lw=1.2, label=label)
        ax.set(xlabel="tube displacement $\\delta$ [µm]",
               title=f"friction 2 + exp. soft., c = {c:g} 1/mm")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("nominal bond stress $\\tau$ [MPa]")
    axes[1].legend(fontsize=7, ncol=2)
    fig.suptitle("Fig. 10: friction and adhesion (solid: superposed layers, dashed: one coupled law)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig10_friction_adhesion.png"))
    for ax in axes:
        ax.set_xlim(0, 100)
    fig.savefig(os.path.join(out, "fig10_friction_adhesion_first_100um.png"))


def plot_retraction(out, runs):
    fig, ax = plt.subplots(figsize=(6.5, 4.2), dpi=120)
    for top, label in (("held", "tube top held during shrinkage (paper)"),
                       ("free", "tube free during shrinkage")):
        rows = runs[("retraction", top)]
        ax.plot([r["delta_mm"] * 1e3 for r in rows], [r["tau_MPa"] for r in rows], "o-", ms=3,
                label=label)
    ax.axhline(0, color="0.6", lw=0.5)
    ax.set(xlabel="tube displacement $\\delta$ [µm]", ylabel="nominal bond stress $\\tau$ [MPa]",
           title="Retraction boundary condition ($\\mu$ 0.4, $\\Delta T$ -25 °C)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "retraction_boundary_condition.png"))


class RenderError(RuntimeError):
    """The interface maps could not be rendered; the message says why, in one line."""


MISSING_PARAVIEW = "ParaView's Python module is missing: install python3-paraview (scripts/setup.sh does)"


class VirtualDisplay:
    """A private Xvfb server for pvbatch, local connections only.

    - Its display number is one the server could bind (it reports it through
      -displayfd; a number in use makes it exit, and the next is tried), not
      one guessed from lock files as xvfb-run does: those miss a socket that
      another server (another /tmp, another chroot) holds.
    - Numbers start at FIRST_DISPLAY: every MPI start probes displays :0 to
      :9 for GPUs (hwloc), and a pushout run beside a render once connected
      to a server there and died when the render ended it (XIO fatal error).
    - It admits only the holder of its cookie (-auth, XAUTHORITY for
      pvbatch), so no other client of this machine ever connects to it."""

    FIRST_DISPLAY = 100
    TRIES = 100

    def __init__(self):
        self.proc = None
        self.display = None
        self.folder = None

    def _write_cookie(self):
        """An Xauthority file of one MIT-MAGIC-COOKIE-1 entry for any
        display of this machine (FamilyWild, no address, no number)."""
        self.folder = tempfile.mkdtemp(prefix="pushout-xvfb-")
        path = os.path.join(self.folder, "Xauthority")
        field = lambda b: struct.pack(">H", len(b)) + b  # noqa: E731
        with open(path, "wb") as f:
            f.write(struct.pack(">H", 0xFFFF) + field(b"") + field(b"")
                    + field(b"MIT-MAGIC-COOKIE-1") + field(os.urandom(16)))
        return path

    def _start(self, xvfb, number):
        """Xvfb on :number; its stderr lines if it did not start, else None."""
        read_end, write_end = os.pipe()
        self.proc = subprocess.Popen([xvfb, f":{number}", "-displayfd", str(write_end), "-auth",
                                      self.auth, "-screen", "0", "1600x1200x24", "-nolisten", "tcp"],
                                     pass_fds=(write_end,), stdout=subprocess.DEVNULL,
                                     stderr=subprocess.PIPE, text=True)
        os.close(write_end)
        reported = b""
        # The server writes its display number once it accepts connections;
        # end of file first means it died.
        while not reported.endswith(b"\n"):
            chunk = os.read(read_end, 16)
            if not chunk:
                break
            reported += chunk
        os.close(read_end)
        if reported.strip().isdigit():
            return None
        self.proc.kill()
        return self.proc.communicate()[1].strip().splitlines()

    def __enter__(self):
        xvfb = shutil.which("Xvfb")
        if not xvfb:
            raise RenderError("Xvfb is missing: install xvfb (scripts/setup.sh does)")
        self.auth = self._write_cookie()
        for number in range(self.FIRST_DISPLAY, self.FIRST_DISPLAY + self.TRIES):
            err = self._start(xvfb, number)
            if err is None:
                self.display = f":{number}"
                return self
        shutil.rmtree(self.folder, ignore_errors=True)
        raise RenderError(f"Xvfb did not start on displays :{self.FIRST_DISPLAY} to "
                          f":{self.FIRST_DISPLAY + self.TRIES - 1}: " + " | ".join(err[-3:]))

    def env(self):
        """The environment for a client of this server."""
        return dict(os.environ, DISPLAY=self.display, XAUTHORITY=self.auth)

    def __exit__(self, *exc):
        self.proc.terminate()
        try:
            self.proc.communicate(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.communicate()
        shutil.rmtree(self.folder, ignore_errors=True)
        return False


def render_interface(folder, png, title):
    """Renders folder/interface.xdmf into png with pvbatch (scripts/render_interface.py),
    under a virtual X server when no DISPLAY is set; returns what the script
    printed (the unrolled extent). Raises RenderError with one clear line when
    it cannot."""
    pvbatch = shutil.which("pvbatch")
    if not pvbatch:
        raise RenderError("ParaView's pvbatch is missing: install paraview (scripts/setup.sh does)")
    cmd = [pvbatch, os.path.join(ROOT, "scripts", "render_interface.py"), folder, png, "--title", title]
    # Up to three tries, each on a server of its own: a loaded machine has
    # failed a first render that the next one did.
    for attempt in range(3):
        if os.environ.get("DISPLAY"):
            p = subprocess.run(cmd, capture_output=True, text=True)
        else:
            with VirtualDisplay() as x:
                p = subprocess.run(cmd, capture_output=True, text=True, env=x.env())
        if p.returncode == 0 and os.path.exists(png):
            return p.stdout
        if "No module named 'paraview'" in p.stdout + p.stderr:
            raise RenderError(MISSING_PARAVIEW)
        time.sleep(1 + attempt)
    lines = [l for l in (p.stdout + p.stderr).splitlines() if "ERR" in l or "Error" in l]
    raise RenderError(f"pvbatch failed three times (last exit {p.returncode}): " + " | ".join(lines[-3:]))


def render_fig8(out, folder):
    render_interface(folder, os.path.join(out, "fig8_interface_maps.png"),
                     "mu 0.4, dT -5 degC, delta = 10 um (paper Fig. 8)")


def plateau_table(out, runs):
    """Friction plateau (last step) against mu p, p the mean interface pressure."""
    rows = []
    for (study, name), curve in sorted(runs.items()):
        if study not in ("fig7", "retraction"):
            continue
        mu = 0.4 if "mu0.2" not in name else 0.2
        last = curve[-1]
        rows.append({"study": study, "case": name, "mu": mu, "tau_plateau_MPa": last["tau_MPa"],
                     "p_MPa": last["p_MPa"], "mu_p_MPa": mu * last["p_MPa"],
                     "ratio": last["tau_MPa"] / (mu * last["p_MPa"])})
    with open(os.path.join(out, "plateaus.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    return rows


def plot_corroded(out, runs):
    """Residual bond stress (tau at the last delta) against x and against
    the crack width after corrosion; push-out curves; OUT/corroded.csv."""
    table = []
    for name in sorted({n for (study, n) in runs if study == "corroded"}):
        folder = os.path.join(out, "corroded", name)
        rows = runs[("corroded", name)]
        try:
            s = pushout_runs.summary(folder)
        except (OSError, ValueError):  # refused before it wrote one
            print(f"corroded {name}: no summary.json (the run's words are its stderr)")
            continue
        if not s["converged"]:
            print(f"corroded {name}: did not converge: {s['message']}")
            continue
        where, cracks, beta, x = name.split("_")
        corr = pushout_runs.corrosion(folder) if os.path.exists(os.path.join(folder, "corrosion.csv")) else []
        table.append({"case": name, "tube": where, "cracks": cracks, "beta": float(beta[4:]),
                      "x_um": float(x[1:]), "p_after_corrosion_MPa": rows[0]["p_MPa"],
                      "crack_width_um": 1e3 * corr[-1]["crack_width_mm"] if corr else 0.0,
                      "tau_peak_MPa": max(r["tau_MPa"] for r in rows),
                      "tau_residual_MPa": rows[-1]["tau_MPa"]})
    if not table:
        raise SystemExit("studies.py: corroded: no case converged: no table, no figure")
    pushout_runs.write_csv(os.path.join(out, "corroded.csv"), table)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), dpi=120, sharey=True)
    styles = {("centred", "one"): "o-", ("centred", "four"): "s-", ("cover15", "one"): "o--",
              ("cover15", "four"): "s--"}
    for (where, cracks), style in styles.items():
        for beta, color in ((2.0, "tab:blue"), (3.0, "tab:red")):
            sel = sorted((r for r in table if r["tube"] == where and r["cracks"] == cracks
                          and r["beta"] == beta), key=lambda r: r["x_um"])
            label = f"{where}, {cracks} crack{'s' if cracks == 'four' else ''}, $\\beta$ {beta:g}"
            axes[0].plot([r["x_um"] for r in sel], [r["tau_residual_MPa"] for r in sel], style,
                         color=color, ms=4, label=label)
            axes[1].plot([r["crack_width_um"] for r in sel], [r["tau_residual_MPa"] for r in sel],
                         style, color=color, ms=4)
    axes[0].set(xlabel="corrosion depth $x$ [µm]", ylabel="residual bond stress $\\tau$ [MPa]")
    axes[1].set(xlabel="crack-mouth opening after corrosion [µm]")
    for ax in axes:
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.suptitle("Corroded push-out: bond left against corrosion depth and crack width (assumed parameters)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "corroded_residual_bond.png"))
    return table


def at_delta(rows, d, key):
    """`key` of a curve at delta d [mm], linear between its rows."""
    for a, b in zip(rows, rows[1:]):
        if a["delta_mm"] <= d <= b["delta_mm"]:
            t = (d - a["delta_mm"]) / (b["delta_mm"] - a["delta_mm"])
            return a[key] + t * (b[key] - a[key])
    return float("nan")


def plot_laws(out, runs):
    """§2.3 rerun: the curves of each adhesion law alone and with friction
    (OUT/laws_comparison.png), and OUT/laws.csv: peak, residuals, the spread
    of t_s1 after the peak, the initial damage (held or free tube top)."""
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), dpi=120, sharey=True)
    table = []
    for ax, mu in zip(axes, (0.0, 0.4)):
        for i, law in enumerate(ADHESION_LAWS):
            rows = runs[("laws", f"{law}_mu{mu:g}")]
            ax.plot([r["delta_mm"] * 1e3 for r in rows], [r["tau_MPa"] for r in rows], "-",
                    color=f"C{i}", lw=1.3, label=law.replace("_", " "))
            peak = max(rows, key=lambda r: r["tau_MPa"])
            row = {"case": f"{law}_mu{mu:g}", "peak_tau_MPa": round(peak["tau_MPa"], 4),
                   "delta_peak_um": round(peak["delta_mm"] * 1e3, 2)}
            for d in SPREAD_AT_MM:
                row[f"tau_{d:g}mm_MPa"] = round(at_delta(rows, d, "tau_MPa"), 4)
                row[f"t_s1_cv_{d:g}mm"] = round(at_delta(rows, d, "t_s1_cv"), 4)
                row[f"t_s1_range_{d:g}mm_MPa"] = (
                    f"{at_delta(rows, d, 't_s1_min_MPa'):.3f}..{at_delta(rows, d, 't_s1_max_MPa'):.3f}")
            table.append(row)
        ax.set(xlabel="tube displacement $\\delta$ [µm]", xlim=(0, 200),
               title="adhesion alone (friction layer at $\\mu$ 0)" if mu == 0 else
               "adhesion with friction ($\\mu$ 0.4)")
        ax.grid(alpha=0.3)
    finish_pair(fig, axes, "§2.3 rerun: adhesion laws (f_t 3 MPa, softening energy 0.12 N/mm), "
                "$\\Delta T$ -25 °C", os.path.join(out, "laws_comparison.png"))
    for top in ("held", "free"):
        for dT in (-25.0, -50.0):
            rows = runs[("laws", f"damage_{top}_dT{dT:g}")]
            peak = max(rows, key=lambda r: r["tau_MPa"])
            table.append({"case": f"damage_{top}_dT{dT:g}", "peak_tau_MPa": round(peak["tau_MPa"], 4),
                          "delta_peak_um": round(peak["delta_mm"] * 1e3, 2),
                          "d_1_mean_step0": round(rows[0]["d_1_mean"], 4),
                          "d_1_max_step0": round(rows[0]["d_1_max"], 4),
                          "tau_step0_MPa": round(rows[0]["tau_MPa"], 4)})
    keys = []
    for r in table:
        keys += [k for k in r if k not in keys]
    with open(os.path.join(out, "laws.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(table)
    return table


def plot_unload_reload(out, runs):
    """The loops against the monotonic curve, whole and the first 50 um;
    returns the permanent displacements [mm]."""
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), dpi=120, sharey=True)
    mono, loops = runs[("unload_reload", "monotonic")], runs[("unload_reload", "loops")]
    permanent = pushout_runs.summary(os.path.join(out, "unload_reload", "loops"))[
        "permanent_displacements_mm"]
    for ax, x_max in zip(axes, (None, 50)):
        ax.plot([r["delta_mm"] * 1e3 for r in mono], [r["tau_MPa"] for r in mono], "-",
                color="0.6", lw=2.5, label="monotonic push")
        ax.plot([r["delta_mm"] * 1e3 for r in loops], [r["tau_MPa"] for r in loops], "o-", ms=2.5,
                lw=1, color="C3", label="unloaded to zero force and reloaded")
        ax.plot([d * 1e3 for d in permanent], [0.0] * len(permanent), "kv", ms=6,
                label="permanent displacements " +
                      ", ".join(f"{d * 1e3:.1f}" for d in permanent) + " µm")
        ax.axhline(0, color="0.6", lw=0.5)
        ax.set(xlabel="tube displacement $\\delta$ [µm]")
        if x_max:
            ax.set_xlim(0, x_max)
        ax.grid(alpha=0.3)
    finish_pair(fig, axes, "Unload and reload: friction 2 + exp. soft. (c 25), $\\Delta T$ -25 °C",
                os.path.join(out, "unload_reload.png"))
    return permanent


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=os.path.join(ROOT, "results", "studies"))
    ap.add_argument("--pushout", default=os.path.join(ROOT, "build", "pushout"))
    ap.add_argument("--quick", action="store_true", help="coarse mesh, few steps")
    ap.add_argument("--jobs", type=argument_types.positive_int, default=os.cpu_count() or 1)
    ap.add_argument("--only", nargs="+",
                    default=["fig7", "fig8", "fig10", "retraction", "unload_reload", "laws"],
                    choices=STUDIES)
    ap.add_argument("--no-render", action="store_true",
                    help="run the fig8 case but do not render its maps (ParaView)")
    ap.add_argument("--reuse", action="store_true",
                    help="keep runs that already converged in OUT from the same scene and values "
                         "(after an interrupted set)")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    if "corroded" in args.only:
        four_cracks_scene(args.out)
    if any(s in args.only for s in embedded_study.STUDIES):
        embedded_study.write_scene(args.out)
    if "laws" in args.only:
        law_scenes(args.out)

    t0 = time.time()
    todo = [(study, name, scene, sets) for study in args.only for name, scene, sets in cases(study, args.quick)]
    runs, seconds = {}, {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = {pool.submit(run_case, args.pushout, study, os.path.join(args.out, study, name), scene,
                               sets, args.quick, args.reuse): (study, name)
                   for study, name, scene, sets in todo}
        for f in concurrent.futures.as_completed(futures):
            study, name = futures[f]
            try:
                seconds[f"{study}/{name}"] = f.result()
            except (pushout_runs.RunError, OSError) as e:
                # The set's figures need every run: the others are not waited for.
                for other in futures:
                    other.cancel()
                raise SystemExit(f"studies.py: {study}/{name}: {e}")
            try:
                runs[(study, name)] = pushout_runs.curve(os.path.join(args.out, study, name))
            except OSError:  # a run that failed before its push (reported with its table)
                runs[(study, name)] = []
            print(f"{study}/{name}: {seconds[f'{study}/{name}']:.1f} s", flush=True)

    if "fig7" in args.only:
        plot_fig7(args.out, runs)
    if "fig10" in args.only:
        plot_fig10(args.out, runs)
    if "retraction" in args.only:
        plot_retraction(args.out, runs)
    if "laws" in args.only:
        for r in plot_laws(args.out, runs):
            print("laws " + ", ".join(f"{k} {v}" for k, v in r.items()))
    if "unload_reload" in args.only:
        permanent = plot_unload_reload(args.out, runs)
        print("unload_reload: permanent displacements " +
              ", ".join(f"{d * 1e3:.3f} um" for d in permanent))
    if "corroded" in args.only:
        for r in plot_corroded(args.out, runs):
            print(f"corroded {r['case']}: p {r['p_after_corrosion_MPa']:.2f} MPa, crack "
                  f"{r['crack_width_um']:.1f} um, residual tau {r['tau_residual_MPa']:.3f} MPa")
    for study in (s for s in embedded_study.STUDIES if s in args.only):
        for g in embedded_study.report(plt, args.out, runs, study):
            if not g["seeds"]:
                print(f"{study} {g['tube']} beta {g['beta']:g} x {g['x_um']:g} um: none of "
                      f"{g['seeds_run']} seeds converged")
                continue
            print(f"{study} {g['tube']} beta {g['beta']:g} x {g['x_um']:g} um "
                  f"({g['seeds']} seeds): residual tau {g['tau_residual_MPa_mean']:.3f} "
                  f"[{g['tau_residual_MPa_min']:.3f}, {g['tau_residual_MPa_max']:.3f}] MPa, "
                  f"surface crack {g['surface_crack_um_mean']:.1f} um")
    render_failed = None
    if "fig8" in args.only and not args.no_render:
        try:
            render_fig8(args.out, os.path.join(args.out, "fig8", "mu0.4_dT-5"))
        except RenderError as e:  # the other figures and tables still get written
            render_failed = f"fig8 interface maps not rendered: {e}"
    if any(s in args.only for s in ("fig7", "retraction")):
        for r in plateau_table(args.out, runs):
            print(f"plateau {r['study']}/{r['case']}: tau {r['tau_plateau_MPa']:.4f} MPa, "
                  f"mu p {r['mu_p_MPa']:.4f} MPa, ratio {r['ratio']:.4f}")
    total = time.time() - t0
    with open(os.path.join(args.out, "timing.json"), "w") as f:
        json.dump({"wall_s": total, "jobs": args.jobs, "quick": args.quick, "runs_s": seconds}, f, indent=2)
    print(f"studies done in {total:.0f} s ({len(todo)} runs, {args.jobs} at a time); figures in {args.out}")
    if render_failed:
        print("studies.py: error: " + render_failed, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/python3
"""Cracks anywhere in the concrete on finer and finer meshes: one case of the
corroded study (docs/corrosion.md, scripts/embedded_study.py) on up to seven
meshes, to see whether its answer converges (docs/cracking.md, "Mesh
objectivity").

The case: the tube 15 mm from a face, beta 2 (--beta), strength field seed 1,
corroded to x = 50 um in 20 steps, pushed 0.2 mm in 20 steps, with the scene
and keys of the study that docs/corrosion.md leads with (STUDY: today's
default integration, IMPL-EX with the strain predictor); meshes (elements per quarter /
through the thickness) 12/4 (the study's), 12/8, 16/8 (the paper's), 24/8,
32/8, 40/8 and 48/8 (the last two some 15 min each). The random strength
field is a function of position, the same on every mesh.

For each: the oxide's pressure after corrosion, the widest surface crack and
its angle, the energy the concrete's cracks dissipated, the bond's peak and
its residual at 0.2 mm, and each one's difference from the finest mesh; the
graded cells' shape (radial_over_hoop: the median cell's extent along the
radius over that along the hoop, 15 to 40 mm from the tube axis); Newton
iterations and wall time (one thread each, one after the other).
Writes bench/results/cracking_mesh.csv, .md and .png (the corrosion and
push curves of every mesh); with --study corroded_embedded_row_band, the
case with that study's keys (the crack band the width of the thinnest row
of cells, cracking.band_width = "row"), into cracking_mesh_row_band.*. With
--lines radial, the graded concrete's lines along rays from the tube axis
(mesh.graded_lines = "radial"), into cracking_mesh[_row_band]_radial.*; with
--outer-size-ratio R, mesh.outer_size_ratio = R (1: graded cells no larger
than the interface's, so that they do not grow more elongated as the mesh is
refined round the tube), into ..._ratioR.*; with --graded-refinement whole,
mesh.graded_refinement = "whole" (every graded cell shrinks with the
interface's, as with ratio 1 but growing to outer_size_ratio: fewer
elements), into ..._whole.*. With --tube centred, the same
case with the tube in the slice's middle (the study's other place), into
cracking_mesh[_row_band]_centred[...].*. With --seed N, the strength field's
seed N instead of 1 (the study's other seeds), into ..._seedN.*; with
--beta 3, the oxide's expansion beta 3 instead of 2 (the study's other
rust: the cover's crack some twice as wide at x = 50 um), into
cracking_mesh[...][_centred]_beta3[...].*.

  bench/cracking_mesh.py [--reuse] [--only MESH ...] [--study STUDY] [--lines radial]
                         [--outer-size-ratio R] [--graded-refinement whole] [--tube centred]
                         [--seed N] [--beta 3]   (MESH as 16x8)
"""
import os
import sys
import time

from common import (ROOT, arguments, check_only, curve, markdown_table, pushout_runs, run, summary,
                    write_csv)

sys.path.insert(0, os.path.join(ROOT, "scripts"))
import embedded_study  # noqa: E402
import plot_curve  # noqa: E402

RESULTS = os.path.join(ROOT, "bench", "results")
# The case: where the tube is (--tube, a WHERE of scripts/embedded_study.py),
# then beta (--beta, 2 by default), the strength field's seed (--seed, 1 by
# default), x = 50 um.
CASE = "{tube}_beta{beta:g}_seed{seed}_x50"
TUBES = tuple(where for (where, _) in embedded_study.WHERE)
DEFAULT_TUBE = "cover15"
# The study whose keys the case takes (scripts/embedded_study.py STUDIES). The
# table made with the implicit cracks under loading.control = "auto" (the
# study "corroded_embedded") on the mesh before dc44ed8 is kept as
# bench/results/cracking_mesh_1dcec97.md.
STUDY = "corroded_embedded_implex_strain"
# --study: the same case with another study's keys; its table is
# bench/results/cracking_mesh_<study less "corroded_embedded_">.md.
OTHER_STUDIES = ("corroded_embedded_row_band",)
MESHES = ((12, 4), (12, 8), (16, 8), (24, 8), (32, 8), (40, 8), (48, 8))


def case_name(tube, beta=2.0, seed=1):
    """CASE with the tube at `tube`, `beta` and the strength field's `seed`."""
    return CASE.format(tube=tube, beta=beta, seed=seed)


def study_sets(study, tube, beta=2.0, seed=1):
    """The --set list of case_name(tube, beta, seed) in `study`."""
    return next(sets for (name, _, sets) in embedded_study.cases(quick=False, study=study)
                if name == case_name(tube, beta, seed))


def case_suffix(tube, beta):
    """The folder and file name suffix of the case's place and beta where they
    are not the default's ("" for neither)."""
    return ("" if tube == DEFAULT_TUBE else "_" + tube) + ("" if beta == 2 else f"_beta{beta:g}")


def variant(args):
    """The mesh keys beyond the meshes' counts that the options set, and the
    folder and file name suffix they give ("" for none; the tube's place and
    beta, when they are not the default's, are in the suffix too)."""
    sets, suffix = [], case_suffix(args.tube, args.beta)
    if args.lines != "blocks":
        sets.append(f"mesh.graded_lines={args.lines}")
        suffix += "_" + args.lines
    if args.outer_size_ratio is not None:
        sets.append(f"mesh.outer_size_ratio={args.outer_size_ratio:g}")
        suffix += f"_ratio{args.outer_size_ratio:g}"
    if args.graded_refinement != "near_tube":
        sets.append(f"mesh.graded_refinement={args.graded_refinement}")
        suffix += "_" + args.graded_refinement
    if args.seed != 1:
        suffix += f"_seed{args.seed}"
    return sets, suffix


def results_name(study, suffix):
    """The base name of the bench's table and figure for `study` with the
    mesh variant's `suffix`."""
    name = "cracking_mesh" if study == STUDY else "cracking_mesh_" + study.replace(
        "corroded_embedded_", "")
    return name + suffix


def radial_frame(corners, axis):
    """A quadrilateral's corners as an array, its centre's distance r from
    the tube axis [mm], and the unit vectors along the radius and the hoop
    there, in the slice's plane."""
    import numpy as np
    P = np.array(corners)
    t = P.mean(axis=0) - np.asarray(axis)
    r = np.linalg.norm(t)
    return P, r, t / r, np.array([-t[1], t[0]]) / r


def cell_shape(out):
    """The median over the concrete cells 15 to 40 mm from the tube axis (the
    graded cells the corrosion cracks) of a cell's extent along the radius
    over its extent along the hoop, in the slice's plane (crack_pattern.csv's
    outlines): 1 for square cells, the same on every mesh of a family refined
    alike in the slice's plane."""
    import numpy as np
    axis = plot_curve.read_scene(os.path.join(out, "scene.toml"))["center"]
    shapes = []
    for corners in plot_curve.cell_outlines(plot_curve.read(os.path.join(out, "crack_pattern.csv"))):
        P, r, radial, hoop = radial_frame(corners, axis)
        if 15 < r < 40:
            shapes.append(np.ptp(P @ radial) / np.ptp(P @ hoop))
    return float(np.median(shapes))


def row(out, mesh, wall_s):
    s = summary(out)
    corr = pushout_runs.corrosion(out)
    push = curve(out)
    concrete = [c for c in s.get("cracks", []) if c["source"] == "concrete"]
    widest = max(concrete, key=lambda c: c["width_mm"]) if concrete else None
    return {"mesh": f"{mesh[0]}/{mesh[1]}", "converged": s["converged"], "dofs": s["dofs"],
            "p_after_corrosion_MPa": round(push[0]["p_MPa"], 3),
            "surface_crack_um": round(1e3 * corr[-1]["crack_width_mm"], 1),
            "widest_angle_deg": round(widest["angle_deg"], 1) if widest else "",
            "concrete_dissipation_Nmm": round(corr[-1]["concrete_dissipation_Nmm"], 1),
            "tau_peak_MPa": round(max(r["tau_MPa"] for r in push), 3),
            "tau_residual_MPa": round(push[-1]["tau_MPa"], 3),
            "radial_over_hoop": round(cell_shape(out), 2),
            "newton_iterations": s["newton_iterations"], "wall_s": round(wall_s, 1)}


def plot(rows, folders, name, tube, beta, seed):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2), dpi=110)
    for r, out in zip(rows, folders):
        corr = pushout_runs.corrosion(out)
        push = curve(out)
        a.plot([1e3 * c["penetration_mm"] for c in corr], [c["p_MPa"] for c in corr], label=r["mesh"])
        b.plot([1e3 * p["delta_mm"] for p in push], [p["tau_MPa"] for p in push], label=r["mesh"])
    a.set(xlabel="corrosion depth x [um]", ylabel="oxide pressure p [MPa]",
          title=f"corrosion ({'cover 15 mm' if tube == 'cover15' else tube}, beta {beta:g}, "
                f"seed {seed})")
    b.set(xlabel="slip delta [um]", ylabel="bond stress tau [MPa]", title="push after x = 50 um")
    for ax in (a, b):
        ax.grid(alpha=0.3)
        ax.legend(title="per quarter / thickness")
    fig.tight_layout()
    fig.savefig(os.path.join(RESULTS, name + ".png"))


def hoop_band_ratio(corners, axis):
    """A quadrilateral's row width over its extent along the hoop direction
    at its centre (the two bands of model/CellWidth.h for a radial crack, in
    the slice's plane); corners in order round it [mm]."""
    import numpy as np
    P, _, _, n = radial_frame(corners, axis)
    extent = np.ptp(P @ n)
    e1 = (P[1] - P[0] + P[2] - P[3]) / 2
    e2 = (P[3] - P[0] + P[2] - P[1]) / 2
    grad = np.linalg.inv(np.column_stack([e1, e2]))  # rows: grad xi_i at the centre
    return min([extent] + [1 / abs(g @ n) for g in grad if abs(g @ n) > 0]) / extent


def plot_layouts(folders):
    """The slice's cells of two meshes side by side (`folders`: layout ->
    a run's folder), coloured by hoop_band_ratio: where the projected band is
    wider than the row of a radial crack."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    fig, axes = plt.subplots(1, len(folders), figsize=(5.2 * len(folders), 4.6), dpi=110)
    for ax, (layout, out) in zip(axes, folders.items()):
        cells = plot_curve.cell_outlines(plot_curve.read(os.path.join(out, "crack_pattern.csv")))
        slice_ = plot_curve.read_scene(os.path.join(out, "scene.toml"))
        shapes = PolyCollection(cells, array=[hoop_band_ratio(c, slice_["center"]) for c in cells],
                                cmap="viridis", edgecolors="k", linewidths=0.2)
        shapes.set_clim(0.4, 1)
        ax.add_collection(shapes)
        ax.set(xlim=(0, slice_["width"]), ylim=(0, slice_["width"]), aspect="equal",
               xlabel="x [mm]", ylabel="y [mm]",
               title=f"mesh.graded_lines = \"{layout}\" ({os.path.basename(out)})")
        fig.colorbar(shapes, ax=ax, label="row width / extent along the hoop direction")
    fig.tight_layout()
    fig.savefig(os.path.join(RESULTS, "cracking_mesh_layouts.png"))


def main():
    args = arguments(__doc__, "bench_cracking_mesh", studies=(STUDY, *OTHER_STUDIES),
                     options=[("--lines", {"choices": ("blocks", "radial"), "default": "blocks",
                                           "help": "mesh.graded_lines"}),
                              ("--outer-size-ratio", {"type": float, "default": None,
                                                      "help": "mesh.outer_size_ratio"}),
                              ("--tube", {"choices": TUBES, "default": DEFAULT_TUBE,
                                          "help": "where the tube is (the study's places)"}),
                              ("--graded-refinement", {"choices": ("near_tube", "whole"),
                                                       "default": "near_tube",
                                                       "help": "mesh.graded_refinement"}),
                              ("--seed", {"type": int, "default": 1,
                                          "choices": embedded_study.SEEDS,
                                          "help": "the strength field's seed"}),
                              ("--beta", {"type": float, "default": 2.0,
                                          "choices": embedded_study.BETAS,
                                          "help": "corrosion.beta"})])
    check_only(args, [f"{m[0]}x{m[1]}" for m in MESHES])
    mesh_sets, suffix = variant(args)
    name = results_name(args.study, suffix)
    scene = embedded_study.write_scene(args.out)
    rows, folders = [], []
    for mesh in MESHES:
        if args.only and f"{mesh[0]}x{mesh[1]}" not in args.only:
            continue
        # The default study's runs where they always were (--reuse).
        out = os.path.join(args.out, *([suffix[1:]] if suffix else []),
                           *([] if args.study == STUDY else [args.study]), f"{mesh[0]}x{mesh[1]}")
        sets = study_sets(args.study, args.tube, beta=args.beta, seed=args.seed) + [
            f"mesh.elements_per_quarter={mesh[0]}",
            f"mesh.elements_through_thickness={mesh[1]}"] + mesh_sets
        start = time.time()
        code = run(args.pushout, scene, out, sets, reuse=args.reuse, check=False)
        print(f"{mesh}: exit {code}, {time.time() - start:.1f} s", flush=True)
        rows.append(row(out, mesh, summary(out)["wall_s"]))
        folders.append(out)
    finest = rows[-1]
    for r in rows:
        for key in ("p_after_corrosion_MPa", "concrete_dissipation_Nmm", "tau_residual_MPa"):
            r[key.rsplit("_", 1)[0] + "_vs_finest"] = f"{r[key] / finest[key] - 1:+.1%}"
    os.makedirs(RESULTS, exist_ok=True)
    write_csv(os.path.join(RESULTS, name + ".csv"), rows)
    plot(rows, folders, name, args.tube, args.beta, args.seed)
    with open(os.path.join(RESULTS, name + ".md"), "w") as f:
        f.write(f"# Cracks anywhere: one case of the corroded study on {len(rows)} meshes\n\n"
                "Made by `bench/cracking_mesh.py"
                + ("" if args.study == STUDY else f" --study {args.study}")
                + ("" if args.lines == "blocks" else f" --lines {args.lines}")
                + ("" if args.outer_size_ratio is None
                   else f" --outer-size-ratio {args.outer_size_ratio:g}")
                + ("" if args.graded_refinement == "near_tube"
                   else f" --graded-refinement {args.graded_refinement}")
                + ("" if args.tube == DEFAULT_TUBE else f" --tube {args.tube}")
                + ("" if args.seed == 1 else f" --seed {args.seed}")
                + ("" if args.beta == 2 else f" --beta {args.beta:g}")
                + ("" if not args.only else " --only " + " ".join(args.only)) +
                "` (one thread per run, this machine, one run "
                f"each): {case_name(args.tube, args.beta, args.seed)} with the scene and keys of the study {args.study}"
                + "".join(", " + s.replace("=", " = ") for s in mesh_sets) + "; the mesh is "
                "elements per quarter / through the thickness, the differences are from the "
                "finest. wall_s is each run's own, and runs may have shared the machine "
                "(timings: bench/cracking_speed.py).\n\n")
        f.write(markdown_table(list(rows[0].keys()), rows))
        f.write(f"\n![curves]({name}.png)\n")
    # Both layouts' paper's meshes (the default study's runs), once both
    # have run.
    paper = {lines: os.path.join(args.out, *([] if lines == "blocks" else [lines]), "16x8")
             for lines in ("blocks", "radial")}
    if args.study == STUDY and args.tube == DEFAULT_TUBE and args.seed == 1 and all(
            os.path.exists(os.path.join(out, "crack_pattern.csv")) for out in paper.values()):
        plot_layouts(paper)


if __name__ == "__main__":
    main()

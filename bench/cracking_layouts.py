#!/usr/bin/python3
"""Cracks anywhere in the concrete on four mesh layouts, over the strength
field's seeds: what the mesh's layout does to the corroded study's answer
beside the seeds' spread (docs/cracking.md, "Radial graded lines").

The case of bench/cracking_mesh.py (the tube 15 mm from a face, or centred
with --tube centred; beta 2, or 3 with --beta 3; corroded to x = 50 um in 20 steps,
pushed 0.2 mm in 20 steps, the keys of the study docs/corrosion.md leads
with) for the strength field's seeds 1-5, on one mesh count (--mesh, 16x8
by default: the paper's) with four layouts of the graded concrete:

  blocks         the default (mesh.graded_lines = "blocks")
  radial         its lines along rays from the tube axis (mesh.graded_lines
                 = "radial"), the same cell counts
  radial_ratio1  radial lines and mesh.outer_size_ratio = 1: graded cells no
                 larger than the interface's, of the same shape on every
                 mesh (bench/cracking_mesh.py's radial_over_hoop), some 3
                 times the dofs
  radial_whole   radial lines and mesh.graded_refinement = "whole": graded
                 cells that shrink with the interface's and keep their
                 shape, growing to outer_size_ratio as the default's; some
                 1.2 times the dofs

For each run the oxide's pressure after corrosion, the widest surface crack,
the concrete's dissipation and the residual bond at 0.2 mm; per layout the
converged seeds' mean, min and max, and each seed's difference from
radial_ratio1's run of the same seed (radial_whole's where --only leaves
radial_ratio1 out). With --tolerance T,
cracking.implex_tolerance = T on every run (the study's IMPL-EX steps held
tighter or looser than its default; into ..._tolT). Runs --jobs at a time (2 by default),
one thread each; a run that ends without a summary stops the bench.
Writes bench/results/cracking_layouts[_centred][_betaB][_MESH][_tolT].csv and
.md (MESH when not 16x8).

  bench/cracking_layouts.py [--reuse] [--only LAYOUT ...] [--tube centred] [--beta 3]
                            [--mesh 12x4] [--tolerance T] [--jobs N]
"""
import concurrent.futures
import os
import statistics
import sys
import time

from common import arguments, check_only, markdown_table, run, summary, write_csv
import argument_types
import cracking_mesh

LAYOUTS = {"blocks": [], "radial": ["mesh.graded_lines=radial"],
           "radial_ratio1": ["mesh.graded_lines=radial", "mesh.outer_size_ratio=1"],
           "radial_whole": ["mesh.graded_lines=radial", "mesh.graded_refinement=whole"]}
# Each run is compared with the run of the same seed on the first of these
# layouts that the bench ran (radial_ratio1's cells keep their shape on every
# mesh; radial_whole's too, at fewer dofs).
REFERENCES = ("radial_ratio1", "radial_whole")
SEEDS = (1, 2, 3, 4, 5)
QUANTITIES = ("p_after_corrosion_MPa", "surface_crack_um", "concrete_dissipation_Nmm",
              "tau_residual_MPa")


def main():
    args = arguments(__doc__, "bench_cracking_layouts", studies=(cracking_mesh.STUDY,),
                     options=[("--tube", {"choices": cracking_mesh.TUBES,
                                          "default": cracking_mesh.DEFAULT_TUBE}),
                              ("--beta", {"type": float, "default": 2.0,
                                          "choices": cracking_mesh.embedded_study.BETAS}),
                              ("--mesh", {"default": "16x8", "type": argument_types.mesh_size,
                                          "help": "per quarter x through"}),
                              ("--tolerance", {"type": float, "default": None,
                                               "help": "cracking.implex_tolerance"}),
                              ("--jobs", {"type": argument_types.positive_int, "default": 2})])
    check_only(args, list(LAYOUTS))
    mesh = tuple(int(n) for n in args.mesh.split("x"))
    suffix = cracking_mesh.case_suffix(args.tube, args.beta) + \
        ("" if args.mesh == "16x8" else "_" + args.mesh) + \
        ("" if args.tolerance is None else f"_tol{args.tolerance:g}")
    tolerance = [] if args.tolerance is None else [f"cracking.implex_tolerance={args.tolerance:g}"]
    scene = cracking_mesh.embedded_study.write_scene(args.out)
    layouts = [name for name in LAYOUTS if not args.only or name in args.only]
    runs = {}  # (layout, seed) -> its folder
    for layout in layouts:
        for seed in SEEDS:
            runs[layout, seed] = os.path.join(args.out, suffix[1:] or "default", layout,
                                              f"seed{seed}")

    def one(key):
        layout, seed = key
        sets = cracking_mesh.study_sets(args.study, args.tube, args.beta, seed) + \
            [f"mesh.elements_per_quarter={mesh[0]}", f"mesh.elements_through_thickness={mesh[1]}"] + \
            LAYOUTS[layout] + tolerance
        start = time.time()
        code = run(args.pushout, scene, runs[key], sets, reuse=args.reuse, check=False)
        print(f"{layout} seed {seed}: exit {code}, {time.time() - start:.1f} s", flush=True)

    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        list(pool.map(one, runs))
    missing = [out for out in runs.values() if not os.path.exists(os.path.join(out, "summary.json"))]
    if missing:
        sys.exit("cracking_layouts.py: no summary.json (the run failed to start or was "
                 "killed): " + ", ".join(missing))

    rows = []
    for (layout, seed), out in runs.items():
        r = cracking_mesh.row(out, mesh, summary(out)["wall_s"])
        rows.append({"layout": layout, "seed": seed, "converged": r["converged"], "dofs": r["dofs"],
                     **{q: r[q] for q in QUANTITIES}, "radial_over_hoop": r["radial_over_hoop"],
                     "wall_s": r["wall_s"]})
    by = {(r["layout"], r["seed"]): r for r in rows}
    reference = next((name for name in REFERENCES if name in layouts), None)
    for r in rows if reference else []:
        ref = by.get((reference, r["seed"]))
        r["tau_residual_vs_" + reference] = (
            f"{r['tau_residual_MPa'] / ref['tau_residual_MPa'] - 1:+.1%}" if ref else "")
    groups = []
    for layout in layouts:
        mine = [r for r in rows if r["layout"] == layout and r["converged"]]
        g = {"layout": layout, "seeds": len(mine),
             "not_converged": sum(1 for r in rows if r["layout"] == layout and not r["converged"])}
        for q in QUANTITIES:
            values = [r[q] for r in mine]
            g[q] = f"{statistics.mean(values):.3f} [{min(values):.3f}, {max(values):.3f}]" \
                if values else ""
        groups.append(g)

    results = os.path.join(cracking_mesh.RESULTS, "cracking_layouts" + suffix)
    os.makedirs(cracking_mesh.RESULTS, exist_ok=True)
    write_csv(results + ".csv", rows)
    with open(results + ".md", "w") as f:
        f.write("# Cracks anywhere: mesh layouts over the strength field's seeds\n\n"
                "Made by `bench/cracking_layouts.py"
                + ("" if args.tube == cracking_mesh.DEFAULT_TUBE else f" --tube {args.tube}")
                + ("" if args.beta == 2 else f" --beta {args.beta:g}")
                + ("" if args.mesh == "16x8" else f" --mesh {args.mesh}")
                + ("" if args.tolerance is None else f" --tolerance {args.tolerance:g}")
                + ("" if not args.only else " --only " + " ".join(args.only))
                + f" --jobs {args.jobs}"
                + "` (one thread per run, this machine; wall_s may have shared it): "
                f"{cracking_mesh.case_name(args.tube, args.beta, 'N')} for seeds "
                f"{', '.join(map(str, SEEDS))} with the keys of the study {args.study}, "
                f"{mesh[0]} elements per quarter, {mesh[1]} through the thickness"
                + ("" if args.tolerance is None
                   else f", cracking.implex_tolerance = {args.tolerance:g}") + "; "
                "the layouts as in the script's help. Per layout, the converged seeds' "
                "mean [min, max]:\n\n")
        f.write(markdown_table(list(groups[0].keys()), groups))
        f.write("\nEach run" + (f" (tau_residual_vs_{reference}: against that layout's run "
                                 "of the same seed)" if reference else "") + ":\n\n")
        f.write(markdown_table(list(rows[0].keys()), rows))


if __name__ == "__main__":
    main()

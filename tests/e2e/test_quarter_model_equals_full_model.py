"""Exact symmetry (model.symmetry = "auto"): a centred push-out runs on a
quarter of the mesh with symmetry conditions and gives the plain
full-Newton full model's curve (friction + adhesion through the peak, with the
thermal step); a tube centred in one direction only runs on a half; crack
planes on a symmetry plane become mirror cracks (one face, opening twice its
normal displacement) and the others' images are cut away: the corrosion
stage and the push equal the full model's (one crack to the nearest
face of an off-centre tube: a half; four cracks on the planes, and four
cracks between them: quarters). Scenes without the symmetry, or asking for
fields under "auto", run on the full model; "symmetric" keeps its cut with
fields (the part's), and the same curve. Each comparison is of two models
or solvers that sum in other orders: to Newton's bound on the two runs
(common.newton_bound over the steps of both stages, corrosion and push:
the laws carry each step's error on)."""
import os
import re

from common import (COARSE_MESH, EXP_SOFT, FRICTION_2, OUT_ROOT, THROUGH_PEAK, check, corrosion,
                    curve, newton_bound, out_dir, run, solved_unknowns, summary)

scene = COARSE_MESH + FRICTION_2 + EXP_SOFT + THROUGH_PEAK
# The quarter model with the default (lagged) solver against the plain
# full-Newton full model (LU of every Jacobian).
quarter, full = out_dir("symmetry_quarter"), out_dir("symmetry_full")
run(scene, quarter)
run(scene, full, sets=["model.symmetry=full", "solver.preconditioner=jacobian",
                       "solver.condensation=off"])
sq, sf = summary(quarter), summary(full)
check(sq["symmetry"] == "quarter" and sf["symmetry"] == "full",
      f"auto -> {sq['symmetry']}, full -> {sf['symmetry']}")
check(sq["dofs"] < 0.35 * sf["dofs"] and 4 * sq["interface_pairs"] == sf["interface_pairs"],
      f"quarter: {sq['dofs']} dofs, {sq['interface_pairs']} joints; full: {sf['dofs']} dofs, "
      f"{sf['interface_pairs']} joints")
check(len(curve(quarter)) == len(curve(full)) == 11, "both converged through 10 steps")


def bound(part, full):
    """Newton's bound on the relative difference of two runs' columns (their
    folders): over every step either made, the corrosion stage's too."""
    s = [summary(part), summary(full)]
    steps = max(x["steps"] + x.get("corrosion_steps", 0) + 1 for x in s)
    return newton_bound(steps, max(solved_unknowns(x) for x in s))


def same(name, part, full, read, keys):
    """Columns `keys` of two runs' tables (`read` of their folders) agree
    to Newton's bound x their largest value."""
    a, b, tol = read(part), read(full), bound(part, full)
    check(len(a) == len(b) and len(a) > 1, f"{name}: {len(a)} and {len(b)} rows")
    for key in keys:
        scale = max(abs(r[key]) for r in b) or 1.0
        diff = max(abs(x[key] - y[key]) for x, y in zip(a, b))
        check(diff <= tol * scale, f"{name}: {key}: max |part - full| = {diff:.1e} <= {tol:.1e} x {scale:.4g}")


same("quarter, lagged", quarter, full, curve, ("P_N", "tau_MPa", "p_MPa", "slip_mm"))


# A tube centred in one direction only: a half model, about y = yc or x = xc.
# (Off-centre in y, the full model's fixings lie on the plane x = xc or in
# mirror pairs, so that none carries a force: a tube-top fixing in y would
# hold the tube's shift against the slice, 3.5e-5 off.)
for name, centre in (("off centre in x", "[42.0, 50.0]"), ("off centre in y", "[50.0, 40.0]")):
    half, full = out_dir(f"symmetry_half_{name[-1]}"), out_dir(f"symmetry_half_{name[-1]}_full")
    off_centre = [f"geometry.tube_center={centre}"]
    run(scene, half, sets=off_centre)
    run(scene, full, sets=off_centre + ["model.symmetry=full"])
    sh, sf = summary(half), summary(full)
    check(sh["symmetry"] == "half" and 2 * sh["interface_pairs"] == sf["interface_pairs"],
          f"tube {name}: {sh['symmetry']} model, {sh['interface_pairs']} of "
          f"{sf['interface_pairs']} joints")
    same(f"half, no crack, tube {name}", half, full, curve, ("P_N", "tau_MPa", "p_MPa", "slip_mm"))

# Crack planes.
corroded = open(os.path.join(os.environ.get("PUSHOUT_SOURCE_DIR", "."), "demo",
                             "pushout_corroded.toml")).read()
centred = corroded.replace("tube_center = [50.0, 25.0]", "tube_center = [50.0, 50.0]")
assert centred != corroded
without_crack = corroded[:corroded.index("[[crack]]")] + corroded[corroded.index("[loading]"):]
crack = corroded[corroded.index("[[crack]]"):corroded.index("[loading]")]
# Four cracks stay elastic here (f_t = 60 MPa, never reached; k = 1000
# N/mm^3, so that they open by microns): past the onset of cracking, four
# softening planes have several equilibrium branches (the slice may localise
# into one or two of them, even with ductile softening), and which one a
# model takes depends on round-off; a cut model cannot take the unsymmetric
# ones. That is why model.symmetry = "auto" keeps the whole slice when cracks
# pair up. The mirror crack past the onset, where there is one branch, is
# one_crack's.
elastic_crack = crack.replace("f_t = 3.0", "f_t = 60.0").replace("k = 100000.0", "k = 1000.0")
assert elastic_crack.count("60.0") == 1 and elastic_crack.count("1000.0") == 1, crack
centred_cracks = lambda angles: without_crack.replace(  # noqa: E731
    "tube_center = [50.0, 25.0]", "tube_center = [50.0, 50.0]") + "".join(
    elastic_crack.replace('angle = "nearest_face"', f"angle = {a}") for a in angles)
short = ["mesh.elements_per_quarter=6", "mesh.elements_through_thickness=3", "corrosion.steps=8",
         "corrosion.penetration=0.03", "loading.steps=6", "loading.push_displacement=0.03"]
# Cracks that are mirror images of each other: "auto" keeps the whole slice
# (it may open one of them more), "symmetric" cuts.
for name, text, part, mirrored in (
        ("one_crack", corroded, "half", 1),
        ("four_cracks_on_planes", centred_cracks((0.0, 90.0, 180.0, 270.0)), "quarter", 2),
        ("four_cracks_between", centred_cracks((30.0, 150.0, 210.0, 330.0)), "quarter", 0)):
    cut, whole = out_dir(f"symmetry_{name}"), out_dir(f"symmetry_{name}_full")
    if part == "quarter":
        auto = out_dir(f"symmetry_{name}_auto")
        run(text, auto, sets=short[:2] + ["corrosion.steps=1", "loading.steps=1"])
        check(summary(auto)["symmetry"] == "full",
              f"{name}: model.symmetry = auto keeps the whole slice (cracks paired by the mirror)")
    run(text, cut, sets=short + ([] if part == "half" else ["model.symmetry=symmetric"]))
    run(text, whole, sets=short + ["model.symmetry=full"])
    sc, sw = summary(cut), summary(whole)
    check(sc["symmetry"] == part and sw["symmetry"] == "full", f"{name}: {sc['symmetry']} model")
    n = len(sw["cracks"])
    same(f"{name}: corrosion", cut, whole, corrosion,
         ["p_MPa", "crack_width_mm"] + [f"w_crack_{i}_mm" for i in range(n)])
    same(f"{name}: push", cut, whole, curve, ("P_N", "tau_MPa", "p_MPa", "slip_mm"))
    for i in range(n):
        for key in ("mouth_opening_mm", "max_opening_mm", "max_damage"):
            a, b = sc["cracks"][i][key], sw["cracks"][i][key]
            check(abs(a - b) <= bound(cut, whole) * max(abs(b), 1e-12),
                  f"{name}: crack {i} {key} {a:.6g} = full model's {b:.6g}")
    check(max(c["max_opening_mm"] for c in sw["cracks"]) > 1e-3,
          f"{name}: the cracks open ({max(c['max_opening_mm'] for c in sw['cracks']) * 1e3:.1f} um)")
    print(f"{name}: {sc['condensed_dofs']} condensed dofs against {sw['condensed_dofs']}, "
          f"wall {sc['wall_s']:.2f} s against {sw['wall_s']:.2f} s ({mirrored} mirror cracks)")

# No symmetry, or fields wanted: the full model.
for name, sets, why in (
        ("symmetry_off_centre", ["geometry.tube_center=[45.0, 40.0]"], "tube off centre"),
        ("symmetry_odd", ["mesh.elements_per_quarter=5"], "odd elements per quarter"),
        ("symmetry_fields", ["output.xdmf=true"], "fields asked for")):
    out = out_dir(name)
    run(COARSE_MESH + FRICTION_2, out, sets=sets + ["loading.steps=1"])
    check(summary(out)["symmetry"] == "full", f"{why}: full model")
# model.symmetry = "symmetric" keeps its cut with fields (they are the
# part's): the four mirror-paired cracks' quarter model, with output.xdmf,
# is the quarter model's curve. Before, fields took the whole slice; on this
# scene (whose cracks the loop above keeps symmetric) only the symmetry
# check would see it, on a scene where they localise (the exploratory
# run's, 50 um of corrosion) two of the four opened and tau fell by 27 %.
fields = out_dir("symmetry_four_cracks_on_planes_fields")
run(centred_cracks((0.0, 90.0, 180.0, 270.0)), fields,
    sets=short + ["model.symmetry=symmetric", "output.xdmf=true"])
check(summary(fields)["symmetry"] == "quarter" and os.path.getsize(os.path.join(fields, "fields.h5")) > 0,
      "symmetric with output.xdmf: a quarter model, its fields written")
same("symmetric with output.xdmf: push", fields, os.path.join(OUT_ROOT, "symmetry_four_cracks_on_planes"), curve,
     ("P_N", "tau_MPa", "p_MPa", "slip_mm"))

# The mirror crack's one jump per pair (its opening) in the explicit
# Jacobian: the half model of one_crack with LU of every Jacobian in double
# (the lagged GMRES would hide an error there) converges as fast as the
# default and to the same curve; the progress line and summary.json count
# the same unknowns.
lu = out_dir("symmetry_one_crack_jacobian")
p = run(os.path.join(OUT_ROOT, "symmetry_one_crack.toml"), lu,
        short + ["solver.preconditioner=jacobian", "solver.precision=double"], check=False,
        quiet=False)
check(p.returncode == 0, f"one_crack, LU of every Jacobian: exit {p.returncode} {p.stderr[-300:]}")
default = os.path.join(OUT_ROOT, "symmetry_one_crack")  # the loop's half model
same("one_crack: LU of every Jacobian", lu, default, curve, ("P_N", "tau_MPa", "p_MPa"))
sl, sd = summary(lu), summary(default)
check(sl["newton_iterations"] <= sd["newton_iterations"],
      f"one_crack: LU of every Jacobian converges in {sl['newton_iterations']} Newton iterations "
      f"(lagged GMRES: {sd['newton_iterations']})")
said = re.search(r"Newton on the (\d+) interface jumps", p.stdout)
check(said and int(said.group(1)) == sl["condensed_dofs"] == sd["condensed_dofs"],
      f"one_crack: {said.group(1) if said else '?'} jumps said, {sl['condensed_dofs']} condensed")
check("(half model by symmetry about" in p.stdout and "full model" not in p.stdout,
      "one_crack: the progress line says the half model")

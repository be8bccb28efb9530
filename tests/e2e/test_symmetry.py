"""Exact symmetry (model.symmetry = "auto"): a centred push-out runs on a
quarter of the mesh with symmetry conditions and gives the plain
full-Newton full model's curve to 1e-6 relative (friction + adhesion through the peak, with the
thermal step); scenes without the symmetry, or asking for fields, run on
the full model."""
from common import COARSE_MESH, EXP_SOFT, FRICTION_2, THROUGH_PEAK, check, curve, out_dir, run, summary

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
a, b = curve(quarter), curve(full)
check(len(a) == len(b) == 11, "both converged through 10 steps")
for key in ("P_N", "tau_MPa", "p_MPa", "slip_mm"):
    scale = max(abs(r[key]) for r in b)
    diff = max(abs(x[key] - y[key]) for x, y in zip(a, b))
    check(diff <= 1e-6 * scale, f"{key}: max |quarter - full| = {diff:.1e} <= 1e-6 x {scale:.4g}")

# No symmetry, or fields wanted: the full model.
for name, sets, why in (
        ("symmetry_off_centre", ["geometry.tube_center=[45.0, 50.0]"], "tube off centre"),
        ("symmetry_odd", ["mesh.elements_per_quarter=5"], "odd elements per quarter"),
        ("symmetry_fields", ["output.xdmf=true"], "fields asked for")):
    out = out_dir(name)
    run(COARSE_MESH + FRICTION_2, out, sets=sets + ["loading.steps=1"])
    check(summary(out)["symmetry"] == "full", f"{why}: full model")

"""The corrosion stage without crack planes, on the circular slice of
test_friction_plateau_matches_lame (outer diameter b = 100 mm, tube radii a = 8, R = 10 mm), with the
law oxide_friction and no temperature change:

1. corrosion.csv: a row for step 0 and each corrosion step, x linear in the
   steps, p growing with x; summary.json counts the corrosion steps.
2. p after corrosion against the plane-stress ring formula with the joint's
   1/k and the oxide layer's beta x / B_ox in series (scripts/analytic.py):
   3 %, as test_friction_plateau_matches_lame (the 20 mm disc sits +1.9 % above the plane-stress
   formula, a 3D effect, not discretisation).
3. The same radial interference as a thermal shrink fit ((beta - 1) x =
   -alpha dT R) gives the same pressure, up to the oxide layer's compliance
   and the polygon: the thermal field moves a facet of the 4 n-gon
   interface (n elements per quarter) by its apothem R cos(pi / 4n), the
   oxide by R. Both run without friction: the concrete's thermal strain is
   isotropic, and its axial part, held by friction against the tube, adds
   shear; and under the oxide's pressure the Poisson strains of tube and
   ring differ axially, so friction adds some (+0.3 % of p on this mesh).
   The ratio of the two pressures against the formula's ratio: 1e-4.
4. The push after corrosion starts from the corroded state; its friction
   plateau is tau = mu p (0.2 %, p of the plateau), and p there is the
   corroded state's p(x) raised by the push itself (the tube, pressed
   axially, swells by Poisson: +1.5 % on this slice, as in test_friction_plateau_matches_lame):
   within 2 %.
5. Without a [corrosion] section nothing changes: no corrosion.csv.
6. Stages of one step that are cut say so by their name ("corrosion step:
   ... retrying with 0.5 of a step"; Newton limited to 4 iterations on the
   corroded demo, coarse, its crack made ductile: c = 3 1/mm, G_F = 1 N/mm,
   so that no snap, where round-off picks how many cuts pass it, lies on
   the way; the whole step takes 5 iterations), and the run goes on to its
   end.
7. A crack plane whose mouth stays closed (the demo's plane turned to 45
   degrees, towards a corner: the cover there is thick; to x = 10 um) reads a width of 0
   in every row and in summary.json, not its penalty's overlap in
   compression (-0.03 um measured before: a width a gauge cannot read)."""
import math
import os

from common import LAME, SOURCE, check, corroded_ring, corrosion, curve, out_dir, run, summary
import analytic

a, R, b = 8.0, 10.0, 50.0
Ec, nuc, Es, nus, k, alpha, dT, mu = 30000.0, 0.2, 200000.0, 0.3, 1000.0, 1e-5, -25.0, 0.4
beta, B_ox = 2.0, 2000.0
x = -alpha * dT * R / (beta - 1)  # the shrink fit's interference, as corrosion [mm]
MESH = "[mesh]\nelements_per_quarter = 8\nelements_through_thickness = 4\n"
steps = 5
scene = corroded_ring(MESH, x, steps, mu=mu, beta=beta, oxide_bulk=B_ox)

out = out_dir("corrosion_ring")
run(scene, out)
rows = corrosion(out)
s = summary(out)
check(len(rows) == steps + 1, f"corrosion.csv has step 0 and {steps} steps ({len(rows)} rows)")
check(s["corrosion_steps"] == steps and abs(s["penetration_mm"] - x) < 1e-15,
      f"summary: {s['corrosion_steps']} corrosion steps, x = {s['penetration_mm']} mm")
check(all(abs(r["penetration_mm"] - x * i / steps) < 1e-15 for i, r in enumerate(rows)),
      "x grows linearly to the final penetration")
check(rows[0]["p_MPa"] == 0 and all(r1["p_MPa"] > r0["p_MPa"] for r0, r1 in zip(rows, rows[1:])),
      "p is 0 before corrosion and grows with x")
check(all(r["crack_width_mm"] == 0 for r in rows), "no crack planes, no crack width")

g0 = (beta - 1) * x
c_ox = beta * x / B_ox
p_formula = analytic.ring_pressure(g0, R, a, b, Ec, nuc, Es, nus, 1 / k + c_ox)
p = rows[-1]["p_MPa"]
err = p / p_formula - 1
check(abs(err) < 0.03, f"p after corrosion {p:.4f} MPa vs ring formula {p_formula:.4f} MPa "
                       f"({100 * err:+.2f} %)")

# The same interference as a shrink fit (law friction, no oxide layer),
# both without friction.
out_t = out_dir("corrosion_ring_thermal")
run(LAME + MESH, out_t, sets=["interface.0.mu=0"])
p_thermal = curve(out_t)[0]["p_MPa"]
out_0 = out_dir("corrosion_ring_mu0")
run(scene, out_0, sets=["interface.0.mu=0"])
p_0 = corrosion(out_0)[-1]["p_MPa"]
polygon = 1 / math.cos(math.pi / (4 * 8))  # oxide's / thermal's normal interference
ratio = p_0 / p_thermal
ratio_formula = polygon * p_formula / analytic.ring_pressure(g0, R, a, b, Ec, nuc, Es, nus, 1 / k)
check(abs(ratio / ratio_formula - 1) < 1e-4,
      f"corrosion / shrink fit pressure {ratio:.6f} vs formula {ratio_formula:.6f} "
      f"({100 * (ratio / ratio_formula - 1):+.4f} %)")

# The push from the corroded state.
push = curve(out)
check(abs(push[0]["p_MPa"] / p - 1) < 1e-12, "the push starts from the corroded state")
tau, p_plateau = push[-1]["tau_MPa"], push[-1]["p_MPa"]
err = tau / (mu * p_plateau) - 1
check(abs(err) < 2e-3, f"plateau tau {tau:.4f} MPa vs mu p {mu * p_plateau:.4f} MPa ({100 * err:+.3f} %)")
err = p_plateau / p - 1
check(abs(err) < 0.02, f"plateau p {p_plateau:.4f} MPa vs corroded p(x) {p:.4f} MPa ({100 * err:+.2f} %)")
check(not os.path.exists(os.path.join(out_t, "corrosion.csv")), "no corrosion stage, no corrosion.csv")

# 6. A stage of one step, cut.
one = out_dir("corrosion_one_step_cut")
p = run(os.path.join(SOURCE, "demo", "pushout_corroded.toml"), one,
        ["mesh.elements_per_quarter=6", "mesh.elements_through_thickness=3", "crack.0.c=3",
         "corrosion.steps=1", "loading.steps=1", "output.plot=false"],
        ["-snes_max_it", "4"], check=False, quiet=False)
retries = [line for line in p.stdout.splitlines() if "retrying" in line]
check(p.returncode == 0 and retries and retries[0].startswith("corrosion step: DIVERGED_MAX_IT"),
      f"one corrosion step, cut: exit {p.returncode}, {retries[:1] or p.stderr[-300:]}")

# 7. A closed mouth reads 0.
closed = out_dir("corrosion_closed_mouth")
run(os.path.join(SOURCE, "demo", "pushout_corroded.toml"), closed,
    sets=["mesh.elements_per_quarter=4", "mesh.elements_through_thickness=2", "loading.steps=2",
          "crack.0.angle=45", "corrosion.penetration=0.01", "corrosion.steps=5"])
rows = corrosion(closed)
widths = [r[k] for r in rows for k in ("crack_width_mm", "w_crack_0_mm")]
planes = [c for c in summary(closed)["cracks"] if c["source"] == "plane"]
# (0, not a penalty's overlap of 1e-5 mm read either way: 1e-12 mm is far below it)
check(max(map(abs, widths)) <= 1e-12 and
      all(abs(c["width_mm"]) <= 1e-12 and abs(c["mouth_opening_mm"]) <= 1e-12 for c in planes),
      f"a closed mouth: widths from {min(widths) * 1e3:.4f} to {max(widths) * 1e3:.4f} um in "
      f"corrosion.csv, {[c['width_mm'] for c in planes]} mm in summary.json (0)")

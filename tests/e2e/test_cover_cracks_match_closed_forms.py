"""Crack planes in the concrete ([[crack]], mesh/cracks.h) under the oxide's
expansion, on the circular slice of test_corrosion_matches_thick_cylinder (outer diameter 2b = 100
mm, tube radii a = 8, R = 10 mm), oxide_friction k 1000, crack law
exponential_softening with a stiff penalty (k 1e6 N/mm^3: the elastic
planes add no compliance to the uncracked ring), f_t 3 MPa, c 20 1/mm.

1. Onset: the ring cracks at its inner surface when p reaches
   p_cr = f_t (b^2 - R^2) / (b^2 + R^2)  (plane stress, scripts/analytic.py).
   With one crack and with four, at x giving 0.95 p_cr (by the ring formula)
   no crack point is damaged and the largest opening is within the elastic
   f_t / k; at 1.05 p_cr the root is damaged.
2. Rigid segments: four cracks, no friction, x = 60 um, on a quarter of
   the slice: the cracks run through, the four mouths open alike, and the mean pressure follows the
   rigid-segment limit p = ((b - R) / R) sigma(w), w the mouth opening,
   within 25 %: the segments translate along their bisectors, so the oxide
   presses harder near the cracks than between them, and the mean pressure
   exceeds the resultant's (the resultant balances the cracks to round-off;
   measured +17 %).
   The condensed bulk (the default on one process) and the whole model
   give the same state (to Newton's bound on the two runs).
3. Directions and outputs: "nearest_face" of an off-centre tube in a square is the
   cover side (-y here); an angle within half an element of a block corner
   is moved onto it (summary.json says so); the model is the full one;
   cracks.xdmf and corrosion.png are written.
4. Widths at the face: read at the plane's quadrature points next to it,
   never below what the penalty allows while the crack reaches the face."""
import math
import re
import os

from common import (SOURCE, check, corroded_ring, corrosion, curve, newton_bound, out_dir, run,
                    solved_unknowns, summary)
import analytic

a, R, b = 8.0, 10.0, 50.0
Ec, nuc, Es, nus, k, beta, B_ox = 30000.0, 0.2, 200000.0, 0.3, 1000.0, 2.0, 2000.0
f_t, k_crack, c = 3.0, 1e6, 20.0
MESH = "[mesh]\nelements_per_quarter = 16\nelements_through_thickness = 1\n"


def crack(angle):
    return (f"[[crack]]\nangle = {angle}\nlaw = \"exponential_softening\"\nk = {k_crack}\n"
            f"f_t = {f_t}\nc = {c}\n")


def scene(x, steps, angles, mu=0.4):
    return (corroded_ring(MESH, x, steps, mu=mu, push=0.001, push_steps=1, beta=beta, oxide_bulk=B_ox)
            + "".join(crack(t) for t in angles))


# 1. Onset.
p_cr = analytic.cracking_onset_pressure(f_t, R, b)
C = sum(analytic.ring_compliances(R, a, b, Ec, nuc, Es, nus)) + 1 / k
for angles in ([90.0], [0.0, 90.0, 180.0, 270.0]):
    for factor in (0.95, 1.05):
        p = factor * p_cr
        x = p * C / ((beta - 1) - p * beta / B_ox)  # p = (beta-1)x / (C + beta x / B_ox)
        out = out_dir(f"cracks_onset_{len(angles)}_{factor}")
        run(scene(x, 2, angles), out)
        cracks = summary(out)["cracks"]
        p_run = corrosion(out)[-1]["p_MPa"]
        damaged = max(cr["max_damage"] for cr in cracks)
        opening = max(cr["max_opening_mm"] for cr in cracks)
        what = f"{len(angles)} crack(s) at p = {p_run:.3f} MPa = {p_run / p_cr:.3f} p_cr"
        if factor < 1:
            check(damaged == 0 and opening <= f_t / k_crack,
                  f"{what}: no damage, largest opening {opening:.3e} mm <= f_t/k {f_t / k_crack:.1e}")
            # Elastic until then: the opening grows as p, so it reaches f_t/k at
            p_onset = p_run * (f_t / k_crack) / opening
            check(abs(p_onset / p_cr - 1) < 0.05,
                  f"{len(angles)} crack(s): onset at p = {p_onset:.3f} MPa vs p_cr {p_cr:.3f} MPa "
                  f"({100 * (p_onset / p_cr - 1):+.1f} %)")
        else:
            check(damaged > 0, f"{what}: the root is damaged (largest damage {damaged:.3f})")

# The bulk condensed onto the jumps of the interface and the planes (the
# default on one process) against the whole model: the last onset run.
whole = out_dir("cracks_onset_whole")
run(scene(x, 2, angles), whole, sets=["solver.condensation=off"])
check(summary(out)["condensed_dofs"] > 0 and summary(whole)["condensed_dofs"] == 0,
      "condensed by default, whole model when asked")
condensed, whole_model = corrosion(out)[-1], corrosion(whole)[-1]
# Each run converged every step to Newton's tolerance, summing in its order:
# that bounds the pressure (a force). Not the openings: their error is the
# residual over the softening cracks' tangent, which Newton's test on the
# forces does not bound (1.3e-7 on a fresh machine where the pressure's
# bound was 8.7e-8): 1e-6 of the opening, a thousandth of the micrometre
# the study reads them to.
agree = newton_bound(len(corrosion(whole)) + len(curve(whole)),
                     max(solved_unknowns(summary(o)) for o in (out, whole)))
for column, tol in (("p_MPa", agree), ("crack_width_mm", 1e-6), ("w_crack_0_mm", 1e-6),
                    ("w_crack_3_mm", 1e-6)):
    diff = abs(condensed[column] - whole_model[column]) / abs(whole_model[column])
    check(diff <= tol, f"condensed and whole model: {column} agrees to {diff:.1e} (<= {tol:.1e})")

# 2. Rigid segments.
out = out_dir("cracks_rigid_segments")
# Once the four cracks soften, the symmetric path (all four open alike) is
# one branch among others: cracks may localise, one closing while the others
# open, and which one the whole slice follows is up to round-off (the
# condensed whole slice leaves it: docs/corrosion.md). On the quarter
# (model.symmetry "symmetric") each crack's mirror image opens as it does,
# so the 180 and 270 degree cracks cannot localise against the 0 and 90;
# those two lie on the cut's two planes, which the quarter's diagonal maps
# onto each other, and open alike: to 1e-6 (openings are displacements, whose
# error Newton's test on the forces does not bound, as above), or
# Newton's bound where larger.
run(scene(0.06, 30, [0.0, 90.0, 180.0, 270.0], mu=0.0), out,
    sets=["solver.condensation=off", 'model.symmetry="symmetric"'])
rows = corrosion(out)
last = rows[-1]
widths = [last[f"w_crack_{i}_mm"] for i in range(4)]
w = sum(widths) / 4
alike = max(newton_bound(len(rows), solved_unknowns(summary(out))), 1e-6)
check(max(widths) - min(widths) <= alike * w, f"the four mouths open alike (to {alike:.1e}): {widths}")
check(abs(last["crack_width_mm"] - max(widths)) < 1e-15, "crack_width_mm is the largest mouth")
check(w > 10 * f_t / k_crack and all(cr["max_damage"] > 0.99 for cr in summary(out)["cracks"]),
      f"the cracks run through: mouth opening {1e3 * w:.1f} um")
w0 = f_t / k_crack
p_limit = analytic.rigid_segments_pressure(lambda w: f_t * math.exp(-c * (w - w0)), w, R, b)
err = last["p_MPa"] / p_limit - 1
check(0 < err < 0.25, f"p {last['p_MPa']:.3f} MPa vs rigid segments ((b-R)/R) sigma(w) "
                      f"{p_limit:.3f} MPa ({100 * err:+.1f} %)")
check(all(r1["p_MPa"] < r0["p_MPa"] for r0, r1 in zip(rows[-5:], rows[-4:])),
      "after the peak the pressure falls as the cracks open")

# 3. Directions.
out = out_dir("cracks_directions")
square = MESH.replace("16", "8") + """
[geometry]
outer_shape = "square"
width = 100.0
tube_center = [50.0, 25.0]
[[interface]]
law = "oxide_friction"
[loading]
push_displacement = 0.002
steps = 1
[corrosion]
penetration = 0.002
steps = 1
[[crack]]
angle = "nearest_face"
[[crack]]
angle = 58.0
"""
run(square, out, sets=["output.xdmf=true"])
s = summary(out)
xdmf = open(os.path.join(out, "cracks.xdmf")).read()
check(all(f'Name="{f}"' in xdmf for f in ("t_n", "w_n", "damage", "crack")),
      "cracks.xdmf has the crack planes' tractions, openings, damage and index")
itf_xdmf = open(os.path.join(out, "interface.xdmf")).read()
cells = [int(n) for n in re.findall(r'<Topology[^>]*NumberOfElements="(\d+)"', itf_xdmf)]
check(all(f'Name="{f}"' in itf_xdmf for f in ("t_n", "w_n", "slip_s1_0", "crack", "crack_damage"))
      and cells and cells[0] == s["interface_pairs"],
      f"interface.xdmf has every joint element, the interface's and the planes' "
      f"({cells[:1]} cells, {s['interface_pairs']} joint elements), with their index and damage")
check(os.path.exists(os.path.join(out, "corrosion.png")), "corrosion.png drawn")
corner = math.degrees(math.atan2(100 - 25, 100 - 50))  # the block corner towards (100, 100)
check(abs(s["cracks"][0]["angle_deg"] - 270) < 1e-9 and not s["cracks"][0]["snapped"],
      f"nearest_face of a tube 15 mm from y = 0: {s['cracks'][0]['angle_deg']} deg")
check(s["cracks"][1]["snapped"] and abs(s["cracks"][1]["angle_deg"] - corner) < 1e-9,
      f"58 deg is moved onto the block corner at {corner:.2f} deg")
check(s["symmetry"] == "full", "crack planes: the full model")

# 4. Crack widths are read where the law evaluates the opening (the plane's
# quadrature points next to the outer face), so they cannot go negative
# while the plane opens: the centred tube of the corroded series (12/4 mesh,
# beta 2, as scripts/studies.py runs it: the damage viscosity's pseudo time
# is the push's) to x = 32.5 um, where the crack reaches the face. A nodal value
# extrapolated over the last element read -0.61 um there. Bound: a face
# still uncracked may be pressed by the ligament's bending (about f_t on the
# compressed side), which the penalty answers with at most -2 f_t / k.
out = out_dir("cracks_width_at_the_face")
run(os.path.join(SOURCE, "demo", "pushout_corroded.toml"), out,
    sets=["mesh.elements_per_quarter=12", "mesh.elements_through_thickness=4",
          "geometry.tube_center=[50.0, 50.0]", "corrosion.penetration=0.0325", "corrosion.steps=13",
          "crack.0.eta=0.001", "loading.steps=20", "output.plot=false"])
rows = corrosion(out)
k_demo, f_t_demo = 1e5, 3.0  # the demo's crack plane [N/mm^3], [MPa]
least = min(r["crack_width_mm"] for r in rows)
check(least >= -2 * f_t_demo / k_demo and rows[-1]["crack_width_mm"] > 10 * f_t_demo / k_demo,
      f"crack widths from {1e3 * least:.4f} um (>= {-2e3 * f_t_demo / k_demo:.2f} um) to "
      f"{1e3 * rows[-1]['crack_width_mm']:.1f} um as the crack reaches the face")

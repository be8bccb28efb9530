"""The triquadratic bulk (mesh.degree = 2: 27-node displacement on the
trilinear hexahedra, 9-node joint elements):
 - its quarter model with the condensed bulk gives the plain full-Newton
   full model's curve to Newton's bound (friction + adhesion through the peak, thermal
   step): the P2 constraints (edge, face and interior dofs on the top,
   support and symmetry planes) and the 9-node pairs are consistent;
 - on the Lame shrink fit it converges to the trilinear bulk's plateau: the
   P2 error against the trilinear 16/8 plateau falls by >= 3x from the 4/2
   to the 8/4 mesh (h^2) and is below 0.5 % at 8/4, so both degrees agree
   on the limit and the trilinear bulk does not lock here.
 - with output.xdmf, the displacement is written at the mesh nodes.
(The assembled 9-node tangent is checked against finite differences in the
unit tests; the P2 points of the run-time/error study are in bench/pareto.py.)"""
import os
import re

from common import (COARSE_MESH, EXP_SOFT, FRICTION_2, LAME, THROUGH_PEAK, check, curve, newton_bound, out_dir, run,
                    solved_unknowns, summary)

adhesion = COARSE_MESH + "degree = 2\n" + FRICTION_2 + EXP_SOFT + THROUGH_PEAK
quarter, full = out_dir("p2_quarter"), out_dir("p2_full_plain")
run(adhesion, quarter)
run(adhesion, full, sets=["model.symmetry=full", "solver.condensation=off",
                          "solver.preconditioner=jacobian"])
sq, sf = summary(quarter), summary(full)
check(sq["symmetry"] == "quarter" and sq["condensed_dofs"] > 0 and sf["symmetry"] == "full",
      f"P2: quarter model condensed onto {sq['condensed_dofs']} jumps; reference {sf['dofs']} dofs")
a, b = curve(quarter), curve(full)
check(len(a) == len(b) == 11, "P2: both converged through 10 steps")
bound = newton_bound(len(b), max(solved_unknowns(sq), solved_unknowns(sf)))
# Newton's test bounds the forces; the slip's error is the residual over the
# softening joints' tangent, which it does not bound: 1e-6 there.
for key, tol in (("P_N", bound), ("p_MPa", bound), ("slip_mm", max(bound, 1e-6))):
    scale = max(abs(r[key]) for r in b)
    diff = max(abs(x[key] - y[key]) for x, y in zip(a, b))
    check(diff <= tol * scale,
          f"P2 {key}: max |quarter condensed - full plain| = {diff:.1e} <= {tol:.1e} x {scale:.4g}")

plateau = {}
for degree, nq, nz in ((1, 16, 8), (2, 4, 2), (2, 8, 4)):
    out = out_dir(f"p2_lame_{degree}_{nq}")
    run(LAME, out, sets=[f"mesh.degree={degree}", f"mesh.elements_per_quarter={nq}",
                         f"mesh.elements_through_thickness={nz}"])
    plateau[(degree, nq)] = curve(out)[-1]["tau_MPa"]
ref = plateau[(1, 16)]
e4, e8 = (abs(plateau[(2, n)] / ref - 1) for n in (4, 8))
check(e4 / e8 >= 3, f"Lame plateau, P2 against P1 16/8 ({ref:.5f} MPa): 4/2 {100 * e4:.2f} %, "
                    f"8/4 {100 * e8:.2f} %, ratio {e4 / e8:.1f} >= 3")
check(e8 < 5e-3, f"P2 8/4 within 0.5 % of the trilinear 16/8 plateau ({100 * e8:.2f} %)")

out = out_dir("p2_fields")
run(COARSE_MESH + "degree = 2\n" + FRICTION_2, out, sets=["loading.steps=2", "output.xdmf=true"])
text = open(os.path.join(out, "fields.xdmf")).read()
nodes = re.search(r'Dimensions="(\d+) 3" Format="HDF">fields.h5:/Mesh/mesh/geometry', text).group(1)
displacement = re.search(r'Attribute Name="displacement"[^>]*>\s*<DataItem Dimensions="(\d+) 3"', text)
check(displacement is not None and displacement.group(1) == nodes,
      f"P2 fields: displacement at the {nodes} mesh nodes")

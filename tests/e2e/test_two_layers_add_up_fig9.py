"""Paper Fig. 9 through the whole pipeline: Friction 1 + Lin. soft. superposed
on one joint (-0.2 N per node), against the analytic sum, and against the sum
of the two single-layer runs (each at -0.1 N per node: the cohesive layer is
insensitive to compression, and each single layer then sees p = 0.4 MPa)."""
import os

from common import SOURCE, check, curve, out_dir, run

import analytic  # scripts/analytic.py, on the path through common

sup = out_dir("fig9_superposed")
run(os.path.join(SOURCE, "demo", "single_joint_fig9.toml"), sup)
rows = curve(sup)
us = [r["u_s_mm"] for r in rows]
exact = [a + b for a, b in zip(analytic.coulomb(us, 100, 0.4, 0.4),
                               analytic.linear_softening(us, 100, 1.0, 0.3))]
worst = max(abs(r["F_s_N"] - e) for r, e in zip(rows, exact))
peak = max(abs(e) for e in exact)
check(worst <= 1e-8 * peak, f"Fig. 9: max |F_s - analytic| = {worst:.3e} N <= 1e-8 x {peak:.3f} N")

single = "[model]\ntype = \"single_joint\"\n[[interface]]\n{}\n[loading]\nnormal_force_per_node = -0.1\n"
fr, coh = out_dir("fig9_friction"), out_dir("fig9_cohesive")
run(single.format('law = "friction"\nk = 100.0\nmu = 0.4'), fr)
run(single.format('law = "linear_softening"\nk = 100.0\nf_t = 1.0\nw_c2 = 0.3'), coh)
sum_rows = [a["F_s_N"] + b["F_s_N"] for a, b in zip(curve(fr), curve(coh))]
diff = max(abs(r["F_s_N"] - s) for r, s in zip(rows, sum_rows))
check(diff <= 1e-8 * peak, f"superposed run = sum of the single-layer runs ({diff:.2e} N)")

# The same path with nodal interface quadrature.
nod = out_dir("fig9_nodal")
run(os.path.join(SOURCE, "demo", "single_joint_fig9.toml"), nod, sets=["mesh.interface_quadrature=nodal"])
worst = max(abs(r["F_s_N"] - e) for r, e in zip(curve(nod), exact))
check(worst <= 1e-8 * peak, f"Fig. 9 with nodal quadrature: {worst:.2e} N")

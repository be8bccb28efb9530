"""The coupled cohesive_friction law through the pipeline, on the Fig. 9 path
extended to full damage. It is cohesion alone plus D times friction alone
(0 <= D <= 1), so at every step it lies between cohesion alone and the
superposition of the two (the coupled curve minus cohesion has the sign of
friction alone and no larger size); it is elastic before the peak and pure
friction (mu p A = 0.16 N) at full damage."""
import os

from common import SOURCE, check, curve, out_dir, run

import analytic  # scripts/analytic.py, on the path through common

out = out_dir("single_joint_cohesive_friction")
run(os.path.join(SOURCE, "demo", "single_joint_cohesive_friction.toml"), out)
rows = curve(out)
us = [r["u_s_mm"] for r in rows]
fr = analytic.coulomb(us, 100, 0.4, 0.4)
coh = analytic.linear_softening(us, 100, 1.0, 0.3)
between = all((r["F_s_N"] - c) * f >= -1e-12 and abs(r["F_s_N"] - c) <= abs(f) + 1e-10
              for r, c, f in zip(rows, coh, fr))
check(between, "coupled lies between cohesion alone and the superposition at every step")
pre = [r for r in rows if 0 < r["u_s_mm"] <= 0.01 and r["step"] <= 20]
check(all(abs(r["F_s_N"] - 100 * r["u_s_mm"]) < 1e-10 for r in pre), "elastic (k A u) up to the peak")
check(abs(rows[-1]["F_s_N"] - 0.16) < 1e-9, f"fully damaged: friction only, F_s = {rows[-1]['F_s_N']:.6f} N")

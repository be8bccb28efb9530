"""Paper Fig. 6 through the whole pipeline: one friction joint (k 100 N/mm^3,
mu 0.4), -0.1 N per upper node, shear path 0 -> 0.02 -> 0.01 -> 0.025 mm.

Analytic: p = 4 x 0.1 N / 1 mm^2 = 0.4 MPa, slip limit mu p A = 0.16 N; the
shear force follows the 1D Coulomb law F = k A (u - u_p), |F| <= 0.16 N, whose
exact value at each path point depends only on the turning points."""
import os

from common import SOURCE, check, curve, out_dir, run

out = out_dir("fig6")
run(os.path.join(SOURCE, "demo", "single_joint_fig6.toml"), out)
rows = curve(out)

k, mu, area, p = 100.0, 0.4, 1.0, 0.4
limit = mu * p * area
u_p, worst = 0.0, 0.0
for r in rows:
    trial = k * area * (r["u_s_mm"] - u_p)
    if abs(trial) > limit:
        u_p += (abs(trial) - limit) / (k * area) * (1 if trial > 0 else -1)
        trial = limit if trial > 0 else -limit
    worst = max(worst, abs(r["F_s_N"] - trial))
check(len(rows) == 61, f"61 rows (step 0 + 3 x 20 steps), got {len(rows)}")
check(worst <= 1e-8 * limit, f"max |F_s - analytic| = {worst:.3e} N <= 1e-8 x {limit} N")
un = [r["u_n_mm"] for r in rows]
check(max(abs(u + p / k) for u in un) < 1e-12, "normal jump -p/k = -0.004 mm at every step")
check(all(abs(r["F_n_N"] + 0.4) < 1e-12 for r in rows), "F_n = -0.4 N")
check(os.path.getsize(os.path.join(out, "curve.png")) > 1000, "curve.png written")

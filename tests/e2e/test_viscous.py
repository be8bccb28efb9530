"""Viscous regularisation of the damage (interface.N.eta, pseudo-time in mm
of push): on a friction + exponential-softening push-out, the curve moves
towards the rate-independent one as eta -> 0 (max |tau_eta - tau_0|
decreases with eta, about tenfold per decade as a first-order regularisation
should, and is below 3 % of the peak for eta = 1e-4 mm), and a viscous law
delays the softening (tau just after the peak is higher)."""
from common import COARSE_MESH, EXP_SOFT, FRICTION_2, check, curve, out_dir, run

scene = COARSE_MESH + FRICTION_2 + EXP_SOFT + """
[loading]
temperature_change = -25.0
push_displacement = 0.1
steps = 40
"""
curves = {}
for eta in (0.0, 1e-2, 1e-3, 1e-4):
    out = out_dir(f"viscous_{eta:g}")
    run(scene, out, sets=[f"interface.1.eta={eta}", "output.plot=false"])
    curves[eta] = curve(out)
ref = curves[0.0]
peak = max(r["tau_MPa"] for r in ref)
errors = {eta: max(abs(a["tau_MPa"] - b["tau_MPa"]) for a, b in zip(curves[eta], ref)) for eta in (1e-2, 1e-3, 1e-4)}
check(errors[1e-2] > errors[1e-3] > errors[1e-4], "error decreases with eta: " + ", ".join(
    f"eta {eta:g} mm: {e:.4f} MPa" for eta, e in errors.items()))
check(errors[1e-3] / errors[1e-4] > 5, f"first order in eta: ratio {errors[1e-3] / errors[1e-4]:.1f} per decade")
check(errors[1e-4] < 0.03 * peak, f"eta 1e-4 mm within 3 % of the peak {peak:.3f} MPa ({errors[1e-4]:.4f} MPa)")
i_peak = max(range(len(ref)), key=lambda i: ref[i]["tau_MPa"])
after = i_peak + 2
check(curves[1e-2][after]["tau_MPa"] > ref[after]["tau_MPa"],
      f"viscosity delays the softening: {curves[1e-2][after]['tau_MPa']:.3f} > {ref[after]['tau_MPa']:.3f} MPa")

"""Viscous regularisation of the damage (interface.N.eta, pseudo-time in mm
of push): on a friction + exponential-softening push-out, the curve moves
towards the rate-independent one as eta -> 0 (max |tau_eta - tau_0|
decreases with eta, about tenfold per decade as a first-order regularisation
should, and is below 3 % of the peak for eta = 1e-4 mm), and a viscous law
delays the softening (tau just after the peak is higher)."""
import math

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

# The thermal step takes the pseudo-time of one nominal step: with the tube
# top held, the concrete's shrinkage damages the adhesion layer already in
# step 0 (|alpha dT| L = 10 um > f_t / k = 3 um), and a viscous layer does
# so too, the more the smaller eta (the tau of step 0 moves towards the
# rate-independent one). With no pseudo-time (dt = 0) a viscous layer
# would keep D_v = 0 in step 0 whatever eta.
thermal = COARSE_MESH + FRICTION_2 + EXP_SOFT + """
[loading]
temperature_change = -50.0
thermal_tube_top = "held"
push_displacement = 0.01
steps = 10
"""
tau0 = {}
for eta in (0.0, 1e-2, 1e-3, 1e-5):
    out = out_dir(f"viscous_thermal_{eta:g}")
    run(thermal, out, sets=[f"interface.1.eta={eta}", "output.plot=false"])
    tau0[eta] = curve(out)[0]["tau_MPa"]
out = out_dir("viscous_thermal_elastic")
run(thermal.replace(EXP_SOFT, '[[interface]]\nlaw = "elastic"\nk = 1000.0\n'), out,
    sets=["output.plot=false"])
undamaged = curve(out)[0]["tau_MPa"]
check(abs(tau0[0.0] - undamaged) > 0.05 * abs(undamaged),
      f"step 0 damages the adhesion layer: tau0 {tau0[0.0]:.4f} MPa vs undamaged {undamaged:.4f} MPa")
gaps = [abs(tau0[eta] - tau0[0.0]) for eta in (1e-2, 1e-3, 1e-5)]
check(gaps[0] > gaps[1] > gaps[2], "a viscous layer damages in step 0, the more the smaller eta: "
      + ", ".join(f"eta {eta:g}: {tau0[eta]:.4f}" for eta in (1e-2, 1e-3, 1e-5)))
check(gaps[2] < 0.02 * abs(tau0[0.0] - undamaged),
      f"eta 1e-5 mm: step 0 within 2 % of the rate-independent one ({tau0[1e-5]:.4f} vs {tau0[0.0]:.4f} MPa)")

# A pull (push_displacement < 0): the pseudo-time is the path's length, |delta|,
# so a viscous damage lags the rate-independent one as under a push (it ran
# backwards: D = -2.4e5 and tau -104 MPa at eta 1e-2, and 0.72 against 0.61
# at eta 1e-3); and tau divides by the contact length L - |delta| left.
pulled = {}
for eta in (0.0, 1e-3):
    out = out_dir(f"viscous_pull_{eta:g}")
    run(scene, out, sets=[f"interface.1.eta={eta}", "loading.push_displacement=-0.1",
                          "output.plot=false"])
    pulled[eta] = curve(out)
damage = [(a["d_1_mean"], b["d_1_mean"]) for a, b in zip(pulled[1e-3], pulled[0.0])]
check(all(0 <= d <= d0 + 1e-12 <= 1 + 1e-12 for d, d0 in damage),
      f"a pull: the viscous damage in [0, 1] and behind the rate-independent one: "
      f"{damage[-1][0]:.4f} against {damage[-1][1]:.4f} at the end")
L, D = 20.0, 20.0  # mm: the default slice's thickness and tube
# (the columns' 12 significant digits: 1e-9 is far above their round-off
# and far below the 2 * 0.1 / 20 = 1 % that L + |delta| made)
check(all(abs(r["tau_MPa"] * math.pi * D * (L - abs(r["delta_mm"])) - r["P_N"]) <= 1e-9 * abs(r["P_N"])
          for r in pulled[0.0]),
      f"a pull: tau = P / (pi D (L - |delta|)): {pulled[0.0][-1]['tau_MPa']:.6f} MPa at "
      f"delta {pulled[0.0][-1]['delta_mm']} mm, P {pulled[0.0][-1]['P_N']:.3f} N")

"""Closed-form single-joint answers along a shear path under compression."""


def coulomb(us, k, mu, p, area=1.0):
    """Shear force of paper §3's friction law: F = k A (u - u_p), |F| <= mu p A."""
    limit, u_p, out = mu * p * area, 0.0, []
    for u in us:
        f = k * area * (u - u_p)
        if abs(f) > limit:
            u_p += (abs(f) - limit) / (k * area) * (1 if f > 0 else -1)
            f = limit if f > 0 else -limit
        out.append(f)
    return out


def linear_softening(us, k, f_t, w_c2, area=1.0):
    """Shear force of Camanho-Davila damage with linear softening (shear only,
    compression elastic): secant to the origin below the largest slip reached."""
    w0, kappa, out = f_t / k, 0.0, []
    for u in us:
        kappa = max(kappa, abs(u))
        if kappa <= w0:
            g = k
        else:
            g = max(f_t * (1 - (kappa - w0) / w_c2), 0.0) / kappa
        out.append(g * u * area)
    return out


# Thick rings (plane stress): the steel tube a < r < R in the concrete ring
# R < r < b (Lamé's closed forms, used as in docs/corrosion.md).

def ring_compliances(R, a, b, Ec, nuc, Es, nus):
    """Radial compliances [mm^3/N] at r = R: the concrete ring's outward
    displacement per unit inner pressure, C_c = (R/Ec)((b^2+R^2)/(b^2-R^2)+nu_c),
    and the tube's inward one per unit outer pressure,
    C_s = (R/Es)((R^2+a^2)/(R^2-a^2)-nu_s)."""
    Cc = R / Ec * ((b * b + R * R) / (b * b - R * R) + nuc)
    Cs = R / Es * ((R * R + a * a) / (R * R - a * a) - nus)
    return Cc, Cs


def ring_pressure(interference, R, a, b, Ec, nuc, Es, nus, joint_compliance=0.0):
    """Contact pressure [MPa] of a radial interference [mm] (a shrink fit
    -alpha dT R, or the oxide's free opening g0 = (beta - 1) x) between tube
    and ring, with further compliances in series (the joint's 1/k, the oxide
    layer's beta x / B_ox) [mm^3/N]."""
    Cc, Cs = ring_compliances(R, a, b, Ec, nuc, Es, nus)
    return interference / (Cc + Cs + joint_compliance)


def cracking_onset_pressure(f_t, R, b):
    """Inner pressure [MPa] at which the hoop stress at r = R of an elastic
    ring reaches f_t: p_cr = f_t (b^2 - R^2)/(b^2 + R^2)."""
    return f_t * (b * b - R * R) / (b * b + R * R)


def rigid_segments_pressure(sigma_of_w, w, R, b):
    """Inner pressure [MPa] a ring cut by radial cracks into rigid segments
    carries when each crack is open by w [mm] with cohesive stress
    sigma_of_w(w) [MPa] over the ligament b - R: p = ((b - R)/R) sigma(w)."""
    return (b - R) / R * sigma_of_w(w)

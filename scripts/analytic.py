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

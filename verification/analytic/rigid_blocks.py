"""Closed forms for rigid blocks on Coulomb joints (VERIFICATION-CATALOG, first section).

Sign conventions: joint normal stress and force compression positive, normal displacement
closing positive, settlement positive downward. SI units; angles in degrees where named _deg.
"""
import math

import numpy as np


def _tan(deg):
    return math.tan(math.radians(deg))


def resting_normal_force(*, mass, g):
    """Normal force of a block resting on a joint: m g."""
    return mass * g


def resting_settlement(*, mass, g, kn, contact_length):
    """Static deflection of the joint spring, m g / (kn L) (NUREG/CR-5429 1.3-3)."""
    return mass * g / (kn * contact_length)


def oscillator_frequency(*, mass, kn, contact_length):
    return math.sqrt(kn * contact_length / mass)


def oscillator_period(*, mass, kn, contact_length):
    """T = 2 pi sqrt(m / (kn L))."""
    return 2.0 * math.pi / oscillator_frequency(mass=mass, kn=kn, contact_length=contact_length)


def oscillator_settlement_history(t, *, mass, g, kn, contact_length, alpha=0.0):
    """Block released at zero overlap: y(t) = d [1 - e^{-a t/2} (cos wd t + a/(2 wd) sin wd t)]."""
    t = np.asarray(t, dtype=float)
    w = oscillator_frequency(mass=mass, kn=kn, contact_length=contact_length)
    if alpha >= 2.0 * w:
        raise ValueError("only the underdamped case (alpha < 2 w) has this form")
    d = resting_settlement(mass=mass, g=g, kn=kn, contact_length=contact_length)
    wd = math.sqrt(w * w - alpha * alpha / 4.0)
    return d * (1.0 - np.exp(-alpha * t / 2.0) * (np.cos(wd * t) + alpha / (2.0 * wd) * np.sin(wd * t)))


def central_difference_period(*, mass, kn, contact_length, dt):
    """Exact period of the undamped central-difference recurrence: sin(w_num dt / 2) = w dt / 2."""
    w = oscillator_frequency(mass=mass, kn=kn, contact_length=contact_length)
    if w * dt >= 2.0:
        raise ValueError("w dt >= 2: the recurrence is unstable and has no period")
    return 2.0 * math.pi / ((2.0 / dt) * math.asin(w * dt / 2.0))


def central_difference_settlement_history(t, *, mass, g, kn, contact_length, alpha, dt):
    """Closed form of the damped central-difference recurrence (NUREG/CR-5429 1.3-21),

        v_{n+1/2} = [v_{n-1/2} (1 - a dt/2) + (g - w^2 y_n) dt] / (1 + a dt/2),  y_{n+1} = y_n + v_{n+1/2} dt,

    with y_0 = 0, v_{-1/2} = 0. Eliminating v: y_{n+1} - 2 c y_n + q y_{n-1} = b, with
    q = (1 - a dt/2)/(1 + a dt/2), 2c = 1 + q - w^2 dt^2 / (1 + a dt/2), b = g dt^2 / (1 + a dt/2).
    The fixed point is d = g / w^2; the roots of z^2 - 2 c z + q = 0 are r e^{+-i theta}, r = sqrt(q),
    so y_n = d + r^n (A cos n theta + B sin n theta), A = -d, and B from y_1 = b (since y_{-1} = y_0).
    """
    n = np.rint(np.asarray(t, dtype=float) / dt)
    w2 = kn * contact_length / mass
    h = 1.0 + alpha * dt / 2.0
    q = (1.0 - alpha * dt / 2.0) / h
    c = 0.5 * (1.0 + q - w2 * dt * dt / h)
    if c * c >= q:
        raise ValueError("the recurrence is not oscillatory at this dt and alpha")
    r = math.sqrt(q)
    theta = math.acos(c / r)
    d = g / w2
    y1 = g * dt * dt / h
    a_coef = -d
    b_coef = (y1 - d - r * a_coef * math.cos(theta)) / (r * math.sin(theta))
    return d + r ** n * (a_coef * np.cos(n * theta) + b_coef * np.sin(n * theta))


def log_decrement(*, alpha, mass, kn, contact_length):
    """delta = 2 pi xi / sqrt(1 - xi^2), xi = alpha / (2 w)."""
    xi = alpha / (2.0 * oscillator_frequency(mass=mass, kn=kn, contact_length=contact_length))
    return 2.0 * math.pi * xi / math.sqrt(1.0 - xi * xi)


def incline_acceleration(*, g, theta_deg, phi_deg, cohesion=0.0, contact_length=1.0, mass=1.0):
    """a = g (sin theta - cos theta tan phi) - c L / m, or 0 when the block stays."""
    th = math.radians(theta_deg)
    a = g * (math.sin(th) - math.cos(th) * _tan(phi_deg)) - cohesion * contact_length / mass
    return max(a, 0.0)


def direct_shear_constant_normal_stress(us, *, ks, sn, cohesion, phi_deg, psi_deg=0.0):
    """(tau, opening): tau = ks us up to us_y = (c + sn tan phi)/ks, then c + sn tan phi;
    opening (us - us_y) tan psi while slipping."""
    us = np.asarray(us, dtype=float)
    strength = cohesion + sn * _tan(phi_deg)
    us_y = strength / ks
    tau = np.where(us < us_y, ks * us, strength)
    opening = np.where(us > us_y, (us - us_y) * _tan(psi_deg), 0.0)
    return tau, opening


def direct_shear_block_rise(us, *, ks, kn, sn, cohesion, phi_deg, psi_deg):
    """Vertical displacement of a block sheared under a dead normal load on a unit-length joint:
    settlement -sn/kn plus the dilatant opening."""
    _, opening = direct_shear_constant_normal_stress(us, ks=ks, sn=sn, cohesion=cohesion, phi_deg=phi_deg,
                                                     psi_deg=psi_deg)
    return -sn / kn + opening


def direct_shear_constant_normal_displacement(us, *, ks, kn, sn0, cohesion, phi_deg, psi_deg):
    """(tau, sn) with the normal displacement held: after yield, sn = sn0 + kn tan psi us_p and
    tau = c + sn tan phi = ks (us - us_p), so us_p = (ks (us - us_y)) / (ks + kn tan phi tan psi)."""
    us = np.asarray(us, dtype=float)
    tp, ts = _tan(phi_deg), _tan(psi_deg)
    us_y = (cohesion + sn0 * tp) / ks
    us_p = np.where(us > us_y, ks * (us - us_y) / (ks + kn * tp * ts), 0.0)
    sn = sn0 + kn * ts * us_p
    tau = np.where(us > us_y, cohesion + sn * tp, ks * us)
    return tau, sn


def coulomb_peak_strength(*, sn, cohesion, phi_deg):
    """c + sn tan phi."""
    return cohesion + sn * _tan(phi_deg)


def coulomb_residual_strength(*, sn, phi_deg):
    """sn tan phi: the strength of a model-5 joint after its first slip."""
    return sn * _tan(phi_deg)


def direct_shear_coulomb_fracture(us, *, ks, sn, cohesion, phi_deg):
    """Model 5 at constant sn: ks us up to the peak c + sn tan phi, then sn tan phi."""
    us = np.asarray(us, dtype=float)
    peak = coulomb_peak_strength(sn=sn, cohesion=cohesion, phi_deg=phi_deg)
    return np.where(ks * us <= peak, ks * us, coulomb_residual_strength(sn=sn, phi_deg=phi_deg))


def tensile_opening_stress(un, *, kn, tension):
    """sn = kn un while sn >= -T0; zero once the joint has broken (monotonic opening)."""
    un = np.asarray(un, dtype=float)
    return np.where(un >= -tension / kn, kn * un, 0.0)


def rigid_block_frequencies(*, width, height, density, kn, ks, contact_length_per_corner=None):
    """Natural angular frequencies of a rectangular block on two bottom-corner contacts
    (normal spring kn Lc, shear spring ks Lc at (+-w/2, -h/2)), in (x, y, theta)."""
    import scipy.linalg
    lc = width / 2.0 if contact_length_per_corner is None else contact_length_per_corner
    m = density * width * height
    inertia = m * (width ** 2 + height ** 2) / 12.0
    stiffness = np.zeros((3, 3))
    for x in (-width / 2.0, width / 2.0):
        y = -height / 2.0
        # shear spring along x at (x, y): displacement of the point along x is ux - y theta
        gs = np.array([1.0, 0.0, -y])
        gn = np.array([0.0, 1.0, x])
        stiffness += ks * lc * np.outer(gs, gs) + kn * lc * np.outer(gn, gn)
    w2 = scipy.linalg.eigh(stiffness, np.diag([m, m, inertia]), eigvals_only=True)
    return np.sort(np.sqrt(w2))


def critical_frac(*, width, height, density, kn, ks, typical_length):
    """FRAC at which w_max dt = 2 for dt = FRAC 2 sqrt(M / (max(kn, ks) l_typ)) (1.3-28, 1.3-29)."""
    w_max = rigid_block_frequencies(width=width, height=height, density=density, kn=kn, ks=ks)[-1]
    m = density * width * height
    dt_per_frac = 2.0 * math.sqrt(m / (max(kn, ks) * typical_length))
    return 2.0 / (w_max * dt_per_frac)

"""Closed-form references for plane-strain linear elasticity (deformable blocks, constant-strain triangles).

Independent of the solver: only math and numpy are used, and every formula is either taken from the
cited text or derived here from Hooke's law, equilibrium and the strain-displacement relations.

Sign conventions: stresses and strains TENSION (extension) POSITIVE. Pressures (p_i, p_o of the Lame
cylinder) are the one exception: they are positive in compression, as pressures always are, so a
pressure p on a surface is a normal stress -p. Polar coordinates (r, theta) with theta measured from
the x axis, anticlockwise; u_r outward, u_theta anticlockwise; sigma_rt is the shear stress on the
r-face in the theta direction. Plane strain throughout: e_zz = 0, so sigma_zz = nu (sigma_xx + sigma_yy).
SI units throughout (Pa, m, s, kg/m^3). Every function takes keyword arguments only; stress, strain and
displacement functions accept numpy arrays (broadcast together) and return arrays.

Elastic constants: E Young's modulus, nu Poisson's ratio (-1 < nu < 1/2), K bulk modulus, G shear
modulus, lam Lame's first constant, M = lam + 2 G = K + 4 G / 3 the constrained (P-wave) modulus.
"""
import math

import numpy as np


def _arr(x):
    return np.asarray(x, dtype=float)


def _check_young_poisson(E, nu):
    E, nu = _arr(E), _arr(nu)
    if np.any(~(E > 0.0)):
        raise ValueError(f"E = {E}: Young's modulus must be positive")
    if np.any(~((nu > -1.0) & (nu < 0.5))):
        raise ValueError(f"nu = {nu}: Poisson's ratio must lie in (-1, 1/2) for a stable isotropic solid")
    return E, nu


# ---------------------------------------------------------------- elastic constants


def lame_from_young(*, E, nu):
    """(lam, G) from (E, nu):

        lam = E nu / ((1 + nu)(1 - 2 nu)),   G = E / (2 (1 + nu))

    (Timoshenko & Goodier, Theory of Elasticity, 3rd ed., ch. 1, Hooke's law; any elasticity text).
    """
    E, nu = _check_young_poisson(E, nu)
    return E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), E / (2.0 * (1.0 + nu))


def bulk_shear_from_young(*, E, nu):
    """(K, G) from (E, nu): K = E / (3 (1 - 2 nu)),  G = E / (2 (1 + nu))."""
    E, nu = _check_young_poisson(E, nu)
    return E / (3.0 * (1.0 - 2.0 * nu)), E / (2.0 * (1.0 + nu))


def young_poisson_from_bulk_shear(*, K, G):
    """(E, nu) from (K, G): E = 9 K G / (3 K + G),  nu = (3 K - 2 G) / (2 (3 K + G)).

    The inverse of bulk_shear_from_young. Needs K > 0 and G > 0, else ValueError.
    """
    K, G = _arr(K), _arr(G)
    if np.any(~(K > 0.0)) or np.any(~(G > 0.0)):
        raise ValueError(f"K = {K}, G = {G}: both moduli must be positive")
    return 9.0 * K * G / (3.0 * K + G), (3.0 * K - 2.0 * G) / (2.0 * (3.0 * K + G))


def constrained_modulus(*, E, nu):
    """Constrained (oedometric, P-wave) modulus M = lam + 2 G = K + 4 G / 3 = E (1 - nu) / ((1 + nu)(1 - 2 nu)):
    the ratio sigma_xx / e_xx under uniaxial strain (e_yy = e_zz = 0)."""
    E, nu = _check_young_poisson(E, nu)
    return E * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu))


def plane_strain_moduli(*, E, nu):
    """(E', nu') = (E / (1 - nu^2), nu / (1 - nu)): the plane-strain constants with which the 2D in-plane
    Hooke's law takes the plane-stress form e_xx = (s_xx - nu' s_yy) / E', e_yy = (s_yy - nu' s_xx) / E'
    (eliminate s_zz = nu (s_xx + s_yy) from the 3D law; Timoshenko & Goodier, ch. 2, plane strain)."""
    E, nu = _check_young_poisson(E, nu)
    return E / (1.0 - nu * nu), nu / (1.0 - nu)


# ---------------------------------------------------------------- homogeneous plane-strain samples


def plane_strain_biaxial(*, E, nu, sigma_xx, sigma_yy):
    """(e_xx, e_yy, sigma_zz) of a sample under uniform in-plane stresses sigma_xx, sigma_yy (no shear),
    plane strain e_zz = 0:

        sigma_zz = nu (sigma_xx + sigma_yy),
        e_xx = ((1 + nu) / E) ((1 - nu) sigma_xx - nu sigma_yy),
        e_yy = ((1 + nu) / E) ((1 - nu) sigma_yy - nu sigma_xx).

    3D isotropic Hooke's law e_ii = (s_ii - nu (s_jj + s_kk)) / E with e_zz = 0 giving s_zz.
    """
    E, nu = _check_young_poisson(E, nu)
    sxx, syy = _arr(sigma_xx), _arr(sigma_yy)
    c = (1.0 + nu) / E
    return c * ((1.0 - nu) * sxx - nu * syy), c * ((1.0 - nu) * syy - nu * sxx), nu * (sxx + syy)


def plane_strain_uniaxial(*, E, nu, sigma_yy):
    """(e_xx, e_yy, sigma_zz) of a sample loaded by sigma_yy with free sides (sigma_xx = 0), e_zz = 0:

        e_xx = -nu (1 + nu) sigma_yy / E,   e_yy = (1 - nu^2) sigma_yy / E,   sigma_zz = nu sigma_yy.

    plane_strain_biaxial with sigma_xx = 0.
    """
    return plane_strain_biaxial(E=E, nu=nu, sigma_xx=0.0, sigma_yy=sigma_yy)


def plane_strain_homogeneous_displacement(*, x, y, E, nu, sigma_xx, sigma_yy, x0=0.0, y0=0.0, shift_y=0.0):
    """(u_x, u_y) of a sample under uniform sigma_xx, sigma_yy (no shear, plane strain) held at
    (x0, y0) without rotation: u_x = e_xx (x - x0), u_y = e_yy (y - y0) + shift_y, the strains of
    plane_strain_biaxial. A sample on rollers along y = y0 with the corner (x0, y0) fixed is
    held so. shift_y translates it: a block resting on another across a joint of normal
    stiffness kn under sigma_yy = -p moves down by the joint's closure too, shift_y = -p / kn.
    """
    exx, eyy, _ = plane_strain_biaxial(E=E, nu=nu, sigma_xx=sigma_xx, sigma_yy=sigma_yy)
    return exx * (_arr(x) - x0), eyy * (_arr(y) - y0) + shift_y


def young_poisson_from_plane_strain_uniaxial(*, sigma_yy, exx, eyy):
    """(E, nu) recovered from a plane-strain uniaxial test (sigma_xx = 0, e_zz = 0) with measured
    sigma_yy, e_xx, e_yy. The test measures the plane-strain constants

        E' = sigma_yy / e_yy = E / (1 - nu^2),   nu' = -e_xx / e_yy = nu / (1 - nu),

    which invert to nu = nu' / (1 + nu'), E = E' (1 - nu^2). Inverse of plane_strain_uniaxial.
    Needs e_yy != 0 and a result with E > 0, -1 < nu < 1/2, else ValueError.
    """
    syy, exx, eyy = _arr(sigma_yy), _arr(exx), _arr(eyy)
    if np.any(eyy == 0.0):
        raise ValueError("e_yy = 0: the test gives no stiffness")
    e_prime = syy / eyy
    nu_prime = -exx / eyy
    nu = nu_prime / (1.0 + nu_prime)
    E = e_prime * (1.0 - nu * nu)
    _check_young_poisson(E, nu)
    return E, nu


def plane_strain_stress_from_strain(*, exx, eyy, gxy, E, nu):
    """(sigma_xx, sigma_yy, sigma_xy, sigma_zz) from the in-plane strains, e_zz = 0:

        s_xx = lam (e_xx + e_yy) + 2 G e_xx,   s_yy = lam (e_xx + e_yy) + 2 G e_yy,
        s_xy = G gamma_xy,                      s_zz = lam (e_xx + e_yy) = nu (s_xx + s_yy),

    gamma_xy = 2 e_xy the engineering shear strain (isotropic Hooke's law, lam and G as lame_from_young).
    """
    lam, G = lame_from_young(E=E, nu=nu)
    exx, eyy, gxy = _arr(exx), _arr(eyy), _arr(gxy)
    vol = lam * (exx + eyy)
    return vol + 2.0 * G * exx, vol + 2.0 * G * eyy, G * gxy, vol


# ---------------------------------------------------------------- patch test


def linear_displacement_field(*, x, y, a0, a1, a2, b0, b1, b2):
    """(u_x, u_y) = (a0 + a1 x + a2 y, b0 + b1 x + b2 y): the linear field every constant-strain
    element must reproduce exactly (patch test; Zienkiewicz & Taylor, The Finite Element Method,
    vol. 1, the patch test)."""
    x, y = _arr(x), _arr(y)
    return a0 + a1 * x + a2 * y, b0 + b1 * x + b2 * y


def stress_from_linear_field(*, a1, a2, b1, b2, E, nu):
    """Constant plane-strain stresses (sigma_xx, sigma_yy, sigma_xy, sigma_zz) of linear_displacement_field:
    strains e_xx = a1, e_yy = b2, gamma_xy = a2 + b1 (the rotation (b1 - a2) / 2 carries no stress),
    then plane_strain_stress_from_strain."""
    return plane_strain_stress_from_strain(exx=a1, eyy=b2, gxy=_arr(a2) + _arr(b1), E=E, nu=nu)


# ---------------------------------------------------------------- Lame thick-walled cylinder


def lame_cylinder(*, r, a, b, p_i, p_o, E, nu):
    """(sigma_rr, sigma_tt, sigma_zz, u_r) in a thick-walled cylinder a <= r <= b under inner pressure p_i
    and outer pressure p_o (pressures positive in compression), plane strain:

        sigma_rr = A - B / r^2,   sigma_tt = A + B / r^2,   sigma_zz = nu (sigma_rr + sigma_tt) = 2 nu A,
        A = (p_i a^2 - p_o b^2) / (b^2 - a^2),   B = (p_i - p_o) a^2 b^2 / (b^2 - a^2),
        u_r = ((1 + nu) / E) ((1 - 2 nu) A r + B / r).

    Lame's problem: Timoshenko & Goodier, Theory of Elasticity, 3rd ed. (1970), ch. 4, "stress distribution
    symmetrical about an axis" (the thick-walled cylinder; the article number differs between editions)
    for the stresses, written here tension positive so that sigma_rr(a) = -p_i and sigma_rr(b) = -p_o.
    u_r is derived here from the plane-strain hoop strain u_r / r = ((1 + nu) / E)((1 - nu) s_tt - nu s_rr),
    measured from the unloaded state. b = numpy.inf is allowed: A = -p_o, B = (p_i - p_o) a^2 (a hole in
    an infinite medium; written with a^2 / b^2 so the limit is exact). r outside [a, b] is a ValueError.
    """
    r = _arr(r)
    E, nu = _check_young_poisson(E, nu)
    if not 0.0 < a < b:
        raise ValueError(f"a = {a}, b = {b}: need 0 < a < b")
    if np.any(r < a * (1.0 - 1e-12)) or np.any(r > b * (1.0 + 1e-12)):
        raise ValueError("r lies outside the wall a <= r <= b")
    q = (a / b) ** 2  # 0 when b is infinite
    A = (p_i * q - p_o) / (1.0 - q)
    B = (p_i - p_o) * a * a / (1.0 - q)
    srr = A - B / r ** 2
    stt = A + B / r ** 2
    szz = nu * (srr + stt)
    ur = (1.0 + nu) / E * ((1.0 - 2.0 * nu) * A * r + B / r)
    return srr, stt, szz, ur


# ---------------------------------------------------------------- Kirsch: circular hole in an infinite plate


def _kirsch_polar(r, theta, a, S_x, S_y):
    r, theta = np.broadcast_arrays(_arr(r), _arr(theta))
    if not a > 0.0:
        raise ValueError(f"a = {a}: the hole radius must be positive")
    if np.any(r < a * (1.0 - 1e-12)):
        raise ValueError("r < a: the point lies inside the hole")
    P, Q = 0.5 * (S_x + S_y), 0.5 * (S_x - S_y)
    q2 = (a / r) ** 2
    q4 = q2 * q2
    c2, s2 = np.cos(2.0 * theta), np.sin(2.0 * theta)
    srr = P * (1.0 - q2) + Q * (1.0 - 4.0 * q2 + 3.0 * q4) * c2
    stt = P * (1.0 + q2) - Q * (1.0 + 3.0 * q4) * c2
    srt = -Q * (1.0 + 2.0 * q2 - 3.0 * q4) * s2
    return r, theta, srr, stt, srt


def _polar_to_cartesian_stress(theta, srr, stt, srt):
    c, s = np.cos(theta), np.sin(theta)
    sxx = srr * c * c + stt * s * s - 2.0 * srt * s * c
    syy = srr * s * s + stt * c * c + 2.0 * srt * s * c
    sxy = (srr - stt) * s * c + srt * (c * c - s * s)
    return sxx, syy, sxy


def _kirsch_displacement(r, theta, a, S_x, S_y, E, nu):
    E, nu = _check_young_poisson(E, nu)
    G = E / (2.0 * (1.0 + nu))
    kappa = 3.0 - 4.0 * nu
    P, Q = 0.5 * (S_x + S_y), 0.5 * (S_x - S_y)
    ur = (P / (4.0 * G) * ((kappa - 1.0) * r + 2.0 * a * a / r)
          + Q / (2.0 * G) * (r + (kappa + 1.0) * a * a / r - a ** 4 / r ** 3) * np.cos(2.0 * theta))
    ut = -Q / (2.0 * G) * (r + (kappa - 1.0) * a * a / r + a ** 4 / r ** 3) * np.sin(2.0 * theta)
    return ur, ut


def kirsch(*, r, theta, a, S_x, S_y, E=None, nu=None):
    """Stresses (and, given E and nu, plane-strain displacements) around a traction-free circular hole of
    radius a in an infinite plate under far-field sigma_xx = S_x, sigma_yy = S_y, tau_xy = 0 (tension
    positive; for principal far-field stresses at an angle, rotate theta). Returns a dict of arrays:

        'srr', 'stt', 'srt'   polar stresses,
        'sxx', 'syy', 'sxy'   the same in Cartesian components (to impose exact tractions or stresses on
                              the outer boundary of a truncated mesh),
        'ur', 'ut'            displacements, only when E and nu are given.

    With P = (S_x + S_y) / 2, Q = (S_x - S_y) / 2 (Kirsch 1898, Z. VDI 42, 797-807; Timoshenko & Goodier,
    Theory of Elasticity, 3rd ed., ch. 4, "effect of circular holes on stress distributions in plates";
    Jaeger, Cook & Zimmerman, Fundamentals of Rock Mechanics, 4th ed., ch. 8, there compression positive):

        srr = P (1 - a^2/r^2) + Q (1 - 4 a^2/r^2 + 3 a^4/r^4) cos 2 theta,
        stt = P (1 + a^2/r^2) - Q (1 + 3 a^4/r^4) cos 2 theta,
        srt = -Q (1 + 2 a^2/r^2 - 3 a^4/r^4) sin 2 theta.

    At the wall stt = 2 P - 4 Q cos 2 theta: for S_x = S, S_y = 0, 3 S at theta = 90 deg and -S at 0.

    Displacements, plane strain, kappa = 3 - 4 nu, G = E / (2 (1 + nu)), measured from the stress-free
    state of the plate (so they include the far-field uniform strain, u ~ r e_inf as r -> inf):

        u_r = P / (4 G) ((kappa - 1) r + 2 a^2/r) + Q / (2 G) (r + (kappa + 1) a^2/r - a^4/r^3) cos 2 theta,
        u_t = -Q / (2 G) (r + (kappa - 1) a^2/r + a^4/r^3) sin 2 theta.

    Derived here by integrating the plane-strain strains e_rr = ((1 - nu) s_rr - nu s_tt) / (2 G) in r and
    e_tt = (u_r + du_t/dtheta) / r in theta, the integration functions fixed by the symmetry about both
    axes and by the far field; the shear strain then reproduces srt / G exactly. The axisymmetric part is
    Lame's u_r = ((1 - 2 nu) P r + P a^2 / r) / (2 G) (note (kappa - 1)/4 = (1 - 2 nu)/2). Compare the
    displacement solutions for the hole in Jaeger, Cook & Zimmerman, ch. 8 (compression positive there).
    kappa = 3 - 4 nu is the plane-strain value; the plane-stress kappa = (3 - nu) / (1 + nu) must not be used
    here. r < a is a ValueError.
    """
    r, theta, srr, stt, srt = _kirsch_polar(r, theta, a, S_x, S_y)
    sxx, syy, sxy = _polar_to_cartesian_stress(theta, srr, stt, srt)
    out = {"srr": srr, "stt": stt, "srt": srt, "sxx": sxx, "syy": syy, "sxy": sxy}
    if (E is None) != (nu is None):
        raise ValueError("give both E and nu for the displacements, or neither")
    if E is not None:
        out["ur"], out["ut"] = _kirsch_displacement(r, theta, a, S_x, S_y, E, nu)
    return out


def kirsch_cartesian_stress(*, x, y, a, S_x, S_y):
    """(sigma_xx, sigma_yy, sigma_xy) of kirsch at Cartesian points (x, y), hole centred at the origin."""
    x, y = _arr(x), _arr(y)
    res = kirsch(r=np.hypot(x, y), theta=np.arctan2(y, x), a=a, S_x=S_x, S_y=S_y)
    return res["sxx"], res["syy"], res["sxy"]


def kirsch_cartesian_displacement(*, x, y, a, S_x, S_y, E, nu):
    """(u_x, u_y) of kirsch at Cartesian points (x, y), hole centred at the origin, plane strain:
    u_x = u_r cos theta - u_t sin theta,  u_y = u_r sin theta + u_t cos theta."""
    x, y = _arr(x), _arr(y)
    theta = np.arctan2(y, x)
    res = kirsch(r=np.hypot(x, y), theta=theta, a=a, S_x=S_x, S_y=S_y, E=E, nu=nu)
    c, s = np.cos(theta), np.sin(theta)
    return res["ur"] * c - res["ut"] * s, res["ur"] * s + res["ut"] * c


def kirsch_excavation_displacement(*, x, y, a, S_x, S_y, E, nu):
    """(u_x, u_y) caused by excavating the hole from a plate already at equilibrium under the far
    field (S_x, S_y): Kirsch's displacement less the plate's before the hole, the homogeneous
    plane-strain field of the same stress (kirsch with a = 0, where every a^2 term vanishes).
    In polar form, with P = (S_x + S_y)/2, Q = (S_x - S_y)/2, kappa = 3 - 4 nu:

        u_r = P a^2 / (2 G r) + Q / (2 G) ((kappa + 1) a^2 / r - a^4 / r^3) cos 2 theta
        u_t = -Q / (2 G) ((kappa - 1) a^2 / r + a^4 / r^3) sin 2 theta

    which falls off as a^2 / r away from the hole (compression negative, so a compressive field
    moves the wall inwards)."""
    E, nu = _check_young_poisson(E, nu)
    if not a > 0.0:
        raise ValueError(f"a = {a}: the hole radius must be positive")
    x, y = _arr(x), _arr(y)
    r, theta = np.hypot(x, y), np.arctan2(y, x)
    # points on the wall may sit inside it by round-off or a small strain (positions after a reset)
    if np.any(r < a * (1.0 - 1e-5)):
        raise ValueError(f"a point lies inside the hole (r < a = {a})")
    G = E / (2.0 * (1.0 + nu))
    kappa = 3.0 - 4.0 * nu
    P, Q = 0.5 * (S_x + S_y), 0.5 * (S_x - S_y)
    ur = P * a * a / (2.0 * G * r) + Q / (2.0 * G) * ((kappa + 1.0) * a * a / r - a ** 4 / r ** 3) * np.cos(2.0 * theta)
    ut = -Q / (2.0 * G) * ((kappa - 1.0) * a * a / r + a ** 4 / r ** 3) * np.sin(2.0 * theta)
    c, s = np.cos(theta), np.sin(theta)
    return ur * c - ut * s, ur * s + ut * c


# ---------------------------------------------------------------- elastic half-plane: line and strip loads
#
# The half-plane is y <= surface_y, x horizontal, y up; d = surface_y - y >= 0 is the depth. Loads are
# per unit length out of the plane (N/m for a line load, Pa for a pressure) and positive DOWNWARD, into
# the solid. Stresses tension positive, sigma_xy for the y-up axes. In 2D the surface displacement of a
# loaded half-plane grows like ln|x| and has no datum at infinity, so only differences between two surface
# points are defined: v(x2) - v(x1), v = u_y positive up.


def _half_plane_depth(y, surface_y):
    d = surface_y - _arr(y)
    if np.any(d < 0.0):
        raise ValueError(f"y > surface_y = {surface_y}: the point lies above the half-plane's surface")
    return d


def _surface_settlement_constant(E, nu):
    # 2 (1 - nu^2) / (pi E): the plane-strain factor of ln|x| in Flamant's surface displacement
    E, nu = _check_young_poisson(E, nu)
    return 2.0 * (1.0 - nu * nu) / (math.pi * E)


def flamant_stress(*, x, y, P, surface_y=0.0):
    """(sigma_xx, sigma_yy, sigma_xy) in the half-plane y <= surface_y under a vertical line load P (N/m,
    downward positive) at x = 0 of the surface (Flamant 1892, C. R. Acad. Sci. Paris 114, 1465-1468;
    Timoshenko & Goodier, Theory of Elasticity, 3rd ed., ch. 4, "concentrated vertical force on a straight
    boundary"; Johnson, Contact Mechanics, eq. 2.15). The stress is purely radial,

        sigma_rr = -2 P cos(theta) / (pi r),   sigma_tt = sigma_rt = 0,

    theta measured from the downward vertical, r the distance from the load. With the depth
    d = surface_y - y = r cos(theta) and the unit radius n = (x, -d) / r (y up), sigma = sigma_rr n n^T:

        sigma_xx = -2 P x^2 d / (pi r^4),   sigma_yy = -2 P d^3 / (pi r^4),   sigma_xy = +2 P x d^2 / (pi r^4).

    sigma_xy is minus Johnson's tau_xz because his z axis points down (e_y = -e_z). Checks: the surface
    d = 0, x != 0 is traction free; the integral of sigma_yy over any horizontal line is -P
    (int d^3 / (x^2 + d^2)^2 dx = pi / 2); equilibrium holds without body force. The load point (r = 0)
    is singular and is a ValueError, as is a point above the surface.
    """
    x = _arr(x)
    d = _half_plane_depth(y, surface_y)
    x, d = np.broadcast_arrays(x, d)
    r2 = x * x + d * d
    if np.any(r2 == 0.0):
        raise ValueError("a point sits on the line load, where Flamant's stresses are singular")
    c = 2.0 * P / (math.pi * r2 * r2)
    return -c * x * x * d, -c * d ** 3, c * x * d * d


def flamant_relative_settlement(*, x1, x2, P, E, nu):
    """v(x2) - v(x1): the difference of the surface's vertical displacement (up positive) between the
    surface points at horizontal distances x1 and x2 from a vertical line load P (N/m, downward positive)
    on a plane-strain elastic half-plane:

        v(x2) - v(x1) = 2 (1 - nu^2) P / (pi E) ln(|x2| / |x1|).

    From Johnson, Contact Mechanics, eq. 2.19b (plane strain), u_z = -(2 (1 - nu^2) / (pi E)) P ln|x| + C
    with z into the solid, and v = -u_z; Timoshenko & Goodier, ch. 4, derive it in plane stress, where the
    factor is 2 / (pi E): plane strain replaces E by E / (1 - nu^2). The point farther from the load is
    higher. Check: along the traction-free surface the
    strains vanish, so d^2 v / dx^2 = -d e_xx / dy there (compatibility: d omega / dx = d e_xy / dx - d e_xx / dy,
    omega the rotation), and -d e_xx / dy = -(1 - nu^2) / E d sigma_xx / dy = -(1 - nu^2) 2 P / (pi E x^2)
    from flamant_stress: exactly the second derivative of the ln above. x = 0 (the load) is a ValueError.
    """
    x1, x2 = np.abs(_arr(x1)), np.abs(_arr(x2))
    if np.any(x1 == 0.0) or np.any(x2 == 0.0):
        raise ValueError("x1 or x2 = 0: the surface displacement under a line load is singular at the load")
    return _surface_settlement_constant(E, nu) * P * np.log(x2 / x1)


def strip_load_stress(*, x, y, q, b, surface_y=0.0):
    """(sigma_xx, sigma_yy, sigma_xy) in the half-plane y <= surface_y under a uniform vertical pressure q
    (Pa, downward positive) on the surface strip |x| <= b. Derived here by integrating flamant_stress with
    P = q dxi over the load positions xi in [-b, b]; with X = x - xi and the antiderivatives

        int d^3 / (X^2 + d^2)^2 dX   = (atan(X/d) + X d / (X^2 + d^2)) / 2,
        int X^2 d / (X^2 + d^2)^2 dX = (atan(X/d) - X d / (X^2 + d^2)) / 2,
        int X d^2 / (X^2 + d^2)^2 dX = -d^2 / (2 (X^2 + d^2)),

    and the angles theta_1 = atan2(x - b, d), theta_2 = atan2(x + b, d) (from the downward vertical to the
    lines joining the point to the strip's edges), alpha = theta_2 - theta_1 (the angle the strip subtends):

        sigma_xx = -(q / pi) (alpha - sin(alpha) cos(theta_1 + theta_2)),
        sigma_yy = -(q / pi) (alpha + sin(alpha) cos(theta_1 + theta_2)),
        sigma_xy = (q / pi) sin(alpha) sin(theta_1 + theta_2).

    These are the classic strip-footing stresses (Poulos & Davis, Elastic Solutions for Soil and Rock
    Mechanics, 1974, ch. 3, uniform vertical loading on a strip, compression positive there, with
    delta = theta_1 and alpha + 2 delta = theta_1 + theta_2; Johnson, Contact Mechanics, ch. 2). Under the
    centre at depth b: sigma_yy = -q (1/2 + 1/pi), sigma_xx = -q (1/2 - 1/pi). On the surface
    sigma_xx = sigma_yy = -q, sigma_xy = 0 under the strip and zero outside; at the edges on the surface the
    stress is discontinuous and the value returned (atan2(0, 0) = 0) is the mean of the two sides for
    sigma_xx and sigma_yy. b <= 0 or a point above the surface is a ValueError.
    """
    if not b > 0.0:
        raise ValueError(f"b = {b}: the strip's half-width must be positive")
    x = _arr(x)
    d = _half_plane_depth(y, surface_y)
    x, d = np.broadcast_arrays(x, d)
    theta_1, theta_2 = np.arctan2(x - b, d), np.arctan2(x + b, d)
    alpha, twice_mid = theta_2 - theta_1, theta_1 + theta_2
    k = q / math.pi
    sin_alpha = np.sin(alpha)
    return (-k * (alpha - sin_alpha * np.cos(twice_mid)), -k * (alpha + sin_alpha * np.cos(twice_mid)),
            k * sin_alpha * np.sin(twice_mid))


def _x_log_abs_x(x):
    # x ln|x| with its limit 0 at x = 0 (the strip's edges)
    ax = np.abs(x)
    return np.where(ax > 0.0, x * np.log(np.where(ax > 0.0, ax, 1.0)), 0.0)


def strip_load_relative_settlement(*, x1, x2, q, b, E, nu):
    """v(x2) - v(x1): the difference of the surface's vertical displacement (up positive) between two
    surface points under a uniform vertical pressure q (Pa, downward positive) on the strip |x| <= b of a
    plane-strain elastic half-plane. Flamant's surface displacement, v = C P ln|x - xi| + const with
    C = 2 (1 - nu^2) / (pi E) (flamant_relative_settlement), integrated with P = q dxi over xi in [-b, b]:
    int ln|X| dX = X ln|X| - X, so

        v(x) = C q ((x + b) ln|x + b| - (x - b) ln|x - b|) + const,

    finite at the edges (0 ln 0 = 0; Johnson, Contact Mechanics, ch. 2, uniform pressure on a strip).
    Under the centre v(b) - v(0) = 2 C q b ln 2 (the edge is higher); far from the strip
    (x + b) ln(x + b) - (x - b) ln(x - b) = 2 b (ln x + 1) + O(b^3 / x^2), Flamant's with P = 2 q b.
    b <= 0 is a ValueError.
    """
    if not b > 0.0:
        raise ValueError(f"b = {b}: the strip's half-width must be positive")
    x1, x2 = _arr(x1), _arr(x2)

    def profile(x):
        return _x_log_abs_x(x + b) - _x_log_abs_x(x - b)

    return _surface_settlement_constant(E, nu) * q * (profile(x2) - profile(x1))


# ---------------------------------------------------------------- waves in an elastic column


def p_wave_speed(*, K, G, rho):
    """Dilatational wave speed c_p = sqrt((K + 4 G / 3) / rho) = sqrt(M / rho).

    Assumes uniaxial strain: a plane wave in an unbounded medium, or a column whose sides are held
    laterally (rollers) so that e_yy = e_zz = 0 and the stiffness is the constrained modulus M
    (dilatational waves in an unbounded medium: Kolsky, Stress Waves in Solids, 1953; Graff, Wave Motion in
    Elastic Solids, 1975). A column with free sides carries the slower bar wave instead
    (plane_strain_bar_wave_speed).
    """
    K, G, rho = _arr(K), _arr(G), _arr(rho)
    return np.sqrt((K + 4.0 * G / 3.0) / rho)


def s_wave_speed(*, G, rho):
    """Shear (distortional) wave speed c_s = sqrt(G / rho) (Kolsky, Stress Waves in Solids; Graff, op. cit.)."""
    return np.sqrt(_arr(G) / _arr(rho))


def plane_strain_bar_wave_speed(*, E, nu, rho):
    """Long-wavelength speed in a plane-strain column with free sides (sigma_xx = 0 across, e_zz = 0):
    c = sqrt(E' / rho), E' = E / (1 - nu^2) (the 1D bar-velocity argument with the plane-strain
    modulus of plane_strain_uniaxial; valid for wavelengths much longer than the column width)."""
    e_prime, _ = plane_strain_moduli(E=E, nu=nu)
    return np.sqrt(e_prime / _arr(rho))


def step_pulse_arrival(*, x, t, c, v0=1.0):
    """(t_arrival, v) for a semi-infinite column whose end x = 0 is driven at constant velocity v0
    from t = 0 (a step in velocity), 1D wave equation with speed c:

        t_arrival = x / c,    v(x, t) = v0 H(t - x / c),   H(0) = 1/2.

    d'Alembert solution of u_tt = c^2 u_xx with a right-running wave only (quiescent column, no
    reflection). v is the particle velocity along +x.
    """
    x, t = _arr(x), _arr(t)
    arrival = x / c
    return arrival, v0 * np.heaviside(t - arrival, 0.5)


def step_pulse_stress(*, x, t, c, v0, rho):
    """Axial stress behind the step front of step_pulse_arrival, tension positive:

        sigma(x, t) = -rho c v0 H(t - x / c),   H(0) = 1/2.

    For a right-running wave v = f(t - x/c), momentum rho v_t = sigma_x gives sigma = -rho c v (the
    impedance relation of 1D wave propagation, e.g. Graff, Wave Motion in Elastic Solids): pushing the
    end into the column (v0 > 0) puts it in compression (sigma < 0), pulling it (v0 < 0) in tension.
    rho c is the impedance of the wave the column carries: c = p_wave_speed for a laterally confined
    column, in which case sigma = M e with e = -v / c.
    """
    _, v = step_pulse_arrival(x=x, t=t, c=c, v0=v0)
    return -_arr(rho) * c * v


def p_wave_arrival_time(*, distance, E, nu, rho):
    """Time for a P-wave front to travel `distance` in a laterally confined column (plane strain,
    e_xx = e_zz = 0): distance / c_p, c_p = sqrt((K + 4G/3) / rho) (p_wave_speed)."""
    K, G = bulk_shear_from_young(E=E, nu=nu)
    return _arr(distance) / p_wave_speed(K=K, G=G, rho=rho)


def s_wave_arrival_time(*, distance, E, nu, rho):
    """Time for an S-wave front to travel `distance`: distance / c_s, c_s = sqrt(G / rho)."""
    _, G = bulk_shear_from_young(E=E, nu=nu)
    return _arr(distance) / s_wave_speed(G=G, rho=rho)


def s_wave_sine_velocity(t, *, distance, E, nu, rho, amplitude, frequency):
    """Velocity at `distance` from a boundary driven from t = 0 at amplitude sin(2 pi f t), carried
    by an S-wave without dispersion: amplitude sin(2 pi f (t - distance / c_s)) after the arrival
    distance / c_s, zero before (s_wave_arrival_time)."""
    t = _arr(t)
    delay = s_wave_arrival_time(distance=distance, E=E, nu=nu, rho=rho)
    return np.where(t >= delay, amplitude * np.sin(2.0 * np.pi * frequency * (t - delay)), 0.0)


def s_wave_sine_half_step_velocity(t, *, dt, distance, E, nu, rho, amplitude, frequency):
    """s_wave_sine_velocity at t - dt / 2: what a history of the velocity of an explicit scheme
    holds at t, the velocity of the half step just ended, v(t - dt/2), without the scheme's other
    errors. dt > 0 is the step of the run (a reference of the discrete scheme's sampling)."""
    if not dt > 0.0:
        raise ValueError(f"dt = {dt}: the step must be positive")
    return s_wave_sine_velocity(_arr(t) - 0.5 * dt, distance=distance, E=E, nu=nu, rho=rho, amplitude=amplitude,
                                frequency=frequency)


def s_wave_sine_displacement(t, *, distance, E, nu, rho, amplitude, frequency):
    """Displacement at `distance` from a boundary whose velocity is amplitude sin(2 pi f t) from
    t = 0, carried by an S-wave without dispersion: the time integral of s_wave_sine_velocity,
    (amplitude / w) (1 - cos(w (t - distance / c_s))) after the arrival, zero before."""
    t = _arr(t)
    delay = s_wave_arrival_time(distance=distance, E=E, nu=nu, rho=rho)
    omega = 2.0 * np.pi * frequency
    return np.where(t >= delay, amplitude / omega * (1.0 - np.cos(omega * (t - delay))), 0.0)



def half_sine_pulse_velocity(t, *, distance, c, amplitude, duration):
    """Particle velocity at `distance` from where a half-sine velocity pulse of the given
    amplitude and duration enters a one-dimensional elastic medium at speed c (no dispersion,
    no reflection): amplitude sin(pi (t - distance / c) / duration) while
    0 <= t - distance / c <= duration, zero before and after. With c = sqrt(M / rho) (M the
    constrained modulus K + 4G/3) for a P wave in a laterally confined column, sqrt(G / rho) for
    an S wave."""
    if not (c > 0.0 and duration > 0.0):
        raise ValueError("c and duration must be positive")
    t = _arr(t)
    local = (t - distance / c) / duration
    return np.where((local >= 0.0) & (local <= 1.0), amplitude * np.sin(np.pi * np.clip(local, 0.0, 1.0)), 0.0)


def hann_pulse_velocity(t, *, distance, c, amplitude, duration, dt=0.0):
    """As half_sine_pulse_velocity for a Hann (sine-squared) pulse: amplitude
    sin^2(pi (t - distance / c) / duration) while 0 <= t - distance / c <= duration, zero before
    and after. Its velocity and acceleration are continuous, so that a discretisation's
    dispersion acts on a spectrum that falls as 1 / f^3, not on the kinks of a half-sine.
    dt > 0 evaluates it at t - dt / 2: the velocity a central-difference history records at t."""
    if not (c > 0.0 and duration > 0.0):
        raise ValueError("c and duration must be positive")
    t = _arr(t) - 0.5 * dt
    local = (t - distance / c) / duration
    inside = (local >= 0.0) & (local <= 1.0)
    return np.where(inside, amplitude * np.sin(np.pi * np.clip(local, 0.0, 1.0)) ** 2, 0.0)


def constrained_wave_speed(*, E, nu, rho):
    """c_p = sqrt((K + 4 G / 3) / rho) of a P wave in one-dimensional strain (a laterally
    confined column), from Young's modulus and Poisson's ratio."""
    E, nu = _check_young_poisson(E, nu)
    return math.sqrt(E * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu)) / rho)


def half_sine_pulse_energy(*, rho, c, width, amplitude, duration):
    """Energy (J per metre out of plane) a half-sine velocity pulse carries through a section of
    the given width of a one-dimensional medium: the power rho c v^2 per unit area integrated
    over the pulse, rho c width amplitude^2 duration / 2."""
    return rho * c * width * amplitude * amplitude * duration / 2.0


def joint_transmission_coefficient(*, frequency, impedance, stiffness, incident_amplitude=1.0):
    """Amplitude of a plane wave transmitted through a linear elastic joint (a displacement
    discontinuity of stiffness k, Pa/m) between two identical half-spaces of impedance Z = rho c,
    at normal incidence, for an incident wave of the given amplitude and frequency (Schoenberg
    1980; Pyrak-Nolte, Myer and Cook 1990): |T| = 1 / sqrt(1 + (w Z / 2 k)^2), w = 2 pi f.

    From the incident (A), reflected (R) and transmitted (T) particle velocities at the joint:
    its stress is continuous, A - R = T, and its opening rate is the stress rate over k,
    T - (A + R) = i w Z T / k; together T / A = 1 / (1 - i w Z / (2 k)). For a P wave k = kn and
    Z = rho c_p; for an S wave k = ks and Z = rho c_s."""
    if not (frequency >= 0.0 and impedance > 0.0 and stiffness > 0.0):
        raise ValueError("frequency must be >= 0, impedance and stiffness positive")
    ratio = 2.0 * math.pi * frequency * impedance / (2.0 * stiffness)
    return incident_amplitude / math.sqrt(1.0 + ratio * ratio)


def column_fundamental_angular_frequency(*, E, nu, rho, height):
    """w_1 = pi c_p / (2 H) of a laterally confined column (one-dimensional strain) fixed at its
    base and free at its top: the quarter-wave mode u = sin(pi y / 2 H) of the wave equation with
    c_p = sqrt((K + 4G/3) / rho)."""
    if not height > 0.0:
        raise ValueError("height must be positive")
    return math.pi * constrained_wave_speed(E=E, nu=nu, rho=rho) / (2.0 * height)


def column_rayleigh_log_decrement(*, E, nu, rho, height, alpha, beta):
    """Logarithmic decrement of the column's fundamental mode under Rayleigh damping: each mode of
    an undamped system keeps its shape under C = alpha M + beta K and decays with the damping
    ratio xi = (alpha / w + beta w) / 2 (Clough and Penzien, Dynamics of Structures, 12-4; the
    reference's 1.3-18); the decrement over one period is 2 pi xi / sqrt(1 - xi^2)."""
    w = column_fundamental_angular_frequency(E=E, nu=nu, rho=rho, height=height)
    xi = 0.5 * (alpha / w + beta * w)
    if not 0.0 <= xi < 1.0:
        raise ValueError(f"damping ratio {xi}: the decrement needs 0 <= xi < 1 (underdamped)")
    return 2.0 * math.pi * xi / math.sqrt(1.0 - xi * xi)


# ---------------------------------------------------------------- one crossed cell: its stiffest mode and step


def crossed_cell_centre_frequency(*, E, nu, rho, side):
    """Angular frequency of the centre gridpoint of one crossed square cell of side s whose four
    corners are held (or driven together): w = sqrt(6 (M + G) / rho) / s, M = K + 4G/3.

    The cell's four constant-strain triangles each join the centre to one side. In the bottom
    one the centre's shape function is (y + s/2) / (s/2), gradient (0, 2/s), so its block of the
    triangle's stiffness A B^T D B (A = s^2 / 4, plane-strain D with M on the diagonal and G for
    shear) is diag(G, M) (2/s)^2 A = diag(G, M); the top one likewise, the left and right ones
    diag(M, G). The centre's stiffness is 2 (M + G) in x and y, uncoupled, and its lumped mass a
    third of each triangle's, rho s^2 / 3. With the corners held it is the only free gridpoint,
    so this is the system's highest (and only) frequency, in x and in y.
    """
    G = E / (2.0 * (1.0 + nu))
    M = constrained_modulus(E=E, nu=nu)
    if not (rho > 0.0 and side > 0.0):
        raise ValueError("rho and side must be positive")
    return math.sqrt(6.0 * (M + G) / rho) / side


def crossed_grid_zone_step(*, E, nu, rho, side):
    """The solver's zone step estimate for a crossed grid of square cells of side s,
    dt_z = 2 min sqrt(m_i / k_i) = s / (4 c_p) (1.3-25 to 1.3-27): each triangle has b_max = s,
    h_min = 2A / b_max = s / 2, so it adds (8/3) M b_max / h_min = 16 M / 3 to the stiffness of
    each of its gridpoints and rho s^2 / 12 to their mass; every gridpoint has m_i / k_i =
    rho s^2 / (64 M), whatever its number of triangles (docs/models/deformable-blocks.md)."""
    return side / (4.0 * constrained_wave_speed(E=E, nu=nu, rho=rho))


def _stiffness_damped_factor(xi):
    # Belytschko's reduction of the critical step for damping ratio xi = beta w / 2.
    return math.sqrt(1.0 + xi * xi) - xi


def crossed_cell_damped_critical_step(*, E, nu, rho, side, beta, fraction=1.0):
    """Critical step of the crossed cell's centre gridpoint under stiffness-proportional damping
    beta: (2 / w)(sqrt(1 + xi^2) - xi), xi = beta w / 2, w = crossed_cell_centre_frequency
    (Belytschko, Liu and Moran, Nonlinear Finite Elements, 6.2, for a viscous stress on the
    strain rate of the half step just ended, as the zones take it); times `fraction`."""
    w = crossed_cell_centre_frequency(E=E, nu=nu, rho=rho, side=side)
    return fraction * 2.0 / w * _stiffness_damped_factor(0.5 * beta * w)


def crossed_grid_solver_step_factor(*, E, nu, rho, side, beta):
    """The factor by which the solver shortens the zone step for stiffness damping on a crossed
    grid of square cells: sqrt(1 + xi^2) - xi with xi = beta w / 2 and w = 2 / dt_z, the bound on
    the zones' highest frequency that the estimate dt_z = crossed_grid_zone_step gives
    (docs/models/deformable-blocks.md); for one cell w is 2 sqrt(2) times the true one when
    nu = 0.25, so the factor is smaller than the mode needs."""
    return _stiffness_damped_factor(beta / crossed_grid_zone_step(E=E, nu=nu, rho=rho, side=side))


def crossed_cell_zone_fraction_at(*, E, nu, rho, side, beta, fraction):
    """The solver.zone_fraction at which the solver's step, zone_fraction dt_z times
    crossed_grid_solver_step_factor, is `fraction` of crossed_cell_damped_critical_step."""
    dt_z = crossed_grid_zone_step(E=E, nu=nu, rho=rho, side=side)
    factor = crossed_grid_solver_step_factor(E=E, nu=nu, rho=rho, side=side, beta=beta)
    critical = crossed_cell_damped_critical_step(E=E, nu=nu, rho=rho, side=side, beta=beta, fraction=fraction)
    return critical / (dt_z * factor)


def rigid_disc_rotation(*, M, E, nu, a):
    """Rotation (radians, counter-clockwise) of a rigid circular disc of radius a bonded in an infinite
    plane-strain elastic plane, under a moment M (N m/m, counter-clockwise). The plane's displacement is
    purely circumferential, u_t = omega a^2 / r (it is harmonic and divergence-free, so it satisfies
    Navier's equations for any nu), with shear stress tau_rt = G (du_t/dr - u_t/r) = -2 G omega a^2 / r^2:
    the disc's edge carries 2 G omega all round it, whose moment is 2 pi a * a * 2 G omega, so

        omega = M / (4 pi G a^2),   G = E / (2 (1 + nu)),

    independent of nu (Muskhelishvili, Some Basic Problems of the Mathematical Theory of Elasticity,
    section 56; Timoshenko & Goodier, ch. 4, "rotating disk" boundary problems)."""
    if a <= 0.0 or E <= 0.0:
        raise ValueError("a and E must be positive")
    G = E / (2.0 * (1.0 + nu))
    return M / (4.0 * math.pi * G * a * a)


def ring_hoop_force(*, p, b):
    """Force (N/m, compression positive for an external pressure p > 0) across any radial section of a
    ring whose outer boundary, a circle or a polygon inscribed in one of radius b, carries a uniform
    external pressure p and whose inner boundary is free: the pressure's resultant on one half,
    p times the chord 2 b between the cut's two outer points, is balanced by the two sections,
    each carrying p b (statics alone, for any material and any inner radius)."""
    return p * b

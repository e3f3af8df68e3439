"""Closed-form references for rigid blocks rocking on a rigid base and toppling about a corner.

Independent of the solver: only math, numpy and scipy are used, and every formula is either taken
from the cited text or derived here from the equations of motion of a rigid body about a fixed
pivot. The time histories (rocking_history, toppling_rotation) integrate those equations with
scipy's DOP853 at relative tolerance 1e-12; that is a numerical solution of the exact equation, not
a closed form, and it is independent of vdec (no contact law, no time-stepping of vdec). The
periods and times are quadratures of the energy integral.

Rocking (Housner 1963). A rigid block of width 2 b and height 2 h (half-dimensions b, h as in
Housner's paper), R = sqrt(b^2 + h^2) the distance from a bottom corner to the centre of mass,
alpha = atan(b / h) the slenderness angle, rocks on a rigid horizontal base about one bottom corner
or the other, without sliding and without bouncing. theta is the block's rotation from upright, of
either sign (the motion is symmetric; counter-clockwise positive, theta > 0 stands the block on its
left corner); the centre of mass is R cos(alpha - |theta|) above the base.
About the corner, with I_O the moment of inertia about it,

    I_O theta'' = -m g R sin(alpha - theta)     (theta > 0; mirror image for theta < 0)

and p = sqrt(m g R / I_O) is the frequency parameter. At theta = 0 the pivot moves to the other
corner; an impact that conserves energy (what an undamped elastic contact model gives) keeps omega
and the motion is symmetric: the period is four times the fall from theta0 to 0.

Toppling. A block of full width w (along the incline) and height h_w (normal to it) on a plane
inclined at beta, rotating down-slope about its lower corner, which is held by friction (friction
angle phi). psi is the tilt from the flat position (psi >= 0, down-slope), delta = atan(w / h_w),
R = sqrt(w^2 + h_w^2) / 2. The centre of mass passes over the pivot when chi = psi + beta - delta
is zero; chi > 0 tips the block down-slope:

    I_O psi'' = m g R sin(chi),    I_O = m (w^2 + h_w^2) / 3.

Sign conventions: the pivot reaction is the force of the incline on the block at the corner,
normal part F_n positive in compression (pushing the block away from the incline), tangential part
F_t positive down-slope. Angles in radians, except parameters whose name ends in _deg (degrees).
SI units throughout; forces per metre of thickness when mass is per metre. Functions whose first
argument is an angle or a time accept numpy arrays and return arrays.

Sources: G. W. Housner, "The behavior of inverted pendulum structures during earthquakes", Bull.
Seism. Soc. Am. 53(2), 403-417, 1963 (frequency parameter, linearised period, restitution of the
plastic impact); N. Makris, "A half-century of rocking isolation", Earthquakes and Structures 7(6),
1187-1221, 2014 (a review restating Housner's results); R. E. Goodman and J. W. Bray, "Toppling of
rock slopes", Proc. ASCE Specialty Conf. on Rock Engineering for Foundations and Slopes, Boulder,
vol. 2, 201-234, 1976 (static sliding and toppling conditions). The exact periods, the pivot
reactions and the friction demand are derived here.
"""
import math

import numpy as np
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq, minimize_scalar

# Relative tolerance of the time histories' integration; the quadratures ask for 1e-13.
_ODE_RTOL = 1e-12


def _deg(x):
    return math.radians(x)


# ---------------------------------------------------------------- the inverted pendulum's fall


def _fall_time(chi0, chi, p):
    """Time for chi'' = p^2 sin chi to go from rest at chi0 (0 < chi0 < pi) to chi >= chi0.

    Energy: chi'^2 = 2 p^2 (cos chi0 - cos chi) = 4 p^2 sin((chi + chi0)/2) sin((chi - chi0)/2), so

        t = integral_{chi0}^{chi} dc / (2 p sqrt(sin((c + chi0)/2) sin((c - chi0)/2))).

    The integrand has an inverse square-root singularity at the turning point c = chi0. With
    c - chi0 = s^2 and x = s^2 / 2 it becomes sqrt(2) / (p sqrt(sin(chi0 + x) sinc(x))), finite
    everywhere; sinc(x) = sin(x) / x is evaluated without the 0/0. As chi0 -> 0 (released near the
    balance point) the time grows like ln(1 / chi0) and the integrand peaks over s < sqrt(2 chi0);
    quad's adaptive bisection resolves that peak down to chi0 ~ 1e-13 without a hint.
    """
    if chi <= chi0:
        return 0.0
    s_end = math.sqrt(chi - chi0)

    def integrand(s):
        x = 0.5 * s * s
        return math.sqrt(2.0) / (p * math.sqrt(math.sin(chi0 + x) * np.sinc(x / math.pi)))

    value, _ = quad(integrand, 0.0, s_end, epsabs=0.0, epsrel=1e-13, limit=200)
    return value


def _speed_from_energy(p, chi0, chi):
    """|chi'| = 2 p sqrt(sin((chi + chi0)/2) sin((chi - chi0)/2)): the product form keeps its
    precision near the turning point, where cos chi0 - cos chi cancels."""
    product = np.sin(0.5 * (chi + chi0)) * np.sin(0.5 * (chi - chi0))
    return 2.0 * p * np.sqrt(np.maximum(product, 0.0))


# ---------------------------------------------------------------- rocking: parameters


def block_radius_and_slenderness(*, b, h):
    """(R, alpha) of a rectangular block of half-width b and half-height h (Housner's notation):
    R = sqrt(b^2 + h^2), the distance from a bottom corner to the centre of mass, and
    alpha = atan(b / h), the angle between R and the vertical when the block stands upright."""
    if not (b > 0.0 and h > 0.0):
        raise ValueError(f"b = {b}, h = {h}: the half-width and half-height must be positive")
    return math.hypot(b, h), math.atan2(b, h)


def rectangle_corner_inertia(*, mass, b, h):
    """Moment of inertia of a rectangle (half-dimensions b, h) about a corner:

        I_O = m ((2b)^2 + (2h)^2) / 12 + m R^2 = (4/3) m R^2    (parallel axes).
    """
    radius, _ = block_radius_and_slenderness(b=b, h=h)
    return 4.0 / 3.0 * mass * radius * radius


def frequency_parameter(*, mass, g, R, inertia_about_corner):
    """Housner's frequency parameter p = sqrt(m g R / I_O), I_O the moment of inertia about the
    pivot corner. For any shape whose centre of mass is R from the corner."""
    if not (mass > 0.0 and g > 0.0 and R > 0.0 and inertia_about_corner > 0.0):
        raise ValueError("mass, g, R and the moment of inertia about the corner must be positive")
    return math.sqrt(mass * g * R / inertia_about_corner)


def rectangle_frequency_parameter(*, g, R):
    """p for a rectangle: I_O = (4/3) m R^2, so p^2 = 3 g / (4 R) (Housner 1963)."""
    if not (g > 0.0 and R > 0.0):
        raise ValueError(f"g = {g}, R = {R}: both must be positive")
    return math.sqrt(3.0 * g / (4.0 * R))


def _check_rocking(theta0, alpha, p):
    if not 0.0 < alpha < 0.5 * math.pi:
        raise ValueError(f"alpha = {alpha} rad: the slenderness angle must lie in (0, pi/2)")
    if not p > 0.0:
        raise ValueError(f"p = {p} 1/s: the frequency parameter must be positive")
    if not 0.0 < abs(theta0) < alpha:
        raise ValueError(f"theta0 = {theta0} rad: free rocking needs 0 < |theta0| < alpha = {alpha} "
                         "(at |theta0| >= alpha the block overturns; at 0 it stands still)")


# ---------------------------------------------------------------- rocking: periods and speed


def housner_period(*, theta0, alpha, p):
    """Housner's free-rocking period (1963), from the equation linearised in alpha:

        T = (4 / p) arccosh(1 / (1 - theta0 / alpha)).

    With sin(alpha - theta) ~ alpha - theta the equation is theta'' = p^2 (theta - alpha), whose
    solution from rest is theta = alpha - (alpha - theta0) cosh(p t); it reaches 0 a quarter period
    later. The linearisation is in the slenderness alpha, not in the amplitude: the formula holds
    for any theta0 < alpha of a slender block. Against the exact period (rocking_period) it is
    short by a relative amount between sqrt(alpha / sin alpha) - 1 ~ alpha^2 / 12 (theta0 -> 0)
    and 0 (theta0 -> alpha). Release from rest, energy-conserving impacts.
    """
    _check_rocking(theta0, alpha, p)
    return 4.0 / p * math.acosh(1.0 / (1.0 - abs(theta0) / alpha))


def rocking_period(*, theta0, alpha, p):
    """Exact period of free rocking with energy-conserving impacts, released from rest at theta0:

        T = 4 integral_0^{theta0} dtheta / |theta'|,
        theta'^2 = 2 p^2 (cos(alpha - theta0) - cos(alpha - theta))     (energy, 0 <= theta <= theta0).

    With phi = alpha - theta this is the fall of an inverted pendulum, phi'' = p^2 sin phi, from
    phi0 = alpha - theta0 to alpha, evaluated by quadrature after a substitution that removes the
    turning point's singularity (see _fall_time). No linearisation: any alpha < pi/2 and
    0 < |theta0| < alpha. (The same fall has the closed form (1/p) F(v | m) with m = cos^2(phi0/2)
    and tan v = sqrt(sin((alpha+phi0)/2) sin((alpha-phi0)/2)) / (sin(phi0/2) cos(alpha/2)), F the
    incomplete elliptic integral of the first kind; the tests use it as an independent check.)
    """
    _check_rocking(theta0, alpha, p)
    return 4.0 * _fall_time(alpha - abs(theta0), alpha, p)


def rectangle_first_impact_time(*, theta0, b, h, g):
    """Time from the release at rest, tilted by theta0 on a bottom corner, to the first impact
    (the face landing, theta = 0) of a rectangular block of half-width b and half-height h:
    a quarter of rocking_period with alpha = atan(b / h) and p^2 = 3 g / (4 R). Measured from
    the release, it needs no assumption about the impact that follows."""
    radius, alpha = block_radius_and_slenderness(b=b, h=h)
    return rocking_period(theta0=theta0, alpha=alpha, p=rectangle_frequency_parameter(g=g, R=radius)) / 4.0


def rocking_angular_velocity(theta, *, theta0, alpha, p):
    """|omega| of free rocking at rotation theta, released from rest at theta0, from energy
    conservation about the pivot corner (elastic impacts, no loss):

        omega^2 = 2 p^2 (cos(alpha - |theta0|) - cos(alpha - |theta|)),    |theta| <= |theta0|.

    Largest at theta = 0: omega_max^2 = 2 p^2 (cos(alpha - theta0) - cos alpha). The same value
    holds on either corner, since I_O and the height of the centre of mass are symmetric.
    """
    _check_rocking(theta0, alpha, p)
    theta = np.abs(np.asarray(theta, dtype=float))
    amplitude = abs(theta0)
    if np.any(theta > amplitude * (1.0 + 1e-12)):
        raise ValueError(f"|theta| beyond the amplitude {amplitude} rad: the block never gets there")
    return _speed_from_energy(p, alpha - amplitude, np.minimum(alpha - theta, alpha))


def housner_restitution(*, alpha, corner_inertia_ratio=4.0 / 3.0):
    """Housner's coefficient of restitution of a perfectly plastic impact, as a ratio of kinetic
    energies after / before the impact at theta = 0:

        r = (omega_after / omega_before)^2 = (1 - 2 sin^2 alpha / kappa)^2,   kappa = I_O / (m R^2),

    from conservation of angular momentum about the corner that strikes (it does not slide or
    bounce): I_O omega_after = I_O omega_before - 2 m R^2 sin^2 alpha omega_before. For a rectangle
    kappa = 4/3 and r = (1 - 1.5 sin^2 alpha)^2 (Housner 1963). For a block symmetric about its
    vertical axis, corners at +-b = +-R sin alpha.

    For reference only: an undamped elastic-contact model (vdec's joints without damping) does not
    dissipate at impact, and its rocking follows r = 1 (rocking_period, rocking_history). r = 0
    at sin^2 alpha = 2 kappa / 4 (alpha = 54.7 deg for a rectangle): a squat block stops dead.
    """
    if not 0.0 < alpha < 0.5 * math.pi:
        raise ValueError(f"alpha = {alpha} rad: the slenderness angle must lie in (0, pi/2)")
    if not corner_inertia_ratio > 0.0:
        raise ValueError(f"corner_inertia_ratio = {corner_inertia_ratio}: I_O / (m R^2) must be positive")
    ratio = 1.0 - 2.0 * math.sin(alpha) ** 2 / corner_inertia_ratio
    return ratio * ratio


# ---------------------------------------------------------------- rocking: time history


def rocking_history(t, *, theta0, alpha, p):
    """(theta(t), omega(t)) of free rocking released from rest at theta0 at t = 0 (component 0:
    rotation in rad, 1: angular velocity in rad/s), energy-conserving impacts.

    Integrates I_O theta'' = -sign(theta) m g R sin(alpha - |theta|), i.e.
    theta'' = -sign(theta) p^2 sin(alpha - |theta|), with DOP853 at relative tolerance 1e-12. At each
    crossing of theta = 0 (located by the integrator's event search) the pivot switches corner
    with omega unchanged, and integration restarts. A numerical solution of the exact equation,
    independent of vdec; its energy (omega^2 / 2 + p^2 cos(alpha - |theta|)) stays within 1e-12
    (relative) of its start over ten periods, and its period is rocking_period to 1e-9.
    """
    _check_rocking(theta0, alpha, p)
    t = np.asarray(t, dtype=float)
    if np.any(~np.isfinite(t)) or np.any(t < 0.0):
        raise ValueError("t must be finite and >= 0: the block is released at t = 0")
    flat = t.ravel()
    theta = np.empty_like(flat)
    omega = np.empty_like(flat)
    at_start = flat == 0.0
    theta[at_start], omega[at_start] = theta0, 0.0
    t_end = float(flat.max()) if flat.size else 0.0
    atol = [1e-14 * alpha, 1e-14 * alpha * p]
    side = math.copysign(1.0, theta0)
    state, t_start = [theta0, 0.0], 0.0
    while t_start < t_end:
        def rhs(_, y, side=side):
            return [y[1], -side * p * p * math.sin(alpha - side * y[0])]

        def reaches_zero(_, y, side=side):
            return side * y[0]
        reaches_zero.terminal, reaches_zero.direction = True, -1.0
        sol = solve_ivp(rhs, (t_start, t_end), state, method="DOP853", rtol=_ODE_RTOL, atol=atol,
                        dense_output=True, events=reaches_zero)
        if sol.status < 0:
            raise RuntimeError(f"rocking_history: integration failed ({sol.message})")
        segment_end = float(sol.t[-1])
        inside = (flat > t_start) & (flat <= segment_end)
        if np.any(inside):
            theta[inside], omega[inside] = sol.sol(flat[inside])
        if sol.status != 1:
            break
        # The pivot moves to the other corner; the block keeps its angular velocity.
        state, t_start, side = [0.0, float(sol.y_events[0][0][1])], segment_end, -side
    return theta.reshape(t.shape), omega.reshape(t.shape)


# ---------------------------------------------------------------- toppling about a corner on an incline


class _Toppling:
    """The geometry of a block pivoting on its down-slope corner and, once released(), its start."""

    def __init__(self, width, height, beta_deg):
        if not (width > 0.0 and height > 0.0):
            raise ValueError(f"width = {width}, height = {height}: both must be positive")
        if not 0.0 <= beta_deg < 90.0:
            raise ValueError(f"beta_deg = {beta_deg}: the incline must lie in [0, 90) degrees")
        self.beta = _deg(beta_deg)
        self.delta = math.atan2(width, height)
        self.R = 0.5 * math.hypot(width, height)
        self.psi0 = 0.0
        self.chi0 = None

    def released(self, psi0, need_motion):
        if not 0.0 <= psi0 < 0.5 * math.pi:
            raise ValueError(f"psi0 = {psi0} rad: the initial tilt must lie in [0, pi/2)")
        self.psi0 = psi0
        self.chi0 = psi0 + self.beta - self.delta
        # A tilt that puts the centre of mass over the pivot to round-off is the balance point.
        if abs(self.chi0) <= 1e-12 * (self.beta + self.delta + psi0):
            self.chi0 = 0.0
        if self.chi0 < 0.0:
            raise ValueError(
                f"psi0 = {psi0} rad: the centre of mass is up-slope of the pivot, so the block falls back "
                f"onto its base and does not topple; toppling from rest needs psi0 >= atan(width / height) "
                f"- beta = {self.delta - self.beta} rad")
        if need_motion and self.chi0 == 0.0:
            raise ValueError(f"psi0 = {psi0} rad puts the centre of mass exactly over the pivot: the block "
                             "balances there and never starts to fall")
        return self

    def chi(self, psi):
        psi = np.asarray(psi, dtype=float)
        if np.any(~((psi >= self.psi0 * (1.0 - 1e-12)) & (psi <= 0.5 * math.pi * (1.0 + 1e-12)))):
            raise ValueError(f"psi outside [psi0, pi/2] = [{self.psi0}, {0.5 * math.pi}] rad: the block starts "
                             "at psi0 and lands on its down-slope face at pi/2")
        return psi + self.beta - self.delta

    def reaction_per_mass_g(self, psi):
        """(F_n, F_t) / (m g) at tilt psi: centre of mass at r = R (-sin(delta - psi), cos(delta - psi))
        from the pivot (x down-slope, y normal to the incline); see toppling_pivot_reaction."""
        chi = self.chi(psi)
        psi = np.asarray(psi, dtype=float)
        # R psi'' / g and R psi'^2 / g for the rectangle, p^2 R = 3 g / 4.
        tangential = 0.75 * np.sin(chi)
        centripetal = 3.0 * np.maximum(np.sin(0.5 * (chi + self.chi0)) * np.sin(0.5 * (chi - self.chi0)), 0.0)
        a = self.delta - psi
        normal = math.cos(self.beta) + tangential * np.sin(a) - centripetal * np.cos(a)
        along = tangential * np.cos(a) + centripetal * np.sin(a) - math.sin(self.beta)
        return normal, along


def toppling_angular_acceleration(psi, *, width, height, beta_deg, g):
    """psi'' = p^2 sin(psi + beta - delta), p^2 = m g R / I_O = 3 g / (4 R), for the block pivoting
    on its down-slope corner (moment of gravity about the fixed pivot; I_O = m (w^2 + h_w^2) / 3)."""
    block = _Toppling(width, height, beta_deg)
    return 0.75 * g / block.R * np.sin(block.chi(psi))


def toppling_angular_velocity(psi, *, width, height, beta_deg, g, psi0=0.0):
    """psi' >= 0 at tilt psi of a block released from rest at psi0, from energy about the pivot:

        psi'^2 = 2 p^2 (cos chi0 - cos chi),   chi = psi + beta - delta,  p^2 = 3 g / (4 R).
    """
    block = _Toppling(width, height, beta_deg).released(psi0, need_motion=False)
    chi = block.chi(psi)
    return _speed_from_energy(math.sqrt(0.75 * g / block.R), block.chi0, chi)


def toppling_pivot_reaction(psi, *, width, height, beta_deg, g, mass, psi0=0.0):
    """(F_n, F_t): the force of the incline on the block at the pivot corner, at tilt psi, for a
    block released from rest at psi0 and pivoting without slip. F_n normal to the incline,
    positive in compression; F_t along it, positive down-slope.

    Rigid body about a fixed point: with x down-slope and y normal to the incline, the centre of
    mass is at r = R (-sin(delta - psi), cos(delta - psi)) from the pivot, so dr/dpsi =
    R (cos(delta - psi), sin(delta - psi)) and d2r/dpsi2 = -r; its acceleration is the tangential
    part psi'' dr/dpsi plus the centripetal part -psi'^2 r. Newton, m a = F + m g with
    g = g (sin beta, -cos beta):

        F_n = m [g cos beta + R psi'' sin(delta - psi) - R psi'^2 cos(delta - psi)]
        F_t = m [R psi'' cos(delta - psi) + R psi'^2 sin(delta - psi) - g sin beta]

    with psi'' and psi'^2 from toppling_angular_acceleration and toppling_angular_velocity
    (R psi'' = (3g/4) sin chi, R psi'^2 = (3g/2)(cos chi0 - cos chi)). Valid while F_n > 0 and
    |F_t| <= F_n tan phi (toppling_liftoff_angle, toppling_slip_angle). At the balance point
    (chi0 = 0, psi = psi0) the block is static: F_n = m g cos beta, F_t = -m g sin beta.
    """
    block = _Toppling(width, height, beta_deg).released(psi0, need_motion=False)
    normal, along = block.reaction_per_mass_g(psi)
    return mass * g * normal, mass * g * along


def toppling_friction_demand(psi, *, width, height, beta_deg, psi0=0.0):
    """|F_t| / F_n at the pivot along the toppling motion from rest at psi0: the friction
    coefficient needed for the corner not to slide. Independent of m and g. Where F_n <= 0 the
    corner lifts off and no friction holds it: the demand is +inf there."""
    block = _Toppling(width, height, beta_deg).released(psi0, need_motion=False)
    normal, along = block.reaction_per_mass_g(psi)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(normal > 0.0, np.abs(along) / np.where(normal > 0.0, normal, 1.0), np.inf)


# Samples of [psi0, psi_end] for the first-crossing searches below; each crossing is then refined
# by brentq, so this sets only the finest feature that can be missed (about 1e-4 rad).
_SCAN_SAMPLES = 16001


def _first_crossing(f, lo, hi):
    """Smallest x in [lo, hi] where f goes from <= 0 to > 0, refined by brentq; inf when f stays <= 0."""
    x = np.linspace(lo, hi, _SCAN_SAMPLES)
    values = f(x)
    above = np.nonzero(values > 0.0)[0]
    if len(above) == 0:
        return math.inf
    i = above[0]
    if i == 0:
        return lo
    return brentq(lambda s: float(f(np.array([s]))[0]), x[i - 1], x[i], xtol=1e-14, rtol=1e-14)


def toppling_liftoff_angle(*, width, height, beta_deg, psi0=0.0):
    """The tilt at which the pivot's normal force F_n first falls to zero, after which the corner
    leaves the incline and the block is no longer pivoting; inf when F_n stays positive up to
    psi = pi/2 (the down-slope face lands). The centripetal term -R psi'^2 cos(delta - psi) grows
    with the fall: a finite block released near its balance point lifts off before it lands (a
    zero-width rod on a flat base only touches F_n = 0, at cos psi = 1/3)."""
    block = _Toppling(width, height, beta_deg).released(psi0, need_motion=False)
    return _first_crossing(lambda s: -block.reaction_per_mass_g(s)[0], psi0, 0.5 * math.pi)


def toppling_slip_angle(*, width, height, beta_deg, phi_deg, psi0=0.0, psi_end=0.5 * math.pi):
    """The first tilt in [psi0, psi_end] at which the pivot needs more friction than it has,
    |F_t| > F_n tan phi (which includes F_n <= 0, lift-off); inf when friction holds the corner
    over the whole range. Up to this angle the motion is toppling without slip."""
    block = _Toppling(width, height, beta_deg).released(psi0, need_motion=False)
    _check_end(psi0, psi_end)
    mu = math.tan(_deg(phi_deg))

    def excess(s):
        normal, along = block.reaction_per_mass_g(s)
        return np.abs(along) - mu * normal
    return _first_crossing(excess, psi0, psi_end)


def _check_end(psi0, psi_end):
    if not psi0 <= psi_end <= 0.5 * math.pi:
        raise ValueError(f"psi_end = {psi_end} rad: it must lie in [psi0, pi/2] = [{psi0}, {0.5 * math.pi}]")


def toppling_largest_friction_demand(*, width, height, beta_deg, psi0=0.0, psi_end=0.5 * math.pi):
    """(largest |F_t| / F_n over [psi0, psi_end], the tilt where it occurs); (inf, lift-off tilt)
    when F_n falls to zero within the range. The maximum is found on 16001 samples and refined by
    a bounded scalar search between the neighbours of the largest sample."""
    block = _Toppling(width, height, beta_deg).released(psi0, need_motion=False)
    _check_end(psi0, psi_end)
    liftoff = toppling_liftoff_angle(width=width, height=height, beta_deg=beta_deg, psi0=psi0)
    if liftoff <= psi_end:
        return math.inf, liftoff

    def demand(s):
        normal, along = block.reaction_per_mass_g(s)
        return np.abs(along) / normal
    if psi_end == psi0:
        return float(demand(np.array([psi0]))[0]), psi0
    x = np.linspace(psi0, psi_end, _SCAN_SAMPLES)
    values = demand(x)
    i = int(np.argmax(values))
    lo, hi = x[max(i - 1, 0)], x[min(i + 1, len(x) - 1)]
    best = minimize_scalar(lambda s: -float(demand(np.array([s]))[0]), bounds=(lo, hi), method="bounded",
                           options={"xatol": 1e-13})
    if -best.fun > values[i]:
        return float(-best.fun), float(best.x)
    return float(values[i]), float(x[i])


def topples_without_slip(*, width, height, beta_deg, phi_deg, psi0=0.0, psi_end=0.5 * math.pi):
    """True when friction holds the pivot from psi0 to psi_end: the largest friction demand
    |F_t| / F_n over the range is at most tan phi (equality counts as holding) and F_n stays
    positive. The static sliding test tan beta > tan phi (static_slides) does not apply to a
    pivoting block: its corner carries neither m g cos beta nor m g sin beta."""
    demand, _ = toppling_largest_friction_demand(width=width, height=height, beta_deg=beta_deg, psi0=psi0,
                                                 psi_end=psi_end)
    return demand <= math.tan(_deg(phi_deg))


def toppling_time(psi, *, width, height, beta_deg, g, psi0=0.0):
    """Time for the block released from rest at psi0 to reach tilt psi (psi0 <= psi <= pi/2),
    pivoting without slip: the fall of the inverted pendulum chi'' = p^2 sin chi from chi0 to chi,
    by quadrature of the energy integral (see rocking_period). Needs chi0 > 0: a block balanced on
    its corner never starts. Scalar or array psi; each value is one quadrature."""
    block = _Toppling(width, height, beta_deg).released(psi0, need_motion=True)
    chi = block.chi(psi)
    p = math.sqrt(0.75 * g / block.R)
    times = [_fall_time(block.chi0, max(float(c), block.chi0), p) for c in np.ravel(chi)]
    return np.reshape(times, np.shape(chi)) if np.ndim(chi) else times[0]


def toppling_rotation(t, *, width, height, beta_deg, g, psi0=0.0):
    """(psi(t), psi'(t)) of the block released from rest at psi0 at t = 0, pivoting on its
    down-slope corner without slip (component 0: tilt in rad, 1: angular velocity in rad/s).

    Integrates psi'' = (3 g / (4 R)) sin(psi + beta - delta) with DOP853 at relative tolerance
    1e-12 (a numerical solution of the exact equation, independent of vdec). Up to the landing of
    the down-slope face (psi = pi/2, reached at toppling_time(pi/2)); a later t is an error. The
    pivot holds only up to toppling_liftoff_angle and toppling_slip_angle: compare a solver's
    rotation with this only over times before those tilts.
    """
    block = _Toppling(width, height, beta_deg).released(psi0, need_motion=True)
    t = np.asarray(t, dtype=float)
    if np.any(~np.isfinite(t)) or np.any(t < 0.0):
        raise ValueError("t must be finite and >= 0: the block is released at t = 0")
    landing = toppling_time(0.5 * math.pi, width=width, height=height, beta_deg=beta_deg, g=g, psi0=psi0)
    t_end = float(t.max()) if t.size else 0.0
    if t_end > landing:
        raise ValueError(f"t = {t_end} s is after the landing at {landing} s (psi = pi/2): the block no "
                         "longer pivots on one corner")
    p2 = 0.75 * g / block.R
    shift = block.beta - block.delta
    if t_end == 0.0:
        return np.full(t.shape, psi0), np.zeros(t.shape)
    sol = solve_ivp(lambda _, y: [y[1], p2 * math.sin(y[0] + shift)], (0.0, t_end), [psi0, 0.0], method="DOP853",
                    rtol=_ODE_RTOL, atol=[1e-14, 1e-14 * math.sqrt(p2)], dense_output=True)
    if sol.status < 0:
        raise RuntimeError(f"toppling_rotation: integration failed ({sol.message})")
    psi, rate = sol.sol(t.ravel())
    return psi.reshape(t.shape), rate.reshape(t.shape)


# ---------------------------------------------------------------- static conditions on an incline


def static_slides(*, beta_deg, phi_deg):
    """A block resting on its base on a plane inclined at beta slides when tan beta > tan phi
    (Goodman and Bray 1976; equality is limiting equilibrium and counts as holding)."""
    return math.tan(_deg(beta_deg)) > math.tan(_deg(phi_deg))


def static_topples(*, width, height, beta_deg):
    """A block resting on its base topples when its weight acts outside the base: width / height
    < tan beta (Goodman and Bray 1976; equality puts the weight through the corner and counts as
    standing)."""
    if not (width > 0.0 and height > 0.0):
        raise ValueError(f"width = {width}, height = {height}: both must be positive")
    return width / height < math.tan(_deg(beta_deg))


def static_mode(*, width, height, beta_deg, phi_deg):
    """Goodman and Bray's (1976) classification of a block resting on an incline: "stable",
    "slides", "topples" or "slides and topples", from static_slides and static_topples.

    These are conditions for the block at rest on its full base. Once it pivots, the corner's
    reaction is set by the motion (toppling_pivot_reaction): a block in the "slides and topples"
    region can topple without slip (topples_without_slip), e.g. w / h_w = 0.25 at beta = 40 deg,
    phi = 30 deg needs a friction coefficient of only 0.383 at the start of its fall.
    """
    slides = static_slides(beta_deg=beta_deg, phi_deg=phi_deg)
    topples = static_topples(width=width, height=height, beta_deg=beta_deg)
    if slides and topples:
        return "slides and topples"
    if slides:
        return "slides"
    if topples:
        return "topples"
    return "stable"

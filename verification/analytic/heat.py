"""Closed-form references for heat conduction and one-way thermal stress (issue 17, "Verification").

Independent of the solver: only math, numpy and scipy are used, and every formula is either taken from
the cited text or derived here in a few lines. Where no closed form exists (a decaying source) the
convolution of the instantaneous source with the power is evaluated by adaptive quadrature after a
change of variable that leaves a smooth integrand.

Model (NUREG/CR-5429 1.4.3, 1.4-13 to 1.4-17): conduction only, q = -k grad T, rho c dT/dt = -div q,
constant properties, diffusivity kappa = k / (rho c). Thermal stress is one-way: a temperature change dT
adds the isotropic free strain alpha dT (volumetric beta = 3 alpha, 1.4-17) and nothing flows back.

Sign conventions: TEMPERATURE RISE POSITIVE; heat flux positive in the direction each function names
(into the solid at a surface, outward along +r from a line source or the axis of a cylinder); stresses and
strains TENSION (extension) POSITIVE; joint normal stress and Coulomb strength as noted at the jointed block.
SI units throughout: m, s, K, W, J, Pa; k in W/(m K), kappa in m^2/s, h in W/(m^2 K), rho c in
J/(m^3 K), alpha in 1/K; a line source q in W per metre of line, a plane source or surface flux in W/m^2.
Every function takes keyword arguments only (but the special functions ierfc(z) and ierfcx(z), like
scipy's); field functions accept numpy arrays (broadcast together) and return arrays. Nonsensical input (a negative depth, t <= 0, k <= 0, nu outside (-1, 1/2), ...) is
a ValueError naming the argument.

Sources: H. S. Carslaw and J. C. Jaeger, Conduction of Heat in Solids, 2nd ed., Oxford, 1959 (cited
"C&J" with the section of the 2nd edition; equation numbers inside a section are not quoted, and the
section numbers 2.2, 2.9, 10.3 and 10.4 are not checked against the book: each formula is verified
independently in tests/python/test_analytic_heat.py instead); S. P. Timoshenko and J. N. Goodier,
Theory of Elasticity, 3rd ed., 1970, ch. 13 "Thermal stress" ("T&G"; the article number differs between
editions); M. Abramowitz and I. A. Stegun, Handbook of Mathematical Functions, 1964 ("A&S").
Special functions: scipy.special erfc, erfcx (erfcx(z) = exp(z^2) erfc(z)) and exp1 (E1).
"""
import math

import numpy as np
from scipy import integrate, optimize, special


def _arr(x):
    return np.asarray(x, dtype=float)


def _positive(name, value):
    value = _arr(value)
    if np.any(~(value > 0.0)):
        raise ValueError(f"{name} = {value}: must be positive")
    return value


def _non_negative(name, value):
    value = _arr(value)
    if np.any(~(value >= 0.0)):
        raise ValueError(f"{name} = {value}: must be zero or positive")
    return value


def _check_young_poisson(E, nu):
    E, nu = _positive("E (Young's modulus)", E), _arr(nu)
    if np.any(~((nu > -1.0) & (nu < 0.5))):
        raise ValueError(f"nu = {nu}: Poisson's ratio must lie in (-1, 1/2) for a stable isotropic solid")
    return E, nu


def _similarity_variable(x, t, kappa):
    """z = x / (2 sqrt(kappa t)) after the checks every semi-infinite solution needs."""
    x = _non_negative("x (depth below the surface)", x)
    t = _positive("t", t)
    kappa = _positive("kappa", kappa)
    return x / (2.0 * np.sqrt(kappa * t))


# ---------------------------------------------------------------- the integrated complementary error function

# Above this argument ierfcx is taken from the continued fraction (below): the direct form
# 1/sqrt(pi) - z erfcx(z) loses about log10(2 z^2) digits to cancellation, 0.9 at z = 2.
_IERFC_SWITCH = 2.0
_IERFC_FRACTION_TERMS = 160


def ierfcx(z):
    """The scaled integrated complementary error function ierfcx(z) = exp(z^2) ierfc(z), finite where
    ierfc underflows (z > 26), as erfcx is to erfc:

        ierfcx(z) = 1/sqrt(pi) - z erfcx(z),     erfcx(z) = exp(z^2) erfc(z).

    That difference loses about log10(2 z^2) digits to cancellation (ierfcx ~ 1 / (2 sqrt(pi) z^2) for
    large z), so above z = 2 it comes from Laplace's continued fraction
    erfcx(z) = (1/sqrt(pi)) / (z + a), a = (1/2)/(z + 1/(z + (3/2)/(z + 2/(z + ...)))) (A&S 7.1.14):
    then ierfcx = (1/sqrt(pi)) a / (z + a), with no subtraction. 160 terms, evaluated from the tail,
    reach round-off for z >= 2 (the fraction converges faster the larger z is). Any real z; for z < 0
    the direct form has no cancellation (and overflows with erfcx below z = -26).
    """
    z = _arr(z)
    direct = 1.0 / math.sqrt(math.pi) - z * special.erfcx(np.minimum(z, _IERFC_SWITCH))
    large = np.maximum(z, _IERFC_SWITCH)
    tail = np.zeros_like(large)
    for n in range(_IERFC_FRACTION_TERMS, 0, -1):
        tail = (0.5 * n) / (large + tail)
    fraction = tail / (math.sqrt(math.pi) * (large + tail))
    return np.where(z > _IERFC_SWITCH, fraction, direct)


def ierfc(z):
    """The integrated complementary error function

        ierfc(z) = integral from z to infinity of erfc(s) ds = exp(-z^2) / sqrt(pi) - z erfc(z)

    (C&J, Appendix II, the repeated integrals i^n erfc; ierfc(0) = 1 / sqrt(pi), d ierfc / dz = -erfc),
    computed as exp(-z^2) ierfcx(z) so that it keeps its relative accuracy for large z until it
    underflows to 0 (z > 26). Any real z.
    """
    z = _arr(z)
    with np.errstate(over="ignore"):   # z^2 beyond the float range: exp(-inf) = 0 is the answer
        return np.exp(-z * z) * ierfcx(z)


# ---------------------------------------------------------------- semi-infinite solid x >= 0, initially at T0


def semi_infinite_step_temperature(*, x, t, T0, Ts, kappa):
    """Temperature at depth x >= 0 of a semi-infinite solid initially at T0 whose surface x = 0 is held at
    Ts from t = 0:

        T = T0 + (Ts - T0) erfc(x / (2 sqrt(kappa t)))

    (C&J, sec. 2.5, surface temperature phi(t) with phi = Ts constant). t > 0.
    """
    z = _similarity_variable(x, t, kappa)
    return T0 + (Ts - T0) * special.erfc(z)


def semi_infinite_step_heat_flux(*, x, t, T0, Ts, k, kappa):
    """Heat flux in +x (into the solid) at depth x of semi_infinite_step_temperature, -k dT/dx:

        q = k (Ts - T0) / sqrt(pi kappa t) exp(-x^2 / (4 kappa t)),

    at the surface x = 0 q = k (Ts - T0) / sqrt(pi kappa t) (d erfc(z)/dz = -2 exp(-z^2) / sqrt(pi),
    dz/dx = 1 / (2 sqrt(kappa t)); C&J sec. 2.5). Positive when the surface is hotter than the solid.
    """
    z = _similarity_variable(x, t, kappa)
    k = _positive("k", k)
    return k * (Ts - T0) / np.sqrt(math.pi * _arr(kappa) * _arr(t)) * np.exp(-z * z)


def semi_infinite_step_heat_flow(*, x, t, T0, Ts, k, kappa, height):
    """Heat flow (W per metre of thickness) in +x through a section x = const of the given height of
    semi_infinite_step_temperature: the flux, uniform over the section, times its height."""
    return semi_infinite_step_heat_flux(x=x, t=t, T0=T0, Ts=Ts, k=k, kappa=kappa) * _positive("height", height)


def semi_infinite_constant_flux_temperature(*, x, t, T0, q0, k, kappa):
    """Temperature at depth x >= 0 of a semi-infinite solid initially at T0 into whose surface a constant
    heat flux q0 (W/m^2, positive into the solid) enters from t = 0:

        T = T0 + (2 q0 / k) sqrt(kappa t) ierfc(x / (2 sqrt(kappa t))),

    the surface temperature rising as T(0, t) - T0 = (2 q0 / k) sqrt(kappa t / pi) (C&J, sec. 2.9,
    constant flux F0 at the surface; ierfc as above). t > 0.
    """
    z = _similarity_variable(x, t, kappa)
    k = _positive("k", k)
    return T0 + 2.0 * q0 / k * np.sqrt(_arr(kappa) * _arr(t)) * ierfc(z)


def semi_infinite_constant_flux_heat_flux(*, x, t, q0, kappa):
    """Heat flux in +x at depth x of semi_infinite_constant_flux_temperature: q = q0 erfc(x / (2 sqrt(kappa t)))
    (-k dT/dx with d ierfc / dz = -erfc; C&J sec. 2.9). Equal to q0 at the surface."""
    z = _similarity_variable(x, t, kappa)
    return q0 * special.erfc(z)


def semi_infinite_convective_temperature(*, x, t, T0, T_inf, h, k, kappa):
    """Temperature at depth x >= 0 of a semi-infinite solid initially at T0 whose surface exchanges heat
    from t = 0 with a medium at T_inf through a heat-transfer coefficient h (-k dT/dx = h (T_inf - T) at
    x = 0, flux into the solid positive):

        (T - T0) / (T_inf - T0) = erfc(z) - exp(H x + H^2 kappa t) erfc(z + H sqrt(kappa t)),

    z = x / (2 sqrt(kappa t)), H = h / k (C&J, sec. 2.7, heat transfer at the surface to a medium at
    constant temperature). With beta = H sqrt(kappa t) and erfc(w) = exp(-w^2) erfcx(w) the exponents
    combine, H x + beta^2 - (z + beta)^2 = -z^2 (as H x = 2 z beta), so

        (T - T0) / (T_inf - T0) = erfc(z) - exp(-z^2) erfcx(z + beta),

    which stays finite for every x, t and h. h -> infinity gives semi_infinite_step_temperature with
    Ts = T_inf; h = 0 an adiabatic surface (T = T0). t > 0, h >= 0.
    """
    z = _similarity_variable(x, t, kappa)
    h = _non_negative("h", h)
    k = _positive("k", k)
    beta = h / k * np.sqrt(_arr(kappa) * _arr(t))
    return T0 + (T_inf - T0) * (special.erfc(z) - np.exp(-z * z) * special.erfcx(z + beta))


def semi_infinite_convective_surface_heat_flux(*, t, T0, T_inf, h, k, kappa):
    """Heat flux into the surface of semi_infinite_convective_temperature: q = h (T_inf - T(0, t))
    = h (T_inf - T0) erfcx(h sqrt(kappa t) / k) (the boundary condition with T(0, t) from the closed form,
    as T(0, t) - T0 = (T_inf - T0)(1 - erfcx(beta))). Falls from h (T_inf - T0) at t = 0 towards
    k (T_inf - T0) / sqrt(pi kappa t) at long times (erfcx(beta) ~ 1 / (beta sqrt(pi)))."""
    t, kappa = _positive("t", t), _positive("kappa", kappa)
    h = _non_negative("h", h)
    k = _positive("k", k)
    return h * (T_inf - T0) * special.erfcx(h / k * np.sqrt(kappa * t))


# ---------------------------------------------------------------- line and plane sources in an infinite medium


def line_source_temperature(*, r, t, q, k, kappa, T0=0.0):
    """Temperature at distance r > 0 from a line source emitting q W per metre of line from t = 0 in an
    infinite medium initially at T0:

        T = T0 + q / (4 pi k) E1(r^2 / (4 kappa t))

    (C&J, sec. 10.4, the continuous line source, written there -Ei(-r^2 / 4 kappa t) = E1). The time integral
    of the instantaneous line source (C&J sec. 10.3), Q' / (4 pi k s) exp(-r^2 / (4 kappa s)) for Q' J/m
    released s seconds earlier. t > 0, r > 0 (the source itself is singular).
    """
    r = _positive("r", r)
    t = _positive("t", t)
    k, kappa = _positive("k", k), _positive("kappa", kappa)
    return T0 + q / (4.0 * math.pi * k) * special.exp1(r * r / (4.0 * kappa * t))


def line_source_radial_heat_flux(*, r, t, q, kappa):
    """Heat flux outward (+r) at distance r from the line source of line_source_temperature:

        q_r = -k dT/dr = q / (2 pi r) exp(-r^2 / (4 kappa t))

    (dE1(u)/du = -exp(-u)/u). 2 pi r q_r -> q as t -> infinity: the source's power crosses every circle."""
    r = _positive("r", r)
    t = _positive("t", t)
    kappa = _positive("kappa", kappa)
    return q / (2.0 * math.pi * r) * np.exp(-r * r / (4.0 * kappa * t))


def _decaying_terms(q, tau):
    """The source's terms as float arrays: q_i (any sign) and time constants tau_i > 0 (inf = constant)."""
    q = np.atleast_1d(_arr(q))
    tau = np.atleast_1d(_arr(tau))
    if q.ndim != 1 or q.shape != tau.shape:
        raise ValueError(f"q {q.shape} and tau {tau.shape}: give one time constant per term")
    if np.any(~(tau > 0.0)):
        raise ValueError(f"tau = {tau}: time constants must be positive (numpy.inf for a constant term)")
    return q, tau


def decaying_source_power(*, t, q, tau):
    """The power q(t) = sum_i q_i exp(-t / tau_i) of the decaying sources below, at times t >= 0.
    tau_i are time constants in seconds (e-folding times, decay constant 1 / tau_i; a half-life
    t_1/2 is tau = t_1/2 / ln 2); tau_i = numpy.inf is a constant term."""
    q, tau = _decaying_terms(q, tau)
    t = _non_negative("t", t)
    return np.sum(q * np.exp(-t[..., None] / tau), axis=-1)


def _quad(integrand, lower, upper, points):
    """Adaptive Gauss-Kronrod to 1e-12 relative (epsabs 0: the caller scales the integrand to O(1))."""
    inside = sorted(p for p in points if lower < p < upper)
    value, _ = integrate.quad(integrand, lower, upper, points=inside or None, epsabs=0.0, epsrel=1e-12,
                              limit=500)
    return value


def _rise_at_each_point(rise_at, distance, t, q, tau, k, kappa):
    """rise_at(distance, t, q, tau, k, kappa) at every point of distance and t broadcast together:
    one quadrature a point."""
    q, tau = _decaying_terms(q, tau)
    t = _positive("t", t)
    k, kappa = float(_positive("k", k)), float(_positive("kappa", kappa))
    distance, t = np.broadcast_arrays(distance, t)
    rise = np.empty(distance.shape)
    for index in np.ndindex(distance.shape):
        rise[index] = rise_at(float(distance[index]), float(t[index]), q, tau, k, kappa)
    return rise


def _decay_release_times(t, tau):
    """Release times t' = tau_i 4^j < t, where term i has fallen by exp(-4^j): breakpoints for the
    quadrature. A term that decays fast compared with t is a narrow peak at the start of the history,
    which a Gauss-Kronrod rule spread over the whole range would step over without noticing."""
    times = []
    for tau_i in tau:
        release = tau_i
        while release < t and len(times) < 400:
            times.append(release)
            release *= 4.0
    return times


def _decaying_line_source_rise(r, t, q, tau, k, kappa):
    """Temperature rise at one (r, t) of decaying_line_source_temperature."""
    u0 = r * r / (4.0 * kappa * t)
    # omega = w - ln u0 = ln(u / u0): the release time t' = t (1 - exp(-omega)) and the weight
    # exp(-(u - u0)) come from expm1 without cancellation even where t' << t (a fast-decaying term),
    # and the factor exp(-u0) is taken out
    upper = math.log1p(60.0 / u0)   # exp(-60) ~ 1e-26 of the weight at omega = 0
    points = [-math.log1p(-release / t) for release in _decay_release_times(t, tau)]

    def integrand(omega):
        release = -t * math.expm1(-omega)
        power = 0.0
        for q_i, tau_i in zip(q, tau):
            power += q_i * math.exp(-release / tau_i)
        return power * math.exp(-u0 * math.expm1(omega))

    return math.exp(-u0) * _quad(integrand, 0.0, upper, points) / (4.0 * math.pi * k)


def decaying_line_source_temperature(*, r, t, q, tau, k, kappa, T0=0.0):
    """Temperature at distance r > 0 from a line source of power q(t') = sum_i q_i exp(-t' / tau_i) W/m
    (decaying_source_power; tau_i time constants, numpy.inf a constant term) switched on at t' = 0 in an
    infinite medium initially at T0. Superposing the instantaneous line source (C&J sec. 10.3) over the
    source's history (Duhamel; C&J sec. 10.4, the continuous source of variable strength):

        T - T0 = (1 / (4 pi k)) integral from 0 to t of q(t') exp(-r^2 / (4 kappa (t - t'))) / (t - t') dt'.

    The kernel is flat near t' = t but has a 1/(t - t') tail over the rest of the history. With
    u = r^2 / (4 kappa (t - t')) (dt' / (t - t') = du / u) and then w = ln u:

        T - T0 = (1 / (4 pi k)) integral from ln u0 to infinity of q(t - r^2 e^-w / (4 kappa)) exp(-e^w) dw,

    u0 = r^2 / (4 kappa t): a smooth, bounded integrand, falling double-exponentially above w = ln u0 + 4.
    For a constant q it is q E1(u0) / (4 pi k) (line_source_temperature). Integrated by scipy quad to
    1e-12 relative in omega = w - ln u0 (t' = -t expm1(-omega), no cancellation for t' << t), the factor
    exp(-u0) taken out (remote points keep their relative accuracy until it underflows), with the times
    where a term has fallen by exp(-4^j) as breakpoints. Good to 1e-9 relative (tested against an
    exact series of E_n, a second quadrature and, for t / tau up to 3e9, the instantaneous-source limit,
    in tests/python/test_analytic_heat.py).
    r, t: arrays (broadcast); q, tau: sequences of equal length. r > 0, t > 0.
    """
    return T0 + _rise_at_each_point(_decaying_line_source_rise, _positive("r", r), t, q, tau, k, kappa)


def _decaying_plane_source_rise(x, t, q, tau, k, kappa):
    """Temperature rise at one (x, t) of decaying_plane_source_temperature."""
    c = x * x / (4.0 * kappa)
    root_t = math.sqrt(t)
    # epsilon = sqrt(t) - v: the release time t' = t - v^2 = epsilon (2 sqrt(t) - epsilon) without
    # cancellation where t' << t; weight exp(-c (1/v^2 - 1/t)) = exp(-c t' / (v^2 t)), the factor
    # exp(-c / t) taken out
    points = [release / (root_t + math.sqrt(t - release)) for release in _decay_release_times(t, tau)]

    def integrand(epsilon):
        release = epsilon * (2.0 * root_t - epsilon)
        v = root_t - epsilon
        if v <= 0.0:
            return 0.0 if c > 0.0 else sum(q_i * math.exp(-t / tau_i) for q_i, tau_i in zip(q, tau))
        power = 0.0
        for q_i, tau_i in zip(q, tau):
            power += q_i * math.exp(-release / tau_i)
        return power * math.exp(-c * release / (v * v * t))

    return math.exp(-c / t) * math.sqrt(kappa / math.pi) / k * _quad(integrand, 0.0, root_t, points)


def decaying_plane_source_temperature(*, x, t, q, tau, k, kappa, T0=0.0):
    """Temperature at distance x from a plane source of power q(t') = sum_i q_i exp(-t' / tau_i) W/m^2
    (decaying_source_power) switched on at t' = 0 in an infinite medium initially at T0: the 1D analogue
    of decaying_line_source_temperature. Superposing the instantaneous plane source Q' / (rho c) /
    (2 sqrt(pi kappa s)) exp(-x^2 / (4 kappa s)) (C&J sec. 2.2) over the history, with s = t - t' = v^2
    (ds / (2 sqrt(s)) = dv, which removes the 1/sqrt(s) singularity at x = 0):

        T - T0 = (1 / k) sqrt(kappa / pi) integral from 0 to sqrt(t) of q(t - v^2) exp(-x^2 / (4 kappa v^2)) dv.

    A constant q gives (q / k) sqrt(kappa t) ierfc(|x| / (2 sqrt(kappa t))): half the power goes each way,
    semi_infinite_constant_flux_temperature with q0 = q / 2; likewise a decaying flux q0(t) into a half-space
    is this with q = 2 q0. At x = 0 one term has the closed form (q / k) sqrt(kappa tau / pi) D(sqrt(t / tau)),
    D Dawson's integral. Integrated by scipy quad to 1e-12 relative in epsilon = sqrt(t) - v
    (t' = epsilon (2 sqrt(t) - epsilon), no cancellation for t' << t) with the same breakpoints as the
    line source; good to 1e-9 relative. x any real (the medium is symmetric), t > 0.
    """
    return T0 + _rise_at_each_point(_decaying_plane_source_rise, np.abs(_arr(x)), t, q, tau, k, kappa)


# ---------------------------------------------------------------- hollow cylinder a <= r <= b


def _check_wall(r, a, b):
    r = _arr(r)
    if not 0.0 < a < b < math.inf:
        raise ValueError(f"a = {a}, b = {b}: need 0 < a < b < infinity")
    if np.any(r < a * (1.0 - 1e-12)) or np.any(r > b * (1.0 + 1e-12)):
        raise ValueError(f"r lies outside the wall a = {a} <= r <= b = {b}")
    return r


def hollow_cylinder_steady_temperature(*, r, a, b, Ta, Tb):
    """Steady temperature in the wall a <= r <= b of a long hollow cylinder held at Ta on r = a and Tb on
    r = b (no source): T = Ta + (Tb - Ta) ln(r / a) / ln(b / a), the radial solution of
    (1/r) d/dr (r dT/dr) = 0 (C&J ch. VII, the hollow cylinder; T&G ch. 13, the long circular cylinder)."""
    r = _check_wall(r, a, b)
    return Ta + (Tb - Ta) * np.log(r / a) / math.log(b / a)


def hollow_cylinder_heat_flow(*, a, b, Ta, Tb, k):
    """Steady heat flow outward through the wall of hollow_cylinder_steady_temperature per metre of
    length: Q = 2 pi k (Ta - Tb) / ln(b / a) (W/m), the same through every circle a <= r <= b."""
    _check_wall(a, a, b)
    return 2.0 * math.pi * float(_positive("k", k)) * (Ta - Tb) / math.log(b / a)


def _hollow_cylinder_moment(r, a, b, Ta, Tb, T_ref):
    """I(r) = integral from a to r of (T(s) - T_ref) s ds for the log profile, in closed form:
    (Ta - T_ref)(r^2 - a^2)/2 + D (r^2 ln(r/a) / 2 - (r^2 - a^2) / 4), D = (Tb - Ta) / ln(b/a)
    (integral of s ln(s/a) ds = s^2 ln(s/a) / 2 - s^2 / 4)."""
    slope = (Tb - Ta) / math.log(b / a)
    return (Ta - T_ref) * (r * r - a * a) / 2.0 + slope * (r * r * np.log(r / a) / 2.0 - (r * r - a * a) / 4.0)


def hollow_cylinder_thermal_stress(*, r, a, b, Ta, Tb, T_ref, E, nu, alpha, axial="plane_strain"):
    """Thermoelastic stresses and radial displacement in the wall a <= r <= b of a long hollow cylinder
    with the steady temperature of hollow_cylinder_steady_temperature, stress-free at the uniform
    temperature T_ref, both surfaces traction-free (sigma_rr = 0 at a and b). Tension positive.
    With dT(r) = T(r) - T_ref and I(r) = integral from a to r of dT(s) s ds (closed form for the
    log profile, _hollow_cylinder_moment):

        sigma_rr = alpha E / ((1 - nu) r^2) ( (r^2 - a^2) / (b^2 - a^2) I(b) - I(r) ),
        sigma_tt = alpha E / ((1 - nu) r^2) ( (r^2 + a^2) / (b^2 - a^2) I(b) + I(r) - dT r^2 ),
        u_r      = (1 + nu) alpha / ((1 - nu) r) ( I(r) + ((1 - 2 nu) r^2 + a^2) / (b^2 - a^2) I(b) )
                   - nu e_zz r,

    (T&G ch. 13, the long circular cylinder, for any radial temperature dT(r)). axial chooses the
    condition along the axis:

        "plane_strain": e_zz = 0, sigma_zz = nu (sigma_rr + sigma_tt) - E alpha dT
                        = alpha E / (1 - nu) (2 nu I(b) / (b^2 - a^2) - dT);
        "generalized":  free ends far from them (Saint-Venant): e_zz uniform with zero axial force,
                        e_zz = alpha 2 I(b) / (b^2 - a^2) (alpha times the mean dT over the section),
                        sigma_zz = alpha E / (1 - nu) (2 I(b) / (b^2 - a^2) - dT); sigma_rr and sigma_tt
                        are the same as in plane strain (the added uniform axial stress E e_zz changes
                        only u_r, by -nu e_zz r).

    A uniform dT (Ta = Tb) gives sigma_rr = sigma_tt = 0, u_r = (1 + nu) alpha dT r in plane strain.
    Returns a dict of arrays: 'srr', 'stt', 'szz', 'ur', 'ezz', 'dT'.
    """
    r = _check_wall(r, a, b)
    E, nu = _check_young_poisson(E, nu)
    if axial not in ("plane_strain", "generalized"):
        raise ValueError(f"axial = {axial!r}: choose 'plane_strain' (e_zz = 0) or 'generalized' (free ends)")
    dT = hollow_cylinder_steady_temperature(r=r, a=a, b=b, Ta=Ta, Tb=Tb) - T_ref
    moment = _hollow_cylinder_moment(r, a, b, Ta, Tb, T_ref)
    moment_b = float(_hollow_cylinder_moment(np.float64(b), a, b, Ta, Tb, T_ref))
    span = b * b - a * a
    c = alpha * E / (1.0 - nu)
    srr = c / (r * r) * ((r * r - a * a) / span * moment_b - moment)
    stt = c / (r * r) * ((r * r + a * a) / span * moment_b + moment - dT * r * r)
    ur = (1.0 + nu) * alpha / ((1.0 - nu) * r) * (moment + ((1.0 - 2.0 * nu) * r * r + a * a) / span * moment_b)
    if axial == "plane_strain":
        ezz = np.zeros_like(r)
        szz = c * (2.0 * nu * moment_b / span - dT)
    else:
        ezz = np.full_like(r, alpha * 2.0 * moment_b / span)
        szz = c * (2.0 * moment_b / span - dT)
        ur = ur - nu * ezz * r
    return {"srr": srr, "stt": stt, "szz": szz, "ur": ur, "ezz": ezz, "dT": dT}


# ---------------------------------------------------------------- uniformly heated blocks, plane strain


def block_uniform_heating(*, dT, E, nu, alpha, held):
    """Stresses and in-plane strains of a homogeneous block heated uniformly by dT (cooling dT < 0) in
    plane strain (e_zz = 0), tension positive, stress-free before. held names the in-plane directions
    held rigidly (zero strain, frictionless) while the others are free (zero stress):

        "xy":   e_xx = e_yy = 0:       sigma_xx = sigma_yy = sigma_zz = -E alpha dT / (1 - 2 nu)
                                       (= -K beta dT, beta = 3 alpha: 1.4-17 of the reference);
        "x":    e_xx = 0, sigma_yy = 0: sigma_xx = sigma_zz = -E alpha dT / (1 - nu),
                                       e_yy = (1 + nu) alpha dT / (1 - nu);
        "none": sigma_xx = sigma_yy = 0: sigma_zz = -E alpha dT, e_xx = e_yy = (1 + nu) alpha dT.

    Derived from the 3D isotropic law e_ii = (s_ii - nu (s_jj + s_kk)) / E + alpha dT with the conditions
    named (e.g. "x": e_zz = 0 gives s_zz = nu s_xx - E alpha dT, then e_xx = 0 gives
    s_xx (1 - nu^2) = -E alpha dT (1 + nu)). Returns a dict 'sxx', 'syy', 'szz', 'exx', 'eyy'.
    """
    E, nu = _check_young_poisson(E, nu)
    dT = _arr(dT)
    free = alpha * dT * E
    zero = np.zeros_like(dT * E * nu)
    if held == "xy":
        s = -free / (1.0 - 2.0 * nu)
        return {"sxx": s, "syy": s, "szz": s, "exx": zero, "eyy": zero}
    if held == "x":
        s = -free / (1.0 - nu)
        return {"sxx": s, "syy": zero, "szz": s, "exx": zero, "eyy": (1.0 + nu) * alpha * dT / (1.0 - nu) + zero}
    if held == "none":
        e = (1.0 + nu) * alpha * dT + zero
        return {"sxx": zero, "syy": zero, "szz": -free + zero, "exx": e, "eyy": e}
    raise ValueError(f"held = {held!r}: choose 'xy', 'x' or 'none'")


def _jointed_block_geometry(E, nu, alpha, joint_angle_deg, cohesion, friction_deg, width, kn, ks):
    E, nu = _check_young_poisson(E, nu)
    E, nu = float(E), float(nu)
    alpha = float(_positive("alpha", alpha))
    width = float(_positive("width", width))
    kn, ks = float(_positive("kn", kn)), float(_positive("ks", ks))
    cohesion = float(_non_negative("cohesion", cohesion))
    if not -90.0 < joint_angle_deg < 90.0:
        raise ValueError(f"joint_angle_deg = {joint_angle_deg}: the joint must cross from the top to the "
                         "bottom, at an angle from the vertical in (-90, 90) degrees")
    if not 0.0 <= friction_deg < 90.0:
        raise ValueError(f"friction_deg = {friction_deg}: the joint friction angle must lie in [0, 90) degrees")
    theta = math.radians(joint_angle_deg)
    c, s = math.cos(theta), math.sin(theta)
    # x-compliance per unit width: block (1 - nu^2) / E plus the joint's x-jump per unit sigma_xx
    compliance = (1.0 - nu * nu) / E + c * (c * c / kn + s * s / ks) / width
    return E, nu, alpha, width, cohesion, theta, compliance


def jointed_block_slip_onset(*, E, nu, alpha, joint_angle_deg, cohesion, friction_deg, width,
                             kn=math.inf, ks=math.inf):
    """Temperature rise dT at which the joint of jointed_block_heating starts to slip:

        P_slip  = c / (cos^2 theta (|tan theta| - tan phi))        (compression sigma_xx = -P_slip),
        dT_slip = P_slip ((1 - nu^2) / E + cos theta (cos^2 theta / kn + sin^2 theta / ks) / L) / ((1 + nu) alpha),

    numpy.inf when |theta| <= phi (the joint never slips, whatever the heating). With rigid joints
    dT_slip = P_slip (1 - nu) / (E alpha). Derivation at jointed_block_heating.
    """
    E, nu, alpha, width, cohesion, theta, compliance = _jointed_block_geometry(
        E, nu, alpha, joint_angle_deg, cohesion, friction_deg, width, kn, ks)
    excess = abs(math.tan(theta)) - math.tan(math.radians(friction_deg))
    if excess <= 0.0:
        return math.inf
    p_slip = cohesion / (math.cos(theta) ** 2 * excess)
    return p_slip * compliance / ((1.0 + nu) * alpha)


def jointed_block_heating(*, dT, E, nu, alpha, joint_angle_deg, cohesion, friction_deg, width,
                          kn=math.inf, ks=math.inf):
    """A rock strip between two rigid, smooth vertical walls at x = 0 and x = L = width (u_x = 0, no shear),
    free at the top and bottom, plane strain, no gravity, cut into two blocks by one straight joint from
    top to bottom whose normal n = (cos theta, sin theta) makes the angle theta = joint_angle_deg with the
    x axis (the joint is theta from the vertical; theta > 0 leans it to the left going up). The joint is
    elastic (normal stiffness kn, shear ks, Pa/m; numpy.inf = rigid) and Coulomb: it slips when
    |tau| = c + sigma_n' tan phi, sigma_n' = -sigma_n the compressive normal stress, without dilation.
    The strip is heated uniformly by dT >= 0 (cooling would open the joint in tension, not covered).

    Homogeneous stress sigma_xx = S, sigma_yy = sigma_xy = 0 in both blocks satisfies every condition
    exactly: free top and bottom, smooth walls, and a joint traction that is the same all along it,
    sigma_n = S cos^2 theta, tau = s . sigma . n = -S sin theta cos theta, s = (-sin theta, cos theta),
    so the blocks keep the same strain and differ by a uniform jump
    [u] = (sigma_n / kn) n + (tau / ks) s + delta s (delta the plastic slip along s). The walls fix
    e_xx L + [u]_x = 0 with e_xx = (1 - nu^2) S / E + (1 + nu) alpha dT (plane strain, sigma_yy = 0);
    the vertical offset of the blocks is free. While the joint sticks (delta = 0):

        S = -(1 + nu) alpha dT / ((1 - nu^2) / E + cos theta (cos^2 theta / kn + sin^2 theta / ks) / L),

    -E alpha dT / (1 - nu) for rigid joints (block_uniform_heating, held "x"). With P = -S the Coulomb
    condition P |sin theta cos theta| = c + P cos^2 theta tan phi gives P_slip (jointed_block_slip_onset).
    Beyond it the stress stays at -P_slip (the condition fixes P, no hardening or dilation) and the walls'
    constraint is met by slip, -delta sin theta = -(1 + nu) alpha (dT - dT_slip) L:

        delta = (1 + nu) alpha (dT - dT_slip) L / sin theta        (block 2, x > joint, moves along s).

    Returns a dict: 'sxx' (= S), 'szz' (= nu S - E alpha dT), 'sigma_n' (tension positive), 'tau',
    'slip' (delta, m, zero before onset), 'dT_slip'. dT may be an array.
    """
    E, nu, alpha, width, cohesion, theta, compliance = _jointed_block_geometry(
        E, nu, alpha, joint_angle_deg, cohesion, friction_deg, width, kn, ks)
    dT = _arr(dT)
    if np.any(~(dT >= 0.0)):
        raise ValueError(f"dT = {dT}: only heating (dT >= 0) is covered; cooling puts the joint in tension")
    dT_slip = jointed_block_slip_onset(E=E, nu=nu, alpha=alpha, joint_angle_deg=joint_angle_deg,
                                       cohesion=cohesion, friction_deg=friction_deg, width=width, kn=kn, ks=ks)
    sticking = dT <= dT_slip
    elastic_dT = np.where(sticking, dT, dT_slip)
    S = -(1.0 + nu) * alpha * elastic_dT / compliance
    slipping_dT = np.where(sticking, 0.0, dT - dT_slip if math.isfinite(dT_slip) else 0.0)
    slip = np.zeros_like(dT) if math.isinf(dT_slip) else (1.0 + nu) * alpha * slipping_dT * width / math.sin(theta)
    c, s = math.cos(theta), math.sin(theta)
    return {"sxx": S, "szz": nu * S - E * alpha * dT, "sigma_n": S * c * c, "tau": -S * s * c,
            "slip": slip, "dT_slip": dT_slip}


STEFAN_BOLTZMANN = 5.670374419e-8  # W/(m^2 K^4), CODATA 2018 (exact in the SI since 2019)


def radiating_slab_surface_temperature(*, T1, T_inf, k, L, emissivity):
    """Steady surface temperature Ts (kelvin) of a slab of thickness L and conductivity k whose face
    x = 0 is held at T1 and whose face x = L radiates to surroundings at T_inf with the emissivity
    given: the conducted flux k (T1 - Ts) / L equals the radiated one, epsilon sigma (Ts^4 - T_inf^4).
    The balance's left side falls and its right side rises with Ts, so its root between T_inf and T1
    is unique; found by Brent's method to round-off (rtol 1e-15). The profile is linear, T1 + (Ts - T1) x / L.
    """
    T1, T_inf = float(_positive("T1", T1)), float(_positive("T_inf", T_inf))
    k, L = float(_positive("k", k)), float(_positive("L", L))
    if not 0.0 < emissivity <= 1.0:
        raise ValueError(f"emissivity = {emissivity}: must be in (0, 1]")
    if T1 == T_inf:
        return T1
    balance = lambda Ts: k * (T1 - Ts) / L - emissivity * STEFAN_BOLTZMANN * (Ts ** 4 - T_inf ** 4)
    return optimize.brentq(balance, min(T1, T_inf), max(T1, T_inf), xtol=1e-300, rtol=1e-15, maxiter=200)

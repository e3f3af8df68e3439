"""Closed-form heat-conduction and thermal-stress references (verification/analytic/heat.py) at known values.

Known values come from tables (erfc, erfcx, E1, Dawson's integral to 10 digits, Abramowitz and Stegun
ch. 5 and 7) or hand arithmetic shown in the comments. The other checks take independent routes, never
the function under test rewritten: the heat equation, boundary conditions and Fourier's law by central
finite differences of the returned fields; heat balances (stored heat = heat put in) by quadrature;
for the decaying sources an exact series and a second quadrature in another variable; for the cylinder
equilibrium, compatibility and Hooke's law by finite differences; for the jointed block an incremental
return-mapping calculation written here.

Tolerances: finite differences with step d carry a truncation error ~ d^2 f''' / 6 relative, chosen
so that it lies near 1e-7 (stated at each check); quadrature to 1e-12 relative compares at 1e-9;
closed forms against table values at 1e-9 (the tables' 10 digits) and against each other at 1e-12.
"""
import math

import numpy as np
import pytest
from scipy import integrate, optimize, special

from analytic import heat

REQ = pytest.mark.requirements("REQ-QA-003")

# A granite-like rock: k = 2.5 W/(m K), kappa = 1e-6 m^2/s (rho c = 2.5e6 J/(m^3 K)), so that
# sqrt(kappa t) = 1 m at t = 1e6 s; E = 10 GPa, nu = 0.25, alpha = 1e-5 /K (E alpha = 1e5 Pa/K).
K_ROCK, KAPPA = 2.5, 1e-6
RHO_C = K_ROCK / KAPPA
ROCK = dict(E=10e9, nu=0.25, alpha=1e-5)

ERFC_1 = 0.1572992071     # A&S table 7.1: erf(1) = 0.8427007929
ERFCX_1 = 0.4275835762    # exp(1) erfc(1) = 2.718281828 * 0.1572992071
E1_1 = 0.2193839344       # A&S table 5.1
DAWSON_1 = 0.5380795069   # A&S table 7.5


def approx(expected, *, rel):
    """pytest.approx with the relative tolerance alone: its default absolute 1e-12 would swallow
    the small values here (temperatures of 1e-9 K, strains of 1e-3)."""
    return pytest.approx(expected, rel=rel, abs=0.0)


def second_difference(f, x, d):
    return (f(x + d) - 2.0 * f(x) + f(x - d)) / (d * d)


def first_difference(f, x, d):
    return (f(x + d) - f(x - d)) / (2.0 * d)


# ---------------------------------------------------------------- ierfc


@REQ
def test_ierfc_known_values():
    # ierfc(0) = 1/sqrt(pi); ierfc(1) = exp(-1)/sqrt(pi) - erfc(1) = 0.2075537487 - 0.1572992071 = 0.0502545416
    assert heat.ierfc(0.0) == approx(1.0 / math.sqrt(math.pi), rel=1e-15)
    assert heat.ierfc(1.0) == approx(0.0502545416, rel=1e-8)
    # ierfc(-z) = ierfc(z) + 2 z (ierfc(z) - ierfc(-z) = -integral of erfc from -z to z = -2 z)
    z = np.array([0.3, 1.0, 2.5])
    np.testing.assert_allclose(heat.ierfc(-z), heat.ierfc(z) + 2.0 * z, rtol=1e-14)


@REQ
def test_ierfc_is_the_integral_of_erfc():
    # exp(z^2) ierfc(z) = integral from 0 to inf of erfcx(z + u) exp(-2 z u - u^2) du (s = z + u), a
    # quadrature that keeps its relative accuracy where ierfc itself is tiny. Both sides of the switch
    # to the continued fraction at z = 2 are sampled.
    for z in (-1.0, 0.0, 0.5, 1.5, 1.999, 2.0, 2.001, 3.0, 6.0, 12.0):
        scaled, _ = integrate.quad(lambda u: special.erfcx(z + u) * math.exp(-2.0 * z * u - u * u),
                                   0.0, math.inf, epsabs=0.0, epsrel=1e-13)
        assert float(heat.ierfc(z)) * math.exp(z * z) == approx(scaled, rel=1e-12), z


@REQ
def test_ierfcx_large_argument_asymptotic_series():
    # ierfcx(z) = exp(z^2) ierfc(z) ~ 1 / (2 sqrt(pi) z^2) sum_m (-1)^m (2m + 1)!! / (2 z^2)^m (the
    # asymptotic series of erfc integrated term by term); at z >= 20 ten terms are exact to round-off.
    # The direct form 1/sqrt(pi) - z erfcx(z) would lose 3 (z = 20) to 12 (z = 1e6) digits here.
    for z in (20.0, 300.0, 1e6):
        series, term = 0.0, 1.0
        for m in range(10):
            series += term
            term *= -(2 * m + 3) / (2.0 * z * z)
        expected = series / (2.0 * math.sqrt(math.pi) * z * z)
        assert heat.ierfcx(z) == approx(expected, rel=1e-13), z
    # ierfc itself underflows quietly to 0, no nan
    np.testing.assert_array_equal(heat.ierfc(np.array([30.0, 1e3, 1e300])), 0.0)


@REQ
def test_ierfc_derivative_is_minus_erfc():
    # d ierfc / dz = -erfc(z), central difference with d = 1e-4: truncation d^2 |erfc''| / 6 < 1e-9
    z = np.array([0.2, 1.0, 1.99, 2.01, 3.0])
    np.testing.assert_allclose(first_difference(heat.ierfc, z, 1e-4), -special.erfc(z), rtol=1e-7)


# ---------------------------------------------------------------- semi-infinite solid


def assert_heat_equation(temperature, x, t, *, rtol):
    """dT/dt = kappa d2T/dx2 by central differences, steps 1e-3 of the local scale (sqrt(kappa t) in x,
    t in t): truncation ~ 1e-6 / 6 of the third and fourth derivatives' scale."""
    dt = 1e-3 * t
    dx = 1e-3 * math.sqrt(KAPPA * t)
    dT_dt = first_difference(lambda s: temperature(x, s), t, dt)
    curvature = second_difference(lambda y: temperature(y, t), x, dx)
    np.testing.assert_allclose(dT_dt, KAPPA * curvature, rtol=rtol)


@REQ
def test_step_surface_temperature_known_values():
    # at x = 2 sqrt(kappa t) (z = 1): T = T0 + (Ts - T0) erfc(1); sqrt(kappa t) = 1 m at t = 1e6 s,
    # 2 m at 4e6 s, 0.1 m at 1e4 s: the profile at several times
    for t, x in ((1e6, 2.0), (4e6, 4.0), (1e4, 0.2)):
        T = heat.semi_infinite_step_temperature(x=x, t=t, T0=20.0, Ts=120.0, kappa=KAPPA)
        assert T == approx(20.0 + 100.0 * ERFC_1, rel=1e-9)
    # surface at Ts for all t; far field and t -> 0 at T0; never outside [T0, Ts]
    t = np.array([1.0, 1e3, 1e9])
    np.testing.assert_array_equal(heat.semi_infinite_step_temperature(x=0.0, t=t, T0=20.0, Ts=120.0,
                                                                      kappa=KAPPA), 120.0)
    assert heat.semi_infinite_step_temperature(x=1.0, t=1e-3, T0=20.0, Ts=120.0, kappa=KAPPA) == 20.0
    x = np.linspace(0.0, 10.0, 101)
    T = heat.semi_infinite_step_temperature(x=x, t=1e6, T0=20.0, Ts=120.0, kappa=KAPPA)
    assert np.all(np.diff(T) < 0.0)
    # x = 10 m is z = 5: erfc(5) = 1.5374597944e-12 (A&S table 7.1), the far field barely warmed
    far = heat.semi_infinite_step_temperature(x=10.0, t=1e6, T0=0.0, Ts=100.0, kappa=KAPPA)
    assert far == approx(100.0 * 1.5374597944e-12, rel=1e-9)


@REQ
def test_step_surface_temperature_solves_the_heat_equation_and_its_flux_is_fouriers():
    x = np.array([0.1, 0.7, 2.0, 3.5])

    def temperature(x, t):
        return heat.semi_infinite_step_temperature(x=x, t=t, T0=20.0, Ts=120.0, kappa=KAPPA)

    assert_heat_equation(temperature, x, 1e6, rtol=1e-5)
    # q = -k dT/dx, d = 1e-4 m against a 1 m scale: truncation ~ 2e-9
    q = heat.semi_infinite_step_heat_flux(x=x, t=1e6, T0=20.0, Ts=120.0, k=K_ROCK, kappa=KAPPA)
    np.testing.assert_allclose(q, -K_ROCK * first_difference(lambda y: temperature(y, 1e6), x, 1e-4), rtol=1e-7)
    # surface flux by hand: k (Ts - T0) / sqrt(pi kappa t) = 2.5 * 100 / sqrt(pi) = 141.0474 W/m^2
    assert heat.semi_infinite_step_heat_flux(x=0.0, t=1e6, T0=20.0, Ts=120.0, k=K_ROCK, kappa=KAPPA) \
        == approx(141.0474, rel=1e-6)
    # through a section 0.05 m high: 141.0474 * 0.05 = 7.05237 W/m
    assert heat.semi_infinite_step_heat_flow(x=0.0, t=1e6, T0=20.0, Ts=120.0, k=K_ROCK, kappa=KAPPA, height=0.05) \
        == approx(7.05237, rel=1e-6)


@REQ
def test_step_surface_heat_stored_equals_heat_in():
    # rho c integral of (T - T0) dx = integral over time of the surface flux (quadratures in x and t)
    t_end = 3e6
    stored, _ = integrate.quad(lambda x: RHO_C * (heat.semi_infinite_step_temperature(
        x=x, t=t_end, T0=20.0, Ts=120.0, kappa=KAPPA) - 20.0), 0.0, 60.0, epsabs=0.0, epsrel=1e-12, limit=200)
    inflow, _ = integrate.quad(lambda t: heat.semi_infinite_step_heat_flux(
        x=0.0, t=t, T0=20.0, Ts=120.0, k=K_ROCK, kappa=KAPPA), 0.0, t_end, epsabs=0.0, epsrel=1e-12)
    assert stored == approx(inflow, rel=1e-9)


@REQ
def test_constant_flux_known_values_and_heat_balance():
    # surface: (2 q0 / k) sqrt(kappa t / pi) = 2 * 100 / 2.5 / sqrt(pi) = 45.135167 K at t = 1e6 s
    T = heat.semi_infinite_constant_flux_temperature(x=0.0, t=1e6, T0=10.0, q0=100.0, k=K_ROCK, kappa=KAPPA)
    assert T == approx(10.0 + 45.135167, rel=1e-7)
    # at z = 1 (x = 2 m): (2 q0 / k) sqrt(kappa t) ierfc(1) = 80 * 0.0502545416 = 4.02036333 K
    T = heat.semi_infinite_constant_flux_temperature(x=2.0, t=1e6, T0=10.0, q0=100.0, k=K_ROCK, kappa=KAPPA)
    assert T == approx(10.0 + 4.02036333, rel=1e-8)
    # the surface rises as sqrt(t): four times the time, twice the rise
    rise = [heat.semi_infinite_constant_flux_temperature(x=0.0, t=t, T0=0.0, q0=100.0, k=K_ROCK, kappa=KAPPA)
            for t in (1e6, 4e6)]
    assert rise[1] == approx(2.0 * rise[0], rel=1e-14)
    # stored heat = q0 t
    stored, _ = integrate.quad(lambda x: RHO_C * heat.semi_infinite_constant_flux_temperature(
        x=x, t=1e6, T0=0.0, q0=100.0, k=K_ROCK, kappa=KAPPA), 0.0, 60.0, epsabs=0.0, epsrel=1e-12, limit=200)
    assert stored == approx(100.0 * 1e6, rel=1e-9)


@REQ
def test_constant_flux_solves_the_heat_equation_with_the_flux_at_the_surface():
    x = np.array([0.0, 0.4, 1.5, 4.0])

    def temperature(x, t):
        return heat.semi_infinite_constant_flux_temperature(x=x, t=t, T0=10.0, q0=100.0, k=K_ROCK, kappa=KAPPA)

    assert_heat_equation(temperature, x[1:], 1e6, rtol=1e-5)
    # -k dT/dx = q0 erfc(z) inside (central differences, d = 1e-4 m) and q0 at the surface
    q = heat.semi_infinite_constant_flux_heat_flux(x=x, t=1e6, q0=100.0, kappa=KAPPA)
    np.testing.assert_allclose(q[1:], -K_ROCK * first_difference(lambda y: temperature(y, 1e6), x[1:], 1e-4),
                               rtol=1e-7)
    assert q[0] == 100.0
    # the surface gradient from a one-sided fourth-order difference (error ~ d^4, d = 1e-3 m)
    d = 1e-3
    f = [float(temperature(i * d, 1e6)) for i in range(5)]
    gradient = (-25.0 * f[0] + 48.0 * f[1] - 36.0 * f[2] + 16.0 * f[3] - 3.0 * f[4]) / (12.0 * d)
    assert -K_ROCK * gradient == approx(100.0, rel=1e-8)


# ---------------------------------------------------------------- convective surface


def convective(x, t, h):
    return heat.semi_infinite_convective_temperature(x=x, t=t, T0=20.0, T_inf=80.0, h=h, k=K_ROCK, kappa=KAPPA)


@REQ
def test_convective_surface_known_values_and_limits():
    # beta = h sqrt(kappa t) / k = 1 for h = k = 2.5 W/(m^2 K), t = 1e6 s: surface (T - T0) / (T_inf - T0)
    # = 1 - erfcx(1) = 0.5724164238
    assert convective(0.0, 1e6, K_ROCK) == approx(20.0 + 60.0 * (1.0 - ERFCX_1), rel=1e-9)
    # flux in at the surface: h (T_inf - T0) erfcx(1) = 2.5 * 60 * 0.4275835762 = 64.13753643 W/m^2
    q = heat.semi_infinite_convective_surface_heat_flux(t=1e6, T0=20.0, T_inf=80.0, h=K_ROCK, k=K_ROCK, kappa=KAPPA)
    assert q == approx(64.13753643, rel=1e-9)
    x = np.array([0.0, 0.5, 2.0, 5.0])
    # h = 0: adiabatic, nothing changes; h -> infinity: the fixed surface temperature
    np.testing.assert_allclose(convective(x, 1e6, 0.0), 20.0, rtol=1e-15)
    fixed = heat.semi_infinite_step_temperature(x=x, t=1e6, T0=20.0, Ts=80.0, kappa=KAPPA)
    np.testing.assert_allclose(convective(x, 1e6, 1e12), fixed, rtol=1e-10)
    # arguments where exp(H x + H^2 kappa t) overflows a double (H^2 kappa t = 1e6): finite, in [T0, T_inf],
    # and at the surface 1 - erfcx(1e3) ~ 1 - 1 / (1e3 sqrt(pi))
    far = convective(np.array([0.0, 1.0, 50.0]), 1e6, 2.5e3)
    assert np.all(np.isfinite(far)) and np.all((far >= 20.0) & (far <= 80.0))
    assert far[0] == approx(80.0 - 60.0 / (1e3 * math.sqrt(math.pi)) * (1.0 - 0.5e-6), rel=1e-12)


@REQ
def test_convective_surface_solves_the_heat_equation_with_its_boundary_condition():
    x = np.array([0.2, 1.0, 3.0])
    assert_heat_equation(lambda x, t: convective(x, t, 4.0), x, 1e6, rtol=1e-5)
    # -k dT/dx = h (T_inf - T) at x = 0: one-sided fourth-order difference, d = 1e-3 m
    for h in (0.5, 4.0, 40.0):
        d = 1e-3
        f = [float(convective(i * d, 1e6, h)) for i in range(5)]
        gradient = (-25.0 * f[0] + 48.0 * f[1] - 36.0 * f[2] + 16.0 * f[3] - 3.0 * f[4]) / (12.0 * d)
        assert -K_ROCK * gradient == approx(h * (80.0 - f[0]), rel=1e-7), h
        q = heat.semi_infinite_convective_surface_heat_flux(t=1e6, T0=20.0, T_inf=80.0, h=h, k=K_ROCK, kappa=KAPPA)
        assert q == approx(h * (80.0 - f[0]), rel=1e-12), h


@REQ
def test_convective_surface_heat_stored_equals_heat_in():
    stored, _ = integrate.quad(lambda x: RHO_C * (convective(x, 2e6, 4.0) - 20.0), 0.0, 60.0,
                               epsabs=0.0, epsrel=1e-12, limit=200)
    inflow, _ = integrate.quad(lambda t: heat.semi_infinite_convective_surface_heat_flux(
        t=t, T0=20.0, T_inf=80.0, h=4.0, k=K_ROCK, kappa=KAPPA), 0.0, 2e6, epsabs=0.0, epsrel=1e-12)
    assert stored == approx(inflow, rel=1e-9)


@REQ
def test_semi_infinite_solutions_reject_bad_input():
    with pytest.raises(ValueError, match="depth"):
        heat.semi_infinite_step_temperature(x=-0.1, t=1.0, T0=0.0, Ts=1.0, kappa=KAPPA)
    with pytest.raises(ValueError, match="t ="):
        heat.semi_infinite_constant_flux_temperature(x=0.0, t=0.0, T0=0.0, q0=1.0, k=K_ROCK, kappa=KAPPA)
    with pytest.raises(ValueError, match="kappa"):
        heat.semi_infinite_step_heat_flux(x=0.0, t=1.0, T0=0.0, Ts=1.0, k=K_ROCK, kappa=-1.0)
    with pytest.raises(ValueError, match="h ="):
        heat.semi_infinite_convective_temperature(x=0.0, t=1.0, T0=0.0, T_inf=1.0, h=-1.0, k=K_ROCK, kappa=KAPPA)
    with pytest.raises(ValueError, match="k ="):
        heat.semi_infinite_convective_surface_heat_flux(t=1.0, T0=0.0, T_inf=1.0, h=1.0, k=0.0, kappa=KAPPA)


# ---------------------------------------------------------------- line source


def radial_heat_equation_residual(temperature, r, t):
    """dT/dt - kappa (d2T/dr2 + dT/dr / r) relative to dT/dt, central differences with steps 1e-3 of
    the local scales (truncation ~ 1e-7)."""
    dT_dt = first_difference(lambda s: temperature(r, s), t, 1e-3 * t)
    dr = 1e-3 * r
    laplacian = second_difference(lambda y: temperature(y, t), r, dr) + \
        first_difference(lambda y: temperature(y, t), r, dr) / r
    return (dT_dt - KAPPA * laplacian) / dT_dt


@REQ
def test_line_source_known_values():
    # r^2 / (4 kappa t) = 1 at r = 2 m, t = 1e6 s: q / (4 pi k) E1(1) = 100 / (10 pi) * 0.2193839344
    T = heat.line_source_temperature(r=2.0, t=1e6, q=100.0, k=K_ROCK, kappa=KAPPA, T0=15.0)
    assert T == approx(15.0 + 100.0 / (10.0 * math.pi) * E1_1, rel=1e-9)
    # long times: E1(u) = -gamma - ln u + u + O(u^2) (A&S 5.1.11), u = 1e-6 here
    T = heat.line_source_temperature(r=2.0, t=1e12, q=100.0, k=K_ROCK, kappa=KAPPA)
    assert T == approx(100.0 / (10.0 * math.pi) * (-0.5772156649 - math.log(1e-6) + 1e-6), rel=1e-10)
    # every circle carries the power at long times; at u = 1 the fraction exp(-1)
    assert 2.0 * math.pi * 2.0 * heat.line_source_radial_heat_flux(r=2.0, t=1e6, q=100.0, kappa=KAPPA) \
        == approx(100.0 * math.exp(-1.0), rel=1e-14)
    assert 2.0 * math.pi * 0.5 * heat.line_source_radial_heat_flux(r=0.5, t=1e15, q=100.0, kappa=KAPPA) \
        == approx(100.0, rel=1e-9)


@REQ
def test_line_source_solves_the_radial_heat_equation_and_fouriers_law():
    r = np.array([0.3, 1.0, 2.0, 4.0])

    def temperature(r, t):
        return heat.line_source_temperature(r=r, t=t, q=100.0, k=K_ROCK, kappa=KAPPA)

    np.testing.assert_allclose(radial_heat_equation_residual(temperature, r, 1e6), 0.0, atol=1e-5)
    # steps 1e-5 r: truncation (1e-5 r)^2 |T'''| / 6 ~ 1e-9 of T' here, round-off ~ 1e-12
    q = heat.line_source_radial_heat_flux(r=r, t=1e6, q=100.0, kappa=KAPPA)
    np.testing.assert_allclose(q, -K_ROCK * first_difference(lambda y: temperature(y, 1e6), r, 1e-5 * r), rtol=1e-7)


@REQ
def test_line_source_heat_stored_equals_heat_released():
    # rho c integral of (T - T0) 2 pi r dr = q t
    stored, _ = integrate.quad(lambda r: RHO_C * 2.0 * math.pi * r * heat.line_source_temperature(
        r=r, t=1e6, q=100.0, k=K_ROCK, kappa=KAPPA), 0.0, 40.0, points=[2.0], epsabs=0.0, epsrel=1e-12, limit=200)
    assert stored == approx(100.0 * 1e6, rel=1e-9)


# ---------------------------------------------------------------- decaying sources

YEAR = 365.25 * 86400.0
# a waste-heat curve: two decaying terms and a constant one (W/m of drift), time constants in years
WASTE_Q = [600.0, 300.0, 50.0]
WASTE_TAU = [2.0 * YEAR, 40.0 * YEAR, math.inf]


def line_source_poisson_series(r, t, q, tau):
    """Exact series for one term q exp(-t' / tau): with u0 = r^2 / (4 kappa t),
    T - T0 = q / (4 pi k) sum_n P(n; t / tau) E_{n+1}(u0), P the Poisson weights (t/tau)^n exp(-t/tau) / n!.
    From the u-form of the convolution, exp(a / (tau u)) expanded in powers of 1/u and
    integral from u0 to inf of u^(-n-1) exp(-u) du = u0^-n E_{n+1}(u0)."""
    u0 = r * r / (4.0 * KAPPA * t)
    if math.isinf(tau):
        return q / (4.0 * math.pi * K_ROCK) * special.exp1(u0)
    mean = t / tau
    total = 0.0
    for n in range(int(mean + 40.0 * math.sqrt(mean) + 60.0)):
        weight = math.exp(n * math.log(mean) - math.lgamma(n + 1.0) - mean)
        total += weight * special.expn(n + 1, u0)
    return q / (4.0 * math.pi * K_ROCK) * total


def line_source_time_quadrature(r, t, q, tau):
    """The convolution in its first form, integrated in s = t - t' (the time since release) over
    logarithmically spaced pieces around the kernel's peak at s = r^2 / (4 kappa)."""
    a = r * r / (4.0 * KAPPA)
    edges = [0.0] + [a * f for f in (0.05, 0.3, 1.0, 3.0, 10.0, 100.0, 1e3, 1e4, 1e5, 1e6) if a * f < t] + [t]
    total = 0.0
    for lo, hi in zip(edges[:-1], edges[1:]):
        part, _ = integrate.quad(
            lambda s: sum(qi * math.exp(-(t - s) / ti) for qi, ti in zip(q, tau)) * math.exp(-a / s) / s
            if s > 0.0 else 0.0, lo, hi, epsabs=0.0, epsrel=1e-12, limit=200)
        total += part
    return total / (4.0 * math.pi * K_ROCK)


@REQ
def test_decaying_source_power_known_values():
    # at t = tau: q exp(-1); a half-life t_1/2 is tau = t_1/2 / ln 2, half the power at t_1/2
    assert heat.decaying_source_power(t=5.0, q=[10.0], tau=[5.0]) == approx(10.0 * math.exp(-1.0), rel=1e-15)
    assert heat.decaying_source_power(t=30.0, q=[8.0], tau=[30.0 / math.log(2.0)]) == approx(4.0, rel=1e-14)
    np.testing.assert_allclose(heat.decaying_source_power(t=np.array([0.0, 1e12]), q=WASTE_Q, tau=WASTE_TAU),
                               [950.0, 50.0], rtol=1e-14)


@REQ
def test_decaying_line_source_constant_term_is_the_continuous_line_source():
    r, t = np.array([0.1, 1.0, 5.0, 30.0]), np.array([1e4, 1e7, 1e9, 3e9])
    np.testing.assert_allclose(
        heat.decaying_line_source_temperature(r=r, t=t, q=[100.0], tau=[math.inf], k=K_ROCK, kappa=KAPPA, T0=5.0),
        heat.line_source_temperature(r=r, t=t, q=100.0, k=K_ROCK, kappa=KAPPA, T0=5.0), rtol=1e-12)
    # a time constant 1e9 times the time is a constant source to within t / tau = 1e-9
    T = heat.decaying_line_source_temperature(r=1.0, t=1e7, q=[100.0], tau=[1e16], k=K_ROCK, kappa=KAPPA)
    assert T == approx(heat.line_source_temperature(r=1.0, t=1e7, q=100.0, k=K_ROCK, kappa=KAPPA), rel=2e-9)


@REQ
@pytest.mark.parametrize("tau_years", [0.01, 1.0, 30.0, 1000.0])
def test_decaying_line_source_matches_the_exact_series(tau_years):
    # t / tau from 1e-4 to 1e4 over 100 years, r from 0.2 m (u0 ~ 3e-6) to 60 m (u0 ~ 0.3 .. 3e4)
    tau = tau_years * YEAR
    for t in (0.1 * YEAR, 3.0 * YEAR, 100.0 * YEAR):
        for r in (0.2, 2.0, 20.0, 60.0):
            expected = line_source_poisson_series(r, t, 100.0, tau)
            T = heat.decaying_line_source_temperature(r=r, t=t, q=[100.0], tau=[tau], k=K_ROCK, kappa=KAPPA)
            assert T == approx(expected, rel=1e-9), (r, t)


@REQ
def test_decaying_line_source_waste_curve_matches_a_second_quadrature_and_the_series():
    r = np.array([0.5, 3.0, 15.0])
    for t in (0.5 * YEAR, 10.0 * YEAR, 100.0 * YEAR):
        T = heat.decaying_line_source_temperature(r=r, t=t, q=WASTE_Q, tau=WASTE_TAU, k=K_ROCK, kappa=KAPPA)
        by_time = [line_source_time_quadrature(ri, t, WASTE_Q, WASTE_TAU) for ri in r]
        by_series = [sum(line_source_poisson_series(ri, t, qi, ti) for qi, ti in zip(WASTE_Q, WASTE_TAU))
                     for ri in r]
        np.testing.assert_allclose(T, by_time, rtol=1e-9)
        np.testing.assert_allclose(T, by_series, rtol=1e-9)


@REQ
@pytest.mark.parametrize("tau,t", [(1e4, 3e9), (1.0, 1e7), (100.0, 3e9), (1.0, 3e9)])
def test_decaying_sources_far_past_their_decay_are_instantaneous_sources(tau, t):
    # A term with tau << t has released q tau J/m (J/m^2) within ~tau of t' = 0. Expanding the kernel
    # K(t - t') in t' and integral of t'^n exp(-t'/tau) dt' = n! tau^(n+1):
    #   T - T0 = q (tau K(t) - tau^2 K'(t) + 2 tau^3 K''(t) / 2 - ...),
    # two terms here, the third ~ 2 (tau / t)^2 <= 2.2e-11 relative for t / tau >= 3e5.
    # Line: K = exp(-a/s) / (4 pi k s), a = r^2 / (4 kappa): K'/K = a / t^2 - 1 / t.
    # Plane: K = exp(-b/s) / (rho c 2 sqrt(pi kappa s)), b = x^2 / (4 kappa): K'/K = b / t^2 - 1 / (2 t).
    # These are the cases where t' << t: a rule that lost t' to cancellation (t' from t - a e^-w) was
    # off by 7e-7 at t / tau = 3e9, and one without breakpoints missed the source altogether.
    for d in (0.2, 3.0):
        a = d * d / (4.0 * KAPPA)
        line = 100.0 * tau * math.exp(-a / t) / (4.0 * math.pi * K_ROCK * t) * (1.0 - tau * (a / t ** 2 - 1.0 / t))
        plane = 100.0 * tau * math.exp(-a / t) / (RHO_C * 2.0 * math.sqrt(math.pi * KAPPA * t)) \
            * (1.0 - tau * (a / t ** 2 - 0.5 / t))
        assert heat.decaying_line_source_temperature(r=d, t=t, q=[100.0], tau=[tau], k=K_ROCK, kappa=KAPPA) \
            == approx(line, rel=1e-9), d
        assert heat.decaying_plane_source_temperature(x=d, t=t, q=[100.0], tau=[tau], k=K_ROCK, kappa=KAPPA) \
            == approx(plane, rel=1e-9), d


@REQ
def test_decaying_plane_source_closed_forms():
    # constant: (q / k) sqrt(kappa t) ierfc(|x| / (2 sqrt(kappa t))); at x = 0, t = 1e6 s: q / (k sqrt(pi))
    x = np.array([-1.5, 0.0, 0.3, 2.0, 8.0])
    T = heat.decaying_plane_source_temperature(x=x, t=1e6, q=[40.0], tau=[math.inf], k=K_ROCK, kappa=KAPPA)
    np.testing.assert_allclose(T, 40.0 / K_ROCK * heat.ierfc(np.abs(x) / 2.0), rtol=1e-12)
    assert T[1] == approx(40.0 / (K_ROCK * math.sqrt(math.pi)), rel=1e-12)
    # decaying, x = 0: (q / k) sqrt(kappa tau / pi) D(sqrt(t / tau)); t = tau = 1e6 s gives
    # (40 / 2.5) (1 / sqrt(pi)) D(1) = 16 * 0.5641895835 * 0.5380795069 = 4.857263 K
    T0 = heat.decaying_plane_source_temperature(x=0.0, t=1e6, q=[40.0], tau=[1e6], k=K_ROCK, kappa=KAPPA)
    assert T0 == approx(16.0 / math.sqrt(math.pi) * DAWSON_1, rel=1e-9)
    for t, tau in ((1e3, 1e6), (1e8, 1e6), (3e9, 1e8), (3e9, 3e5)):
        T0 = heat.decaying_plane_source_temperature(x=0.0, t=t, q=[40.0], tau=[tau], k=K_ROCK, kappa=KAPPA)
        assert T0 == approx(40.0 / K_ROCK * math.sqrt(KAPPA * tau / math.pi) * special.dawsn(math.sqrt(t / tau)),
                                   rel=1e-9)


@REQ
def test_decaying_plane_source_matches_a_quadrature_in_time():
    # the instantaneous plane source Q' / (rho c) / (2 sqrt(pi kappa s)) exp(-x^2 / (4 kappa s)) summed over
    # releases, integrated in s = t - t' with s = 0 excluded by the split (its 1/sqrt(s) is integrable:
    # quad's end-point rule never samples it)
    for x in (0.0, 1.0, 10.0):
        for t in (1.0 * YEAR, 100.0 * YEAR):
            def kernel(s):
                power = sum(qi * math.exp(-(t - s) / ti) for qi, ti in zip(WASTE_Q, WASTE_TAU))
                return power / RHO_C / (2.0 * math.sqrt(math.pi * KAPPA * s)) * math.exp(-x * x / (4.0 * KAPPA * s))
            edges = [0.0] + [f * YEAR for f in (0.01, 0.1, 1.0, 10.0) if f * YEAR < t] + [t]
            expected = sum(integrate.quad(kernel, lo, hi, epsabs=0.0, epsrel=1e-12, limit=200)[0]
                           for lo, hi in zip(edges[:-1], edges[1:]))
            T = heat.decaying_plane_source_temperature(x=x, t=t, q=WASTE_Q, tau=WASTE_TAU, k=K_ROCK, kappa=KAPPA)
            assert T == approx(expected, rel=1e-9), (x, t)


@REQ
def test_sources_reject_bad_input():
    with pytest.raises(ValueError, match="r ="):
        heat.line_source_temperature(r=0.0, t=1.0, q=1.0, k=K_ROCK, kappa=KAPPA)
    with pytest.raises(ValueError, match="one time constant per term"):
        heat.decaying_line_source_temperature(r=1.0, t=1.0, q=[1.0, 2.0], tau=[1.0], k=K_ROCK, kappa=KAPPA)
    with pytest.raises(ValueError, match="tau ="):
        heat.decaying_plane_source_temperature(x=1.0, t=1.0, q=[1.0], tau=[0.0], k=K_ROCK, kappa=KAPPA)
    with pytest.raises(ValueError, match="t ="):
        heat.decaying_line_source_temperature(r=1.0, t=-1.0, q=[1.0], tau=[1.0], k=K_ROCK, kappa=KAPPA)
    with pytest.raises(ValueError, match="t ="):
        heat.decaying_source_power(t=-1.0, q=[1.0], tau=[1.0])


# ---------------------------------------------------------------- hollow cylinder

WALL = dict(a=1.0, b=3.0)


def cylinder(r, **overrides):
    args = dict(WALL, Ta=150.0, Tb=40.0, T_ref=25.0, **ROCK)
    args.update(overrides)
    return heat.hollow_cylinder_thermal_stress(r=r, **args)


def hooke_strains(srr, stt, szz, dT, *, E, nu, alpha):
    """3D isotropic law with the free thermal strain: e_ii = (s_ii - nu (s_jj + s_kk)) / E + alpha dT."""
    return ((srr - nu * (stt + szz)) / E + alpha * dT, (stt - nu * (srr + szz)) / E + alpha * dT,
            (szz - nu * (srr + stt)) / E + alpha * dT)


@REQ
def test_hollow_cylinder_steady_temperature_and_heat_flow():
    # at r = sqrt(a b) the logarithmic profile is at the mean of Ta and Tb: sqrt(3) m -> 95 C
    T = heat.hollow_cylinder_steady_temperature(r=np.array([1.0, math.sqrt(3.0), 3.0]), Ta=150.0, Tb=40.0, **WALL)
    np.testing.assert_allclose(T, [150.0, 95.0, 40.0], rtol=1e-14)
    # Q = 2 pi k (Ta - Tb) / ln(b / a) = 2 pi 2.5 110 / ln 3 = 1727.876 / 1.0986123 = 1572.7805 W/m,
    # equal to -2 pi r k dT/dr
    # at every radius (central differences, d = 1e-5 m: truncation ~ 1e-10 relative)
    Q = heat.hollow_cylinder_heat_flow(Ta=150.0, Tb=40.0, k=K_ROCK, **WALL)
    assert Q == approx(1572.7805, rel=1e-7)
    r = np.array([1.2, 2.0, 2.9])
    gradient = first_difference(lambda y: heat.hollow_cylinder_steady_temperature(r=y, Ta=150.0, Tb=40.0, **WALL),
                                r, 1e-5)
    np.testing.assert_allclose(-2.0 * math.pi * r * K_ROCK * gradient, Q, rtol=1e-8)


@REQ
@pytest.mark.parametrize("axial", ["plane_strain", "generalized"])
def test_hollow_cylinder_stresses_are_in_equilibrium_compatible_and_traction_free(axial):
    E, nu, alpha = ROCK["E"], ROCK["nu"], ROCK["alpha"]
    res = cylinder(np.array([1.0, 3.0]), axial=axial)
    # traction-free surfaces, against the stress scale E alpha dT ~ 1e7 Pa
    np.testing.assert_allclose(res["srr"], 0.0, atol=1e-6)
    r = np.linspace(1.05, 2.95, 9)
    d = 1e-4   # central differences on a 1 m scale: truncation ~ 2e-9 relative

    def field(name):
        return lambda y: cylinder(y, axial=axial)[name]

    res = cylinder(r, axial=axial)
    # equilibrium: d sigma_rr / dr + (sigma_rr - sigma_tt) / r = 0, against the stress gradient scale
    residual = first_difference(field("srr"), r, d) + (res["srr"] - res["stt"]) / r
    np.testing.assert_allclose(residual, 0.0, atol=1e-7 * np.max(np.abs(res["stt"])))
    err, ett, ezz = hooke_strains(res["srr"], res["stt"], res["szz"], res["dT"], E=E, nu=nu, alpha=alpha)
    # compatibility of the strains Hooke's law gives: d(r e_tt)/dr = e_rr
    compatibility = first_difference(lambda y: y * hooke_strains(
        *(cylinder(y, axial=axial)[n] for n in ("srr", "stt", "szz", "dT")), E=E, nu=nu, alpha=alpha)[1], r, d)
    np.testing.assert_allclose(compatibility, err, rtol=1e-7)
    # the displacement gives the same strains: e_tt = u / r, e_rr = du/dr; e_zz as returned, uniform
    np.testing.assert_allclose(res["ur"] / r, ett, rtol=1e-12)
    np.testing.assert_allclose(first_difference(field("ur"), r, d), err, rtol=1e-7)
    np.testing.assert_allclose(ezz, res["ezz"], atol=1e-15)
    assert np.ptp(res["ezz"]) == 0.0
    if axial == "plane_strain":
        np.testing.assert_array_equal(res["ezz"], 0.0)
    else:
        # zero axial force: integral of sigma_zz 2 pi r dr over the wall (quadrature), against the
        # force scale E alpha (Ta - Tb) pi (b^2 - a^2) = 1e7 * 1.1 * 8 pi ~ 2.8e8 N
        scale = 1e5 * 110.0 * math.pi * 8.0
        force, _ = integrate.quad(lambda y: 2.0 * math.pi * y * float(cylinder(y, axial=axial)["szz"]),
                                  1.0, 3.0, epsabs=1e-12 * scale, epsrel=0.0)
        assert abs(force) < 1e-10 * scale


@REQ
def test_hollow_cylinder_matches_timoshenko_goodier_closed_form():
    # T&G's form for T = Ti on r = a, 0 on r = b, stress-free at 0, free ends (generalized plane strain):
    # with c = alpha E Ti / (2 (1 - nu) ln(b/a)),
    #   s_rr = c (-ln(b/r) - a^2 / (b^2 - a^2) (1 - b^2/r^2) ln(b/a)),
    #   s_tt = c (1 - ln(b/r) - a^2 / (b^2 - a^2) (1 + b^2/r^2) ln(b/a)),
    #   s_zz = c (1 - 2 ln(b/r) - 2 a^2 / (b^2 - a^2) ln(b/a)).
    a, b, Ti = 1.0, 3.0, 100.0
    r = np.linspace(a, b, 7)
    log_ba = math.log(b / a)
    c = ROCK["alpha"] * ROCK["E"] * Ti / (2.0 * (1.0 - ROCK["nu"]) * log_ba)
    res = cylinder(r, Ta=Ti, Tb=0.0, T_ref=0.0, axial="generalized")
    np.testing.assert_allclose(res["srr"], c * (-np.log(b / r) - a * a / (b * b - a * a) * (1.0 - b * b / r ** 2) * log_ba),
                               atol=1e-9 * c)
    np.testing.assert_allclose(res["stt"], c * (1.0 - np.log(b / r) - a * a / (b * b - a * a) * (1.0 + b * b / r ** 2) * log_ba),
                               rtol=1e-12)
    np.testing.assert_allclose(res["szz"], c * (1.0 - 2.0 * np.log(b / r) - 2.0 * a * a / (b * b - a * a) * log_ba),
                               rtol=1e-12)
    # by hand at the hot inner surface: c = 1e5 * 100 / (1.5 ln 3) = 6.0683e6 Pa,
    # s_tt(a) = c (1 - ln 3 - (1/8) 10 ln 3) = c (1 - 2.25 ln 3) = -1.47188 c = -8.9317e6 Pa (compressive)
    assert res["stt"][0] == approx(-8.9317e6, rel=1e-4)


@REQ
def test_hollow_cylinder_uniform_temperature_is_free_expansion():
    r = np.linspace(1.0, 3.0, 5)
    res = cylinder(r, Ta=75.0, Tb=75.0, T_ref=25.0)
    np.testing.assert_allclose(res["srr"], 0.0, atol=1e-6)
    np.testing.assert_allclose(res["stt"], 0.0, atol=1e-6)
    # plane strain: s_zz = -E alpha dT = -1e5 * 50 = -5e6 Pa; u_r = (1 + nu) alpha dT r = 6.25e-4 r
    np.testing.assert_allclose(res["szz"], -5e6, rtol=1e-12)
    np.testing.assert_allclose(res["ur"], 6.25e-4 * r, rtol=1e-12)
    free = cylinder(r, Ta=75.0, Tb=75.0, T_ref=25.0, axial="generalized")
    np.testing.assert_allclose(free["szz"], 0.0, atol=1e-6)
    np.testing.assert_allclose(free["ur"], 5e-4 * r, rtol=1e-12)   # alpha dT r: free in 3D


@REQ
def test_hollow_cylinder_rejects_bad_input():
    with pytest.raises(ValueError, match="outside the wall"):
        cylinder(0.5)
    with pytest.raises(ValueError, match="0 < a < b"):
        heat.hollow_cylinder_steady_temperature(r=1.0, a=2.0, b=1.0, Ta=1.0, Tb=0.0)
    with pytest.raises(ValueError, match="axial"):
        cylinder(2.0, axial="plane_stress")
    with pytest.raises(ValueError, match="Poisson"):
        cylinder(2.0, nu=0.5)


# ---------------------------------------------------------------- heated blocks


@REQ
def test_block_uniform_heating_known_values():
    # E alpha dT = 1e5 * 100 = 1e7 Pa; nu = 0.25
    full = heat.block_uniform_heating(dT=100.0, held="xy", **ROCK)
    for name in ("sxx", "syy", "szz"):
        assert full[name] == approx(-2e7, rel=1e-14)     # / (1 - 2 nu) = / 0.5
    lateral = heat.block_uniform_heating(dT=100.0, held="x", **ROCK)
    assert lateral["sxx"] == approx(-1e7 / 0.75, rel=1e-14) and lateral["syy"] == 0.0
    assert lateral["eyy"] == approx(1.25e-3 / 0.75, rel=1e-14)
    free = heat.block_uniform_heating(dT=100.0, held="none", **ROCK)
    assert (free["sxx"], free["syy"]) == (0.0, 0.0) and free["szz"] == approx(-1e7, rel=1e-14)
    assert (free["exx"], free["eyy"]) == (approx(1.25e-3, rel=1e-14), approx(1.25e-3, rel=1e-14))


@REQ
@pytest.mark.parametrize("held", ["xy", "x", "none"])
def test_block_uniform_heating_satisfies_hookes_law_and_its_constraints(held):
    dT = np.array([-40.0, 0.0, 100.0])
    res = heat.block_uniform_heating(dT=dT, held=held, **ROCK)
    exx, eyy, ezz = hooke_strains(res["sxx"], res["syy"], res["szz"], dT, **ROCK)
    np.testing.assert_allclose(ezz, 0.0, atol=1e-18)                       # plane strain
    np.testing.assert_allclose(exx, res["exx"], atol=1e-18)
    np.testing.assert_allclose(eyy, res["eyy"], atol=1e-18)
    held_x, held_y = held in ("xy", "x"), held == "xy"
    np.testing.assert_array_equal(res["exx"] if held_x else res["sxx"], 0.0)
    np.testing.assert_array_equal(res["eyy"] if held_y else res["syy"], 0.0)


def jointed_incremental(dT_end, *, theta_deg, c, phi_deg, L, kn, ks, steps=4000):
    """The jointed block by increments with a Coulomb check, written from the conditions alone.
    Given the plastic slip delta along s, the walls' condition e_xx L + [u]_x = 0 with
    e_xx = (1 - nu^2) S / E + (1 + nu) alpha dT and [u]_x = S cos (cos^2 / kn + sin^2 / ks) - delta sin
    fixes S; the slip stays while the Coulomb function f = |tau| - c - P cos^2 tan(phi) (P = -S,
    tau = P sin cos) is negative, and where a trial state has f > 0 delta is found by root-finding
    (brentq) on f = 0."""
    E, nu, alpha = ROCK["E"], ROCK["nu"], ROCK["alpha"]
    th, tan_phi = math.radians(theta_deg), math.tan(math.radians(phi_deg))
    cs, sn = math.cos(th), math.sin(th)
    compliance = (1.0 - nu * nu) * L / E + cs * (cs * cs / kn + sn * sn / ks)

    def stress(dT, slip):
        return (slip * sn - (1.0 + nu) * alpha * dT * L) / compliance

    def coulomb(dT, slip):
        P = -stress(dT, slip)
        return abs(P * sn * cs) - c - P * cs * cs * tan_phi

    slip = 0.0
    history = []
    for dT in np.linspace(0.0, dT_end, steps + 1):
        if coulomb(dT, slip) > 0.0:
            # between the slip so far (f > 0) and the slip that relieves all stress (P = 0, f = -c < 0)
            relieved = (1.0 + nu) * alpha * dT * L / sn
            slip = optimize.brentq(lambda d: coulomb(dT, d), *sorted((slip, relieved)), xtol=1e-22, rtol=1e-15)
        history.append((dT, stress(dT, slip), slip))
    return history


@REQ
def test_jointed_block_slip_onset_known_value():
    # theta = 60, phi = 30, c = 1 MPa, rigid joint: P_slip = c / (cos^2 60 (tan 60 - tan 30))
    # = 1e6 / (0.25 * 1.1547005) = 3.4641016 MPa; dT_slip = P (1 - nu) / (E alpha) = 3.4641016e6 * 0.75 / 1e5
    # = 25.980762 K
    args = dict(joint_angle_deg=60.0, cohesion=1e6, friction_deg=30.0, width=4.0, **ROCK)
    assert heat.jointed_block_slip_onset(**args) == approx(25.980762, rel=1e-7)
    res = heat.jointed_block_heating(dT=np.array([10.0, 25.980762, 60.0]), **args)
    # sticking: the laterally held block (E alpha dT / (1 - nu)); slipping: stress held at -P_slip
    np.testing.assert_allclose(res["sxx"], [-1e6 / 0.75, -3.4641016e6, -3.4641016e6], rtol=1e-7)
    # on the joint at onset: sigma_n = S cos^2 = -0.8660254 MPa, tau = P sin cos = 1.5 MPa
    # = c + 0.8660254 tan 30 = 1 + 0.5 MPa
    assert res["sigma_n"][1] == approx(-0.8660254e6, rel=1e-7)
    assert res["tau"][1] == approx(1.5e6, rel=1e-7)
    # slip beyond onset: (1 + nu) alpha (dT - dT_slip) L / sin 60 = 1.25e-5 * 34.019238 * 4 / 0.8660254
    assert res["slip"][0] == 0.0
    assert res["slip"][2] == approx(1.25e-5 * 34.019238 * 4.0 / 0.8660254, rel=1e-7)
    # szz = nu S - E alpha dT throughout
    np.testing.assert_allclose(res["szz"], 0.25 * res["sxx"] - 1e5 * np.array([10.0, 25.980762, 60.0]), rtol=1e-14)


@REQ
@pytest.mark.parametrize("theta_deg,kn,ks", [(60.0, math.inf, math.inf), (50.0, 2e9, 5e8), (-70.0, 1e10, 1e9)])
def test_jointed_block_matches_an_incremental_coulomb_calculation(theta_deg, kn, ks):
    args = dict(cohesion=5e5, friction_deg=35.0, width=3.0)
    history = jointed_incremental(80.0, theta_deg=theta_deg, c=args["cohesion"], phi_deg=args["friction_deg"],
                                  L=args["width"], kn=kn, ks=ks)
    dT = np.array([h[0] for h in history])
    res = heat.jointed_block_heating(dT=dT, joint_angle_deg=theta_deg, kn=kn, ks=ks, **args, **ROCK)
    np.testing.assert_allclose(res["sxx"], [h[1] for h in history], rtol=1e-12)
    np.testing.assert_allclose(res["slip"], [h[2] for h in history], rtol=1e-10, atol=1e-18)
    assert 0.0 < res["dT_slip"] < 80.0      # the case crosses onset
    # the onset lies between the last sticking and the first slipping increment
    slipping = np.array([h[2] != 0.0 for h in history])
    first = int(np.argmax(slipping))
    assert dT[first - 1] <= res["dT_slip"] <= dT[first]


@REQ
def test_jointed_block_that_cannot_slip_and_bad_input():
    # |theta| <= phi: friction alone holds the joint whatever the heating
    args = dict(joint_angle_deg=20.0, cohesion=0.0, friction_deg=30.0, width=2.0, **ROCK)
    assert heat.jointed_block_slip_onset(**args) == math.inf
    res = heat.jointed_block_heating(dT=np.array([0.0, 500.0]), **args)
    np.testing.assert_array_equal(res["slip"], 0.0)
    assert res["sxx"][1] == approx(-5e7 / 0.75, rel=1e-14)
    with pytest.raises(ValueError, match="only heating"):
        heat.jointed_block_heating(dT=-1.0, **args)
    with pytest.raises(ValueError, match="joint_angle_deg"):
        heat.jointed_block_slip_onset(**dict(args, joint_angle_deg=90.0))
    with pytest.raises(ValueError, match="friction_deg"):
        heat.jointed_block_slip_onset(**dict(args, friction_deg=90.0))
    with pytest.raises(ValueError, match="kn"):
        heat.jointed_block_slip_onset(**args, kn=0.0)
    with pytest.raises(ValueError, match="held"):
        heat.block_uniform_heating(dT=1.0, held="y", **ROCK)


@pytest.mark.requirements("REQ-QA-003", "REQ-THERM-008")
def test_radiating_slab_balances_conduction_and_radiation():
    Ts = heat.radiating_slab_surface_temperature(T1=600.0, T_inf=300.0, k=3.0, L=1.0, emissivity=0.8)
    # Independently: the conducted and the radiated fluxes agree at Ts, and Ts lies between the two.
    conducted = 3.0 * (600.0 - Ts) / 1.0
    radiated = 0.8 * 5.670374419e-8 * (Ts ** 4 - 300.0 ** 4)
    assert 300.0 < Ts < 600.0
    assert conducted == pytest.approx(radiated, rel=1e-12, abs=0)
    # A black face to cold surroundings of a thin, very conductive slab is near T1; a poor emitter too.
    assert heat.radiating_slab_surface_temperature(T1=600.0, T_inf=300.0, k=1e6, L=1.0, emissivity=1.0) == pytest.approx(600.0, rel=1e-4, abs=0)
    assert heat.radiating_slab_surface_temperature(T1=600.0, T_inf=300.0, k=3.0, L=1.0, emissivity=1e-9) == pytest.approx(600.0, rel=1e-6, abs=0)
    # Known value: 3 (600 - 386.1778) = 642.67 W/m^2 = 0.8 sigma (386.1778^4 - 300^4).
    assert Ts == pytest.approx(386.1778, abs=1e-4)
    with pytest.raises(ValueError):
        heat.radiating_slab_surface_temperature(T1=600.0, T_inf=300.0, k=3.0, L=1.0, emissivity=1.5)

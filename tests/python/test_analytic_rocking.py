"""Rocking and toppling references (verification/analytic/rocking.py) at known values.

Known values are worked by hand in the comments. Consistency checks take independent routes:
the elliptic-function closed forms of the inverted pendulum's fall (scipy.special, not used by the
module), finite differences of the centre of mass's path for the pivot reactions, angular
momentum by cross products for the restitution, and limits with textbook answers.
"""
import math

import numpy as np
import pytest
from scipy.special import ellipj, ellipk, ellipkinc

from analytic import rocking as rk

REQ = pytest.mark.requirements("REQ-QA-003")

# The rocking block: b = 0.25 m, h = 1 m (a 0.5 m x 2 m block), g = 9.81 m/s^2.
# R = sqrt(0.0625 + 1) = 1.0307764064, alpha = atan(0.25) = 0.24497866313 rad,
# p^2 = 3 g / (4 R) = 29.43 / 4.1231056256 = 7.1378234448 1/s^2, p = 2.6716705345 1/s.
ALPHA = math.atan(0.25)
P = 2.6716705344819895
# The toppling block of issue 22: w / h_w = 0.25 on a 40 degree incline, friction 30 degrees.
ISSUE_BLOCK = dict(width=0.25, height=1.0, beta_deg=40.0)


def fall_time_elliptic(chi0, chi, p):
    """Time for chi'' = p^2 sin chi from rest at chi0 to chi, in closed form: with u = chi/2,
    cos u = cos u0 cos w, then w = pi/2 - v, the energy integral becomes the incomplete elliptic
    integral of the first kind, t = (1/p) [K(m) - F(v1 | m)], m = cos^2(chi0/2), and the addition
    formula K - F(v1) = F(v') with tan v' = 1 / (sqrt(1 - m) tan v1) removes the cancellation:
    tan v' = sqrt(sin((chi+chi0)/2) sin((chi-chi0)/2)) / (sin(chi0/2) cos(chi/2))."""
    tan_v = math.sqrt(math.sin(0.5 * (chi + chi0)) * math.sin(0.5 * (chi - chi0))) / (
        math.sin(0.5 * chi0) * math.cos(0.5 * chi))
    return ellipkinc(math.atan(tan_v), math.cos(0.5 * chi0) ** 2) / p


def fall_angle_jacobi(t, chi0, p):
    """chi(t) of the same fall by inverting it: cos(chi/2) = cos(chi0/2) sn(K(m) - p t | m)."""
    m = math.cos(0.5 * chi0) ** 2
    sn, _, _, _ = ellipj(ellipk(m) - p * np.asarray(t), m)
    return 2.0 * np.arccos(math.cos(0.5 * chi0) * sn)


# ---------------------------------------------------------------- rocking: parameters


@REQ
def test_block_parameters_known_values():
    radius, alpha = rk.block_radius_and_slenderness(b=0.25, h=1.0)
    assert radius == pytest.approx(1.0307764064, rel=1e-10, abs=0)
    assert alpha == pytest.approx(0.24497866313, rel=1e-10, abs=0)
    # I_O by parallel axes: m ((2b)^2 + (2h)^2) / 12 + m R^2 = 2 * (0.25 + 4) / 12 + 2 * 1.0625 = 2.8333333 (m = 2)
    assert rk.rectangle_corner_inertia(mass=2.0, b=0.25, h=1.0) == pytest.approx(2.8333333333, rel=1e-10, abs=0)
    p = rk.rectangle_frequency_parameter(g=9.81, R=radius)
    assert p == pytest.approx(P, rel=1e-12, abs=0)
    assert rk.frequency_parameter(mass=2.0, g=9.81, R=radius, inertia_about_corner=2.8333333333333) == \
        pytest.approx(P, rel=1e-12, abs=0)
    # Another shape: a thin rod of length L = 2 m on its end, R = 1 m, I_O = m L^2 / 3 = 4/3 (m = 1):
    # p^2 = 9.81 * 1 / (4/3) = 7.3575, p = 2.7124712
    assert rk.frequency_parameter(mass=1.0, g=9.81, R=1.0, inertia_about_corner=4.0 / 3.0) == \
        pytest.approx(2.7124712, rel=1e-7, abs=0)


@REQ
def test_housner_period_known_values():
    # theta0 / alpha = 1/2: T p = 4 arccosh 2 = 4 ln(2 + sqrt 3) = 4 * 1.3169578969 = 5.2678315877
    # theta0 / alpha = 3/4: T p = 4 arccosh 4 = 4 ln(4 + sqrt 15) = 4 * 2.0634370689 = 8.2537482756
    assert rk.housner_period(theta0=0.5 * ALPHA, alpha=ALPHA, p=1.0) == pytest.approx(5.2678315877, rel=1e-10, abs=0)
    assert rk.housner_period(theta0=-0.75 * ALPHA, alpha=ALPHA, p=2.0) == pytest.approx(8.2537482756 / 2, rel=1e-10, abs=0)
    # it is the quarter period of theta = alpha - (alpha - theta0) cosh(p t), which reaches 0 at T/4
    quarter = rk.housner_period(theta0=0.3, alpha=0.4, p=P) / 4.0
    assert 0.4 - (0.4 - 0.3) * math.cosh(P * quarter) == pytest.approx(0.0, abs=1e-14)


# ---------------------------------------------------------------- rocking: exact period


@REQ
@pytest.mark.parametrize("alpha", [0.05, ALPHA, 0.8, 1.3])
def test_exact_period_is_the_elliptic_closed_form(alpha):
    # The quadrature against the incomplete elliptic integral, from near rest (1e-4) to near
    # overturning (0.99). Beyond 0.99 the elliptic form itself loses digits (m -> 1 with
    # 1 - m = sin^2(phi0/2) no longer resolved), not the quadrature.
    for ratio in (1e-4, 0.01, 0.1, 0.5, 0.9, 0.99):
        theta0 = ratio * alpha
        exact = 4.0 * fall_time_elliptic(alpha - theta0, alpha, P)
        assert rk.rocking_period(theta0=theta0, alpha=alpha, p=P) == pytest.approx(exact, rel=1e-12, abs=0), ratio


@REQ
@pytest.mark.parametrize("alpha", [0.05, ALPHA, 0.8, 1.3])
def test_linearised_period_is_short_by_at_most_alpha_squared_over_12(alpha):
    # Housner's linearisation is in alpha, not in the amplitude. As theta0 -> 0 both periods
    # follow a constant angular acceleration from theta0 to 0, p^2 sin alpha (exact) against p^2 alpha
    # (linearised), so T / T_H -> sqrt(alpha / sin alpha) = 1 + alpha^2/12 + ...; as theta0 -> alpha
    # both spend ever longer near the top, where both equations agree, and T / T_H -> 1.
    # In between the excess falls monotonically.
    bound = math.sqrt(alpha / math.sin(alpha)) - 1.0
    ratios = [1e-6, 1e-3, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 0.9999]
    excess = np.array([rk.rocking_period(theta0=r * alpha, alpha=alpha, p=P) /
                       rk.housner_period(theta0=r * alpha, alpha=alpha, p=P) - 1.0 for r in ratios])
    assert np.all(excess > 0.0) and np.all(excess <= bound)
    assert np.all(np.diff(excess) < 0.0)
    assert excess[0] == pytest.approx(bound, rel=1e-5, abs=0)
    assert excess[-1] < 0.03 * bound


@REQ
@pytest.mark.parametrize("alpha", [0.05, 0.1, ALPHA, 0.5])
def test_exact_period_to_second_order_in_alpha(alpha):
    # phi = alpha - theta: phi'' = p^2 sin phi, and with sin phi = phi - phi^3/6 the energy gives
    # phi' = p sqrt(phi^2 - phi0^2) (1 - (phi^2 + phi0^2)/24 + ...). With phi = phi0 cosh u the quarter period is
    #   (1/p) [U + (phi0^2/24) (3U/2 + sinh U cosh U / 2)],   cosh U = alpha / phi0 = 1 / (1 - r),  r = theta0 / alpha,
    # whose first term is Housner's. So
    #   T / T_H = 1 + alpha^2 (1 - r)^2 (3 U + sinh U cosh U) / (48 U) + O(alpha^4)
    # (-> 1 + alpha^2/12 as r -> 0; 1 + 0.029325 alpha^2 at r = 1/2, where U = ln(2 + sqrt 3), sinh U = sqrt 3).
    # The next term is at most alpha^4 / 160 (its r -> 0 value, from sqrt(alpha / sin alpha)); alpha^6 terms
    # bring it to alpha^4 / 157 at alpha = 0.5, so alpha^4 / 150 bounds it here.
    for ratio in (1e-3, 0.01, 0.1, 0.5, 0.9, 0.99):
        U = math.acosh(1.0 / (1.0 - ratio))
        second_order = alpha ** 2 * (1.0 - ratio) ** 2 * (3.0 * U + math.sinh(U) * math.cosh(U)) / (48.0 * U)
        excess = rk.rocking_period(theta0=ratio * alpha, alpha=alpha, p=P) / rk.housner_period(
            theta0=ratio * alpha, alpha=alpha, p=P) - 1.0
        assert abs(excess - second_order) <= alpha ** 4 / 150.0, ratio
    assert (3.0 * math.log(2.0 + math.sqrt(3.0)) + 2.0 * math.sqrt(3.0)) / (
        4.0 * 48.0 * math.log(2.0 + math.sqrt(3.0))) == pytest.approx(0.029325, rel=1e-4, abs=0)


@REQ
@pytest.mark.parametrize("alpha", [0.05, 0.1, ALPHA, 0.5])
def test_near_overturning_the_periods_differ_by_a_constant(alpha):
    # Released ever nearer the top, both periods grow like (4/p) ln(1 / (alpha - theta0)) at the same
    # rate (both equations are theta'' = p^2 (theta - alpha) there), so their difference tends to a
    # constant: with cosh U = 1/(1 - r) -> inf, (1 - r)^2 sinh U cosh U -> 1 in the expansion of the test
    # above, T / T_H - 1 -> alpha^2 / (48 U) and T - T_H -> (4 U / p) alpha^2 / (48 U) = alpha^2 / (12 p),
    # to O(alpha^4) (0.0012 alpha^4 / p at every alpha here, so alpha^4 / 500 bounds it).
    # (Much nearer the top than 1 - 1e-6, theta0 = r alpha itself loses the digits of alpha - theta0.)
    theta0 = (1.0 - 1e-6) * alpha
    difference = rk.rocking_period(theta0=theta0, alpha=alpha, p=P) - rk.housner_period(theta0=theta0, alpha=alpha, p=P)
    assert abs(difference * P - alpha ** 2 / 12.0) <= alpha ** 4 / 500.0


@REQ
def test_small_amplitude_limit():
    # Near theta = 0 the equation is theta'' = -p^2 sin alpha + p^2 cos alpha theta. Expanding the
    # energy integral to first order in theta0:
    #   T = 4 sqrt(2 theta0 / (p^2 sin alpha)) (1 + (5/12) theta0 cot alpha + O(theta0^2)),
    # (integral_0^theta0 (theta0 + theta) (theta0 - theta)^(-1/2) dtheta = (10/3) theta0^(3/2)).
    # So T -> 0 like sqrt(theta0): the smaller the rocking, the faster.
    for ratio in (1e-4, 1e-3):
        theta0 = ratio * ALPHA
        first_order = theta0 / math.tan(ALPHA)
        limit = 4.0 * math.sqrt(2.0 * theta0 / (P * P * math.sin(ALPHA))) * (1.0 + 5.0 / 12.0 * first_order)
        T = rk.rocking_period(theta0=theta0, alpha=ALPHA, p=P)
        assert abs(T / limit - 1.0) <= 2.0 * first_order ** 2


# ---------------------------------------------------------------- rocking: speed and restitution


@REQ
def test_angular_velocity_known_values():
    # theta0 = alpha / 2: omega^2 at theta = 0 is 2 p^2 (cos(alpha/2) - cos alpha),
    # cos alpha = h / R = 1 / 1.0307764064 = 0.9701425001, cos(alpha/2) = sqrt((1 + cos alpha)/2) = 0.9925075567,
    # omega^2 = 2 * 7.1378234448 * 0.0223650566 = 0.3192756498, omega = 0.5650448211 rad/s
    w = rk.rocking_angular_velocity(np.array([0.0, 0.5 * ALPHA, -0.5 * ALPHA, 0.25 * ALPHA, -0.25 * ALPHA]),
                                    theta0=0.5 * ALPHA, alpha=ALPHA, p=P)
    assert w[0] == pytest.approx(0.5650448211, rel=1e-9, abs=0)
    assert w[1] == 0.0 and w[2] == 0.0
    assert w[3] == w[4] > 0.0
    with pytest.raises(ValueError):
        rk.rocking_angular_velocity(np.array([0.6 * ALPHA]), theta0=0.5 * ALPHA, alpha=ALPHA, p=P)


@REQ
def test_housner_restitution_known_values():
    # b / h = 0.25: sin^2 alpha = b^2 / R^2 = 1/17; r = (1 - 1.5/17)^2 = (31/34)^2 = 961/1156 = 0.8313148789
    assert rk.housner_restitution(alpha=ALPHA) == pytest.approx(961.0 / 1156.0, rel=1e-14, abs=0)
    # a square block, alpha = 45 deg: (1 - 0.75)^2 = 0.0625
    assert rk.housner_restitution(alpha=math.pi / 4) == pytest.approx(0.0625, rel=1e-14, abs=0)
    # it stops dead at sin^2 alpha = 2/3 (b / h = sqrt 2)
    assert rk.housner_restitution(alpha=math.atan(math.sqrt(2.0))) == pytest.approx(0.0, abs=1e-30)


@REQ
@pytest.mark.parametrize("b,h,inertia_centre", [(0.25, 1.0, None), (0.6, 1.0, None), (0.25, 1.0, 0.2)])
def test_housner_restitution_is_angular_momentum_about_the_striking_corner(b, h, inertia_centre):
    # Before impact the block (m = 1) turns about the corner A = (b, 0) with omega1 = 1; its centre
    # G = (0, h) moves at v = omega1 z x (G - A). Angular momentum about the corner B = (-b, 0) that
    # strikes is I_G omega1 + m (G - B) x v, and after the plastic impact I_B omega2 carries it all.
    inertia_centre = (4 * b * b + 4 * h * h) / 12.0 if inertia_centre is None else inertia_centre
    G, A, B = np.array([0.0, h]), np.array([b, 0.0]), np.array([-b, 0.0])
    r_a = G - A
    v = np.array([-r_a[1], r_a[0]])
    r_b = G - B
    momentum = inertia_centre + (r_b[0] * v[1] - r_b[1] * v[0])
    inertia_corner = inertia_centre + b * b + h * h
    omega2 = momentum / inertia_corner
    radius, alpha = rk.block_radius_and_slenderness(b=b, h=h)
    kappa = inertia_corner / radius ** 2
    assert rk.housner_restitution(alpha=alpha, corner_inertia_ratio=kappa) == pytest.approx(omega2 ** 2, rel=1e-13, abs=0)


# ---------------------------------------------------------------- rocking: history


@REQ
@pytest.mark.parametrize("ratio", [0.05, 0.5, 0.99])
def test_rocking_history_conserves_energy(ratio):
    # Energy per unit I_O: omega^2 / 2 + p^2 cos(alpha - |theta|), over ten periods and twenty impacts.
    # The integrator's local error is held to 1e-12 relative; energy stays within 1e-12 of its start.
    theta0 = ratio * ALPHA
    T = rk.rocking_period(theta0=theta0, alpha=ALPHA, p=P)
    t = np.linspace(0.0, 10.0 * T, 8001)
    theta, omega = rk.rocking_history(t, theta0=theta0, alpha=ALPHA, p=P)
    energy = 0.5 * omega ** 2 + P * P * np.cos(ALPHA - np.abs(theta))
    start = P * P * math.cos(ALPHA - theta0)
    assert np.max(np.abs(energy / start - 1.0)) <= 1e-12
    # and it never swings beyond its amplitude (an energy error of 1e-12 moves the turning point by
    # 1e-12 / tan(alpha - theta0) of alpha, below 1e-11 alpha here)
    assert np.max(np.abs(theta)) <= theta0 + 1e-11 * ALPHA


@REQ
def test_rocking_history_is_the_jacobi_closed_form():
    # First quarter: phi = alpha - theta falls from phi0 = alpha - theta0 as cos(phi/2) = cos(phi0/2) sn(K - p t | m).
    # The next three quarters are its mirror images: theta(T/2 - t) = -theta(t), theta(T - t) = theta(t).
    theta0 = 0.5 * ALPHA
    T = rk.rocking_period(theta0=theta0, alpha=ALPHA, p=P)
    t = np.linspace(0.0, T / 4.0, 401)
    closed = ALPHA - fall_angle_jacobi(t, ALPHA - theta0, P)
    for shift, sign, reverse in ((0.0, 1.0, False), (T / 2.0, -1.0, True), (T / 2.0, -1.0, False), (T, 1.0, True),
                                 (5.0 * T, 1.0, False)):
        times = shift - t if reverse else shift + t
        theta, _ = rk.rocking_history(times, theta0=theta0, alpha=ALPHA, p=P)
        np.testing.assert_allclose(theta, sign * closed, rtol=0, atol=1e-11 * ALPHA)
    theta, omega = rk.rocking_history(np.array([T / 4.0, T / 2.0, T]), theta0=theta0, alpha=ALPHA, p=P)
    np.testing.assert_allclose(theta, [0.0, -theta0, theta0], rtol=0, atol=1e-11 * ALPHA)
    omega_max = rk.rocking_angular_velocity(0.0, theta0=theta0, alpha=ALPHA, p=P)
    assert omega[0] == pytest.approx(-omega_max, rel=1e-10, abs=0)
    # and a release to the other side is the mirror image
    mirrored, _ = rk.rocking_history(t, theta0=-theta0, alpha=ALPHA, p=P)
    np.testing.assert_allclose(mirrored, -closed, rtol=0, atol=1e-11 * ALPHA)


@REQ
@pytest.mark.parametrize("ratio", [0.1, 0.9])
def test_rocking_history_period_is_the_quadrature_period(ratio):
    # upward zero crossings of theta, located by linear interpolation between samples 1e-4 T apart
    # (the interpolation error is below (dt)^2 |theta''| / (8 |theta'|) ~ 1e-9 T)
    theta0 = ratio * ALPHA
    T = rk.rocking_period(theta0=theta0, alpha=ALPHA, p=P)
    t = np.linspace(0.0, 6.0 * T, 60001)
    theta, _ = rk.rocking_history(t, theta0=theta0, alpha=ALPHA, p=P)
    i = np.nonzero((theta[:-1] < 0.0) & (theta[1:] >= 0.0))[0]
    crossings = t[i] - theta[i] * (t[i + 1] - t[i]) / (theta[i + 1] - theta[i])
    assert len(crossings) == 6
    np.testing.assert_allclose(np.diff(crossings), T, rtol=1e-9)
    assert crossings[0] == pytest.approx(0.75 * T, rel=1e-9, abs=0)


@REQ
def test_rocking_rejects_bad_input():
    with pytest.raises(ValueError):  # overturns
        rk.rocking_period(theta0=ALPHA, alpha=ALPHA, p=P)
    with pytest.raises(ValueError):  # stands still
        rk.housner_period(theta0=0.0, alpha=ALPHA, p=P)
    with pytest.raises(ValueError):
        rk.rocking_history(np.array([-1.0]), theta0=0.1, alpha=ALPHA, p=P)
    with pytest.raises(ValueError):
        rk.rocking_period(theta0=0.1, alpha=ALPHA, p=0.0)
    with pytest.raises(ValueError):
        rk.block_radius_and_slenderness(b=0.0, h=1.0)
    with pytest.raises(ValueError):
        rk.housner_restitution(alpha=2.0)


# ---------------------------------------------------------------- toppling: pivot reactions


@REQ
def test_pivot_reaction_at_the_start_of_toppling_from_rest():
    """The block of issue 22 (w = 0.25 m, h_w = 1 m, beta = 40 deg, m = 1000 kg, g = 9.81), flat on the
    incline at rest: delta = atan(0.25) = 14.0362 deg, so chi0 = beta - delta = 25.9638 deg > 0 and it
    topples from psi0 = 0. At rest psi' = 0, and R psi'' = R p^2 sin chi0 = (3 g / 4) sin chi0:

        F_n = m g (cos beta + 3/4 sin chi0 sin delta)
            = 9810 (0.7660444431 + 0.75 * 0.4378025109 * 0.2425356250) = 9810 * 0.8456814723 = 8296.1352 N
        F_t = m g (3/4 sin chi0 cos delta - sin beta)
            = 9810 (0.75 * 0.4378025109 * 0.9701425001 - 0.6427876097) = 9810 * (-0.3242394928) = -3180.7894 N

    (up-slope: friction holds the corner). Demand |F_t| / F_n = 0.3834061682 < tan 30 deg = 0.5773502692,
    although tan beta = 0.839 > tan phi: the static sliding test does not apply to a pivoting block.
    Eliminating the angles with tan delta = t = w / h_w gives the demand as
    (tan beta (4 t^2 + 1) + 3 t) / (t^2 + 4 + 3 t tan beta) = (0.8390996 * 1.25 + 0.75) / (4.0625 + 0.6292247).
    """
    normal, along = rk.toppling_pivot_reaction(0.0, g=9.81, mass=1000.0, **ISSUE_BLOCK)
    assert normal == pytest.approx(8296.1352, rel=1e-8, abs=0)
    assert along == pytest.approx(-3180.7894, rel=1e-8, abs=0)
    demand = rk.toppling_friction_demand(0.0, **ISSUE_BLOCK)
    tb, t = math.tan(math.radians(40.0)), 0.25
    assert demand == pytest.approx((tb * (4 * t * t + 1) + 3 * t) / (t * t + 4 + 3 * t * tb), rel=1e-13, abs=0)
    assert demand == pytest.approx(0.3834061682, rel=1e-9, abs=0)
    # and a wider block on a steeper incline: t = 0.5, beta = 45 deg: (1 * 2 + 1.5) / (4.25 + 1.5) = 0.6086956522
    assert rk.toppling_friction_demand(0.0, width=0.5, height=1.0, beta_deg=45.0) == pytest.approx(
        3.5 / 5.75, rel=1e-13, abs=0)


@REQ
@pytest.mark.parametrize("beta_deg", [0.0, 10.0, 30.0])
def test_block_balanced_on_its_corner_carries_its_weight(beta_deg):
    # psi0 = delta - beta puts the centre of mass over the pivot: psi' = psi'' = 0, so the corner carries the
    # whole weight, F_n = m g cos beta normal and F_t = -m g sin beta along (on a flat base F_t = 0, F_n = m g).
    width, height = 0.6, 1.0
    psi0 = math.atan(0.6) - math.radians(beta_deg)
    normal, along = rk.toppling_pivot_reaction(psi0, width=width, height=height, beta_deg=beta_deg, g=9.81,
                                               mass=500.0, psi0=psi0)
    assert normal == pytest.approx(500.0 * 9.81 * math.cos(math.radians(beta_deg)), rel=1e-13, abs=0)
    assert along == pytest.approx(-500.0 * 9.81 * math.sin(math.radians(beta_deg)), rel=1e-13, abs=1e-10)
    assert rk.toppling_angular_velocity(psi0, width=width, height=height, beta_deg=beta_deg, g=9.81, psi0=psi0) == 0.0
    assert rk.toppling_angular_acceleration(psi0, width=width, height=height, beta_deg=beta_deg, g=9.81) == \
        pytest.approx(0.0, abs=1e-14)
    with pytest.raises(ValueError):  # balanced: it never starts to fall
        rk.toppling_time(0.5, width=width, height=height, beta_deg=beta_deg, g=9.81, psi0=psi0)


@REQ
def test_thin_rod_falls_like_the_hinged_rod_of_the_textbooks():
    # A rod of length L hinged at its foot, falling from upright on a flat base (beta = 0): with
    # psi'' = (3g/2L) sin psi and psi'^2 = (3g/L)(1 - cos psi) the reactions are
    #   F_n = (m g / 4) (1 - 3 cos psi)^2,   F_t = (3/4) m g sin psi (3 cos psi - 2),
    # (the horizontal reaction reverses at cos psi = 2/3, the normal one touches zero at cos psi = 1/3).
    # A 1e-9-wide block released from its balance point is that rod to O(1e-9).
    rod = dict(width=1e-9, height=2.0, beta_deg=0.0)
    psi = np.linspace(1e-9, 1.5, 31)
    normal, along = rk.toppling_pivot_reaction(psi, g=10.0, mass=1.0, psi0=1e-9, **rod)
    np.testing.assert_allclose(normal, 2.5 * (1.0 - 3.0 * np.cos(psi)) ** 2, rtol=0, atol=1e-7)
    np.testing.assert_allclose(along, 7.5 * np.sin(psi) * (3.0 * np.cos(psi) - 2.0), rtol=0, atol=1e-7)
    # on an incline, at the start: F_t = m g sin beta (3/4 - 1) = -m g sin beta / 4, F_n = m g cos beta
    normal, along = rk.toppling_pivot_reaction(0.0, g=10.0, mass=1.0, width=1e-9, height=2.0, beta_deg=30.0)
    assert normal == pytest.approx(10.0 * math.cos(math.radians(30.0)), rel=1e-8, abs=0)
    assert along == pytest.approx(-2.5 * 0.5, rel=1e-8, abs=0)


@REQ
def test_pivot_reaction_is_newton_for_the_centre_of_mass_path():
    # Independent route: the centre of mass's path from toppling_rotation, (x, y) = R (-sin(delta - psi),
    # cos(delta - psi)) from the pivot, differentiated twice by the five-point stencil (truncation
    # ~ h^4 f''''''/90 ~ 1e-10 m/s^2 at h = 2 ms; the integrator's 1e-12 error amplified by 16/(3 h^2) ~ 1.3e-6
    # m/s^2), gives m a - m g = the pivot force, to 1e-5 of m g.
    g, mass, h = 9.81, 1000.0, 2e-3
    delta, R, beta = math.atan(0.25), 0.5 * math.hypot(0.25, 1.0), math.radians(40.0)
    landing = rk.toppling_time(math.pi / 2, g=g, **ISSUE_BLOCK)
    centres = np.linspace(0.05, 0.9, 12) * landing
    stencil = np.array([-2, -1, 0, 1, 2]) * h
    psi, _ = rk.toppling_rotation(centres[:, None] + stencil[None, :], g=g, **ISSUE_BLOCK)
    x, y = -R * np.sin(delta - psi), R * np.cos(delta - psi)
    weights = np.array([-1.0, 16.0, -30.0, 16.0, -1.0]) / (12.0 * h * h)
    ax, ay = x @ weights, y @ weights
    force_t = mass * (ax - g * math.sin(beta))
    force_n = mass * (ay + g * math.cos(beta))
    normal, along = rk.toppling_pivot_reaction(psi[:, 2], g=g, mass=mass, **ISSUE_BLOCK)
    np.testing.assert_allclose(normal, force_n, rtol=0, atol=1e-5 * mass * g)
    np.testing.assert_allclose(along, force_t, rtol=0, atol=1e-5 * mass * g)


# ---------------------------------------------------------------- toppling: motion


@REQ
def test_toppling_rotation_time_and_speed_agree():
    g = 9.81
    landing = rk.toppling_time(math.pi / 2, g=g, **ISSUE_BLOCK)
    t = np.linspace(0.0, landing, 201)
    psi, rate = rk.toppling_rotation(t, g=g, **ISSUE_BLOCK)
    # the Jacobi closed form of the fall, chi = psi + beta - delta from chi0 = beta - delta
    shift = math.radians(40.0) - math.atan(0.25)
    p = math.sqrt(0.75 * g / (0.5 * math.hypot(0.25, 1.0)))
    np.testing.assert_allclose(psi, fall_angle_jacobi(t, shift, p) - shift, rtol=0, atol=1e-11)
    assert psi[-1] == pytest.approx(math.pi / 2, rel=1e-11, abs=0)
    # speed from energy and time by quadrature, at the integrated angles
    np.testing.assert_allclose(rk.toppling_angular_velocity(psi, g=g, **ISSUE_BLOCK), rate, rtol=1e-10)
    np.testing.assert_allclose(rk.toppling_time(psi[1:], g=g, **ISSUE_BLOCK), t[1:], rtol=1e-10)
    # landing (0.608 s for this block): the elliptic fall from chi0 to pi/2 + chi0
    assert landing == pytest.approx(fall_time_elliptic(shift, math.pi / 2 + shift, p), rel=1e-12, abs=0)
    with pytest.raises(ValueError):
        rk.toppling_rotation(np.array([landing * 1.001]), g=g, **ISSUE_BLOCK)


@REQ
def test_liftoff_and_slip_of_the_issue_block():
    # F_n falls as the centripetal term grows and reaches 0 (at 0.583 rad, 33.4 deg); before that the
    # demand |F_t| / F_n rises through tan 30 deg (at 0.438 rad, 25.1 deg). So the block topples without
    # slip only up to 0.438 rad; beyond, its corner slides. Both angles are checked by what defines them.
    liftoff = rk.toppling_liftoff_angle(**ISSUE_BLOCK)
    slip = rk.toppling_slip_angle(phi_deg=30.0, **ISSUE_BLOCK)
    assert 0.0 < slip < liftoff < math.pi / 2
    normal, _ = rk.toppling_pivot_reaction(np.array([liftoff - 1e-6, liftoff, liftoff + 1e-6]), g=9.81, mass=1.0,
                                           **ISSUE_BLOCK)
    assert normal[0] > 0.0 and abs(normal[1]) < 1e-12 and normal[2] < 0.0
    assert np.all(rk.toppling_pivot_reaction(np.linspace(0.0, liftoff - 1e-6, 1001), g=9.81, mass=1.0,
                                             **ISSUE_BLOCK)[0] > 0.0)
    tan_phi = math.tan(math.radians(30.0))
    assert rk.toppling_friction_demand(slip, **ISSUE_BLOCK) == pytest.approx(tan_phi, rel=1e-12, abs=0)
    demand, where = rk.toppling_largest_friction_demand(psi_end=slip, **ISSUE_BLOCK)
    assert demand == pytest.approx(tan_phi, rel=1e-12, abs=0) and where == pytest.approx(slip, rel=1e-12, abs=0)
    assert np.all(rk.toppling_friction_demand(np.linspace(0.0, slip - 1e-6, 1001), **ISSUE_BLOCK) < tan_phi)
    # the demand first falls from 0.3834 (to 0.283 near 0.23 rad), then rises: the start is the largest up to 0.3
    demand, where = rk.toppling_largest_friction_demand(psi_end=0.3, **ISSUE_BLOCK)
    assert demand == pytest.approx(0.3834061682, rel=1e-9, abs=0) and where == 0.0
    assert rk.topples_without_slip(phi_deg=30.0, psi_end=slip - 1e-6, **ISSUE_BLOCK)
    assert not rk.topples_without_slip(phi_deg=30.0, psi_end=slip + 1e-6, **ISSUE_BLOCK)
    assert rk.toppling_largest_friction_demand(psi_end=0.6, **ISSUE_BLOCK) == (math.inf, liftoff)
    # a corner without enough friction slips at once: demand 0.6087 at the start against tan 30 deg
    assert rk.toppling_slip_angle(width=0.5, height=1.0, beta_deg=45.0, phi_deg=30.0) == 0.0


@REQ
def test_interior_maximum_of_the_demand_is_found():
    # The rod balanced upright on a flat base (test above): for cos psi = c > 2/3 the demand is
    # D = 3 s (3c - 2) / (1 - 3c)^2, s = sin psi. d/dpsi [s (2 - 3c) / (1 - 3c)^2] has the numerator
    # (1 - 3c) [(3 + 2c - 6c^2)(1 - 3c) - 6 (1 - c^2)(2 - 3c)] = (1 - 3c)(11 c - 9), so the maximum is at
    # cos psi = 9/11 (psi = 0.6125547383 rad), s = sqrt(40)/11, |3c - 2| = 5/11, (1 - 3c)^2 = 256/121:
    # D_max = 3 (sqrt(40)/11)(5/11)(121/256) = 15 sqrt(10) / 128 = 0.3705794133.
    rod = dict(width=1e-9, height=2.0, beta_deg=0.0, psi0=1e-9)
    demand, where = rk.toppling_largest_friction_demand(psi_end=0.8, **rod)
    # (the 16001-sample scan alone is 1e-9 off in D and 2e-5 rad in psi: the refinement matters)
    assert demand == pytest.approx(15.0 * math.sqrt(10.0) / 128.0, rel=1e-12, abs=0)
    assert where == pytest.approx(math.acos(9.0 / 11.0), abs=1e-7)
    # so a friction angle of 21 deg (tan = 0.3839) holds the foot up to 0.8 rad, and 20 deg (0.3640) does not
    assert rk.toppling_slip_angle(phi_deg=21.0, psi_end=0.8, **rod) == math.inf
    assert rk.topples_without_slip(phi_deg=21.0, psi_end=0.8, **rod)
    assert rk.toppling_slip_angle(phi_deg=20.0, psi_end=0.8, **rod) < math.acos(9.0 / 11.0)
    assert not rk.topples_without_slip(phi_deg=20.0, psi_end=0.8, **rod)


# ---------------------------------------------------------------- static conditions


@REQ
def test_static_conditions_of_goodman_and_bray():
    # stable: beta < phi, w / h > tan beta; slides: beta > phi, w / h > tan beta;
    # topples: beta < phi, w / h < tan beta; both: beta > phi, w / h < tan beta (tan 20 = 0.364, tan 40 = 0.839)
    assert rk.static_mode(width=1.0, height=1.0, beta_deg=20.0, phi_deg=30.0) == "stable"
    assert rk.static_mode(width=1.0, height=1.0, beta_deg=40.0, phi_deg=30.0) == "slides"
    assert rk.static_mode(width=0.3, height=1.0, beta_deg=20.0, phi_deg=30.0) == "topples"
    assert rk.static_mode(width=0.25, height=1.0, beta_deg=40.0, phi_deg=30.0) == "slides and topples"
    # limiting equilibrium holds: tan beta = tan phi does not slide; w / h = tan beta does not topple
    assert not rk.static_slides(beta_deg=30.0, phi_deg=30.0)
    assert rk.static_slides(beta_deg=30.000001, phi_deg=30.0)
    assert not rk.static_topples(width=math.tan(math.radians(30.0)), height=1.0, beta_deg=30.0)
    assert not rk.static_topples(width=1.0, height=1.0, beta_deg=45.0 - 1e-9)
    assert rk.static_topples(width=1.0, height=1.0, beta_deg=45.000001)
    # a block that topples statically also topples by the dynamic functions from psi0 = 0, and one that
    # stands does not
    rk.toppling_pivot_reaction(0.0, width=0.3, height=1.0, beta_deg=20.0, g=9.81, mass=1.0)
    with pytest.raises(ValueError):
        rk.toppling_pivot_reaction(0.0, width=1.0, height=1.0, beta_deg=40.0, g=9.81, mass=1.0)


@REQ
def test_toppling_rejects_bad_input():
    with pytest.raises(ValueError):  # beyond the landing of the face
        rk.toppling_friction_demand(1.6, **ISSUE_BLOCK)
    with pytest.raises(ValueError):  # before the release
        rk.toppling_friction_demand(0.1, psi0=0.2, **ISSUE_BLOCK)
    with pytest.raises(ValueError):
        rk.toppling_slip_angle(phi_deg=30.0, psi_end=2.0, **ISSUE_BLOCK)
    with pytest.raises(ValueError):
        rk.toppling_rotation(np.array([-0.1]), g=9.81, **ISSUE_BLOCK)
    with pytest.raises(ValueError):
        rk.toppling_time(0.1, width=0.25, height=1.0, beta_deg=95.0, g=9.81)
    with pytest.raises(ValueError):
        rk.static_topples(width=0.0, height=1.0, beta_deg=10.0)


@REQ
@pytest.mark.parametrize("share", [0.25, 0.9])
def test_first_impact_time_is_the_fall_of_the_equation_of_motion(share):
    # Integrated here from I_O theta'' = -m g R sin(alpha - theta) written for the lean
    # phi = theta0 - (rotation towards the face), with I_O = (4/3) m R^2, independent of the
    # quadrature: the time at which the lean reaches zero.
    from scipy.integrate import solve_ivp
    b, h, g = 0.5, 1.0, 9.81
    radius, alpha = math.hypot(b, h), math.atan(b / h)
    theta0 = share * alpha

    def rhs(_, y):
        return [y[1], -0.75 * g / radius * math.sin(alpha - y[0])]

    def landed(_, y):
        return y[0]
    landed.terminal, landed.direction = True, -1
    fall = solve_ivp(rhs, (0.0, 10.0), [theta0, 0.0], events=landed, rtol=1e-12, atol=1e-14, method="DOP853")
    assert rk.rectangle_first_impact_time(theta0=theta0, b=b, h=h, g=g) == pytest.approx(fall.t_events[0][0], rel=1e-9, abs=0)


@REQ
def test_first_impact_time_of_a_slender_block_is_housners_quarter_period():
    # alpha = 0.01: the linearisation's error, ~ alpha^2 / 12, is below 1e-5
    b, h, g = 0.01, 1.0, 9.81
    radius, alpha = math.hypot(b, h), math.atan(b / h)
    p = math.sqrt(3.0 * g / (4.0 * radius))
    assert rk.rectangle_first_impact_time(theta0=0.5 * alpha, b=b, h=h, g=g) == \
        pytest.approx(rk.housner_period(theta0=0.5 * alpha, alpha=alpha, p=p) / 4.0, rel=1e-5, abs=0)

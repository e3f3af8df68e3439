"""Closed-form rigid-block references (verification/analytic/rigid_blocks.py) at known values.

Known values are worked by hand in the comments; limits, continuity and consistency checks use
independent routes (a plain loop of the recurrence, finite differences of the ODE, numerical
peak search), never the function under test rewritten.
"""
import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from analytic import rigid_blocks as rb

REQ = pytest.mark.requirements("REQ-QA-003")

# The benchmark block: 1 m x 1 m x 1 m of rock, 2500 kg, on a joint kn = 1e8 Pa/m, L = 1 m.
# w = sqrt(1e8 / 2500) = 200 rad/s, d = m g / (kn L) = 2500 * 10 / 1e8 = 2.5e-4 m.
BLOCK = dict(mass=2500.0, g=10.0, kn=1e8, contact_length=1.0)
SPRING = dict(mass=2500.0, kn=1e8, contact_length=1.0)
W = 200.0
D = 2.5e-4


def recurrence_loop(n_steps, *, mass, g, kn, contact_length, alpha, dt):
    """The solver's update (NUREG/CR-5429 1.3-21) stepped literally, y_0 = 0, v_{-1/2} = 0."""
    w2 = kn * contact_length / mass
    y, v, out = 0.0, 0.0, [0.0]
    for _ in range(n_steps):
        v = (v * (1.0 - alpha * dt / 2.0) + (g - w2 * y) * dt) / (1.0 + alpha * dt / 2.0)
        y = y + v * dt
        out.append(y)
    return np.array(out)


def continuous_from_initial_velocity(t, v0, *, mass, g, kn, contact_length, alpha):
    """y'' + alpha y' + w^2 y = g, y(0) = 0, y'(0) = v0: y = d + e^{-alpha t/2} (A cos wd t + B sin wd t)
    with A = -d and y'(0) = -alpha A / 2 + wd B = v0, so B = (v0 - alpha d / 2) / wd."""
    w2 = kn * contact_length / mass
    d, wd = g / w2, math.sqrt(w2 - alpha * alpha / 4.0)
    b = (v0 - alpha * d / 2.0) / wd
    return d + np.exp(-alpha * t / 2.0) * (-d * np.cos(wd * t) + b * np.sin(wd * t))


# ---------------------------------------------------------------- known values


@REQ
def test_known_values():
    # resting: N = m g = 2500 * 10 = 25000 N; d = 25000 / (1e8 * 1) = 2.5e-4 m
    assert rb.resting_normal_force(mass=2500.0, g=10.0) == pytest.approx(25000.0, rel=1e-15, abs=0)
    assert rb.resting_settlement(**BLOCK) == pytest.approx(2.5e-4, rel=1e-15, abs=0)
    # 2 m of contact halves it: 25000 / 2e8 = 1.25e-4 m
    assert rb.resting_settlement(mass=2500.0, g=10.0, kn=1e8, contact_length=2.0) == pytest.approx(1.25e-4, rel=1e-15, abs=0)
    # w = sqrt(1e8 / 2500) = 200 rad/s, T = 2 pi / 200 = pi / 100 s
    assert rb.oscillator_frequency(**SPRING) == pytest.approx(200.0, rel=1e-15, abs=0)
    assert rb.oscillator_period(**SPRING) == pytest.approx(math.pi / 100.0, rel=1e-15, abs=0)
    # 45 degrees, phi = 20: 9.81 * sin45 * (1 - tan20) = 9.81 * 0.7071067812 * 0.6360297657 = 4.411958821 m/s^2
    assert rb.incline_acceleration(g=9.81, theta_deg=45, phi_deg=20) == pytest.approx(4.411958821, rel=1e-9, abs=0)
    assert rb.incline_half_acceleration(g=9.81, theta_deg=45, phi_deg=20) == pytest.approx(2.2059794105, rel=1e-9, abs=0)
    # held at 20 degrees: 2500 * 9.81 * sin20 / (1e10 * 1) = 2500 * 9.81 * 0.3420201433 / 1e10 = 8.388044015e-7 m
    assert rb.incline_elastic_slide(mass=2500.0, g=9.81, theta_deg=20.0, ks=1e10, contact_length=1.0) == \
        pytest.approx(8.388044015e-7, rel=1e-9, abs=0)
    # 20 degrees, phi = 30: friction holds
    assert rb.incline_acceleration(g=9.81, theta_deg=20, phi_deg=30) == 0.0
    # damping xi = 40 / (2 * 200) = 0.1: delta = 2 pi * 0.1 / sqrt(0.99) = 0.6283185307 * 1.0050378153 = 0.6314838834
    assert rb.log_decrement(alpha=40.0, **SPRING) == pytest.approx(0.6314838834, rel=1e-9, abs=0)
    # constant normal displacement: post-yield slope ks kn tp ts / (ks + kn tp ts)
    us = np.array([1e-3, 2e-3])
    tau, _ = rb.direct_shear_constant_normal_displacement(us, ks=1e9, kn=1e9, sn0=0, cohesion=2e5, phi_deg=30,
                                                          psi_deg=10)
    k = 1e9 * math.tan(math.radians(30)) * math.tan(math.radians(10))
    assert (tau[1] - tau[0]) / 1e-3 == pytest.approx(1e9 * k / (1e9 + k), rel=1e-9, abs=0)


# ---------------------------------------------------------------- incline


@REQ
def test_incline_with_cohesion():
    # c L / m = 3000 * 1 / 2500 = 1.2 m/s^2 off the frictional 4.411958821: a = 3.211958821
    p = dict(g=9.81, theta_deg=45, phi_deg=20, contact_length=1.0, mass=2500.0)
    assert rb.incline_acceleration(cohesion=3000.0, **p) == pytest.approx(3.211958821, rel=1e-9, abs=0)
    assert rb.incline_slides(cohesion=3000.0, **p)
    # c = 12000 Pa: 12000 / 2500 = 4.8 > 4.41, the joint holds
    assert rb.incline_acceleration(cohesion=12000.0, **p) == 0.0
    assert not rb.incline_slides(cohesion=12000.0, **p)


@REQ
def test_incline_slides_agrees_with_the_sign_of_the_acceleration():
    for theta in np.linspace(1.0, 89.0, 45):
        for phi in (10.0, 25.0, 40.0):
            for c in (0.0, 1000.0):
                p = dict(g=9.81, theta_deg=theta, phi_deg=phi, cohesion=c, contact_length=1.0, mass=2500.0)
                assert rb.incline_slides(**p) == (rb.incline_acceleration(**p) > 0.0)
    # without cohesion the threshold is theta = phi, where the block just sticks
    assert rb.incline_slides(g=9.81, theta_deg=30.01, phi_deg=30)
    assert not rb.incline_slides(g=9.81, theta_deg=29.99, phi_deg=30)
    for phi in (10.0, 25.0, 30.0, 33.3, 45.0, 60.0):
        assert not rb.incline_slides(g=9.81, theta_deg=phi, phi_deg=phi)
        assert rb.incline_acceleration(g=9.81, theta_deg=phi, phi_deg=phi) == 0.0


@REQ
def test_incline_displacement():
    # released at t0 = 0.5 s with a = 4.411958821:
    # x(1) = a * 0.5^2 / 2 = 0.5514948526, x(2) = a * 1.5^2 / 2 = 4.963453674
    t = np.array([0.0, 0.5, 1.0, 2.0])
    x = rb.incline_displacement(t, g=9.81, theta_deg=45, phi_deg=20, t0=0.5)
    np.testing.assert_allclose(x, [0.0, 0.0, 0.5514948526, 4.963453674], rtol=1e-9, atol=0.0)
    # the slope of x against t^2 (t0 = 0) is a / 2
    tt = np.linspace(0.0, 2.0, 21)
    x = rb.incline_displacement(tt, g=9.81, theta_deg=45, phi_deg=20)
    slope = np.polyfit(tt ** 2, x, 1)[0]
    assert slope == pytest.approx(rb.incline_half_acceleration(g=9.81, theta_deg=45, phi_deg=20), rel=1e-12, abs=0)
    # a block that sticks does not move
    assert np.all(rb.incline_displacement(tt, g=9.81, theta_deg=20, phi_deg=30) == 0.0)


# ---------------------------------------------------------------- continuous oscillator


@REQ
def test_undamped_settlement_history_known_points():
    # alpha = 0: y = d (1 - cos w t); at T/4, T/2, T: d, 2 d, 0
    t = np.array([0.0, math.pi / 400.0, math.pi / 200.0, math.pi / 100.0])
    y = rb.oscillator_settlement_history(t, **BLOCK)
    np.testing.assert_allclose(y, [0.0, D, 2.0 * D, 0.0], rtol=1e-12, atol=1e-12 * D)


@REQ
def test_damped_settlement_history_known_points():
    # alpha = 40, w = 200: wd = sqrt(40000 - 400) = 198.9974874; the first peak is at wd t = pi,
    # where y = d (1 + e^{-alpha pi / (2 wd)}) = 2.5e-4 * (1 + e^{-0.31574194}) = 2.5e-4 * 1.72924761 = 4.3231190e-4
    wd = math.sqrt(39600.0)
    y = rb.oscillator_settlement_history(np.array([0.0, math.pi / wd, 10.0]), alpha=40.0, **BLOCK)
    np.testing.assert_allclose(y, [0.0, 4.3231190e-4, D], rtol=1e-7, atol=1e-15)


@REQ
def test_damped_settlement_history_solves_the_equation_of_motion():
    # y'' + alpha y' + w^2 y = g by central finite differences, y(0) = 0, y'(0) = 0 by one-sided ones
    alpha, h = 40.0, 1e-6
    t = np.linspace(0.001, 0.1, 50)

    def y(s):
        return rb.oscillator_settlement_history(s, alpha=alpha, **BLOCK)

    acc = (y(t + h) - 2.0 * y(t) + y(t - h)) / h ** 2
    vel = (y(t + h) - y(t - h)) / (2.0 * h)
    residual = acc + alpha * vel + W ** 2 * y(t) - 10.0
    assert np.max(np.abs(residual)) < 1e-3 * 10.0
    assert y(np.array([0.0]))[0] == 0.0
    # from rest under g: y(h) = g h^2 / 2 + O(h^3) = 5e-12 m
    assert y(np.array([h]))[0] == pytest.approx(5e-12, rel=1e-3, abs=0)


@REQ
def test_oscillator_alpha_to_zero_limit():
    t = np.linspace(0.0, 0.2, 401)
    undamped = D * (1.0 - np.cos(W * t))
    for alpha in (1e-3, 1e-6):
        y = rb.oscillator_settlement_history(t, alpha=alpha, **BLOCK)
        # the decay changes y by about d alpha t / 2 <= 2.5e-4 * alpha * 0.1
        assert np.max(np.abs(y - undamped)) < 2.0 * D * alpha * 0.1
    # delta -> pi alpha / w as alpha -> 0
    assert rb.log_decrement(alpha=1e-6, **SPRING) == pytest.approx(math.pi * 1e-6 / W, rel=1e-12, abs=0)
    assert rb.log_decrement(alpha=0.0, **SPRING) == 0.0


@REQ
def test_log_decrement_from_successive_peaks_of_the_damped_history():
    alpha = 40.0

    def minus_y(s):
        return -float(rb.oscillator_settlement_history(np.array([s]), alpha=alpha, **BLOCK)[0])

    # one bracket per oscillation, search numerically for each maximum
    period = 2.0 * math.pi / math.sqrt(W ** 2 - alpha ** 2 / 4.0)
    peaks = []
    for k in range(4):
        found = minimize_scalar(minus_y, bounds=(k * period + 0.1 * period, k * period + 0.9 * period),
                                method="bounded", options={"xatol": 1e-12})
        peaks.append(-found.fun - D)
    decrements = np.log(np.array(peaks[:-1]) / np.array(peaks[1:]))
    np.testing.assert_allclose(decrements, rb.log_decrement(alpha=alpha, **SPRING), rtol=1e-6)


@REQ
def test_oscillator_rejects_overdamping():
    with pytest.raises(ValueError):
        rb.oscillator_settlement_history(np.array([0.0]), alpha=400.0, **BLOCK)
    with pytest.raises(ValueError):
        rb.log_decrement(alpha=400.0, **SPRING)


# ---------------------------------------------------------------- central-difference recurrence


@REQ
def test_central_difference_period():
    # w dt = 1: sin(w_num dt / 2) = 1/2, w_num dt = pi / 3, so the period is exactly 6 steps
    dt = 1.0 / W
    assert rb.central_difference_period(dt=dt, **SPRING) == pytest.approx(6.0 * dt, rel=1e-14, abs=0)
    # small w dt: asin x = x + x^3 / 6 gives T_num / T = 1 - (w dt)^2 / 24 + O((w dt)^4)
    for wdt in (1e-1, 1e-2):
        shortening = 1.0 - rb.central_difference_period(dt=wdt / W, **SPRING) / rb.oscillator_period(**SPRING)
        assert shortening == pytest.approx(wdt ** 2 / 24.0, rel=wdt ** 2, abs=0)
    with pytest.raises(ValueError):
        rb.central_difference_period(dt=2.0 / W, **SPRING)


@REQ
def test_central_difference_history_known_steps():
    # alpha = 0, w dt = 1 (dt = 5e-3): y_{n+1} = y_n + y_n - y_{n-1} + (g - w^2 y_n) dt^2 with g dt^2 = d,
    # by hand: 0, d, 2d, 2d, d, 0, 0, d -- period six steps
    dt = 1.0 / W
    y = rb.central_difference_settlement_history(np.arange(8) * dt, alpha=0.0, dt=dt, **BLOCK)
    np.testing.assert_allclose(y, np.array([0, 1, 2, 2, 1, 0, 0, 1]) * D, rtol=0.0, atol=1e-12 * D)
    # alpha = 40, dt = 5e-4: h = 1 + 40 * 5e-4 / 2 = 1.01, y_1 = g dt^2 / h = 2.5e-6 / 1.01 = 2.475247525e-6;
    # y_2 = y_1 (1 + 2c), 2c = (2 - w^2 dt^2) / h = 1.99 / 1.01, so y_2 = (2.5e-6 / 1.01)(3 / 1.01) = 7.352220371e-6
    y = rb.central_difference_settlement_history(np.array([0.0, 5e-4, 1e-3]), alpha=40.0, dt=5e-4, **BLOCK)
    np.testing.assert_allclose(y, [0.0, 2.475247525e-6, 7.352220371e-6], rtol=1e-9, atol=1e-20)


@REQ
def test_central_difference_closed_form_matches_the_recurrence():
    # the benchmark's own step (w dt = 0.2 / sqrt 3), a coarse one, one past w dt = sqrt 2 (theta > pi / 2)
    # and one near the stability limit, each with and without damping
    for dt in (0.0005773502691896258, 5e-3, 8e-3, 9.5e-3):
        for alpha in (0.0, 2.0, 40.0):
            n = np.arange(2001)
            closed = rb.central_difference_settlement_history(n * dt, alpha=alpha, dt=dt, **BLOCK)
            loop = recurrence_loop(2000, alpha=alpha, dt=dt, **BLOCK)
            # relative to the static settlement. The loop's own round-off accumulates as a phase drift over the
            # 2000 steps; undamped and at w dt = 1.9 it reaches 2.4e-12, elsewhere it stays below 1e-12.
            tol = 5e-12 if (dt > 9e-3 and alpha == 0.0) else 1e-12
            assert np.max(np.abs(closed - loop)) <= tol * D, (dt, alpha)


@REQ
def test_central_difference_history_tends_to_the_continuous_solution():
    # Against oscillator_settlement_history the error is first order: v_{-1/2} = 0 starts the scheme
    # with v_0 = (v_{-1/2} + v_{1/2}) / 2 = g dt / (2 h), not 0 -- a sin term of amplitude ~ d w dt / 2.
    # Against the continuous solution started with that velocity it is second order.
    alpha = 40.0
    t = np.arange(0, 201) * 5e-4  # 0 .. 0.1 s, on every grid below
    plain, started = [], []
    for dt in (5e-4, 2.5e-4, 1.25e-4, 6.25e-5):
        discrete = rb.central_difference_settlement_history(t, alpha=alpha, dt=dt, **BLOCK)
        exact = rb.oscillator_settlement_history(t, alpha=alpha, **BLOCK)
        v0 = 10.0 * dt / (2.0 * (1.0 + alpha * dt / 2.0))
        plain.append(np.max(np.abs(discrete - exact)))
        started.append(np.max(np.abs(discrete - continuous_from_initial_velocity(t, v0, alpha=alpha, **BLOCK))))
    plain, started = np.array(plain), np.array(started)
    np.testing.assert_allclose(plain[:-1] / plain[1:], 2.0, rtol=0.05)
    np.testing.assert_allclose(started[:-1] / started[1:], 4.0, rtol=0.05)
    # leading first-order error (v0 / wd) e^{-alpha t/2} sin wd t,
    # v0 / wd ~ d w dt / 2 = 2.5e-4 * 200 * 5e-4 / 2 = 1.25e-5;
    # e^{-alpha t/2} sin wd t peaks at tan wd t = 2 wd / alpha = 9.95, wd t = 1.4706, t = 7.39 ms:
    # e^{-0.1478} * 0.995 = 0.858, so the error is about 1.25e-5 * 0.858 = 1.073e-5
    assert plain[0] == pytest.approx(1.073e-5, rel=0.03, abs=0)
    # and the helper is the plain continuous solution when v0 = 0
    np.testing.assert_allclose(continuous_from_initial_velocity(t, 0.0, alpha=alpha, **BLOCK),
                               rb.oscillator_settlement_history(t, alpha=alpha, **BLOCK), rtol=0, atol=1e-15 * D)


@REQ
def test_central_difference_history_decays_at_the_continuous_rate_for_small_dt():
    # successive sampled maxima of y_n - d: at w dt = 0.02 the sampling misses a peak by at most (w dt)^2 / 8 = 5e-5
    # of its height and the discrete decay differs from the continuous by O((w dt)^2), so the mean log ratio
    # matches delta = 0.6314838 to about 1e-3
    dt = 1e-4
    n = np.arange(1001)
    y = rb.central_difference_settlement_history(n * dt, alpha=40.0, dt=dt, **BLOCK) - D
    i = np.nonzero((y[1:-1] > y[:-2]) & (y[1:-1] >= y[2:]) & (y[1:-1] > 0.0))[0] + 1
    assert len(i) >= 3
    delta = np.mean(np.log(y[i][:-1] / y[i][1:]))
    assert delta == pytest.approx(0.6314838, rel=2e-3, abs=0)


@REQ
def test_central_difference_history_rejects_bad_input():
    with pytest.raises(ValueError):  # unstable: w dt = 2
        rb.central_difference_settlement_history(np.array([0.0]), alpha=0.0, dt=2.0 / W, **BLOCK)
    with pytest.raises(ValueError):  # off the step grid
        rb.central_difference_settlement_history(np.array([0.5e-3 * 1.5]), alpha=0.0, dt=0.5e-3, **BLOCK)
    with pytest.raises(ValueError):  # too heavily damped to oscillate
        rb.central_difference_settlement_history(np.array([0.0]), alpha=400.0, dt=1e-4, **BLOCK)


# ---------------------------------------------------------------- direct shear


@REQ
def test_direct_shear_constant_normal_stress():
    # strength 2e5 + 1e6 tan30 = 2e5 + 577350.2692 = 777350.2692 Pa, us_y = 7.773502692e-4 m;
    # at us = 2e-3: opening = (2e-3 - 7.773502692e-4) tan10 = 1.2226497308e-3 * 0.1763269807 = 2.155861e-4 m
    p = dict(ks=1e9, sn=1e6, cohesion=2e5, phi_deg=30.0, psi_deg=10.0)
    tau, opening = rb.direct_shear_constant_normal_stress(np.array([0.0, 5e-4, 7.773502692e-4, 2e-3]), **p)
    np.testing.assert_allclose(tau, [0.0, 5e5, 777350.2692, 777350.2692], rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(opening, [0.0, 0.0, 0.0, 2.155861e-4], rtol=1e-6, atol=1e-12)
    # the block under the dead load sits kn-closed by sn / kn = 1e6 / 1e9 = 1e-3 m, then rises by the opening
    rise = rb.direct_shear_block_rise(np.array([0.0, 2e-3]), kn=1e9, **p)
    np.testing.assert_allclose(rise, [-1e-3, -1e-3 + 2.155861e-4], rtol=1e-6)
    # no dilation by default
    _, opening = rb.direct_shear_constant_normal_stress(np.array([2e-3]), ks=1e9, sn=1e6, cohesion=2e5, phi_deg=30)
    assert opening[0] == 0.0


@REQ
def test_direct_shear_constant_normal_displacement_continuity_and_slope():
    ks, kn = 1e9, 1e9
    p = dict(ks=ks, kn=kn, sn0=0.0, cohesion=2e5, phi_deg=30.0, psi_deg=10.0)
    tp, ts = math.tan(math.radians(30.0)), math.tan(math.radians(10.0))
    # yield at us_y = 2e5 / 1e9 = 2e-4 m; K = kn tan30 tan10 = 1e9 * 0.5773502692 * 0.1763269807 = 1.0180243e8 Pa/m,
    # post-yield slope ks K / (ks + K) = 1.0180243e17 / 1.10180243e9 = 9.2396265e7 Pa/m
    us_y = 2e-4
    eps = 1e-12
    tau, sn = rb.direct_shear_constant_normal_displacement(np.array([us_y - eps, us_y, us_y + eps]), **p)
    np.testing.assert_allclose(tau, 2e5, rtol=1e-6)
    np.testing.assert_allclose(sn, 0.0, atol=1e-1)
    us = np.linspace(3e-4, 3e-3, 10)
    tau, sn = rb.direct_shear_constant_normal_displacement(us, **p)
    np.testing.assert_allclose(np.diff(tau) / np.diff(us), 9.2396265e7, rtol=1e-6)
    np.testing.assert_allclose(tau, 2e5 + 9.2396265e7 * (us - us_y), rtol=1e-6)
    # on the yield surface, and the elastic part of the slip carries the stress
    np.testing.assert_allclose(tau, 2e5 + sn * tp, rtol=1e-12)
    us_p = sn / (kn * ts)
    np.testing.assert_allclose(tau, ks * (us - us_p), rtol=1e-12)
    # elastic branch
    tau, sn = rb.direct_shear_constant_normal_displacement(np.array([1e-4]), **p)
    assert tau[0] == pytest.approx(1e5, rel=1e-12, abs=0) and sn[0] == 0.0


@REQ
def test_direct_shear_constant_normal_displacement_limits():
    us = np.linspace(0.0, 3e-3, 31)
    # no dilation: perfectly plastic at c + sn0 tan phi = 2e5 + 1e6 * 0.5773502692, sn stays sn0
    tau, sn = rb.direct_shear_constant_normal_displacement(us, ks=1e9, kn=1e9, sn0=1e6, cohesion=2e5, phi_deg=30,
                                                           psi_deg=0)
    np.testing.assert_allclose(tau, np.minimum(1e9 * us, 777350.2692), rtol=1e-9)
    np.testing.assert_allclose(sn, 1e6, rtol=0)
    # a very stiff normal restraint: the hardening dominates and the slope tends to ks
    tau, _ = rb.direct_shear_constant_normal_displacement(np.array([1e-3, 2e-3]), ks=1e9, kn=1e15, sn0=0, cohesion=2e5,
                                                          phi_deg=30, psi_deg=10)
    assert (tau[1] - tau[0]) / 1e-3 == pytest.approx(1e9, rel=1e-5, abs=0)


@REQ
def test_direct_shear_coulomb_fracture():
    # peak 777350.2692 Pa at us = 7.773502692e-4 m, then the residual 1e6 tan30 = 577350.2692 Pa: a drop of c = 2e5
    tau = rb.direct_shear_coulomb_fracture(np.array([0.0, 5e-4, 7.7735e-4, 7.7736e-4, 5e-3]), ks=1e9, sn=1e6,
                                           cohesion=2e5, phi_deg=30.0)
    np.testing.assert_allclose(tau, [0.0, 5e5, 777350.0, 577350.2692, 577350.2692], rtol=1e-9, atol=1e-9)
    assert rb.coulomb_peak_strength(sn=1e6, cohesion=2e5, phi_deg=30.0) == pytest.approx(777350.2692, rel=1e-10, abs=0)
    assert rb.coulomb_residual_strength(sn=1e6, phi_deg=30.0) == pytest.approx(577350.2692, rel=1e-10, abs=0)


@REQ
def test_tensile_opening_stress():
    # kn = 1e9, T0 = 1e5: elastic down to un = -1e-4 m (sn = -1e5 Pa), broken beyond
    un = np.array([1e-4, 0.0, -5e-5, -1e-4, -1.0001e-4, -1e-3])
    sn = rb.tensile_opening_stress(un, kn=1e9, tension=1e5)
    np.testing.assert_allclose(sn, [1e5, 0.0, -5e4, -1e5, 0.0, 0.0], rtol=1e-12, atol=1e-9)


# ---------------------------------------------------------------- rigid block on two corners


@REQ
def test_rigid_block_frequencies_known_values():
    # 1 x 1 m, rho = 2500: m = 2500, I = 2500 * 2 / 12 = 416.667; kn = ks = 1e8, Lc = 0.5 per corner.
    # vertical: 2 kn Lc / m = 1e8 / 2500 = 4e4 -> 200 rad/s.
    # sliding-rocking: Kxx = 2 ks Lc = 1e8, Kxt = 2 ks Lc h/2 = 5e7, Ktt = 2 (kn Lc w^2/4 + ks Lc h^2/4) = 5e7;
    # det(K - lam M) = 0 -> lam^2 - 1.6e5 lam + 2.4e9 = 0 -> lam = 8e4 -+ 2e4 sqrt(10) = 16754.447, 143245.553
    w = rb.rigid_block_frequencies(width=1.0, height=1.0, density=2500.0, kn=1e8, ks=1e8)
    np.testing.assert_allclose(w, [math.sqrt(16754.4469), 200.0, math.sqrt(143245.5531)], rtol=1e-8)
    np.testing.assert_allclose(w, [129.4389694, 200.0, 378.4779428], rtol=1e-9)


@REQ
def test_rigid_block_frequencies_limits_and_scaling():
    # no shear stiffness: free sliding (w = 0), vertical 200 rad/s, and pure rocking about the centroid with
    # Ktt = 2 kn Lc (w/2)^2 = 2.5e7, w^2 = 2.5e7 / 416.667 = 6e4 -> 244.9489743 rad/s
    w = rb.rigid_block_frequencies(width=1.0, height=1.0, density=2500.0, kn=1e8, ks=0.0)
    np.testing.assert_allclose(w, [0.0, 200.0, 244.9489743], rtol=1e-9, atol=1e-6)
    # frequencies scale with sqrt(Lc)
    base = rb.rigid_block_frequencies(width=2.0, height=1.0, density=2500.0, kn=1e9, ks=4e8)
    scaled = rb.rigid_block_frequencies(width=2.0, height=1.0, density=2500.0, kn=1e9, ks=4e8,
                                        contact_length_per_corner=4.0)
    np.testing.assert_allclose(scaled, base * 2.0, rtol=1e-12)


@REQ
def test_critical_frac():
    # dt = FRAC * 2 sqrt(m / K_max), K_max = 1e8 * 1: sqrt(m / K_max) = 1 / 200;
    # w_max dt = 2 -> FRAC = 200 / w_max = 200 / 378.4779428 = 0.5284323797
    frac = rb.critical_frac(width=1.0, height=1.0, density=2500.0, kn=1e8, ks=1e8, typical_length=1.0)
    assert frac == pytest.approx(0.5284323797, rel=1e-9, abs=0)
    # at that FRAC the fastest mode sits exactly on the stability limit w dt = 2
    p = dict(width=2.0, height=0.5, density=2700.0, kn=3e9, ks=1e9)
    frac = rb.critical_frac(typical_length=0.7, **p)
    dt = frac * 2.0 * math.sqrt(2700.0 * 2.0 * 0.5 / (3e9 * 0.7))
    assert rb.rigid_block_frequencies(**p)[-1] * dt == pytest.approx(2.0, rel=1e-12, abs=0)


@REQ
def test_rigid_block_time_step():
    # FRAC 2 sqrt(m / (max(kn, ks) l_typ)) = 0.5 * 2 * sqrt(2500 / (1e8 * 3)) = sqrt(8.3333e-6) = 2.886751346e-3 s
    assert rb.rigid_block_time_step(mass=2500.0, kn=1e8, ks=1e8, typical_length=3.0, frac=0.5) == pytest.approx(
        2.886751346e-3, rel=1e-9, abs=0)
    # the larger of the two stiffnesses governs: 2 * sqrt(2500 / 4e8) = 2 * 2.5e-3 = 5e-3 s
    assert rb.rigid_block_time_step(mass=2500.0, kn=1e8, ks=4e8, typical_length=1.0, frac=1.0) == pytest.approx(
        5e-3, rel=1e-14, abs=0)
    # the stability sweep's block (l_typ = 3 m): critical FRAC = 0.5284323797 * sqrt(3) = 0.9152717
    assert rb.critical_frac(width=1.0, height=1.0, density=2500.0, kn=1e8, ks=1e8, typical_length=3.0) == \
        pytest.approx(0.9152717, rel=1e-7, abs=0)


@pytest.mark.requirements("REQ-MOTION-008")
def test_rayleigh_damping_closed_forms():
    # m = 2500, kn L = 1e8: w = 200 rad/s. alpha = 10, beta = 2.5e-4: xi = 10/400 + 2.5e-4*200/2 = 0.05
    assert rb.rayleigh_damping_ratio(alpha=10.0, beta=2.5e-4, mass=2500.0, kn=1e8, contact_length=1.0) == \
        pytest.approx(0.05, rel=1e-14, abs=0)
    # w = 400: 10/800 + 2.5e-4*400/2 = 0.0125 + 0.05 = 0.0625
    assert rb.rayleigh_damping_ratio(alpha=10.0, beta=2.5e-4, mass=2500.0, kn=4e8, contact_length=1.0) == \
        pytest.approx(0.0625, rel=1e-14, abs=0)
    assert rb.rayleigh_log_decrement(alpha=10.0, beta=2.5e-4, mass=2500.0, kn=1e8, contact_length=1.0) == \
        pytest.approx(2.0 * math.pi * 0.05 / math.sqrt(1.0 - 0.0025), rel=1e-14, abs=0)
    # alpha = 0 reduces to the mass-damping decrement's form with xi = beta w / 2
    assert rb.rayleigh_log_decrement(alpha=40.0, beta=0.0, mass=2500.0, kn=1e8, contact_length=1.0) == \
        pytest.approx(rb.log_decrement(alpha=40.0, mass=2500.0, kn=1e8, contact_length=1.0), rel=1e-14, abs=0)
    # xi_s = 2.5e-4 * 400 / 2 = 0.05: sqrt(1.0025) - 0.05
    assert rb.stiffness_damping_step_factor(beta=2.5e-4, mass=2500.0, kn=4e8, contact_length=1.0) == \
        pytest.approx(math.sqrt(1.0025) - 0.05, rel=1e-14, abs=0)
    with pytest.raises(ValueError):
        rb.rayleigh_log_decrement(alpha=1e4, beta=0.0, mass=2500.0, kn=1e8, contact_length=1.0)


def damped_recurrence_loop(n_steps, *, w_dt, xi, v0=1.0):
    """The solver's update with the viscous force on the lagged velocity, stepped literally
    (w = 1, dt = w_dt, beta = 2 xi): v += -dt (x + beta v); x += dt v."""
    dt, beta = w_dt, 2.0 * xi
    x, v, out = 0.0, v0, []
    for _ in range(n_steps):
        v += -dt * (x + beta * v)
        x += dt * v
        out.append(x)
    return np.array(out)


@pytest.mark.requirements("REQ-QA-003", "REQ-MOTION-008")
def test_stiffness_damped_critical_step_and_growth_per_step():
    # w = 200 rad/s, beta = 7.5e-3 s: xi = 0.75, sqrt(1 + 0.5625) - 0.75 = 1.25 - 0.75 = 0.5, so
    # dt_c = (2 / 200) 0.5 = 5e-3 s; at fraction 0.95, 4.75e-3 s.
    assert rb.stiffness_damped_critical_step(beta=7.5e-3, **SPRING) == pytest.approx(5e-3, rel=1e-14, abs=0)
    assert rb.stiffness_damped_critical_step(beta=7.5e-3, fraction=0.95, **SPRING) == \
        pytest.approx(4.75e-3, rel=1e-14, abs=0)
    # beta = 0: the undamped 2 / w.
    assert rb.stiffness_damped_critical_step(beta=0.0, **SPRING) == pytest.approx(0.01, rel=1e-14, abs=0)
    # Undamped, W = 2.5: lambda^2 + 4.25 lambda + 1 = 0, roots -0.25 and -4.
    assert rb.stiffness_damped_growth_per_step(w_dt=2.5, xi=0.0) == pytest.approx(4.0, rel=1e-14, abs=0)
    # xi = 0.75, W = 1.05: lambda^2 + 0.6775 lambda - 0.575 = 0, disc = 0.45900625 + 2.3 = 2.75900625,
    # |lambda| = (0.6775 + 1.6610257...) / 2 = 1.16926...
    assert rb.stiffness_damped_growth_per_step(w_dt=1.05, xi=0.75) == \
        pytest.approx((0.6775 + math.sqrt(2.75900625)) / 2.0, rel=1e-14, abs=0)
    # Complex pair: xi = 0.1, W = 0.5: c = 1 - 0.1 = 0.9, |lambda| = sqrt(0.9).
    assert rb.stiffness_damped_growth_per_step(w_dt=0.5, xi=0.1) == pytest.approx(math.sqrt(0.9), rel=1e-14, abs=0)
    # The critical step is where the growth passes 1, for several xi.
    for xi in (0.05, 0.75, 3.0):
        w_dt_critical = 2.0 * (math.sqrt(1.0 + xi * xi) - xi)
        assert rb.stiffness_damped_growth_per_step(w_dt=w_dt_critical, xi=xi) == pytest.approx(1.0, rel=1e-12, abs=0)
        assert rb.stiffness_damped_growth_per_step(w_dt=0.99 * w_dt_critical, xi=xi) < 1.0
        assert rb.stiffness_damped_growth_per_step(w_dt=1.01 * w_dt_critical, xi=xi) > 1.0
    # The literal loop grows or decays at that rate: over 200 steps, the late amplitude ratio.
    for w_dt, xi in ((0.95, 0.75), (1.05, 0.75)):
        x = np.abs(damped_recurrence_loop(400, w_dt=w_dt, xi=xi))
        measured = (x[399] / x[199]) ** (1.0 / 200.0)
        assert measured == pytest.approx(rb.stiffness_damped_growth_per_step(w_dt=w_dt, xi=xi), rel=1e-9, abs=0)
    with pytest.raises(ValueError):
        rb.stiffness_damped_growth_per_step(w_dt=-1.0, xi=0.5)


@pytest.mark.requirements("REQ-QA-003", "REQ-MOTION-010")
def test_newmark_sliding_block_known_values_and_consistency():
    kw = dict(g=10.0, phi_deg=30.0, base_acceleration=10.0, pulse_start=0.05, pulse_duration=0.1)
    mu_g = 10.0 * math.tan(math.radians(30.0))
    # Newmark's slip V^2 / (2 mu g) (1 - mu g / a) by hand: V = 1 m/s.
    slip = rb.newmark_rectangular_pulse_slip(g=10.0, phi_deg=30.0, base_acceleration=10.0, pulse_duration=0.1)
    assert slip == pytest.approx(1.0 / (2 * mu_g) * (1 - mu_g / 10.0), rel=1e-14, abs=0)
    assert slip == pytest.approx(0.03660254037844387, rel=1e-12, abs=0)
    # Long after the catch-up the base is ahead of the block by exactly that slip.
    late = np.array([1.0, 2.0])
    base = rb.sliding_block_base_displacement(late, base_acceleration=10.0, pulse_start=0.05, pulse_duration=0.1)
    assert base - rb.sliding_block_on_pulsed_base(late, **kw) == pytest.approx([slip, slip], rel=1e-12, abs=0)
    # The block's velocity (finite differences) is mu g (t - t0) while it slides, continuous at
    # the catch-up, and V after it; it never exceeds the base's.
    t = np.linspace(0.0, 0.5, 50001)
    x = rb.sliding_block_on_pulsed_base(t, **kw)
    v = np.gradient(x, t)
    ts = 0.05 + 1.0 / mu_g
    sliding = (t > 0.06) & (t < ts - 0.01)
    assert np.allclose(v[sliding], mu_g * (t[sliding] - 0.05), rtol=1e-6, atol=0.0)
    assert np.allclose(v[t > ts + 0.01], 1.0, rtol=1e-9, atol=0.0)
    vb = np.gradient(rb.sliding_block_base_displacement(t, base_acceleration=10.0, pulse_start=0.05,
                                                        pulse_duration=0.1), t)
    assert np.all(v <= vb + 1e-6)
    # A pulse the joint can carry: the block moves with the base, no slip.
    weak = dict(kw, base_acceleration=5.0)
    assert np.allclose(rb.sliding_block_on_pulsed_base(t, **weak),
                       rb.sliding_block_base_displacement(t, base_acceleration=5.0, pulse_start=0.05,
                                                          pulse_duration=0.1), rtol=0.0, atol=0.0)
    assert rb.newmark_rectangular_pulse_slip(g=10.0, phi_deg=30.0, base_acceleration=5.0, pulse_duration=0.1) == 0.0


# ---------------------------------------------------------------- rigid block on a viscous edge
# The BND-VISCOUS-RIGID block: 2 m x 1 m, 2500 kg/m^3 (m = 5000, I = 5000 x 5 / 12 = 2083.33),
# its bottom edge on a medium of rho = 2000, E = 5e7, nu = 0.25: G = 2e7, K = 5e7 / 1.5 = 3.333e7,
# rho C_s = sqrt(2000 x 2e7) = 2e5, rho C_p = sqrt(2000 x (3.333e7 + 2.667e7)) = sqrt(1.2e11) = 3.4641e5.
VISCOUS_MEDIUM = dict(density=2000.0, young=5e7, poisson=0.25)
VISCOUS_BLOCK = dict(width=2.0, height=1.0, density=2500.0, edge_from=(-1.0, -0.5), edge_to=(1.0, -0.5),
                     medium=VISCOUS_MEDIUM)
ZN, ZS = math.sqrt(1.2e11), 2e5


def lagged_dashpot_loop(n_steps, q0, mass_matrix, dashpot_matrix, dt, load=(0.0, 0.0, 0.0)):
    """q += dt M^-1 (f - C q), stepped literally, component by component."""
    q, out = list(q0), [list(q0)]
    for _ in range(n_steps):
        force = [load[i] - sum(dashpot_matrix[i][j] * q[j] for j in range(3)) for i in range(3)]
        q = [q[i] + dt * force[i] / mass_matrix[i][i] for i in range(3)]
        out.append(q)
    return np.array(out)


@pytest.mark.requirements("REQ-QA-003", "REQ-BOUNDARY-005")
def test_dashpot_matrix_of_rigid_edges_at_known_values():
    zn, zs = rb.medium_impedances(**VISCOUS_MEDIUM)
    assert (zn, zs) == (pytest.approx(ZN, rel=1e-14, abs=0), pytest.approx(ZS, rel=1e-14, abs=0))
    # Bottom edge, by hand: [[Zs L, 0, Zs L H/2], [0, Zn L, 0], [Zs L H/2, 0, Zn L^3/12 + Zs L H^2/4]].
    bottom = rb.rigid_edge_dashpot_matrix(edge_from=(-1.0, -0.5), edge_to=(1.0, -0.5), centroid=(0.0, 0.0),
                                          normal_impedance=ZN, shear_impedance=ZS)
    expected = [[4e5, 0.0, 2e5], [0.0, 2.0 * ZN, 0.0], [2e5, 0.0, ZN * 8.0 / 12.0 + 1e5]]
    assert np.allclose(bottom, expected, rtol=1e-14, atol=1e-9)
    # The right side from (1, -0.5) up to (1, 0.5): n = (1, 0), t = (0, 1), r = (1, y). Normal
    # dashpots on vx - w y (mean y 0), shear on vy + w: [[Zn, 0, 0], [0, Zs, Zs], [0, Zs, Zn/12 + Zs]].
    right = rb.rigid_edge_dashpot_matrix(edge_from=(1.0, -0.5), edge_to=(1.0, 0.5), centroid=(0.0, 0.0),
                                         normal_impedance=ZN, shear_impedance=ZS)
    assert np.allclose(right, [[ZN, 0.0, 0.0], [0.0, ZS, ZS], [0.0, ZS, ZN / 12.0 + ZS]], rtol=1e-14, atol=1e-9)
    # Independent route: Gauss-Legendre quadrature of G^T D G along a slanted edge.
    a, b, c = np.array([0.3, -0.7]), np.array([1.1, 0.4]), np.array([0.2, 0.1])
    t = (b - a) / np.linalg.norm(b - a)
    n = np.array([t[1], -t[0]])
    d = ZN * np.outer(n, n) + ZS * np.outer(t, t)
    nodes, weights = np.polynomial.legendre.leggauss(4)
    quadrature = np.zeros((3, 3))
    for s, w in zip(nodes, weights):
        r = a + 0.5 * (s + 1.0) * (b - a) - c
        g = np.array([[1.0, 0.0, -r[1]], [0.0, 1.0, r[0]]])
        quadrature += 0.5 * w * np.linalg.norm(b - a) * g.T @ d @ g
    slanted = rb.rigid_edge_dashpot_matrix(edge_from=a, edge_to=b, centroid=c, normal_impedance=ZN, shear_impedance=ZS)
    assert np.allclose(slanted, quadrature, rtol=1e-13, atol=1e-8)
    # The incident wave's load is C (2 v_in, 0): the steady state.
    vin = np.array([0.3, -0.2])
    load = rb.rigid_edge_input_force(edge_from=a, edge_to=b, centroid=c, normal_impedance=ZN, shear_impedance=ZS,
                                     input_velocity=vin)
    assert np.allclose(load, slanted @ np.array([0.6, -0.4, 0.0]), rtol=1e-13, atol=1e-8)
    with pytest.raises(ValueError):
        rb.rigid_edge_dashpot_matrix(edge_from=a, edge_to=a, centroid=c, normal_impedance=ZN, shear_impedance=ZS)


@pytest.mark.requirements("REQ-QA-003", "REQ-BOUNDARY-005")
def test_viscous_rigid_block_recurrence_continuum_and_their_difference():
    q0 = (1e-3, -2e-3, 5e-4)
    mass = rb.rectangle_mass_matrix(width=2.0, height=1.0, density=2500.0)
    assert np.allclose(np.diag(mass), [5000.0, 5000.0, 5000.0 * 5.0 / 12.0], rtol=1e-15, atol=0)
    dashpots = rb.rigid_edge_dashpot_matrix(edge_from=(-1.0, -0.5), edge_to=(1.0, -0.5), centroid=(0.0, 0.0),
                                            normal_impedance=ZN, shear_impedance=ZS)
    dt = 5e-5
    loop = lagged_dashpot_loop(300, q0, mass, dashpots, dt)
    t = dt * np.arange(301)
    for k, dof in enumerate(("vx", "vy", "w")):
        closed = rb.viscous_rigid_block_velocity_discrete(t, initial_velocity=q0, dof=dof, dt=dt, **VISCOUS_BLOCK)
        assert np.allclose(closed, loop[:, k], rtol=0, atol=1e-16), dof
    # vy is a mode of its own: Zn L / m = 2 ZN / 5000 /s, e^(-lambda t) and (1 - lambda dt)^n.
    lam = 2.0 * ZN / 5000.0
    assert rb.viscous_rigid_block_velocity(0.01, initial_velocity=q0, dof="vy", **VISCOUS_BLOCK) == \
        pytest.approx(-2e-3 * math.exp(-lam * 0.01), rel=1e-13, abs=0)
    assert rb.viscous_rigid_block_velocity_discrete(0.01, initial_velocity=q0, dof="vy", dt=dt, **VISCOUS_BLOCK) == \
        pytest.approx(-2e-3 * (1.0 - lam * dt) ** 200, rel=1e-12, abs=0)
    # The continuum solves M dq/dt = -C q: central differences of it.
    h = 1e-6
    q = lambda s: np.array([rb.viscous_rigid_block_velocity(s, initial_velocity=q0, dof=d, **VISCOUS_BLOCK)
                            for d in ("vx", "vy", "w")])
    for s in (0.0 + 2 * h, 0.005, 0.02):
        derivative = (q(s + h) - q(s - h)) / (2.0 * h)
        assert np.allclose(mass @ derivative, -dashpots @ q(s), rtol=1e-7, atol=1e-12)
    # The decay rates: 138.56 for vy; 45.98 and 192.87 for (vx, w), roots of
    # lambda^2 - (80 + 158.79) lambda + (80 x 158.79 - 40 x 96) with C_ww / I = (ZN 8/12 + 1e5) / 2083.3.
    cww = (ZN * 8.0 / 12.0 + 1e5) / (5000.0 * 5.0 / 12.0)
    tr, det = 80.0 + cww, 80.0 * cww - 40.0 * 96.0
    root = math.sqrt(tr * tr - 4.0 * det)
    rates = rb.viscous_rigid_block_decay_rates(**VISCOUS_BLOCK)
    assert np.allclose(rates, sorted([(tr - root) / 2.0, lam, (tr + root) / 2.0]), rtol=1e-12, atol=0)
    assert rb.viscous_rigid_block_critical_step(**VISCOUS_BLOCK) == pytest.approx(4.0 / (tr + root), rel=1e-12, abs=0)
    # The lag bound holds for the two closed forms and is first order: it halves with dt.
    for dof in ("vx", "vy", "w"):
        bound = rb.viscous_rigid_block_lag_error_bound(initial_velocity=q0, dof=dof, dt=dt, **VISCOUS_BLOCK)
        long_t = dt * np.arange(2001)
        cont = rb.viscous_rigid_block_velocity(long_t, initial_velocity=q0, dof=dof, **VISCOUS_BLOCK)
        disc = rb.viscous_rigid_block_velocity_discrete(long_t, initial_velocity=q0, dof=dof, dt=dt, **VISCOUS_BLOCK)
        error = np.max(np.abs(cont - disc)) / np.max(np.abs(cont))
        assert 0.5 * bound < error <= bound, dof
        half = rb.viscous_rigid_block_lag_error_bound(initial_velocity=q0, dof=dof, dt=dt / 2, **VISCOUS_BLOCK)
        assert half == pytest.approx(bound / 2.0, rel=0.01, abs=0)
    # The dissipation is the kinetic energy the recurrence lost, summed step by step.
    # Each step the dashpots' force -C q_{n-1/2} works on the mean velocity: dissipation dt C q . qbar.
    taken = sum(dt * (dashpots @ loop[i]) @ (0.5 * (loop[i] + loop[i + 1])) for i in range(300))
    assert taken > 0.0
    assert rb.viscous_rigid_block_dissipation(initial_velocity=q0, dt=dt, time=300 * dt, **VISCOUS_BLOCK) == \
        pytest.approx(taken, rel=1e-12, abs=0)


@pytest.mark.requirements("REQ-QA-003", "REQ-BOUNDARY-005")
def test_viscous_rigid_block_under_an_incident_wave_tends_to_twice_its_velocity():
    vin = (1e-3, 5e-4)
    mass = rb.rectangle_mass_matrix(width=2.0, height=1.0, density=2500.0)
    dashpots = rb.rigid_edge_dashpot_matrix(edge_from=(-1.0, -0.5), edge_to=(1.0, -0.5), centroid=(0.0, 0.0),
                                            normal_impedance=ZN, shear_impedance=ZS)
    # On the bottom edge n = (0, -1): the load 2 L (Zs vx, Zn vy) at (0, -H/2), moment H/2 x 2 L Zs vx.
    load = (2 * 2 * ZS * 1e-3, 2 * 2 * ZN * 5e-4, 0.5 * 2 * 2 * ZS * 1e-3)
    assert np.allclose(rb.rigid_edge_input_force(edge_from=(-1.0, -0.5), edge_to=(1.0, -0.5), centroid=(0.0, 0.0),
                                                 normal_impedance=ZN, shear_impedance=ZS, input_velocity=vin),
                       load, rtol=1e-14, atol=0)
    dt = 5e-5
    loop = lagged_dashpot_loop(400, (0.0, 0.0, 0.0), mass, dashpots, dt, load)
    t = dt * np.arange(401)
    for k, dof in enumerate(("vx", "vy", "w")):
        closed = rb.viscous_rigid_block_velocity_discrete(t, initial_velocity=(0, 0, 0), input_velocity=vin, dof=dof,
                                                          dt=dt, **VISCOUS_BLOCK)
        assert np.allclose(closed, loop[:, k], rtol=0, atol=1e-16), dof
    late = 2.0
    assert rb.viscous_rigid_block_velocity(late, initial_velocity=(0, 0, 0), input_velocity=vin, dof="vx",
                                           **VISCOUS_BLOCK) == pytest.approx(2e-3, rel=1e-12, abs=0)
    assert rb.viscous_rigid_block_velocity(late, initial_velocity=(0, 0, 0), input_velocity=vin, dof="vy",
                                           **VISCOUS_BLOCK) == pytest.approx(1e-3, rel=1e-12, abs=0)
    assert abs(rb.viscous_rigid_block_velocity(late, initial_velocity=(0, 0, 0), input_velocity=vin, dof="w",
                                               **VISCOUS_BLOCK)) < 1e-15


@pytest.mark.requirements("REQ-QA-003", "REQ-BOUNDARY-005")
def test_viscous_rigid_block_step_limit_at_known_values():
    # Soft joint (k = 0): FRAC 2 / lambda, lambda = c_t / m + c_r / I. The bottom edge (L = 2, at
    # H / 2 = 0.5 below the centroid): its translation matrix diag(ZS L, ZN L), largest ZN L = 2 ZN;
    # its rotation entry ZN L^3 / 12 + ZS L H^2 / 4 = 2 ZN / 3 + ZS / 2; m = 5000, I = 5000 x 5 / 12.
    inertia = 5000.0 * 5 / 12
    rate = 2 * ZN / 5000.0 + (2 * ZN / 3 + ZS / 2) / inertia
    assert rb.viscous_rigid_block_step_limit(joint_stiffness=0.0, frac=1.0, **VISCOUS_BLOCK) == \
        pytest.approx(2.0 / rate, rel=1e-14, abs=0)
    # No dashpot rate beside a joint k: the undamped 2 sqrt(m / k) of 4 / sqrt(4 k / m), times FRAC.
    k = 1e10 * 2 * math.sqrt(1.25)
    assert rb.viscous_rigid_block_step_limit(joint_stiffness=1e10, frac=0.1, **VISCOUS_BLOCK) == \
        pytest.approx(0.1 * 4.0 / (rate + math.sqrt(rate ** 2 + 4 * k / 5000.0)), rel=1e-14, abs=0)


@pytest.mark.requirements("REQ-QA-003", "REQ-BOUNDARY-005")
@pytest.mark.parametrize("poisson", [0.25, 0.0, 0.45])
def test_viscous_rigid_block_step_limit_bounds_the_fastest_coupled_mode(poisson):
    # The lagged recurrence q+ = (I - dt A) q is stable while dt < 2 / lambda_max(A = M^-1 C); the
    # limit at FRAC = 1 with soft joints must not exceed it, also where the edge couples sliding and
    # spin strongly (nu = 0: Zs close to Zn), where limits of translation and rotation taken apart
    # exceeded it by 12 %.
    medium = dict(VISCOUS_MEDIUM, poisson=poisson)
    zn, zs = rb.medium_impedances(**medium)
    mass = rb.rectangle_mass_matrix(width=2.0, height=1.0, density=2500.0)
    dashpots = rb.rigid_edge_dashpot_matrix(edge_from=(-1.0, -0.5), edge_to=(1.0, -0.5), centroid=(0.0, 0.0),
                                            normal_impedance=zn, shear_impedance=zs)
    fastest = max(np.linalg.eigvals(np.linalg.solve(mass, dashpots)).real)
    limit = rb.viscous_rigid_block_step_limit(joint_stiffness=0.0, frac=1.0, **dict(VISCOUS_BLOCK, medium=medium))
    assert limit <= 2.0 / fastest
    # ... and is not far below it: the bound is the sum of two rates of which one dominates.
    assert limit >= 0.5 * 2.0 / fastest


@pytest.mark.requirements("REQ-QA-003", "REQ-BOUNDARY-005")
def test_viscous_rigid_block_under_a_sine_wave():
    vin, frequency, dt = (1e-3, 5e-4), 20.0, 5e-5
    w = 2.0 * math.pi * frequency
    mass = rb.rectangle_mass_matrix(width=2.0, height=1.0, density=2500.0)
    dashpots = rb.rigid_edge_dashpot_matrix(edge_from=(-1.0, -0.5), edge_to=(1.0, -0.5), centroid=(0.0, 0.0),
                                            normal_impedance=ZN, shear_impedance=ZS)
    load = rb.rigid_edge_input_force(edge_from=(-1.0, -0.5), edge_to=(1.0, -0.5), centroid=(0.0, 0.0),
                                     normal_impedance=ZN, shear_impedance=ZS, input_velocity=vin)
    common = dict(initial_velocity=(0.0, 0.0, 0.0), input_velocity=vin, input_frequency=frequency, **VISCOUS_BLOCK)
    # The recurrence with the load at each step's start, stepped literally.
    q, loop = np.zeros(3), [np.zeros(3)]
    for n in range(600):
        q = q + dt * np.linalg.solve(mass, load * math.sin(w * n * dt) - dashpots @ q)
        loop.append(q)
    loop = np.array(loop)
    t = dt * np.arange(601)
    for k, dof in enumerate(("vx", "vy", "w")):
        closed = rb.viscous_rigid_block_velocity_discrete(t, dof=dof, dt=dt, **common)
        assert np.allclose(closed, loop[:, k], rtol=0, atol=1e-15), dof
    # vy alone, by hand: dv/dt = lam (2 v_in,y sin(w t) - v), v(0) = 0, lam = 2 ZN / 5000:
    # v = 2 v_in,y lam (lam sin wt - w cos wt + w e^(-lam t)) / (lam^2 + w^2).
    lam = 2.0 * ZN / 5000.0
    for s in (0.003, 0.02, 0.1):
        by_hand = 2 * 5e-4 * lam * (lam * math.sin(w * s) - w * math.cos(w * s) + w * math.exp(-lam * s)) / (lam ** 2 + w ** 2)
        assert rb.viscous_rigid_block_velocity(s, dof="vy", **common) == pytest.approx(by_hand, rel=1e-12, abs=0)
    # The continuum solves M dq/dt = f sin(w t) - C q.
    h = 1e-6
    q = lambda s: np.array([rb.viscous_rigid_block_velocity(s, dof=d, **common) for d in ("vx", "vy", "w")])
    for s in (0.004, 0.03):
        derivative = (q(s + h) - q(s - h)) / (2.0 * h)
        assert np.allclose(mass @ derivative, load * math.sin(w * s) - dashpots @ q(s), rtol=1e-7, atol=1e-9)

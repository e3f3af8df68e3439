"""The dispersion relation of the crossed column (verification/analytic/dispersion.py) at known values.

The independent route: the Bloch eigenproblem of one crossed cell, assembled here from the stiffness
of each constant-strain triangle (A B^T D B, plane strain) and a third of each triangle's mass at its
vertices, solved numerically; the module's closed form, derived by hand from the three springs of
the cell, must return the wavenumber the eigenproblem started from.
"""
import math

import numpy as np
import pytest

from analytic import dispersion as dp
from analytic import elastic as el

REQ = pytest.mark.requirements("REQ-QA-003")

# The DY-DISPERSION rock: G = 2.5 GPa, c_s = 1000 m/s, M = lam + 2 G = 7.5 GPa.
ROCK = dict(E=6.25e9, nu=0.25, rho=2500.0)
C_S = 1000.0


def bloch_cell_frequency_squared(kappa, h, width, E, nu, rho):
    """Omega^2 of the acoustic branch at kappa = k h: one crossed cell, x motion only (y held),
    the two corner rows in Bloch relation u_j+1 = u_j exp(-i kappa), every node of a row alike."""
    lam, G = el.lame_from_young(E=E, nu=nu)
    M = lam + 2.0 * G
    nodes = np.array([[0.0, 0.0], [width, 0.0], [width, h], [0.0, h], [width / 2.0, h / 2.0]])
    stiffness, mass = np.zeros((5, 5)), np.zeros(5)
    for tri in ((0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)):
        p = nodes[list(tri)]
        area = 0.5 * ((p[1, 0] - p[0, 0]) * (p[2, 1] - p[0, 1]) - (p[2, 0] - p[0, 0]) * (p[1, 1] - p[0, 1]))
        # Gradients of the linear shape functions: N_i = (a_i + b_i x + c_i y) / (2 A).
        b = np.array([p[1, 1] - p[2, 1], p[2, 1] - p[0, 1], p[0, 1] - p[1, 1]]) / (2.0 * area)
        c = np.array([p[2, 0] - p[1, 0], p[0, 0] - p[2, 0], p[1, 0] - p[0, 0]]) / (2.0 * area)
        # u_x only: e_xx = b . u, gamma_xy = c . u; energy A (M e_xx^2 + G gamma^2) / 2.
        local = area * (M * np.outer(b, b) + G * np.outer(c, c))
        for i in range(3):
            mass[tri[i]] += rho * area / 3.0
            for j in range(3):
                stiffness[tri[i], tri[j]] += local[i, j]
    phase = np.exp(-1j * kappa)
    T = np.array([[1, 0], [1, 0], [phase, 0], [phase, 0], [0, 1]], dtype=complex)
    K = T.conj().T @ stiffness @ T
    Mm = T.conj().T @ np.diag(mass) @ T
    eigenvalues = np.linalg.eigvals(np.linalg.solve(Mm, K))
    return float(np.min(eigenvalues.real))


@REQ
@pytest.mark.parametrize("kappa, width_over_h, nu", [(math.pi / 4, 1.0, 0.25), (math.pi / 8, 1.0, 0.25),
                                                     (math.pi / 4, 0.5, 0.4), (1.2, 2.0, 0.1)])
def test_closed_form_returns_the_wavenumber_of_the_assembled_cell(kappa, width_over_h, nu):
    h = 1.25
    E = 2.0 * 2.5e9 * (1.0 + nu)                        # G = 2.5 GPa whatever nu
    omega2 = bloch_cell_frequency_squared(kappa, h, width_over_h * h, E, nu, 2500.0)
    dt = 0.5 * h / C_S
    # Central differences: Omega = (2 / dt) sin(w dt / 2), so w = (2 / dt) asin(Omega dt / 2).
    frequency = 2.0 / dt * math.asin(math.sqrt(omega2) * dt / 2.0) / (2.0 * math.pi)
    k = dp.crossed_column_shear_wavenumber(frequency=frequency, h=h, width=width_over_h * h, dt=dt, E=E, nu=nu,
                                           rho=2500.0)
    assert k * h == pytest.approx(kappa, rel=1e-10)


@REQ
def test_long_waves_travel_at_the_shear_wave_speed():
    # 1000 zones per wavelength and a step of a tenth of the zone crossing: k -> w / c_s.
    h = 10.0 / 1000
    k = dp.crossed_column_shear_wavenumber(frequency=100.0, h=h, width=h, dt=0.1 * h / C_S, **ROCK)
    assert k == pytest.approx(2.0 * math.pi * 100.0 / C_S, rel=1e-5)


@REQ
def test_thin_cells_give_the_mass_between_lumped_and_consistent():
    # width -> 0: the side triangles' K3 = 2 h M / w^2 pins the centre to the corners' mean and the
    # relation becomes rho h (1 - sin^2(kappa/2) / 3) Omega^2 = 4 (G / h) sin^2(kappa / 2).
    h, dt, frequency = 1.25, 1e-5, 100.0
    k = dp.crossed_column_shear_wavenumber(frequency=frequency, h=h, width=1e-5 * h, dt=dt, **ROCK)
    s2 = math.sin(k * h / 2.0) ** 2
    omega2 = (2.0 / dt * math.sin(math.pi * frequency * dt)) ** 2
    assert 2500.0 * h * (1.0 - s2 / 3.0) * omega2 == pytest.approx(4.0 * 2.5e9 / h * s2, rel=1e-9)


@REQ
def test_dispersion_error_is_second_order_and_not_the_lumped_chains():
    # At a fixed Courant number the phase lag falls four times per halving of h (its (k h)^2 term);
    # the lumped chain of springs G / h and masses rho h lags six times as much (it has no centre node).
    lags, chain = [], []
    for n in (8, 16, 32, 64):
        h = 10.0 / n
        dt = 0.144 * h / C_S
        lags.append(dp.crossed_column_phase_error(frequency=100.0, h=h, width=h, dt=dt, distance=40.0, **ROCK))
        chain.append((dp.lumped_chain_wavenumber(frequency=100.0, h=h, dt=dt, c=C_S) - 2 * math.pi * 100.0 / C_S) * 40.0)
    orders = [math.log2(a / b) for a, b in zip(lags, lags[1:])]
    assert all(lag > 0 for lag in lags)
    assert orders[-1] == pytest.approx(2.0, abs=0.01) and orders[0] > orders[1] > orders[2] > 2.0
    assert chain[-1] / lags[-1] == pytest.approx(6.7, rel=0.05)


@REQ
def test_lumped_chain_is_exact_at_courant_number_one():
    # c dt = h: sin(w h / 2c) = sin(k h / 2), so k = w / c for every frequency below the cut-off.
    h = 0.5
    for f in (50.0, 200.0, 700.0):
        assert dp.lumped_chain_wavenumber(frequency=f, h=h, dt=h / C_S, c=C_S) == pytest.approx(2 * math.pi * f / C_S, rel=1e-12, abs=0)


@REQ
def test_frequencies_beyond_the_branch_are_refused():
    with pytest.raises(ValueError, match="acoustic branch"):
        dp.crossed_column_shear_wavenumber(frequency=2000.0, h=1.25, width=1.25, dt=1e-5, **ROCK)
    with pytest.raises(ValueError, match="cut-off"):
        dp.lumped_chain_wavenumber(frequency=2000.0, h=1.25, dt=1e-5, c=C_S)
    with pytest.raises(ValueError, match="dt"):
        dp.crossed_column_shear_wavenumber(frequency=100.0, h=1.25, width=1.25, dt=0.0, **ROCK)


@REQ
def test_midpoint_driven_base_keeps_the_phase_and_gains_amplitude():
    # The sum dt sum_k A sin(w (k + 1/2) dt), added up here, against the closed form at t_n = n dt.
    A, f, dt = 0.01, 100.0, 1e-3
    omega = 2 * math.pi * f
    n = np.arange(0, 60)
    summed = np.concatenate([[0.0], np.cumsum(dt * A * np.sin(omega * (np.arange(59) + 0.5) * dt))])
    gain = dp.driven_sine_displacement_gain(frequency=f, dt=dt)
    assert summed == pytest.approx(gain * A / omega * (1.0 - np.cos(omega * n * dt)), rel=1e-12, abs=1e-18)
    # w dt = pi / 3: (pi / 6) / sin(pi / 6) = pi / 3.
    assert dp.driven_sine_displacement_gain(frequency=1.0 / 6.0, dt=1.0) == pytest.approx(math.pi / 3.0, rel=1e-14, abs=0)


@REQ
def test_discrete_wave_at_a_station_is_the_base_motion_delayed_by_k_distance():
    h, dt, L = 0.625, 9e-5, 40.0
    t = np.array([0.01, 0.039, 0.041, 0.07])
    u = dp.crossed_column_sine_displacement(t, distance=L, h=h, width=h, dt=dt, amplitude=0.01, frequency=100.0, **ROCK)
    k = dp.crossed_column_shear_wavenumber(frequency=100.0, h=h, width=h, dt=dt, **ROCK)
    omega = 2 * math.pi * 100.0
    expected = dp.driven_sine_displacement_gain(frequency=100.0, dt=dt) * 0.01 / omega * (1 - np.cos(omega * t[2:] - k * L))
    assert u[:2] == pytest.approx([0.0, 0.0], abs=0.0)     # before L / c_s = 40 ms
    assert u[2:] == pytest.approx(expected, rel=1e-13, abs=0)


@REQ
def test_undispersed_sine_displacement_is_the_integral_of_the_velocity():
    params = dict(distance=25.0, E=10e9, nu=0.25, rho=2500.0, amplitude=0.01, frequency=50.0)
    t = np.linspace(0.0, 0.05, 20001)
    u = el.s_wave_sine_displacement(t, **params)
    v = el.s_wave_sine_velocity(t, **params)
    assert np.gradient(u, t)[1:-1] == pytest.approx(v[1:-1], abs=2e-6)
    assert u[t < 25.0 / 1264.9] == pytest.approx(0.0, abs=0.0)
    # Half a period after the arrival the displacement is its largest, 2 A / w.
    assert el.s_wave_sine_displacement(25.0 / math.sqrt(4e9 / 2500.0) + 0.01, **params) == pytest.approx(
        2 * 0.01 / (2 * math.pi * 50.0), rel=1e-12, abs=0)

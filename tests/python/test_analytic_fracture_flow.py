"""Fracture-flow references (verification/analytic/fracture_flow.py) at known values.

Known values are worked by hand in the comments. Consistency checks take independent routes:
quadrature of the parallel-plate velocity profiles (Newtonian and Bingham), finite differences of
the diffusion equation in space and time, a method-of-lines solution of the finite joint
(scipy solve_ivp, Richardson-extrapolated), the Fourier series against the image series, an ODE
integration of the deformable joint's pressure profile, quadrature of the grout front's dt/dI
written from the flow law, and a dense numpy solve of a random network.

Tolerances: 1e-12 relative where the two sides are closed forms of the same quantity in double
precision (a few roundings apart); the looser ones are stated where they are used, with the error
of the independent route that sets them.
"""
import math

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp
from scipy.optimize import minimize
from scipy.special import erfc

from analytic import fracture_flow as ff

REQ = pytest.mark.requirements("REQ-QA-003")

# A water-filled joint: a = 0.1 mm, mu = 1 mPa s, Kw = 2 GPa, kn = 10 GPa/m.
# T = a^3 / (12 mu) = 1e-12 / 0.012 = 8.3333333333e-11 m^3/(Pa s)
# rigid:      S = a / Kw = 5e-14 m/Pa,                D = T / S = 1666.6666667 m^2/s
# deformable: S = 5e-14 + 1e-10 = 1.0005e-10 m/Pa,    D = 0.83291687 m^2/s
WATER = dict(aperture=1e-4, viscosity=1e-3, fluid_bulk_modulus=2e9)
T_WATER = 1e-12 / 0.012
# Grout: a = 0.1 mm, mu = 0.05 Pa s, tau_y = 5 Pa, dp = 1 MPa.
# J0 = 2 * 5 / 1e-4 = 1e5 Pa/m, I_max = 1e6 * 1e-4 / 10 = 10 m, t0 = 6 * 0.05 * 1e6 / 25 = 12000 s.
GROUT = dict(aperture=1e-4, viscosity=0.05, overpressure=1e6, yield_stress=5.0)
LAWS = ("linear", "buckingham")


# ---------------------------------------------------------------- cubic law and point contacts


@REQ
def test_cubic_law_known_values():
    # a = 1e-4, mu = 1e-3, L = 2, dp = 1e4: q = 1e-12 * 1e4 / (0.012 * 2) = 4.1666666667e-7 m^2/s
    assert ff.cubic_law_flow(aperture=1e-4, viscosity=1e-3, length=2.0, pressure_drop=1e4) == \
        pytest.approx(4.1666666667e-7, rel=1e-10, abs=0)
    assert ff.cubic_law_conductance(aperture=1e-4, viscosity=1e-3, length=2.0) == pytest.approx(4.1666666667e-11, rel=1e-10, abs=0)
    # the flow reverses with the pressure drop
    assert ff.cubic_law_flow(aperture=1e-4, viscosity=1e-3, length=2.0, pressure_drop=-1e4) == \
        pytest.approx(-4.1666666667e-7, rel=1e-10, abs=0)
    # point contact: kc = 2e-9, dp = 5e3 -> q = 1e-5
    assert ff.point_contact_flow(permeability=2e-9, pressure_drop=5e3) == pytest.approx(1e-5, rel=1e-15, abs=0)


@REQ
def test_cubic_law_slope_is_three_on_a_log_log_plot():
    apertures = np.array([2e-5, 5e-5, 1e-4, 2e-4, 5e-4])
    q = ff.cubic_law_flow(aperture=apertures, viscosity=1e-3, length=1.0, pressure_drop=1e3)
    slope, _ = np.polyfit(np.log(apertures), np.log(q), 1)
    assert slope == pytest.approx(3.0, abs=1e-12)


@REQ
@pytest.mark.parametrize("aperture", [3e-5, 1e-4, 7e-4])
def test_cubic_law_is_the_integral_of_the_poiseuille_profile(aperture):
    # u(y) = J (a^2/4 - y^2) / (2 mu) across the slot, integrated by quadrature (rel 1e-13)
    mu, J = 1.3e-3, 2.5e4
    q, _ = quad(lambda y: J * (aperture ** 2 / 4 - y * y) / (2 * mu), -aperture / 2, aperture / 2, epsrel=1e-14)
    assert ff.cubic_law_flow(aperture=aperture, viscosity=mu, length=2.0, pressure_drop=2.0 * J) == \
        pytest.approx(q, rel=1e-12, abs=0)


# ---------------------------------------------------------------- storage and diffusivity


@REQ
def test_storage_and_diffusivity_known_values():
    assert ff.joint_storage(aperture=1e-4, fluid_bulk_modulus=2e9) == pytest.approx(5e-14, rel=1e-15, abs=0)
    assert ff.joint_storage(aperture=1e-4, fluid_bulk_modulus=2e9, normal_stiffness=1e10) == \
        pytest.approx(1.0005e-10, rel=1e-14, abs=0)
    assert ff.joint_transmissivity(aperture=1e-4, viscosity=1e-3) == pytest.approx(T_WATER, rel=1e-15, abs=0)
    assert ff.hydraulic_diffusivity(**WATER) == pytest.approx(1666.6666666667, rel=1e-12, abs=0)
    # a^2 Kw / (12 mu) for a rigid joint
    assert ff.hydraulic_diffusivity(**WATER) == pytest.approx(1e-8 * 2e9 / 0.012, rel=1e-14, abs=0)
    assert ff.hydraulic_diffusivity(**WATER, normal_stiffness=1e10) == pytest.approx(T_WATER / 1.0005e-10, rel=1e-14, abs=0)
    assert ff.hydraulic_diffusivity(**WATER, normal_stiffness=1e10) == pytest.approx(0.83291687, rel=1e-8, abs=0)


# ---------------------------------------------------------------- semi-infinite joint


@REQ
def test_semi_infinite_step_known_values():
    D = 1666.6666666666667
    t = 0.3
    x = 2.0 * math.sqrt(D * t)                 # erfc(1) = 0.15729920705028513
    assert ff.step_pressure_semi_infinite(x=x, t=t, p0=1e5, p1=6e5, **WATER) == \
        pytest.approx(1e5 + 5e5 * 0.15729920705028513, rel=1e-13, abs=0)
    assert ff.step_pressure_semi_infinite(x=0.0, t=t, p0=1e5, p1=6e5, **WATER) == 6e5
    # q = T dp / sqrt(pi D t) = 8.3333e-11 * 5e5 / sqrt(pi * 500) = 4.1666667e-5 / 39.633272976 = 1.0513052e-6
    assert ff.step_inflow_rate_semi_infinite(t=t, p0=1e5, p1=6e5, **WATER) == pytest.approx(1.0513052e-6, rel=1e-7, abs=0)
    # V = 2 S dp sqrt(D t / pi) = 2 * 5e-14 * 5e5 * sqrt(500 / pi) = 5e-8 * 12.615662610 = 6.3078313e-7
    assert ff.step_inflow_volume_semi_infinite(t=t, p0=1e5, p1=6e5, **WATER) == pytest.approx(6.3078313e-7, rel=1e-8, abs=0)


@REQ
@pytest.mark.parametrize("kn", [math.inf, 1e10])
def test_semi_infinite_step_solves_the_diffusion_equation(kn):
    # central differences, relative steps 1e-4: truncation ~1e-8 of the terms, rounding ~1e-8
    D = ff.hydraulic_diffusivity(**WATER, normal_stiffness=kn)
    t = 1e-3 / D * 40.0
    x = np.array([0.2, 0.5, 1.0, 1.5]) * math.sqrt(D * t)
    p = lambda x, t: ff.step_pressure_semi_infinite(x=x, t=t, p0=0.0, p1=1.0, **WATER, normal_stiffness=kn)
    ht, hx = 1e-4 * t, 1e-4 * math.sqrt(D * t)
    p_t = (p(x, t + ht) - p(x, t - ht)) / (2 * ht)
    p_xx = (p(x + hx, t) - 2 * p(x, t) + p(x - hx, t)) / hx ** 2
    np.testing.assert_allclose(p_t, D * p_xx, rtol=1e-5)


@REQ
@pytest.mark.parametrize("kn", [math.inf, 1e10])
def test_semi_infinite_inflow_is_the_mouth_gradient_and_the_stored_volume(kn):
    D = ff.hydraulic_diffusivity(**WATER, normal_stiffness=kn)
    S = ff.joint_storage(aperture=1e-4, fluid_bulk_modulus=2e9, normal_stiffness=kn)
    t, p0, p1 = 2.0 / D, 2e5, 7e5
    args = dict(p0=p0, p1=p1, **WATER, normal_stiffness=kn)
    # rate = -T dp/dx at the mouth: fourth-order one-sided difference, h = 1e-3 sqrt(D t) (error ~1e-10)
    h = 1e-3 * math.sqrt(D * t)
    p = [ff.step_pressure_semi_infinite(x=k * h, t=t, **args) for k in range(5)]
    dpdx = (-25 * p[0] + 48 * p[1] - 36 * p[2] + 16 * p[3] - 3 * p[4]) / (12 * h)
    rate = ff.step_inflow_rate_semi_infinite(t=t, **args)
    assert rate == pytest.approx(-T_WATER * dpdx, rel=1e-7, abs=0)
    # volume = S * integral of (p - p0) dx, by quadrature (rel 1e-12) to 20 sqrt(D t), where erfc(10) = 2e-45,
    # with breakpoints where the profile bends: over the whole range at once quad's estimate was 1 %
    # (its result 8e-10 off for the rigid joint)
    L = math.sqrt(D * t)
    stored, _ = quad(lambda x: S * (ff.step_pressure_semi_infinite(x=x, t=t, **args) - p0), 0.0, 20 * L,
                     points=[L, 3 * L, 8 * L], epsrel=1e-13, limit=200)
    assert ff.step_inflow_volume_semi_infinite(t=t, **args) == pytest.approx(stored, rel=1e-11, abs=0)
    # rate = dV/dt (central difference, relative step 1e-5)
    dt = 1e-5 * t
    dvdt = (ff.step_inflow_volume_semi_infinite(t=t + dt, **args) - ff.step_inflow_volume_semi_infinite(t=t - dt, **args)) / (2 * dt)
    assert rate == pytest.approx(dvdt, rel=1e-8, abs=0)


# ---------------------------------------------------------------- finite joint


def finite_args(far_end, series="auto", kn=math.inf):
    return dict(p0=1e5, p1=3e5, length=2.0, far_end=far_end, series=series, **WATER, normal_stiffness=kn)


def time_of(tau, kn=math.inf, length=2.0):
    return tau * length ** 2 / ff.hydraulic_diffusivity(**WATER, normal_stiffness=kn)


@REQ
@pytest.mark.parametrize("far_end", ["fixed", "impermeable"])
@pytest.mark.parametrize("tau", [0.005, 0.03, 0.1, 0.4, 2.0])
def test_fourier_and_image_series_agree(far_end, tau):
    # two independent representations of the same solution; both summed to 4e-18: agreement to 1e-13
    t = time_of(tau)
    x = np.linspace(0.0, 2.0, 9)
    fourier, images = finite_args(far_end, "fourier"), finite_args(far_end, "images")
    np.testing.assert_allclose(ff.step_pressure_finite(x=x, t=t, **fourier),
                               ff.step_pressure_finite(x=x, t=t, **images), rtol=1e-13)
    for f in (ff.step_inflow_rate_finite, ff.step_inflow_volume_finite):
        assert f(t=t, **fourier) == pytest.approx(f(t=t, **images), rel=1e-13, abs=0)


@REQ
@pytest.mark.parametrize("far_end", ["fixed", "impermeable"])
def test_finite_joint_known_values(far_end):
    # tau = 1: the Fourier series' first term is exp(-pi^2) = 5.17e-5 (fixed) or exp(-pi^2/4) = 0.0848 (closed).
    # fixed, mid-joint: u = 1/2 - (2/pi) sum sin(n pi/2) exp(-n^2 pi^2) / n = 0.5 - 0.63662 * 5.1723e-5 = 0.49996707
    # closed, mid-joint: u = 1 - (4/pi) sin(pi/4) exp(-pi^2/4) - (4/(3 pi)) sin(3 pi/4) exp(-9 pi^2/4) ...
    #   = 1 - 0.9003163 * 0.0848050 - 0.3001054 * 2.2885e-10 = 0.9236487
    t = time_of(1.0)
    u = (ff.step_pressure_finite(x=1.0, t=t, **finite_args(far_end)) - 1e5) / 2e5
    expected = 0.5 - 2 / math.pi * math.exp(-math.pi ** 2) if far_end == "fixed" else \
        1 - 4 / math.pi * math.sin(math.pi / 4) * math.exp(-math.pi ** 2 / 4) \
        - 4 / (3 * math.pi) * math.sin(3 * math.pi / 4) * math.exp(-9 * math.pi ** 2 / 4)
    assert u == pytest.approx(expected, rel=1e-12, abs=0)
    assert u == pytest.approx(0.49996707 if far_end == "fixed" else 0.9236487, rel=1e-7, abs=0)
    # the mouth flow F(1) = 1 + 2 exp(-pi^2) (fixed) or 2 exp(-pi^2/4) + 2 exp(-9 pi^2/4) (closed), times T dp / L
    F = 1 + 2 * math.exp(-math.pi ** 2) if far_end == "fixed" else 2 * math.exp(-math.pi ** 2 / 4) + 2 * math.exp(-9 * math.pi ** 2 / 4)
    assert ff.step_inflow_rate_finite(t=t, **finite_args(far_end)) == pytest.approx(T_WATER * 2e5 / 2.0 * F, rel=1e-12, abs=0)


@REQ
@pytest.mark.parametrize("far_end", ["fixed", "impermeable"])
def test_finite_joint_start_time_shifts_the_clock(far_end):
    # A step at start_time = 3 s read at t = 3 s + t1 is the step at 0 read at t1; a read before the
    # step is refused, as t <= 0 is.
    t1 = time_of(0.3)
    args = dict(finite_args(far_end), normal_stiffness=1e10)
    assert ff.step_pressure_finite(3.0 + t1, x=0.7, start_time=3.0, **args) == pytest.approx(
        ff.step_pressure_finite(t1, x=0.7, **args), rel=1e-12, abs=0)
    assert ff.step_inflow_volume_finite(3.0 + t1, start_time=3.0, **args) == pytest.approx(
        ff.step_inflow_volume_finite(t1, **args), rel=1e-12, abs=0)
    with pytest.raises(ValueError, match="t = "):
        ff.step_pressure_finite(2.5, x=0.7, start_time=3.0, **args)


@REQ
@pytest.mark.parametrize("far_end", ["fixed", "impermeable"])
@pytest.mark.parametrize("kn", [math.inf, 1e10])
def test_finite_joint_at_short_times_is_the_semi_infinite_joint(far_end, kn):
    # tau = 0.01: the far end's first image is erfc(1 / sqrt(0.01) = 10) ~ 2e-45 away
    t = time_of(0.01, kn)
    x = np.linspace(0.0, 0.6, 7)
    semi = dict(p0=1e5, p1=3e5, **WATER, normal_stiffness=kn)
    np.testing.assert_allclose(ff.step_pressure_finite(x=x, t=t, **finite_args(far_end, kn=kn)),
                               ff.step_pressure_semi_infinite(x=x, t=t, **semi), rtol=1e-14)
    assert ff.step_inflow_rate_finite(t=t, **finite_args(far_end, kn=kn)) == \
        pytest.approx(ff.step_inflow_rate_semi_infinite(t=t, **semi), rel=1e-13, abs=0)
    assert ff.step_inflow_volume_finite(t=t, **finite_args(far_end, kn=kn)) == \
        pytest.approx(ff.step_inflow_volume_semi_infinite(t=t, **semi), rel=1e-13, abs=0)


@REQ
def test_finite_joint_at_long_times_is_steady():
    t = time_of(40.0)       # exp(-pi^2 * 40 / 4) = 1e-43
    x = np.linspace(0.0, 2.0, 5)
    np.testing.assert_allclose(ff.step_pressure_finite(x=x, t=t, **finite_args("fixed")), 3e5 - 2e5 * x / 2.0, rtol=1e-14)
    np.testing.assert_allclose(ff.step_pressure_finite(x=x, t=t, **finite_args("impermeable")), 3e5, rtol=1e-14)
    # steady cubic-law flow through, none into the closed joint, which holds S dp L
    assert ff.step_inflow_rate_finite(t=t, **finite_args("fixed")) == pytest.approx(T_WATER * 2e5 / 2.0, rel=1e-14, abs=0)
    assert ff.step_inflow_rate_finite(t=t, **finite_args("impermeable")) == pytest.approx(0.0, abs=1e-40)
    assert ff.step_inflow_volume_finite(t=t, **finite_args("impermeable")) == pytest.approx(5e-14 * 2e5 * 2.0, rel=1e-14, abs=0)
    # fixed: (T dp / L) t + S dp L / 3 (the stored triangle is S dp L / 2; 1/3 is what the mouth has
    # sent beyond the steady rate: the flow out of the far end lags it by S dp L / 6)
    assert ff.step_inflow_volume_finite(t=t, **finite_args("fixed")) == \
        pytest.approx(T_WATER * 2e5 / 2.0 * t + 5e-14 * 2e5 * 2.0 / 3.0, rel=1e-14, abs=0)


@REQ
@pytest.mark.parametrize("far_end", ["fixed", "impermeable"])
def test_finite_joint_inflow_is_dv_dt_and_the_mouth_gradient(far_end):
    args = finite_args(far_end, kn=1e10)
    for tau in (0.02, 0.1, 0.5):
        t = time_of(tau, 1e10)
        dt = 1e-5 * t       # central difference: error ~1e-10 relative
        dvdt = (ff.step_inflow_volume_finite(t=t + dt, **args) - ff.step_inflow_volume_finite(t=t - dt, **args)) / (2 * dt)
        rate = ff.step_inflow_rate_finite(t=t, **args)
        assert rate == pytest.approx(dvdt, rel=1e-8, abs=0)
        h = 1e-4 * 2.0      # fourth-order one-sided gradient at the mouth: error ~1e-12
        p = [ff.step_pressure_finite(x=k * h, t=t, **args) for k in range(5)]
        dpdx = (-25 * p[0] + 48 * p[1] - 36 * p[2] + 16 * p[3] - 3 * p[4]) / (12 * h)
        assert rate == pytest.approx(-T_WATER * dpdx, rel=1e-6, abs=0)


@REQ
def test_closed_joint_inflow_is_what_it_stores():
    S = ff.joint_storage(aperture=1e-4, fluid_bulk_modulus=2e9, normal_stiffness=1e10)
    args = finite_args("impermeable", kn=1e10)
    for tau in (0.03, 0.3):
        t = time_of(tau, 1e10)
        stored, _ = quad(lambda x: S * (ff.step_pressure_finite(x=x, t=t, **args) - 1e5), 0.0, 2.0, epsrel=1e-13)
        assert ff.step_inflow_volume_finite(t=t, **args) == pytest.approx(stored, rel=1e-11, abs=0)


def method_of_lines(far_end, cells, taus):
    """u(xi, tau) of u_tau = u_xixi on [0, 1], u(0) = 1, u(1) = 0 or u_xi(1) = 0, u(., 0) = 0:
    second-order central differences on `cells` cells (the closed end by a mirror node),
    integrated in time by scipy's Radau at rtol 1e-11; returns the nodes and u at taus."""
    h = 1.0 / cells
    nodes = np.linspace(0.0, 1.0, cells + 1)
    free = cells if far_end == "impermeable" else cells - 1     # unknowns at nodes 1 .. free

    def rhs(_, u):
        full = np.concatenate([[1.0], u, [u[-2]] if far_end == "impermeable" else [0.0]])
        return (full[2:] - 2 * full[1:-1] + full[:-2]) / h ** 2

    main = np.full(free, -2.0 / h ** 2)
    jac = np.diag(main) + np.diag(np.full(free - 1, 1.0 / h ** 2), 1) + np.diag(np.full(free - 1, 1.0 / h ** 2), -1)
    if far_end == "impermeable":
        jac[-1, -2] = 2.0 / h ** 2
    sol = solve_ivp(rhs, (0.0, max(taus)), np.zeros(free), method="Radau", t_eval=taus, jac=jac,
                    rtol=1e-11, atol=1e-13)
    u = np.zeros((len(taus), cells + 1))
    u[:, 0] = 1.0
    u[:, 1:free + 1] = sol.y.T
    return nodes, u


@REQ
@pytest.mark.parametrize("far_end", ["fixed", "impermeable"])
def test_finite_joint_matches_a_method_of_lines_solution(far_end):
    # 40 and 80 cells, Richardson-extrapolated (error O(h^4) ~ 1e-7 at tau >= 0.05 once the
    # start-up singularity has diffused); the comparison at 2e-6 of the step.
    taus = [0.05, 0.2, 0.8]
    coarse_nodes, coarse = method_of_lines(far_end, 40, taus)
    _, fine = method_of_lines(far_end, 80, taus)
    extrapolated = (4.0 * fine[:, ::2] - coarse) / 3.0
    for k, tau in enumerate(taus):
        exact = (ff.step_pressure_finite(x=2.0 * coarse_nodes, t=time_of(tau), **finite_args(far_end)) - 1e5) / 2e5
        np.testing.assert_allclose(extrapolated[k], exact, atol=2e-6)
        # and the unextrapolated fine grid is second-order close, not exact (the check can see 1e-4)
        assert np.max(np.abs(fine[k, ::2] - exact)) > 1e-8


@REQ
@pytest.mark.parametrize("far_end", ["fixed", "impermeable"])
def test_auto_series_is_continuous_at_its_switch(far_end):
    t = time_of(0.1)
    below, above = t * (1 - 1e-13), t * (1 + 1e-13)
    for f, kw in ((ff.step_pressure_finite, dict(x=0.7)), (ff.step_inflow_rate_finite, {}), (ff.step_inflow_volume_finite, {})):
        assert f(t=below, **kw, **finite_args(far_end)) == pytest.approx(f(t=above, **kw, **finite_args(far_end)), rel=1e-12, abs=0)


# ---------------------------------------------------------------- pressure-dependent aperture

# kn = 1e9 Pa/m, a_out = 1e-4, p_in = 1e5, p_out = 0: a_in = 1e-4 + 1e5 / 1e9 = 2e-4.
DEFORMABLE = dict(p_in=1e5, p_out=0.0, outlet_aperture=1e-4, normal_stiffness=1e9, viscosity=1e-3, length=1.0)


@REQ
def test_deformable_joint_known_values():
    # q = 1e9 (16e-16 - 1e-16) / (48e-3) = 3.125e-5 m^2/s
    assert ff.deformable_joint_steady_flow(**DEFORMABLE) == pytest.approx(3.125e-5, rel=1e-12, abs=0)
    # mid-joint: a^4 = (16 + 1)/2 e-16 -> a = 8.5^(1/4) e-4 = 1.7074694e-4, p = 1e9 (a - a_out) = 70746.94 Pa
    a, p = ff.deformable_joint_steady_profile(x=0.5, **DEFORMABLE)
    assert a == pytest.approx(8.5 ** 0.25 * 1e-4, rel=1e-14, abs=0)
    assert p == pytest.approx(1e9 * (8.5 ** 0.25 - 1) * 1e-4, rel=1e-12, abs=0)
    a, p = ff.deformable_joint_steady_profile(x=np.array([0.0, 1.0]), **DEFORMABLE)
    np.testing.assert_allclose(a, [2e-4, 1e-4], rtol=1e-15)
    np.testing.assert_allclose(p, [1e5, 0.0], atol=1e-9)


@REQ
def test_deformable_joint_profile_integrates_the_cubic_law():
    # dp/dx = -12 mu q / a(p)^3 from p_in, a(p) = a_out + (p - p_out)/kn; DOP853 at rtol 1e-12
    q = ff.deformable_joint_steady_flow(**DEFORMABLE)
    sol = solve_ivp(lambda x, p: [-12e-3 * q / (1e-4 + (p[0] - 0.0) / 1e9) ** 3], (0.0, 1.0), [1e5],
                    method="DOP853", rtol=1e-12, atol=1e-9, dense_output=True)
    assert sol.y[0, -1] == pytest.approx(0.0, abs=1e-6)          # reaches p_out at L: 1e-11 of p_in
    x = np.linspace(0.0, 1.0, 11)
    _, p = ff.deformable_joint_steady_profile(x=x, **DEFORMABLE)
    np.testing.assert_allclose(p, sol.sol(x)[0], atol=1e-6)


@REQ
def test_stiff_deformable_joint_is_the_cubic_law():
    # kn = 1e15: the inlet opens by d = dp / kn = 1e-10 m, 1e-6 of a_out; expanding (a + d)^4 - a^4,
    # q / q_cubic = 1 + (3/2) d / a + (d / a)^2 + ...: 1.5e-6 above the cubic law, known to ~1e-4 of
    # itself (a_in^4 - a_out^4 loses 6 digits to cancellation)
    stiff = dict(DEFORMABLE, normal_stiffness=1e15)
    cubic = ff.cubic_law_flow(aperture=1e-4, viscosity=1e-3, length=1.0, pressure_drop=1e5)
    assert ff.deformable_joint_steady_flow(**stiff) / cubic - 1.0 == pytest.approx(1.5e-6, rel=1e-3, abs=0)


# ---------------------------------------------------------------- jacking and hydrostatics


@REQ
def test_jacking_aperture_known_values():
    # a0 = 5e-5, sn = 2e6, kn = 1e10: closed at and below sn, 5e-5 + 1e6 / 1e10 = 1.5e-4 at p = 3e6
    args = dict(closed_aperture=5e-5, normal_stress=2e6, normal_stiffness=1e10)
    np.testing.assert_allclose(ff.jacking_aperture(pressure=np.array([0.0, 1.9e6, 2e6, 3e6]), **args),
                               [5e-5, 5e-5, 5e-5, 1.5e-4], rtol=1e-14)
    # the slope above the opening pressure is 1 / kn
    assert (ff.jacking_aperture(pressure=4e6, **args) - ff.jacking_aperture(pressure=3e6, **args)) / 1e6 == \
        pytest.approx(1e-10, rel=1e-9, abs=0)


@REQ
def test_hydrostatic_pressure_and_column_stresses_known_values():
    # 1000 * 9.81 * 10 = 98100 Pa; dry above the table
    assert ff.hydrostatic_pressure(depth_below_table=10.0, water_density=1000.0, g=9.81) == pytest.approx(98100.0, rel=1e-15, abs=0)
    assert ff.hydrostatic_pressure(depth_below_table=-3.0, water_density=1000.0, g=9.81) == 0.0
    # rock 2500 kg/m^3, joint 10 m down, table 2 m down: total 245250, p = 78480, effective 166770
    total, p, eff = ff.column_joint_stresses(depth=10.0, rock_density=2500.0, water_density=1000.0, g=9.81, table_depth=2.0)
    assert (total, p, eff) == pytest.approx((245250.0, 78480.0, 166770.0), rel=1e-14, abs=0)
    # 3 m of water standing on top adds 29430 Pa to the total stress and the pressure alike
    total, p, eff = ff.column_joint_stresses(depth=10.0, rock_density=2500.0, water_density=1000.0, g=9.81, table_depth=-3.0)
    assert (total, p, eff) == pytest.approx((274680.0, 127530.0, 147150.0), rel=1e-14, abs=0)
    # a surcharge loads the contacts only
    total, p, eff = ff.column_joint_stresses(depth=np.array([0.0, 4.0]), rock_density=2000.0, water_density=1000.0,
                                             g=10.0, surcharge=1e5)
    np.testing.assert_allclose(total, [1e5, 1.8e5], rtol=1e-15)
    np.testing.assert_allclose(eff, [1e5, 1.4e5], rtol=1e-15)


# ---------------------------------------------------------------- Bingham laws


def bingham_slit_flow_by_quadrature(a, mu, tau_y, J):
    """q of a Bingham fluid between plates, from the velocity profile integrated numerically:
    shear stress J y, rigid plug where |J y| <= tau_y, mu du/dy = -(J y - tau_y) outside (y > 0),
    u(a/2) = 0, symmetric."""
    y0 = tau_y / J
    if y0 >= a / 2:
        return 0.0
    u = lambda y: (J * ((a / 2) ** 2 - max(y, y0) ** 2) / 2 - tau_y * (a / 2 - max(y, y0))) / mu
    half, _ = quad(u, 0.0, a / 2, points=[y0], epsrel=1e-13, epsabs=0.0)
    return 2.0 * half


@REQ
def test_bingham_threshold_and_laws_known_values():
    # J0 = 2 * 5 / 1e-4 = 1e5 Pa/m; T = 1e-12 / (12 * 0.05) = 1.6666667e-12
    assert ff.bingham_threshold_gradient(aperture=1e-4, yield_stress=5.0) == pytest.approx(1e5, rel=1e-15, abs=0)
    args = dict(aperture=1e-4, viscosity=0.05, yield_stress=5.0)
    T = 1e-12 / 0.6
    # linear law at J = 3 J0: T (3e5 - 1e5) = 3.3333333e-7
    assert ff.bingham_linear_flow(gradient=3e5, **args) == pytest.approx(T * 2e5, rel=1e-14, abs=0)
    # Buckingham at J = 2 J0: r = 1/2, 1 - 3/4 + 1/16 = 0.3125, q = T 2e5 0.3125 = 1.0416667e-7
    assert ff.buckingham_flow(gradient=2e5, **args) == pytest.approx(T * 2e5 * 0.3125, rel=1e-14, abs=0)
    assert ff.buckingham_flow(gradient=-2e5, **args) == pytest.approx(-T * 2e5 * 0.3125, rel=1e-14, abs=0)


@REQ
@pytest.mark.parametrize("ratio", [1.01, 1.5, 3.0, 20.0])
def test_buckingham_law_is_the_integral_of_the_bingham_profile(ratio):
    a, mu, tau_y = 2e-4, 0.03, 4.0
    J = ratio * 2 * tau_y / a
    assert ff.buckingham_flow(aperture=a, viscosity=mu, yield_stress=tau_y, gradient=J) == \
        pytest.approx(bingham_slit_flow_by_quadrature(a, mu, tau_y, J), rel=1e-11, abs=0)


@REQ
@pytest.mark.parametrize("law", [ff.bingham_linear_flow, ff.buckingham_flow])
def test_bingham_laws_without_yield_stress_are_newtonian(law):
    J = np.array([-3e4, -1.0, 0.0, 2.0, 5e5])
    np.testing.assert_allclose(law(aperture=1e-4, viscosity=1e-3, yield_stress=0.0, gradient=J),
                               ff.cubic_law_flow(aperture=1e-4, viscosity=1e-3, length=1.0, pressure_drop=J), rtol=1e-15)


@REQ
@pytest.mark.parametrize("law", [ff.bingham_linear_flow, ff.buckingham_flow])
def test_bingham_laws_do_not_flow_up_to_the_threshold(law):
    args = dict(aperture=1e-4, viscosity=0.05, yield_stress=5.0)
    J = np.array([-1e5, -5e4, 0.0, 3e4, 1e5])
    np.testing.assert_array_equal(law(gradient=J, **args), 0.0)
    # and flow just above it, in the direction of the gradient
    assert law(gradient=1.001e5, **args) > 0.0 > law(gradient=-1.001e5, **args)


@REQ
def test_buckingham_law_approaches_the_asymptote_three_halves_threshold():
    # q_B - T (J - 3/2 J0) = T J0^3 / (2 J^2) exactly; at J = 100 J0 that is 5e-5 T J0
    args = dict(aperture=1e-4, viscosity=0.05, yield_stress=5.0)
    T, J0 = 1e-12 / 0.6, 1e5
    for ratio in (10.0, 100.0, 1000.0):
        J = ratio * J0
        gap = ff.buckingham_flow(gradient=J, **args) - T * (J - 1.5 * J0)
        assert gap == pytest.approx(T * J0 / (2 * ratio ** 2), rel=1e-6, abs=0)
    # below the linear law everywhere above the threshold: their ratio is (1 - r)(2 + r) / 2 < 1
    J = J0 * np.array([1.0001, 1.1, 2.0, 10.0])
    r = J0 / J
    np.testing.assert_allclose(ff.buckingham_flow(gradient=J, **args) / ff.bingham_linear_flow(gradient=J, **args),
                               (1 - r) * (2 + r) / 2, rtol=1e-9)


# ---------------------------------------------------------------- grout penetration


@REQ
def test_grout_scales_known_values():
    assert ff.grout_max_penetration(aperture=1e-4, overpressure=1e6, yield_stress=5.0) == pytest.approx(10.0, rel=1e-15, abs=0)
    assert ff.grout_time_scale(viscosity=0.05, overpressure=1e6, yield_stress=5.0) == pytest.approx(12000.0, rel=1e-15, abs=0)


@REQ
def test_grout_dimensionless_time_known_values():
    # linear, I_D = 1/2: 0.5 (-0.5 + ln 2) = 0.09657359027997264
    # Buckingham, I_D = 1/2: 1/3 + (2/9) ln(0.5 / 1.25) = 0.3333333333 - 0.2036201626 = 0.12971317069
    assert ff.grout_dimensionless_time(relative_penetration=0.5, law="linear") == pytest.approx(0.09657359027997264, rel=1e-14, abs=0)
    assert ff.grout_dimensionless_time(relative_penetration=0.5, law="buckingham") == pytest.approx(0.1297131706946, rel=1e-12, abs=0)
    # I_D = 0.9: linear 0.5 (-0.9 + ln 10) = 0.70129254649702; Buckingham 3 + (2/9) ln(0.1/1.45) = 2.40574474
    assert ff.grout_dimensionless_time(relative_penetration=0.9, law="linear") == pytest.approx(0.7012925464970229, rel=1e-14, abs=0)
    assert ff.grout_dimensionless_time(relative_penetration=0.9, law="buckingham") == \
        pytest.approx(3.0 + 2.0 / 9.0 * math.log(0.1 / 1.45), rel=1e-13, abs=0)
    # both start as I_D^2 / 4: at I_D = 1e-6, 2.5e-13 (next term I_D^3 / 6 or I_D^3 / 4: 1e-6 relative)
    for law in LAWS:
        assert ff.grout_dimensionless_time(relative_penetration=1e-6, law=law) == pytest.approx(2.5e-13, rel=2e-6, abs=0)


def grout_time_by_quadrature(penetration, law):
    """t (s) for the front to reach I, integrating dt = a dI / q(J = dp / I) by quadrature, q from
    the flow law written out here (a, mu, dp, tau_y of GROUT)."""
    a, mu, dp, tau_y = 1e-4, 0.05, 1e6, 5.0
    J0 = 2 * tau_y / a

    def q(I):
        J = dp / I
        if law == "linear":
            return a ** 3 / (12 * mu) * (J - J0)
        return a ** 3 * J / (12 * mu) * (1 - 1.5 * J0 / J + 0.5 * (J0 / J) ** 3)

    value, _ = quad(lambda I: a / q(I), 0.0, penetration, epsrel=1e-13, epsabs=0.0, limit=200)
    return value


@REQ
@pytest.mark.parametrize("law", LAWS)
@pytest.mark.parametrize("relative", [0.01, 0.3, 0.7, 0.95, 0.999])
def test_grout_time_is_the_quadrature_of_dt_di(law, relative):
    t0 = 12000.0
    expected = grout_time_by_quadrature(10.0 * relative, law)
    assert t0 * ff.grout_dimensionless_time(relative_penetration=relative, law=law) == pytest.approx(expected, rel=1e-10, abs=0)


@REQ
@pytest.mark.parametrize("law", LAWS)
def test_grout_penetration_inverts_the_time(law):
    relative = np.array([1e-7, 0.05, 0.0999, 0.1001, 0.4, 0.5, 0.6, 0.9, 0.9999])
    t = 12000.0 * ff.grout_dimensionless_time(relative_penetration=relative, law=law)
    np.testing.assert_allclose(ff.grout_penetration(t=t, **GROUT, law=law), 10.0 * relative, rtol=1e-13)
    assert ff.grout_penetration(t=0.0, **GROUT, law=law) == 0.0


@REQ
def test_grout_penetration_at_early_times_is_newtonian():
    # dI/dt = a^2 dp / (12 mu I): I = sqrt(a^2 dp t / (6 mu)); at t = 1e-6 t0 = 0.012 s,
    # I = sqrt(1e-8 * 1e6 * 0.012 / 0.3) = 0.02 m; the threshold slows it by ~I_D / 3 (linear) = 7e-4
    for law in LAWS:
        I = ff.grout_penetration(t=0.012, **GROUT, law=law)
        assert I == pytest.approx(0.02, rel=2e-3, abs=0)
        assert I < 0.02


@REQ
def test_grout_penetration_approaches_i_max_under_both_laws():
    t0 = 12000.0
    t = t0 * np.array([0.01, 0.1, 1.0, 10.0, 100.0])
    linear = ff.grout_penetration(t=t, **GROUT, law="linear")
    buckingham = ff.grout_penetration(t=t, **GROUT, law="buckingham")
    assert np.all(np.diff(linear) > 0) and np.all(np.diff(buckingham) > 0)
    assert np.all(buckingham < linear) and np.all(linear <= 10.0)
    # linear: 1 - I_D = exp(-1 - 2 t_D - I_D + 1) -> exp(-1 - 2 t_D) at I_D -> 1: exp(-21) = 7.6e-10 at t_D = 10
    assert 10.0 - linear[3] == pytest.approx(10.0 * math.exp(-21.0), rel=1e-6, abs=0)
    # Buckingham: 1 - I_D -> 1 / (3 t_D) (next order ~ ln(t_D) / t_D^2): 1/300 at t_D = 100, to 2 %
    assert (10.0 - buckingham[4]) / 10.0 == pytest.approx(1.0 / 300.0, rel=2e-2, abs=0)
    # both reach I_max to 1e-5 relative by t_D = 1e5
    for law in LAWS:
        assert ff.grout_penetration(t=1e5 * t0, **GROUT, law=law) == pytest.approx(10.0, rel=1e-5, abs=0)


# ---------------------------------------------------------------- steady network

MU = 1e-3
C1 = 1e-12 / (12 * MU * 1.0)        # a = 1e-4, L = 1: 8.3333e-11
C2 = 8e-12 / (12 * MU * 2.0)        # a = 2e-4, L = 2: 3.3333e-10
SERIES = dict(domain_ids=["A", "B", "C"], fixed=[True, False, True], link_from=["A", "B"], link_to=["B", "C"],
              aperture=[1e-4, 2e-4], length=[1.0, 2.0], viscosity=MU)


@REQ
def test_network_series_circuit_known_values():
    # q = dp / (1/C1 + 1/C2) = 1e5 / (1.2e10 + 3e9) = 6.6666667e-6; p_B = 1e5 - q / C1 = 2e4
    r = ff.steady_network_flow(fixed_pressure=[1e5, np.nan, 0.0], **SERIES)
    np.testing.assert_allclose(r["link_flow"], [6.6666666666667e-6] * 2, rtol=1e-12)
    np.testing.assert_allclose(r["pressure"], [1e5, 2e4, 0.0], rtol=1e-12)
    np.testing.assert_allclose(r["boundary_inflow"], [6.6666666666667e-6, 0.0, -6.6666666666667e-6], rtol=1e-12)
    assert r["iterations"] == 1 and not np.any(r["stagnant"])


@REQ
def test_network_parallel_circuit_known_values():
    # three links between X (2e4 Pa) and Y (0): q_k = C_k 2e4; links listed both ways round
    r = ff.steady_network_flow(domain_ids=[7, 9], fixed=[True, True], fixed_pressure=[2e4, 0.0],
                               link_from=[7, 9, 7], link_to=[9, 7, 9], aperture=[1e-4, 2e-4, 1e-4],
                               length=[1.0, 2.0, 4.0], viscosity=MU)
    np.testing.assert_allclose(r["link_flow"], [C1 * 2e4, -C2 * 2e4, C1 / 4 * 2e4], rtol=1e-14)
    assert r["boundary_inflow"][0] == pytest.approx((C1 + C2 + C1 / 4) * 2e4, rel=1e-14, abs=0)


@REQ
def test_network_source_raises_its_domain_by_flow_over_conductance():
    # 1e-9 m^2/s injected into B, drained to A at 0 through one link: p_B = 1e-9 / C1 = 12 Pa
    r = ff.steady_network_flow(domain_ids=["A", "B"], fixed=[True, False], fixed_pressure=[0.0, 0.0],
                               source=[0.0, 1e-9], link_from=["A"], link_to=["B"], aperture=1e-4, length=1.0,
                               viscosity=MU)
    assert r["pressure"][1] == pytest.approx(12.0, rel=1e-13, abs=0)
    assert r["boundary_inflow"][0] == pytest.approx(-1e-9, rel=1e-13, abs=0)


def random_network(seed, domains=40, extra_links=60):
    """A connected random network: a random spanning tree plus extra links; three fixed domains."""
    rng = np.random.default_rng(seed)
    order = rng.permutation(domains)
    frm = [order[k] for k in range(1, domains)]
    to = [order[rng.integers(0, k)] for k in range(1, domains)]
    for _ in range(extra_links):
        a, b = rng.choice(domains, size=2, replace=False)
        frm.append(a)
        to.append(b)
    fixed = np.zeros(domains, dtype=bool)
    fixed[rng.choice(domains, size=3, replace=False)] = True
    source = np.where(fixed, 0.0, rng.normal(0.0, 1e-8, domains) * (rng.random(domains) < 0.2))
    return dict(domain_ids=[f"d{k}" for k in range(domains)], fixed=fixed,
                fixed_pressure=np.where(fixed, rng.uniform(0.0, 1e5, domains), np.nan),
                link_from=[f"d{k}" for k in frm], link_to=[f"d{k}" for k in to],
                aperture=rng.uniform(2e-5, 3e-4, len(frm)), length=rng.uniform(0.1, 2.0, len(frm)),
                viscosity=MU, source=source)


@REQ
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_network_matches_a_dense_solve_and_balances_mass(seed):
    net = random_network(seed)
    r = ff.steady_network_flow(**net)
    n = len(net["domain_ids"])
    i = np.array([int(d[1:]) for d in net["link_from"]])
    j = np.array([int(d[1:]) for d in net["link_to"]])
    C = net["aperture"] ** 3 / (12 * MU * net["length"])
    K = np.zeros((n, n))
    for a, b, c in zip(i, j, C):
        K[a, a] += c; K[b, b] += c; K[a, b] -= c; K[b, a] -= c
    free, fixed = ~net["fixed"], net["fixed"]
    p = np.array(net["fixed_pressure"], dtype=float)
    p[free] = np.linalg.solve(K[np.ix_(free, free)], net["source"][free] - K[np.ix_(free, fixed)] @ p[fixed])
    # rounding of two solves of a system of condition ~1e4: 1e-10 relative to the largest pressure
    np.testing.assert_allclose(r["pressure"], p, atol=1e-10 * np.max(np.abs(p)))
    scale = np.max(np.abs(r["link_flow"]))
    # every free domain balances and the boundary flows close the books, to round-off
    residual = np.bincount(i, r["link_flow"], n) - np.bincount(j, r["link_flow"], n) - net["source"]
    assert np.max(np.abs(residual[free])) < 1e-12 * scale
    assert abs(np.sum(r["boundary_inflow"]) + np.sum(net["source"])) < 1e-12 * scale


@REQ
def test_network_bingham_series_flows_only_above_both_thresholds():
    # tau_y = 1e-3 Pa: h1 = 2e-3 * 1 / 1e-4 = 20 Pa, h2 = 2e-3 * 2 / 2e-4 = 20 Pa
    args = dict(SERIES, yield_stress=1e-3)
    r = ff.steady_network_flow(fixed_pressure=[1e5, np.nan, 0.0], **args)
    q = (1e5 - 40.0) / (1 / C1 + 1 / C2)      # 6.664e-6
    np.testing.assert_allclose(r["link_flow"], [q, q], rtol=1e-12)
    assert r["pressure"][1] == pytest.approx(1e5 - 20.0 - q / C1, rel=1e-12, abs=0)
    for p_a in (39.0, 5.0):                  # below h1 + h2: rest, B stagnant between the bounds
        r = ff.steady_network_flow(fixed_pressure=[p_a, np.nan, 0.0], **args)
        np.testing.assert_array_equal(r["link_flow"], 0.0)
        assert r["stagnant"].tolist() == [False, True, False]
        assert p_a - 20.0 <= r["pressure"][1] <= 20.0
        np.testing.assert_array_equal(r["boundary_inflow"], 0.0)


@REQ
def test_network_bingham_parallel_links_open_one_by_one():
    # X - Y at dp = 30 Pa through links with h = 20 Pa (a = 1e-4, L = 1) and h = 40 Pa (a = 1e-4, L = 2)
    args = dict(domain_ids=["X", "Y"], fixed=[True, True], link_from=["X", "X"], link_to=["Y", "Y"],
                aperture=1e-4, length=[1.0, 2.0], viscosity=MU, yield_stress=1e-3)
    r = ff.steady_network_flow(fixed_pressure=[30.0, 0.0], **args)
    np.testing.assert_allclose(r["link_flow"], [C1 * 10.0, 0.0], rtol=1e-14)
    r = ff.steady_network_flow(fixed_pressure=[0.0, 50.0], **args)
    np.testing.assert_allclose(r["link_flow"], [-C1 * 30.0, -C1 / 2 * 10.0], rtol=1e-14)


@REQ
def test_network_bingham_injection_pushes_past_the_threshold():
    # 1e-9 m^2/s into B, out to A at 0 through h = 20 Pa: p_B = 20 + 1e-9 / C1 = 32 Pa
    r = ff.steady_network_flow(domain_ids=["A", "B"], fixed=[True, False], fixed_pressure=[0.0, 0.0],
                               source=[0.0, 1e-9], link_from=["A"], link_to=["B"], aperture=1e-4, length=1.0,
                               viscosity=MU, yield_stress=1e-3)
    assert r["pressure"][1] == pytest.approx(32.0, rel=1e-13, abs=0)
    assert r["link_flow"][0] == pytest.approx(-1e-9, rel=1e-13, abs=0)
    assert not r["stagnant"][1]


def network_arrays(net, tau_y):
    """Link endpoints (indices), conductances and Bingham thresholds of a random_network."""
    i = np.array([int(d[1:]) for d in net["link_from"]])
    j = np.array([int(d[1:]) for d in net["link_to"]])
    return i, j, net["aperture"] ** 3 / (12 * MU * net["length"]), 2 * tau_y * net["length"] / net["aperture"]


@REQ
@pytest.mark.parametrize("tau_y", [0.02, 0.2, 1.0, 5.0])
@pytest.mark.parametrize("seed", [4, 5, 6, 7])
def test_network_bingham_solution_obeys_the_law_on_every_link_and_balances(seed, tau_y):
    # thresholds 2 tau_y L / a from ~1e1 to ~1e6 Pa against pressures up to 1e5: from nearly all
    # links flowing to most of the network at rest
    net = random_network(seed)
    r = ff.steady_network_flow(**net, yield_stress=tau_y)
    n = len(net["domain_ids"])
    i, j, C, h = network_arrays(net, tau_y)
    dp = r["pressure"][i] - r["pressure"][j]
    q = r["link_flow"]
    # the solve's rounding on pressures (condition of the network's Laplacian ~1e6 at most)
    slack = 1e-9 * max(np.max(np.abs(r["pressure"])), np.max(h))
    flowing = np.abs(dp) - h > slack
    assert 0 < np.sum(flowing) < len(i)           # each case has links of both kinds
    # at rest: below the threshold, flowing at most what the rounding of dp lets through
    assert np.all(np.abs(q[~flowing]) <= C[~flowing] * 2 * slack)
    # flowing: down the pressure gradient, at C (|dp| - h)
    np.testing.assert_allclose(q[flowing], C[flowing] * (dp[flowing] - np.sign(dp[flowing]) * h[flowing]),
                               rtol=1e-9, atol=1e-12 * np.max(np.abs(q)))
    # balance to round-off of the terms summed, C dp and C h (which cancel on slow links)
    scale = np.max(C * (np.abs(dp) + h))
    residual = np.bincount(i, q, n) - np.bincount(j, q, n) - net["source"]
    assert np.max(np.abs(residual[~net["fixed"]])) < 1e-12 * scale
    assert abs(np.sum(r["boundary_inflow"]) + np.sum(net["source"])) < 1e-12 * scale
    # stagnant domains are free ones all of whose links are at rest
    at_rest = np.ones(n, dtype=bool)
    at_rest[i[flowing]] = at_rest[j[flowing]] = False
    assert np.all(at_rest[r["stagnant"]] & ~net["fixed"][r["stagnant"]])


@REQ
@pytest.mark.parametrize("seed,tau_y", [(4, 0.2), (5, 1.0)])
def test_network_bingham_flows_minimise_the_dissipation_potential(seed, tau_y):
    # F(p) = sum C (|dp| - h)_+^2 / 2 - sum source p over the free pressures, minimised by
    # scipy's L-BFGS-B from zero (a different algorithm: quasi-Newton, no active sets). The flows
    # are unique; L-BFGS-B stops when F no longer falls by eps, which leaves them ~1e-7 of the
    # largest flow off: compared at 1e-6.
    net = random_network(seed)
    r = ff.steady_network_flow(**net, yield_stress=tau_y)
    n = len(net["domain_ids"])
    i, j, C, h = network_arrays(net, tau_y)
    free, p, unit = ~net["fixed"], np.array(net["fixed_pressure"], dtype=float), 1e5

    def flows(x):
        p[free] = unit * x
        dp = p[i] - p[j]
        return C * np.sign(dp) * np.maximum(np.abs(dp) - h, 0.0)

    def potential(x):
        q = flows(x)
        gradient = (np.bincount(i, q, n) - np.bincount(j, q, n) - net["source"])[free] * unit
        return 0.5 * np.sum(q * q / C) - unit * np.dot(net["source"][free], x), gradient

    best = minimize(potential, np.zeros(np.sum(free)), jac=True, method="L-BFGS-B",
                    options=dict(gtol=1e-20, ftol=1e-20, maxiter=20000, maxcor=50))
    q = flows(best.x)
    np.testing.assert_allclose(r["link_flow"], q, atol=1e-6 * np.max(np.abs(q)))


@REQ
def test_network_bingham_with_a_vanishing_yield_stress_is_newtonian():
    net = random_network(3)
    newtonian = ff.steady_network_flow(**net)
    bingham = ff.steady_network_flow(**net, yield_stress=1e-12)     # thresholds ~1e-8 Pa
    np.testing.assert_allclose(bingham["link_flow"], newtonian["link_flow"], atol=1e-9 * np.max(np.abs(newtonian["link_flow"])))


@REQ
def test_network_bingham_iteration_stops_at_its_limit():
    with pytest.raises(RuntimeError, match="did not settle in 3 solves"):
        ff.steady_network_flow(**random_network(4), yield_stress=1.0, max_iterations=3)


# ---------------------------------------------------------------- bad input


@REQ
def test_bad_single_joint_input_is_refused():
    with pytest.raises(ValueError, match="aperture"):
        ff.cubic_law_flow(aperture=0.0, viscosity=1e-3, length=1.0, pressure_drop=1.0)
    with pytest.raises(ValueError, match="viscosity"):
        ff.cubic_law_conductance(aperture=1e-4, viscosity=-1.0, length=1.0)
    with pytest.raises(ValueError, match="permeability"):
        ff.point_contact_flow(permeability=-1e-9, pressure_drop=1.0)
    with pytest.raises(ValueError, match="normal_stiffness"):
        ff.joint_storage(aperture=1e-4, fluid_bulk_modulus=2e9, normal_stiffness=0.0)
    with pytest.raises(ValueError, match="t = "):
        ff.step_pressure_semi_infinite(x=1.0, t=0.0, p0=0.0, p1=1.0, **WATER)
    with pytest.raises(ValueError, match="x = "):
        ff.step_pressure_semi_infinite(x=-1.0, t=1.0, p0=0.0, p1=1.0, **WATER)
    with pytest.raises(ValueError, match="x = "):
        ff.step_pressure_finite(x=2.5, t=1.0, **finite_args("fixed"))
    with pytest.raises(ValueError, match="far_end"):
        ff.step_inflow_rate_finite(t=1.0, **dict(finite_args("fixed"), far_end="open"))
    with pytest.raises(ValueError, match="series"):
        ff.step_inflow_rate_finite(t=1.0, **finite_args("fixed", series="taylor"))
    with pytest.raises(ValueError, match="closes the joint"):
        ff.deformable_joint_steady_flow(**dict(DEFORMABLE, p_in=-2e5))
    with pytest.raises(ValueError, match="closed_aperture"):
        ff.jacking_aperture(pressure=1.0, closed_aperture=0.0, normal_stress=1.0, normal_stiffness=1.0)
    with pytest.raises(ValueError, match="depth"):
        ff.column_joint_stresses(depth=-1.0, rock_density=2500.0, water_density=1000.0, g=9.81)
    with pytest.raises(ValueError, match="yield_stress"):
        ff.bingham_threshold_gradient(aperture=1e-4, yield_stress=-1.0)
    with pytest.raises(ValueError, match="relative_penetration"):
        ff.grout_dimensionless_time(relative_penetration=1.0, law="linear")
    with pytest.raises(ValueError, match="law"):
        ff.grout_penetration(t=1.0, **GROUT, law="power")
    with pytest.raises(ValueError, match="yield_stress"):
        ff.grout_max_penetration(aperture=1e-4, overpressure=1e6, yield_stress=0.0)


@REQ
def test_bad_network_input_is_refused():
    good = dict(SERIES, fixed_pressure=[1e5, np.nan, 0.0])
    with pytest.raises(ValueError, match="link 1: link_to = 'D'"):
        ff.steady_network_flow(**dict(good, link_to=["B", "D"]))
    with pytest.raises(ValueError, match="twice"):
        ff.steady_network_flow(**dict(good, domain_ids=["A", "A", "C"]))
    with pytest.raises(ValueError, match="itself"):
        ff.steady_network_flow(**dict(good, link_to=["B", "B"]))
    with pytest.raises(ValueError, match=r"domains \['B'\] have a fixed pressure and an inflow"):
        ff.steady_network_flow(**dict(good, fixed=[True, True, True], fixed_pressure=[1.0, 2.0, 3.0], source=[0, 1e-9, 0]))
    with pytest.raises(ValueError, match="no domain has a fixed pressure"):
        ff.steady_network_flow(**dict(good, fixed=[False] * 3))
    with pytest.raises(ValueError, match=r"domains \['C'\] are linked to no fixed"):
        ff.steady_network_flow(**dict(good, fixed=[True, False, False], link_from=["A"], link_to=["B"],
                                      aperture=1e-4, length=1.0))
    with pytest.raises(ValueError, match=r"aperture: links \[1\]"):
        ff.steady_network_flow(**dict(good, aperture=[1e-4, 0.0]))
    with pytest.raises(ValueError, match="length: one value per link"):
        ff.steady_network_flow(**dict(good, length=[1.0, 2.0, 3.0]))
    with pytest.raises(ValueError, match="fixed_pressure: domains"):
        ff.steady_network_flow(**dict(good, fixed_pressure=[np.nan, np.nan, 0.0]))

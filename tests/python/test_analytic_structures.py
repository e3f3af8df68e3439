"""Closed-form rock-support references (verification/analytic/structures.py) at known values.

Known values are hand arithmetic shown in the comments or published tables (the cantilever's
beta_n L to 9 digits, Blevins table 8-1). The other checks take independent routes, never the
function under test rewritten: scipy's solve_bvp on the differential equation, a dense linear solve of
the spring chain or the frame assembled here, eigenvalues of the flexibility matrix built from the
continuum's influence functions, quadrature for equilibrium, central differences of the fields, and
Lame's thick cylinder for the thin ring.

Tolerances: a closed form against another closed form or a linear solve of the cable chain: 1e-12
relative (condition numbers below 1e4); against a solve of the frame stiffness, whose condition number
grows as n^4 (6e5 at 16 elements, 2e7 at 40, 1.5e8 at 64): 1e-9; against solve_bvp run to tol 1e-10: 1e-7; finite differences with step d:
truncation ~ d^2 f''' / 6 relative, stated at each check; a discrete model against the continuum: its
O(h^2) error, measured and bounded.
"""
import math

import numpy as np
import pytest
from scipy import integrate

from analytic import elastic
from analytic import structures as st

REQ = pytest.mark.requirements("REQ-QA-003")


def approx(expected, *, rel):
    """pytest.approx with the relative tolerance alone (no hidden absolute 1e-12)."""
    return pytest.approx(expected, rel=rel, abs=0.0)


# A steel cable grouted in rock: EA = 2e7 N (about 100 mm^2 of steel), k_bond = 5e7 N/m/m, so that
# alpha = sqrt(2.5) = 1.5811 /m; L chosen per test. F0 = 100 kN.
EA, K_BOND, F0 = 2e7, 5e7, 1e5
ALPHA = math.sqrt(K_BOND / EA)


def cable_chain_solution(*, L, n, F0=F0, anchored_tail=False):
    """The discrete cable solved as a dense linear system assembled here: axial springs EA/h, bond
    springs k_bond h at the nodes, half at the end nodes, F0 at node 0."""
    h = L / n
    K = np.zeros((n + 1, n + 1))
    for i in range(n):
        K[i:i + 2, i:i + 2] += EA / h * np.array([[1.0, -1.0], [-1.0, 1.0]])
    bond = np.full(n + 1, K_BOND * h)
    bond[0] = bond[-1] = 0.5 * K_BOND * h
    K += np.diag(bond)
    f = np.zeros(n + 1)
    f[0] = F0
    s = np.linalg.solve(K, f)
    return s, EA / h * (s[:-1] - s[1:])


def cable_bvp(*, L, far_end):
    """EA s'' = k_bond s, s'(0) = -F0 / EA, and s'(L) = 0 (free) or s(L) = 0 (anchored), by solve_bvp."""
    x = np.linspace(0.0, L, 201)

    def ode(_, y):
        return np.vstack([y[1], K_BOND / EA * y[0]])

    def bc(ya, yb):
        return np.array([ya[1] + F0 / EA, yb[1] if far_end == "free" else yb[0]])

    guess = np.vstack([np.full_like(x, F0 / (EA * ALPHA)), np.zeros_like(x)])
    sol = integrate.solve_bvp(ode, bc, x, guess, tol=1e-10, max_nodes=100000)
    assert sol.success
    return sol


# ---------------------------------------------------------------- cable, elastic bond


@REQ
def test_cable_elastic_known_values():
    # alpha L = ln 4: F(L/2) / F0 = sinh(ln 2) / sinh(ln 4) = 1 / (2 cosh(ln 2)) = 1 / 2.5 = 0.4, and
    # tanh(ln 4) = 15 / 17: head stiffness EA alpha 15/17.
    L = math.log(4.0) / ALPHA
    F = st.cable_elastic_force(np.array([0.0, 0.5 * L, L]), F0=F0, L=L, EA=EA, k_bond=K_BOND)
    assert F[0] == approx(F0, rel=1e-15) and F[1] == approx(0.4 * F0, rel=1e-14) and F[2] == 0.0
    assert st.cable_head_stiffness(L=L, EA=EA, k_bond=K_BOND) == approx(EA * ALPHA * 15.0 / 17.0, rel=1e-14)
    # anchored far end: cosh(ln 2) / cosh(ln 4) = 1.25 / 2.125 at L/2, 1 / 2.125 at L; stiffness EA alpha 17/15
    anchored = dict(F0=F0, L=L, EA=EA, k_bond=K_BOND, far_end="anchored")
    F = st.cable_elastic_force(np.array([0.5 * L, L]), **anchored)
    np.testing.assert_allclose(F, [F0 * 1.25 / 2.125, F0 / 2.125], rtol=1e-14)
    assert st.cable_head_stiffness(L=L, EA=EA, k_bond=K_BOND, far_end="anchored") == approx(EA * ALPHA * 17 / 15, rel=1e-14)
    assert st.cable_elastic_displacement(L, **anchored) == 0.0
    assert st.cable_elastic_displacement(0.0, F0=F0, L=L, EA=EA, k_bond=K_BOND) \
        == approx(F0 / (EA * ALPHA * 15.0 / 17.0), rel=1e-14)


@REQ
def test_cable_elastic_head_stiffness_limits():
    # short (alpha L = 1e-4): free end -> k_bond L (a rigid bar on its bond), anchored -> EA / L;
    # relative corrections (alpha L)^2 / 3 = 3e-9. Long (alpha L = 40, beyond any overflow of sinh
    # with 300): both EA alpha.
    short = 1e-4 / ALPHA
    assert st.cable_head_stiffness(L=short, EA=EA, k_bond=K_BOND) == approx(K_BOND * short, rel=1e-8)
    assert st.cable_head_stiffness(L=short, EA=EA, k_bond=K_BOND, far_end="anchored") == approx(EA / short, rel=1e-8)
    for far_end in ("free", "anchored"):
        assert st.cable_head_stiffness(L=40.0 / ALPHA, EA=EA, k_bond=K_BOND, far_end=far_end) \
            == approx(EA * ALPHA, rel=1e-15)
        F = st.cable_elastic_force(np.array([0.0, 1.0]), F0=F0, L=300.0 / ALPHA, EA=EA, k_bond=K_BOND, far_end=far_end)
        np.testing.assert_allclose(F, [F0, F0 * math.exp(-ALPHA)], rtol=1e-14)


@pytest.mark.parametrize("far_end", ["free", "anchored"])
@REQ
def test_cable_elastic_solves_the_bond_equation(far_end):
    L = 2.0
    sol = cable_bvp(L=L, far_end=far_end)
    x = np.linspace(0.0, L, 9)
    common = dict(F0=F0, L=L, EA=EA, k_bond=K_BOND, far_end=far_end)
    scale = F0 / (EA * ALPHA)
    np.testing.assert_allclose(st.cable_elastic_displacement(x, **common), sol.sol(x)[0], rtol=1e-7, atol=1e-7 * scale)
    np.testing.assert_allclose(st.cable_elastic_force(x, **common), -EA * sol.sol(x)[1], rtol=1e-7, atol=1e-7 * F0)
    # equilibrium: the bond takes F0 less what the far end holds
    bond, _ = integrate.quad(lambda y: K_BOND * float(st.cable_elastic_displacement(y, **common)), 0.0, L,
                             epsabs=0.0, epsrel=1e-13)
    tail = float(st.cable_elastic_force(L, **common))
    assert bond + tail == approx(F0, rel=1e-12)


@REQ
def test_cable_discrete_is_the_spring_chain_to_round_off():
    for L, n in ((2.0, 1), (2.0, 2), (2.0, 7), (2.0, 40), (20.0, 400), (30.0, 3)):
        s, F = cable_chain_solution(L=L, n=n)
        h = L / n
        common = dict(F0=F0, L=L, EA=EA, k_bond=K_BOND, n=n)
        np.testing.assert_allclose(st.cable_discrete_displacement(np.arange(n + 1) * h, **common), s, rtol=1e-12)
        np.testing.assert_allclose(st.cable_discrete_force((np.arange(n) + 0.5) * h, **common), F, rtol=1e-11)
        assert st.cable_discrete_head_stiffness(L=L, EA=EA, k_bond=K_BOND, n=n) == approx(F0 / s[0], rel=1e-12)
    # one segment by hand: a = EA/L, b = k L / 2 at each node; head stiffness b (2a + b) / (a + b)
    a, b = EA / 2.0, K_BOND
    assert st.cable_discrete_head_stiffness(L=2.0, EA=EA, k_bond=K_BOND, n=1) == approx(b * (2 * a + b) / (a + b), rel=1e-14)


@REQ
def test_cable_discrete_converges_to_the_continuum_at_second_order():
    # The head stiffness's relative error falls by 4 per halving of h from 20 segments (alpha h =
    # 0.24) on: 0.70 %, 0.18 %, 0.044 %, 0.011 % at 20, 40, 80, 160. The segment forces' largest
    # error (relative to F0: 0.59 % at 20 segments) falls likewise, if less regularly (the largest
    # moves along the cable).
    L = 3.0
    exact = st.cable_head_stiffness(L=L, EA=EA, k_bond=K_BOND)
    stiffness, forces = [], []
    for n in (20, 40, 80, 160):
        stiffness.append(st.cable_discrete_head_stiffness(L=L, EA=EA, k_bond=K_BOND, n=n) / exact - 1.0)
        mid = (np.arange(n) + 0.5) * L / n
        discrete = st.cable_discrete_force(mid, F0=F0, L=L, EA=EA, k_bond=K_BOND, n=n)
        forces.append(np.max(np.abs(discrete - st.cable_elastic_force(mid, F0=F0, L=L, EA=EA, k_bond=K_BOND))) / F0)
    np.testing.assert_allclose(np.log2(np.array(stiffness[:-1]) / np.array(stiffness[1:])), 2.0, atol=0.02)
    assert 0.0065 < stiffness[0] < 0.0075
    assert np.all(np.array(forces[:-1]) / np.array(forces[1:]) > 3.4) and forces[0] < 7e-3
    theta = st.cable_discrete_theta(L=L, EA=EA, k_bond=K_BOND, n=1000)
    assert theta / (L / 1000) == approx(ALPHA, rel=1e-6)   # theta = alpha h (1 - (alpha h)^2 / 24 + ...)


# ---------------------------------------------------------------- cable, slipping bond

S_BOND = 2e4   # N/m: capacity s_bond L = 60 kN over 3 m
SLIP = dict(L=3.0, EA=EA, k_bond=K_BOND, s_bond=S_BOND)


@REQ
def test_cable_slip_onset_and_capacity():
    first = st.cable_first_slip_force(**SLIP)
    assert first == approx(S_BOND / ALPHA * math.tanh(ALPHA * 3.0), rel=1e-15)
    # at the first slip the head's bond force k s(0) reaches s_bond, from the elastic solution
    head = st.cable_elastic_displacement(0.0, F0=first, L=3.0, EA=EA, k_bond=K_BOND)
    assert K_BOND * head == approx(S_BOND, rel=1e-14)
    assert st.cable_slip_length(F0=first, **SLIP) == 0.0
    assert st.cable_slip_length(F0=first * (1 + 1e-9), **SLIP) > 0.0
    capacity = st.cable_pullout_capacity(L=3.0, s_bond=S_BOND)
    assert capacity == 6e4
    assert st.cable_slip_length(F0=capacity, **SLIP) == 3.0
    np.testing.assert_allclose(st.cable_slip_force(np.array([0.0, 1.0, 3.0]), F0=capacity, **SLIP), [6e4, 4e4, 0.0],
                               rtol=1e-15, atol=0.0)
    with pytest.raises(ValueError, match="capacity"):
        st.cable_slip_length(F0=capacity * (1 + 1e-12), **SLIP)


@REQ
def test_cable_slip_profile_balances_and_is_continuous():
    F = 0.9 * st.cable_pullout_capacity(L=3.0, s_bond=S_BOND)
    a = st.cable_slip_length(F0=F, **SLIP)
    assert 0.0 < a < 3.0
    # slipped part: slope -s_bond; at a the elastic part starts at (s_bond / alpha) tanh(alpha (L - a))
    x = np.array([0.0, 0.5 * a, a, a + 1e-9])
    profile = st.cable_slip_force(x, F0=F, **SLIP)
    assert profile[0] == approx(F, rel=1e-15)
    assert profile[1] == approx(F - S_BOND * 0.5 * a, rel=1e-14)
    assert profile[2] == approx(S_BOND / ALPHA * math.tanh(ALPHA * (3.0 - a)), rel=1e-12)
    assert profile[3] == approx(profile[2], rel=1e-8)
    # the elastic part is an elastic free-end cable of length L - a pulled by F_a, slipping at its head
    tail = st.cable_elastic_displacement(0.0, F0=profile[2], L=3.0 - a, EA=EA, k_bond=K_BOND)
    assert K_BOND * tail == approx(S_BOND, rel=1e-12)


@REQ
def test_cable_discrete_slip_converges_to_the_closed_form():
    # The active-set solution of the spring-slider chain (its own algorithm) against the closed
    # form: slipped length within a segment, forces and head displacement at O(h^2).
    F = 0.8 * st.cable_pullout_capacity(L=3.0, s_bond=S_BOND)
    a = st.cable_slip_length(F0=F, **SLIP)
    head = st.cable_slip_head_displacement(F0=F, **SLIP)
    errors = []
    for n in (50, 100, 200, 400):
        d = st.cable_discrete_slip(F0=F, n=n, **SLIP)
        h = 3.0 / n
        # node i slips when k s_i >= s_bond: the last slipped node lies within one segment of a
        assert abs(d["x_nodes"][d["slipped_nodes"] - 1] - a) <= h
        reference = st.cable_slip_force(d["x_segments"], F0=F, **SLIP)
        errors.append(np.max(np.abs(d["force"] - reference)) / F)
        assert d["displacement"][0] == approx(head, rel=0.5 * (10.0 / n) ** 2)
        # equilibrium of the chain: the bond takes all of F0 (the far end is free)
        assert np.sum(d["bond_force"]) == approx(F, rel=1e-12)
    assert errors[-1] < 2e-4 and errors[-1] < errors[0] / 8.0


@REQ
def test_cable_discrete_slip_below_first_slip_is_the_elastic_chain():
    n = 12
    elastic_head = st.cable_discrete_displacement(0.0, F0=1.0, L=3.0, EA=EA, k_bond=K_BOND, n=n)
    first = S_BOND / (K_BOND * elastic_head)        # the head node reaches its cap
    d = st.cable_discrete_slip(F0=0.999 * first, n=n, **SLIP)
    assert d["slipped_nodes"] == 0
    s, F = cable_chain_solution(L=3.0, n=n, F0=0.999 * first)
    np.testing.assert_allclose(d["displacement"], s, rtol=1e-12)
    assert st.cable_discrete_slip(F0=1.001 * first, n=n, **SLIP)["slipped_nodes"] == 1
    # at the capacity every node but the last has slipped, the last just at its cap
    full = st.cable_discrete_slip(F0=st.cable_pullout_capacity(L=3.0, s_bond=S_BOND), n=n, **SLIP)
    assert full["slipped_nodes"] == n
    assert K_BOND * full["displacement"][-1] == approx(S_BOND, rel=1e-12)


@REQ
def test_cable_rejects_bad_input():
    with pytest.raises(ValueError, match="EA"):
        st.cable_elastic_force(0.0, F0=F0, L=1.0, EA=0.0, k_bond=K_BOND)
    with pytest.raises(ValueError, match="k_bond"):
        st.cable_head_stiffness(L=1.0, EA=EA, k_bond=-1.0)
    with pytest.raises(ValueError, match="x = "):
        st.cable_elastic_force(1.5, F0=F0, L=1.0, EA=EA, k_bond=K_BOND)
    with pytest.raises(ValueError, match="far_end"):
        st.cable_elastic_force(0.5, F0=F0, L=1.0, EA=EA, k_bond=K_BOND, far_end="fixed")
    with pytest.raises(ValueError, match="n \\(number"):
        st.cable_discrete_force(0.5, F0=F0, L=1.0, EA=EA, k_bond=K_BOND, n=0)
    with pytest.raises(ValueError, match="n \\(number"):
        st.cable_discrete_force(0.5, F0=F0, L=1.0, EA=EA, k_bond=K_BOND, n=2.0)
    with pytest.raises(ValueError, match="s_bond"):
        st.cable_slip_length(F0=1.0, L=1.0, EA=EA, k_bond=K_BOND, s_bond=0.0)
    with pytest.raises(ValueError, match="F0"):
        st.cable_slip_length(F0=-1.0, L=1.0, EA=EA, k_bond=K_BOND, s_bond=1.0)
    with pytest.raises(ValueError, match="L \\(cable"):
        st.cable_elastic_force(0.0, F0=F0, L=float("nan"), EA=EA, k_bond=K_BOND)


# ---------------------------------------------------------------- frame beams

# A steel-like section: E = 2e11 Pa, I = 1e-5 m^4 (EI = 2e6 N m^2), L = 2 m, P = 10 kN, q = 5 kN/m.
BEAM = dict(L=2.0, E=2e11, I=1e-5)
EI = 2e6


def cantilever_flexibility(nodes):
    """Deflection and rotation at the nodes (w_1, theta_1, ..., w_n, theta_n) under unit point loads
    and unit moments there, from the continuum's influence functions of a cantilever clamped at 0
    (T&G: a load P at b deflects x <= b by P x^2 (3b - x) / 6EI and rotates it by P x (2b - x) / 2EI,
    and beyond b the beam is straight; a moment M at b bends x <= b into M x^2 / 2EI)."""
    n = len(nodes)
    F = np.zeros((2 * n, 2 * n))
    for i, a in enumerate(nodes):
        for j, b in enumerate(nodes):
            lo = min(a, b)
            if a <= b:
                F[2 * i, 2 * j] = a * a * (3 * b - a) / (6 * EI)
                F[2 * i + 1, 2 * j] = a * (2 * b - a) / (2 * EI)
                F[2 * i, 2 * j + 1] = a * a / (2 * EI)
            else:
                F[2 * i, 2 * j] = b * b * (3 * a - b) / (6 * EI)
                F[2 * i + 1, 2 * j] = b * b / (2 * EI)
                F[2 * i, 2 * j + 1] = b * (2 * a - b) / (2 * EI)
            F[2 * i + 1, 2 * j + 1] = lo / EI
    return F


def quartic(values_at, L):
    """The polynomial of degree 4 through nine samples of a field on [0, L] (exact for a quartic)."""
    x = np.linspace(0.0, L, 9)
    return np.poly1d(np.polyfit(x, values_at(x), 4))


@REQ
def test_cantilever_point_load_known_values():
    # P L^3 / 3EI = 1e4 * 8 / 6e6 = 0.013333..., P L^2 / 2EI = 1e4 * 4 / 4e6 = 0.01
    assert st.cantilever_tip_deflection(P=1e4, **BEAM) == approx(8e4 / 6e6, rel=1e-15)
    assert st.cantilever_tip_rotation(P=1e4, **BEAM) == approx(0.01, rel=1e-15)
    assert st.cantilever_point_load_deflection(2.0, P=1e4, **BEAM) == approx(8e4 / 6e6, rel=1e-15)
    # at L/2: P (L/2)^2 (3L - L/2) / 6EI = 1e4 * 1 * 5 / 1.2e7 (5/16 of the tip)
    assert st.cantilever_point_load_deflection(1.0, P=1e4, **BEAM) == approx(5e4 / 1.2e7, rel=1e-15)


@REQ
def test_frame_elements_reproduce_the_continuum_flexibility_exactly():
    # The inverse of the clamped frame stiffness is the continuum's flexibility at the nodes: for
    # any nodal loads, the nodal deflections and rotations of cubic elements are exact.
    for n in (1, 2, 5, 16):
        K = st.cantilever_frame_stiffness(elements=n, **BEAM)
        nodes = np.arange(1, n + 1) * 2.0 / n
        np.testing.assert_allclose(np.linalg.inv(K), cantilever_flexibility(nodes), rtol=1e-10, atol=1e-14)
        f = np.zeros(2 * n)
        f[-2] = 1e4
        u = np.linalg.solve(K, f)
        tip = st.cantilever_elements_tip(P=1e4, elements=n, **BEAM)
        assert u[-2] == approx(tip["deflection"], rel=1e-9) and u[-1] == approx(tip["rotation"], rel=1e-9)
        np.testing.assert_allclose(u[0::2], st.cantilever_point_load_deflection(nodes, P=1e4, **BEAM), rtol=1e-9)
    # the free-free matrix has the two rigid-body modes in its null space
    K = st.frame_bending_stiffness(elements=4, **BEAM)
    x = np.arange(5) * 0.5
    for mode in (np.column_stack([np.ones(5), np.zeros(5)]).ravel(), np.column_stack([x, np.ones(5)]).ravel()):
        assert np.max(np.abs(K @ mode)) < 1e-9 * np.max(np.abs(K))


@REQ
def test_cantilever_uniform_load_solves_the_beam_equation():
    q = 5e3
    w = quartic(lambda x: st.cantilever_uniform_deflection(x, q=q, **BEAM), 2.0)
    d = [w.deriv(k) for k in range(5)]
    # EI w'''' = q; clamped: w = w' = 0 at 0; free: w'' = w''' = 0 at L
    assert EI * d[4](0.0) == approx(q, rel=1e-9)
    assert abs(d[0](0.0)) < 1e-12 * w(2.0) and abs(d[1](0.0)) < 1e-12 * d[1](2.0)
    assert abs(d[2](2.0)) < 1e-9 * abs(d[2](0.0)) and abs(d[3](2.0)) < 1e-9 * abs(d[3](0.0))
    # tip q L^4 / 8EI = 5e3 * 16 / 1.6e7 = 5e-3; rotation q L^3 / 6EI = 4e4 / 1.2e7
    assert st.cantilever_uniform_deflection(2.0, q=q, **BEAM) == approx(5e-3, rel=1e-15)
    assert st.cantilever_uniform_rotation(2.0, q=q, **BEAM) == approx(4e4 / 1.2e7, rel=1e-15)
    x = np.array([0.3, 1.1, 1.9])
    np.testing.assert_allclose(st.cantilever_uniform_rotation(x, q=q, **BEAM), d[1](x), rtol=1e-9)


@REQ
def test_cantilever_lumped_uniform_load_is_the_frame_solution():
    q = 5e3
    for n in (1, 2, 3, 10, 40):
        K = st.cantilever_frame_stiffness(elements=n, **BEAM)
        f = np.zeros(2 * n)
        f[0::2] = q * 2.0 / n
        f[-2] *= 0.5
        u = np.linalg.solve(K, f)
        tip = st.cantilever_lumped_uniform_tip(q=q, elements=n, **BEAM)
        assert tip["deflection"] == approx(u[-2], rel=1e-9)
        assert tip["rotation"] == approx(u[-1], rel=1e-9)
    # n = 1 by hand: q L / 2 = 5 kN at the tip, 5e3 L^3 / 3EI = 5e3 * 8 / 6e6
    assert st.cantilever_lumped_uniform_tip(q=q, elements=1, **BEAM)["deflection"] == approx(4e4 / 6e6, rel=1e-15)


@REQ
def test_simply_supported_uniform_load_solves_the_beam_equation():
    q = 5e3
    w = quartic(lambda x: st.simply_supported_uniform_deflection(x, q=q, **BEAM), 2.0)
    d = [w.deriv(k) for k in range(5)]
    scale = st.simply_supported_midspan_deflection(q=q, **BEAM)
    assert EI * d[4](0.0) == approx(q, rel=1e-9)
    for end in (0.0, 2.0):
        assert abs(d[0](end)) < 1e-12 * scale and abs(EI * d[2](end)) < 1e-9 * q
    # 5 q L^4 / 384EI = 5 * 5e3 * 16 / 7.68e8; M = -EI w'' = q x (L - x) / 2, q L^2 / 8 = 2500 N m at midspan
    assert scale == approx(4e5 / 7.68e8, rel=1e-15)
    assert st.simply_supported_uniform_deflection(1.0, q=q, **BEAM) == approx(scale, rel=1e-15)
    x = np.array([0.0, 0.4, 1.0, 1.7])
    np.testing.assert_allclose(st.simply_supported_uniform_moment(x, q=q, L=2.0), -EI * d[2](x), rtol=1e-9, atol=1e-9 * q)
    assert st.simply_supported_uniform_moment(1.0, q=q, L=2.0) == 2500.0


@REQ
def test_simply_supported_lumped_load_is_the_frame_solution():
    q = 5e3
    for n in (2, 4, 6, 20, 64):
        K = st.frame_bending_stiffness(elements=n, **BEAM)
        free = [i for i in range(2 * n + 2) if i not in (0, 2 * n)]   # w_0 = w_n = 0
        f = np.zeros(2 * n + 2)
        f[0::2] = q * 2.0 / n
        u = np.linalg.solve(K[np.ix_(free, free)], f[free])
        midspan = u[free.index(n)]
        assert st.simply_supported_lumped_midspan_deflection(q=q, elements=n, **BEAM) == approx(midspan, rel=1e-9)
    # n = 2 by hand: q L / 2 at midspan, P L^3 / 48EI = 5e3 * 8 / 9.6e7
    assert st.simply_supported_lumped_midspan_deflection(q=q, elements=2, **BEAM) == approx(4e4 / 9.6e7, rel=1e-15)


# ---------------------------------------------------------------- cantilever frequencies

# Blevins, Formulas for Natural Frequency and Mode Shape, table 8-1, clamped-free
BETA_L = [1.87510407, 4.69409113, 7.85475744, 10.99554073]
FREQ = dict(E=2e11, I=1e-5, rho=7800.0, A=0.01, L=2.0)
F_SCALE = math.sqrt(2e6 / (78.0 * 16.0)) / (2.0 * math.pi)     # sqrt(EI / (rho A L^4)) / 2 pi


@REQ
def test_cantilever_beta_L_are_the_published_roots():
    roots = st.cantilever_beta_L(modes=8)
    np.testing.assert_allclose(roots[:4], BETA_L, rtol=1e-8)
    # cos x + 1 / cosh x vanishes to the rounding of x itself (|d/dx| ~ 1): a few eps x
    assert np.max(np.abs(1.0 + np.cos(roots) * np.cosh(roots)) / np.cosh(roots) / roots) < 4 * np.finfo(float).eps
    # beyond: (2n - 1) pi / 2 + delta, delta = (-1)^(n+1) 2 exp(-(2n - 1) pi / 2) to O(delta^2)
    n = np.arange(5, 9)
    x0 = (2 * n - 1) * math.pi / 2
    np.testing.assert_allclose(roots[4:] - x0, (-1.0) ** (n + 1) * 2.0 * np.exp(-x0), rtol=1e-4)


@REQ
def test_cantilever_frequencies_known_values():
    f = st.cantilever_frequencies(modes=4, **FREQ)
    np.testing.assert_allclose(f, np.array(BETA_L) ** 2 * F_SCALE, rtol=2e-8)
    # EI = 2e6, rho A = 78 kg/m, L = 2: f1 = 1.8751^2 / 2pi * sqrt(2e6 / 1248) = 0.559598 * 40.0320 = 22.402 Hz
    assert f[0] == approx(22.402, rel=1e-4)


@REQ
@pytest.mark.parametrize("ratio", [0.0, 1.0 / 12.0, 0.5])
def test_cantilever_lumped_frequencies_from_the_flexibility(ratio):
    # Another route to the same discrete model: omega^-2 are the eigenvalues of F M, F the
    # continuum's nodal flexibility (exact for cubic elements). With no rotary inertia only the
    # translational part of F (loads alone, rotations free) enters.
    for n in (1, 2, 5, 12):
        h = 2.0 / n
        nodes = np.arange(1, n + 1) * h
        m = np.full(n, 78.0 * h)
        m[-1] *= 0.5
        F = cantilever_flexibility(nodes)
        if ratio == 0.0:
            lam = np.linalg.eigvals(F[0::2, 0::2] @ np.diag(m))
        else:
            lam = np.linalg.eigvals(F @ np.diag(np.column_stack([m, ratio * m * h * h]).ravel()))
        expected = np.sort(1.0 / np.sqrt(np.real(lam)) / (2.0 * math.pi))[:min(n, 3)]
        found = st.cantilever_lumped_frequencies(elements=n, modes=min(n, 3), rotary_inertia_ratio=ratio, **FREQ)
        np.testing.assert_allclose(found, expected, rtol=1e-10)
    # one element by hand: the tip mass rho A L / 2 on the tip stiffness 3EI / L^3:
    # omega^2 = 6 EI / (rho A L^4), f = sqrt(6) F_SCALE
    if ratio == 0.0:
        assert st.cantilever_lumped_frequencies(elements=1, **FREQ)[0] == approx(math.sqrt(6.0) * F_SCALE, rel=1e-13)


@REQ
def test_cantilever_lumped_frequencies_converge_at_second_order():
    exact = st.cantilever_frequencies(**FREQ)[0]
    errors = np.array([st.cantilever_lumped_frequencies(elements=n, **FREQ)[0] / exact - 1.0 for n in (8, 16, 32, 64)])
    assert np.all(errors < 0.0)
    np.testing.assert_allclose(np.log2(errors[:-1] / errors[1:]), 2.0, atol=0.01)
    np.testing.assert_allclose(errors * np.array([8, 16, 32, 64]) ** 2, -0.459, atol=0.004)
    # Richardson from 32 and 64 elements: the continuum to O(n^-4), 1e-7 here
    f32, f64 = (st.cantilever_lumped_frequencies(elements=n, **FREQ)[0] for n in (32, 64))
    assert f64 + (f64 - f32) / 3.0 == approx(exact, rel=2e-7)
    # a rotary inertia lowers the frequency, less and less as the elements shrink
    for n in (4, 16):
        with_j = st.cantilever_lumped_frequencies(elements=n, rotary_inertia_ratio=1 / 12, **FREQ)[0]
        assert with_j < st.cantilever_lumped_frequencies(elements=n, **FREQ)[0]
    assert st.cantilever_lumped_frequencies(elements=64, rotary_inertia_ratio=1 / 12, **FREQ)[0] == approx(exact, rel=3e-4)


@REQ
def test_beams_reject_bad_input():
    with pytest.raises(ValueError, match="I \\(second"):
        st.cantilever_tip_deflection(P=1.0, L=1.0, E=1.0, I=0.0)
    with pytest.raises(ValueError, match="x = "):
        st.cantilever_uniform_deflection(-0.1, q=1.0, L=1.0, E=1.0, I=1.0)
    with pytest.raises(ValueError, match="elements"):
        st.cantilever_elements_tip(P=1.0, L=1.0, E=1.0, I=1.0, elements=0)
    with pytest.raises(ValueError, match="even"):
        st.simply_supported_lumped_midspan_deflection(q=1.0, L=1.0, E=1.0, I=1.0, elements=3)
    with pytest.raises(ValueError, match="modes"):
        st.cantilever_lumped_frequencies(elements=2, modes=3, **FREQ)
    with pytest.raises(ValueError, match="rotary_inertia_ratio"):
        st.cantilever_lumped_frequencies(elements=2, rotary_inertia_ratio=-1.0, **FREQ)
    with pytest.raises(ValueError, match="rho"):
        st.cantilever_frequencies(E=1.0, I=1.0, rho=0.0, A=1.0, L=1.0)
    with pytest.raises(ValueError, match="P"):
        st.cantilever_tip_deflection(P="heavy", L=1.0, E=1.0, I=1.0)


# ---------------------------------------------------------------- Winkler foundation

# EI = 2e6 N m^2, k = 1.28e8 N/m/m: lambda^4 = k / 4EI = 16, lambda = 2 /m. P = 100 kN.
WINKLER = dict(k=1.28e8, E=2e11, I=1e-5)
LAM, P_W = 2.0, 1e5


def winkler_half_beam_bvp(c):
    """EI w'''' + k w = 0 on 0 <= x <= c, w'(0) = 0, EI w'''(0) = P/2, w''(c) = w'''(c) = 0, by solve_bvp."""
    x = np.linspace(0.0, c, 401)

    def ode(_, y):
        return np.vstack([y[1], y[2], y[3], -WINKLER["k"] / EI * y[0]])

    def bc(ya, yb):
        return np.array([ya[1], EI * ya[3] - 0.5 * P_W, yb[2], yb[3]])

    sol = integrate.solve_bvp(ode, bc, x, np.zeros((4, x.size)), tol=1e-10, max_nodes=200000)
    assert sol.success
    return sol


@REQ
def test_winkler_known_values():
    assert st.winkler_lambda(**WINKLER) == approx(LAM, rel=1e-15)
    # w(0) = P lambda / 2k = 1e5 * 2 / 2.56e8, M(0) = P / 4 lambda = 12500 N m
    assert st.winkler_deflection(0.0, P=P_W, **WINKLER) == approx(2e5 / 2.56e8, rel=1e-15)
    assert st.winkler_moment(0.0, P=P_W, **WINKLER) == approx(12500.0, rel=1e-15)
    # zeros: deflection at lambda x = 3 pi / 4, moment at pi / 4; both even in x
    w0 = st.winkler_deflection(0.0, P=P_W, **WINKLER)
    assert abs(st.winkler_deflection(3 * math.pi / 8, P=P_W, **WINKLER)) < 1e-15 * w0
    assert abs(st.winkler_moment(math.pi / 8, P=P_W, **WINKLER)) < 1e-11
    x = np.array([0.3, 1.2, 2.5])
    np.testing.assert_array_equal(st.winkler_deflection(-x, P=P_W, **WINKLER), st.winkler_deflection(x, P=P_W, **WINKLER))
    np.testing.assert_array_equal(st.winkler_moment(-x, P=P_W, **WINKLER), st.winkler_moment(x, P=P_W, **WINKLER))


@REQ
def test_winkler_infinite_beam_solves_the_equation_and_balances_the_load():
    # EI w'''' = -k w away from the load: fourth central differences at steps d and d/2 (d = 0.05 /
    # lambda) extrapolated (Richardson), truncation O((lambda d)^4) ~ 1e-6, rounding eps w / d^4 ~ 1e-9
    # of k w; M = -EI w'' by a central second difference with d = 1e-3 / lambda: truncation ~ 1e-6.
    def w(y):
        return st.winkler_deflection(y, P=P_W, **WINKLER)

    def fourth(y, d):
        return (w(y - 2 * d) - 4 * w(y - d) + 6 * w(y) - 4 * w(y + d) + w(y + 2 * d)) / d ** 4

    x = np.array([0.2, 0.7, 1.3, 2.1])
    d = 0.05 / LAM
    extrapolated = (4.0 * fourth(x, 0.5 * d) - fourth(x, d)) / 3.0
    np.testing.assert_allclose(EI * extrapolated, -WINKLER["k"] * w(x), rtol=1e-5, atol=1e-6 * WINKLER["k"] * w(0.0))
    d = 1e-3 / LAM
    second = (w(x - d) - 2 * w(x) + w(x + d)) / d ** 2
    np.testing.assert_allclose(st.winkler_moment(x, P=P_W, **WINKLER), -EI * second, rtol=1e-5, atol=1e-6 * 12500.0)
    # the foundation carries the whole load: 2 integral_0^inf k w dx = P
    half, _ = integrate.quad(lambda y: float(w(y)), 0.0, np.inf, epsabs=0.0, epsrel=1e-12, limit=200)
    assert 2.0 * WINKLER["k"] * half == approx(P_W, rel=1e-10)


@REQ
def test_winkler_finite_beam_against_solve_bvp_and_limits():
    for lam_L in (1.0, 4.0, 9.0):
        c = 0.5 * lam_L / LAM
        sol = winkler_half_beam_bvp(c)
        x = np.linspace(0.0, c, 7)
        beam = st.winkler_finite_beam(x, P=P_W, L=2 * c, **WINKLER)
        scale = st.winkler_deflection(0.0, P=P_W, **WINKLER)
        np.testing.assert_allclose(beam["deflection"], sol.sol(x)[0], rtol=1e-7, atol=1e-8 * scale)
        np.testing.assert_allclose(beam["moment"], -EI * sol.sol(x)[2], rtol=1e-6, atol=1e-7 * 12500.0)
        np.testing.assert_array_equal(st.winkler_finite_beam(-x, P=P_W, L=2 * c, **WINKLER)["deflection"], beam["deflection"])
    # long (lambda L = 80): the infinite beam to round-off, no overflow
    x = np.array([0.0, 0.4, 1.5, 5.0])
    long = st.winkler_finite_beam(x, P=P_W, L=40.0, **WINKLER)
    np.testing.assert_allclose(long["deflection"], st.winkler_deflection(x, P=P_W, **WINKLER), rtol=1e-12, atol=1e-20)
    np.testing.assert_allclose(long["moment"], st.winkler_moment(x, P=P_W, **WINKLER), rtol=1e-11, atol=1e-10)
    # short (lambda L = 0.01): a rigid beam on springs, w = P / (k L), to (lambda L)^4 / ... ~ 1e-9
    short = st.winkler_finite_beam(np.array([0.0, 0.0025]), P=P_W, L=0.005, **WINKLER)["deflection"]
    np.testing.assert_allclose(short, P_W / (WINKLER["k"] * 0.005), rtol=1e-8)


@REQ
def test_winkler_discrete_beam_balances_and_converges():
    for L in (1.0, 4.0):
        errors = []
        for n in (8, 16, 32, 64):
            d = st.winkler_discrete_beam(P=P_W, L=L, elements=n, **WINKLER)
            # the springs carry the load (to the frame solve's 1e-9); the beam is symmetric about its centre
            assert d["spring_force"].sum() == approx(P_W, rel=1e-9)
            np.testing.assert_allclose(d["deflection"], d["deflection"][::-1], rtol=1e-9, atol=1e-9 * d["deflection"].max())
            assert d["x"][n // 2] == 0.0
            assert abs(d["rotation"][n // 2]) < 1e-10 * np.max(d["deflection"]) / L
            exact = st.winkler_finite_beam(d["x"], P=P_W, L=L, **WINKLER)["deflection"]
            errors.append(np.max(np.abs(d["deflection"] - exact)) / np.max(np.abs(exact)))
        ratios = np.array(errors[:-1]) / np.array(errors[1:])
        if L == 1.0:     # lambda L = 2: 0.38 % at 8 elements (lambda h = 0.25), then second order
            assert 0.0037 < errors[0] < 0.0039
            np.testing.assert_allclose(np.log2(ratios), 2.0, atol=0.01)
        else:            # lambda L = 8: 1.0 %, 0.15 %, 0.040 %, 0.010 %, second order from 16 elements
            assert errors[-1] < 1.1e-4 and np.all(ratios > 3.6)
    with pytest.raises(ValueError, match="even"):
        st.winkler_discrete_beam(P=P_W, L=1.0, elements=7, **WINKLER)


@REQ
def test_winkler_length_for_accuracy():
    unit = dict(P=1.0, k=4.0, E=1.0, I=1.0)   # lambda = 1
    for measure, function in (("deflection", st.winkler_deflection), ("moment", st.winkler_moment)):
        lam_L = st.winkler_length_for_accuracy(measure=measure)
        assert 7.7 < lam_L < 7.75
        infinite = float(function(0.0, **unit))

        def error(v):
            return abs(float(st.winkler_finite_beam(0.0, L=v, **unit)[measure]) / infinite - 1.0)

        assert error(lam_L) == approx(1e-3, rel=1e-8)
        assert max(error(v) for v in np.linspace(lam_L + 1e-6, 20.0, 400)) < 1e-3
        assert max(error(v) for v in np.linspace(lam_L - 1.0, lam_L - 1e-6, 100)) > 1e-3
    assert st.winkler_length_for_accuracy(tolerance=1e-2) < st.winkler_length_for_accuracy()
    with pytest.raises(ValueError, match="measure"):
        st.winkler_length_for_accuracy(measure="shear")
    with pytest.raises(ValueError, match="tolerance"):
        st.winkler_length_for_accuracy(tolerance=2.0)


@REQ
def test_winkler_rejects_bad_input():
    with pytest.raises(ValueError, match="k \\(foundation"):
        st.winkler_deflection(0.0, P=1.0, k=0.0, E=1.0, I=1.0)
    with pytest.raises(ValueError, match="x = "):
        st.winkler_finite_beam(0.6, P=1.0, k=1.0, E=1.0, I=1.0, L=1.0)
    with pytest.raises(ValueError, match="L \\(beam"):
        st.winkler_finite_beam(0.0, P=1.0, k=1.0, E=1.0, I=1.0, L=-1.0)


# ---------------------------------------------------------------- bolt across a joint


def joint_limit_shear(*, N0, P, bolt_direction, phi):
    """The shear force that makes the upper block slide along +s on a joint (normal +n into the upper
    block), limit equilibrium with vectors: the block carries a normal load N0 onto the joint, the bolt
    pulls it by P along bolt_direction; Coulomb: T = (compression on the joint) tan phi + the bolt's
    pull against +s."""
    s, n = np.array([1.0, 0.0]), np.array([0.0, 1.0])
    pull = P * np.asarray(bolt_direction) / np.linalg.norm(bolt_direction)
    compression = N0 - pull @ n
    return compression * math.tan(phi) - pull @ s


@REQ
def test_bolt_joint_shear_increase_by_vector_equilibrium():
    phi = math.radians(30.0)
    for alpha_deg in (0.0, 20.0, 30.0, 45.0, 72.0, 90.0):
        a = math.radians(alpha_deg)
        # the bolt anchored below the joint pulls the upper block down and back (-s, -n): the shear
        # along +s stretches it
        bolted = joint_limit_shear(N0=1e5, P=5e4, bolt_direction=[-math.cos(a), -math.sin(a)], phi=phi)
        plain = joint_limit_shear(N0=1e5, P=0.0, bolt_direction=[1.0, 0.0], phi=phi)
        assert st.bolt_joint_shear_increase(P=5e4, alpha_deg=alpha_deg, phi_deg=30.0) \
            == pytest.approx(bolted - plain, rel=1e-13, abs=1e-9)
    # known values: normal bolt P tan 30 = 0.5773502692 P; along the joint P; largest P / cos phi at alpha = phi
    assert st.bolt_joint_shear_increase(P=1.0, alpha_deg=90.0, phi_deg=30.0) == approx(0.5773502692, rel=1e-9)
    assert st.bolt_joint_shear_increase(P=1.0, alpha_deg=0.0, phi_deg=30.0) == 1.0
    angles = np.linspace(0.0, 90.0, 9001)
    values = [st.bolt_joint_shear_increase(P=1.0, alpha_deg=v, phi_deg=30.0) for v in angles]
    assert angles[int(np.argmax(values))] == pytest.approx(30.0, abs=0.01)
    assert max(values) == approx(1.0 / math.cos(phi), rel=1e-12)


@REQ
def test_reinforcement_shear_limit_known_values():
    # F_s = pi d^2 sigma_b / 4 = pi * 6.25e-4 * 4e8 / 4 = 196349.54 N for a 25 mm bar at 400 MPa
    F_s = st.reinforcement_capacity(d=0.025, sigma_b=4e8)
    assert F_s == approx(196349.5408, rel=1e-9)
    bar = dict(d=0.025, sigma_b=4e8)
    assert st.reinforcement_shear_limit(theta_deg=0.0, shear_increment=1e-4, **bar) == approx(F_s, rel=1e-15)
    assert st.reinforcement_shear_limit(theta_deg=90.0, shear_increment=1e-4, **bar) == approx(0.5 * F_s, rel=1e-15)
    assert st.reinforcement_shear_limit(theta_deg=0.0, shear_increment=-1e-4, **bar) == 0.0
    assert st.reinforcement_shear_limit(theta_deg=60.0, shear_increment=1e-4, **bar) == approx(0.75 * F_s, rel=1e-15)
    # the sign of du_s is carried onto |cos theta0|: theta0 = 120 degrees, du_s > 0 is again 0.75 F_s
    assert st.reinforcement_shear_limit(theta_deg=120.0, shear_increment=1e-4, **bar) == approx(0.75 * F_s, rel=1e-15)
    assert st.reinforcement_shear_limit(theta_deg=120.0, shear_increment=-1e-4, **bar) == approx(0.25 * F_s, rel=1e-14)
    for theta in (10.0, 45.0, 100.0, 170.0):
        both = sum(st.reinforcement_shear_limit(theta_deg=theta, shear_increment=du, **bar) for du in (2.0, -3.0))
        assert both == approx(F_s, rel=1e-15)
    # Bjurstrom 1.4-39: 0.67 * 6.25e-4 * sqrt(4e8 * 1e8) = 0.67 * 6.25e-4 * 2e8 = 83750 N
    assert st.bjurstrom_shear_limit(d=0.025, sigma_b=4e8, sigma_c=1e8) == approx(83750.0, rel=1e-14)


@REQ
def test_bolts_reject_bad_input():
    with pytest.raises(ValueError, match="alpha_deg"):
        st.bolt_joint_shear_increase(P=1.0, alpha_deg=95.0, phi_deg=30.0)
    with pytest.raises(ValueError, match="phi_deg"):
        st.bolt_joint_shear_increase(P=1.0, alpha_deg=45.0, phi_deg=90.0)
    with pytest.raises(ValueError, match="P \\(bolt"):
        st.bolt_joint_shear_increase(P=-1.0, alpha_deg=45.0, phi_deg=30.0)
    with pytest.raises(ValueError, match="shear_increment"):
        st.reinforcement_shear_limit(d=0.025, sigma_b=4e8, theta_deg=45.0, shear_increment=0.0)
    with pytest.raises(ValueError, match="d \\(bar"):
        st.reinforcement_capacity(d=0.0, sigma_b=4e8)


# ---------------------------------------------------------------- lining in an elastic medium

# A 0.3 m concrete lining (E_l = 30 GPa, nu_l = 0.2) of radius 3 m in rock of E_m = 5 GPa, nu_m = 0.3,
# p0 = 10 MPa. C = 5e9 * 3 * 0.96 / (30e9 * 0.3 * 0.91) = 14.4 / 8.19 = 1.758241758.
LINING = dict(R=3.0, t=0.3, E_l=30e9, nu_l=0.2, E_m=5e9, nu_m=0.3)


def thick_lining_pressure(*, R, t, E_l, nu_l, E_m, nu_m, p0, released_fraction):
    """The contact pressure of a thick lining (Lame cylinder R - t <= r <= R, free inside) bonded in a
    hole of radius R, from compatibility at r = R, each side by elastic.lame_cylinder: the lining's
    inward displacement under p equals the hole's further inward displacement as its wall pressure
    drops from (1 - lam_d) p0 to p. Solved in closed form since both are linear in p."""
    def lining_in(p):
        return -elastic.lame_cylinder(r=R, a=R - t, b=R, p_i=0.0, p_o=p, E=E_l, nu=nu_l)[3]

    def hole_in(p):   # the change of the wall's pressure from (1 - lam_d) p0 to p
        return -elastic.lame_cylinder(r=R, a=R, b=np.inf, p_i=p - (1.0 - released_fraction) * p0, p_o=0.0,
                                      E=E_m, nu=nu_m)[3]

    # lining_in(p) = c1 p, hole_in(p) = c2 ((1 - lam_d) p0 - p)
    c1, c2 = lining_in(1.0), -hole_in((1.0 - released_fraction) * p0 + 1.0)
    return c2 * (1.0 - released_fraction) * p0 / (c1 + c2)


@REQ
def test_lining_ring_known_values():
    assert st.compressibility_ratio(**LINING) == approx(14.4 / 8.19, rel=1e-14)
    ring = st.lining_ring(p0=1e7, **LINING)
    # p = p0 / (1 + C (1 - nu_m)) = 1e7 / (1 + 0.7 * 14.4 / 8.19) = 1e7 * 8.19 / 18.27
    assert ring["support_pressure"] == approx(1e7 * 8.19 / 18.27, rel=1e-14)
    assert ring["thrust"] == approx(3.0 * 1e7 * 8.19 / 18.27, rel=1e-14)
    assert ring["hoop_stress"] == approx(10.0 * 1e7 * 8.19 / 18.27, rel=1e-14)
    # ring: u = p R^2 (1 - nu_l^2) / (E_l t) = p * 9 * 0.96 / 9e9; installed at once, the wall's is the ring's
    assert ring["lining_displacement"] == approx(ring["support_pressure"] * 8.64 / 9e9, rel=1e-14)
    assert ring["wall_displacement"] == ring["lining_displacement"]
    # the hole's side of the same displacement: (p0 - p) R (1 + nu_m) / E_m
    assert ring["wall_displacement"] == approx((1e7 - ring["support_pressure"]) * 3.0 * 1.3 / 5e9, rel=1e-13)


@REQ
def test_lining_ring_installation_and_limits():
    late = st.lining_ring(p0=1e7, released_fraction=0.4, **LINING)
    early = st.lining_ring(p0=1e7, **LINING)
    assert late["support_pressure"] == approx(0.6 * early["support_pressure"], rel=1e-14)
    # the wall moved 0.4 p0 R (1 + nu_m) / E_m = 4e6 * 3.9 / 5e9 before the lining, then with it
    assert late["wall_displacement"] - late["lining_displacement"] == approx(4e6 * 3.9 / 5e9, rel=1e-14)
    assert late["wall_displacement"] == approx((1e7 - late["support_pressure"]) * 3.9 / 5e9, rel=1e-13)
    assert st.lining_ring(p0=1e7, released_fraction=1.0, **LINING)["support_pressure"] == 0.0
    # a stiff lining takes all that is left, a soft one nothing
    stiff = st.lining_ring(p0=1e7, released_fraction=0.4, **dict(LINING, E_l=1e20))
    assert stiff["support_pressure"] == approx(6e6, rel=1e-9)
    soft = st.lining_ring(p0=1e7, **dict(LINING, E_l=1e3))
    assert soft["support_pressure"] < 1e-5 * 1e7


@REQ
def test_lining_ring_is_the_thin_limit_of_the_thick_cylinder():
    # The thin ring differs from Lame's thick lining (outer radius R) by O(t / R), less than 2t/3R
    # here: the relative difference halves with t.
    differences = []
    for t in (0.06, 0.03, 0.015, 0.0075):
        for lam_d in (0.0, 0.5):
            params = dict(LINING, t=t)
            thick = thick_lining_pressure(p0=1e7, released_fraction=lam_d, **params)
            thin = st.lining_ring(p0=1e7, released_fraction=lam_d, **params)["support_pressure"]
            assert thin == approx(thick, rel=2.0 * t / 3.0)
        differences.append(abs(thin / thick - 1.0))
    # first order: the ratio of successive differences rises towards 2 (1.85, 1.92, 1.96)
    ratios = np.array(differences[:-1]) / np.array(differences[1:])
    assert np.all((ratios > 1.8) & (ratios < 2.0)) and np.all(np.diff(ratios) > 0.0)


@REQ
def test_lining_rejects_bad_input():
    with pytest.raises(ValueError, match="released_fraction"):
        st.lining_ring(p0=1e7, released_fraction=1.5, **LINING)
    with pytest.raises(ValueError, match="nu_m"):
        st.lining_ring(p0=1e7, **dict(LINING, nu_m=0.5))
    with pytest.raises(ValueError, match="t = "):
        st.lining_ring(p0=1e7, **dict(LINING, t=3.0))
    with pytest.raises(ValueError, match="p0"):
        st.lining_ring(p0=-1.0, **LINING)


# ---------------------------------------------------------------- roof wedge held by cables


def wedge_vertical_residual(*, W, T, N, alpha, phi):
    """Sum of the vertical forces on the symmetric wedge at limit (friction fully mobilised against
    falling), from the force vectors on its right face and the mirror image on its left."""
    outward = np.array([math.cos(alpha), math.sin(alpha)])    # the right face's outward normal (apex up)
    upward_along = np.array([-math.sin(alpha), math.cos(alpha)])
    right = -N * outward + N * math.tan(phi) * upward_along
    return 2.0 * right[1] + T - W


@REQ
def test_wedge_support_force_by_vector_equilibrium():
    assert st.wedge_support_force(W=2e5, half_apex_angle_deg=30.0, phi_deg=35.0) == 2e5   # dead weight
    for alpha_deg, phi_deg, N in ((30.0, 35.0, 1e5), (20.0, 40.0, 3e5), (45.0, 30.0, 1e5)):
        T = st.wedge_support_force(W=2e5, half_apex_angle_deg=alpha_deg, phi_deg=phi_deg, normal_force=N)
        residual = wedge_vertical_residual(W=2e5, T=T, N=N, alpha=math.radians(alpha_deg), phi=math.radians(phi_deg))
        assert abs(residual) < 1e-10 * 2e5
        # friction helps only when phi > alpha
        assert (T < 2e5) == (phi_deg > alpha_deg)
    # weight: unit weight 26 kN/m^3, span 4 m, alpha = 45 degrees: area 4 * 2 / 2 = 4 m^2, 104 kN/m
    assert st.wedge_weight(unit_weight=2.6e4, span=4.0, half_apex_angle_deg=45.0) == approx(1.04e5, rel=1e-14)


@REQ
def test_wedge_cable_forces_balance_the_wedge():
    equal = st.wedge_cable_forces(total=1.2e5, positions=[-1.5, -0.5, 0.5, 1.5])
    np.testing.assert_allclose(equal, 3e4, rtol=1e-14)
    x, k = np.array([-1.0, 0.2, 1.4]), np.array([1.0, 2.0, 0.5])
    F = st.wedge_cable_forces(total=1e5, positions=x, stiffnesses=k, centroid=0.1)
    assert F.sum() == approx(1e5, rel=1e-14)
    assert abs(F @ (x - 0.1)) < 1e-10 * 1e5
    # a rigid motion: the cable extensions F / k lie on a straight line in x
    slopes = np.diff(F / k) / np.diff(x)
    assert slopes[0] == approx(slopes[1], rel=1e-12)
    # two cables at -a and 2a about the centroid: the lever rule, 2/3 and 1/3
    np.testing.assert_allclose(st.wedge_cable_forces(total=3.0, positions=[-1.0, 2.0]), [2.0, 1.0], rtol=1e-14)
    np.testing.assert_allclose(st.wedge_cable_forces(total=3.0, positions=[0.0]), [3.0], rtol=0)
    # cables all at the centroid: no moment, the wedge translates and they share by stiffness
    np.testing.assert_allclose(st.wedge_cable_forces(total=3.0, positions=[0.1, 0.1], stiffnesses=[1.0, 3.0],
                                                     centroid=0.1), [0.75, 2.25], rtol=1e-15)
    with pytest.raises(ValueError, match="positions"):
        st.wedge_cable_forces(total=3.0, positions=[1.0])
    with pytest.raises(ValueError, match="positions"):
        st.wedge_cable_forces(total=3.0, positions=[1.0, 1.0])
    with pytest.raises(ValueError, match="stiffnesses"):
        st.wedge_cable_forces(total=3.0, positions=[1.0, -1.0], stiffnesses=[1.0])
    with pytest.raises(ValueError, match="half_apex_angle_deg"):
        st.wedge_support_force(W=1.0, half_apex_angle_deg=90.0, phi_deg=30.0)
    with pytest.raises(ValueError, match="normal_force"):
        st.wedge_support_force(W=1.0, half_apex_angle_deg=30.0, phi_deg=30.0, normal_force=-1.0)


@REQ
def test_grout_bond_laws():
    # 1.4-42 by quadrature of the annulus's shear strain F' / (2 pi r G_g) across it: D = 25 mm,
    # t = 12.5 mm (ln 2), G_g = 9 GPa: 2 pi 9e9 / ln 2 = 8.158e10 N/m/m
    D, t, G = 0.025, 0.0125, 9e9
    slip, _ = integrate.quad(lambda r: 1.0 / (2.0 * math.pi * r * G), D / 2, D / 2 + t, epsabs=0.0, epsrel=1e-13)
    assert st.grout_bond_stiffness(G_g=G, D=D, t=t) == approx(1.0 / slip, rel=1e-12)
    assert st.grout_bond_stiffness(G_g=G, D=D, t=t) == approx(2 * math.pi * 9e9 / math.log(2.0), rel=1e-15)
    # 1.4-44: pi * 0.05 * 2e6 = 314159.27 N/m
    assert st.grout_bond_strength(D=D, t=t, tau_peak=2e6) == approx(math.pi * 1e5, rel=1e-15)
    with pytest.raises(ValueError, match="G_g"):
        st.grout_bond_stiffness(G_g=0.0, D=D, t=t)
    with pytest.raises(ValueError, match="tau_peak"):
        st.grout_bond_strength(D=D, t=t, tau_peak=-1.0)


@REQ
def test_winkler_discrete_deflection_is_the_discrete_beams_node():
    beam = st.winkler_discrete_beam(P=1000.0, k=1e8, E=200e9, I=1e-5, L=4.0, elements=32)
    for node in (0, 8, 16, 32):
        x = beam["x"][node]
        assert st.winkler_discrete_deflection(x, P=1000.0, k=1e8, E=200e9, I=1e-5, L=4.0, elements=32) == beam["deflection"][node]
    with pytest.raises(ValueError, match="not a node"):
        st.winkler_discrete_deflection(0.01, P=1000.0, k=1e8, E=200e9, I=1e-5, L=4.0, elements=32)


@REQ
def test_first_periods_are_the_inverse_first_frequencies():
    args = dict(E=200e9, I=1e-5, rho=7850.0, A=0.01, L=2.0)
    assert st.cantilever_first_period(**args) * st.cantilever_frequencies(**args)[0] == pytest.approx(1.0, rel=1e-15, abs=0)
    lumped = st.cantilever_lumped_first_period(**args, elements=8, rotary_inertia_ratio=1.0 / 12.0)
    f = st.cantilever_lumped_frequencies(**args, elements=8, rotary_inertia_ratio=1.0 / 12.0)[0]
    assert lumped * f == pytest.approx(1.0, rel=1e-15, abs=0)
    # the lumped cantilever is slower than the continuum (it converges from below in frequency)
    assert lumped > st.cantilever_first_period(**args)


@REQ
def test_lining_ring_in_a_finite_medium_with_interface_springs_is_the_three_springs_in_series():
    args = dict(R=1.0, t=0.2, E_l=30e9, nu_l=0.0, E_m=10e9, nu_m=0.25, p0=10e6)
    plain = st.lining_ring(**args)
    # huge outer radius and stiff springs: the infinite-medium formula
    near = st.lining_ring(**args, outer_radius=1e6, interface_stiffness=1e30)
    assert near["support_pressure"] == pytest.approx(plain["support_pressure"], rel=1e-9, abs=0)
    # an independent form: Lame's hollow cylinder for the medium (wall displacement of a unit
    # pressure drop, from the stresses' radial equilibrium solved numerically) and springs in series
    b, k = 10.0, 1e12
    R, nu, E = 1.0, 0.25, 10e9
    # u(r) = A r + B / r in plane strain: sigma_r = E/((1+nu)(1-2nu)) ((A (1) ) ...) solved for
    # sigma_r(R) = -1, sigma_r(b) = 0 by a linear system
    lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
    def sigma_r(A, B, r):
        return 2 * (lam + mu) * A - 2 * mu * B / r ** 2
    M = np.array([[2 * (lam + mu), -2 * mu / R ** 2], [2 * (lam + mu), -2 * mu / b ** 2]])
    A, B = np.linalg.solve(M, np.array([-1.0, 0.0]))   # a unit pressure on the wall, none outside
    f_m = A * R + B / R                                  # outward per unit pressure: inward per unit drop
    f_l = R * R / (30e9 * 0.2)
    expected = 10e6 * f_m / (f_m + f_l + 1.0 / k)
    got = st.lining_ring(**args, outer_radius=b, interface_stiffness=k)
    assert got["support_pressure"] == pytest.approx(expected, rel=1e-12, abs=0)
    assert got["wall_displacement"] == pytest.approx(expected * (f_l + 1.0 / k), rel=1e-12, abs=0)
    with pytest.raises(ValueError, match="outer_radius"):
        st.lining_ring(**args, outer_radius=0.5)


@REQ
def test_discrete_slip_scalar_forms_are_the_chains_segment_and_head():
    args = dict(F0=1e4, L=2.0, EA=1e8, k_bond=1e8, s_bond=8000.0, n=20)
    cable = st.cable_discrete_slip(**args)
    assert st.cable_discrete_slip_segment_force(0.05, **args) == cable["force"][0]
    assert st.cable_discrete_slip_segment_force(0.95, **args) == cable["force"][9]
    assert st.cable_discrete_slip_segment_force(2.0, **args) == cable["force"][19]
    assert st.cable_discrete_slip_head_displacement(**args) == cable["displacement"][0]


# ================================================================ local reinforcement (bolts)

@REQ
def test_yielding_spring_known_values_and_its_law():
    # K u F / (F + K u): half the bound when K u = F_max; linear when unbounded; odd in u.
    assert st.yielding_spring_force(1e-3, K=1e8, F_max=1e5) == pytest.approx(5e4, rel=1e-15)
    assert st.yielding_spring_force(-1e-3, K=1e8, F_max=1e5) == pytest.approx(-5e4, rel=1e-15)
    assert st.yielding_spring_force(2e-3, K=1e8, F_max=math.inf) == pytest.approx(2e5, rel=1e-15)
    # It solves dF/du = K (1 - F / F_max)^2 (1.4-48, 1.4-49 loading from zero), F(0) = 0.
    u, h = np.linspace(1e-4, 0.05, 50), 1e-8
    F = st.yielding_spring_force(u, K=1e8, F_max=1e5)
    slope = (st.yielding_spring_force(u + h, K=1e8, F_max=1e5) - st.yielding_spring_force(u - h, K=1e8, F_max=1e5)) / (2 * h)
    assert slope == pytest.approx(1e8 * (1.0 - F / 1e5) ** 2, rel=1e-6)


@REQ
def test_active_length_stretch_is_the_geometry():
    # 0.2 m at 45 degrees, slid 20 mm: |(0.1414 + 0.02, 0.1414)| - 0.2
    assert st.bolt_active_length_stretch(0.02, L=0.2, alpha_deg=45.0) == pytest.approx(
        math.hypot(0.2 / math.sqrt(2) + 0.02, 0.2 / math.sqrt(2)) - 0.2, rel=1e-14, abs=0)
    # small slides: us cos(alpha); normal opening: un sin(alpha)
    assert st.bolt_active_length_stretch(1e-7, L=0.2, alpha_deg=60.0) == pytest.approx(0.5e-7, rel=1e-5, abs=0)
    assert st.bolt_active_length_stretch(0.0, L=0.2, alpha_deg=60.0, un=1e-7) == pytest.approx(
        math.sin(math.radians(60.0)) * 1e-7, rel=1e-5, abs=0)


@REQ
def test_crushed_axial_displacement_closed_form_for_a_normal_bolt():
    # alpha = 90: u_eff = us - L asinh(us / L) (derivation in the docstring)
    for us in (1e-3, 0.02, 0.1):
        assert st.bolt_crushed_axial_displacement(us, L=0.2, alpha_deg=90.0) == pytest.approx(
            us - 0.2 * math.asinh(us / 0.2), rel=1e-8, abs=0)
    # crushing only reduces what the turning adds: between the straight part and the stretch
    us = 0.02
    crushed = st.bolt_crushed_axial_displacement(us, L=0.2, alpha_deg=45.0)
    assert us * math.cos(math.radians(45.0)) < crushed < st.bolt_active_length_stretch(us, L=0.2, alpha_deg=45.0)


@REQ
def test_direct_shear_reduces_to_bjurstrom_for_an_axial_bolt_that_does_not_turn():
    # Shear spring off, a long active length: (R - N tan phi) / Fa -> cos a + sin a tan phi
    for alpha in (30.0, 45.0, 60.0):
        R, Fa, Fs, Nc = st.bolt_direct_shear(1e-3, N=1e5, phi_deg=30.0, L=1e4, alpha_deg=alpha, Ka=1e8, Fa_max=1e5,
                                             Ks=0.0, Fs=8e4, crushing=False)
        assert Fs == 0.0
        assert st.bolt_resistance_per_unit_tension(R=R, Fa=Fa, N=1e5, phi_deg=30.0) == pytest.approx(
            st.bolt_joint_shear_increase(P=1.0, alpha_deg=alpha, phi_deg=30.0), rel=1e-6)
        assert Nc == pytest.approx(1e5 + Fa * math.sin(math.radians(alpha)), rel=1e-6)


@REQ
def test_direct_shear_shear_bound_follows_the_sense_of_shear():
    # Bound F_s (1 + cos a) / 2: stretched at 45 degrees, shortened at 135; a huge slide reaches it.
    big = 10.0
    for alpha, bound in ((45.0, 8e4 * (1 + math.cos(math.radians(45.0))) / 2),
                         (135.0, 8e4 * (1 - math.cos(math.radians(45.0))) / 2), (90.0, 4e4)):
        _, _, Fs, _ = st.bolt_direct_shear(big, N=1e5, phi_deg=30.0, L=0.2, alpha_deg=alpha, Ka=1e8, Fa_max=1e5,
                                           Ks=2e7, Fs=8e4, crushing=False)
        assert abs(Fs) == pytest.approx(bound, rel=1e-3)
    # the joint's closure under the clamp, when asked for, converges: un = -(Nc - N) / k_j
    R1, Fa1, _, N1 = st.bolt_direct_shear(0.02, N=1e5, phi_deg=30.0, L=0.2, alpha_deg=45.0, Ka=1e8, Fa_max=1e5,
                                          Ks=2e7, Fs=8e4, crushing=False, joint_normal_stiffness=1e9)
    R0, Fa0, _, N0 = st.bolt_direct_shear(0.02, N=1e5, phi_deg=30.0, L=0.2, alpha_deg=45.0, Ka=1e8, Fa_max=1e5,
                                          Ks=2e7, Fs=8e4, crushing=False)
    assert Fa1 < Fa0  # the closure shortens the stretch
    with pytest.raises(ValueError):
        st.bolt_direct_shear(0.02, N=1e5, phi_deg=30.0, L=0.2, alpha_deg=45.0, Ka=1e8, Fa_max=1e5, Ks=2e7, Fs=8e4,
                             crushing=True, joint_normal_stiffness=1e9)
    with pytest.raises(ValueError):
        st.bolt_resistance_per_unit_tension(R=1.0, Fa=0.0, N=1.0, phi_deg=30.0)

"""Closed-form rock-support references (verification/analytic/structures.py) at known values.

Known values are hand arithmetic shown in the comments or published tables (the cantilever's
beta_n L to 9 digits, Blevins table 8-1). The other checks take independent routes, never the
function under test rewritten: scipy's solve_bvp on the differential equation, a dense linear solve of
the spring chain or the frame assembled here, eigenvalues of the flexibility matrix built from the
continuum's influence functions, quadrature for equilibrium, central differences of the fields, and
Lame's thick cylinder for the thin ring.

Tolerances: a closed form against another closed form or a linear solve: 1e-12 relative (condition
numbers stay below 1e4 here); against solve_bvp run to tol 1e-10: 1e-7; finite differences with step d:
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

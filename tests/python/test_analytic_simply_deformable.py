"""Closed-form simply-deformable-block references (verification/analytic/simply_deformable.py) at known values.

Known values are worked by hand in the comments. The other checks take independent routes, never the
function under test rewritten: a six-mode simply-deformable block built here (its stiffness from the
plane-strain Lame matrix, its loads from Gauss quadrature of the tractions, its supports as exact
constraints) and solved by numpy; the column assembled here on other unknowns (face displacements,
two-node bar elements) and solved statically or by an eigen-solve; the rigid chain by a numpy
eigen-solve; the continuum by scipy quadrature of its strain; the beam by the unit-load method with
scipy quadrature.
"""
import math

import numpy as np
import pytest
import scipy.linalg
from scipy import integrate

from analytic import simply_deformable as sd

REQ = pytest.mark.requirements("REQ-QA-003")

# A rock: E = 10 GPa, nu = 0.25, so G = 4 GPa, lambda = 4 GPa, E / (1 - nu^2) = 1.0667e10 Pa,
# K + 4G/3 = 6.6667e9 + 5.3333e9 = 1.2e10 Pa.
ROCK = dict(E=1e10, nu=0.25)
# The column: H = 10 m, 5 blocks of h = 2 m, rho g = 2500 x 10 = 25000 Pa/m, M = 1e10 Pa.
COLUMN = dict(height=10.0, n_blocks=5, rho=2500.0, g=10.0, modulus=1e10)


def lame(E, nu):
    return E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), E / (2.0 * (1.0 + nu))


# ---------------------------------------------------------------- one block's six modes, built here


def modes(r):
    """Displacement (2 x 6) at offset r from the centroid for q = (u_c, v_c, w, e11, e22, e12):
    rigid translation, rotation w, and the uniform strain (e12 the tensor shear strain)."""
    rx, ry = r
    return np.array([[1.0, 0.0, -ry, rx, 0.0, ry],
                     [0.0, 1.0, rx, 0.0, ry, rx]])


def block_stiffness(area, E, nu):
    """A B^T D B with (exx, eyy, gxy) = B q and D the plane-strain matrix in Lame's constants."""
    lam, G = lame(E, nu)
    d = np.array([[lam + 2 * G, lam, 0.0], [lam, lam + 2 * G, 0.0], [0.0, 0.0, G]])
    b = np.zeros((3, 6))
    b[0, 3], b[1, 4], b[2, 5] = 1.0, 1.0, 2.0
    return area * b.T @ d @ b, d


def edge_forces(a, b, traction, points=3):
    """Gauss-point forces (position, force) of a uniform traction on the edge a -> b."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    nodes, weights = np.polynomial.legendre.leggauss(points)
    length = np.linalg.norm(b - a)
    return [(a + 0.5 * (s + 1.0) * (b - a), 0.5 * w * length * np.asarray(traction, float))
            for s, w in zip(nodes, weights)]


def solve_held(stiffness, load, rows):
    """K q = Q + C^T lambda, C q = 0: the exact constrained solution and the reactions' multipliers."""
    c = np.array(rows)
    n, m = stiffness.shape[0], c.shape[0]
    kkt = np.block([[stiffness, -c.T], [c, np.zeros((m, m))]])
    x = np.linalg.solve(kkt, np.concatenate([load, np.zeros(m)]))
    return x[:n], x[n:]


# ---------------------------------------------------------------- a block between platens


@REQ
def test_platen_known_values():
    # free: e_yy = (1 - 0.0625) 1e6 / 1e10 = 9.375e-5, e_xx = -0.25 x 1.25 x 1e-4 = -3.125e-5 (widens),
    # s_zz = 0.25 MPa
    free = sd.platen_compression_strains(stress=1e6, lateral="free", **ROCK)
    for key, value in dict(exx=-3.125e-5, eyy=9.375e-5, ezz=0.0, sxx=0.0, syy=1e6, szz=2.5e5).items():
        assert free[key] == pytest.approx(value, rel=1e-14, abs=0), key
    # held: s_xx = s_zz = 0.25 / 0.75 MPa = 333333.3 Pa, e_yy = 1e6 x 1.25 x 0.5 / (0.75 x 1e10) = 8.3333e-5
    held = sd.platen_compression_strains(stress=1e6, lateral="held", **ROCK)
    for key, value in dict(exx=0.0, eyy=1e6 / 1.2e10, ezz=0.0, sxx=1e6 / 3, syy=1e6, szz=1e6 / 3).items():
        assert held[key] == pytest.approx(value, rel=1e-14, abs=0), key
    # the column's moduli are the platen's stress over strain: 1.0667e10 and 1.2e10 Pa
    assert sd.column_modulus(lateral="free", **ROCK) == pytest.approx(1e10 / 0.9375, rel=1e-15, abs=0)
    assert sd.column_modulus(lateral="held", **ROCK) == pytest.approx(1.2e10, rel=1e-15, abs=0)


@REQ
@pytest.mark.parametrize("nu", [0.0, 0.25, 0.45, -0.3])
@pytest.mark.parametrize("lateral", ["free", "held"])
def test_platen_solves_hookes_law_in_lame_constants(nu, lateral):
    # Six unknowns (three strains, three stresses, tension positive), sigma = lambda tr(e) + 2 G e,
    # and three conditions: s_yy = -1e6, e_zz = 0, and s_xx = 0 (free) or e_xx = 0 (held).
    lam, G = lame(1e10, nu)
    a = np.zeros((6, 6))
    a[:3, :3] = -(lam * np.ones((3, 3)) + 2 * G * np.eye(3))
    a[:3, 3:] = np.eye(3)
    a[3, 4] = 1.0
    a[4, 2] = 1.0
    a[5, 3 if lateral == "free" else 0] = 1.0
    e_xx, e_yy, e_zz, s_xx, s_yy, s_zz = np.linalg.solve(a, [0, 0, 0, -1e6, 0, 0])
    got = sd.platen_compression_strains(stress=1e6, E=1e10, nu=nu, lateral=lateral)
    expected = dict(exx=-e_xx, eyy=-e_yy, ezz=-e_zz, sxx=-s_xx, syy=-s_yy, szz=-s_zz)
    for key, value in expected.items():
        assert got[key] == pytest.approx(value, rel=1e-12, abs=1e-12 * abs(expected["eyy"] if key[0] == "e" else 1e6))
    # the column's modulus is the same stress over strain; held, K + 4G/3 with K = lambda + 2G/3
    assert sd.column_modulus(E=1e10, nu=nu, lateral=lateral) == pytest.approx(1e6 / -e_yy, rel=1e-12, abs=0)
    if lateral == "held":
        assert sd.column_modulus(E=1e10, nu=nu, lateral=lateral) == pytest.approx(lam + 2 * G / 3 + 4 * G / 3,
                                                                                 rel=1e-12, abs=0)


@REQ
@pytest.mark.parametrize("lateral", ["free", "held"])
def test_platen_is_exact_for_a_simply_deformable_block(lateral):
    # A 2 m x 1 m block, centroid at the origin: the upper platen's uniform traction (0, -1 MPa) on the
    # top face; the lower platen, frictionless, holds u_y at both bottom corners and one u_x (rigid
    # sliding); held sides hold u_x at the middle of each side.
    k, d = block_stiffness(2.0, **ROCK)
    load = sum(modes(x).T @ f for x, f in edge_forces((1.0, 0.5), (-1.0, 0.5), (0.0, -1e6)))
    rows = [modes((-1.0, -0.5))[1], modes((1.0, -0.5))[1], modes((0.0, -0.5))[0]]
    if lateral == "held":
        rows += [modes((-1.0, 0.0))[0], modes((1.0, 0.0))[0]]
    q, _ = solve_held(k, load, rows)
    strain = np.array([q[3], q[4], 2 * q[5]])
    stress = d @ strain
    lam, _ = lame(**ROCK)
    got = sd.platen_compression_strains(stress=1e6, lateral=lateral, **ROCK)
    assert got["exx"] == pytest.approx(-q[3], rel=1e-12, abs=1e-20)
    assert got["eyy"] == pytest.approx(-q[4], rel=1e-12, abs=0)
    assert abs(q[5]) < 1e-20
    assert got["sxx"] == pytest.approx(-stress[0], rel=1e-10, abs=1e-6)
    assert got["syy"] == pytest.approx(-stress[1], rel=1e-12, abs=0)
    assert got["szz"] == pytest.approx(-lam * (q[3] + q[4]), rel=1e-12, abs=0)


# ---------------------------------------------------------------- a column under its own weight


def static_column(n, h, rho, g, M, kn):
    """The column built here as blocks (v_j up, e_j extension) with springs kn across each joint's
    opening (or, bonded, the openings held at 0), loaded by each block's weight: statically solved.
    Returns the downward displacement at y (the block above a joint's level)."""
    k = np.zeros((2 * n, 2 * n))
    load = np.zeros(2 * n)
    openings = []
    for j in range(n):
        k[2 * j + 1, 2 * j + 1] = M * h
        load[2 * j] = -rho * g * h
        # gravity's work in the strain mode: integral of -rho g s over the block, s from its centroid
        load[2 * j + 1] = integrate.quad(lambda s: -rho * g * s, -h / 2, h / 2)[0]
        row = np.zeros(2 * n)
        row[2 * j:2 * j + 2] = (1.0, -h / 2)        # bottom face of block j
        if j > 0:
            row[2 * j - 2:2 * j] -= (1.0, h / 2)    # less the top face of block j - 1
        openings.append(row)
    if math.isinf(kn):
        q, _ = solve_held(k, load, openings)
    else:
        q = np.linalg.solve(k + kn * sum(np.outer(r, r) for r in openings), load)

    def settlement(y):
        j = min(int(math.floor(y / h + 1e-9)), n - 1)
        return -(q[2 * j] + q[2 * j + 1] * (y - (j + 0.5) * h))
    return settlement


@REQ
def test_column_known_values():
    y = np.array([0.0, 1.0, 2.0, 3.0, 4.0, 10.0])
    # Bonded: block j shortens by rho g h (n - j - 1/2) / M: 25000 x 2 x 4.5 / 1e10 = 2.25e-5 for the lowest,
    # 1.75e-5, 1.25e-5, 0.75e-5, 0.25e-5 above; u(1) = 2.25e-5 x 1 / 2 ... the lowest block's strain times 1 m:
    # u(1) = 2.25e-5, u(2) = 4.5e-5, u(3) = 4.5e-5 + 1.75e-5 / 2 = 6.25e-5, u(4) = 8e-5, u(10) = 2.25e-5 x 2
    # + 1.75e-5 x 2 + ... = (4.5 + 3.5 + 2.5 + 1.5 + 0.5) 1e-5 = 1.25e-4 = rho g H^2 / 2M.
    bonded = sd.column_self_weight_displacement(y=y, **COLUMN)
    np.testing.assert_allclose(bonded, [0.0, 2.25e-5, 4.5e-5, 6.25e-5, 8e-5, 1.25e-4], rtol=1e-14, atol=1e-20)
    # Continuum: 25000 (10 y - y^2 / 2) / 1e10: 0, 2.375e-5, 4.5e-5, 6.375e-5, 8e-5, 1.25e-4.
    continuum = sd.continuum_column_self_weight_displacement(y=y, height=10.0, rho=2500.0, g=10.0, modulus=1e10)
    np.testing.assert_allclose(continuum, [0.0, 2.375e-5, 4.5e-5, 6.375e-5, 8e-5, 1.25e-4], rtol=1e-14, atol=1e-20)
    # kn = 1e10 Pa/m: joint j closes by 25000 x 2 x (5 - j) / 1e10 = 2.5e-5, 2e-5, 1.5e-5, 1e-5, 0.5e-5; a joint's
    # level takes the block above it: u(0) = 2.5e-5, u(1) = 4.75e-5, u(2) = 4.5e-5 + 4.5e-5 = 9e-5,
    # u(3) = 9e-5 + 1.75e-5 = 1.075e-4, u(4) = 8e-5 + 6e-5 = 1.4e-4, u(10) = 1.25e-4 + 7.5e-5 = 2e-4.
    jointed = sd.column_self_weight_displacement(y=y, kn=1e10, **COLUMN)
    np.testing.assert_allclose(jointed, [2.5e-5, 4.75e-5, 9e-5, 1.075e-4, 1.4e-4, 2e-4], rtol=1e-14, atol=1e-20)


@REQ
@pytest.mark.parametrize("n", [1, 2, 3, 7])
@pytest.mark.parametrize("kn", [math.inf, 1e10, 3e8])
def test_column_matches_a_static_solve_of_the_blocks(n, kn):
    H, rho, g, M = 10.0, 2500.0, 10.0, 1e10
    settlement = static_column(n, H / n, rho, g, M, kn)
    h = H / n
    ys = sorted(set(np.concatenate([np.linspace(0.0, H, 4 * n + 1), [0.3 * h, H - 0.1 * h]])))
    got = sd.column_self_weight_displacement(y=np.array(ys), height=H, n_blocks=n, rho=rho, g=g, modulus=M, kn=kn)
    expected = np.array([settlement(y) for y in ys])
    np.testing.assert_allclose(got, expected, rtol=1e-10, atol=1e-18)


@REQ
def test_continuum_column_is_the_integral_of_its_strain():
    # The shortening strain at s is the weight above over M, rho g (H - s) / M; integrated by quadrature.
    for y in (0.0, 0.7, 3.3, 9.99, 10.0):
        by_quadrature = integrate.quad(lambda s: 25000.0 * (10.0 - s) / 1e10, 0.0, y, epsabs=0, epsrel=1e-13)[0]
        assert sd.continuum_column_self_weight_displacement(y=y, height=10.0, rho=2500.0, g=10.0, modulus=1e10) == \
            pytest.approx(by_quadrature, rel=1e-12, abs=1e-20)


@REQ
@pytest.mark.parametrize("n", [1, 2, 5, 10])
def test_column_is_exact_at_block_boundaries_and_converges_as_h_squared(n):
    H, rho, g, M, kn = 10.0, 2500.0, 10.0, 1e10, 4e9
    h = H / n
    common = dict(height=H, rho=rho, g=g, modulus=M)
    boundaries = np.arange(n + 1) * h
    closures = np.array([sum(rho * g * h * (n - j) / kn for j in range(min(k + 1, n))) for k in range(n + 1)])
    # at y = k h the blocks equal the continuum plus the closures of the joints at and below it (the
    # top, y = H, has none above the highest block's)
    np.testing.assert_allclose(sd.column_self_weight_displacement(y=boundaries, n_blocks=n, kn=kn, **common),
                               sd.continuum_column_self_weight_displacement(y=boundaries, **common) + closures,
                               rtol=1e-13, atol=0)
    # bonded, the error is largest mid-block and there exactly rho g h^2 / 8M (25000 x 100 / 8e10 = 3.125e-5 m
    # for n = 1, a quarter of the top's 1.25e-4), everywhere an under-estimate
    y = np.linspace(0.0, H, 40 * n + 1)
    error = sd.continuum_column_self_weight_displacement(y=y, **common) - \
        sd.column_self_weight_displacement(y=y, n_blocks=n, **common)
    assert np.all(error >= -1e-20)
    assert error.max() == pytest.approx(rho * g * h * h / (8.0 * M), rel=1e-10, abs=0)
    assert error.max() == pytest.approx(1.25e-4 / (4 * n * n), rel=1e-10, abs=0)
    mids = (np.arange(n) + 0.5) * h
    np.testing.assert_allclose(sd.continuum_column_self_weight_displacement(y=mids, **common) -
                               sd.column_self_weight_displacement(y=mids, n_blocks=n, **common),
                               rho * g * h * h / (8.0 * M), rtol=1e-9, atol=0)


@REQ
def test_column_rejects_nonsense():
    with pytest.raises(ValueError):
        sd.column_self_weight_displacement(y=10.5, **COLUMN)
    with pytest.raises(ValueError):
        sd.column_self_weight_displacement(y=-0.1, **COLUMN)
    with pytest.raises(ValueError):
        sd.column_self_weight_displacement(y=1.0, **dict(COLUMN, n_blocks=2.5))
    with pytest.raises(ValueError):
        sd.column_self_weight_displacement(y=1.0, **dict(COLUMN, n_blocks=0))
    with pytest.raises(ValueError):
        sd.column_self_weight_displacement(y=1.0, kn=0.0, **COLUMN)
    with pytest.raises(ValueError):
        sd.column_self_weight_displacement(y=1.0, **dict(COLUMN, rho=-2500.0))
    with pytest.raises(ValueError):
        sd.continuum_column_self_weight_displacement(y=1.0, height=10.0, rho=2500.0, g=10.0, modulus=0.0)
    with pytest.raises(ValueError):
        sd.column_modulus(E=1e10, nu=0.5, lateral="held")
    with pytest.raises(ValueError):
        sd.column_modulus(E=1e10, nu=0.25, lateral="sideways")
    with pytest.raises(ValueError):
        sd.platen_compression_strains(stress=1e6, E=-1e10, nu=0.25, lateral="free")
    with pytest.raises(ValueError):
        sd.platen_compression_strains(stress=math.nan, E=1e10, nu=0.25, lateral="free")


# ---------------------------------------------------------------- a column's axial vibration

FREQ = dict(height=10.0, rho=2500.0, modulus=1e10)


def rigid_chain_frequency(n, m, k):
    """Masses m on springs k, the lowest sprung to the base, the top free: numpy's eigen-solve."""
    stiffness = 2 * k * np.eye(n) - k * np.eye(n, k=1) - k * np.eye(n, k=-1)
    stiffness[-1, -1] = k
    return math.sqrt(np.linalg.eigvalsh(stiffness / m)[0]) / (2 * math.pi)


def bar_element_chain_frequency(n, h, rho, M, kn):
    """The column on other unknowns: each block a two-node bar element (bottom and top face), stiffness
    (M / h) [[1, -1], [-1, 1]] and consistent mass (rho h / 6) [[2, 1], [1, 2]], the joints springs kn
    between a block's bottom node and the top node of the one below (the base for the lowest)."""
    k, m = np.zeros((2 * n, 2 * n)), np.zeros((2 * n, 2 * n))
    for j in range(n):
        s = slice(2 * j, 2 * j + 2)
        k[s, s] += M / h * np.array([[1.0, -1.0], [-1.0, 1.0]])
        m[s, s] += rho * h / 6.0 * np.array([[2.0, 1.0], [1.0, 2.0]])
        k[2 * j, 2 * j] += kn
        if j > 0:
            k[2 * j - 1, 2 * j - 1] += kn
            k[2 * j, 2 * j - 1] -= kn
            k[2 * j - 1, 2 * j] -= kn
    return math.sqrt(scipy.linalg.eigh(k, m, eigvals_only=True)[0]) / (2 * math.pi)


@REQ
def test_frequency_known_values():
    # Continuum, bonded: c = sqrt(1e10 / 2500) = 2000 m/s, f = 2000 / 40 = 50 Hz.
    assert sd.jointed_column_first_frequency(n_blocks=5, kn=math.inf, blocks="continuum", **FREQ) == \
        pytest.approx(50.0, rel=1e-15, abs=0)
    # kn = 1e10 Pa/m, h = 2 m: 1 / M_eff = 1e-10 + 1 / 2e10 = 1.5e-10, c = sqrt(6.6667e9 / 2500) = 1632.993 m/s,
    # f = 40.82483 Hz.
    assert sd.jointed_column_first_frequency(n_blocks=5, kn=1e10, blocks="continuum", **FREQ) == \
        pytest.approx(1632.993161855452 / 40.0, rel=1e-14, abs=0)
    # Rigid, n = 5: sqrt(k / m) = sqrt(1e10 / 5000) = 1414.2136 /s, sin(pi / 22) = 0.1423148383,
    # w = 2 x 1414.2136 x 0.1423148383 = 402.52715 rad/s, f = 64.06419 Hz (M not used).
    assert sd.jointed_column_first_frequency(n_blocks=5, kn=1e10, blocks="rigid", **FREQ) == \
        pytest.approx(402.527148826027 / (2 * math.pi), rel=1e-13, abs=0)
    assert sd.jointed_column_first_frequency(n_blocks=5, kn=1e10, blocks="rigid", **dict(FREQ, modulus=1.0)) == \
        sd.jointed_column_first_frequency(n_blocks=5, kn=1e10, blocks="rigid", **FREQ)
    # Simply-deformable, n = 1 (h = 10 m): unknowns (v, e), the base joint's opening v - 5 e:
    # K = [[1e10, -5e10], [-5e10, 2.5e11 + 1e11]], masses 25000 and 2500 x 1000 / 12 = 208333.3.
    # det(K - lambda M) = 0: a lambda^2 + b lambda + c with a = 25000 x 208333.3 = 5.2083e9,
    # b = -(1e10 x 208333.3 + 3.5e11 x 25000) = -1.08333e16, c = kn M h = 1e21; the smaller root
    # lambda = 96810 /s^2, w = 311.14 rad/s, f = 49.521 Hz (against the homogenised bar's 47.673 Hz).
    a = 25000.0 * 2500.0 * 1000.0 / 12.0
    b = -(1e10 * 2500.0 * 1000.0 / 12.0 + 3.5e11 * 25000.0)
    c = 1e21
    lam = (-b - math.sqrt(b * b - 4 * a * c)) / (2 * a)
    assert lam == pytest.approx(96810, rel=1e-4, abs=0)
    assert sd.jointed_column_first_frequency(n_blocks=1, kn=1e10, **FREQ) == \
        pytest.approx(math.sqrt(lam) / (2 * math.pi), rel=1e-10, abs=0)
    assert sd.jointed_column_first_frequency(n_blocks=1, kn=1e10, **FREQ) == pytest.approx(49.521, rel=1e-4, abs=0)


@REQ
@pytest.mark.parametrize("n", [1, 2, 3, 5, 12, 40])
def test_rigid_chain_closed_form_matches_an_eigen_solve(n):
    h = 10.0 / n
    assert sd.jointed_column_first_frequency(n_blocks=n, kn=3e9, blocks="rigid", **FREQ) == \
        pytest.approx(rigid_chain_frequency(n, 2500.0 * h, 3e9), rel=1e-11, abs=0)


@REQ
@pytest.mark.parametrize("n", [1, 2, 4, 9])
@pytest.mark.parametrize("kn", [1e8, 1e10, 1e12])
def test_simply_deformable_chain_matches_bar_elements_with_joint_springs(n, kn):
    # Two modes per block (v, e with mass rho h^3 / 12) are a two-node element with consistent mass.
    assert sd.jointed_column_first_frequency(n_blocks=n, kn=kn, **FREQ) == \
        pytest.approx(bar_element_chain_frequency(n, 10.0 / n, 2500.0, 1e10, kn), rel=1e-10, abs=0)


@REQ
@pytest.mark.parametrize("n", [1, 2, 3, 6, 20])
def test_simply_deformable_chain_bonded_is_the_consistent_mass_bar(n):
    # Dispersion of two-node elements with consistent mass (interior equation with u_j = sin(j theta)):
    # (M / h)(2 - 2 cos theta) = w^2 (rho h / 6)(4 + 2 cos theta); the free top needs theta = pi / (2n).
    # n = 1: w^2 = (6 x 1e10 / (2500 x 100)) (1 - 0) / (2 + 0) = 1.2e5, f = 346.41 / 2 pi = 55.133 Hz
    # (10 % above the bar's 50 Hz).
    h, theta = 10.0 / n, math.pi / (2 * n)
    w2 = 6.0 * 1e10 / (2500.0 * h * h) * (1.0 - math.cos(theta)) / (2.0 + math.cos(theta))
    bonded = sd.jointed_column_first_frequency(n_blocks=n, kn=math.inf, **FREQ)
    assert bonded == pytest.approx(math.sqrt(w2) / (2 * math.pi), rel=1e-11, abs=0)
    if n == 1:
        assert bonded == pytest.approx(math.sqrt(1.2e5) / (2 * math.pi), rel=1e-12, abs=0)
    # ... and stiff joints tend to it from below, in proportion to their compliance 1 / (kn h) against
    # the blocks' 1 / M (the relative gap times kn h / M is 1.125 at n = 1, 0.52 at n = 20). Not stiffer:
    # the eigen-solve's round-off grows with the ratio of the highest mode to the first.
    gaps = [1.0 - sd.jointed_column_first_frequency(n_blocks=n, kn=r * 1e10 / h, **FREQ) / bonded for r in (1e3, 1e4)]
    assert 0.0 < gaps[0] < 1.2e-3
    assert gaps[0] / gaps[1] == pytest.approx(10.0, rel=0.02, abs=0)


@REQ
def test_simply_deformable_chain_limits():
    # (a) n grows with kn h fixed (= M: half the compliance in the joints, phi = 1/2, M_eff = M / 2,
    # f_bar = sqrt(5e9 / 2500) / 40 = 35.355 Hz): the error -> -phi / (2n), first order. Seen:
    # n = 8: -0.0300, n = 64: -0.00388, n = 128: -0.00195 (n x error = -0.2486, -0.2493). The rigid
    # chain (phi = 1) against its own bar (M_eff = kn h): -0.0602 at n = 8, -0.0039 at n = 128.
    for n in (32, 64, 128):
        h = 10.0 / n
        bar = sd.jointed_column_first_frequency(n_blocks=n, kn=1e10 / h, blocks="continuum", **FREQ)
        assert bar == pytest.approx(math.sqrt(5e9 / 2500.0) / 40.0, rel=1e-14, abs=0)
        error = sd.jointed_column_first_frequency(n_blocks=n, kn=1e10 / h, **FREQ) / bar - 1.0
        assert abs(n * error + 0.25) < 0.2 / n
        rigid = sd.jointed_column_first_frequency(n_blocks=n, kn=1e10 / h, blocks="rigid", **FREQ)
        assert abs(n * (rigid / (math.sqrt(1e10 / 2500.0) / 40.0) - 1.0) + 0.5) < 0.2 / n
    # bonded, second order: n^2 (f / 50 - 1) -> pi^2 / 96 = 0.1028 (n = 10: +0.00103, n = 80: +1.6e-5)
    for n in (20, 40, 80):
        error = sd.jointed_column_first_frequency(n_blocks=n, kn=math.inf, **FREQ) / 50.0 - 1.0
        assert n * n * error == pytest.approx(math.pi ** 2 / 96.0, rel=0.01, abs=0)
    # (b) M -> inf: the blocks stop deforming and the chain tends to the rigid one from below, the gap in
    # proportion to kn h / M (gap x M / (kn h) = 0.125 at n = 1, 0.34 at n = 3, 0.45 at n = 10)
    for n in (1, 3, 10):
        rigid = sd.jointed_column_first_frequency(n_blocks=n, kn=1e10, blocks="rigid", **FREQ)
        gaps = [1.0 - sd.jointed_column_first_frequency(n_blocks=n, kn=1e10, **dict(FREQ, modulus=m)) / rigid
                for m in (1e13, 1e14)]
        assert 0.0 < gaps[0] < 1.5e-3
        assert gaps[0] / gaps[1] == pytest.approx(10.0, rel=0.02, abs=0)
    # (c) kn -> inf and n -> inf: the bar of modulus M, 50 Hz. At n = 100 and kn h = 1e5 M the joints take
    # about -0.5e-5 of it and the elements add pi^2 / 96e4 = +1.03e-5.
    f = sd.jointed_column_first_frequency(n_blocks=100, kn=1e5 * 1e10 / 0.1, **FREQ)
    assert f == pytest.approx(50.0, rel=2e-5, abs=0)
    assert f != pytest.approx(50.0, rel=1e-6, abs=0)


@REQ
def test_frequency_rejects_nonsense():
    with pytest.raises(ValueError):
        sd.jointed_column_first_frequency(n_blocks=5, kn=math.inf, blocks="rigid", **FREQ)
    with pytest.raises(ValueError):
        sd.jointed_column_first_frequency(n_blocks=5, kn=1e10, blocks="elastic", **FREQ)
    with pytest.raises(ValueError):
        sd.jointed_column_first_frequency(n_blocks=5, kn=-1e10, **FREQ)
    with pytest.raises(ValueError):
        sd.jointed_column_first_frequency(n_blocks=0, kn=1e10, **FREQ)
    with pytest.raises(ValueError):
        sd.jointed_column_first_frequency(n_blocks=5, kn=1e10, **dict(FREQ, modulus=math.inf))


# ---------------------------------------------------------------- a long block in bending

BEAM = dict(length=5.0, depth=1.0, E=1e10, nu=0.25, load=1e5)


@REQ
def test_bending_known_values():
    # Cantilever, L = 5, d = 1, P = 1e5 N/m: E' = 1.0667e10, I = 1/12, E'I = 8.8889e8:
    # P L^3 / 3 E'I = 1.25e7 / 2.6667e9 = 4.6875e-3; shear P L / (5/6 G d) = 5e5 / 3.3333e9 = 1.5e-4;
    # total 4.8375e-3 m.
    assert sd.long_block_bending_deflection(**BEAM) == pytest.approx(4.8375e-3, rel=1e-13, abs=0)
    # Simply supported, P at mid-span: 1.25e7 / (48 x 8.8889e8) = 2.9297e-4, 5e5 / (4 x 3.3333e9) = 3.75e-5;
    # total 3.3047e-4 m.
    assert sd.long_block_bending_deflection(support="simply-supported", **BEAM) == \
        pytest.approx(2.9296875e-4 + 3.75e-5, rel=1e-13, abs=0)
    # One simply-deformable block: P L / (G d) = 5e5 / 4e9 = 1.25e-4 m, 2.6 % of the beam's.
    assert sd.simply_deformable_cantilever_tip_deflection(**BEAM) == pytest.approx(1.25e-4, rel=1e-14, abs=0)


@REQ
@pytest.mark.parametrize("nu", [0.0, 0.2, 0.4])
@pytest.mark.parametrize("shape", [(5.0, 1.0), (2.0, 1.0), (10.0, 0.5)])
def test_bending_by_the_unit_load_method(nu, shape):
    # delta = integral M m / (E' I) + V v / (k G A) dx, m and v of a unit load where P acts, by quadrature.
    L, d = shape
    P, E = 1e5, 1e10
    ei, kga = E / (1 - nu * nu) * d ** 3 / 12.0, 5.0 / 6.0 * E / (2 * (1 + nu)) * d
    cantilever = integrate.quad(lambda x: P * (L - x) * (L - x) / ei + P / kga, 0.0, L, epsabs=0, epsrel=1e-13)[0]
    half = integrate.quad(lambda x: (P * x / 2) * (x / 2) / ei + (P / 2) * 0.5 / kga, 0.0, L / 2, epsabs=0,
                          epsrel=1e-13)[0]
    common = dict(length=L, depth=d, E=E, nu=nu, load=P)
    assert sd.long_block_bending_deflection(**common) == pytest.approx(cantilever, rel=1e-12, abs=0)
    assert sd.long_block_bending_deflection(support="simply-supported", **common) == \
        pytest.approx(2 * half, rel=1e-12, abs=0)


@REQ
@pytest.mark.parametrize("nu", [0.0, 0.25, 0.45])
@pytest.mark.parametrize("shape", [(5.0, 1.0), (1.0, 2.0)])
def test_one_simply_deformable_block_held_on_its_end_face(nu, shape):
    # The block built here: held at both corners of its end x = 0 (four exact constraints), a uniform
    # shear traction P / d on its end x = L (Gauss forces); the centroid at (L / 2, 0).
    L, d = shape
    P, E = 1e5, 1e10
    k, dmat = block_stiffness(L * d, E, nu)
    centre = np.array([L / 2, 0.0])
    forces = edge_forces((L, -d / 2), (L, d / 2), (0.0, P / d))
    load = sum(modes(x - centre).T @ f for x, f in forces)
    corners = [np.array([0.0, -d / 2]), np.array([0.0, d / 2])]
    rows = [modes(c - centre)[i] for c in corners for i in (0, 1)]
    q, reactions = solve_held(k, load, rows)
    tip = sd.simply_deformable_cantilever_tip_deflection(length=L, depth=d, E=E, nu=nu, load=P)
    for y in (-d / 2, 0.0, d / 2):   # the loaded face moves as a whole
        ux, uy = modes(np.array([L, y]) - centre) @ q
        assert uy == pytest.approx(tip, rel=1e-12, abs=0)
        assert abs(ux) < 1e-12 * tip
    # the mean stress of the boundary forces (load and reactions) is pure shear P / d, which the
    # uniform strain carries: tension positive, sym sum F (x) r / A
    all_forces = forces + [(c, reactions[2 * i:2 * i + 2]) for i, c in enumerate(corners)]
    mean = sum(np.outer(f, x - centre) for x, f in all_forces) / (L * d)
    assert np.allclose(0.5 * (mean + mean.T), [[0.0, P / d], [P / d, 0.0]], rtol=0, atol=1e-9 * P / d)
    assert dmat @ np.array([q[3], q[4], 2 * q[5]]) == pytest.approx([0.0, 0.0, P / d], rel=1e-12, abs=1e-9 * P / d)
    # 5/6 of the Timoshenko beam's shear part, and none of its bending
    beam = sd.long_block_bending_deflection(length=L, depth=d, E=E, nu=nu, load=P)
    bending = 4 * P * L ** 3 / (E / (1 - nu * nu) * d ** 3)
    assert tip == pytest.approx(5.0 / 6.0 * (beam - bending), rel=1e-12, abs=0)


@REQ
def test_bending_rejects_nonsense():
    with pytest.raises(ValueError):
        sd.long_block_bending_deflection(support="fixed-fixed", **BEAM)
    with pytest.raises(ValueError):
        sd.long_block_bending_deflection(**dict(BEAM, depth=0.0))
    with pytest.raises(ValueError):
        sd.long_block_bending_deflection(**dict(BEAM, nu=-1.0))
    with pytest.raises(ValueError):
        sd.simply_deformable_cantilever_tip_deflection(**dict(BEAM, length=-5.0))
    with pytest.raises(ValueError):
        sd.simply_deformable_cantilever_tip_deflection(**dict(BEAM, load=math.inf))


@REQ
def test_column_energy_known_values_and_the_sum_of_its_blocks():
    # H = 10, w = 1, rho g = 25 kPa/m, M = 1e10: the continuum holds 25e3^2 * 1000 / 6e10 = 10.41667 J/m;
    # 5 blocks hold 1 - 1/100 of it, 10.3125 J/m; with joints of kn = 1e10 each holds F^2 / (2 kn),
    # summed in the loop below.
    U = sd.continuum_column_self_weight_strain_energy(height=10.0, width=1.0, rho=2500.0, g=10.0, modulus=1e10)
    assert U == pytest.approx(10.416666666666666, rel=1e-12, abs=0)
    blocks = sd.column_self_weight_strain_energy(height=10.0, width=1.0, n_blocks=5, rho=2500.0, g=10.0, modulus=1e10)
    assert blocks == pytest.approx(10.3125, rel=1e-12, abs=0)
    # The same from each block's mean stress, summed by hand in a loop, and the joints' springs.
    h, total = 2.0, 0.0
    for above in range(5):
        stress = 25e3 * h * (above + 0.5)
        total += h * stress ** 2 / 2e10 + (25e3 * h * (above + 1)) ** 2 / (2 * 1e10)
    jointed = sd.column_self_weight_strain_energy(height=10.0, width=1.0, n_blocks=5, rho=2500.0, g=10.0,
                                                  modulus=1e10, kn=1e10)
    assert jointed == pytest.approx(total, rel=1e-12, abs=0)
    # The blocks' shortfall is 1 / (4 n^2) of the continuum's at every n.
    for n in (1, 2, 7, 40):
        ratio = sd.column_self_weight_strain_energy(height=3.0, width=2.0, n_blocks=n, rho=2700.0, g=9.81,
                                                    modulus=5e9) / sd.continuum_column_self_weight_strain_energy(
            height=3.0, width=2.0, rho=2700.0, g=9.81, modulus=5e9)
        assert ratio == pytest.approx(1.0 - 1.0 / (4 * n * n), rel=1e-12, abs=0)


@REQ
def test_settled_height_is_the_height_less_the_displacement():
    # The top of a 10 m column (rho g = 25 kPa/m, M = 1e10, 5 blocks) settles rho g H^2 / (2M) = 1.25e-4 m.
    y = sd.column_self_weight_settled_height(y=10.0, height=10.0, n_blocks=5, rho=2500.0, g=10.0, modulus=1e10)
    assert y == pytest.approx(10.0 - 1.25e-4, rel=1e-14, abs=0)


@REQ
def test_the_first_period_is_the_inverse_of_the_first_frequency():
    # The homogenised bar with kn h = M (H = 10, h = 2, M = 1e10, kn = 5e9): M_eff = M / 2 = 5e9,
    # c = sqrt(5e9 / 2500) = 1414.21 m/s, f = c / (4 H) = 35.355 Hz, T = 0.028284 s.
    T = sd.jointed_column_first_period(height=10.0, n_blocks=5, rho=2500.0, modulus=1e10, kn=5e9, blocks="continuum")
    assert T == pytest.approx(4.0 * 10.0 / math.sqrt(5e9 / 2500.0), rel=1e-12, abs=0)

"""Closed-form plane-strain elasticity references (verification/analytic/elastic.py) at known values.

Known values are worked by hand in the comments; equilibrium, compatibility and Hooke's-law checks use
independent routes (central finite differences of the returned fields, the 3D compliance written out
here, numerical time integration), never the function under test rewritten.
"""
import math

import numpy as np
import pytest
from scipy.integrate import cumulative_trapezoid, quad

from analytic import elastic as el

REQ = pytest.mark.requirements("REQ-QA-003")

# The reference rock: E = 10 GPa, nu = 0.25, so lam = G = 4 GPa, K = 20/3 GPa, M = lam + 2 G = 12 GPa,
# kappa = 3 - 4 nu = 2.
ROCK = dict(E=10e9, nu=0.25)
G_ROCK = 4e9


def plane_strain_strains(sxx, syy, sxy, *, E, nu):
    """3D isotropic compliance with e_zz = 0 imposed: s_zz = nu (s_xx + s_yy) from
    e_zz = (s_zz - nu (s_xx + s_yy)) / E = 0, then e_xx = (s_xx - nu (s_yy + s_zz)) / E, etc.,
    gamma_xy = 2 (1 + nu) s_xy / E. Returns (e_xx, e_yy, gamma_xy)."""
    szz = nu * (sxx + syy)
    return (sxx - nu * (syy + szz)) / E, (syy - nu * (sxx + szz)) / E, 2.0 * (1.0 + nu) * sxy / E


# ---------------------------------------------------------------- elastic constants


@REQ
def test_elastic_constants_known_values():
    # E = 10 GPa, nu = 0.25: lam = 10e9 * 0.25 / (1.25 * 0.5) = 4e9, G = 10e9 / 2.5 = 4e9,
    # K = 10e9 / (3 * 0.5) = 6.6667e9, M = K + 4 G / 3 = 6.6667e9 + 5.3333e9 = 12e9 = lam + 2 G
    lam, G = el.lame_from_young(**ROCK)
    assert (lam, G) == (pytest.approx(4e9, rel=1e-14, abs=0), pytest.approx(4e9, rel=1e-14, abs=0))
    K, G = el.bulk_shear_from_young(**ROCK)
    assert (K, G) == (pytest.approx(20e9 / 3.0, rel=1e-14, abs=0), pytest.approx(4e9, rel=1e-14, abs=0))
    assert el.constrained_modulus(**ROCK) == pytest.approx(12e9, rel=1e-14, abs=0)
    # E' = 10e9 / (1 - 0.0625) = 1.0666667e10, nu' = 0.25 / 0.75 = 1/3
    e_prime, nu_prime = el.plane_strain_moduli(**ROCK)
    assert e_prime == pytest.approx(1.0666666667e10, rel=1e-10, abs=0) and nu_prime == pytest.approx(1.0 / 3.0, rel=1e-14, abs=0)
    # E = 70 GPa, nu = 0.3: lam = 21e9 / (1.3 * 0.4) = 40.384615e9, G = 70e9 / 2.6 = 26.923077e9,
    # K = 70e9 / 1.2 = 58.333333e9
    lam, G = el.lame_from_young(E=70e9, nu=0.3)
    np.testing.assert_allclose([lam, G], [40.384615385e9, 26.923076923e9], rtol=1e-10)
    K, _ = el.bulk_shear_from_young(E=70e9, nu=0.3)
    assert K == pytest.approx(58.333333333e9, rel=1e-10, abs=0)
    # back: E = 9 K G / (3 K + G) = 9 * 6.6667 * 4 / (20 + 4) e9 = 10e9, nu = (20 - 8) / (2 * 24) = 0.25
    E, nu = el.young_poisson_from_bulk_shear(K=20e9 / 3.0, G=4e9)
    assert (E, nu) == (pytest.approx(10e9, rel=1e-14, abs=0), pytest.approx(0.25, rel=1e-14, abs=0))


@REQ
def test_elastic_constants_round_trip_vectorised():
    E = np.array([1e6, 10e9, 70e9, 200e9])
    nu = np.array([-0.5, 0.0, 0.3, 0.49])
    K, G = el.bulk_shear_from_young(E=E, nu=nu)
    E2, nu2 = el.young_poisson_from_bulk_shear(K=K, G=G)
    np.testing.assert_allclose(E2, E, rtol=1e-13)
    np.testing.assert_allclose(nu2, nu, rtol=1e-12, atol=1e-15)
    lam, G2 = el.lame_from_young(E=E, nu=nu)
    np.testing.assert_allclose(G2, G, rtol=1e-15)
    # K = lam + 2 G / 3 and M = lam + 2 G = K + 4 G / 3
    np.testing.assert_allclose(lam + 2.0 * G / 3.0, K, rtol=1e-12)
    np.testing.assert_allclose(el.constrained_modulus(E=E, nu=nu), K + 4.0 * G / 3.0, rtol=1e-12)


@REQ
def test_elastic_constants_reject_bad_input():
    for E, nu in ((10e9, 0.5), (10e9, -1.0), (0.0, 0.25), (-1.0, 0.25), (10e9, np.array([0.2, 0.6]))):
        with pytest.raises(ValueError):
            el.lame_from_young(E=E, nu=nu)
    with pytest.raises(ValueError):
        el.young_poisson_from_bulk_shear(K=1e9, G=0.0)


# ---------------------------------------------------------------- homogeneous samples


@REQ
def test_plane_strain_uniaxial_known_values():
    # sigma_yy = -1 MPa (compression), E = 10 GPa, nu = 0.25:
    # e_yy = (1 - 0.0625) * -1e6 / 1e10 = -9.375e-5, e_xx = -0.25 * 1.25 * -1e6 / 1e10 = +3.125e-5,
    # sigma_zz = 0.25 * -1e6 = -2.5e5
    exx, eyy, szz = el.plane_strain_uniaxial(sigma_yy=-1e6, **ROCK)
    np.testing.assert_allclose([exx, eyy, szz], [3.125e-5, -9.375e-5, -2.5e5], rtol=1e-13)
    # biaxial s_xx = -2 MPa, s_yy = -1 MPa: s_zz = -0.75 MPa,
    # e_xx = (1.25 / 1e10)(0.75 * -2e6 - 0.25 * -1e6) = 1.25e-10 * -1.25e6 = -1.5625e-4,
    # e_yy = (1.25 / 1e10)(0.75 * -1e6 - 0.25 * -2e6) = 1.25e-10 * -0.25e6 = -3.125e-5
    exx, eyy, szz = el.plane_strain_biaxial(sigma_xx=-2e6, sigma_yy=-1e6, **ROCK)
    np.testing.assert_allclose([exx, eyy, szz], [-1.5625e-4, -3.125e-5, -7.5e5], rtol=1e-13)


@REQ
def test_plane_strain_biaxial_agrees_with_the_3d_compliance():
    rng = np.random.default_rng(7)
    sxx, syy = rng.uniform(-5e6, 5e6, 20), rng.uniform(-5e6, 5e6, 20)
    for E, nu in ((10e9, 0.25), (50e9, 0.0), (1e9, 0.45), (30e9, -0.3)):
        exx, eyy, szz = el.plane_strain_biaxial(sigma_xx=sxx, sigma_yy=syy, E=E, nu=nu)
        # the full 6x6 isotropic compliance restricted to normal stresses, solved for s_zz with e_zz = 0
        S = np.array([[1.0, -nu, -nu], [-nu, 1.0, -nu], [-nu, -nu, 1.0]]) / E
        szz_ref = -(S[2, 0] * sxx + S[2, 1] * syy) / S[2, 2]
        np.testing.assert_allclose(szz, szz_ref, rtol=1e-12, atol=1e-6)
        np.testing.assert_allclose(exx, S[0, 0] * sxx + S[0, 1] * syy + S[0, 2] * szz_ref, rtol=1e-10, atol=1e-20)
        np.testing.assert_allclose(eyy, S[1, 0] * sxx + S[1, 1] * syy + S[1, 2] * szz_ref, rtol=1e-10, atol=1e-20)


@REQ
def test_young_poisson_from_plane_strain_uniaxial():
    # from the known values above: E' = -1e6 / -9.375e-5 = 1.0666667e10, nu' = 3.125e-5 / 9.375e-5 = 1/3,
    # nu = (1/3) / (4/3) = 0.25, E = 1.0666667e10 * 0.9375 = 1e10
    E, nu = el.young_poisson_from_plane_strain_uniaxial(sigma_yy=-1e6, exx=3.125e-5, eyy=-9.375e-5)
    assert (E, nu) == (pytest.approx(10e9, rel=1e-13, abs=0), pytest.approx(0.25, rel=1e-13, abs=0))
    # round trip over a range of materials, in tension and compression
    E0, nu0 = np.array([1e9, 10e9, 70e9, 5e6]), np.array([0.0, 0.25, 0.3, 0.49])
    for s in (2e6, -3e6):
        exx, eyy, _ = el.plane_strain_uniaxial(E=E0, nu=nu0, sigma_yy=s)
        E, nu = el.young_poisson_from_plane_strain_uniaxial(sigma_yy=s, exx=exx, eyy=eyy)
        np.testing.assert_allclose(E, E0, rtol=1e-12)
        np.testing.assert_allclose(nu, nu0, rtol=1e-12, atol=1e-15)
    with pytest.raises(ValueError):
        el.young_poisson_from_plane_strain_uniaxial(sigma_yy=1e6, exx=0.0, eyy=0.0)
    with pytest.raises(ValueError):  # lateral expansion larger than axial: nu' = 2 -> nu = 2/3, not a solid
        el.young_poisson_from_plane_strain_uniaxial(sigma_yy=-1e6, exx=2e-4, eyy=-1e-4)


# ---------------------------------------------------------------- patch test


@REQ
def test_linear_field_and_its_stresses_known_values():
    c = dict(a0=0.01, a1=1e-4, a2=3e-4, b0=-0.02, b1=-1e-4, b2=-2e-4)
    # at (2, 3): ux = 0.01 + 2e-4 + 9e-4 = 0.0111, uy = -0.02 - 2e-4 - 6e-4 = -0.0208
    ux, uy = el.linear_displacement_field(x=np.array([0.0, 2.0]), y=np.array([0.0, 3.0]), **c)
    np.testing.assert_allclose(ux, [0.01, 0.0111], rtol=1e-14)
    np.testing.assert_allclose(uy, [-0.02, -0.0208], rtol=1e-14)
    # e_xx = 1e-4, e_yy = -2e-4, gamma = 3e-4 - 1e-4 = 2e-4; lam = G = 4e9: lam tr e = 4e9 * -1e-4 = -4e5
    # s_xx = -4e5 + 8e9 * 1e-4 = 4e5, s_yy = -4e5 + 8e9 * -2e-4 = -2e6, s_xy = 4e9 * 2e-4 = 8e5,
    # s_zz = -4e5 = 0.25 * (4e5 - 2e6)
    s = el.stress_from_linear_field(a1=1e-4, a2=3e-4, b1=-1e-4, b2=-2e-4, **ROCK)
    np.testing.assert_allclose(s, [4e5, -2e6, 8e5, -4e5], rtol=1e-12)
    # a rigid rotation (a2 = -b1) and a translation carry no stress
    np.testing.assert_allclose(el.stress_from_linear_field(a1=0.0, a2=1e-3, b1=-1e-3, b2=0.0, **ROCK), 0.0, atol=0.0)


@REQ
def test_linear_field_stresses_satisfy_hookes_law():
    rng = np.random.default_rng(3)
    a1, a2, b1, b2 = rng.uniform(-1e-3, 1e-3, (4, 50))
    for E, nu in ((10e9, 0.25), (1e9, 0.45), (60e9, 0.1)):
        sxx, syy, sxy, szz = el.stress_from_linear_field(a1=a1, a2=a2, b1=b1, b2=b2, E=E, nu=nu)
        exx, eyy, gxy = plane_strain_strains(sxx, syy, sxy, E=E, nu=nu)
        # strains of the field by finite differences of the displacement itself (exact for a linear field)
        h = 0.5
        ux0, uy0 = el.linear_displacement_field(x=1.0, y=2.0, a0=0.3, a1=a1, a2=a2, b0=-0.1, b1=b1, b2=b2)
        uxx, uyx = el.linear_displacement_field(x=1.0 + h, y=2.0, a0=0.3, a1=a1, a2=a2, b0=-0.1, b1=b1, b2=b2)
        uxy, uyy = el.linear_displacement_field(x=1.0, y=2.0 + h, a0=0.3, a1=a1, a2=a2, b0=-0.1, b1=b1, b2=b2)
        scale = 1e-3
        np.testing.assert_allclose(exx, (uxx - ux0) / h, rtol=0, atol=1e-11 * scale)
        np.testing.assert_allclose(eyy, (uyy - uy0) / h, rtol=0, atol=1e-11 * scale)
        np.testing.assert_allclose(gxy, (uxy - ux0) / h + (uyx - uy0) / h, rtol=0, atol=1e-11 * scale)
        # and e_zz = (s_zz - nu (s_xx + s_yy)) / E = 0
        np.testing.assert_allclose((szz - nu * (sxx + syy)) / E, 0.0, atol=1e-15 * scale)


# ---------------------------------------------------------------- Lame cylinder

LAME = dict(a=1.0, b=2.0, p_i=10e6, p_o=0.0, **ROCK)


@REQ
def test_lame_known_values():
    # a = 1, b = 2, p_i = 10 MPa: A = 10e6 * 1 / 3 = 3.3333e6, B = 10e6 * 4 / 3 = 13.3333e6 Pa m^2.
    # wall: srr = -10e6, stt = A + B = 50e6/3 = 16.6667e6 (= p_i (b^2 + a^2)/(b^2 - a^2) = 5/3 p_i);
    # outside: srr = A - B/4 = 0, stt = A + B/4 = 20e6/3; szz = 2 nu A = 0.5 * 3.3333e6 = 1.6667e6.
    # u_r = (1.25 / 1e10)(0.5 A r + B / r): at r = 1, 1.25e-10 * (5/3 + 40/3) e6 = 1.25e-10 * 15e6 = 1.875e-3 m;
    # at r = 2, 1.25e-10 * (10/3 + 20/3) e6 = 1.25e-3 m
    srr, stt, szz, ur = el.lame_cylinder(r=np.array([1.0, 2.0]), **LAME)
    np.testing.assert_allclose(srr, [-10e6, 0.0], rtol=1e-13, atol=1e-8)
    np.testing.assert_allclose(stt, [50e6 / 3.0, 20e6 / 3.0], rtol=1e-13)
    np.testing.assert_allclose(szz, 5e6 / 3.0, rtol=1e-13)
    np.testing.assert_allclose(ur, [1.875e-3, 1.25e-3], rtol=1e-13)
    # outer pressure only: stt(a) = -2 p_o b^2 / (b^2 - a^2) = -8/3 p_o
    _, stt, _, _ = el.lame_cylinder(r=1.0, a=1.0, b=2.0, p_i=0.0, p_o=3e6, **ROCK)
    assert stt == pytest.approx(-8e6, rel=1e-13, abs=0)
    # equal pressures: uniform srr = stt = -p, u_r = (1 + nu)(1 - 2 nu)(-p) r / E = 1.25 * 0.5 * -1e6 * 1.5 / 1e10
    srr, stt, szz, ur = el.lame_cylinder(r=1.5, a=1.0, b=2.0, p_i=1e6, p_o=1e6, **ROCK)
    np.testing.assert_allclose([srr, stt, szz, ur], [-1e6, -1e6, -5e5, -9.375e-5], rtol=1e-13)


@REQ
def test_lame_equilibrium_and_boundary_conditions():
    r = np.linspace(1.0, 2.0, 41)[1:-1]
    for p_i, p_o in ((10e6, 0.0), (0.0, 5e6), (7e6, 3e6), (-2e6, 1e6)):
        p = dict(a=1.0, b=2.0, p_i=p_i, p_o=p_o, **ROCK)
        srr, stt, szz, _ = el.lame_cylinder(r=np.array([1.0, 2.0]), **p)
        np.testing.assert_allclose(srr, [-p_i, -p_o], rtol=1e-13, atol=1e-7)
        # d srr / dr + (srr - stt) / r = 0, central differences
        h = 1e-5
        srr, stt, szz, _ = el.lame_cylinder(r=r, **p)
        dsrr = (el.lame_cylinder(r=r + h, **p)[0] - el.lame_cylinder(r=r - h, **p)[0]) / (2.0 * h)
        assert np.max(np.abs(dsrr + (srr - stt) / r)) < 1e-6 * 10e6
        np.testing.assert_allclose(szz, 0.25 * (srr + stt), rtol=1e-13, atol=1e-7)


@REQ
def test_lame_displacement_strains_give_the_stresses():
    # e_rr = du/dr (finite differences), e_tt = u / r, then the 3D compliance with e_zz = 0 (no shear)
    r = np.linspace(1.0, 2.0, 21)[1:-1]
    h = 1e-6
    for nu in (0.0, 0.25, 0.45):
        p = dict(a=1.0, b=2.0, p_i=7e6, p_o=3e6, E=10e9, nu=nu)
        srr, stt, szz, ur = el.lame_cylinder(r=r, **p)
        err = (el.lame_cylinder(r=r + h, **p)[3] - el.lame_cylinder(r=r - h, **p)[3]) / (2.0 * h)
        ett = ur / r
        e_rr, e_tt, _ = plane_strain_strains(srr, stt, 0.0, E=10e9, nu=nu)
        np.testing.assert_allclose(err, e_rr, rtol=0, atol=1e-7 * 1e6 / 10e9)
        np.testing.assert_allclose(ett, e_tt, rtol=0, atol=1e-12 * 1e6 / 10e9)
        # e_zz = (szz - nu (srr + stt)) / E = 0
        np.testing.assert_allclose(szz, nu * (srr + stt), rtol=1e-13, atol=1e-7)


@REQ
def test_lame_infinite_outer_radius_is_a_pressurised_hole():
    # b -> inf, p_o = 0: A = 0, B = p_i a^2: srr = -p_i a^2 / r^2, stt = +p_i a^2 / r^2, szz = 0,
    # u_r = (1 + nu) p_i a^2 / (E r); at r = 2 a: -/+ 2.5 MPa, u_r = 1.25 * 10e6 / (1e10 * 2) = 6.25e-4 m
    srr, stt, szz, ur = el.lame_cylinder(r=np.array([1.0, 2.0]), a=1.0, b=np.inf, p_i=10e6, p_o=0.0, **ROCK)
    np.testing.assert_allclose(srr, [-10e6, -2.5e6], rtol=1e-14)
    np.testing.assert_allclose(stt, [10e6, 2.5e6], rtol=1e-14)
    np.testing.assert_allclose(szz, 0.0, atol=1e-9)
    np.testing.assert_allclose(ur, [1.25e-3, 6.25e-4], rtol=1e-14)
    # and a large finite b approaches it at the rate a^2 / b^2 = 1e-8: with q = a^2 / b^2 the finite cylinder has
    # A = p_i q / (1 - q) and B = p_i a^2 / (1 - q), so stt - stt_inf = p_i q (1 + a^2 / r^2) / (1 - q) <= 2 p_i q
    # (1 + 1e-8), i.e. 0.2 Pa at the wall
    r = np.linspace(1.0, 5.0, 9)
    finite = el.lame_cylinder(r=r, a=1.0, b=1e4, p_i=10e6, p_o=0.0, **ROCK)
    infinite = el.lame_cylinder(r=r, a=1.0, b=np.inf, p_i=10e6, p_o=0.0, **ROCK)
    np.testing.assert_allclose(finite[1] - infinite[1], 10e6 * 1e-8 * (1.0 + 1.0 / r ** 2), rtol=1e-6)
    np.testing.assert_allclose(finite[0] - infinite[0], 10e6 * 1e-8 * (1.0 - 1.0 / r ** 2), rtol=0, atol=1e-8)


@REQ
def test_lame_rejects_points_outside_the_wall():
    with pytest.raises(ValueError):
        el.lame_cylinder(r=np.array([0.5, 1.5]), **LAME)
    with pytest.raises(ValueError):
        el.lame_cylinder(r=2.5, **LAME)
    with pytest.raises(ValueError):
        el.lame_cylinder(r=1.0, a=2.0, b=1.0, p_i=1.0, p_o=0.0, **ROCK)


# ---------------------------------------------------------------- Kirsch


@REQ
def test_kirsch_hole_wall_known_values():
    S = 1e6
    th = np.radians([0.0, 45.0, 90.0, 180.0, 270.0])
    # uniaxial S_x = S: stt(a) = S - 2 S cos 2 theta: -S at 0 and 180, S at 45, 3 S at 90 and 270
    res = el.kirsch(r=1.0, theta=th, a=1.0, S_x=S, S_y=0.0)
    np.testing.assert_allclose(res["stt"], [-S, S, 3 * S, -S, 3 * S], rtol=1e-13, atol=1e-9 * S)
    np.testing.assert_allclose(res["srr"], 0.0, atol=1e-9 * S)
    np.testing.assert_allclose(res["srt"], 0.0, atol=1e-9 * S)
    # compression S_x = -S: the signs follow, -3 S at 90 deg and +S at 0
    res = el.kirsch(r=1.0, theta=np.radians([0.0, 90.0]), a=1.0, S_x=-S, S_y=0.0)
    np.testing.assert_allclose(res["stt"], [S, -3 * S], rtol=1e-13)
    # hydrostatic S_x = S_y = -p: stt(a) = -2 p everywhere (2 P with P = -p)
    res = el.kirsch(r=1.0, theta=th, a=1.0, S_x=-5e6, S_y=-5e6)
    np.testing.assert_allclose(res["stt"], -10e6, rtol=1e-13)
    # S_x = -10, S_y = -5 MPa: P = -7.5, Q = -2.5 MPa; stt(a) = 2 P - 4 Q cos 2 theta = -15 + 10 cos 2 theta:
    # -5 MPa at 0 (the hole's side facing the larger stress), -25 MPa at 90 deg
    res = el.kirsch(r=2.0, theta=np.radians([0.0, 90.0]), a=2.0, S_x=-10e6, S_y=-5e6)
    np.testing.assert_allclose(res["stt"], [-5e6, -25e6], rtol=1e-13)
    # interior point, uniaxial S, r = 2 a, theta = 90: a^2/r^2 = 1/4, a^4/r^4 = 1/16, cos 2 theta = -1:
    # stt = S/2 (1.25) + S/2 (1 + 3/16) = 0.625 S + 0.59375 S = 1.21875 S;
    # srr = S/2 (0.75) - S/2 (1 - 1 + 3/16) = 0.375 S - 0.09375 S = 0.28125 S
    res = el.kirsch(r=2.0, theta=math.pi / 2, a=1.0, S_x=S, S_y=0.0)
    assert res["stt"] == pytest.approx(1.21875 * S, rel=1e-13, abs=0)
    assert res["srr"] == pytest.approx(0.28125 * S, rel=1e-13, abs=0)


@REQ
def test_kirsch_far_field_and_cartesian_components():
    Sx, Sy = -10e6, -4e6
    th = np.linspace(0.0, 2.0 * math.pi, 25)
    res = el.kirsch(r=1e4, theta=th, a=1.0, S_x=Sx, S_y=Sy)
    # a^2 / r^2 = 1e-8: the far field to 1e-8 relative
    np.testing.assert_allclose(res["sxx"], Sx, rtol=0, atol=5e-8 * 10e6)
    np.testing.assert_allclose(res["syy"], Sy, rtol=0, atol=5e-8 * 10e6)
    np.testing.assert_allclose(res["sxy"], 0.0, atol=5e-8 * 10e6)
    # polar far field: srr = Sx cos^2 + Sy sin^2, srt = (Sy - Sx) sin cos
    np.testing.assert_allclose(res["srr"], Sx * np.cos(th) ** 2 + Sy * np.sin(th) ** 2, rtol=0, atol=5e-8 * 10e6)
    np.testing.assert_allclose(res["srt"], (Sy - Sx) * np.sin(th) * np.cos(th), rtol=0, atol=5e-8 * 10e6)
    # invariants: the trace and the determinant of the in-plane stress are the same in both frames
    res = el.kirsch(r=np.linspace(1.0, 4.0, 25), theta=th, a=1.0, S_x=Sx, S_y=Sy)
    np.testing.assert_allclose(res["sxx"] + res["syy"], res["srr"] + res["stt"], rtol=1e-13)
    np.testing.assert_allclose(res["sxx"] * res["syy"] - res["sxy"] ** 2, res["srr"] * res["stt"] - res["srt"] ** 2,
                               rtol=1e-11)
    # on the x axis (theta = 0) and the y axis the two frames coincide (sxx = srr, syy = stt on x)
    x_axis = el.kirsch(r=1.7, theta=0.0, a=1.0, S_x=Sx, S_y=Sy)
    assert x_axis["sxx"] == pytest.approx(x_axis["srr"], rel=1e-15, abs=0)
    assert x_axis["syy"] == pytest.approx(x_axis["stt"], rel=1e-15, abs=0)
    # kirsch_cartesian_stress at (0, 1.7) equals the polar call at theta = 90 deg
    sxx, syy, sxy = el.kirsch_cartesian_stress(x=0.0, y=1.7, a=1.0, S_x=Sx, S_y=Sy)
    y_axis = el.kirsch(r=1.7, theta=math.pi / 2, a=1.0, S_x=Sx, S_y=Sy)
    np.testing.assert_allclose([sxx, syy, sxy], [y_axis["stt"], y_axis["srr"], 0.0], rtol=1e-13, atol=1e-6)


@REQ
def test_kirsch_hole_is_traction_free_everywhere():
    th = np.linspace(0.0, 2.0 * math.pi, 73)
    res = el.kirsch(r=0.3, theta=th, a=0.3, S_x=-7e6, S_y=2e6)
    np.testing.assert_allclose(res["srr"], 0.0, atol=1e-8 * 7e6)
    np.testing.assert_allclose(res["srt"], 0.0, atol=1e-8 * 7e6)
    # the Cartesian traction on the wall, t = s . n with n = (cos, sin), vanishes too
    c, s = np.cos(th), np.sin(th)
    np.testing.assert_allclose(res["sxx"] * c + res["sxy"] * s, 0.0, atol=1e-8 * 7e6)
    np.testing.assert_allclose(res["sxy"] * c + res["syy"] * s, 0.0, atol=1e-8 * 7e6)


@REQ
def test_kirsch_equilibrium_by_finite_differences():
    # polar equilibrium, no body force:
    #   d srr/dr + (1/r) d srt/dtheta + (srr - stt)/r = 0,   (1/r) d stt/dtheta + d srt/dr + 2 srt / r = 0
    a, hr, ht = 1.0, 1e-5, 1e-5
    r, th = np.meshgrid(np.linspace(1.05, 5.0, 12), np.linspace(0.0, 2 * math.pi, 19))
    for Sx, Sy in ((1e6, 0.0), (-10e6, -4e6), (-3e6, -3e6), (2e6, -5e6)):
        def k(rr, tt):
            return el.kirsch(r=rr, theta=tt, a=a, S_x=Sx, S_y=Sy)
        c = k(r, th)
        dr = {key: (k(r + hr, th)[key] - k(r - hr, th)[key]) / (2 * hr) for key in ("srr", "srt")}
        dt = {key: (k(r, th + ht)[key] - k(r, th - ht)[key]) / (2 * ht) for key in ("stt", "srt")}
        radial = dr["srr"] + dt["srt"] / r + (c["srr"] - c["stt"]) / r
        hoop = dt["stt"] / r + dr["srt"] + 2.0 * c["srt"] / r
        scale = max(abs(Sx), abs(Sy)) / a
        assert np.max(np.abs(radial)) < 1e-5 * scale
        assert np.max(np.abs(hoop)) < 1e-5 * scale
    # the axisymmetric part (S_x = S_y) has no theta dependence and no shear, and d srr/dr + (srr - stt)/r = 0
    res = el.kirsch(r=r, theta=th, a=a, S_x=-3e6, S_y=-3e6)
    assert np.max(np.abs(res["srt"])) == 0.0
    assert np.max(np.abs(res["srr"] - res["srr"][0])) < 1e-9 * 3e6
    dsrr = (el.kirsch(r=r + hr, theta=th, a=a, S_x=-3e6, S_y=-3e6)["srr"]
            - el.kirsch(r=r - hr, theta=th, a=a, S_x=-3e6, S_y=-3e6)["srr"]) / (2 * hr)
    assert np.max(np.abs(dsrr + (res["srr"] - res["stt"]) / r)) < 1e-5 * 3e6 / a


@REQ
def test_kirsch_displacement_known_values():
    # S_x = S = 1 MPa, a = 1, E = 10 GPa, nu = 0.25: G = 4e9, kappa = 2, P = Q = S/2.
    # r = a, theta = 0: u_r = S a (kappa+1)/(8G) + S a (kappa+1)/(4G) = 3 S a (kappa+1)/(8G) = 9e6/3.2e10 = 2.8125e-4
    # r = a, theta = 90: u_r = S a (kappa+1)/(8G) - S a (kappa+1)/(4G) = -S a (kappa+1)/(8G) = -9.375e-5
    # r = a, theta = 45: u_t = -Q/(2G) (a + (kappa-1) a + a) = -S a (kappa+1)/(4G) = -1.875e-4
    S = 1e6
    res = el.kirsch(r=1.0, theta=np.radians([0.0, 90.0, 45.0]), a=1.0, S_x=S, S_y=0.0, **ROCK)
    np.testing.assert_allclose(res["ur"][:2], [2.8125e-4, -9.375e-5], rtol=1e-13)
    # (sin 2 theta at 90 deg is 1.2e-16 in floating point, hence the absolute tolerance)
    np.testing.assert_allclose(res["ut"], [0.0, 0.0, -1.875e-4], rtol=1e-13, atol=1e-15 * 1.875e-4)
    # hoop strain at the wall, theta = 90: (u_r + du_t/dtheta)/a with du_t/dtheta = Q (kappa+1) a / G = 3.75e-4:
    # -9.375e-5 + 3.75e-4 = 2.8125e-4 = (1 - nu) stt / (2 G) = 0.75 * 3e6 / 8e9 (plane strain, srr = 0)
    h = 1e-6
    ut = el.kirsch(r=1.0, theta=np.array([math.pi / 2 - h, math.pi / 2 + h]), a=1.0, S_x=S, S_y=0.0, **ROCK)["ut"]
    ett = res["ur"][1] + (ut[1] - ut[0]) / (2 * h)
    assert ett == pytest.approx(2.8125e-4, rel=1e-8, abs=0)
    # far from the hole u_r -> e_xx r at theta = 0, e_xx the uniform plane-strain strain of the uniaxial sample
    # loaded along x: (1 - nu^2) S / E = 0.9375 * 1e6 / 1e10 = 9.375e-5 (the hole adds O(a^2 / r^2) = 1e-8)
    far = el.kirsch(r=1e4, theta=0.0, a=1.0, S_x=S, S_y=0.0, **ROCK)
    assert far["ur"] / 1e4 == pytest.approx(9.375e-5, rel=1e-7, abs=0)
    # E and nu come together
    with pytest.raises(ValueError):
        el.kirsch(r=1.0, theta=0.0, a=1.0, S_x=S, S_y=0.0, E=10e9)


@REQ
def test_kirsch_displacement_strains_reproduce_the_stresses_in_plane_strain():
    # central differences of (u_x, u_y) in x and y, against the Kirsch stresses through the 3D compliance
    # with e_zz = 0 (written out in plane_strain_strains above, not taken from the module)
    a, h = 1.0, 1e-5
    xs, ys = np.meshgrid(np.linspace(-4.0, 4.0, 17), np.linspace(-4.0, 4.0, 17))
    keep = np.hypot(xs, ys) > 1.1 * a
    x, y = xs[keep], ys[keep]
    for (Sx, Sy), nu in (((1e6, 0.0), 0.25), ((-10e6, -4e6), 0.3), ((2e6, -5e6), 0.45), ((-3e6, -3e6), 0.0)):
        p = dict(a=a, S_x=Sx, S_y=Sy, E=10e9, nu=nu)

        def u(xx, yy):
            return el.kirsch_cartesian_displacement(x=xx, y=yy, **p)

        exx = (u(x + h, y)[0] - u(x - h, y)[0]) / (2 * h)
        eyy = (u(x, y + h)[1] - u(x, y - h)[1]) / (2 * h)
        gxy = (u(x, y + h)[0] - u(x, y - h)[0]) / (2 * h) + (u(x + h, y)[1] - u(x - h, y)[1]) / (2 * h)
        sxx, syy, sxy = el.kirsch_cartesian_stress(x=x, y=y, a=a, S_x=Sx, S_y=Sy)
        e_ref = plane_strain_strains(sxx, syy, sxy, E=10e9, nu=nu)
        scale = max(abs(Sx), abs(Sy)) / 10e9
        for got, want in zip((exx, eyy, gxy), e_ref):
            np.testing.assert_allclose(got, want, rtol=0, atol=1e-7 * scale)
        # the same in polar components: e_rr = du_r/dr, e_tt = (u_r + du_t/dtheta)/r,
        # g_rt = (1/r) du_r/dtheta + du_t/dr - u_t/r
        r, th = np.hypot(x, y), np.arctan2(y, x)

        def k(rr, tt):
            return el.kirsch(r=rr, theta=tt, **p)

        c = k(r, th)
        err = (k(r + h, th)["ur"] - k(r - h, th)["ur"]) / (2 * h)
        ett = (c["ur"] + (k(r, th + h)["ut"] - k(r, th - h)["ut"]) / (2 * h)) / r
        grt = (k(r, th + h)["ur"] - k(r, th - h)["ur"]) / (2 * h) / r \
            + (k(r + h, th)["ut"] - k(r - h, th)["ut"]) / (2 * h) - c["ut"] / r
        e_ref = plane_strain_strains(c["srr"], c["stt"], c["srt"], E=10e9, nu=nu)
        for got, want in zip((err, ett, grt), e_ref):
            np.testing.assert_allclose(got, want, rtol=0, atol=1e-7 * scale)


@REQ
def test_kirsch_displacement_check_detects_a_wrong_law():
    # negative controls for the test above, so that its agreement means something: displacements computed with
    # a different nu (0.3 or 0.2) miss plane-strain Hooke's law for nu = 0.25, and the module's displacements
    # (nu = 0.25) miss the plane-STRESS law e_xx = (s_xx - nu s_yy) / E, by far more than the 1e-7 tolerance
    a, h, x, y = 1.0, 1e-5, np.array([1.5, 0.0, 2.0]), np.array([0.0, 1.5, 2.0])
    sxx, syy, sxy = el.kirsch_cartesian_stress(x=x, y=y, a=a, S_x=1e6, S_y=0.0)
    plane_strain = plane_strain_strains(sxx, syy, sxy, E=10e9, nu=0.25)[0]
    plane_stress = (sxx - 0.25 * syy) / 10e9

    def exx(nu):
        ux = [el.kirsch_cartesian_displacement(x=x + s, y=y, a=a, S_x=1e6, S_y=0.0, E=10e9, nu=nu)[0]
              for s in (h, -h)]
        return (ux[0] - ux[1]) / (2 * h)

    assert np.max(np.abs(exx(0.25) - plane_strain)) < 1e-7 * 1e6 / 10e9
    for wrong_nu in (0.3, 0.2):
        assert np.max(np.abs(exx(wrong_nu) - plane_strain)) > 1e-3 * 1e6 / 10e9
    assert np.max(np.abs(exx(0.25) - plane_stress)) > 1e-3 * 1e6 / 10e9


@REQ
def test_kirsch_hydrostatic_is_lame_with_an_infinite_outer_radius():
    # S_x = S_y = -p is Lame's hole (p_i = 0) under an outer pressure p at b = inf:
    # srr = -p (1 - a^2/r^2), stt = -p (1 + a^2/r^2), u_r = -p ((1 - 2 nu) r + a^2 / r) / (2 G) from both
    r = np.linspace(1.0, 6.0, 11)
    k = el.kirsch(r=r, theta=0.7, a=1.0, S_x=-4e6, S_y=-4e6, **ROCK)
    srr, stt, _, ur = el.lame_cylinder(r=r, a=1.0, b=np.inf, p_i=0.0, p_o=4e6, **ROCK)
    np.testing.assert_allclose(k["srr"], srr, rtol=1e-13, atol=1e-6)
    np.testing.assert_allclose(k["stt"], stt, rtol=1e-13)
    np.testing.assert_allclose(k["ur"], ur, rtol=1e-13)
    np.testing.assert_allclose(k["ut"], 0.0, atol=0.0)
    # at r = 2: u_r = -4e6 (0.5 * 2 + 0.5) / 8e9 = -7.5e-4 m
    assert ur[2] == pytest.approx(-7.5e-4, rel=1e-13, abs=0)


@REQ
def test_kirsch_rejects_points_inside_the_hole():
    with pytest.raises(ValueError):
        el.kirsch(r=np.array([0.99, 2.0]), theta=0.0, a=1.0, S_x=1.0, S_y=0.0)
    with pytest.raises(ValueError):
        el.kirsch_cartesian_displacement(x=0.5, y=0.5, a=1.0, S_x=1.0, S_y=0.0, **ROCK)


# ---------------------------------------------------------------- waves


@REQ
def test_wave_speeds_known_values():
    # K = 20/3 GPa, G = 4 GPa, rho = 2500: M = 12 GPa, c_p = sqrt(4.8e6) = 2190.8902300 m/s,
    # c_s = sqrt(1.6e6) = 1264.9110641 m/s; free-sided plane-strain column: sqrt(1.0666667e10 / 2500) = 2065.5911180 m/s
    assert el.p_wave_speed(K=20e9 / 3.0, G=4e9, rho=2500.0) == pytest.approx(2190.8902300, rel=1e-10, abs=0)
    assert el.s_wave_speed(G=4e9, rho=2500.0) == pytest.approx(1264.9110641, rel=1e-10, abs=0)
    assert el.plane_strain_bar_wave_speed(E=10e9, nu=0.25, rho=2500.0) == pytest.approx(2065.5911180, rel=1e-10, abs=0)
    # c_p / c_s = sqrt(2 (1 - nu) / (1 - 2 nu)) = sqrt(3) at nu = 0.25; nu = 0: c_p = c_bar = sqrt(E / rho)
    K, G = el.bulk_shear_from_young(E=np.array([10e9, 10e9]), nu=np.array([0.25, 0.0]))
    cp, cs = el.p_wave_speed(K=K, G=G, rho=2500.0), el.s_wave_speed(G=G, rho=2500.0)
    assert cp[0] / cs[0] == pytest.approx(math.sqrt(3.0), rel=1e-14, abs=0)
    assert cp[1] == pytest.approx(2000.0, rel=1e-14, abs=0)
    assert el.plane_strain_bar_wave_speed(E=10e9, nu=0.0, rho=2500.0) == pytest.approx(2000.0, rel=1e-14, abs=0)


@REQ
def test_step_pulse_known_values():
    # c = 2000 m/s, t = 0.05 s: the front is at 100 m; v0 = 0.1 m/s, rho = 2500: sigma = -2500 * 2000 * 0.1 = -5e5 Pa
    x = np.array([0.0, 50.0, 100.0, 200.0])
    arrival, v = el.step_pulse_arrival(x=x, t=0.05, c=2000.0, v0=0.1)
    np.testing.assert_allclose(arrival, [0.0, 0.025, 0.05, 0.1], rtol=1e-15)
    np.testing.assert_allclose(v, [0.1, 0.1, 0.05, 0.0], rtol=1e-15)
    sigma = el.step_pulse_stress(x=x, t=0.05, c=2000.0, v0=0.1, rho=2500.0)
    np.testing.assert_allclose(sigma, [-5e5, -5e5, -2.5e5, 0.0], rtol=1e-15)
    # pulling the end puts the column in tension
    assert el.step_pulse_stress(x=10.0, t=1.0, c=2000.0, v0=-0.1, rho=2500.0) == pytest.approx(5e5, rel=1e-15, abs=0)
    # histories at a gauge: nothing before x / c
    t = np.array([0.0, 0.0499, 0.0501])
    _, v = el.step_pulse_arrival(x=100.0, t=t, c=2000.0, v0=0.1)
    np.testing.assert_allclose(v, [0.0, 0.0, 0.1])


@REQ
def test_step_pulse_stress_is_the_constrained_modulus_times_the_strain():
    # integrate v in time for the displacement, difference it in x for the strain, multiply by M = K + 4G/3:
    # a laterally confined column (uniaxial strain) at c = c_p must carry sigma = M e = -rho c v0 behind the front
    K, G, rho, v0 = 20e9 / 3.0, 4e9, 2500.0, 0.2
    c = el.p_wave_speed(K=K, G=G, rho=rho)
    t = np.linspace(0.0, 0.2, 200001)
    dx = 1.0
    strains = []
    for x in (50.0, 120.0, 300.0):
        u = [cumulative_trapezoid(el.step_pulse_arrival(x=xx, t=t, c=c, v0=v0)[1], t, initial=0.0)[-1]
             for xx in (x + dx, x - dx)]
        strains.append((u[0] - u[1]) / (2 * dx))
    # the trapezoid rule smears the step by at most v0 dt / 2 = 1e-7 m in each u (dt = 1e-6 s), so the strain is
    # off by at most 2e-7 / (2 dx) = 1e-7 of v0 / c = 9.13e-5: 1.1e-3 relative
    sigma = (K + 4.0 * G / 3.0) * np.array(strains)
    expected = el.step_pulse_stress(x=np.array([50.0, 120.0, 300.0]), t=0.2, c=c, v0=v0, rho=rho)
    # -rho c v0 = -2500 * 2190.89023 * 0.2 = -1.0954451e6 Pa
    np.testing.assert_allclose(expected, -1.0954451150e6, rtol=1e-10)
    np.testing.assert_allclose(sigma, expected, rtol=1.5e-3)


@REQ
def test_homogeneous_displacement_of_a_uniaxial_sample():
    # E = 10 GPa, nu = 0.25, syy = -1 MPa, sxx = 0: exx = -nu (1 + nu) syy / E = 0.3125e-4,
    # eyy = (1 - nu^2) syy / E = -0.9375e-4; at (1, 2) from the origin: (3.125e-5, -1.875e-4).
    ux, uy = el.plane_strain_homogeneous_displacement(x=np.array([1.0, 0.0]), y=np.array([2.0, 0.0]), sigma_xx=0.0,
                                                      sigma_yy=-1e6, **ROCK)
    assert ux == pytest.approx([3.125e-5, 0.0], rel=1e-12, abs=1e-20)
    assert uy == pytest.approx([-1.875e-4, 0.0], rel=1e-12, abs=1e-20)
    # Held elsewhere: the field shifts with the held point.
    ux, uy = el.plane_strain_homogeneous_displacement(x=1.0, y=2.0, sigma_xx=0.0, sigma_yy=-1e6, x0=1.0, y0=1.0, **ROCK)
    assert ux == pytest.approx(0.0, abs=1e-20) and uy == pytest.approx(-0.9375e-4, rel=1e-12, abs=0)
    # A block above a joint of kn = 1e10 Pa/m under 1 MPa: 0.1 mm more down, ux unchanged.
    ux, uy = el.plane_strain_homogeneous_displacement(x=1.0, y=2.0, sigma_xx=0.0, sigma_yy=-1e6, shift_y=-1e-4, **ROCK)
    assert ux == pytest.approx(3.125e-5, rel=1e-12, abs=0) and uy == pytest.approx(-2.875e-4, rel=1e-12, abs=0)


@REQ
def test_wave_arrival_times():
    # E = 10 GPa, nu = 0.25, rho = 2500: K = 6.6667 GPa, G = 4 GPa, M = K + 4G/3 = 12 GPa;
    # c_p = sqrt(12e9 / 2500) = 2190.890 m/s, c_s = sqrt(4e9 / 2500) = 1264.911 m/s;
    # over 50 m: 22.8218 ms and 39.5285 ms.
    assert el.p_wave_arrival_time(distance=50.0, E=10e9, nu=0.25, rho=2500.0) == pytest.approx(50.0 / 2190.890230, rel=1e-9, abs=0)
    assert el.s_wave_arrival_time(distance=50.0, E=10e9, nu=0.25, rho=2500.0) == pytest.approx(50.0 / 1264.911064, rel=1e-9, abs=0)


@REQ
def test_s_wave_sine_velocity():
    # c_s = 1264.911 m/s: over 25 m the delay is 19.7642 ms; a quarter period of 50 Hz (5 ms) later
    # the velocity is at its crest; before the delay it is zero.
    delay = 25.0 / 1264.911064
    v = el.s_wave_sine_velocity(np.array([0.5 * delay, delay + 0.005, delay + 0.01]), distance=25.0, E=10e9,
                                nu=0.25, rho=2500.0, amplitude=0.01, frequency=50.0)
    # c_s typed to 10 digits: the delay is off by 1e-12 s, the sine by 2 pi 50 Hz x 1e-12 s x 0.01.
    assert v == pytest.approx([0.0, 0.01, 0.0], abs=1e-11)


@REQ
def test_s_wave_sine_half_step_velocity_is_the_sine_half_a_step_earlier():
    # dt = 2 ms: at t = delay + 6 ms the half step's velocity is the one at delay + 5 ms, the crest;
    # at delay + 0.5 ms it is the one at the arrival, zero.
    delay = 25.0 / 1264.911064
    v = el.s_wave_sine_half_step_velocity(np.array([delay + 0.006, delay + 0.001, delay + 0.0005]), dt=0.002,
                                          distance=25.0, E=10e9, nu=0.25, rho=2500.0, amplitude=0.01, frequency=50.0)
    assert v == pytest.approx([0.01, 0.0, 0.0], abs=1e-11)
    with pytest.raises(ValueError, match="dt"):
        el.s_wave_sine_half_step_velocity(0.1, dt=0.0, distance=25.0, E=10e9, nu=0.25, rho=2500.0, amplitude=0.01,
                                          frequency=50.0)



@pytest.mark.requirements("REQ-QA-003")
def test_kirsch_excavation_displacement_is_kirsch_less_the_plate_before_the_hole():
    E, nu = 10e9, 0.25
    G = E / (2.0 * (1.0 + nu))
    # hydrostatic: only the a^2 / r term, P a^2 / (2 G r), radial
    ux, uy = el.kirsch_excavation_displacement(x=[2.0, 0.0], y=[0.0, 3.0], a=1.0, S_x=-5e3, S_y=-5e3, E=E, nu=nu)
    assert ux[0] == pytest.approx(-5e3 / (2.0 * G * 2.0), rel=1e-12, abs=0) and uy[0] == pytest.approx(0.0, abs=1e-20)
    assert uy[1] == pytest.approx(-5e3 / (2.0 * G * 3.0), rel=1e-12, abs=0)
    # biaxial, anywhere outside the hole: Kirsch's displacement less the homogeneous plane-strain
    # displacement of the far field, u = (eps_x x, eps_y y) (elastic.plane_strain_biaxial)
    x, y = np.array([1.0, 1.3, 0.2, -2.0, 3.0]), np.array([0.0, 0.9, 1.5, 0.7, -4.0])
    kx, ky = el.kirsch_cartesian_displacement(x=x, y=y, a=1.0, S_x=-10e3, S_y=-4e3, E=E, nu=nu)
    exx, eyy, _ = el.plane_strain_biaxial(E=E, nu=nu, sigma_xx=-10e3, sigma_yy=-4e3)
    hx, hy = el.kirsch_excavation_displacement(x=x, y=y, a=1.0, S_x=-10e3, S_y=-4e3, E=E, nu=nu)
    assert np.allclose(hx, kx - exx * x, rtol=1e-12, atol=1e-18)
    assert np.allclose(hy, ky - eyy * y, rtol=1e-12, atol=1e-18)
    with pytest.raises(ValueError, match="inside the hole"):
        el.kirsch_excavation_displacement(x=[0.5], y=[0.0], a=1.0, S_x=-1.0, S_y=0.0, E=E, nu=nu)


@pytest.mark.requirements("REQ-QA-003")
def test_half_sine_pulse_and_constrained_wave_speed():
    # E = 10 GPa, nu = 0.25: K = 6.667 GPa, G = 4 GPa, M = K + 4G/3 = 12 GPa; rho = 2500: 2190.89 m/s
    c = el.constrained_wave_speed(E=10e9, nu=0.25, rho=2500.0)
    assert c == pytest.approx(math.sqrt(12e9 / 2500.0), rel=1e-12, abs=0)
    arrival = 45.0 / c
    v = el.half_sine_pulse_velocity([arrival - 1e-6, arrival + 0.005, arrival + 0.0025, arrival + 0.0100001],
                                    distance=45.0, c=c, amplitude=-0.01, duration=0.01)
    assert v[0] == 0.0 and v[3] == 0.0
    assert v[1] == pytest.approx(-0.01, rel=1e-12, abs=0)
    assert v[2] == pytest.approx(-0.01 * math.sin(math.pi / 4.0), rel=1e-12, abs=0)


@pytest.mark.requirements("REQ-QA-003")
def test_hann_pulse_is_zero_outside_and_sine_squared_inside():
    c = 1264.9110640673518
    arrival = 50.0 / c
    v = el.hann_pulse_velocity([arrival - 1e-6, arrival + 0.02, arrival + 0.01, arrival + 0.0400001],
                               distance=50.0, c=c, amplitude=0.02, duration=0.04)
    assert v[0] == 0.0 and v[3] == 0.0
    assert v[1] == pytest.approx(0.02, rel=1e-12, abs=0)
    assert v[2] == pytest.approx(0.01, rel=1e-12, abs=0)
    # The half-step lag: recorded at t + dt/2, the value of t.
    lagged = el.hann_pulse_velocity(arrival + 0.01 + 1e-4, distance=50.0, c=c, amplitude=0.02, duration=0.04, dt=2e-4)
    assert lagged == pytest.approx(0.01, rel=1e-12, abs=0)
    with pytest.raises(ValueError):
        el.hann_pulse_velocity(0.0, distance=1.0, c=0.0, amplitude=1.0, duration=1.0)


@pytest.mark.requirements("REQ-QA-003")
def test_half_sine_pulse_energy_is_the_integral_of_the_power():
    from scipy.integrate import quad
    rho, c, width, amplitude, duration = 2500.0, 2190.0, 1.0, 0.01, 0.01
    power = lambda t: rho * c * width * (amplitude * math.sin(math.pi * t / duration)) ** 2
    assert el.half_sine_pulse_energy(rho=rho, c=c, width=width, amplitude=amplitude, duration=duration) == \
        pytest.approx(quad(power, 0.0, duration)[0], rel=1e-12, abs=0)


@pytest.mark.requirements("REQ-QA-003", "REQ-ZONE-017")
def test_joint_transmission_coefficient_solves_the_interface_conditions():
    # Known values: w Z / 2k = 1 gives 1 / sqrt(2); a stiff joint transmits all, a soft one little.
    Z, k = 5.477e6, 5.477e6 * 2 * math.pi * 100.0 / 2
    assert el.joint_transmission_coefficient(frequency=100.0, impedance=Z, stiffness=k) == pytest.approx(
        1 / math.sqrt(2), rel=1e-14, abs=0)
    assert el.joint_transmission_coefficient(frequency=100.0, impedance=Z, stiffness=1e30) == pytest.approx(
        1.0, rel=1e-14, abs=0)
    assert el.joint_transmission_coefficient(frequency=0.0, impedance=Z, stiffness=k, incident_amplitude=0.01) \
        == 0.01
    # Independently: solve the two interface conditions as a complex linear system for R and T.
    for f in (10.0, 50.0, 200.0, 1000.0):
        w = 2 * math.pi * f
        # unknowns (R, T): A - R - T = 0 (stress), T - R - i w Z T / k = A (opening rate = stress rate / k)
        system = np.array([[-1.0, -1.0], [-1.0, 1.0 - 1j * w * Z / k]])
        R, T = np.linalg.solve(system, np.array([-1.0, 1.0], dtype=complex))
        assert el.joint_transmission_coefficient(frequency=f, impedance=Z, stiffness=k) == pytest.approx(
            abs(T), rel=1e-12, abs=0)
        assert abs(R) ** 2 + abs(T) ** 2 == pytest.approx(1.0, rel=1e-12, abs=0)  # a lossless joint


@pytest.mark.requirements("REQ-QA-003", "REQ-ZONE-018")
def test_column_mode_and_its_rayleigh_decrement():
    # c_p = 2190.89 m/s for E = 10 GPa, nu = 0.25, rho = 2500; w_1 = pi c_p / 20 on H = 10 m.
    w = el.column_fundamental_angular_frequency(E=10e9, nu=0.25, rho=2500.0, height=10.0)
    assert w == pytest.approx(math.pi * 2190.8902300206646 / 20.0, rel=1e-14, abs=0)
    # The quarter-wave shape solves the wave equation with u(0) = 0 and du/dy(H) = 0: by finite
    # differences, c^2 u'' = -w^2 u along the column.
    y = np.linspace(0.0, 10.0, 2001)
    u = np.sin(math.pi * y / 20.0)
    curvature = np.gradient(np.gradient(u, y), y)
    c = 2190.8902300206646
    assert np.max(np.abs(c * c * curvature[5:-5] + w * w * u[5:-5])) < 1e-4 * w * w
    # Rayleigh: alpha = xi w and beta = xi / w give xi at w; beta alone gives beta w / 2.
    d = el.column_rayleigh_log_decrement(E=10e9, nu=0.25, rho=2500.0, height=10.0, alpha=0.05 * w, beta=0.05 / w)
    assert d == pytest.approx(2 * math.pi * 0.05 / math.sqrt(1 - 0.05 ** 2), rel=1e-14, abs=0)
    d = el.column_rayleigh_log_decrement(E=10e9, nu=0.25, rho=2500.0, height=10.0, alpha=0.0, beta=2.9e-4)
    xi = 2.9e-4 * w / 2
    assert d == pytest.approx(2 * math.pi * xi / math.sqrt(1 - xi * xi), rel=1e-14, abs=0)
    with pytest.raises(ValueError):
        el.column_rayleigh_log_decrement(E=10e9, nu=0.25, rho=2500.0, height=10.0, alpha=0.0, beta=1.0)


def crossed_cell_centre_stiffness_by_assembly(*, E, nu, side):
    """The centre gridpoint's 2 x 2 block of the crossed cell's stiffness, assembled from the four
    constant-strain triangles' A B^T D B with B built from the vertex coordinates (independent of
    the closed form's per-triangle reasoning)."""
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    G = E / (2 * (1 + nu))
    D = np.array([[lam + 2 * G, lam, 0.0], [lam, lam + 2 * G, 0.0], [0.0, 0.0, G]])
    h = side / 2.0
    corners = [(-h, -h), (h, -h), (h, h), (-h, h)]
    block = np.zeros((2, 2))
    for k in range(4):
        pts = np.array([corners[k], corners[(k + 1) % 4], (0.0, 0.0)])
        x, y = pts[:, 0], pts[:, 1]
        area = 0.5 * ((x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]))
        # Gradient of the centre's (third vertex's) shape function.
        bx, by = (y[0] - y[1]) / (2 * area), (x[1] - x[0]) / (2 * area)
        B = np.array([[bx, 0.0], [0.0, by], [by, bx]])
        block += area * B.T @ D @ B
    return block


@pytest.mark.requirements("REQ-QA-003", "REQ-ZONE-018")
def test_crossed_cell_centre_mode_and_its_damped_critical_step():
    kw = dict(E=10e9, nu=0.25, rho=2500.0, side=1.0)
    # nu = 0.25: G = 4e9, K = 6.667e9, M = 12e9; w^2 = 6 (12e9 + 4e9) / 2500 = 3.84e7.
    assert el.crossed_cell_centre_frequency(**kw) == pytest.approx(math.sqrt(3.84e7), rel=1e-14, abs=0)
    # dt_z = s / (4 c_p), c_p = sqrt(12e9 / 2500) = sqrt(4.8e6).
    assert el.crossed_grid_zone_step(**kw) == pytest.approx(1.0 / (4.0 * math.sqrt(4.8e6)), rel=1e-14, abs=0)
    # Against the assembled triangles and the lumped mass rho s^2 / 3, at two Poisson's ratios and
    # another cell size: the block is isotropic and its eigenvalue over the mass is w^2.
    for nu, side in ((0.25, 1.0), (0.0, 0.5), (0.45, 2.0)):
        block = crossed_cell_centre_stiffness_by_assembly(E=10e9, nu=nu, side=side)
        assert block[0, 1] == pytest.approx(0.0, abs=1e-6 * block[0, 0])
        assert block[0, 0] == pytest.approx(block[1, 1], rel=1e-12, abs=0)
        w2 = np.linalg.eigvalsh(block).max() / (2500.0 * side * side / 3.0)
        w = el.crossed_cell_centre_frequency(E=10e9, nu=nu, rho=2500.0, side=side)
        assert w * w == pytest.approx(w2, rel=1e-12, abs=0)
    # The damped critical step: xi = beta w / 2; beta = 1.5 / w gives xi = 0.75 and the factor 0.5.
    w = el.crossed_cell_centre_frequency(**kw)
    assert el.crossed_cell_damped_critical_step(beta=1.5 / w, **kw) == pytest.approx(1.0 / w, rel=1e-14, abs=0)
    assert el.crossed_cell_damped_critical_step(beta=0.0, fraction=0.95, **kw) == \
        pytest.approx(1.9 / w, rel=1e-14, abs=0)
    # The solver's factor from w = 2 / dt_z = 8 c_p / s: xi_z = beta 4 c_p / s.
    xi_z = 2.4e-4 * 4.0 * math.sqrt(4.8e6)
    assert el.crossed_grid_solver_step_factor(beta=2.4e-4, **kw) == \
        pytest.approx(math.sqrt(1.0 + xi_z * xi_z) - xi_z, rel=1e-14, abs=0)
    # The zone fraction puts the solver's step at the fraction asked of the critical step.
    zf = el.crossed_cell_zone_fraction_at(beta=2.4e-4, fraction=0.95, **kw)
    solver_step = zf * el.crossed_grid_zone_step(**kw) * el.crossed_grid_solver_step_factor(beta=2.4e-4, **kw)
    assert solver_step == pytest.approx(0.95 * el.crossed_cell_damped_critical_step(beta=2.4e-4, **kw),
                                        rel=1e-14, abs=0)


# ---------------------------------------------------------------- elastic half-plane: Flamant and the strip load


def central_gradient(field, x, y, h):
    """(d/dx, d/dy) of each component of field(x, y) (a tuple of arrays) by central differences."""
    fxp, fxm, fyp, fym = field(x + h, y), field(x - h, y), field(x, y + h), field(x, y - h)
    return ([(p - m) / (2.0 * h) for p, m in zip(fxp, fxm)], [(p - m) / (2.0 * h) for p, m in zip(fyp, fym)])


def equilibrium_residuals(field, x, y, h):
    """d sxx/dx + d sxy/dy and d sxy/dx + d syy/dy of a stress field (sxx, syy, sxy)(x, y)."""
    (dxx_dx, _, dxy_dx), (_, dyy_dy, dxy_dy) = central_gradient(field, x, y, h)
    return dxx_dx + dxy_dy, dxy_dx + dyy_dy


def quad_over_strip(integrand, b, singular_points, epsabs):
    """int_{-b}^{b} integrand(xi) dxi, split at the integrand's singular points inside the strip so that
    quad's Gauss-Kronrod nodes (interior only) never land on one; epsabs for the pieces that vanish."""
    from scipy.integrate import quad
    cuts = sorted({-b, b, *(p for p in singular_points if -b < p < b)})
    return sum(quad(integrand, lo, hi, epsabs=epsabs, epsrel=1e-12, limit=200)[0] for lo, hi in zip(cuts[:-1], cuts[1:]))


def surface_curvature_from_strains(field, x, *, E, nu, h):
    """d^2 v / dx^2 on the surface y = 0 from compatibility: v_x = e_xy + omega and
    d omega / dx = d e_xy / dx - d e_xx / dy (e_xy the tensor shear strain), so
    v_xx = 2 d e_xy / dx - d e_xx / dy; the strains from the stresses by the plane-strain compliance,
    d/dy one-sided into the solid (second order), d/dx central."""
    def strains(xx, yy):
        return plane_strain_strains(*field(xx, yy), E=E, nu=nu)
    exx_0, exx_1, exx_2 = strains(x, 0.0)[0], strains(x, -h)[0], strains(x, -2.0 * h)[0]
    dexx_dy = (3.0 * exx_0 - 4.0 * exx_1 + exx_2) / (2.0 * h)
    dexy_dx = (strains(x + h, 0.0)[2] - strains(x - h, 0.0)[2]) / (4.0 * h)
    return 2.0 * dexy_dx - dexx_dy


@REQ
def test_flamant_stress_known_values():
    P = 1e6
    # under the load at depth 1: sigma_rr = -2 P / pi along the vertical, so syy = -2 P / pi, sxx = sxy = 0
    sxx, syy, sxy = el.flamant_stress(x=0.0, y=-1.0, P=P)
    assert syy == pytest.approx(-2.0 * P / math.pi, rel=1e-15, abs=0)
    assert sxx == 0.0 and sxy == 0.0
    # at (1, -1): r = sqrt 2, theta = 45 deg, sigma_rr = -2 P cos45 / (pi sqrt 2) = -P / pi along
    # n = (1, -1) / sqrt 2, so sxx = syy = -P / (2 pi) and sxy = n_x n_y sigma_rr = +P / (2 pi)
    sxx, syy, sxy = el.flamant_stress(x=1.0, y=-1.0, P=P)
    np.testing.assert_allclose([sxx, syy, sxy], np.array([-1.0, -1.0, 1.0]) * P / (2.0 * math.pi), rtol=1e-15)
    # the mirror point (-1, -1): sxy changes sign, the normal stresses do not; a surface at y = 5 shifts all
    sxx, syy, sxy = el.flamant_stress(x=-1.0, y=4.0, P=P, surface_y=5.0)
    np.testing.assert_allclose([sxx, syy, sxy], np.array([-1.0, -1.0, -1.0]) * P / (2.0 * math.pi), rtol=1e-15)
    # radial: the principal direction of compression points at the load, so sxy / sxx = -d / x, syy / sxx = d^2 / x^2
    x, y = np.array([0.3, -2.0, 4.0]), np.array([-1.7, -0.4, -3.0])
    sxx, syy, sxy = el.flamant_stress(x=x, y=y, P=P)
    np.testing.assert_allclose(sxy * x, -sxx * (-y), rtol=1e-14)
    np.testing.assert_allclose(syy * x * x, sxx * y * y, rtol=1e-14)


@REQ
def test_flamant_stress_equilibrium_and_compatibility_by_finite_differences():
    P, h = 1e6, 1e-5
    x, y = np.meshgrid(np.linspace(-3.0, 3.0, 13), np.linspace(-0.5, -3.0, 6))

    def field(xx, yy):
        return el.flamant_stress(x=xx, y=yy, P=P)

    fx, fy = equilibrium_residuals(field, x, y, h)
    scale = P / 0.5 ** 2  # |grad sigma| ~ P / r^2, r >= 0.5
    assert np.max(np.abs(fx)) < 1e-5 * scale
    assert np.max(np.abs(fy)) < 1e-5 * scale

    # Beltrami-Michell without body force: sxx + syy is harmonic (five-point Laplacian)
    def trace(xx, yy):
        sxx, syy, _ = el.flamant_stress(x=xx, y=yy, P=P)
        return sxx + syy
    hl = 1e-3
    lap = (trace(x + hl, y) + trace(x - hl, y) + trace(x, y + hl) + trace(x, y - hl) - 4.0 * trace(x, y)) / hl ** 2
    assert np.max(np.abs(lap)) < 1e-4 * P / 0.5 ** 3


@REQ
def test_flamant_surface_is_traction_free_and_the_load_balances():
    P = 2.5e6
    x = np.array([-7.0, -1.0, -1e-3, 1e-3, 0.2, 30.0])
    sxx, syy, sxy = el.flamant_stress(x=x, y=1.5, P=P, surface_y=1.5)
    np.testing.assert_array_equal(syy, 0.0)
    np.testing.assert_array_equal(sxy, 0.0)
    # the vertical stress over a horizontal line at any depth carries the whole load, -P; the shear stress
    # integrates to 0 (no horizontal load) and the first moment of syy to 0 (the load acts at x = 0)
    for depth in (0.01, 1.0, 40.0):
        total = quad(lambda s: el.flamant_stress(x=s, y=-depth, P=P)[1], -np.inf, np.inf, epsabs=0, epsrel=1e-12)[0]
        assert total == pytest.approx(-P, rel=1e-10, abs=0)
        shear = quad(lambda s: el.flamant_stress(x=s, y=-depth, P=P)[2], -np.inf, np.inf, epsabs=1e-9 * P)[0]
        assert abs(shear) < 1e-8 * P


@REQ
def test_flamant_rejects_the_load_point_and_points_above_the_surface():
    with pytest.raises(ValueError, match="above"):
        el.flamant_stress(x=np.array([1.0, 1.0]), y=np.array([-1.0, 0.1]), P=1.0)
    with pytest.raises(ValueError, match="singular"):
        el.flamant_stress(x=0.0, y=2.0, P=1.0, surface_y=2.0)
    with pytest.raises(ValueError):
        el.flamant_relative_settlement(x1=0.0, x2=1.0, P=1.0, **ROCK)
    with pytest.raises(ValueError):
        el.flamant_relative_settlement(x1=1.0, x2=2.0, P=1.0, E=1e9, nu=0.5)


@REQ
def test_flamant_relative_settlement_known_values():
    # ROCK: 2 (1 - nu^2) / (pi E) = 2 * 0.9375 / (pi 1e10) = 1.875e-10 / pi per N/m; x2 = e x1: ln = 1
    P = 1e6
    assert el.flamant_relative_settlement(x1=2.0, x2=2.0 * math.e, P=P, **ROCK) == \
        pytest.approx(1.875e-4 / math.pi, rel=1e-14, abs=0)
    # symmetric about the load, antisymmetric in (x1, x2), additive along the surface
    assert el.flamant_relative_settlement(x1=-2.0, x2=2.0, P=P, **ROCK) == 0.0
    a = el.flamant_relative_settlement(x1=0.5, x2=-3.0, P=P, **ROCK)
    b = el.flamant_relative_settlement(x1=-3.0, x2=11.0, P=P, **ROCK)
    assert el.flamant_relative_settlement(x1=-3.0, x2=0.5, P=P, **ROCK) == pytest.approx(-a, rel=1e-15, abs=0)
    assert el.flamant_relative_settlement(x1=0.5, x2=11.0, P=P, **ROCK) == pytest.approx(a + b, rel=1e-14, abs=0)
    # nu = 0: 2 P / (pi E) ln 10 over a decade, vectorised
    out = el.flamant_relative_settlement(x1=np.array([1.0, 0.1]), x2=np.array([10.0, -1.0]), P=P, E=10e9, nu=0.0)
    np.testing.assert_allclose(out, 2e-4 / math.pi * math.log(10.0), rtol=1e-14)


@REQ
def test_surface_settlements_satisfy_compatibility_with_the_stresses():
    # d^2 v / dx^2 of the relative settlement (central differences in x2) against the curvature that the
    # stresses' strains impose along the surface (surface_curvature_from_strains), for Flamant and the strip
    E, nu, P, q, b = 10e9, 0.3, 1e6, 2e6, 1.5
    hv, hs = 1e-4, 1e-6
    x = np.array([-6.0, -2.2, -0.9, -0.2, 0.4, 1.1, 1.8, 5.0])
    flamant_v = el.flamant_relative_settlement
    v_xx = (flamant_v(x1=1.0, x2=x + hv, P=P, E=E, nu=nu) - 2.0 * flamant_v(x1=1.0, x2=x, P=P, E=E, nu=nu)
            + flamant_v(x1=1.0, x2=x - hv, P=P, E=E, nu=nu)) / hv ** 2
    expected = surface_curvature_from_strains(lambda xx, yy: el.flamant_stress(x=xx, y=yy, P=P), x, E=E, nu=nu, h=hs)
    np.testing.assert_allclose(v_xx, expected, rtol=1e-5)
    strip_v = el.strip_load_relative_settlement
    v_xx = (strip_v(x1=0.0, x2=x + hv, q=q, b=b, E=E, nu=nu) - 2.0 * strip_v(x1=0.0, x2=x, q=q, b=b, E=E, nu=nu)
            + strip_v(x1=0.0, x2=x - hv, q=q, b=b, E=E, nu=nu)) / hv ** 2
    expected = surface_curvature_from_strains(lambda xx, yy: el.strip_load_stress(x=xx, y=yy, q=q, b=b),
                                              x, E=E, nu=nu, h=hs)
    np.testing.assert_allclose(v_xx, expected, rtol=1e-5)


@REQ
def test_strip_load_stress_known_values_and_surface_tractions():
    q, b = 3e6, 2.0
    # under the centre at depth b: theta_1 = -45, theta_2 = 45 deg, alpha = pi / 2, sin alpha = 1, cos 0 = 1:
    # syy = -q (1/2 + 1/pi) = -0.8183 q, sxx = -q (1/2 - 1/pi) = -0.1817 q (the classic strip-footing values)
    sxx, syy, sxy = el.strip_load_stress(x=0.0, y=-b, q=q, b=b)
    assert syy == pytest.approx(-q * (0.5 + 1.0 / math.pi), rel=1e-14, abs=0)
    assert sxx == pytest.approx(-q * (0.5 - 1.0 / math.pi), rel=1e-14, abs=0)
    assert sxy == pytest.approx(0.0, abs=1e-15 * q)
    # below the edge x = b at depth 2 b: theta_1 = 0, theta_2 = atan(1) = 45 deg = alpha:
    # sxy = (q / pi) sin45 sin45 = q / (2 pi), syy = -(q / pi)(pi/4 + 1/2), sxx = -(q / pi)(pi/4 - 1/2)
    sxx, syy, sxy = el.strip_load_stress(x=b, y=10.0 - 2.0 * b, q=q, b=b, surface_y=10.0)
    np.testing.assert_allclose([sxx, syy, sxy], q / math.pi * np.array([-(math.pi / 4 - 0.5), -(math.pi / 4 + 0.5), 0.5]),
                               rtol=1e-14)
    # surface: -q normal and no shear under the strip, free outside, the mean -q/2 at the edges
    x = np.array([-5.0, -b, -1.0, 0.0, 1.9, b, 2.1])
    sxx, syy, sxy = el.strip_load_stress(x=x, y=0.0, q=q, b=b)
    np.testing.assert_allclose(syy, [0.0, -q / 2, -q, -q, -q, -q / 2, 0.0], rtol=1e-15, atol=1e-9)
    np.testing.assert_allclose(sxx, [0.0, -q / 2, -q, -q, -q, -q / 2, 0.0], rtol=1e-15, atol=1e-9)
    np.testing.assert_allclose(sxy[[0, 2, 3, 4, 6]], 0.0, atol=1e-9)
    with pytest.raises(ValueError):
        el.strip_load_stress(x=0.0, y=-1.0, q=q, b=0.0)
    with pytest.raises(ValueError):
        el.strip_load_stress(x=0.0, y=0.5, q=q, b=b)


@REQ
def test_strip_load_stress_is_flamant_integrated_over_the_strip():
    q, b = 3e6, 1.25
    for x, y in ((0.0, -0.5), (0.7, -0.1), (-2.0, -1.0), (1.25, -0.3), (4.0, -6.0), (-0.3, -20.0)):
        closed = el.strip_load_stress(x=x, y=y, q=q, b=b)
        for k in range(3):
            numeric = quad_over_strip(lambda xi: el.flamant_stress(x=x - xi, y=y, P=q)[k], b, [x],
                                      epsabs=1e-13 * q)
            assert closed[k] == pytest.approx(numeric, rel=1e-10, abs=1e-10 * q)
    # and it is in equilibrium by itself (finite differences, away from the edges)
    xs, ys = np.meshgrid(np.linspace(-4.0, 4.0, 9), np.linspace(-0.3, -3.0, 5))
    fx, fy = equilibrium_residuals(lambda xx, yy: el.strip_load_stress(x=xx, y=yy, q=q, b=b), xs, ys, 1e-5)
    assert np.max(np.abs(fx)) < 1e-5 * q / 0.3
    assert np.max(np.abs(fy)) < 1e-5 * q / 0.3


@REQ
def test_strip_relative_settlement_is_flamant_integrated_over_the_strip():
    q, b = 2e6, 1.5
    # ROCK: v(b) - v(0) = 2 C q b ln 2, C = 1.875e-10 / pi: the edge stands above the centre
    assert el.strip_load_relative_settlement(x1=0.0, x2=b, q=q, b=b, **ROCK) == \
        pytest.approx(2.0 * 1.875e-10 / math.pi * q * b * math.log(2.0), rel=1e-14, abs=0)
    # against quad over the strip of Flamant's relative settlement, load at xi: the kernel is
    # flamant_relative_settlement(x1 - xi, x2 - xi) per unit load
    pairs = ((0.0, 0.4), (0.3, b), (-b, 2.0), (-0.7, 3.5), (5.0, -9.0), (-1.0, 1.0))
    for x1, x2 in pairs:
        numeric = quad_over_strip(lambda xi: el.flamant_relative_settlement(x1=x1 - xi, x2=x2 - xi, P=q, **ROCK),
                                  b, [x1, x2], epsabs=1e-17)
        closed = el.strip_load_relative_settlement(x1=x1, x2=x2, q=q, b=b, **ROCK)
        assert closed == pytest.approx(numeric, rel=1e-10, abs=1e-12 * 1.875e-10 * q * b)
    with pytest.raises(ValueError):
        el.strip_load_relative_settlement(x1=0.0, x2=1.0, q=q, b=-1.0, **ROCK)


@REQ
def test_strip_settlement_tends_to_flamant_far_from_the_strip():
    # (x + b) ln(x + b) - (x - b) ln(x - b) = 2 b (ln x + 1) - b^3 / (3 x^2) + O(b^5 / x^4) (Taylor: the
    # odd terms of g(x + b) - g(x - b), g = t ln t, g' = ln t + 1, g''' = -1 / t^2): between x1 and x2 the strip's
    # settlement differs from Flamant's with P = 2 q b by -C q b^3 / 3 (1 / x2^2 - 1 / x1^2)
    q, b = 2e6, 0.5
    C = 2.0 * (1.0 - 0.25 ** 2) / (math.pi * 10e9)
    for x1, x2 in ((50.0, 400.0), (-80.0, 30.0), (1e3, -1e4)):
        strip = el.strip_load_relative_settlement(x1=x1, x2=x2, q=q, b=b, **ROCK)
        point = el.flamant_relative_settlement(x1=x1, x2=x2, P=2.0 * q * b, **ROCK)
        correction = -C * q * b ** 3 / 3.0 * (1.0 / x2 ** 2 - 1.0 / x1 ** 2)
        assert strip - point == pytest.approx(correction, rel=1e-3, abs=0)
    # the far field's stresses too: at distances >> b the strip acts as the line load 2 q b to O(b^2 / r^2)
    x, y = np.array([0.0, 30.0, -60.0]), np.array([-100.0, -80.0, -40.0])
    strip = el.strip_load_stress(x=x, y=y, q=q, b=b)
    point = el.flamant_stress(x=x, y=y, P=2.0 * q * b)
    for s, p in zip(strip, point):
        np.testing.assert_allclose(s, p, rtol=0, atol=1e-3 * np.max(np.abs(point)))


@pytest.mark.requirements("REQ-QA-003", "REQ-BEM-009")
def test_rigid_disc_rotation_at_known_values():
    # G = 4 GPa: omega = 1e6 / (4 pi 4e9) for a = 1 m, a quarter of that at a = 2 m, any nu.
    assert el.rigid_disc_rotation(M=1e6, E=10e9, nu=0.25, a=1.0) == pytest.approx(1.9894367886486918e-05, rel=1e-14, abs=0)
    assert el.rigid_disc_rotation(M=1e6, E=10e9, nu=0.25, a=2.0) == pytest.approx(1.9894367886486918e-05 / 4, rel=1e-14, abs=0)
    assert el.rigid_disc_rotation(M=-2e6, E=8e9, nu=0.0, a=1.0) == pytest.approx(-2e6 / (4 * math.pi * 4e9), rel=1e-14, abs=0)
    with pytest.raises(ValueError):
        el.rigid_disc_rotation(M=1.0, E=1e9, nu=0.25, a=0.0)


@pytest.mark.requirements("REQ-QA-003", "REQ-BEM-009")
def test_rigid_disc_rotation_from_the_shear_stress_of_its_field():
    # Independently: integrate the moment of tau_rt = G (du_t/dr - u_t/r) of u_t = omega a^2 / r,
    # differentiated numerically, round the disc's edge.
    E, nu, a, omega = 10e9, 0.3, 1.5, 1e-5
    G = E / (2 * (1 + nu))
    h = 1e-6
    ut = lambda r: omega * a * a / r
    tau = G * ((ut(a + h) - ut(a - h)) / (2 * h) - ut(a) / a)
    moment = -tau * 2 * math.pi * a * a   # the plane's stress on the disc resists its turning
    assert el.rigid_disc_rotation(M=moment, E=E, nu=nu, a=a) == pytest.approx(omega, rel=1e-8, abs=0)


@pytest.mark.requirements("REQ-QA-003", "REQ-BEM-009")
def test_ring_hoop_force_balances_half_the_ring():
    # The lumped pressure on the half polygon between two opposite vertices, summed edge by edge.
    p, b, n = 3e5, 2.0, 16
    pts = [(b * math.cos(2 * math.pi * k / n), b * math.sin(2 * math.pi * k / n)) for k in range(n // 2 + 1)]
    # The pressure on an edge pushes against its outward normal (dy, -dx): (-p dy, p dx) on the upper half.
    fx = sum(-p * (y1 - y0) for (x0, y0), (x1, y1) in zip(pts, pts[1:]))
    fy = sum(p * (x1 - x0) for (x0, y0), (x1, y1) in zip(pts, pts[1:]))
    assert abs(fx) < 1e-9 * p * b
    assert -fy / 2 == pytest.approx(el.ring_hoop_force(p=p, b=b), rel=1e-12)

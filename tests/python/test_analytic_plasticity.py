"""Mohr-Coulomb closed forms (verification/analytic/plasticity.py) at known values."""
import math

import numpy as np
import pytest

from analytic import plasticity as pl

REQ = pytest.mark.requirements("REQ-QA-003")


@REQ
def test_n_phi_known_values():
    # phi = 30 deg: (1 + 0.5) / (1 - 0.5) = 3; phi = 45 deg: (1 + 0.7071) / (1 - 0.7071) = 5.8284.
    assert pl.n_phi(friction_deg=30.0) == pytest.approx(3.0, rel=1e-14, abs=0)
    assert pl.n_phi(friction_deg=45.0) == pytest.approx(3.0 + 2.0 * math.sqrt(2.0), rel=1e-14, abs=0)
    with pytest.raises(ValueError):
        pl.n_phi(friction_deg=0.0)


@REQ
def test_biaxial_peak_stress_known_values():
    # c = 1 MPa, phi = 30 deg: unconfined strength 2 c sqrt(3) = 3.4641 MPa; under 1 MPa of
    # confinement 1 x 3 + 3.4641 = 6.4641 MPa (compression, so negative).
    assert pl.biaxial_peak_stress(confining_pressure=0.0, cohesion=1e6, friction_deg=30.0) == \
        pytest.approx(-2e6 * math.sqrt(3.0), rel=1e-14, abs=0)
    assert pl.biaxial_peak_stress(confining_pressure=1e6, cohesion=1e6, friction_deg=30.0) == \
        pytest.approx(-6.464101615e6, rel=1e-9, abs=0)


@pytest.mark.requirements("REQ-QA-003", "REQ-MC-005")
def test_single_plane_of_weakness_known_values():
    rock = dict(cohesion=1e6, friction_deg=30.0, joint_friction_deg=30.0)
    # No confinement, c_w = 0.2 MPa, phi_w = 30 deg: at beta = 60 deg the plane slips at
    # 2 c_w / ((1 - 1/3) sin 120) = 0.4 MPa / 0.57735 = 0.69282 MPa.
    assert pl.single_plane_of_weakness_peak_stress(confining_pressure=0.0, joint_cohesion=0.2e6, joint_angle_deg=60.0,
                                                   **rock) == pytest.approx(-0.4e6 / (2.0 / 3.0 * math.sin(math.radians(120.0))), rel=1e-12, abs=0)
    # At beta = 45 deg: 0.4 MPa / (1 - tan 30) = 0.94641 MPa.
    assert pl.single_plane_of_weakness_peak_stress(confining_pressure=0.0, joint_cohesion=0.2e6, joint_angle_deg=45.0,
                                                   **rock) == pytest.approx(-0.4e6 / (1.0 - math.tan(math.radians(30.0))), rel=1e-12, abs=0)
    # Cohesionless plane under 1 MPa, beta = 45 + phi_w / 2 = 60 deg: the minimum, sigma1 = N_phi_w sigma3 = 3 MPa.
    assert pl.single_plane_of_weakness_peak_stress(confining_pressure=1e6, joint_cohesion=0.0, joint_angle_deg=60.0,
                                                   **rock) == pytest.approx(-3e6, rel=1e-12, abs=0)
    # beta <= phi_w or beta = 90 deg: the plane cannot slip and the rock fails, 2 c sqrt(3) unconfined.
    for beta in (20.0, 30.0, 90.0):
        assert pl.single_plane_of_weakness_peak_stress(confining_pressure=0.0, joint_cohesion=0.2e6, joint_angle_deg=beta,
                                                       **rock) == pytest.approx(-2e6 * math.sqrt(3.0), rel=1e-12, abs=0)
    # A strong plane (c_w = 5 MPa) at 60 deg: the rock is weaker.
    assert pl.single_plane_of_weakness_peak_stress(confining_pressure=0.0, joint_cohesion=5e6, joint_angle_deg=60.0,
                                                   **rock) == pytest.approx(-2e6 * math.sqrt(3.0), rel=1e-12, abs=0)


# The FLAC verification case "Cylindrical hole in an infinite Mohr-Coulomb medium": a = 1 m,
# p0 = 30 MPa, c = 3.45 MPa, phi = 30 deg, K = 3.9 GPa, G = 2.8 GPa, so
# E = 9 K G / (3 K + G) = 6.7779 GPa and nu = (3 K - 2 G) / (2 (3 K + G)) = 61/290 = 0.21034.
FLAC_K, FLAC_G = 3.9e9, 2.8e9
FLAC = dict(a=1.0, p0=30e6, E=9.0 * FLAC_K * FLAC_G / (3.0 * FLAC_K + FLAC_G),
            nu=(3.0 * FLAC_K - 2.0 * FLAC_G) / (2.0 * (3.0 * FLAC_K + FLAC_G)),
            cohesion=3.45e6, friction_deg=30.0)
SIGMA_C = 2.0 * 3.45e6 * math.sqrt(3.0)                 # 11.951 MPa
P_CRIT = (2.0 * 30e6 - SIGMA_C) / (1.0 + 3.0)           # 12.012 MPa


def _salencon(r, pi=0.0, dilation_deg=0.0, **over):
    return pl.salencon_tunnel(r=r, **{**FLAC, "pi": pi, "dilation_deg": dilation_deg, **over})


def _zones(rp, a=1.0, b=4.0, n=400):
    """Points strictly inside the plastic zone and strictly inside the elastic zone, clear of
    the wall and of R_p by more than a finite-difference step."""
    return np.linspace(a + 1e-3, rp - 1e-3, n), np.linspace(rp + 1e-3, b, n)


@REQ
def test_salencon_plastic_radius_and_wall_displacement_known_values():
    # By hand, pi = 0, psi = 0: N_phi = 3, sigma_c = 2 x 3.45 sqrt(3) = 11.951 MPa,
    # R_p = [2 (30 x 2 + 11.951) / (4 x 11.951)]^(1/2) = (143.902 / 47.805)^(1/2) = 1.7350 m,
    # sigma_re = (60 - 11.951) / 4 = 12.012 MPa (compression).
    # Wall displacement (N_psi = 1, A = sigma_c / 2 = 5.9756 MPa, (R_p/a)^2 (R_p/a)^2 = 9.0615):
    # 2 G u / a = -(1 - 2 nu)(p0 + A) + (1 - nu)(9 - 1)/4 A x 9.0615 + ((1 - nu) 4/4 - nu) A
    #           = -0.57931 x 35.976 + 1.57931 x 54.147 + 0.57931 x 5.9756 = 68.135 MPa,
    # u = 68.135e6 / 5.6e9 = 12.167 mm inward.
    out = _salencon(np.array([1.0, 1.7349981445794187]))
    assert out["plastic_radius"] == pytest.approx(1.7349981, rel=1e-7, abs=0)
    assert out["plastic_radius"] == pytest.approx(1.7350, abs=5e-5)
    assert out["wall_displacement"] == pytest.approx(-0.0121671, rel=1e-5, abs=0)
    assert out["ur"][0] == out["wall_displacement"]
    # Wall: srr = -pi = 0, stt = -sigma_c (unconfined strength); at R_p: srr = -sigma_re.
    assert out["srr"][0] == pytest.approx(0.0, abs=1e-6)
    assert out["stt"][0] == pytest.approx(-SIGMA_C, rel=1e-12, abs=0)
    assert out["srr"][1] == pytest.approx(-12.0122124e6, rel=1e-8, abs=0)


@REQ
@pytest.mark.parametrize("pi", [0.0, 5e6])
def test_salencon_equilibrium_in_both_zones(pi):
    # d(srr)/dr + (srr - stt) / r = 0, central differences (error ~ h^2 |srr'''| ~ 1e-6 x p0).
    h = 1e-5
    rp = _salencon(1.0, pi=pi)["plastic_radius"]
    for r in _zones(rp):
        mid, up, down = _salencon(r, pi=pi), _salencon(r + h, pi=pi), _salencon(r - h, pi=pi)
        residual = (up["srr"] - down["srr"]) / (2.0 * h) + (mid["srr"] - mid["stt"]) / r
        assert np.max(np.abs(residual)) < 1e-6 * 30e6


@REQ
def test_salencon_yield_holds_in_the_plastic_zone_and_not_beyond():
    # Tension positive, s1 = stt (most compressive), s3 = srr: on yield s1 = s3 N_phi - sigma_c.
    out = _salencon(1.0)
    plastic, elastic = _zones(out["plastic_radius"])
    p = _salencon(plastic)
    assert np.allclose(p["stt"], 3.0 * p["srr"] - SIGMA_C, rtol=0.0, atol=1e-8 * 30e6)
    e = _salencon(elastic)
    assert np.all(e["stt"] > 3.0 * e["srr"] - SIGMA_C)      # strictly inside the yield surface
    assert np.all(e["stt"] <= e["srr"])                      # stt stays the major compression
    assert np.all(p["stt"] <= p["srr"])


@REQ
@pytest.mark.parametrize("dilation_deg", [0.0, 10.0, 30.0])
def test_salencon_continuity_at_the_plastic_radius(dilation_deg):
    rp = _salencon(1.0, dilation_deg=dilation_deg)["plastic_radius"]
    eps = 1e-9
    inner = _salencon(rp * (1.0 - eps), dilation_deg=dilation_deg)
    outer = _salencon(rp * (1.0 + eps), dilation_deg=dilation_deg)
    for key in ("srr", "stt"):
        assert inner[key] == pytest.approx(outer[key], rel=1e-7, abs=0)
    assert inner["ur"] == pytest.approx(outer["ur"], rel=1e-7, abs=0)
    # The elastic-zone displacement at R_p: (p0 - sigma_re) R_p / (2 G), inward.
    assert outer["ur"] == pytest.approx(-(30e6 - P_CRIT) * rp / (2.0 * FLAC_G), rel=1e-7, abs=0)


@REQ
@pytest.mark.parametrize("pi", [P_CRIT, 20e6, 30e6, 40e6])
def test_salencon_elastic_when_the_support_holds_the_wall(pi):
    # pi >= p_crit = 12.012 MPa: no plastic zone, Lame's hole in an infinite medium,
    # tension positive srr = -p0 + (p0 - pi) a^2/r^2, stt = -p0 - (p0 - pi) a^2/r^2,
    # ur = -(p0 - pi) a^2 / (2 G r) (inward for pi < p0, outward for pi > p0).
    r = np.linspace(1.0, 6.0, 51)
    out = _salencon(r, pi=pi, dilation_deg=10.0)
    assert out["plastic_radius"] == 1.0
    assert np.allclose(out["srr"], -30e6 + (30e6 - pi) / r**2, rtol=1e-13, atol=1e-6)
    assert np.allclose(out["stt"], -30e6 - (30e6 - pi) / r**2, rtol=1e-13, atol=1e-6)
    assert np.allclose(out["ur"], -(30e6 - pi) / (2.0 * FLAC_G * r), rtol=1e-12, atol=1e-18)
    assert out["wall_displacement"] == pytest.approx(-(30e6 - pi) / (2.0 * FLAC_G), rel=1e-12, abs=1e-18)
    # Just below p_crit a plastic zone opens, growing continuously from the wall.
    if pi == P_CRIT:
        assert _salencon(1.0, pi=pi * (1.0 - 1e-6))["plastic_radius"] == pytest.approx(1.0, abs=1e-6)
        assert _salencon(1.0, pi=pi * (1.0 - 1e-6))["plastic_radius"] > 1.0


def _plastic_strains(r, h, dilation_deg, pi=0.0):
    """Total strains (extension positive) by central differences of ur, less the elastic strains
    from the stresses through plane-strain Hooke's law."""
    E, nu = FLAC["E"], FLAC["nu"]
    mid = _salencon(r, pi=pi, dilation_deg=dilation_deg)
    up = _salencon(r + h, pi=pi, dilation_deg=dilation_deg)
    down = _salencon(r - h, pi=pi, dilation_deg=dilation_deg)
    e_r, e_t = (up["ur"] - down["ur"]) / (2.0 * h), mid["ur"] / r
    ds_r, ds_t = mid["srr"] + 30e6, mid["stt"] + 30e6          # change from the in-situ stress
    k = (1.0 + nu) / E
    return e_r - k * ((1.0 - nu) * ds_r - nu * ds_t), e_t - k * ((1.0 - nu) * ds_t - nu * ds_r)


@REQ
@pytest.mark.parametrize("dilation_deg", [0.0, 10.0])
@pytest.mark.parametrize("pi", [0.0, 5e6])
def test_salencon_plastic_strains_obey_the_flow_rule(dilation_deg, pi):
    # Plastic zone: e_r^p + N_psi e_t^p = 0 with e_t^p < 0 (hoop contraction) and e_r^p > 0;
    # elastic zone: no plastic strain. Strains here are ~1e-3; the difference errors ~1e-12.
    h = 1e-5
    s = math.sin(math.radians(dilation_deg))
    n_psi = (1.0 + s) / (1.0 - s)
    rp = _salencon(1.0, pi=pi, dilation_deg=dilation_deg)["plastic_radius"]
    plastic, elastic = _zones(rp)
    ep_r, ep_t = _plastic_strains(plastic, h, dilation_deg, pi)
    scale = np.max(np.abs(ep_t))
    assert scale > 1e-4                                       # the check is not vacuous
    assert np.max(np.abs(ep_r + n_psi * ep_t)) < 1e-7 * scale
    assert np.all(ep_t < 0.0) and np.all(ep_r > 0.0)
    # Volumetric plastic strain (1 - N_psi) e_t^p: zero without dilation, expansion with it.
    if dilation_deg == 0.0:
        assert np.max(np.abs(ep_r + ep_t)) < 1e-7 * scale
    else:
        assert np.all(ep_r + ep_t > 0.0)
    ep_r, ep_t = _plastic_strains(elastic, h, dilation_deg, pi)
    assert np.max(np.abs(ep_r)) < 1e-7 * scale and np.max(np.abs(ep_t)) < 1e-7 * scale


@REQ
def test_salencon_dilation_changes_the_displacement_not_the_stresses():
    r = np.linspace(1.0, 4.0, 31)
    plain, dilating = _salencon(r), _salencon(r, dilation_deg=10.0)
    assert plain["plastic_radius"] == dilating["plastic_radius"]
    assert np.array_equal(plain["srr"], dilating["srr"]) and np.array_equal(plain["stt"], dilating["stt"])
    assert dilating["wall_displacement"] < plain["wall_displacement"] < 0.0   # more convergence
    elastic = r > plain["plastic_radius"]
    assert np.allclose(plain["ur"][elastic], dilating["ur"][elastic], rtol=1e-14, atol=0.0)
    # Far away the stresses return to the in-situ -p0.
    far = _salencon(np.array([1e4]))
    assert far["srr"][0] == pytest.approx(-30e6, rel=1e-6, abs=0) and far["stt"][0] == pytest.approx(-30e6, rel=1e-6, abs=0)


@REQ
def test_salencon_rejects_bad_input():
    with pytest.raises(ValueError):
        _salencon(np.array([0.5, 1.0]))                       # inside the tunnel
    with pytest.raises(ValueError):
        _salencon(1.0 - 1e-9)                                 # inside by more than round-off
    with pytest.raises(ValueError):
        _salencon(1.0, dilation_deg=31.0)                     # psi > phi
    with pytest.raises(ValueError):
        _salencon(1.0, dilation_deg=-1.0)
    with pytest.raises(ValueError):
        _salencon(1.0, pi=-1.0)
    with pytest.raises(ValueError):
        _salencon(1.0, cohesion=0.0)                          # unbounded plastic zone at pi = 0
    with pytest.raises(ValueError):
        _salencon(1.0, pi=60e6)                               # expansion failure, not covered
    with pytest.raises(ValueError):
        _salencon(1.0, nu=0.5)


@REQ
def test_salencon_takes_a_wall_point_with_round_off_at_the_wall():
    # A vertex of a 256-sided polygon on the wall lies at r = 1 - 1.1e-16.
    at_wall = _salencon(np.array([1.0]))
    rounded = _salencon(np.array([1.0 - 1.1e-16]))
    for key in ("ur", "srr", "stt"):
        assert rounded[key][0] == at_wall[key][0]


@REQ
def test_plastic_strain_rate_ratio_known_values():
    assert pl.plastic_strain_rate_ratio(dilation_deg=0.0) == -1.0
    assert pl.plastic_strain_rate_ratio(dilation_deg=30.0) == pytest.approx(-3.0, rel=1e-15, abs=0)
    assert pl.plastic_strain_rate_ratio(dilation_deg=10.0) == pytest.approx(-(1 + math.sin(math.radians(10))) / (1 - math.sin(math.radians(10))))
    with pytest.raises(ValueError, match="dilation"):
        pl.plastic_strain_rate_ratio(dilation_deg=90.0)

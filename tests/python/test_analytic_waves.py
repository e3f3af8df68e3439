"""Wave references (verification/analytic/waves.py) at known values.

Known values are worked by hand in the comments. The consistency checks take independent routes:
Aki & Richards' closed-form free-surface coefficients typed in here; the reflected field rebuilt
from the returned amplitudes and checked against the wave equation, the dashpot conditions and
the energy flux by finite differences of the displacement field (not by the module's algebra);
the layer's multiple-reflection sum against the frequency-domain transfer function through an
FFT, and against the step response summed by hand.
"""
import cmath
import math

import numpy as np
import pytest

from analytic import waves as wv

REQ = pytest.mark.requirements("REQ-QA-003")

SQ3 = math.sqrt(3.0)


def lame(nu):
    """(lam, G, alpha) with rho = 1, beta = 1: G = 1, lam = 2 nu / (1 - 2 nu), alpha^2 = lam + 2."""
    lam = 2.0 * nu / (1.0 - 2.0 * nu)
    return lam, 1.0, math.sqrt(lam + 2.0)


def complex_ratio(result, which):
    return result[f"reflected_{which}_magnitude"] * cmath.exp(1j * math.radians(result[f"reflected_{which}_phase_deg"]))


def aki_richards_free_surface(theta_deg, nu, wave):
    """Free-surface coefficients of Aki & Richards (Quantitative Seismology, 2nd ed., ch. 5),
    p the ray parameter, i and j the P and S angles, time factor exp(-i w t) (cos of an evanescent
    wave's angle is i sqrt(...), Im > 0):

        PP = (-(1/b^2 - 2p^2)^2 + 4p^2 (cos i / a)(cos j / b)) / D,  PS = 4 (a/b) p (cos i / a)(1/b^2 - 2p^2) / D,
        SP = 4 (b/a) p (cos j / b)(1/b^2 - 2p^2) / D,                SS = ((1/b^2 - 2p^2)^2 - 4p^2 (cos i / a)(cos j / b)) / D,
        D = (1/b^2 - 2p^2)^2 + 4p^2 (cos i / a)(cos j / b).

    Returned complex-conjugated: the module's time factor is exp(+i w t)."""
    _, _, a = lame(nu)
    b = 1.0
    p = math.sin(math.radians(theta_deg)) / (a if wave == "P" else b)
    ci_a = cmath.sqrt(1.0 / a ** 2 - p * p)
    ci_a = complex(ci_a.real, abs(ci_a.imag))
    cj_b = cmath.sqrt(1.0 / b ** 2 - p * p)
    x = 1.0 / b ** 2 - 2.0 * p * p
    d = x * x + 4.0 * p * p * ci_a * cj_b
    if wave == "P":
        pair = ((-x * x + 4.0 * p * p * ci_a * cj_b) / d, 4.0 * (a / b) * p * ci_a * x / d)
    else:
        pair = (4.0 * (b / a) * p * cj_b * x / d, (x * x - 4.0 * p * p * ci_a * cj_b) / d)
    return pair[0].conjugate(), pair[1].conjugate()


# ---------------------------------------------------------------- oblique incidence: known values


@REQ
def test_speed_ratio_and_critical_angle_known_values():
    # nu = 1/4: alpha^2 / beta^2 = 2 * 0.75 / 0.5 = 3; critical angle asin(1 / sqrt 3) = 35.2643897 degrees
    assert wv.speed_ratio(nu=0.25) == pytest.approx(SQ3, rel=1e-15, abs=0)
    assert wv.sv_critical_angle_deg(nu=0.25) == pytest.approx(35.2643896828, rel=1e-11, abs=0)
    # nu = 0: alpha / beta = sqrt 2, critical angle 45 degrees; nu = 1/3: sqrt(2 * (2/3) / (1/3)) = 2, 30 degrees
    assert wv.speed_ratio(nu=0.0) == pytest.approx(math.sqrt(2.0), rel=1e-15, abs=0)
    assert wv.sv_critical_angle_deg(nu=0.0) == pytest.approx(45.0, rel=1e-14, abs=0)
    assert wv.sv_critical_angle_deg(nu=1.0 / 3.0) == pytest.approx(30.0, rel=1e-13, abs=0)


@REQ
@pytest.mark.parametrize("nu", [0.0, 0.25, 0.4, 0.49])
def test_standard_viscous_boundary_reflects_nothing_at_normal_incidence(nu):
    for wave in ("P", "SV"):
        r = wv.viscous_boundary_reflection(angle_deg=0.0, nu=nu, wave=wave)
        assert abs(r["reflected_p"]) <= 1e-15 and abs(r["reflected_s"]) <= 1e-15
        assert r["energy_reflected"] <= 1e-30
        assert r["energy_absorbed"] == pytest.approx(1.0, rel=1e-14, abs=0)


@REQ
def test_normal_incidence_with_other_dashpots_is_the_impedance_mismatch():
    # One dimension: a dashpot a rho c_p on a P wave reflects -(1 - a)/(1 + a) of it (P motion along the
    # propagation direction, so a free surface, a = 0, gives -1: the surface moves at twice the
    # incident velocity); a = 1/2: -1/3, energy 1/9. An SV wave on b rho c_s: +(1 - b)/(1 + b); b = 2: -1/3.
    r = wv.viscous_boundary_reflection(angle_deg=0.0, nu=0.25, wave="P", a=0.5, b=7.0)
    assert r["reflected_p"] == pytest.approx(-1.0 / 3.0, rel=1e-14, abs=0) and r["reflected_s"] == 0.0
    assert (r["energy_reflected"], r["energy_absorbed"]) == (pytest.approx(1.0 / 9.0, rel=1e-13, abs=0),
                                                             pytest.approx(8.0 / 9.0, rel=1e-14, abs=0))
    r = wv.viscous_boundary_reflection(angle_deg=0.0, nu=0.25, wave="SV", a=7.0, b=2.0)
    assert r["reflected_s"] == pytest.approx(-1.0 / 3.0, rel=1e-14, abs=0) and r["reflected_p"] == 0.0
    assert wv.viscous_boundary_reflection(angle_deg=0.0, nu=0.3, wave="P", a=0.0, b=0.0)["reflected_p"] == \
        pytest.approx(-1.0, rel=1e-15, abs=0)
    assert wv.viscous_boundary_reflection(angle_deg=0.0, nu=0.3, wave="SV", a=0.0, b=0.0)["reflected_s"] == \
        pytest.approx(1.0, rel=1e-15, abs=0)


@REQ
def test_standard_boundary_p_wave_at_60_degrees_known_value():
    # nu = 1/4, beta = rho = 1: alpha = sqrt 3, lam = G = 1. P at 60 degrees: p = sin 60 / sqrt 3 = 1/2,
    # eta_p = sqrt(1/3 - 1/4) = 1 / (2 sqrt 3), eta_s = sqrt(1 - 1/4) = sqrt(3) / 2, reflected SV at 30 degrees.
    # Polarisations: incident (sqrt3/2, -1/2), reflected P (sqrt3/2, 1/2), reflected SV (sqrt3/2, -1/2).
    # Normal condition lam (p d_x + eta d_z) + 2 G eta d_z + alpha d_z:
    #   incident 1/sqrt3 + 1/(2 sqrt3) - sqrt3/2 = 0, P: 1/sqrt3 + 1/(2 sqrt3) + sqrt3/2 = sqrt 3, SV: 0 - sqrt3/2 - sqrt3/2 = -sqrt 3
    #   so R_P = R_S = R.
    # Tangential condition G (eta d_x + p d_z) + beta d_x:
    #   incident -1/4 - 1/4 + sqrt3/2 = (sqrt3 - 1)/2, P: 1/4 + 1/4 + sqrt3/2 = (1 + sqrt3)/2, SV: 3/4 - 1/4 + sqrt3/2 = (1 + sqrt3)/2
    #   so (1 + sqrt3) R = -(sqrt3 - 1)/2, R = -(sqrt3 - 1)^2 / 4 = -(2 - sqrt3)/2 = -0.1339746.
    # Energy: P R^2; SV R^2 (beta^2 eta_s) / (alpha^2 eta_p) = R^2 (sqrt3/2) / (3 / (2 sqrt3)) = R^2; total
    # 2 R^2 = (7 - 4 sqrt3)/2 = 0.0358984.
    R = -(2.0 - SQ3) / 2.0
    r = wv.viscous_boundary_reflection(angle_deg=60.0, nu=0.25, wave="P")
    assert (r["reflected_p"], r["reflected_s"]) == (pytest.approx(R, rel=1e-13, abs=0), pytest.approx(R, rel=1e-13, abs=0))
    assert r["energy_reflected"] == pytest.approx((7.0 - 4.0 * SQ3) / 2.0, rel=1e-12, abs=0)
    assert r["energy_absorbed"] == pytest.approx(1.0 - (7.0 - 4.0 * SQ3) / 2.0, rel=1e-13, abs=0)
    assert (r["angle_p_deg"], r["angle_s_deg"]) == (pytest.approx(60.0, rel=1e-13, abs=0), pytest.approx(30.0, rel=1e-13, abs=0))
    # every field is a plain float, as a verification problem's reference component must be
    assert all(type(value) is float for value in r.values())
    # The mirror case, an SV wave at 30 degrees (reflected P at 60), works out to the same numbers.
    r = wv.viscous_boundary_reflection(angle_deg=30.0, nu=0.25, wave="SV")
    assert (r["reflected_p"], r["reflected_s"]) == (pytest.approx(R, rel=1e-13, abs=0), pytest.approx(R, rel=1e-13, abs=0))
    assert r["energy_reflected"] == pytest.approx((7.0 - 4.0 * SQ3) / 2.0, rel=1e-12, abs=0)


@REQ
@pytest.mark.parametrize("wave", ["P", "SV"])
@pytest.mark.parametrize("nu", [0.1, 0.25, 0.45])
def test_free_surface_limit_is_aki_and_richards(wave, nu):
    # below and above the SV critical angle (35.3 degrees at nu = 1/4), where the P wave is evanescent
    for theta in (0.0, 5.0, 20.0, 33.0, 40.0, 60.0, 77.0, 89.0):
        r = wv.viscous_boundary_reflection(angle_deg=theta, nu=nu, wave=wave, a=0.0, b=0.0)
        pp, ps = aki_richards_free_surface(theta, nu, wave)
        assert abs(complex_ratio(r, "p") - pp) <= 1e-12 and abs(complex_ratio(r, "s") - ps) <= 1e-12, theta
        assert r["energy_reflected"] == pytest.approx(1.0, rel=1e-13, abs=0) and r["energy_absorbed"] == 0.0


@REQ
def test_free_surface_known_values_nu_one_quarter():
    # Aki & Richards' PP numerator at nu = 1/4 (alpha = sqrt 3), 60 degrees: p = 1/2, 1 - 2 p^2 = 1/2,
    # -(1/2)^2 + 4 (1/4)(cos 60 / sqrt 3)(cos 30) = -1/4 + 1/4 = 0: all the energy goes to SV (PS = 1,
    # energy (sqrt3/2) / (3 / (2 sqrt 3)) = 1). The SV wave at 30 degrees mirrors it: SS = 0, SP = 1.
    r = wv.viscous_boundary_reflection(angle_deg=60.0, nu=0.25, wave="P", a=0.0, b=0.0)
    assert abs(r["reflected_p"]) <= 1e-15 and r["reflected_s"] == pytest.approx(1.0, rel=1e-14, abs=0)
    assert r["energy_s"] == pytest.approx(1.0, rel=1e-14, abs=0)
    r = wv.viscous_boundary_reflection(angle_deg=30.0, nu=0.25, wave="SV", a=0.0, b=0.0)
    assert abs(r["reflected_s"]) <= 1e-15 and r["reflected_p"] == pytest.approx(1.0, rel=1e-14, abs=0)
    # Beyond the critical angle the reflected SV wave keeps all the energy, with a phase shift.
    # SV at 45 degrees: p^2 = 1/2, 1 - 2 p^2 = 0, so SS = -4 p^2 (...) / (+4 p^2 (...)) = -1, SP = 0.
    r = wv.viscous_boundary_reflection(angle_deg=45.0, nu=0.25, wave="SV", a=0.0, b=0.0)
    assert r["reflected_s_magnitude"] == pytest.approx(1.0, rel=1e-14, abs=0)
    assert abs(r["reflected_s_phase_deg"]) == pytest.approx(180.0, rel=1e-14, abs=0)
    assert r["reflected_p_magnitude"] <= 1e-15 and r["energy_p"] == 0.0
    assert math.isnan(r["reflected_s"]) and math.isnan(r["angle_p_deg"])


# ---------------------------------------------------------------- oblique incidence: the field itself


def plane_waves(theta_deg, nu, wave, r):
    """[(amplitude, (p, eta), polarisation)] of the incident and reflected waves as the docstring defines
    them, exp(i w (t - p x - eta z)), z into the medium, beta = rho = 1."""
    _, _, alpha = lame(nu)
    c_inc = alpha if wave == "P" else 1.0
    p = math.sin(math.radians(theta_deg)) / c_inc
    eta_p = cmath.sqrt(1.0 / alpha ** 2 - p * p)
    eta_p = complex(eta_p.real, -abs(eta_p.imag))        # decays into z > 0
    eta_s = math.sqrt(1.0 - p * p)
    def p_pol(eta):
        return np.array([alpha * p, alpha * eta])
    def s_pol(eta, sign):
        return sign * np.array([eta, -p])
    incident = (1.0, (p, -eta_p), p_pol(-eta_p)) if wave == "P" else (1.0, (p, -eta_s), s_pol(-eta_s, -1.0))
    return [incident,
            (complex_ratio(r, "p"), (p, eta_p), p_pol(eta_p)),
            (complex_ratio(r, "s"), (p, eta_s), s_pol(eta_s, 1.0))]


def displacement(waves, x, z):
    return sum(U * d * np.exp(-1j * (s[0] * x + s[1] * z)) for U, s, d in waves)   # w = 1


def stress_by_differences(waves, x, z, lam, G, h=1e-5):
    """(s_xx, s_zz, s_xz) from central differences of the displacement (w = 1)."""
    dudx = (displacement(waves, x + h, z) - displacement(waves, x - h, z)) / (2 * h)
    dudz = (displacement(waves, x, z + h) - displacement(waves, x, z - h)) / (2 * h)
    div = dudx[0] + dudz[1]
    return lam * div + 2 * G * dudx[0], lam * div + 2 * G * dudz[1], G * (dudz[0] + dudx[1])


def flux_towards_boundary(waves, z, lam, G):
    """Mean energy flux in -z per unit length: <sigma_iz v_i> = Re(sigma_iz conj(v_i)) / 2, v = i u."""
    _, szz, sxz = stress_by_differences(waves, 0.3, z, lam, G)
    v = 1j * displacement(waves, 0.3, z)
    return 0.5 * (sxz * np.conj(v[0]) + szz * np.conj(v[1])).real


CASES = [("P", 10.0, 0.25, 1.0, 1.0), ("P", 50.0, 0.25, 1.0, 1.0), ("P", 75.0, 0.4, 1.0, 1.0),
         ("P", 40.0, 0.2, 0.6, 1.7), ("SV", 20.0, 0.25, 1.0, 1.0), ("SV", 34.0, 0.3, 2.0, 0.5),
         ("SV", 50.0, 0.25, 1.0, 1.0), ("SV", 70.0, 0.1, 0.3, 0.8)]


@REQ
@pytest.mark.parametrize("wave, theta, nu, a, b", CASES)
def test_reflected_field_solves_the_wave_equation_and_the_dashpot_conditions(wave, theta, nu, a, b):
    lam, G, alpha = lame(nu)
    waves = plane_waves(theta, nu, wave, wv.viscous_boundary_reflection(angle_deg=theta, nu=nu, wave=wave, a=a, b=b))
    # Navier: -w^2 rho u = div sigma, at a point inside, by differences of differences (h = 1e-4)
    x, z, h = 0.7, 1.3, 1e-4
    sx_p, _, sxz_xp = stress_by_differences(waves, x + h, z, lam, G)
    sx_m, _, sxz_xm = stress_by_differences(waves, x - h, z, lam, G)
    _, szz_p, sxz_zp = stress_by_differences(waves, x, z + h, lam, G)
    _, szz_m, sxz_zm = stress_by_differences(waves, x, z - h, lam, G)
    div = np.array([(sx_p - sx_m + sxz_zp - sxz_zm) / (2 * h), (sxz_xp - sxz_xm + szz_p - szz_m) / (2 * h)])
    scale = np.max(np.abs(displacement(waves, x, z))) + 1.0
    np.testing.assert_allclose(div, -displacement(waves, x, z), atol=1e-6 * scale, rtol=0)
    # dashpots on z = 0 (outward normal -z): sigma_zz = a rho alpha v_z, sigma_xz = b rho beta v_x
    _, szz, sxz = stress_by_differences(waves, x, 0.0, lam, G)
    v = 1j * displacement(waves, x, 0.0)
    assert abs(szz - a * alpha * v[1]) <= 1e-8 * alpha ** 2 and abs(sxz - b * v[0]) <= 1e-8 * alpha ** 2


@REQ
@pytest.mark.parametrize("wave, theta, nu, a, b", CASES)
def test_incident_flux_is_reflected_flux_plus_what_the_dashpots_absorb(wave, theta, nu, a, b):
    lam, G, alpha = lame(nu)
    r = wv.viscous_boundary_reflection(angle_deg=theta, nu=nu, wave=wave, a=a, b=b)
    waves = plane_waves(theta, nu, wave, r)
    incident = flux_towards_boundary(waves[:1], 0.0, lam, G)
    reflected_p = -flux_towards_boundary(waves[1:2], 0.0, lam, G)
    reflected_s = -flux_towards_boundary(waves[2:], 0.0, lam, G)
    v = 1j * displacement(waves, 0.0, 0.0)
    absorbed = 0.5 * (a * alpha * abs(v[1]) ** 2 + b * abs(v[0]) ** 2)
    assert incident > 0.0
    assert r["energy_p"] == pytest.approx(reflected_p / incident, rel=0, abs=1e-9)
    assert r["energy_s"] == pytest.approx(reflected_s / incident, rel=0, abs=1e-9)
    # incident comes from differences: central differences at h = 1e-5 are good to ~1e-10
    assert r["energy_absorbed"] == pytest.approx(absorbed / incident, rel=1e-9, abs=0)
    assert reflected_p + reflected_s + absorbed == pytest.approx(incident, rel=1e-9, abs=0)
    # the net flux of the whole field is the same through every plane z (the waves' cross terms carry
    # none on average): it is what the dashpots take
    for z in (0.0, 0.37, 2.9):
        assert flux_towards_boundary(waves, z, lam, G) == pytest.approx(absorbed, rel=1e-8, abs=1e-12)


@REQ
def test_standard_boundary_reflects_more_at_grazing_incidence():
    # a = b = 1, nu = 1/4: reflected energy stays below 0.1 % of the incident up to 30 degrees from the
    # normal for a P wave, passes 3.5 % at 60 degrees (the worked value above) and tends to all of it at
    # grazing incidence, where the incident wave carries no flux through the boundary.
    energy = [wv.viscous_boundary_reflection(angle_deg=t, nu=0.25, wave="P")["energy_reflected"]
              for t in (10.0, 30.0, 60.0, 89.9)]
    assert energy[0] < energy[1] < 1e-3 < energy[2] < energy[3] and energy[3] > 0.98


@REQ
def test_viscous_boundary_rejects_bad_input():
    good = dict(angle_deg=30.0, nu=0.25, wave="P", a=1.0, b=1.0)
    for key, value in (("angle_deg", 90.0), ("angle_deg", -1.0), ("angle_deg", math.nan), ("nu", 0.5),
                       ("nu", -1.0), ("wave", "S"), ("a", -0.1), ("b", math.inf)):
        with pytest.raises(ValueError, match=key):
            wv.viscous_boundary_reflection(**{**good, key: value})


# ---------------------------------------------------------------- a layer on a half-space

# Soft soil on rock: rho1 = 1800, c1 = 200, rho2 = 2400, c2 = 1000, H = 25 m: alpha_z = 360000 / 2400000
# = 0.15, tau = H / c1 = 0.125 s, f1 = c1 / 4H = 2 Hz.
SOIL = dict(H=25.0, rho1=1800.0, c1=200.0, rho2=2400.0, c2=1000.0)


@REQ
def test_layer_amplification_known_values():
    assert wv.impedance_ratio(rho1=1800.0, c1=200.0, rho2=2400.0, c2=1000.0) == pytest.approx(0.15, rel=1e-15, abs=0)
    assert wv.layer_resonance_frequency(H=25.0, c1=200.0) == 2.0
    assert wv.layer_resonance_frequency(H=25.0, c1=200.0, mode=3) == 10.0
    # at f1: cos kH = 0, |F| = 1 / alpha_z = 6.6667; at 4 Hz kH = pi: 1; at 0: 1;
    # at 1 Hz kH = pi/4: 1 / sqrt(0.5 + 0.0225 * 0.5) = 1 / sqrt(0.51125) = 1 / 0.7150175 = 1.3985672
    amp = wv.layer_amplification(frequency=np.array([0.0, 1.0, 2.0, 4.0, 6.0]), **SOIL)
    np.testing.assert_allclose(amp, [1.0, 1.3985672, 1.0 / 0.15, 1.0, 1.0 / 0.15], rtol=1e-7)
    assert isinstance(wv.layer_amplification(frequency=2.0, **SOIL), float)
    # the resonance is a peak
    assert wv.layer_amplification(frequency=1.99, **SOIL) < 1.0 / 0.15 > wv.layer_amplification(frequency=2.01, **SOIL)
    # alpha_z = 1 (no contrast): the layer is not there, |F| = 1 at every frequency, and F = exp(-i w tau)
    same = dict(H=25.0, rho1=2000.0, c1=500.0, rho2=2000.0, c2=500.0)
    f = np.linspace(0.0, 30.0, 31)
    np.testing.assert_allclose(wv.layer_transfer_function(frequency=f, **same), np.exp(-2j * np.pi * f * 0.05), rtol=0, atol=1e-15)


@REQ
def test_layer_without_contrast_moves_at_twice_the_incident_velocity_delayed():
    same = dict(H=30.0, rho1=2000.0, c1=300.0, rho2=2500.0, c2=240.0)   # rho c = 600000 on both sides
    pulse = lambda s: np.exp(-((s - 0.2) / 0.03) ** 2) * np.sin(40.0 * s)
    t = np.linspace(0.0, 1.0, 2001)
    expected = np.where(t >= 0.1, 2.0 * pulse(t - 0.1), 0.0)
    np.testing.assert_allclose(wv.layer_surface_velocity(t, input=pulse, **same), expected, rtol=0, atol=1e-15)


@REQ
def test_input_given_below_the_interface_arrives_later():
    # D = 100 m of half-space (c2 = 1000 m/s) under the interface: 0.1 s later, nothing before
    t = np.linspace(0.0, 3.0, 601)
    sine = {"amplitude": 0.01, "frequency": 3.0, "phase": 0.4}
    at_interface = wv.layer_surface_velocity(t, input=sine, **SOIL)
    below = wv.layer_surface_velocity(t + 0.1, input=sine, input_depth=100.0, **SOIL)
    np.testing.assert_allclose(below, at_interface, rtol=0, atol=1e-15)
    # the first motion at the surface: at D / c2 + H / c1 = 0.1 + 0.125 s, the transmitted wave doubled,
    # 2 T A sin(2 pi f s + phase) = 2 (2 / 1.15) 0.01 sin(0.4 + 6 pi 1e-4) 1e-4 s after
    early = wv.layer_surface_velocity(np.array([0.2249, 0.2251]), input=sine, input_depth=100.0, **SOIL)
    assert early[0] == 0.0
    assert early[1] == pytest.approx(4.0 / 1.15 * 0.01 * math.sin(0.4 + 6.0 * math.pi * 1e-4), rel=1e-9, abs=0)
    with pytest.raises(ValueError, match="input_depth"):
        wv.layer_surface_velocity(t, input=sine, input_depth=-1.0, **SOIL)


@REQ
def test_layer_step_response_known_values():
    # alpha_z = 0.5 (rho1 c1 = 1e6, rho2 c2 = 2e6), tau = H / c1 = 0.1 s, unit step v_in = 1 for t >= 0:
    # T = 2 / 1.5 = 4/3, surface 2 T = 8/3 from tau; R = (0.5 - 1) / 1.5 = -1/3 per round trip 2 tau:
    # 8/3 (1 - 1/3) = 16/9 from 3 tau, 8/3 (1 - 1/3 + 1/9) = 56/27 from 5 tau; limit 8/3 / (1 + 1/3) = 2
    # (the outcrop motion: a static step passes the layer unchanged).
    stiff = dict(H=20.0, rho1=5000.0, c1=200.0, rho2=4000.0, c2=500.0)
    step = lambda s: np.ones_like(s)
    v = wv.layer_surface_velocity(np.array([0.05, 0.15, 0.25, 0.35, 0.45, 0.55, 6.0]), input=step, **stiff)
    np.testing.assert_allclose(v, [0.0, 8 / 3, 8 / 3, 16 / 9, 16 / 9, 56 / 27, 2.0], rtol=1e-13)
    assert isinstance(wv.layer_surface_velocity(0.15, input=step, **stiff), float)


@REQ
@pytest.mark.parametrize("frequency", [1.0, 2.0, 3.3])
def test_long_sine_tends_to_the_steady_amplitude(frequency):
    # alpha_z = 0.15: R = -0.85 / 1.15 = -0.739, after 110 round trips of 0.25 s |R|^110 = 4e-15
    t = np.linspace(28.0, 30.0, 801)
    v = wv.layer_surface_velocity(t, input={"amplitude": 0.01, "frequency": frequency}, **SOIL)
    F = wv.layer_transfer_function(frequency=frequency, **SOIL)
    steady = 2.0 * 0.01 * np.abs(F) * np.sin(2 * np.pi * frequency * t + np.angle(F))
    np.testing.assert_allclose(v, steady, rtol=0, atol=1e-12)
    if frequency == 2.0:   # at resonance the steady amplitude is 2 A / alpha_z
        assert np.max(np.abs(v)) == pytest.approx(0.02 / 0.15, rel=1e-5, abs=0)


@REQ
def test_multiple_reflections_agree_with_the_transfer_function_for_any_input():
    # A Ricker-like pulse through the FFT: surface = irfft(2 F(f) V_in(f)); the sum is exact, the FFT
    # route is exact for a band-limited, periodic signal, so the pulse must have died out within the window.
    stiff = dict(H=20.0, rho1=5000.0, c1=200.0, rho2=4000.0, c2=500.0)   # alpha_z = 0.5, tau = 0.1 s
    n, dt = 4096, 0.0025
    t = np.arange(n) * dt
    arg = (np.pi * 8.0 * (t - 0.3)) ** 2
    pulse = (1.0 - 2.0 * arg) * np.exp(-arg)
    f = np.fft.rfftfreq(n, dt)
    by_fft = np.fft.irfft(2.0 * wv.layer_transfer_function(frequency=f, **stiff) * np.fft.rfft(pulse), n)
    ricker = lambda s: (1.0 - 2.0 * (np.pi * 8.0 * (s - 0.3)) ** 2) * np.exp(-(np.pi * 8.0 * (s - 0.3)) ** 2)
    by_sum = wv.layer_surface_velocity(t, input=ricker, **stiff)
    assert np.max(np.abs(by_sum)) > 1.0
    np.testing.assert_allclose(by_sum, by_fft, rtol=0, atol=1e-9)


@REQ
def test_layer_rejects_bad_input():
    with pytest.raises(ValueError, match="H"):
        wv.layer_amplification(frequency=1.0, **{**SOIL, "H": 0.0})
    with pytest.raises(ValueError, match="frequency"):
        wv.layer_amplification(frequency=-1.0, **SOIL)
    with pytest.raises(ValueError, match="c2"):
        wv.layer_transfer_function(frequency=1.0, **{**SOIL, "c2": math.nan})
    with pytest.raises(ValueError, match="unknown key"):
        wv.layer_surface_velocity(1.0, input={"amplitude": 1.0, "frequency": 2.0, "delay": 0.1}, **SOIL)
    with pytest.raises(ValueError, match="frequency"):
        wv.layer_surface_velocity(1.0, input={"amplitude": 1.0, "frequency": 0.0}, **SOIL)
    with pytest.raises(ValueError, match="input"):
        wv.layer_surface_velocity(1.0, input=3.0, **SOIL)
    with pytest.raises(ValueError, match="mode"):
        wv.layer_resonance_frequency(H=1.0, c1=1.0, mode=0)


@pytest.mark.requirements("REQ-QA-003")
def test_boundary_amplitude_ratios_at_60_degrees_are_worked_by_hand():
    # R_P = R_S = -(2 - sqrt 3) / 2 at 60 degrees (nu = 1/4), reflected P at 60 and SV at 30
    # degrees: along the boundary sin 60 (1 + R_P) + R_S cos 30 over sin 60 is 1 + 2 R_P = sqrt 3 - 1;
    # normal to it the reflected parts cancel (R_P cos 60 - R_S sin 30 = 0).
    assert wv.viscous_boundary_p_amplitude_ratio(angle_deg=60.0, nu=0.25, component="x") == \
        pytest.approx(math.sqrt(3.0) - 1.0, rel=1e-12, abs=0)
    assert wv.viscous_boundary_p_amplitude_ratio(angle_deg=60.0, nu=0.25, component="z") == \
        pytest.approx(1.0, rel=1e-12, abs=0)
    with pytest.raises(ValueError):
        wv.viscous_boundary_p_amplitude_ratio(angle_deg=60.0, nu=0.25, component="y")


@pytest.mark.requirements("REQ-QA-003")
@pytest.mark.parametrize("angle", [20.0, 45.0, 60.0, 75.0])
def test_reflected_energy_from_the_ratios_returns_the_closed_form_share(angle):
    ratio = {k: wv.viscous_boundary_p_amplitude_ratio(angle_deg=angle, nu=0.3, component=k) for k in ("x", "z")}
    # Peaks as a model would give them, the incident ones of any size.
    share = wv.viscous_boundary_p_reflected_energy(boundary_x=0.7 * ratio["x"], incident_x=0.7,
                                                      boundary_z=0.4 * ratio["z"], incident_z=0.4,
                                                      angle_deg=angle, nu=0.3)
    assert share == pytest.approx(wv.viscous_boundary_reflection(angle_deg=angle, nu=0.3)["energy_reflected"],
                                  rel=1e-9, abs=0)
    # No reflection at all (both ratios 1) is no energy.
    assert wv.viscous_boundary_p_reflected_energy(boundary_x=1.0, incident_x=1.0, boundary_z=1.0, incident_z=1.0,
                                                     angle_deg=angle, nu=0.3) == pytest.approx(0.0, rel=0, abs=1e-15)


@pytest.mark.requirements("REQ-QA-003")
def test_pulse_velocity_at_the_boundary_peaks_at_the_arrival_with_the_ratio_of_the_incident():
    c_p, distance = 2000.0, 50.0
    t = distance / c_p
    for component, d in (("x", math.sin(math.radians(60.0))), ("z", -math.cos(math.radians(60.0)))):
        v = wv.viscous_boundary_p_pulse_velocity([t, t + 2.0 / c_p], angle_deg=60.0, nu=0.25, c_p=c_p, amplitude=0.01,
                                                    width=2.0, distance=distance, component=component)
        ratio = wv.viscous_boundary_p_amplitude_ratio(angle_deg=60.0, nu=0.25, component=component)
        assert v[0] == pytest.approx(0.01 * d * ratio, rel=1e-12, abs=0)
        assert v[1] == pytest.approx(0.01 * d * ratio * math.exp(-1.0), rel=1e-12, abs=0)
    # The half-step lag: the value recorded at t is the one of t - dt/2.
    lagged = wv.viscous_boundary_p_pulse_velocity(t + 1e-4, angle_deg=60.0, nu=0.25, c_p=c_p, amplitude=0.01,
                                                     width=2.0, distance=distance, component="z", dt=2e-4)
    assert lagged == pytest.approx(-0.005, rel=1e-12, abs=0)

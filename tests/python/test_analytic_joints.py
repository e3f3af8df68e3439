"""Continuously-yielding joint references (verification/analytic/joints.py and the 50-digit
program verification/reference/cy_joint_reference.cpp) at known values.

The program is found at $VDEC_CY_REFERENCE or beside $VDEC_EXECUTABLE (ctest sets both); when
it is not built these tests fail, they do not skip."""
import math
import os
import subprocess

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq

from analytic import joints as jt

CY = pytest.mark.requirements("REQ-QA-003")
CLOSURE = pytest.mark.requirements("REQ-QA-003")

# The CY-SHEAR problem's joint: elastic length L = sn/ks = 1 mm, roughness R = 0.5 mm.
KS, SN = 1e9, 1e6
L = SN / KS
SOFT = dict(ks=KS, sn=SN, phi_deg=30.0, phi0_deg=45.0, roughness=5e-4)
FLAT = dict(SOFT, phi0_deg=30.0)
TAN30 = math.tan(math.radians(30.0))


def _cy(us, component, params=SOFT, turning_points=()):
    return jt.continuously_yielding_direct_shear(
        np.asarray(us, dtype=float), component=component, turning_points=turning_points, **params)


def _cy_error(us, component, params=SOFT, turning_points=()):
    return jt.continuously_yielding_direct_shear_error(
        np.asarray(us, dtype=float), component=component, turning_points=turning_points, **params)


def _run_program(*args, stdin="0.001\n"):
    return subprocess.run([jt.cy_reference_executable(), *args], input=stdin,
                          capture_output=True, text=True, check=False)


# One-sided fourth-order difference weights for f'(0) from f(0), f(h), ..., f(4h).
ONE_SIDED = np.array([-25.0, 48.0, -36.0, 16.0, -3.0]) / 12.0


@CY
def test_reference_program_is_built_and_found():
    path = jt.cy_reference_executable()
    assert os.path.basename(path) == "vdec_cy_reference"
    assert os.access(path, os.X_OK)


@CY
def test_without_softening_the_shear_stress_is_the_exponential_closed_form():
    # phi0 = phi: phi_eff stays phi, so dtau/dus = ks (1 - tau/tau_m) with a fixed
    # tau_m = sn tan(phi): tau = tau_m (1 - exp(-ks us / tau_m)); us_p = us - tau/ks.
    us = np.linspace(0.0, 20.0 * L, 201)
    tau_m = SN * TAN30
    exact = -tau_m * np.expm1(-KS * us / tau_m)
    tau = _cy(us, "tau", FLAT)
    assert np.allclose(tau, exact, rtol=1e-15, atol=0.0)
    assert tau[-1] == pytest.approx(tau_m, rel=1e-12, abs=0)        # 20 L = 34.6 tau_m/ks: on the plateau
    assert np.all(_cy(us, "phi_eff_deg", FLAT) == 30.0)
    assert np.allclose(_cy(us, "us_p", FLAT), us - exact / KS, rtol=0.0, atol=1e-15 * us[-1])
    # |tau| < sn tan(phi) throughout: no dilation at all.
    assert np.all(_cy(us, "opening", FLAT) == 0.0)


@CY
def test_softening_peaks_above_the_residual_then_softens_to_it():
    us = np.linspace(0.0, 30.0 * L, 3001)
    tau = _cy(us, "tau")
    phi = _cy(us, "phi_eff_deg")
    us_p = _cy(us, "us_p")
    opening = _cy(us, "opening")
    residual = SN * TAN30
    peak = int(np.argmax(tau))
    assert 0 < peak < 500                                    # within the first 5 L
    assert tau[peak] > 1.08 * residual                       # 630.8 kPa against 577.4 kPa
    # After 60 roughness lengths of slip phi_eff - phi ~ exp(-56): the residual sn tan(phi).
    assert tau[-1] == pytest.approx(residual, rel=1e-12, abs=0)
    assert phi[-1] == pytest.approx(30.0, rel=1e-12, abs=0)
    # Softening, monotonically (strictly until tau is within round-off of the residual).
    assert np.all(np.diff(tau[peak:]) <= 0.0)
    assert np.all(np.diff(tau[peak:])[tau[peak + 1:] > (1.0 + 1e-12) * residual] < 0.0)
    assert np.all(np.diff(phi) <= 0.0) and phi[0] == 45.0 and phi[1] < 45.0
    assert np.all(np.diff(us_p) > 0.0)
    # Above sn tan(phi) the joint dilates, and only there: no opening before tau first exceeds
    # the residual, then it grows while tau stays above (measurably, by 1e-6).
    above = tau > residual
    assert np.all(opening[: np.argmax(above)] == 0.0)
    clearly_above = tau > (1.0 + 1e-6) * residual
    assert np.all(np.diff(opening)[clearly_above[1:] & clearly_above[:-1]] > 0.0)
    assert np.all(np.diff(opening) >= 0.0)


@CY
def test_at_the_peak_tau_equals_the_bounding_strength():
    # Bracket the peak from a dense sample, then locate it as the zero of dtau/dus (a
    # fourth-order central difference of step h: truncation ~1e-17 ks, round-off of the double
    # tau ~1e-13 ks). tau is flat at the peak, so the largest sample only places it to ~1e-8 L
    # (F ~ 1e-9 there); the slope's zero places it to ~1e-15 m, where |F| ~ 1e-13.
    us = np.linspace(0.0, 5.0 * L, 2001)
    tau = _cy(us, "tau")
    i = int(np.argmax(tau))
    h = 1e-3 * L
    weights = np.array([1.0, -8.0, 8.0, -1.0]) / (12.0 * h)

    def slope(u):
        return float(weights @ _cy(u + h * np.array([-2.0, -1.0, 1.0, 2.0]), "tau"))

    assert slope(us[i - 1]) > 0.0 > slope(us[i + 1])
    u_peak = brentq(slope, us[i - 1], us[i + 1], xtol=1e-18, rtol=4.0 * np.finfo(float).eps)
    tau_peak = float(_cy(u_peak, "tau"))
    bound = SN * math.tan(math.radians(float(_cy(u_peak, "phi_eff_deg"))))
    assert tau_peak == pytest.approx(bound, rel=1e-12, abs=0)       # F = 0 at the peak
    assert tau_peak >= tau.max() * (1.0 - 1e-15)


@CY
@pytest.mark.parametrize("turning_point", [0.8 * L, 3.0 * L])
def test_reversal_restores_the_elastic_slope(turning_point):
    # Before (0.8 L) and after (3 L) the peak. Right after the turning point r = tau/tau_m of
    # the new direction, so F = 1 and dtau/dus = ks; without the reset F would be 1 + |tau/tau_m|.
    # Step h: truncation of the difference ~1e-16 ks, round-off of the double tau ~1e-11 ks.
    h = 1e-4 * L
    us = turning_point - h * np.arange(5.0)
    tau = _cy(np.concatenate(([0.5 * turning_point], us)), "tau", turning_points=(turning_point,))[1:]
    slope = -(ONE_SIDED @ tau) / h                           # dtau/dus, us decreasing
    assert slope == pytest.approx(KS, rel=1e-10, abs=0)
    # Just before the turning point the slope was ks F < ks.
    before = _cy(turning_point - h * np.arange(5.0)[::-1], "tau")
    assert (before[-1] - before[-2]) / h < 0.9 * KS


@CY
@pytest.mark.parametrize("back, capped", [(0.05 * L, True), (0.3 * L, False), (0.9 * L, False)])
def test_second_reversal_caps_r_at_three_quarters(back, capped):
    # Load to 3 L, go back by `back`, reverse again. After 0.05 L tau has fallen by ~0.05 sn
    # only: tau/tau_m = 0.934 > 0.75, so r = 0.75 and dtau/dus = ks (1 - tau/tau_m)/0.25
    # (0.26 ks instead of ks). After 0.3 L tau/tau_m = 0.563 and after 0.9 L it is negative
    # (tau has changed sign): r = tau/tau_m and F = 1 again.
    tp1 = 3.0 * L
    tp2 = tp1 - back
    h = 1e-4 * L
    us = np.concatenate(([tp1, tp2], tp2 + h * np.arange(5.0)))
    tau = _cy(us, "tau", turning_points=(tp1, tp2))
    phi = _cy(us, "phi_eff_deg", turning_points=(tp1, tp2))
    ratio = tau[1] / (SN * math.tan(math.radians(phi[1])))
    assert (ratio > 0.75) == capped
    expected = KS * (1.0 - ratio) / 0.25 if capped else KS
    slope = (ONE_SIDED @ tau[2:]) / h
    assert slope == pytest.approx(expected, rel=1e-9, abs=0)


def _integrate_cy_with_scipy(samples, turning_points, ks, sn, phi_deg, phi0_deg, roughness):
    """The model's equations (module docstring of joints.py) integrated afresh in double
    precision with scipy's DOP853, in SI units, along the same path rules as the program."""
    phi_b = math.radians(phi_deg)
    state = np.array([0.0, math.radians(phi0_deg), 0.0, 0.0])   # tau, phi_eff, us_p, opening
    d, r, pos, k = 0, 0.0, 0.0, 0
    out = []

    def rhs(_s, y, d, r):
        tau_m = d * sn * math.tan(y[1])
        f = (1.0 - y[0] / tau_m) / (1.0 - r)
        i = max(0.0, math.atan(abs(y[0]) / sn) - phi_b)
        return [d * ks * f, -(y[1] - phi_b) * (1.0 - f) / roughness, 1.0 - f, (1.0 - f) * math.tan(i)]

    def advance(state, start, end):
        if end == start:
            return state
        sol = solve_ivp(rhs, (0.0, abs(end - start)), state, method="DOP853", args=(d, r),
                        rtol=1e-13, atol=[1e-12 * sn, 1e-15, 1e-18, 1e-18])
        return sol.y[:, -1]

    for b in samples:
        while True:
            if d == 0:
                d = int(np.sign(turning_points[0] if turning_points else b)) or 1
            if k < len(turning_points) and (d * (b - turning_points[k]) > 0 or d * (b - pos) < 0):
                state = advance(state, pos, turning_points[k])
                pos, d, k = turning_points[k], -d, k + 1
                r = min(state[0] / (d * sn * math.tan(state[1])), 0.75)
                continue
            state = advance(state, pos, b)
            pos = b
            break
        out.append(state.copy())
    return np.array(out)


@CY
def test_program_agrees_with_an_independent_double_precision_integration():
    # A cycle 0 -> 2 mm -> -2 mm -> 0 (CY-CYCLIC), sampled sparsely: every branch of the model
    # (peak, softening, reversal, dilation on and off, tau through zero).
    tps = (2.0 * L, -2.0 * L)
    t = np.linspace(0.0, 1.0, 41)
    us = 2.0 * L * np.sin(2.0 * np.pi * t)
    expected = _integrate_cy_with_scipy(us, tps, **SOFT)
    got = np.column_stack([_cy(us, c, turning_points=tps) for c in ("tau", "phi_eff_deg", "us_p", "opening")])
    assert np.allclose(got[:, 0], expected[:, 0], rtol=0.0, atol=1e-9 * SN)
    assert np.allclose(np.radians(got[:, 1]), expected[:, 1], rtol=0.0, atol=1e-11)
    assert np.allclose(got[:, 2], expected[:, 2], rtol=0.0, atol=1e-11 * L)
    assert np.allclose(got[:, 3], expected[:, 3], rtol=0.0, atol=1e-11 * L)
    assert got[:, 3].max() > 1e-2 * L                       # the opening is exercised


@CY
def test_error_estimates_are_far_below_double_precision():
    # The standard case: 500 samples of the CY-CYCLIC path (two reversals).
    tps = (2.0 * L, -2.0 * L)
    us = 2.0 * L * np.sin(2.0 * np.pi * np.linspace(0.0, 1.0, 500))
    tau = _cy(us, "tau", turning_points=tps)
    scale = {"tau": np.abs(tau).max(), "opening": _cy(us, "opening", turning_points=tps).max(),
             "us_p": _cy(us, "us_p", turning_points=tps).max(), "phi_eff_deg": 45.0}
    for component, size in scale.items():
        err = _cy_error(us, component, turning_points=tps)
        assert np.all(err >= 0.0)
        assert err.max() < 1e-25 * size, component
    # A genuine comparison of two runs, not a column of zeros.
    assert _cy_error(us, "tau", turning_points=tps).max() > 0.0


@CY
def test_samples_behind_with_no_turning_point_left_are_refused():
    with pytest.raises(ValueError, match="behind"):
        _cy([0.0, 2.0 * L, 1.0 * L], "tau")
    # The same samples with a turning point in between are a valid path.
    assert _cy([0.0, 2.0 * L, 1.0 * L], "tau", turning_points=(2.0 * L,)).shape == (3,)


@CY
@pytest.mark.parametrize("bad", [dict(ks=0.0), dict(sn=-1e6), dict(phi_deg=0.0), dict(phi_deg=90.0),
                                 dict(phi0_deg=20.0), dict(phi0_deg=90.0), dict(roughness=0.0)])
def test_bad_cy_parameters_raise(bad):
    with pytest.raises(ValueError):
        _cy([0.0, L], "tau", {**SOFT, **bad})


@CY
def test_bad_cy_component_and_samples_raise():
    with pytest.raises(ValueError, match="component"):
        _cy([0.0, L], "normal_stress")
    with pytest.raises(ValueError):
        _cy([0.0, np.nan], "tau")


@CY
@pytest.mark.parametrize("args, named", [
    (["--ks", "-1", "--sn", "1e6", "--phi", "30", "--phi0", "45", "--roughness", "5e-4"], "--ks"),
    (["--ks", "1e9", "--sn", "abc", "--phi", "30", "--phi0", "45", "--roughness", "5e-4"], "--sn"),
    (["--ks", "1e9", "--sn", "1e6", "--phi", "30", "--phi0", "25", "--roughness", "5e-4"], "--phi0"),
    (["--ks", "1e9", "--sn", "1e6", "--phi", "30", "--phi0", "45"], "--roughness"),
    (["--ks", "1e9", "--sn", "1e6", "--phi", "30", "--phi0", "45", "--roughness", "5e-4",
      "--friction", "30"], "--friction"),
    (["--ks", "1e9", "--sn", "1e6", "--phi", "30", "--phi0", "45", "--roughness", "5e-4",
      "--turning-points", "1e-3,2e-3"], "--turning-points"),
])
def test_bad_command_line_option_exits_2_naming_it(args, named):
    done = _run_program(*args)
    assert done.returncode == 2
    assert named in done.stderr
    assert done.stdout == ""


@CY
def test_bad_stdin_line_exits_2_naming_it():
    args = ["--ks=1e9", "--sn=1e6", "--phi=30", "--phi0=45", "--roughness=5e-4"]
    done = _run_program(*args, stdin="0\n0.001\nnot-a-number\n")
    assert done.returncode == 2 and "stdin line 3" in done.stderr
    ok = _run_program(*args, stdin="0\n0.001\n")
    assert ok.returncode == 0 and len(ok.stdout.splitlines()) == 2
    assert all(len(line.split()) == 9 for line in ok.stdout.splitlines())


@CY
def test_program_lookup(monkeypatch, tmp_path):
    found = jt.cy_reference_executable()
    monkeypatch.setenv("VDEC_CY_REFERENCE", found)
    monkeypatch.setenv("VDEC_EXECUTABLE", str(tmp_path / "vdec"))
    assert jt.cy_reference_executable() == found          # the explicit path wins
    monkeypatch.delenv("VDEC_CY_REFERENCE")
    monkeypatch.setenv("VDEC_EXECUTABLE", os.path.join(os.path.dirname(found), "vdec"))
    assert jt.cy_reference_executable() == found          # beside vdec, where the build puts it
    monkeypatch.setenv("VDEC_EXECUTABLE", str(tmp_path / "vdec"))
    with pytest.raises(FileNotFoundError, match="VDEC_EXECUTABLE"):
        jt.cy_reference_executable()                       # nothing beside this vdec
    monkeypatch.delenv("VDEC_EXECUTABLE")
    with pytest.raises(FileNotFoundError, match="VDEC_CY_REFERENCE"):
        jt.cy_reference_executable()
    monkeypatch.setenv("VDEC_CY_REFERENCE", str(tmp_path / "missing"))
    with pytest.raises(FileNotFoundError, match="missing"):
        jt.cy_reference_executable()


# ---------------------------------------------------------------- normal closure

# CY-CLOSURE: kn0 = 1 GPa/m, an = 1e6, en = 0.5: s* = (1e9/1e6)^2 = 1 MPa, un* = 1 mm.
CLOSE = dict(kn0=1e9, an=1e6, en=0.5)


def _closure_params(en, s_star=1e6, kn0=1e9):
    """an chosen so that an sn^en overtakes kn0 at s_star."""
    return dict(kn0=kn0, an=kn0 / s_star**en, en=en)


@CLOSURE
def test_closure_known_values():
    # By hand: up to 1 mm sn = 1e9 un; at 2 mm (1e6^0.5 + 1e6 x 0.5 x 1e-3)^2 = 1500^2 = 2.25 MPa.
    sn = jt.continuously_yielding_normal_closure([0.0, 0.5e-3, 1e-3, 2e-3], **CLOSE)
    assert np.allclose(sn, [0.0, 0.5e6, 1e6, 2.25e6], rtol=1e-14, atol=0.0)
    assert jt.continuously_yielding_closure_of_stress(2.25e6, **CLOSE) == pytest.approx(2e-3, rel=1e-14, abs=0)
    # en = 1, an = kn0/s* = 1000 /m: sn = 1e6 exp(1000 (un - 1e-3)), e MPa at 2 mm.
    p1 = _closure_params(1.0)
    assert jt.continuously_yielding_normal_closure(2e-3, **p1) == pytest.approx(1e6 * math.e, rel=1e-14, abs=0)


@CLOSURE
@pytest.mark.parametrize("en", [0.2, 0.5, 0.8, 1.0])
def test_closure_solves_dsn_dun_equals_kn(en):
    p = _closure_params(en)

    def kn(sn):
        return max(p["kn0"], p["an"] * max(sn, 0.0) ** en)

    un = np.linspace(0.0, 3e-3, 61)
    sol = solve_ivp(lambda _u, s: [kn(s[0])], (0.0, un[-1]), [0.0], method="DOP853", t_eval=un,
                    rtol=1e-13, atol=1e-6)
    assert np.allclose(jt.continuously_yielding_normal_closure(un, **p), sol.y[0], rtol=1e-10, atol=1e-3)
    # And the inverse as the quadrature un(sn) = integral of dsigma / kn(sigma) from 0.
    s_star = 1e6
    for sn in (0.3e6, 1e6, 2.5e6, 7e6):
        un_q = quad(lambda s: 1.0 / kn(s), 0.0, sn, points=[s_star] if sn > s_star else None,
                    epsabs=0.0, epsrel=1e-13)[0]
        assert jt.continuously_yielding_closure_of_stress(sn, **p) == pytest.approx(un_q, rel=1e-12, abs=0)


@CLOSURE
@pytest.mark.parametrize("en", [0.2, 0.5, 1.0])
def test_closure_is_continuous_and_smooth_at_the_threshold(en):
    # At un* = s*/kn0 both the stress (s*) and the slope (kn0 = an s*^en) match.
    p = _closure_params(en)
    un_star, h = 1e-3, 1e-9
    below = jt.continuously_yielding_normal_closure(np.array([un_star - 2 * h, un_star - h, un_star]), **p)
    above = jt.continuously_yielding_normal_closure(np.array([un_star, un_star + h, un_star + 2 * h]), **p)
    assert below[-1] == pytest.approx(1e6, rel=1e-14, abs=0) and above[0] == below[-1]
    assert (3 * below[2] - 4 * below[1] + below[0]) / (2 * h) == pytest.approx(1e9, rel=1e-6, abs=0)
    assert (-3 * above[0] + 4 * above[1] - above[2]) / (2 * h) == pytest.approx(1e9, rel=1e-6, abs=0)


@CLOSURE
def test_closure_beyond_the_threshold_grows_at_kn_of_sn():
    # en = 1: d ln(sn)/d un = an exactly; en = 0.5: d sn/d un = an sn^0.5.
    un = np.linspace(1.5e-3, 4e-3, 11)
    p1 = _closure_params(1.0)
    sn1 = jt.continuously_yielding_normal_closure(un, **p1)
    assert np.allclose(np.diff(np.log(sn1)) / np.diff(un), p1["an"], rtol=1e-9)
    h = 1e-9
    sn = jt.continuously_yielding_normal_closure(un, **CLOSE)
    slope = (jt.continuously_yielding_normal_closure(un + h, **CLOSE)
             - jt.continuously_yielding_normal_closure(un - h, **CLOSE)) / (2 * h)
    assert np.allclose(slope, 1e6 * np.sqrt(sn), rtol=1e-6)


@CLOSURE
def test_closure_with_en_zero_is_linear():
    un = np.linspace(0.0, 1e-2, 11)
    # kn = max(kn0, an): the larger constant throughout.
    assert np.allclose(jt.continuously_yielding_normal_closure(un, kn0=1e9, an=2e9, en=0.0), 2e9 * un, rtol=1e-15)
    assert np.allclose(jt.continuously_yielding_normal_closure(un, kn0=1e9, an=5e8, en=0.0), 1e9 * un, rtol=1e-15)
    assert jt.continuously_yielding_closure_of_stress(4e6, kn0=1e9, an=2e9, en=0.0) == pytest.approx(2e-3, rel=1e-15, abs=0)


@CLOSURE
@pytest.mark.parametrize("en", [0.0, 0.3, 0.5, 0.99, 1.0])
def test_closure_inverse_round_trips(en):
    p = _closure_params(en) if en > 0.0 else dict(kn0=1e9, an=3e9, en=0.0)
    un = np.concatenate((np.linspace(0.0, 1e-3, 7), np.linspace(1e-3, 5e-3, 9)))
    sn = jt.continuously_yielding_normal_closure(un, **p)
    assert np.allclose(jt.continuously_yielding_closure_of_stress(sn, **p), un, rtol=1e-12, atol=0.0)
    sn_grid = np.linspace(0.0, 5e6, 21)
    back = jt.continuously_yielding_normal_closure(jt.continuously_yielding_closure_of_stress(sn_grid, **p), **p)
    assert np.allclose(back, sn_grid, rtol=1e-12, atol=0.0)
    assert np.all(np.diff(sn) >= 0.0)


@CLOSURE
@pytest.mark.parametrize("bad", [dict(kn0=0.0), dict(kn0=-1e9), dict(an=0.0), dict(en=-0.1), dict(en=1.5)])
def test_bad_closure_parameters_raise(bad):
    with pytest.raises(ValueError):
        jt.continuously_yielding_normal_closure(1e-3, **{**CLOSE, **bad})
    with pytest.raises(ValueError):
        jt.continuously_yielding_closure_of_stress(1e6, **{**CLOSE, **bad})


@CLOSURE
def test_closure_outside_the_domain_raises():
    with pytest.raises(ValueError, match="closure"):
        jt.continuously_yielding_normal_closure([1e-3, -1e-6], **CLOSE)
    with pytest.raises(ValueError, match="normal stress"):
        jt.continuously_yielding_closure_of_stress(-1.0, **CLOSE)


@CY
def test_block_rise_is_the_elastic_closure_plus_the_opening():
    us = np.linspace(0.0, 10.0 * L, 201)
    rise = jt.continuously_yielding_block_rise(us, kn=2e9, **SOFT)
    opening = _cy(us, "opening")
    assert rise[0] == -SN / 2e9
    assert np.allclose(rise - opening, -SN / 2e9, rtol=0.0, atol=1e-18)
    assert opening[-1] > 1e-2 * L
    with pytest.raises(ValueError, match="kn"):
        jt.continuously_yielding_block_rise(us, kn=0.0, **SOFT)

"""Closed-form references for elastic waves at a boundary: plane P and SV waves meeting a
Lysmer-Kuhlemeyer viscous boundary at oblique incidence, and a vertically incident S wave
amplified by a uniform layer on an elastic half-space (one-dimensional site response).

Independent of the solver: only math and numpy are used, and every formula is derived here from
the plane-wave solutions of the elastic wave equation and the boundary or interface conditions;
the sources named give the classical results these reduce to.

Conventions common to the module. Isotropic linear elasticity, plane strain. c_p = alpha and
c_s = beta are the P and S speeds, alpha / beta = sqrt(2 (1 - nu) / (1 - 2 nu)). Angles are
measured from the boundary's NORMAL (0 = normal incidence, 90 = grazing), in degrees in every
parameter whose name ends in _deg. Harmonic quantities carry the time factor exp(+i w t) (the
engineering convention of Kramer 1996): a phase phi > 0 is an advance, a reflected wave
Re(R exp(i w t)) for an incident Re(exp(i w t)). Amplitude ratios are ratios of displacement
and equally of particle velocity (one frequency). Energy ratios are ratios of time-averaged
energy flux through the boundary (the component normal to it), per unit boundary length.
SI units; densities and speeds enter only as ratios.
"""
import math

import numpy as np


def _finite(name, value):
    try:
        number = float(value) if not isinstance(value, (bool, str)) else math.nan
    except (TypeError, ValueError):
        number = math.nan
    if not math.isfinite(number):
        raise ValueError(f"{name} = {value!r}: must be a finite number")
    return number


def _positive(name, value):
    if not _finite(name, value) > 0.0:
        raise ValueError(f"{name} = {value}: must be positive")
    return float(value)


# ---------------------------------------------------------------- oblique incidence on a viscous boundary


def speed_ratio(*, nu):
    """alpha / beta = c_p / c_s = sqrt(2 (1 - nu) / (1 - 2 nu)) of an isotropic solid of Poisson's
    ratio nu (c_p^2 = (lam + 2 G) / rho, c_s^2 = G / rho, lam / G = 2 nu / (1 - 2 nu)).
    sqrt(3) for nu = 1/4."""
    nu = _finite("nu", nu)
    if not -1.0 < nu < 0.5:
        raise ValueError(f"nu = {nu}: Poisson's ratio must lie in (-1, 1/2) for a stable isotropic solid")
    return math.sqrt(2.0 * (1.0 - nu) / (1.0 - 2.0 * nu))


def sv_critical_angle_deg(*, nu):
    """Critical angle of an incident SV wave, asin(beta / alpha) in degrees: beyond it the
    reflected P wave no longer propagates (its horizontal slowness sin(theta) / beta exceeds
    1 / alpha) but decays away from the boundary. 35.264 degrees for nu = 1/4."""
    return math.degrees(math.asin(1.0 / speed_ratio(nu=nu)))


def _vertical_slowness(p, speed):
    """Slowness normal to the boundary, into the medium, of a wave of horizontal slowness p going
    away from the boundary: sqrt(1/c^2 - p^2) >= 0 when it propagates; when p > 1/c the branch
    -i sqrt(p^2 - 1/c^2), which with exp(i w (t - p x - eta z)) decays as z grows."""
    q = 1.0 / (speed * speed) - p * p
    return complex(math.sqrt(q), 0.0) if q >= 0.0 else complex(0.0, -math.sqrt(-q))


def _p_polarisation(p, eta, alpha):
    return np.array([alpha * p, alpha * eta], dtype=complex)


def _sv_polarisation(p, eta, beta, towards_boundary):
    # Along the boundary the SV motion is counted positive for both directions (Aki & Richards'
    # choice): (cos j, -sin j) going away from the boundary, (cos j, +sin j) coming towards it.
    sign = -1.0 if towards_boundary else 1.0
    return sign * np.array([beta * eta, -beta * p], dtype=complex)


def _boundary_residuals(p, eta, d, alpha, beta, a, b):
    """(normal, tangential) dashpot-condition residuals of one plane wave of unit amplitude, over the
    common factor -i w exp(i w (t - p x)) (rho = 1, beta = 1 units; see viscous_boundary_reflection)."""
    lam, mu = alpha * alpha - 2.0 * beta * beta, beta * beta
    normal = lam * (p * d[0] + eta * d[1]) + 2.0 * mu * eta * d[1] + a * alpha * d[1]
    tangential = mu * (eta * d[0] + p * d[1]) + b * beta * d[0]
    return normal, tangential


def viscous_boundary_reflection(*, angle_deg, nu, wave="P", a=1.0, b=1.0):
    """Reflection of a plane P or SV wave by a viscous boundary (Lysmer and Kuhlemeyer 1969, J. Eng.
    Mech. Div. ASCE 95 EM4, "Finite dynamic model for infinite media"; NUREG/CR-5429 1.3-35, 1.3-36):
    the edge of an elastic half-plane that carries the dashpot tractions

        t_n = -a rho c_p v_n,    t_s = -b rho c_s v_s

    (t the traction the dashpots exert on the medium, n the OUTWARD normal, s along the boundary;
    a = b = 1 the standard boundary, a = b = 0 a free surface).

    Frame: x along the boundary, z the INWARD normal (into the medium, z > 0). The incident wave
    comes towards the boundary at angle_deg = theta from the normal, propagation direction
    (sin theta, -cos theta); horizontal slowness p = sin(theta) / c_incident (Snell). It reflects into
    a P wave along (sin theta_p, cos theta_p), sin theta_p = p alpha, and an SV wave along
    (sin theta_s, cos theta_s), sin theta_s = p beta. Polarisations (Aki & Richards, Quantitative
    Seismology, 2nd ed. 2002, ch. 5): a P wave moves along its propagation direction; an SV wave
    moves at right angles to it with its component along the boundary positive: (cos theta_s,
    sin theta_s) for an SV wave coming towards the boundary, (cos theta_s, -sin theta_s) for one
    going away. With these, a = b = 0 gives Aki & Richards' free-surface coefficients (ch. 5), complex
    conjugated for the time factor (Achenbach, Wave Propagation in Elastic Solids, 1973, ch. 5, has
    the same magnitudes).

    Derivation. Each wave is u = U d exp(i w (t - p x - eta z)), eta its slowness along z (negative
    for the incident wave, positive for the reflected ones). Its velocity is v = i w u and Hooke's law
    gives sigma_zz = -i w U [lam (p d_x + eta d_z) + 2 G eta d_z] and sigma_xz = -i w U G (eta d_x + p d_z).
    On the boundary z = 0 the traction on the medium is t = -(sigma_xz, sigma_zz), v_n = -v_z, v_s = v_x,
    so the dashpot conditions read sigma_zz = a rho alpha v_z and sigma_xz = b rho beta v_x, i.e. for the
    sum over the three waves

        sum U [lam (p d_x + eta d_z) + 2 G eta d_z + a rho alpha d_z] = 0,
        sum U [G (eta d_x + p d_z) + b rho beta d_x] = 0,

    two linear equations for the two reflected amplitudes, solved here for a unit incident one. All
    coefficients are real while every wave propagates, and independent of frequency (the dashpot
    stress and the waves' stresses are both proportional to the velocity): the reflected waves are
    then the incident waveform, whatever its shape, scaled by the ratios. At normal incidence with
    a = 1 (P) or b = 1 (SV) the dashpot stress is exactly that of the outgoing wave: no reflection.

    Energy. A plane wave of amplitude U carries the mean flux rho w^2 |U|^2 c cos(angle) / 2 =
    rho w^2 |U|^2 c^2 eta / 2 through the boundary, so each reflected wave takes |R|^2 c^2 eta /
    (c_inc^2 |eta_inc|) of the incident flux (|R_P|^2 for a P wave reflected from a P wave). The
    dashpots absorb the mean power w^2 (a rho alpha |V_z|^2 + b rho beta |V_x|^2) / 2, V the total
    boundary velocity over i w; incident = reflected + absorbed (the waves' cross terms carry no
    mean flux through the boundary: they vary with z while the net flux cannot).

    Above the critical angle of an incident SV wave (sv_critical_angle_deg, 35.26 degrees for
    nu = 1/4) the reflected P wave is evanescent: eta_p = -i sqrt(p^2 - 1/alpha^2), it decays away from
    the boundary, carries no energy through it (energy_p = 0, angle_p_deg = nan) and the ratios are
    complex: the reflected SV wave is phase-shifted (its waveform changes shape), so the signed
    real ratios are nan and only magnitude and phase (time factor exp(+i w t)) are given. A P wave
    meets no critical angle at a single boundary (beta < alpha).

    Values (a = b = 1, nu = 1/4): reflected energy 0.03 % of the incident for a P wave at 30 degrees,
    3.6 % at 60 (R_P = R_S = -(2 - sqrt 3) / 2 there), 35 % at 80; for an SV wave 3.6 % at 30, 11 % at
    60. NUREG/CR-5429 (sec. 1.3) calls the boundary "nearly totally effective" for angles of incidence
    above 30 degrees: that is the angle from the boundary plane. L&K's own curves were not available
    to compare with.

    Parameters: angle_deg in [0, 90); nu in (-1, 1/2); wave "P" or "SV"; a, b >= 0.
    Returns a dict of floats:
        reflected_p, reflected_s          signed amplitude ratios (nan where complex, see above)
        reflected_p_magnitude, reflected_s_magnitude, reflected_p_phase_deg, reflected_s_phase_deg
        energy_p, energy_s                fractions of the incident flux reflected as P and as SV
        energy_reflected                  energy_p + energy_s
        energy_absorbed                   fraction absorbed by the dashpots (from the boundary velocity)
        angle_p_deg, angle_s_deg          reflection angles from the normal (nan: evanescent)
    """
    angle_deg = _finite("angle_deg", angle_deg)
    if not 0.0 <= angle_deg < 90.0:
        raise ValueError(f"angle_deg = {angle_deg}: the angle from the boundary's normal must lie in [0, 90)")
    a, b = _finite("a", a), _finite("b", b)
    if a < 0.0 or b < 0.0:
        raise ValueError(f"a = {a}, b = {b}: dashpot factors must be >= 0 (a negative one does work on the wave)")
    if wave not in ("P", "SV"):
        raise ValueError(f"wave = {wave!r}: must be \"P\" or \"SV\"")
    theta = math.radians(angle_deg)
    alpha, beta = speed_ratio(nu=nu), 1.0  # units of beta and rho
    c_inc = alpha if wave == "P" else beta
    p = math.sin(theta) / c_inc
    eta_p, eta_s = _vertical_slowness(p, alpha), _vertical_slowness(p, beta)
    if wave == "P":
        eta_inc = -eta_p
        d_inc = _p_polarisation(p, eta_inc, alpha)
    else:
        eta_inc = -eta_s
        d_inc = _sv_polarisation(p, eta_inc, beta, towards_boundary=True)
    d_p = _p_polarisation(p, eta_p, alpha)
    d_s = _sv_polarisation(p, eta_s, beta, towards_boundary=False)
    n_p, t_p = _boundary_residuals(p, eta_p, d_p, alpha, beta, a, b)
    n_s, t_s = _boundary_residuals(p, eta_s, d_s, alpha, beta, a, b)
    n_i, t_i = _boundary_residuals(p, eta_inc, d_inc, alpha, beta, a, b)
    det = n_p * t_s - n_s * t_p
    if abs(det) == 0.0:
        raise ValueError(f"angle_deg = {angle_deg}, nu = {nu}, a = {a}, b = {b}: the boundary conditions are singular")
    r_p = (-n_i * t_s + n_s * t_i) / det   # Cramer's rule on [[n_p, n_s], [t_p, t_s]] R = -(n_i, t_i)
    r_s = (-n_p * t_i + n_i * t_p) / det

    incident_flux = c_inc * c_inc * abs(eta_inc.real)
    energy_p = abs(r_p) ** 2 * alpha * alpha * eta_p.real / incident_flux
    energy_s = abs(r_s) ** 2 * beta * beta * eta_s.real / incident_flux
    v = d_inc + r_p * d_p + r_s * d_s   # boundary velocity over i w exp(i w (t - p x))
    absorbed = (a * alpha * abs(v[1]) ** 2 + b * beta * abs(v[0]) ** 2) / incident_flux
    propagating = eta_p.imag == 0.0
    r_p, r_s = complex(r_p), complex(r_s)
    return {
        "reflected_p": r_p.real if propagating else math.nan,
        "reflected_s": r_s.real if propagating else math.nan,
        "reflected_p_magnitude": abs(r_p),
        "reflected_s_magnitude": abs(r_s),
        "reflected_p_phase_deg": math.degrees(math.atan2(r_p.imag, r_p.real)),
        "reflected_s_phase_deg": math.degrees(math.atan2(r_s.imag, r_s.real)),
        "energy_p": float(energy_p),
        "energy_s": float(energy_s),
        "energy_reflected": float(energy_p + energy_s),
        "energy_absorbed": float(absorbed),
        "angle_p_deg": math.degrees(math.asin(p * alpha)) if propagating else math.nan,
        "angle_s_deg": math.degrees(math.asin(p * beta)),
    }


# ---------------------------------------------------------------- a layer on a half-space


def _layer_parameters(H, rho1, c1, rho2, c2):
    H, rho1, c1 = _positive("H", H), _positive("rho1", rho1), _positive("c1", c1)
    rho2, c2 = _positive("rho2", rho2), _positive("c2", c2)
    return H / c1, rho1 * c1 / (rho2 * c2)


def impedance_ratio(*, rho1, c1, rho2, c2):
    """alpha_z = rho1 c1 / (rho2 c2): the layer's shear impedance over the half-space's (Kramer 1996,
    7.2). 0 for a rigid base, 1 for no contrast."""
    _, alpha_z = _layer_parameters(1.0, rho1, c1, rho2, c2)
    return alpha_z


def layer_resonance_frequency(*, H, c1, mode=1):
    """f_n = (2 n - 1) c1 / (4 H), n = mode >= 1: the peaks of layer_amplification (kH = (2n - 1) pi / 2,
    where cos kH = 0 and the amplification is 1 / alpha_z whatever the half-space)."""
    H, c1 = _positive("H", H), _positive("c1", c1)
    if isinstance(mode, bool) or not isinstance(mode, int) or mode < 1:
        raise ValueError(f"mode = {mode!r}: must be an integer >= 1")
    return (2 * mode - 1) * c1 / (4.0 * H)


def layer_transfer_function(*, frequency, H, rho1, c1, rho2, c2):
    """Complex ratio F of the surface motion of a uniform elastic layer on an elastic half-space to the
    outcrop motion, for a vertically incident S wave of the given frequency (Hz, >= 0; an array is
    accepted), time factor exp(+i w t):

        F = 1 / (cos kH + i alpha_z sin kH),   k = w / c1,   alpha_z = rho1 c1 / (rho2 c2)

    (Kramer, Geotechnical Earthquake Engineering, 1996, sec. 7.2.1, "uniform undamped soil on elastic
    rock"). The layer is 0 <= z <= H (z down from the free surface), density rho1, shear speed c1, on a
    half-space z > H (rho2, c2). The outcrop motion is twice the incident wave's: what the half-space
    alone, with a free surface at z = H, would show. Both motions are referred to the same time: the
    incident wave's at the interface z = H.

    Derivation: u = A (exp(i(wt + kz)) + exp(i(wt - kz))) in the layer satisfies the free surface
    (G du/dz = 0 at z = 0); in the half-space u = C exp(i(wt + k2 (z - H))) + D exp(i(wt - k2 (z - H))),
    C the incident (upgoing) wave. Continuity of u and of G du/dz at z = H give C + D = 2 A cos kH and
    C - D = 2 i A alpha_z sin kH (G1 k / (G2 k2) = alpha_z), so C = A (cos kH + i alpha_z sin kH), and
    surface / outcrop = 2 A / 2 C.
    """
    tau, alpha_z = _layer_parameters(H, rho1, c1, rho2, c2)
    f = np.asarray(frequency, dtype=float)
    if np.any(~(f >= 0.0)) or np.any(~np.isfinite(f)):
        raise ValueError(f"frequency = {frequency}: must be finite and >= 0 (Hz)")
    kh = 2.0 * math.pi * f * tau
    return 1.0 / (np.cos(kh) + 1j * alpha_z * np.sin(kh))


def layer_amplification(*, frequency, H, rho1, c1, rho2, c2):
    """|F| = 1 / sqrt(cos^2 kH + alpha_z^2 sin^2 kH): the amplitude of the surface motion over the outcrop
    motion (twice the incident amplitude) of layer_transfer_function. 1 at f = 0 and at f = c1 / (2H)
    multiples; 1 / alpha_z at the resonances f_n = (2n - 1) c1 / (4H). Float for a scalar frequency."""
    value = np.abs(layer_transfer_function(frequency=frequency, H=H, rho1=rho1, c1=c1, rho2=rho2, c2=c2))
    return float(value) if np.ndim(value) == 0 else value


def _sine_input(spec):
    allowed = {"amplitude", "frequency", "phase"}
    unknown = set(spec) - allowed
    if unknown or not {"amplitude", "frequency"} <= set(spec):
        raise ValueError(f"input = {spec!r}: a sine input is {{amplitude, frequency[, phase]}}"
                         + (f"; unknown key(s) {', '.join(sorted(unknown))}" if unknown else ""))
    amplitude = _finite("input.amplitude", spec["amplitude"])
    frequency = _positive("input.frequency", spec["frequency"])
    phase = _finite("input.phase", spec.get("phase", 0.0))
    return lambda s: amplitude * np.sin(2.0 * math.pi * frequency * s + phase)


def layer_surface_velocity(t, *, H, rho1, c1, rho2, c2, input, input_depth=0.0):
    """Surface velocity history of a uniform elastic layer on an elastic half-space (the set-up of
    layer_transfer_function) under a vertically incident S wave, as the finite sum of its multiple
    reflections, exact for any input:

        v_surface(t) = (4 / (1 + alpha_z)) sum_{n >= 0} R^n v_in(t - D / c2 - (2n + 1) H / c1),
        R = (alpha_z - 1) / (alpha_z + 1),

    the sum over the n with t - D / c2 - (2n + 1) H / c1 >= 0. "input" is v_in(t), the particle velocity of the
    INCIDENT (upgoing) wave where it is given: at the interface z = H (input_depth = 0), or at
    input_depth = D > 0 below it in the half-space, where it passes D / c2 earlier, so that the sum
    uses v_in(t - D / c2). The second is how a vdec model carries it: the half-space is a block of its
    material under the layer on a viscous base (whose dashpots take that block's impedance rho2 c2)
    at depth D below the interface, with input_velocity v_in. The incident wave starts at t = 0 where
    it is given: v_in is taken as 0 before, and only evaluated at times >= 0. The outcrop motion (at
    the interface's time) is 2 v_in(t - D / c2).

    Derivation (1D S waves, impedances Z = rho c, velocity amplitudes): an upgoing wave crossing from
    the half-space into the layer is transmitted with T = 2 Z2 / (Z1 + Z2) = 2 / (1 + alpha_z); at the
    free surface it reflects with +1 and the surface moves at twice the upgoing wave's velocity; a
    downgoing wave in the layer reflects at the base with R = (Z1 - Z2) / (Z1 + Z2) = (alpha_z - 1) /
    (alpha_z + 1) (continuity of velocity and of shear stress at the interface, a wave's shear stress
    being -Z v going down and +Z v going up, z down; R = -1 on a rigid base, 0 without contrast). Note
    the sign: (1 - alpha_z) / (1 + alpha_z) is the ratio of the STRESSES of those waves, or the
    reflection of an upgoing wave in the half-space. Each round trip takes 2 H / c1.
    Summing the geometric series for v_in = exp(i w t) gives layer_transfer_function times 2 v_in.
    Cost: one evaluation of v_in per round trip up to max(t); terms stop when R^n underflows.

    t: times (s), float or array. input: a callable v_in(s) taking a numpy array of times >= 0, or
    {"amplitude": A, "frequency": f, "phase": phi (default 0)}, the sine A sin(2 pi f s + phi) switched
    on at s = 0 (vdec's sine history times an input_velocity A).
    input_depth: D >= 0 (m), see above.
    Returns the surface velocity, float for a scalar t.
    """
    tau, alpha_z = _layer_parameters(H, rho1, c1, rho2, c2)
    depth = _finite("input_depth", input_depth)
    if depth < 0.0:
        raise ValueError(f"input_depth = {depth}: the depth below the interface must be >= 0")
    delay = depth / c2
    if callable(input):
        incident = input
    elif isinstance(input, dict):
        incident = _sine_input(input)
    else:
        raise ValueError(f"input = {input!r}: give a callable v_in(t) or {{amplitude, frequency[, phase]}}")
    times = np.asarray(t, dtype=float)
    if not np.all(np.isfinite(times)):
        raise ValueError("t: times must be finite")
    reflection = (alpha_z - 1.0) / (alpha_z + 1.0)
    transmission = 4.0 / (1.0 + alpha_z)
    total = np.zeros(times.shape)
    latest = float(np.max(times)) if times.size else 0.0
    weight, n = 1.0, 0
    while delay + (2 * n + 1) * tau <= latest and weight != 0.0:
        shifted = times - delay - (2 * n + 1) * tau
        arrived = shifted >= 0.0
        values = np.asarray(incident(np.where(arrived, shifted, 0.0)), dtype=float)
        total += weight * np.where(arrived, np.broadcast_to(values, times.shape), 0.0)
        weight *= reflection
        n += 1
    total *= transmission
    return float(total) if total.ndim == 0 else total


def viscous_boundary_p_pulse_velocity(t, *, angle_deg, nu, c_p, amplitude, width, distance, component, dt=0.0):
    """Velocity of a point of a standard viscous boundary (a = b = 1) as a plane Gaussian P pulse
    passes it at angle_deg from the boundary's normal, in the frame of viscous_boundary_reflection
    (x along the boundary, z the inward normal): the incident particle velocity
    amplitude g d, d = (sin theta, -cos theta), g = exp(-((distance - c_p t) / width)^2) (the pulse's
    centre `distance` upstream of the point along d at t = 0), plus the reflected P and SV waves,
    which leave the point with the same waveform (the ratios are real below any critical angle):

        v = amplitude g (d + R_P (sin theta_p, cos theta_p) + R_S (cos theta_s, -sin theta_s)).

    component "x" (along the boundary) or "z" (inward normal). dt > 0 evaluates at t - dt / 2: the
    velocity a central-difference history records at t is that of the half step before."""
    theta = math.radians(_finite("angle_deg", angle_deg))
    reflection = viscous_boundary_reflection(angle_deg=angle_deg, nu=nu, wave="P")
    theta_p = math.radians(reflection["angle_p_deg"])
    theta_s = math.radians(reflection["angle_s_deg"])
    direction = np.array([math.sin(theta), -math.cos(theta)])
    total = (direction + reflection["reflected_p"] * np.array([math.sin(theta_p), math.cos(theta_p)])
             + reflection["reflected_s"] * np.array([math.cos(theta_s), -math.sin(theta_s)]))
    if component not in ("x", "z"):
        raise ValueError(f"component = {component!r}: use 'x' or 'z'")
    t = np.asarray(t, dtype=float) - 0.5 * _finite("dt", dt)
    g = np.exp(-((_finite("distance", distance) - _positive("c_p", c_p) * t) / _positive("width", width)) ** 2)
    return amplitude * g * total[0 if component == "x" else 1]


def viscous_boundary_p_amplitude_ratio(*, angle_deg, nu, component):
    """The boundary's velocity over the incident wave's, per component, as a plane P wave meets a
    standard viscous boundary (a = b = 1) at angle_deg from its normal: (d + R_P e_P + R_S e_S)_k / d_k
    (viscous_boundary_p_pulse_velocity's factor over the incident one's), k = "x" along the
    boundary or "z" along the normal. 1 for both at normal incidence; a boundary that reflected
    nothing would give 1 at every angle."""
    reflection = viscous_boundary_reflection(angle_deg=angle_deg, nu=nu, wave="P")
    theta, theta_p, theta_s = (math.radians(a) for a in (angle_deg, reflection["angle_p_deg"], reflection["angle_s_deg"]))
    if component == "x":
        incident = math.sin(theta)
        reflected = reflection["reflected_p"] * math.sin(theta_p) + reflection["reflected_s"] * math.cos(theta_s)
    elif component == "z":
        incident = -math.cos(theta)
        reflected = reflection["reflected_p"] * math.cos(theta_p) - reflection["reflected_s"] * math.sin(theta_s)
    else:
        raise ValueError(f"component = {component!r}: use 'x' or 'z'")
    if incident == 0.0:
        raise ValueError("the incident wave has no velocity along that component at this angle")
    return (incident + reflected) / incident


def viscous_boundary_p_reflected_energy(*, boundary_x, incident_x, boundary_z, incident_z, angle_deg, nu):
    """The share of a plane P wave's energy flux that a boundary reflects, recovered from what a
    model records at a point of the boundary: the peak velocities along the boundary (x) and the
    normal (z) there (boundary_*) and those of the same incident wave at the same point in a model
    without the boundary (incident_*). Their ratios give d + R_P e_P + R_S e_S component by
    component (the polarisations of viscous_boundary_reflection, the reflected waves at the angles
    Snell's law gives), a 2 x 2 system for R_P and R_S; the reflected share of the flux is then
    R_P^2 + R_S^2 (c_s cos theta_s) / (c_p cos theta). Both peaks of a component are taken with
    the sign that makes them positive (so the ratio is that of the signed amplitudes when the
    reflection does not reverse the component). Compared with viscous_boundary_reflection's
    energy_reflected, it tests the reflection coefficients of a model's boundary directly."""
    if not 0.0 < _finite("angle_deg", angle_deg) < 90.0:
        raise ValueError("angle_deg must lie in (0, 90): at normal incidence the x component carries nothing")
    reflection = viscous_boundary_reflection(angle_deg=angle_deg, nu=nu, wave="P")
    theta, theta_p, theta_s = (math.radians(a) for a in (angle_deg, reflection["angle_p_deg"], reflection["angle_s_deg"]))
    d = np.array([math.sin(theta), -math.cos(theta)])
    total = d * np.array([boundary_x / incident_x, boundary_z / incident_z])
    basis = np.array([[math.sin(theta_p), math.cos(theta_s)], [math.cos(theta_p), -math.sin(theta_s)]])
    r_p, r_s = np.linalg.solve(basis, total - d)
    return float(r_p ** 2 + r_s ** 2 * (math.cos(theta_s) / (speed_ratio(nu=nu) * math.cos(theta))))

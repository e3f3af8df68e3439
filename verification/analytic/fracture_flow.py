"""Closed-form references for fluid flow in rock joints (parallel-plate flow, pressure diffusion,
Bingham grout) and an independent steady solve of a network of joints.

Independent of the solver: only math, numpy and scipy are used, and every formula is either taken
from the cited text or derived here from two relations, mass conservation along the joint and the
parallel-plate (Poiseuille) velocity profile.

Geometry. A joint is a slot between two parallel walls, aperture a (m), along a coordinate x from
its mouth (x = 0); flows are per unit out-of-plane width (m^2/s, volumes m^3/m = m^2).

Sign conventions: fluid pressure p POSITIVE IN COMPRESSION; normal stresses on joints (sn, the
total and effective normal stresses of the hydrostatic column) also positive in compression, as
is usual for joints; aperture opening positive. A flow rate q is positive in the direction of
decreasing pressure for the single-joint laws (q = C * pressure drop), +x along a joint, and from
the link's first domain to its second in the network solve. A gradient J is the pressure drop per
unit length (Pa/m), positive in the flow direction.
SI units throughout: Pa, m, s, Pa s (dynamic viscosity mu), Pa (fluid bulk modulus Kw), Pa/m
(joint normal stiffness kn), kg/m^3, m/s^2. Arguments are keyword-only, except the independent
variable of a function a verification problem plots against (t, x, aperture, pressure, gradient,
depth), which comes first and may be given by position or by name (the harness calls a series
reference as f(x, **params) and a field reference as f(x=..., **params)). The single-joint
functions accept numpy arrays (broadcast together) and return arrays (0-d for scalar input).
Nonsensical input (non-positive aperture, viscosity, length, modulus or stiffness; t <= 0; a point
outside the joint) raises ValueError naming the argument.

Sources. NUREG/CR-5429 Vol. 1 (UDEC), 1.4.2.4 and 1.4.2.7: the cubic law 1.4-3, the threshold
gradient of a Bingham fluid 1.4-6 (J0 = 2 tau_y / a), the point-contact law 1.4-7 (q = kc dp)
and the joint law 1.4-8 (q = kj a^3 dp / l, kj = 1 / (12 mu)); the linear Bingham law is its
Fig. 1.4-3 (no flow below J0, the Newtonian slope above it). The reference's Buckingham equation
1.4-5 is the one for a circular pipe (bracket 1 - 4/3 r + 1/3 r^4); between plates the bracket is
1 - 3/2 r + 1/2 r^3, derived in buckingham_flow. Transient diffusion: H. S. Carslaw and
J. C. Jaeger, Conduction of Heat in Solids, 2nd ed., 1959, ch. II (the semi-infinite solid: the
erfc solution) and ch. III (the slab: Fourier and image series). Bingham slit flow: the standard
result (e.g. R. B. Bird, G. C. Dai and B. J. Yarusso, The rheology and flow of viscoplastic
materials, Rev. Chem. Eng. 1 (1983) 1-70); the same law in the form used for grouting,
dI/dt = (b^2 |dp/dx| / 12 mu) [1 - 3 (Z/b) + 4 (Z/b)^3] with Z = tau_0 / |dp/dx| and b the
aperture, and the maximum penetration I_max = dp b / (2 tau_0), are eqs. (2) and (3) of
G. Gustafson, J. Claesson and A. Fransson, Steering parameters for rock grouting, J. Appl. Math.
2013, 269594 (Z / b = J0 / (2 |J|), so their bracket is ours). The grout penetration histories
are derived here.
"""
import math

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl
from scipy.optimize import brentq
from scipy.sparse.csgraph import connected_components
from scipy.special import erfc

# Series truncation: terms are dropped once their exponential factor is below exp(-_SERIES_EXPONENT)
# = 4e-18 of the leading term, far below the 1e-12 the references promise; rounding (~1e-15) then
# limits the accuracy.
_SERIES_EXPONENT = 40.0
# Below this dimensionless time D t / L^2 the image (erfc) series is summed, above it the Fourier
# series: both need at most a handful of terms there (the image series' second term is
# erfc(1 / sqrt(0.1)) = 8e-6 of the first and the Fourier series' ninth exp(-64 pi^2 0.1) = 4e-28).
_SERIES_SWITCH_TAU = 0.1


def _arr(x):
    return np.asarray(x, dtype=float)


def _positive(name, value, unit):
    v = _arr(value)
    if np.any(~(v > 0.0)):
        raise ValueError(f"{name} = {value} {unit}: must be positive")
    return v


def _positive_or_inf(name, value, unit):
    v = _arr(value)
    if np.any(~(v > 0.0)):
        raise ValueError(f"{name} = {value} {unit}: must be positive (math.inf for a rigid joint)")
    return v


def _finite(name, value, unit):
    v = _arr(value)
    if np.any(~np.isfinite(v)):
        raise ValueError(f"{name} = {value} {unit}: must be finite")
    return v


# ---------------------------------------------------------------- steady laws of one joint


def cubic_law_conductance(*, aperture, viscosity, length):
    """C = a^3 / (12 mu L) (m^2 / (Pa s)): the flow per unit width per unit pressure drop of a
    joint of length L, so that q = C dp (UDEC 1.4-8 with kj = 1 / (12 mu)).

    Poiseuille flow between parallel plates: the velocity profile u(y) = J (a^2/4 - y^2) / (2 mu)
    across the slot (|y| <= a/2, J = dp / L) integrates to q = a^3 J / (12 mu)."""
    a = _positive("aperture", aperture, "m")
    mu = _positive("viscosity", viscosity, "Pa s")
    L = _positive("length", length, "m")
    return a ** 3 / (12.0 * mu * L)


def cubic_law_flow(aperture, *, viscosity, length, pressure_drop):
    """q = a^3 dp / (12 mu L) (m^2/s), the cubic law (UDEC 1.4-3, 1.4-8), positive from the high
    to the low pressure end; dp = p_upstream - p_downstream of either sign."""
    return cubic_law_conductance(aperture=aperture, viscosity=viscosity, length=length) * \
        _finite("pressure_drop", pressure_drop, "Pa")


def point_contact_flow(pressure_drop, *, permeability):
    """q = kc dp (UDEC 1.4-7): the flow through a point contact (corner-edge or corner-corner),
    kc (m^2 / (Pa s)) the contact permeability, a property of the contact and not of an
    aperture; kc >= 0 (0 seals the contact)."""
    kc = _arr(permeability)
    if np.any(~(kc >= 0.0)) or np.any(~np.isfinite(kc)):
        raise ValueError(f"permeability = {permeability} m^2/(Pa s): must be finite and >= 0")
    return kc * _finite("pressure_drop", pressure_drop, "Pa")


# ---------------------------------------------------------------- transient pressure diffusion


def joint_storage(*, aperture, fluid_bulk_modulus, normal_stiffness=math.inf):
    """S (m/Pa): the fluid volume a joint takes in per unit joint area (length x out-of-plane
    width) per unit rise of pressure,

        S = a / Kw                 rigid joint (normal_stiffness = math.inf),
        S = a / Kw + 1 / kn        deformable joint whose aperture opens by dp / kn.

    Derivation. The fluid mass per unit joint area is rho a. Its rate of change is
    d(rho a)/dt = rho (a / rho drho/dt + da/dt); with the fluid's compressibility
    drho / rho = dp / Kw and the joint's elastic opening da = dp / kn (effective normal stress
    sn - p, kn its stiffness, sn held) this is rho (a / Kw + 1 / kn) dp/dt. Mass conservation
    along the joint, d(rho a)/dt + d(rho q)/dx = 0 with rho nearly uniform (dp / Kw << 1), is
    then S dp/dt = -dq/dx. Linearised: the opening is small against a (dp / kn << a), so a and
    the conductance a^3 / (12 mu) are taken constant."""
    a = _positive("aperture", aperture, "m")
    kw = _positive("fluid_bulk_modulus", fluid_bulk_modulus, "Pa")
    kn = _positive_or_inf("normal_stiffness", normal_stiffness, "Pa/m")
    return a / kw + 1.0 / kn


def joint_transmissivity(*, aperture, viscosity):
    """T = a^3 / (12 mu) (m^3 / (Pa s)): q = -T dp/dx, the cubic law per unit gradient."""
    a = _positive("aperture", aperture, "m")
    mu = _positive("viscosity", viscosity, "Pa s")
    return a ** 3 / (12.0 * mu)


def hydraulic_diffusivity(*, aperture, viscosity, fluid_bulk_modulus, normal_stiffness=math.inf):
    """D = T / S (m^2/s), T = a^3 / (12 mu), S = joint_storage: S dp/dt = -dq/dx with
    q = -T dp/dx is the diffusion equation dp/dt = D d2p/dx2. Rigid joint: D = a^2 Kw / (12 mu);
    deformable: D = (a^3 / (12 mu)) / (a / Kw + 1 / kn)."""
    return joint_transmissivity(aperture=aperture, viscosity=viscosity) / joint_storage(
        aperture=aperture, fluid_bulk_modulus=fluid_bulk_modulus, normal_stiffness=normal_stiffness)


def _diffusion_constants(aperture, viscosity, fluid_bulk_modulus, normal_stiffness):
    T = joint_transmissivity(aperture=aperture, viscosity=viscosity)
    S = joint_storage(aperture=aperture, fluid_bulk_modulus=fluid_bulk_modulus,
                      normal_stiffness=normal_stiffness)
    return T, S, T / S


def _step(p0, p1):
    """(p0, p1 - p0) as arrays, both finite."""
    p0 = _finite("p0", p0, "Pa")
    return p0, _finite("p1", p1, "Pa") - p0


def _time(t):
    t = _arr(t)
    if np.any(~(t > 0.0)) or np.any(~np.isfinite(t)):
        raise ValueError(f"t = {t} s: the time since the pressure step must be positive and finite")
    return t


def step_pressure_semi_infinite(t, *, x, p0, p1, aperture, viscosity, fluid_bulk_modulus,
                                normal_stiffness=math.inf):
    """p(x, t) = p0 + (p1 - p0) erfc(x / (2 sqrt(D t))) (Pa): a semi-infinite joint (x >= 0) at
    pressure p0 whose mouth is raised to p1 at t = 0 and held there; D = hydraulic_diffusivity.

    The similarity solution of dp/dt = D d2p/dx2 with p(0, t) = p1, p(x, 0) = p0,
    p(inf, t) = p0 (Carslaw & Jaeger ch. II)."""
    x = _arr(x)
    if np.any(~(x >= 0.0)):
        raise ValueError(f"x = {x} m: a point of the joint lies at x >= 0 from its mouth")
    t = _time(t)
    _, _, D = _diffusion_constants(aperture, viscosity, fluid_bulk_modulus, normal_stiffness)
    p0, rise = _step(p0, p1)
    return p0 + rise * erfc(x / (2.0 * np.sqrt(D * t)))


def step_inflow_rate_semi_infinite(t, *, p0, p1, aperture, viscosity, fluid_bulk_modulus,
                                   normal_stiffness=math.inf):
    """q(0, t) = T (p1 - p0) / sqrt(pi D t) = S (p1 - p0) sqrt(D / (pi t)) (m^2/s): the flow
    into the mouth of the semi-infinite joint, -T dp/dx at x = 0 of step_pressure_semi_infinite
    (d erfc(z)/dz = -2 exp(-z^2) / sqrt(pi))."""
    t = _time(t)
    T, _, D = _diffusion_constants(aperture, viscosity, fluid_bulk_modulus, normal_stiffness)
    _, rise = _step(p0, p1)
    return T * rise / np.sqrt(math.pi * D * t)


def step_inflow_volume_semi_infinite(t, *, p0, p1, aperture, viscosity, fluid_bulk_modulus,
                                     normal_stiffness=math.inf):
    """V(t) = 2 S (p1 - p0) sqrt(D t / pi) (m^2): the volume per unit width that has entered
    the mouth by time t, the time integral of step_inflow_rate_semi_infinite; equal to the
    stored volume S * integral (p - p0) dx, as integral_0^inf erfc(x / (2 sqrt(D t))) dx =
    2 sqrt(D t / pi)."""
    t = _time(t)
    _, S, D = _diffusion_constants(aperture, viscosity, fluid_bulk_modulus, normal_stiffness)
    _, rise = _step(p0, p1)
    return 2.0 * S * rise * np.sqrt(D * t / math.pi)


def _since(t, start_time):
    """t - start_time, the time since the step (checked positive by the caller's _time)."""
    return _arr(t) - _finite("start_time", start_time, "s")


_FAR_ENDS = ("fixed", "impermeable")


def _finite_joint_setup(far_end, series, length, t, aperture, viscosity, fluid_bulk_modulus,
                        normal_stiffness):
    if far_end not in _FAR_ENDS:
        raise ValueError(f"far_end = {far_end!r}: must be 'fixed' (held at p0) or 'impermeable'")
    if series not in ("auto", "fourier", "images"):
        raise ValueError(f"series = {series!r}: must be 'auto', 'fourier' or 'images'")
    L = _positive("length", length, "m")
    t = _time(t)
    T, S, D = _diffusion_constants(aperture, viscosity, fluid_bulk_modulus, normal_stiffness)
    tau = D * t / (L * L)
    if series == "auto":
        use_fourier = tau >= _SERIES_SWITCH_TAU
    else:
        use_fourier = np.full(tau.shape, series == "fourier")
    return L, T, S, tau, use_fourier


def _fourier_modes(far_end, tau):
    """Eigenvalues lam_n of the slab (u(0) = 0 and u(1) = 0 or u'(1) = 0), enough of them that
    exp(-lam^2 tau) of the last one is below exp(-_SERIES_EXPONENT) for the smallest tau."""
    lam_max = math.sqrt(_SERIES_EXPONENT / float(np.min(tau)))
    if far_end == "fixed":
        count = int(math.ceil(lam_max / math.pi)) + 1
        return math.pi * np.arange(1, count + 1)
    count = int(math.ceil(lam_max / math.pi + 0.5)) + 1
    return math.pi * (np.arange(count) + 0.5)


def _image_count(tau):
    """Image pairs m = 0 .. M such that exp(-m^2 / tau) of the first dropped one is below
    exp(-_SERIES_EXPONENT) for the largest tau."""
    return int(math.ceil(math.sqrt(_SERIES_EXPONENT * float(np.max(tau))))) + 2


def _finite_profile(far_end, xi, tau, use_fourier):
    """u = (p - p0) / (p1 - p0) at xi = x / L, tau = D t / L^2 (arrays of one shape)."""
    u = np.empty(np.broadcast(xi, tau).shape)
    xi, tau, use_fourier = np.broadcast_to(xi, u.shape), np.broadcast_to(tau, u.shape), \
        np.broadcast_to(use_fourier, u.shape)
    if np.any(use_fourier):
        xs, ts = xi[use_fourier][:, None], tau[use_fourier][:, None]
        lam = _fourier_modes(far_end, ts)[None, :]
        if far_end == "fixed":
            u[use_fourier] = 1.0 - xs[:, 0] - np.sum(2.0 / lam * np.sin(lam * xs) * np.exp(-lam ** 2 * ts), axis=1)
        else:
            u[use_fourier] = 1.0 - np.sum(2.0 / lam * np.sin(lam * xs) * np.exp(-lam ** 2 * ts), axis=1)
    images = ~use_fourier
    if np.any(images):
        xs, ts = xi[images][:, None], tau[images][:, None]
        n = np.arange(_image_count(ts))[None, :]
        scale = 1.0 / (2.0 * np.sqrt(ts))
        near, far = erfc((2 * n + xs) * scale), erfc((2 * n + 2 - xs) * scale)
        if far_end == "fixed":
            u[images] = np.sum(near - far, axis=1)
        else:
            u[images] = np.sum((-1.0) ** n * (near + far), axis=1)
    return u


def _finite_mouth_flux(far_end, tau, use_fourier, cumulative):
    """-du/dxi at xi = 0 (cumulative=False) or its integral over tau from 0 (True)."""
    out = np.empty(tau.shape)
    if np.any(use_fourier):
        ts = tau[use_fourier][:, None]
        lam = _fourier_modes(far_end, ts)[None, :]
        decay = np.exp(-lam ** 2 * ts)
        steady = 1.0 if far_end == "fixed" else 0.0
        if cumulative:
            # integral of steady + 2 sum exp(-lam^2 s) ds = steady tau + 2 sum (1 - exp(-lam^2 tau)) / lam^2,
            # and 2 sum 1 / lam^2 is 1/3 (fixed: 2 / pi^2 * pi^2 / 6) or 1 (impermeable: 8 / pi^2 * pi^2 / 8).
            total = 1.0 / 3.0 if far_end == "fixed" else 1.0
            out[use_fourier] = steady * ts[:, 0] + total - np.sum(2.0 * decay / lam ** 2, axis=1)
        else:
            out[use_fourier] = steady + np.sum(2.0 * decay, axis=1)
    images = ~use_fourier
    if np.any(images):
        ts = tau[images][:, None]
        m = np.arange(1, _image_count(ts) + 1)[None, :]
        sign = 1.0 if far_end == "fixed" else (-1.0) ** m
        root = np.sqrt(ts)
        if cumulative:
            # integral_0^tau exp(-m^2/s) / sqrt(pi s) ds = 2 sqrt(tau/pi) exp(-m^2/tau) - 2 m erfc(m / sqrt(tau))
            one = 2.0 * root / math.sqrt(math.pi)
            terms = one * np.exp(-m ** 2 / ts) - 2.0 * m * erfc(m / root)
            out[images] = one[:, 0] + np.sum(2.0 * sign * terms, axis=1)
        else:
            out[images] = (1.0 + np.sum(2.0 * sign * np.exp(-m ** 2 / ts), axis=1)) / np.sqrt(math.pi * ts[:, 0])
    return out


def step_pressure_finite(t, *, x, p0, p1, length, far_end, aperture, viscosity,
                         fluid_bulk_modulus, normal_stiffness=math.inf, series="auto", start_time=0.0):
    """p(x, t) (Pa) in a joint 0 <= x <= L at p0 whose mouth is raised to p1 at t = 0, the far end
    x = L either held at p0 (far_end = "fixed") or closed (far_end = "impermeable").

    With u = (p - p0) / (p1 - p0), xi = x / L, tau = D t / L^2 (D = hydraulic_diffusivity) the
    problem is u_tau = u_xixi, u(0) = 1, u(xi, 0) = 0 and u(1) = 0 or u_xi(1) = 0. Separation of
    variables (Carslaw & Jaeger ch. III) gives

        fixed:        u = 1 - xi - sum_{n>=1} (2 / lam_n) sin(lam_n xi) exp(-lam_n^2 tau),  lam_n = n pi
        impermeable:  u = 1 -      sum_{k>=0} (2 / lam_k) sin(lam_k xi) exp(-lam_k^2 tau),  lam_k = (k + 1/2) pi

    and the method of images (reflections of the erfc solution in xi = 0 and xi = 1)

        fixed:        u = sum_{n>=0} [erfc((2n + xi) / (2 sqrt tau)) - erfc((2n + 2 - xi) / (2 sqrt tau))]
        impermeable:  u = sum_{n>=0} (-1)^n [erfc((2n + xi) / (2 sqrt tau)) + erfc((2n + 2 - xi) / (2 sqrt tau))].

    series="auto" sums the image series for tau < 0.1 and the Fourier series above, each until a
    term's exponential factor falls below exp(-40) = 4e-18 (at most ten terms in either range), so
    truncation error is far below 1e-12 and rounding (~1e-15 relative to p1 - p0) limits the
    accuracy; "fourier" or "images" forces one series at every tau (the number of terms grows
    as 1 / sqrt(tau) or sqrt(tau)), which the tests use to check one against the other.
    start_time: the time of the step on the clock of t (a run whose flow starts after a phase
    that settles the blocks); the solution is taken at t - start_time.
    """
    L, _, _, tau, use_fourier = _finite_joint_setup(far_end, series, length, _since(t, start_time), aperture,
                                                    viscosity, fluid_bulk_modulus, normal_stiffness)
    x = _arr(x)
    if np.any(~((x >= 0.0) & (x <= L))):
        raise ValueError(f"x = {x} m: a point of the joint lies in [0, length = {length}] m")
    p0, rise = _step(p0, p1)
    return p0 + rise * _finite_profile(far_end, x / L, tau, use_fourier)


def step_inflow_rate_finite(t, *, p0, p1, length, far_end, aperture, viscosity, fluid_bulk_modulus,
                            normal_stiffness=math.inf, series="auto"):
    """q(0, t) = -T dp/dx at the mouth (m^2/s) of step_pressure_finite, T = a^3 / (12 mu):
    q = (T (p1 - p0) / L) F(tau) with

        fixed:        F = 1 + 2 sum_{n>=1} exp(-n^2 pi^2 tau)            = (1 + 2 sum_{m>=1} exp(-m^2 / tau)) / sqrt(pi tau)
        impermeable:  F = 2 sum_{k>=0} exp(-(k + 1/2)^2 pi^2 tau)        = (1 + 2 sum_{m>=1} (-1)^m exp(-m^2 / tau)) / sqrt(pi tau)

    (Fourier form, then image form; series as in step_pressure_finite). At short times both
    become the semi-infinite joint's T (p1 - p0) / sqrt(pi D t); at long times the fixed end
    carries the steady cubic-law flow T (p1 - p0) / L and the closed end none."""
    L, T, _, tau, use_fourier = _finite_joint_setup(far_end, series, length, t, aperture, viscosity,
                                                    fluid_bulk_modulus, normal_stiffness)
    _, rise = _step(p0, p1)
    return T * rise / L * _finite_mouth_flux(far_end, tau, use_fourier, cumulative=False)


def step_inflow_volume_finite(t, *, p0, p1, length, far_end, aperture, viscosity, fluid_bulk_modulus,
                              normal_stiffness=math.inf, series="auto", start_time=0.0):
    """V(t) (m^2): the volume per unit width that has entered the mouth by time t, the integral
    of step_inflow_rate_finite, V = S (p1 - p0) L G(tau) (T / D = S) with G the integral of F:

        fixed:        G = tau + 1/3 - 2 sum_{n>=1} exp(-n^2 pi^2 tau) / (n pi)^2
        impermeable:  G = 1 - 2 sum_{k>=0} exp(-lam_k^2 tau) / lam_k^2,  lam_k = (k + 1/2) pi
        images:       G = 2 sqrt(tau/pi) + 2 sum_{m>=1} s_m [2 sqrt(tau/pi) exp(-m^2/tau) - 2 m erfc(m / sqrt tau)],

    s_m = 1 (fixed) or (-1)^m (impermeable); 1/3 and 1 are the sums 2 sum 1 / lam^2. A closed
    joint ends full, V = S (p1 - p0) L. Through a fixed far end V tends to
    (T (p1 - p0) / L) t + S (p1 - p0) L / 3: the joint stores S (p1 - p0) L / 2 (the linear
    profile) and the far end's outflow lags the steady rate by S (p1 - p0) L / 6. start_time as
    in step_pressure_finite."""
    L, _, S, tau, use_fourier = _finite_joint_setup(far_end, series, length, _since(t, start_time), aperture,
                                                    viscosity, fluid_bulk_modulus, normal_stiffness)
    _, rise = _step(p0, p1)
    return S * rise * L * _finite_mouth_flux(far_end, tau, use_fourier, cumulative=True)


# ---------------------------------------------------------------- pressure-dependent aperture


def _deformable_inlet_aperture(p_in, p_out, outlet_aperture, normal_stiffness):
    a_out = _positive("outlet_aperture", outlet_aperture, "m")
    kn = _positive("normal_stiffness", normal_stiffness, "Pa/m")
    a_in = a_out + (_finite("p_in", p_in, "Pa") - _finite("p_out", p_out, "Pa")) / kn
    if np.any(~(a_in > 0.0)):
        raise ValueError(f"p_in = {p_in} Pa, p_out = {p_out} Pa: the inlet aperture "
                         f"a_out + (p_in - p_out) / kn = {a_in} m closes the joint; raise p_in or a_out")
    return a_in, a_out, kn


def deformable_joint_steady_flow(*, p_in, p_out, outlet_aperture, normal_stiffness, viscosity, length):
    """q = kn (a_in^4 - a_out^4) / (48 mu L) (m^2/s): steady flow along a joint of length L whose
    aperture follows the pressure, a(p) = a_out + (p - p_out) / kn, from x = 0 (p_in) to x = L
    (p_out); a_in = a(p_in).

    Set-up for which it holds: every point of the joint carries the same, constant total normal
    stress sn and closes elastically under its effective stress, a = a0 - (sn - p) / kn (a0 the
    aperture at zero effective stress, kn the joint normal stiffness, Pa/m, constant; a stays
    above any residual aperture, so a_out = a0 - (sn - p_out) / kn > a_res). Then dp = kn da
    pointwise. The aperture varies along the joint as a fourth root, which one rigid block
    cannot follow: in a block model the joint is the base of a row of short blocks, each free to
    move normal to the joint (held against sliding and rotation) and loaded by sn on its top, on
    a fixed block; the row's domain pressures tend to p(x) as the blocks shorten.
    Derivation: steady flow has one q along the joint, q = -(a^3 / (12 mu)) dp/dx (cubic law with
    the local aperture); dp = kn da gives q = -(kn a^3 / (12 mu)) da/dx, i.e.
    d(a^4)/dx = -48 mu q / kn, so a^4 falls linearly from a_in^4 to a_out^4:
    q = kn (a_in^4 - a_out^4) / (48 mu L). As kn -> inf it is the cubic law with a = a_out."""
    a_in, a_out, kn = _deformable_inlet_aperture(p_in, p_out, outlet_aperture, normal_stiffness)
    mu = _positive("viscosity", viscosity, "Pa s")
    L = _positive("length", length, "m")
    return kn * (a_in ** 4 - a_out ** 4) / (48.0 * mu * L)


def deformable_joint_steady_profile(x, *, p_in, p_out, outlet_aperture, normal_stiffness, viscosity, length):
    """(a(x), p(x)) of deformable_joint_steady_flow: a(x) = [a_in^4 - 48 mu q x / kn]^(1/4)
    = [a_in^4 - (a_in^4 - a_out^4) x / L]^(1/4) and p(x) = p_out + kn (a(x) - a_out)."""
    a_in, a_out, kn = _deformable_inlet_aperture(p_in, p_out, outlet_aperture, normal_stiffness)
    _positive("viscosity", viscosity, "Pa s")
    L = _positive("length", length, "m")
    x = _arr(x)
    if np.any(~((x >= 0.0) & (x <= L))):
        raise ValueError(f"x = {x} m: a point of the joint lies in [0, length = {length}] m")
    a4_in = a_in ** 4
    a = (a4_in - (a4_in - a_out ** 4) * x / L) ** 0.25
    return a, _arr(p_out) + kn * (a - a_out)


# ---------------------------------------------------------------- hydraulic jacking


def jacking_aperture(pressure, *, closed_aperture, normal_stress, normal_stiffness):
    """Hydraulic aperture (m) of a joint under total normal stress sn (compression positive)
    against its fluid pressure p:

        a = a0                       p <= sn
        a = a0 + (p - sn) / kn       p >  sn.

    Model: the joint's walls are in contact while the pressure is below the total normal stress
    (positive effective stress sn - p), and its hydraulic aperture there is a0, independent of
    the contact stress (e.g. the residual aperture of a closed joint); once p exceeds sn the
    walls separate and the excess pressure p - sn is carried by the elastic restraint of the
    surrounding rock, of stiffness kn (Pa/m) per unit joint area, so the walls part by
    (p - sn) / kn."""
    a0 = _positive("closed_aperture", closed_aperture, "m")
    kn = _positive("normal_stiffness", normal_stiffness, "Pa/m")
    p = _finite("pressure", pressure, "Pa")
    sn = _finite("normal_stress", normal_stress, "Pa")
    return a0 + np.maximum(p - sn, 0.0) / kn


# ---------------------------------------------------------------- hydrostatics


def hydrostatic_pressure(depth_below_table, *, water_density, g):
    """p = rho_w g d (Pa) at depth d below a free water table; 0 above it (d < 0: the joints
    are dry, no suction). Fluid at rest: dp/dz = -rho_w g, p = 0 at the table."""
    d = _finite("depth_below_table", depth_below_table, "m")
    rho = _positive("water_density", water_density, "kg/m^3")
    gv = _positive("g", g, "m/s^2")
    return rho * gv * np.maximum(d, 0.0)


def column_joint_stresses(depth, *, rock_density, water_density, g, table_depth=0.0, surcharge=0.0):
    """(total, pressure, effective) normal stress (Pa, compression positive) on a horizontal
    joint at `depth` below the top of a column of blocks of density rho_r, with a water table
    `table_depth` below the top (negative: water stands above the top):

        total     = rho_r g depth + rho_w g max(-table_depth, 0) + surcharge
        pressure  = rho_w g max(depth - table_depth, 0)          (hydrostatic_pressure)
        effective = total - pressure.

    Vertical equilibrium of the column above the joint: the joints have negligible aperture, so
    the blocks fill the column and carry their own weight, that of any water standing on top and
    the surcharge (Pa); the total stress is shared between the fluid pressure in the joint and
    the effective (contact) stress, Terzaghi's principle. The total pressure is returned; the
    reference's buoyancy formulation (UDEC 1.4.2.7) instead carries p - rho_w g depth in its
    domains and applies the hydrostatic part as buoyancy of the blocks, which leaves the
    effective stress the same."""
    depth = _arr(depth)
    if np.any(~(depth >= 0.0)) or np.any(~np.isfinite(depth)):
        raise ValueError(f"depth = {depth} m: the joint lies at a finite depth >= 0 below the top")
    rho_r = _positive("rock_density", rock_density, "kg/m^3")
    rho_w = _positive("water_density", water_density, "kg/m^3")
    gv = _positive("g", g, "m/s^2")
    table = _finite("table_depth", table_depth, "m")
    total = rho_r * gv * depth + rho_w * gv * np.maximum(-table, 0.0) + _finite("surcharge", surcharge, "Pa")
    pressure = hydrostatic_pressure(depth_below_table=depth - table, water_density=rho_w, g=gv)
    return total, pressure, total - pressure


# ---------------------------------------------------------------- Bingham fluid


def bingham_threshold_gradient(*, aperture, yield_stress):
    """J0 = 2 tau_y / a (Pa/m), UDEC 1.4-6: the force balance on the fluid between the plates,
    J a = 2 tau_y (pressure drop per length times aperture against the wall shear stress on
    both walls), is where the wall stress reaches the yield stress and flow can start."""
    a = _positive("aperture", aperture, "m")
    tau = _arr(yield_stress)
    if np.any(~(tau >= 0.0)) or np.any(~np.isfinite(tau)):
        raise ValueError(f"yield_stress = {yield_stress} Pa: must be finite and >= 0")
    return 2.0 * tau / a


def bingham_linear_flow(gradient, *, aperture, viscosity, yield_stress):
    """The reference's law (UDEC Fig. 1.4-3): no flow while |J| <= J0, the Newtonian slope on
    the excess above it,

        q = sign(J) (a^3 / (12 mu)) (|J| - J0)    |J| > J0,     q = 0 otherwise,

    J the pressure drop per unit length (Pa/m), J0 = bingham_threshold_gradient. It is Bingham
    flow's asymptote shifted: the exact slit law (buckingham_flow) approaches
    (a^3 / (12 mu)) (|J| - 3/2 J0), not |J| - J0."""
    J0 = bingham_threshold_gradient(aperture=aperture, yield_stress=yield_stress)
    J = _finite("gradient", gradient, "Pa/m")
    T = joint_transmissivity(aperture=aperture, viscosity=viscosity)
    return np.sign(J) * T * np.maximum(np.abs(J) - J0, 0.0)


def buckingham_flow(gradient, *, aperture, viscosity, yield_stress):
    """Bingham flow between parallel plates (Buckingham's equation for a slit):

        q = sign(J) (a^3 |J| / (12 mu)) (1 - 3/2 r + 1/2 r^3),   r = J0 / |J| < 1;   q = 0 for r >= 1.

    Derivation (slit flow of a Bingham fluid): across the slot (|y| <= a/2) the shear
    stress is tau = J y. The fluid is rigid where |tau| <= tau_y, a plug |y| <= y0 = tau_y / |J|,
    and flows with mu du/dy = -(J y - tau_y sign(y)) outside it. With u = 0 at the walls,
    u(y) = (J / (2 mu)) ((a/2)^2 - y^2) - (tau_y / mu)(a/2 - |y|) for y0 <= |y| <= a/2 and
    u(y0) in the plug. Integrating u over the slot gives the bracket above with
    r = y0 / (a/2) = J0 / |J|; the plug fills the slot at r = 1, J = J0 (UDEC 1.4-6). Same law
    as Gustafson et al. (2013) eq. (3), whose Z / b is r / 2."""
    J0 = bingham_threshold_gradient(aperture=aperture, yield_stress=yield_stress)
    J = _finite("gradient", gradient, "Pa/m")
    T = joint_transmissivity(aperture=aperture, viscosity=viscosity)
    magnitude = np.abs(J)
    flowing = magnitude > J0
    r = np.where(flowing, J0 / np.where(flowing, magnitude, 1.0), 1.0)
    # 1 - 3/2 r + 1/2 r^3 = (1 - r)^2 (2 + r) / 2, without the cancellation near the threshold
    return np.where(flowing, np.sign(J) * T * magnitude * (1.0 - r) ** 2 * (2.0 + r) / 2.0, 0.0)


# ---------------------------------------------------------------- grout penetration

_GROUT_LAWS = ("linear", "buckingham")
# Below this relative penetration the two laws' dimensionless times are summed as power series
# (their closed forms lose digits to cancellation there: both are I_D^2 / 4 + ...); 40 terms leave
# a remainder below 0.1^40 times the leading one.
_SERIES_BELOW = 0.1
_SERIES_TERMS = 40
# Brent's method's tightest relative tolerance (scipy refuses less than 4 eps).
_BRENT_RTOL = 4.0 * np.finfo(float).eps


def grout_max_penetration(*, aperture, overpressure, yield_stress):
    """I_max = dp a / (2 tau_y) (m), Gustafson et al. (2013) eq. (2): the grout front stops
    where the gradient over the grouted length, dp / I, has fallen to the threshold
    J0 = 2 tau_y / a (both laws: neither flows at J0)."""
    a = _positive("aperture", aperture, "m")
    dp = _positive("overpressure", overpressure, "Pa")
    tau = _positive("yield_stress", yield_stress, "Pa")
    return dp * a / (2.0 * tau)


def grout_time_scale(*, viscosity, overpressure, yield_stress):
    """t0 = 6 mu dp / tau_y^2 (s): the time unit of grout_dimensionless_time, t_D = t / t0.
    The aperture cancels: t0 = 12 mu dp / (a^2 J0^2) with J0 = 2 tau_y / a."""
    mu = _positive("viscosity", viscosity, "Pa s")
    dp = _positive("overpressure", overpressure, "Pa")
    tau = _positive("yield_stress", yield_stress, "Pa")
    return 6.0 * mu * dp / (tau * tau)


# c_k of 2 t_D = sum_{k>=0} c_k x^(k+2) / (k+2): the Taylor coefficients of the integrand divided
# by x, 1 / (1 - x) (linear: all 1) or 1 / ((1 - x)^2 (1 + x/2)) (Buckingham: the Cauchy product of
# sum (j+1) x^j and sum (-1/2)^j x^j).
_SERIES_POWERS = np.arange(_SERIES_TERMS) + 2
_SERIES_COEFFICIENTS = {
    "linear": np.ones(_SERIES_TERMS),
    "buckingham": np.array([sum((j + 1) * (-0.5) ** (n - j) for j in range(n + 1)) for n in range(_SERIES_TERMS)]),
}


def _twice_dimensionless_time(x, law):
    """2 t_D(x) for 0 <= x < 1, x = I / I_max (scalar)."""
    if x < _SERIES_BELOW:
        return float(np.sum(_SERIES_COEFFICIENTS[law] * x ** _SERIES_POWERS / _SERIES_POWERS))
    if law == "linear":
        return -x - math.log1p(-x)
    return 2.0 / 3.0 * x / (1.0 - x) + 4.0 / 9.0 * (math.log1p(-x) - math.log1p(0.5 * x))


def _twice_dimensionless_time_near_refusal(y, law):
    """2 t_D as a function of y = 1 - x, for the front near I_max (x >= 1/2), where x / (1 - x)
    and ln(1 - x) are better computed from y itself."""
    if law == "linear":
        return -(1.0 - y) - math.log(y)
    return 2.0 / 3.0 * (1.0 - y) / y + 4.0 / 9.0 * math.log(2.0 * y / (3.0 - y))


def _check_law(law):
    if law not in _GROUT_LAWS:
        raise ValueError(f"law = {law!r}: must be 'linear' (the reference's) or 'buckingham'")


def grout_dimensionless_time(relative_penetration, *, law):
    """t_D = t / t0 (t0 = grout_time_scale) at which the grout front reaches I_D = I / I_max,
    grouting from a borehole into a planar joint (1D, parallel plates of aperture a) under a
    constant overpressure dp over the water pressure ahead of the front.

    Derivation. The grout is incompressible and fills 0 <= x <= I, so the flow q is uniform
    behind the front and so is the gradient, J = dp / I; the front advances at dI/dt = q / a.
    With J0 = 2 tau_y / a, I_max = dp / J0 and r = J0 / J = I / I_max = I_D:

      linear law:  q = (a^3 / (12 mu)) (J - J0), so dI/dt = (a^2 J0 / (12 mu)) (1 - I_D) / I_D and
                   c dt = I_D dI_D / (1 - I_D), c = a^2 J0^2 / (12 mu dp) = tau_y^2 / (3 mu dp) = 2 / t0.
                   Integrated from I_D = 0 at t = 0: c t = -I_D - ln(1 - I_D), i.e.

                       t_D = 0.5 [-I_D - ln(1 - I_D)]

                   (the form quoted for the linear law; this derivation confirms it with t0 as defined).
      Buckingham:  q = (a^3 J / (12 mu)) (1 - 3/2 r + 1/2 r^3) and 1 - 3/2 r + 1/2 r^3 =
                   (1 - r)^2 (2 + r) / 2, so c dt = 2 I_D dI_D / ((1 - I_D)^2 (2 + I_D)). Partial
                   fractions, 2x / ((1-x)^2 (2+x)) = -4/9 / (1-x) + 2/3 / (1-x)^2 - 4/9 / (2+x), give

                       t_D = (1/3) I_D / (1 - I_D) + (2/9) ln((1 - I_D) / (1 + I_D / 2)).

    Both start as t_D = I_D^2 / 4 (the Newtonian I = sqrt(a^2 dp t / (6 mu))); the linear law
    approaches I_max exponentially, 1 - I_D ~ exp(-1 - 2 t_D), Buckingham's only as
    1 - I_D ~ 1 / (3 t_D). Below I_D = 0.1 each is summed as its Taylor series (40 terms),
    above it evaluated in closed form, to full double precision either way."""
    _check_law(law)
    x = _arr(relative_penetration)
    if np.any(~((x >= 0.0) & (x < 1.0))):
        raise ValueError(f"relative_penetration = {relative_penetration}: I / I_max lies in [0, 1) "
                         "(the front reaches I_max only as t -> infinity)")
    flat = [0.5 * _twice_dimensionless_time(float(v), law) for v in x.ravel()]
    return np.array(flat).reshape(x.shape)


def _relative_penetration(t_dimensionless, law):
    """I_D at t_D (scalar), inverting grout_dimensionless_time by Brent's method: in x = I_D
    while the front is short of I_max / 2, else in y = 1 - I_D, so that the answer keeps full
    relative precision at both ends."""
    target = 2.0 * t_dimensionless
    if target == 0.0:
        return 0.0
    half = _twice_dimensionless_time(0.5, law)
    if target <= half:
        return brentq(lambda x: _twice_dimensionless_time(x, law) - target, 0.0, 0.5,
                      xtol=1e-300, rtol=_BRENT_RTOL, maxiter=400)
    low = 0.5
    while _twice_dimensionless_time_near_refusal(low, law) < target:
        low *= 0.5
        if low < 1e-300:          # the front is within 1e-300 of I_max: I_D rounds to 1
            return 1.0
    y = brentq(lambda y: _twice_dimensionless_time_near_refusal(y, law) - target, low, 0.5,
               xtol=1e-300, rtol=_BRENT_RTOL, maxiter=400)
    return 1.0 - y


def grout_penetration(t, *, aperture, viscosity, overpressure, yield_stress, law):
    """I(t) (m): the grout front's distance from the borehole at time t >= 0 after injection
    under constant overpressure started, I = I_max I_D(t / t0), I_D the inverse of
    grout_dimensionless_time for the chosen law ("linear" or "buckingham"), t0 =
    grout_time_scale, I_max = grout_max_penetration."""
    _check_law(law)
    t = _arr(t)
    if np.any(~(t >= 0.0)) or np.any(~np.isfinite(t)):
        raise ValueError(f"t = {t} s: the time since injection started must be finite and >= 0")
    i_max = grout_max_penetration(aperture=aperture, overpressure=overpressure, yield_stress=yield_stress)
    t0 = grout_time_scale(viscosity=viscosity, overpressure=overpressure, yield_stress=yield_stress)
    flat = [_relative_penetration(float(v) / t0, law) for v in t.ravel()]
    return i_max * np.array(flat).reshape(t.shape)


# ---------------------------------------------------------------- steady network


def _ids_to_indices(domain_ids, link_domain, which):
    index = {d: k for k, d in enumerate(domain_ids)}
    out = np.empty(len(link_domain), dtype=int)
    for n, d in enumerate(link_domain):
        if d not in index:
            raise ValueError(f"link {n}: {which} = {d!r} is not among domain_ids; "
                             "every link joins two listed domains")
        out[n] = index[d]
    return out


def _per_link(name, value, unit, links):
    v = _arr(value)
    if v.shape not in ((), (links,)):
        raise ValueError(f"{name}: one value per link ({links}) or one for all expected, got shape {v.shape}")
    bad = np.flatnonzero(np.broadcast_to(~(v > 0.0) | ~np.isfinite(v), (links,)))
    if bad.size:
        raise ValueError(f"{name}: links {list(bad)} have no finite positive value ({unit})")
    return np.broadcast_to(v, (links,)).astype(float)


def _network_input(domain_ids, fixed, fixed_pressure, source, link_from, link_to, aperture, length,
                   viscosity, yield_stress):
    ids = list(domain_ids)
    if len(set(ids)) != len(ids):
        raise ValueError("domain_ids: an id is listed twice; each domain needs its own id")
    n = len(ids)
    fixed = np.asarray(fixed, dtype=bool)
    fixed_pressure = _arr(fixed_pressure)
    source = np.zeros(n) if source is None else _arr(source)
    for name, v in (("fixed", fixed), ("fixed_pressure", fixed_pressure), ("source", source)):
        if v.shape != (n,):
            raise ValueError(f"{name}: one value per domain expected ({n}), got shape {v.shape}")
    if not np.any(fixed):
        raise ValueError("fixed: no domain has a fixed pressure, so the steady pressures are not "
                         "determined; fix the pressure of at least one domain")
    if np.any(~np.isfinite(fixed_pressure[fixed])):
        bad = [ids[k] for k in np.flatnonzero(fixed & ~np.isfinite(fixed_pressure))]
        raise ValueError(f"fixed_pressure: domains {bad} are fixed but their pressure is not finite")
    if np.any(~np.isfinite(source)):
        raise ValueError("source: every inflow must be finite")
    if np.any(fixed & (source != 0.0)):
        bad = [ids[k] for k in np.flatnonzero(fixed & (source != 0.0))]
        raise ValueError(f"source: domains {bad} have a fixed pressure and an inflow source; a fixed "
                         "pressure absorbs any inflow, so give the source to a free domain or drop it")
    i = _ids_to_indices(ids, link_from, "link_from")
    j = _ids_to_indices(ids, link_to, "link_to")
    if len(j) != len(i):
        raise ValueError(f"link_from ({len(i)}) and link_to ({len(j)}) must have one entry per link")
    if np.any(i == j):
        raise ValueError(f"links {list(np.flatnonzero(i == j))}: join a domain to itself")
    a, L = (_per_link(name, v, unit, len(i)) for name, v, unit in
            (("aperture", aperture, "m"), ("length", length, "m")))
    C = cubic_law_conductance(aperture=a, viscosity=viscosity, length=L)
    threshold = bingham_threshold_gradient(aperture=a, yield_stress=yield_stress) * L
    return ids, fixed, fixed_pressure, source, i, j, C, threshold


def _determined(n, fixed, i, j, active):
    """Per domain: is it joined to a fixed-pressure domain by active links? And the component
    labels of the active graph."""
    graph = sp.coo_matrix((np.ones(int(np.sum(active))), (i[active], j[active])), shape=(n, n))
    _, labels = connected_components(graph, directed=False)
    return np.isin(labels, np.unique(labels[fixed])), labels


def _laplacian(n, i, j, weight):
    """The weighted graph Laplacian: sum over links of weight (e_i - e_j)(e_i - e_j)^T."""
    rows = np.concatenate([i, j, i, j])
    cols = np.concatenate([i, j, j, i])
    return sp.csr_matrix((np.concatenate([weight, weight, -weight, -weight]), (rows, cols)), shape=(n, n))


def _solve_linear(n, fixed, pressure, source, i, j, C, offset, active, held):
    """Pressures of the free, not held domains from the balance at each of them,
    sum over its active links of q = C (p_i - p_j - offset) (out of i) = source."""
    unknown = ~fixed & ~held
    ca = np.where(active, C, 0.0)
    K = _laplacian(n, i, j, ca)
    rhs = source + np.bincount(i, weights=ca * offset, minlength=n) - np.bincount(j, weights=ca * offset, minlength=n)
    p = pressure.copy()
    if np.any(unknown):
        known = ~unknown
        Kuu = K[unknown][:, unknown].tocsc()
        p[unknown] = spl.spsolve(Kuu, rhs[unknown] - K[unknown][:, known] @ p[known])
    return p


# Relative slack on the Bingham law at the converged state: the linear solves' rounding on
# pressure differences (a graph Laplacian of condition up to ~1e6 times 1e-16).
_LAW_SLACK = 1e-10
# Conductance, relative to the cubic law's, that the Newton step gives links that do not flow.
_REGULARISATION = 1e-6


def _link_flows(pressure, i, j, C, threshold):
    """q = C sign(dp) max(|dp| - h, 0) per link (h = 0: the cubic law)."""
    dp = pressure[i] - pressure[j]
    return C * np.sign(dp) * np.maximum(np.abs(dp) - threshold, 0.0)


def _flowing_set(pressure, i, j, threshold):
    dp = pressure[i] - pressure[j]
    active = np.abs(dp) > threshold
    return active, np.where(active, np.sign(dp), 0.0)


def _imbalance(n, pressure, source, i, j, C, threshold):
    """Per domain: flow out through its links minus its source (the gradient of F)."""
    q = _link_flows(pressure, i, j, C, threshold)
    return np.bincount(i, weights=q, minlength=n) - np.bincount(j, weights=q, minlength=n) - source


def _regularised_newton_step(n, fixed, pressure, source, i, j, C, threshold):
    """Newton's step on F with the links that do not flow given a conductance _REGULARISATION C
    instead of none: the matrix is then positive definite on the free domains (each reaches a
    fixed one), so the step is a descent direction of F even where no link flows."""
    active, _ = _flowing_set(pressure, i, j, threshold)
    weight = np.where(active, C, _REGULARISATION * C)
    step = np.zeros(n)
    free = ~fixed
    K = _laplacian(n, i, j, weight)
    step[free] = spl.spsolve(K[free][:, free].tocsc(), -_imbalance(n, pressure, source, i, j, C, threshold)[free])
    return step


def _exact_line_search(pressure, step, source, i, j, C, threshold):
    """alpha > 0 minimising the dissipation potential F(p + alpha step), F = sum_links
    C (|dp| - h)_+^2 / 2 - sum source p. F is convex and piecewise quadratic in alpha, so its
    derivative sum q (step_i - step_j) - source . step is nondecreasing and piecewise linear:
    bracket its zero by doubling, then Brent's method."""
    along = step[i] - step[j]
    slope = lambda alpha: float(np.dot(_link_flows(pressure + alpha * step, i, j, C, threshold), along)
                                - np.dot(source, step))
    high = 1.0
    while slope(high) < 0.0:
        high *= 2.0
        if high > 1e30:
            raise RuntimeError("steady_network_flow: the dissipation potential does not grow along the "
                               "Newton step, which a network whose every domain reaches a fixed one rules out")
    if slope(0.0) >= 0.0:
        return 0.0
    return brentq(slope, 0.0, high, xtol=1e-15, rtol=_BRENT_RTOL, maxiter=200)


def _flowing_set_with_sources(n, fixed, pressure, source, i, j, threshold):
    """Step 2 of steady_network_flow: the flowing links and their signs at `pressure`, the links
    out of every stagnant group with a net source added (directed out of it for injection, into
    it for extraction), and the free domains that stay held (joined to no fixed one)."""
    active, sign = _flowing_set(pressure, i, j, threshold)
    determined, labels = _determined(n, fixed, i, j, active)
    while True:
        pending = [lab for lab in np.unique(labels[~determined]) if np.sum(source[labels == lab]) != 0.0]
        if not pending:
            return active, sign, ~fixed & ~determined
        for lab in pending:
            inside = labels == lab
            outward = 1.0 if np.sum(source[inside]) > 0.0 else -1.0
            # The links leaving the group are not flowing (the group is a component of the
            # flowing links) and exist (every domain reaches a fixed one), so each pass joins
            # the group to its neighbours and the loop ends.
            leaving = inside[i] != inside[j]
            active = active | leaving
            sign = np.where(leaving, np.where(inside[i], outward, -outward), sign)
        determined, labels = _determined(n, fixed, i, j, active)


def _bingham_steady_state(n, fixed, pressure, source, i, j, C, threshold, limit, yield_stress):
    """Steps 2-5 of steady_network_flow from the Newtonian pressures: (pressure, flow,
    stagnant, iterations)."""
    iterations = 1
    while True:
        active, sign, held = _flowing_set_with_sources(n, fixed, pressure, source, i, j, threshold)
        candidate = _solve_linear(n, fixed, pressure, source, i, j, C, sign * threshold, active, held)
        iterations += 1
        dp = candidate[i] - candidate[j]
        slack = _LAW_SLACK * max(np.max(np.abs(candidate)), np.max(threshold))
        flow = np.where(active, C * (dp - sign * threshold), 0.0)
        # A set can be obeyed by a solve that held a stagnant domain on a flowing link (held, it
        # takes any flow): the free domains must balance too, to the rounding of their flows.
        out_of = np.bincount(i, weights=flow, minlength=n) - np.bincount(j, weights=flow, minlength=n)
        balance_slack = _LAW_SLACK * max(np.max(C) * max(np.max(np.abs(candidate)), np.max(threshold)), 1e-300)
        balanced = np.all(np.abs(np.where(fixed, 0.0, out_of - source)) <= balance_slack)
        if balanced and np.all(np.where(active, sign * dp >= threshold - slack, np.abs(dp) <= threshold + slack)):
            # stagnant: joined to no fixed domain by links that flow by more than round-off
            moving = active & (sign * dp - threshold > slack)
            stagnant = ~fixed & ~_determined(n, fixed, i, j, moving)[0]
            return candidate, flow, stagnant, iterations
        if iterations >= limit:
            raise RuntimeError(f"steady_network_flow: the set of flowing links did not settle in "
                               f"{iterations} solves (Bingham, yield_stress = {yield_stress} Pa); "
                               "raise max_iterations or check the network")
        step = _regularised_newton_step(n, fixed, pressure, source, i, j, C, threshold)
        pressure = pressure + _exact_line_search(pressure, step, source, i, j, C, threshold) * step


def steady_network_flow(*, domain_ids, fixed, fixed_pressure, link_from, link_to, aperture, length,
                        viscosity, source=None, yield_stress=0.0, max_iterations=None):
    """Steady pressures and flows of a network of domains joined by flow links (joints), a
    code-to-code reference for vdec's steady solve: independent of vdec, it takes only the
    domains and apertures vdec reports.

    Input. domain_ids: hashable ids, one per domain; fixed (bool), fixed_pressure (Pa, read where
    fixed) and source (m^2/s injected into the domain, default none; only on free domains) per
    domain; per link: link_from and link_to (domain ids), hydraulic aperture (m) and length (m),
    scalars broadcast. viscosity mu (Pa s); yield_stress tau_y (Pa) > 0 makes the fluid Bingham
    with the reference's linear law (bingham_linear_flow); Buckingham's law is not offered here.

    Newtonian (tau_y = 0). Each link carries q = C (p_from - p_to), C = a^3 / (12 mu L)
    (cubic_law_conductance); each free domain balances, sum of outflows = its source. That is
    K p = s with K the weighted graph Laplacian, partitioned into free and fixed domains and
    solved with scipy.sparse (spsolve). Every free domain must be linked, through other domains,
    to a fixed one, else ValueError naming them.

    Bingham (tau_y > 0). A link flows only if |p_from - p_to| > h, h = J0 L = 2 tau_y L / a, and
    then q = C (dp - sign(dp) h). The steady state minimises the convex, piecewise-quadratic
    dissipation potential F(p) = sum_links C (|dp| - h)_+^2 / 2 - sum_domains source p over the
    free pressures (its gradient is each free domain's imbalance); its flows are unique, its
    pressures need not be. The iteration is Newton's method on the set of flowing links:
      1. start from the Newtonian pressures;
      2. take as flowing the links with |dp| > h, with the sign of their dp; free domains joined
         to no fixed one by flowing links are "stagnant": their pressure is held (a group of them
         with a net source cannot rest: its links to the rest are made flowing, out of it for
         injection, into it for extraction, until it reaches a fixed domain);
      3. solve the linear balance of that set (each flowing link a conductance C with a fixed
         offset sign * h) for the pressures p*;
      4. if p* obeys the set it was solved with, stop: every flowing link has |dp| >= h in its
         direction and every other |dp| <= h, both within 1e-10 of the largest pressure or
         threshold (the rounding of the solve; without it a link at its threshold, flowing
         nothing, can flip in and out of the set forever). That is a steady state of the law,
         and its flows (taken from the set: C (dp - sign h) or 0) balance every free domain to
         round-off;
      5. else take a damped Newton step on F from p: the matrix of the flowing links, with the
         others given 1e-6 of their conductance so that it is positive definite and the step a
         descent direction even across stagnant domains, and the step length that minimises F
         along it (an exact line search: F is piecewise quadratic along a line). Go to 2.
    Plain Newton (p = p* in step 5) cycles between sets on random networks; the line search
    makes F decrease at every step, so the iterates converge to a minimiser and step 4 then
    recognises its set. It raises RuntimeError after max_iterations passes (default
    50 + 2 * number of links; random networks of 100 links take up to ~40). Free domains not
    joined to a fixed one by links that flow (by more than round-off) are flagged "stagnant":
    the flow does not determine their pressure, which is one that satisfies their links'
    thresholds. A Newtonian network takes one solve.

    Returns a dict: "pressure" (Pa, per domain in the order of domain_ids), "link_flow"
    (m^2/s, from link_from to link_to), "boundary_inflow" (m^2/s, per domain: at a fixed domain
    the flow it sends into the network, zero elsewhere), "stagnant" (bool per domain),
    "iterations" (solves of step 3, the first Newtonian solve included). Mass balance:
    sum(boundary_inflow) + sum(source) = 0 to round-off.
    """
    mu = _positive("viscosity", viscosity, "Pa s")
    ids, fixed, fixed_pressure, source, i, j, C, threshold = _network_input(
        domain_ids, fixed, fixed_pressure, source, link_from, link_to, aperture, length, mu, yield_stress)
    n, links = len(ids), len(i)
    every_link = np.ones(links, dtype=bool)
    reached, _ = _determined(n, fixed, i, j, every_link)
    if not np.all(reached):
        raise ValueError(f"domains {[ids[k] for k in np.flatnonzero(~reached)]} are linked to no "
                         "fixed-pressure domain, so their steady pressure is not determined; link "
                         "them to one or fix the pressure of one of them")
    pressure = np.where(fixed, fixed_pressure, 0.0)
    pressure = _solve_linear(n, fixed, pressure, source, i, j, C, np.zeros(links), every_link,
                             np.zeros(n, dtype=bool))
    if np.any(threshold > 0.0):
        limit = 50 + 2 * links if max_iterations is None else int(max_iterations)
        pressure, flow, stagnant, iterations = _bingham_steady_state(
            n, fixed, pressure, source, i, j, C, threshold, limit, yield_stress)
    else:
        flow = C * (pressure[i] - pressure[j])
        stagnant, iterations = np.zeros(n, dtype=bool), 1
    out_of = np.bincount(i, weights=flow, minlength=n) - np.bincount(j, weights=flow, minlength=n)
    return {"pressure": pressure, "link_flow": flow, "boundary_inflow": np.where(fixed, out_of, 0.0),
            "stagnant": stagnant, "iterations": iterations}

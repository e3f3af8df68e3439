"""Closed-form references for rigid blocks on Coulomb joints (VERIFICATION-CATALOG, first section).

Independent of the solver: only math, numpy and scipy are used, and every formula is derived
here from the physics (or from the solver's published time-stepping equations, never its code).

Sign conventions: joint normal stress and force compression positive, normal displacement
closing positive, settlement positive downward, shear displacement positive in the direction
of loading. SI units throughout; angles in degrees where the parameter name ends in _deg.
Functions whose first argument is a time or displacement accept numpy arrays and return arrays.
"""
import math

import numpy as np
import scipy.linalg


def _tan(deg):
    return math.tan(math.radians(deg))


# ---------------------------------------------------------------- block on an accelerating base


def sliding_block_on_pulsed_base(t, *, g, phi_deg, base_acceleration, pulse_start, pulse_duration):
    """Horizontal displacement of a block resting on a horizontal Coulomb joint (friction angle
    phi, no cohesion) whose base is at rest until pulse_start, accelerates at base_acceleration
    for pulse_duration and moves on at V = base_acceleration pulse_duration (Newmark 1965, the
    rectangular acceleration pulse). The joint can give the block at most mu g, mu = tan phi: with
    a > mu g it slides, accelerating at mu g from the pulse's start until its velocity reaches V
    at t_s = pulse_start + V / (mu g), and moves with the base after that:
    x = mu g (t - t0)^2 / 2 for t0 <= t <= t_s, x(t_s) + V (t - t_s) after. With a <= mu g it
    moves with the base."""
    mu_g = _tan(phi_deg) * g
    a, t0, t1 = base_acceleration, pulse_start, pulse_duration
    if not (mu_g > 0.0 and a > 0.0 and t1 > 0.0):
        raise ValueError("friction, base acceleration and pulse duration must be positive")
    t = np.asarray(t, dtype=float)
    if a <= mu_g:
        return sliding_block_base_displacement(t, base_acceleration=a, pulse_start=t0, pulse_duration=t1)
    v = a * t1
    ts = t0 + v / mu_g
    tau = np.clip(t - t0, 0.0, None)
    return np.where(t <= ts, 0.5 * mu_g * tau * tau, 0.5 * mu_g * (ts - t0) ** 2 + v * (t - ts))


def sliding_block_base_displacement(t, *, base_acceleration, pulse_start, pulse_duration):
    """The base's displacement under the rectangular acceleration pulse: a (t - t0)^2 / 2 during
    it, then a t1^2 / 2 + V (t - t0 - t1), V = a t1."""
    a, t0, t1 = base_acceleration, pulse_start, pulse_duration
    t = np.asarray(t, dtype=float)
    tau = np.clip(t - t0, 0.0, t1)
    return 0.5 * a * tau * tau + a * t1 * np.clip(t - t0 - t1, 0.0, None)


def newmark_rectangular_pulse_slip(*, g, phi_deg, base_acceleration, pulse_duration):
    """The block's slip relative to its base once it has stopped sliding: V^2 / (2 mu g)
    (1 - mu g / a), V = a t1 (Newmark 1965); zero when a <= mu g."""
    mu_g = _tan(phi_deg) * g
    a = base_acceleration
    if a <= mu_g:
        return 0.0
    v = a * pulse_duration
    return v * v / (2.0 * mu_g) * (1.0 - mu_g / a)


# ---------------------------------------------------------------- block on an inclined joint


def _incline_net_acceleration(g, theta_deg, phi_deg, cohesion, contact_length, mass):
    """Driving minus resisting force per unit mass along the slope; 0 at limiting equilibrium."""
    th = math.radians(theta_deg)
    driving = g * math.sin(th)
    resisting = g * math.cos(th) * _tan(phi_deg) + cohesion * contact_length / mass
    net = driving - resisting
    # At theta = phi (no cohesion) the two sides agree only to round-off; limiting equilibrium
    # must read as sticking, not as a 1e-16 m/s^2 slide.
    if net <= 1e-12 * (abs(driving) + abs(resisting)):
        return 0.0
    return net


def incline_acceleration(*, g, theta_deg, phi_deg, cohesion=0.0, contact_length=1.0, mass=1.0):
    """Acceleration down the slope of a block on a joint inclined at theta:

        a = g (sin theta - cos theta tan phi) - c L / m,   and 0 when that is <= 0.

    Newton's second law along the slope with the Coulomb joint strength c L + N tan phi,
    N = m g cos theta (e.g. Meriam & Kraige, Engineering Mechanics: Dynamics, friction on an
    incline; Coulomb slip joint of NUREG/CR-5429). When the driving force does not exceed the
    strength, friction holds the block and the acceleration is zero, not negative. A net
    acceleration within 1e-12 (relative) of zero counts as limiting equilibrium, i.e. 0.
    """
    return _incline_net_acceleration(g, theta_deg, phi_deg, cohesion, contact_length, mass)


def incline_elastic_slide(*, mass, g, theta_deg, ks, contact_length):
    """Static shear displacement of a block held on a joint inclined at theta:

        us = m g sin(theta) / (ks L),

    the joint's linear shear law tau = ks us carrying the weight's component along the slope,
    tau L = m g sin(theta) (Coulomb slip joint below its strength, NUREG/CR-5429).
    """
    return mass * g * math.sin(math.radians(theta_deg)) / (ks * contact_length)


def incline_half_acceleration(*, g, theta_deg, phi_deg, cohesion=0.0, contact_length=1.0, mass=1.0):
    """a / 2: the slope of the down-slope displacement against t^2, since x = a t^2 / 2."""
    return 0.5 * incline_acceleration(g=g, theta_deg=theta_deg, phi_deg=phi_deg, cohesion=cohesion,
                                      contact_length=contact_length, mass=mass)


def incline_slides(*, g, theta_deg, phi_deg, cohesion=0.0, contact_length=1.0, mass=1.0):
    """True when m g sin theta > c L + m g cos theta tan phi (Coulomb criterion on the joint).

    Equality counts as sticking: the joint can just carry the load. Evaluated per unit mass with
    the same round-off allowance as incline_acceleration, so the two always agree.
    """
    return _incline_net_acceleration(g, theta_deg, phi_deg, cohesion, contact_length, mass) > 0.0


def incline_displacement(t, *, g, theta_deg, phi_deg, t0=0.0, cohesion=0.0, contact_length=1.0, mass=1.0):
    """Down-slope displacement of a block released from rest at t0:

        x(t) = a (t - t0)^2 / 2 for t > t0, else 0,   a = incline_acceleration(...).

    Uniform acceleration from rest (constant-acceleration kinematics).
    """
    t = np.asarray(t, dtype=float)
    a = incline_acceleration(g=g, theta_deg=theta_deg, phi_deg=phi_deg, cohesion=cohesion,
                             contact_length=contact_length, mass=mass)
    elapsed = t - t0
    return np.where(elapsed > 0.0, 0.5 * a * elapsed * elapsed, 0.0)


# ---------------------------------------------------------------- block resting on a joint


def resting_normal_force(*, mass, g):
    """Normal force of a block resting on a horizontal joint: N = m g (static equilibrium)."""
    return mass * g


def resting_settlement(*, mass, g, kn, contact_length):
    """Static closure of the joint under the block's weight: d = m g / (kn L).

    Linear joint normal law sn = kn un with sn = m g / L (Goodman-type joint; NUREG/CR-5429
    joint normal stiffness).
    """
    return mass * g / (kn * contact_length)


# ---------------------------------------------------------------- block oscillating on a joint


def oscillator_frequency(*, mass, kn, contact_length):
    """Natural angular frequency of the block on its joint spring: w = sqrt(kn L / m).

    Single-degree-of-freedom oscillator with stiffness k = kn L (e.g. Chopra, Dynamics of
    Structures, ch. 2).
    """
    return math.sqrt(kn * contact_length / mass)


def oscillator_period(*, mass, kn, contact_length):
    """Natural period T = 2 pi / w = 2 pi sqrt(m / (kn L))."""
    return 2.0 * math.pi / oscillator_frequency(mass=mass, kn=kn, contact_length=contact_length)


def oscillator_settlement_history(t, *, mass, g, kn, contact_length, alpha=0.0):
    """Settlement of a block released from rest at zero overlap onto a joint, under gravity:

        y(t) = d [1 - e^{-alpha t/2} (cos wd t + alpha / (2 wd) sin wd t)],
        d = m g / (kn L),  w^2 = kn L / m,  wd = sqrt(w^2 - alpha^2 / 4).

    Solution of y'' + alpha y' + w^2 y = g with y(0) = y'(0) = 0; mass-proportional damping
    (force -alpha m v, NUREG/CR-5429 1.3-20) is viscous damping with 2 xi w = alpha (Chopra,
    Dynamics of Structures, 2.2). Underdamped only (alpha < 2 w), else ValueError.
    """
    t = np.asarray(t, dtype=float)
    w = oscillator_frequency(mass=mass, kn=kn, contact_length=contact_length)
    if not 0.0 <= alpha < 2.0 * w:
        raise ValueError(f"alpha = {alpha} 1/s: this form needs 0 <= alpha < 2 w = {2.0 * w} (underdamped)")
    d = resting_settlement(mass=mass, g=g, kn=kn, contact_length=contact_length)
    wd = math.sqrt(w * w - alpha * alpha / 4.0)
    decay = np.exp(-0.5 * alpha * t)
    return d * (1.0 - decay * (np.cos(wd * t) + alpha / (2.0 * wd) * np.sin(wd * t)))


def log_decrement(*, alpha, mass, kn, contact_length):
    """Logarithmic decrement of the damped oscillation, ln(y_k / y_{k+1}) over one period:

        delta = 2 pi xi / sqrt(1 - xi^2),  xi = alpha / (2 w)

    (Chopra, Dynamics of Structures, 2.2.4). Needs xi < 1, else ValueError.
    """
    xi = alpha / (2.0 * oscillator_frequency(mass=mass, kn=kn, contact_length=contact_length))
    if not 0.0 <= xi < 1.0:
        raise ValueError(f"damping ratio {xi}: the decrement needs 0 <= xi < 1 (underdamped)")
    return 2.0 * math.pi * xi / math.sqrt(1.0 - xi * xi)


def rayleigh_damping_ratio(*, alpha, beta, mass, kn, contact_length):
    """Critical-damping ratio of the block's oscillation on its joint under Rayleigh damping:
    xi = alpha / (2 w) + beta w / 2 (1.3-18; Chopra, Dynamics of Structures, 11.4), with
    w = sqrt(kn L / m) the undamped frequency."""
    w = oscillator_frequency(mass=mass, kn=kn, contact_length=contact_length)
    return alpha / (2.0 * w) + beta * w / 2.0


def rayleigh_log_decrement(*, alpha, beta, mass, kn, contact_length):
    """Logarithmic decrement 2 pi xi / sqrt(1 - xi^2) with xi = rayleigh_damping_ratio."""
    xi = rayleigh_damping_ratio(alpha=alpha, beta=beta, mass=mass, kn=kn, contact_length=contact_length)
    if not 0.0 <= xi < 1.0:
        raise ValueError(f"damping ratio {xi}: the decrement needs 0 <= xi < 1 (underdamped)")
    return 2.0 * math.pi * xi / math.sqrt(1.0 - xi * xi)


def stiffness_damping_step_factor(*, beta, mass, kn, contact_length):
    """The factor by which stiffness-proportional damping beta lowers the critical step of
    central differences for a mode of frequency w = sqrt(kn L / m): sqrt(1 + xi^2) - xi with
    xi = beta w / 2 (Belytschko, Liu and Moran, Nonlinear Finite Elements, 6.2; the time-step
    note after 1.3-22)."""
    xi = 0.5 * beta * oscillator_frequency(mass=mass, kn=kn, contact_length=contact_length)
    return math.sqrt(1.0 + xi * xi) - xi


def stiffness_damped_critical_step(*, beta, mass, kn, contact_length, fraction=1.0):
    """Critical step of central differences for the block's mode on its joint under
    stiffness-proportional damping beta: dt_c = (2 / w) (sqrt(1 + xi^2) - xi), xi = beta w / 2,
    w = sqrt(kn L / m); times `fraction` (the step of a run set to that fraction of it).

    The solver's viscous force acts on the velocity of the half step just ended (the contact
    stage takes the displacement increment of the last motion stage), so, per unit mass,

        v_{n+1/2} = v_{n-1/2} - dt w^2 (x_n + beta v_{n-1/2}),   x_{n+1} = x_n + dt v_{n+1/2}.

    Eliminating v, with W = w dt: x_{n+1} - (2 - W^2 - 2 xi W) x_n + (1 - 2 xi W) x_{n-1} = 0. Its
    root lambda = -1 appears when 4 - W^2 - 4 xi W = 0, i.e. W = 2 (sqrt(1 + xi^2) - xi)
    (Belytschko, Liu and Moran, Nonlinear Finite Elements, 6.2; the time-step note after
    NUREG/CR-5429 1.3-22); see stiffness_damped_growth_per_step for the roots on either side.
    """
    w = oscillator_frequency(mass=mass, kn=kn, contact_length=contact_length)
    return fraction * 2.0 / w * stiffness_damping_step_factor(beta=beta, mass=mass, kn=kn, contact_length=contact_length)


def stiffness_damped_growth_per_step(*, w_dt, xi):
    """Largest modulus of the roots of the damped recurrence of stiffness_damped_critical_step,

        lambda^2 - (2 - W^2 - 2 xi W) lambda + (1 - 2 xi W) = 0,   W = w dt,  xi = beta w / 2:

    the factor by which the amplitude of the mode's worst solution changes per step (below 1:
    stable; above 1: it grows, its energy by the square). At xi = 0 this is the undamped
    central-difference recurrence (1 for W <= 2).
    """
    if w_dt < 0.0 or xi < 0.0:
        raise ValueError(f"w dt = {w_dt}, xi = {xi}: both must be >= 0")
    b = 2.0 - w_dt * w_dt - 2.0 * xi * w_dt
    c = 1.0 - 2.0 * xi * w_dt
    disc = b * b - 4.0 * c
    if disc < 0.0:
        return math.sqrt(c)  # complex pair: |lambda|^2 = c
    root = math.sqrt(disc)
    return max(abs(0.5 * (b + root)), abs(0.5 * (b - root)))


# ---------------------------------------------------------------- the central-difference scheme itself


def central_difference_period(*, mass, kn, contact_length, dt):
    """Exact period of the undamped central-difference recurrence on the joint spring:

        T_num = 2 pi / w_num,   sin(w_num dt / 2) = w dt / 2.

    Putting y_n = e^{i n w_num dt} into y_{n+1} - 2 y_n + y_{n-1} = -(w dt)^2 y_n gives
    cos(w_num dt) = 1 - (w dt)^2 / 2, i.e. the relation above (central-difference recurrence;
    cf. Bathe, Finite Element Procedures, 9.4). The scheme is stable only for w dt < 2, where
    the roots stay on the unit circle; otherwise ValueError.
    """
    w = oscillator_frequency(mass=mass, kn=kn, contact_length=contact_length)
    if w * dt >= 2.0:
        raise ValueError(f"w dt = {w * dt} >= 2: the recurrence is unstable and has no period")
    w_num = 2.0 * math.asin(0.5 * w * dt) / dt
    return 2.0 * math.pi / w_num


def central_difference_settlement_history(t, *, mass, g, kn, contact_length, alpha, dt):
    """Exact solution of the solver's time-stepping recurrence for the block released on a joint.

    The recurrence (velocities at half steps, NUREG/CR-5429 1.3-21), with k = kn L, w^2 = k / m:

        v_{n+1/2} = [v_{n-1/2} (1 - alpha dt/2) + (g - w^2 y_n) dt] / (1 + alpha dt/2),
        y_{n+1}   = y_n + v_{n+1/2} dt,          y_0 = 0,  v_{-1/2} = 0.

    Eliminating v (with h = 1 + alpha dt/2 and y_{-1} = y_0, which is what v_{-1/2} = 0 means):

        y_{n+1} - 2 c y_n + q y_{n-1} = g dt^2 / h,
        q = (1 - alpha dt/2) / h,   c = (2 - w^2 dt^2) / (2 h).

    The fixed point is d = g / w^2. The characteristic roots of z^2 - 2 c z + q = 0 are
    r e^{+-i theta} with r = sqrt(q) and, since q - c^2 = dt^2 D / (4 h^2), D = 4 w^2 - alpha^2 - w^4 dt^2,

        tan theta = dt sqrt(D) / (2 - w^2 dt^2).

    So y_n = d + r^n (A cos n theta + B sin n theta). y_0 = 0 gives A = -d; y_1 = g dt^2 / h gives
    B = (y_1 - d + c d) / sqrt(q - c^2), which simplifies to

        B = g (dt - alpha / w^2) / sqrt(D).

    (The simplified forms avoid the cancellation in 1 - c and q - c^2 at small w dt.) Needs D > 0:
    the recurrence then oscillates and decays (D > 0 also implies alpha dt < 2, so q > 0);
    otherwise ValueError.

    t must be on the step grid, t = n dt (to round-off); it is rounded to the nearest n.

    Note: v_{-1/2} = 0 is not v(0) = 0: the start is equivalent to an initial velocity of about
    g dt / 2, so this history differs from oscillator_settlement_history by O(w dt) relative
    (the sin term B ~ d w dt / 2 at alpha = 0), not O(dt^2).
    """
    steps = np.asarray(t, dtype=float) / dt
    n = np.rint(steps)
    if np.any(np.abs(steps - n) > 1e-6):
        raise ValueError("t is not on the time-step grid t = n dt")
    if np.any(n < 0):
        raise ValueError("the recurrence starts at t = 0; negative t has no value")
    w2 = kn * contact_length / mass
    disc = 4.0 * w2 - alpha * alpha - w2 * w2 * dt * dt
    if alpha < 0.0 or disc <= 0.0:
        raise ValueError(f"alpha = {alpha}, w dt = {math.sqrt(w2) * dt}: the recurrence does not oscillate "
                         "(needs 4 w^2 - alpha^2 - w^4 dt^2 > 0 and alpha >= 0)")
    h = 1.0 + 0.5 * alpha * dt
    r = math.sqrt((1.0 - 0.5 * alpha * dt) / h)
    theta = math.atan2(dt * math.sqrt(disc), 2.0 - w2 * dt * dt)
    d = g / w2
    a_coef = -d
    b_coef = g * (dt - alpha / w2) / math.sqrt(disc)
    return d + np.power(r, n) * (a_coef * np.cos(n * theta) + b_coef * np.sin(n * theta))


# ---------------------------------------------------------------- direct shear of a joint


def coulomb_peak_strength(*, sn, cohesion, phi_deg):
    """Coulomb joint strength tau_p = c + sn tan phi (Mohr-Coulomb criterion on the joint)."""
    return cohesion + sn * _tan(phi_deg)


def coulomb_residual_strength(*, sn, phi_deg):
    """Strength after the cohesion is lost: tau_r = sn tan phi (NUREG/CR-5429 model 5,
    Coulomb slip with residual strength, after the first slip)."""
    return sn * _tan(phi_deg)


def direct_shear_constant_normal_stress(us, *, ks, sn, cohesion, phi_deg, psi_deg=0.0):
    """(tau, normal_opening) of a joint sheared monotonically (us >= 0) at constant normal stress:

        tau = ks us                     for us <= us_y = (c + sn tan phi) / ks,
        tau = c + sn tan phi            after,
        opening = (us - us_y) tan psi   for us > us_y, else 0.

    Elastic-perfectly-plastic Coulomb slip joint; dilation only during slip, at the dilation
    angle psi, on the plastic shear displacement us - us_y (NUREG/CR-5429 Coulomb slip joint
    with dilation). The opening is a normal displacement in the opening sense (positive up).
    """
    us = np.asarray(us, dtype=float)
    strength = coulomb_peak_strength(sn=sn, cohesion=cohesion, phi_deg=phi_deg)
    us_y = strength / ks
    slipping = us > us_y
    tau = np.where(slipping, strength, ks * us)
    opening = np.where(slipping, (us - us_y) * _tan(psi_deg), 0.0)
    return tau, opening


def direct_shear_block_rise(us, *, ks, kn, sn, cohesion, phi_deg, psi_deg):
    """Vertical position of a block sheared under a dead normal load on a unit-length joint,
    measured from zero overlap: the elastic closure -sn / kn plus the dilatant opening of
    direct_shear_constant_normal_stress."""
    _, opening = direct_shear_constant_normal_stress(us, ks=ks, sn=sn, cohesion=cohesion, phi_deg=phi_deg,
                                                     psi_deg=psi_deg)
    return -sn / kn + opening


def direct_shear_constant_normal_displacement(us, *, ks, kn, sn0, cohesion, phi_deg, psi_deg):
    """(tau, sn) of a joint sheared monotonically (us >= 0) with its normal displacement held.

    Elastic until yield at us_y = (c + sn0 tan phi) / ks. After yield, us = us_e + us_p with
    tau = ks us_e; the dilation us_p tan psi cannot open the held joint, so it is taken up
    elastically and sn = sn0 + kn tan psi us_p; slip keeps tau = c + sn tan phi. Solving

        ks (us - us_p) = c + (sn0 + kn tan psi us_p) tan phi

    gives us_p = ks (us - us_y) / (ks + K), K = kn tan phi tan psi, so

        tau = tau_y + (us - us_y) ks K / (ks + K),   sn = sn0 + kn tan psi us_p.

    The post-yield slope is d tau / d us = ks K / (ks + K): the joint spring ks in series with
    the dilatancy hardening K (derived here from the Coulomb slip joint with dilation).
    """
    us = np.asarray(us, dtype=float)
    tp, ts = _tan(phi_deg), _tan(psi_deg)
    us_y = (cohesion + sn0 * tp) / ks
    hardening = kn * tp * ts
    slipping = us > us_y
    us_p = np.where(slipping, ks * (us - us_y) / (ks + hardening), 0.0)
    sn = sn0 + kn * ts * us_p
    tau = np.where(slipping, ks * (us - us_p), ks * us)
    return tau, sn


def direct_shear_coulomb_fracture(us, *, ks, sn, cohesion, phi_deg):
    """Model 5 (Coulomb slip with residual strength) sheared monotonically at constant sn:

        tau = ks us          while ks us <= c + sn tan phi,
        tau = sn tan phi     after the peak (the cohesion is lost at the first slip).

    The drop is abrupt: once past the peak, the elastic part ks us exceeds the residual strength,
    so the joint slides at sn tan phi.
    """
    us = np.asarray(us, dtype=float)
    peak = coulomb_peak_strength(sn=sn, cohesion=cohesion, phi_deg=phi_deg)
    residual = coulomb_residual_strength(sn=sn, phi_deg=phi_deg)
    return np.where(ks * us <= peak, ks * us, residual)


def tensile_opening_stress(un, *, kn, tension):
    """Normal stress of a joint pulled apart monotonically (un decreasing from 0; closing positive):

        sn = kn un   while sn >= -T0, i.e. un >= -T0 / kn;   sn = 0 once broken.

    Linear normal law with tensile strength T0; a broken joint carries no tension
    (NUREG/CR-5429 joint tensile strength).
    """
    un = np.asarray(un, dtype=float)
    return np.where(un >= -tension / kn, kn * un, 0.0)


# ---------------------------------------------------------------- rigid block on two corner contacts


def rigid_block_frequencies(*, width, height, density, kn, ks, contact_length_per_corner=None):
    """Sorted natural angular frequencies [rad/s] of a rectangular rigid block (unit thickness)
    resting on a fixed base through its two bottom corners.

    Degrees of freedom (x, y, theta) at the centroid; M = diag(m, m, I), m = rho w h,
    I = m (w^2 + h^2) / 12. Each corner at (px, py) = (+-w/2, -h/2) carries a normal spring
    kn Lc along y and a shear spring ks Lc along x (Lc defaults to w / 2). A small rotation moves
    the corner by (-py theta, px theta), so the spring elongations are g . (x, y, theta) with
    g_shear = (1, 0, -py) and g_normal = (0, 1, px), and K = sum k g g^T. The shear springs sit
    below the centroid, so they couple x and theta (rocking-sliding). Solves K phi = w^2 M phi
    (small-displacement rigid-body dynamics, e.g. Clough & Penzien, Dynamics of Structures).
    """
    lc = width / 2.0 if contact_length_per_corner is None else contact_length_per_corner
    m = density * width * height
    inertia = m * (width ** 2 + height ** 2) / 12.0
    py = -height / 2.0
    stiffness = np.zeros((3, 3))
    for px in (-width / 2.0, width / 2.0):
        g_shear = np.array([1.0, 0.0, -py])
        g_normal = np.array([0.0, 1.0, px])
        stiffness += ks * lc * np.outer(g_shear, g_shear) + kn * lc * np.outer(g_normal, g_normal)
    w2 = scipy.linalg.eigh(stiffness, np.diag([m, m, inertia]), eigvals_only=True)
    # A zero stiffness (ks = 0) leaves a free mode whose eigenvalue may come out as -1e-12.
    return np.sort(np.sqrt(np.clip(w2, 0.0, None)))


def rigid_block_time_step(*, mass, kn, ks, typical_length, frac):
    """The solver's automatic time step for rigid blocks:

        dt = FRAC * 2 sqrt(M_min / K_max),   K_max = max(kn, ks) * l_typ

    (NUREG/CR-5429 1.3-28, 1.3-29), with M_min the smallest block mass (here `mass`).
    """
    return frac * 2.0 * math.sqrt(mass / (max(kn, ks) * typical_length))


def critical_frac(*, width, height, density, kn, ks, typical_length):
    """The time-step fraction FRAC at which the single block of rigid_block_frequencies becomes
    unstable.

    The solver takes dt = FRAC * 2 sqrt(M_min / K_max), K_max = max(kn, ks) l_typ
    (NUREG/CR-5429 1.3-28, 1.3-29; rigid_block_time_step), with M_min = m = rho w h here.
    Central differences are stable while w_max dt < 2, so the limit is
    FRAC = 1 / (w_max sqrt(m / K_max)).
    """
    w_max = rigid_block_frequencies(width=width, height=height, density=density, kn=kn, ks=ks)[-1]
    m = density * width * height
    dt_at_frac_one = rigid_block_time_step(mass=m, kn=kn, ks=ks, typical_length=typical_length, frac=1.0)
    return 2.0 / (w_max * dt_at_frac_one)


# ---------------------------------------------------------------- rigid block on a viscous edge


def medium_impedances(*, density, young, poisson):
    """(rho C_p, rho C_s) of an elastic medium: C_p = sqrt((K + 4 G / 3) / rho) (one-dimensional
    strain), C_s = sqrt(G / rho), K = E / (3 (1 - 2 nu)), G = E / (2 (1 + nu)) (Kolsky, Stress Waves
    in Solids; the impedances of Lysmer and Kuhlemeyer's dashpots, NUREG/CR-5429 1.3-35, 1.3-36)."""
    if not (density > 0.0 and young > 0.0 and -1.0 < poisson < 0.5):
        raise ValueError(f"density {density}, young {young}, poisson {poisson}: not an elastic medium")
    bulk = young / (3.0 * (1.0 - 2.0 * poisson))
    shear = young / (2.0 * (1.0 + poisson))
    return math.sqrt(density * (bulk + 4.0 * shear / 3.0)), math.sqrt(density * shear)


def _edge_frame(edge_from, edge_to):
    a, b = np.asarray(edge_from, dtype=float), np.asarray(edge_to, dtype=float)
    d = b - a
    length = math.hypot(d[0], d[1])
    if not length > 0.0:
        raise ValueError("the edge has no length")
    t = d / length
    return a, b, length, t, np.array([t[1], -t[0]])  # n outward: the block on the left of from -> to


def rigid_edge_dashpot_matrix(*, edge_from, edge_to, centroid, normal_impedance, shear_impedance):
    """The 3 x 3 dashpot matrix C of a viscous edge of a rigid block, on q = (vx, vy, w) at the
    centroid: the edge's force and moment about the centroid are -C q.

    A point r (from the centroid) of the edge moves at u = v + w (-r_y, r_x) = G(r) q with
    G = [[1, 0, -r_y], [0, 1, r_x]]; the dashpots' traction is -D u, D = Zn n n^T + Zs t t^T
    (Lysmer and Kuhlemeyer; n the outward normal, t the edge direction). The generalised force
    (Fx, Fy, M) of a traction T at r is G^T T (M = r_x T_y - r_y T_x), so C = int_edge G^T D G ds.
    G is linear in r and r linear along the edge, r = ra + s (rb - ra) with s in [0, 1]; the
    integral is exact from int r ds = L (ra + rb) / 2 and
    int r r^T ds = L [(ra ra^T + rb rb^T) / 3 + (ra rb^T + rb ra^T) / 6].

    For the bottom edge of a W x H rectangle (ra = (-W/2, -H/2), rb = (W/2, -H/2), L = W):
    C = [[Zs W, 0, Zs W H/2], [0, Zn W, 0], [Zs W H/2, 0, Zn W^3/12 + Zs W H^2/4]]: the shear
    dashpots, below the centroid, couple vx and w; the normal ones resist rotation by Zn W^3/12.
    """
    a, b, length, t, n = _edge_frame(edge_from, edge_to)
    c = np.asarray(centroid, dtype=float)
    ra, rb = a - c, b - c
    d = normal_impedance * np.outer(n, n) + shear_impedance * np.outer(t, t)
    mean_r = 0.5 * (ra + rb)
    second = (np.outer(ra, ra) + np.outer(rb, rb)) / 3.0 + (np.outer(ra, rb) + np.outer(rb, ra)) / 6.0
    # G(r) = [I | p(r)] with p(r) = (-r_y, r_x), linear in r: p = P r, P = [[0, -1], [1, 0]].
    rot = np.array([[0.0, -1.0], [1.0, 0.0]])
    matrix = np.zeros((3, 3))
    matrix[:2, :2] = length * d
    coupling = length * d @ rot @ mean_r
    matrix[:2, 2] = coupling
    matrix[2, :2] = coupling
    matrix[2, 2] = length * np.trace(rot.T @ d @ rot @ second)
    return matrix


def rigid_edge_input_force(*, edge_from, edge_to, centroid, normal_impedance, shear_impedance, input_velocity):
    """Generalised force (Fx, Fy, M about the centroid) of an incident wave of particle velocity
    v_in on a viscous edge: the traction 2 D v_in (Joyner and Chen 1975), uniform along the edge,
    so F = 2 L D v_in acting at the edge's midpoint. Equal to C (2 v_in, 0): a block translating
    at 2 v_in is in equilibrium with its dashpots, which is why the steady velocity is 2 v_in."""
    a, b, length, t, n = _edge_frame(edge_from, edge_to)
    vin = np.asarray(input_velocity, dtype=float)
    force = 2.0 * length * (normal_impedance * np.dot(vin, n) * n + shear_impedance * np.dot(vin, t) * t)
    r = 0.5 * (a + b) - np.asarray(centroid, dtype=float)
    return np.array([force[0], force[1], r[0] * force[1] - r[1] * force[0]])


def rectangle_mass_matrix(*, width, height, density):
    """diag(m, m, I) of a W x H rectangle (unit thickness) about its centroid: m = rho W H,
    I = m (W^2 + H^2) / 12."""
    m = density * width * height
    return np.diag([m, m, m * (width ** 2 + height ** 2) / 12.0])


_DOF = {"vx": 0, "vy": 1, "w": 2}


def _viscous_block_system(width, height, density, edge_from, edge_to, medium, initial_velocity, input_velocity):
    zn, zs = medium_impedances(**medium)
    centroid = (0.0, 0.0)  # the rectangle's own frame: vertices at (+-W/2, +-H/2)
    c = rigid_edge_dashpot_matrix(edge_from=edge_from, edge_to=edge_to, centroid=centroid, normal_impedance=zn,
                                  shear_impedance=zs)
    m = rectangle_mass_matrix(width=width, height=height, density=density)
    a = np.linalg.solve(m, c)
    q0 = np.asarray(initial_velocity, dtype=float)
    if input_velocity is None:
        return a, q0, np.zeros(3)
    f = rigid_edge_input_force(edge_from=edge_from, edge_to=edge_to, centroid=centroid, normal_impedance=zn,
                               shear_impedance=zs, input_velocity=input_velocity)
    return a, q0, np.linalg.solve(c, f)


def viscous_rigid_block_velocity(t, *, width, height, density, edge_from, edge_to, medium, initial_velocity,
                                 dof, input_velocity=None, input_frequency=None):
    """Velocity component dof ("vx", "vy" or "w") of a free W x H rigid block (no gravity, no
    contact) with one viscous edge, from q(0) = initial_velocity = (vx, vy, w):

        M dq/dt = -C q + f,   q(t) = q_s + expm(-A t) (q0 - q_s),   A = M^-1 C,  q_s = C^-1 f,

    M = rectangle_mass_matrix, C = rigid_edge_dashpot_matrix with the impedances of the medium
    beyond the edge (medium = {density, young, poisson}), f = rigid_edge_input_force of the
    incident wave input_velocity (none: f = 0). q_s = (2 v_in, 0): the block ends up moving at
    twice the incident particle velocity, without rotation. Edge points are in the rectangle's
    frame (centroid at the origin) at t = 0; the motion is linear, so the edge's rotation with the
    block (an O(rotation) change of C) is left out: valid while the block turns through a
    negligible angle.

    With input_frequency (Hz) the incident wave is v_in sin(w t), w = 2 pi input_frequency (a
    `sine` history): f becomes f sin(w t), whose steady response is q_p(t) = Im(Q e^{i w t}) with
    (i w I + A) Q = A q_s (q_s = C^-1 f as above, so M^-1 f = A q_s), and
    q(t) = q_p(t) + expm(-A t) (q0 - q_p(0))."""
    a, q0, qs = _viscous_block_system(width, height, density, edge_from, edge_to, medium, initial_velocity,
                                      input_velocity)
    t = np.asarray(t, dtype=float)
    k = _DOF[dof]
    if input_frequency is None:
        out = np.array([qs[k] + (scipy.linalg.expm(-a * float(s)) @ (q0 - qs))[k] for s in t.ravel()])
        return out.reshape(t.shape)
    w = 2.0 * math.pi * input_frequency
    amplitude = np.linalg.solve(1j * w * np.eye(3) + a, a @ qs)
    start = q0 - amplitude.imag
    out = np.array([(amplitude * np.exp(1j * w * float(s))).imag[k] + (scipy.linalg.expm(-a * float(s)) @ start)[k]
                    for s in t.ravel()])
    return out.reshape(t.shape)


def viscous_rigid_block_velocity_discrete(t, *, width, height, density, edge_from, edge_to, medium,
                                          initial_velocity, dof, dt, input_velocity=None, input_frequency=None):
    """The solver's recurrence for viscous_rigid_block_velocity: the dashpots act on the velocity
    of the half step before (the velocity given at -dt/2 is q_{-1/2}), so 1.3-21 without damping is

        q_{n+1/2} = q_{n-1/2} + dt M^-1 (f - C q_{n-1/2}),   i.e.  q_{n-1/2} = q_s + (I - dt A)^n (q0 - q_s),

    sampled at t = n dt (a block velocity sample at time t is v(t - dt/2)). t must lie on the step
    grid (to 1e-6 of a step).

    With input_frequency the load is f sin(w n dt), taken at the time of the step's start (the
    positions the dashpots act on): q_{n+1/2} = q_{n-1/2} + dt (A q_s sin(w n dt) - A q_{n-1/2}).
    Its steady response is Im(P z^n), z = e^{i w dt}, with P z = P + dt (A q_s - A P), i.e.
    ((z - 1) I + dt A) P = dt A q_s; so q_{n-1/2} = Im(P z^n) + (I - dt A)^n (q0 - Im P)."""
    a, q0, qs = _viscous_block_system(width, height, density, edge_from, edge_to, medium, initial_velocity,
                                      input_velocity)
    steps = np.asarray(t, dtype=float) / dt
    n = np.rint(steps)
    if np.any(np.abs(steps - n) > 1e-6) or np.any(n < 0):
        raise ValueError("t is not on the time-step grid t = n dt, n >= 0")
    step = np.eye(3) - dt * a
    k = _DOF[dof]
    if input_frequency is None:
        out = np.array([qs[k] + (np.linalg.matrix_power(step, int(j)) @ (q0 - qs))[k] for j in n.ravel()])
        return out.reshape(n.shape)
    z = np.exp(2j * math.pi * input_frequency * dt)
    amplitude = np.linalg.solve((z - 1.0) * np.eye(3) + dt * a, dt * (a @ qs))
    start = q0 - amplitude.imag
    out = np.array([(amplitude * z ** int(j)).imag[k] + (np.linalg.matrix_power(step, int(j)) @ start)[k]
                    for j in n.ravel()])
    return out.reshape(n.shape)


def viscous_rigid_block_decay_rates(*, width, height, density, edge_from, edge_to, medium):
    """The decay rates lambda (1/s) of the free block's modes: the eigenvalues of A = M^-1 C
    (real and >= 0: C is symmetric positive semi-definite and M positive), sorted."""
    a, _, _ = _viscous_block_system(width, height, density, edge_from, edge_to, medium, (0.0, 0.0, 0.0), None)
    return np.sort(np.linalg.eigvals(a).real)


def viscous_rigid_block_critical_step(*, width, height, density, edge_from, edge_to, medium):
    """The largest stable step of the lagged-velocity recurrence: (I - dt A)^n decays while
    |1 - dt lambda| < 1 for every decay rate, i.e. dt < 2 / lambda_max."""
    return 2.0 / viscous_rigid_block_decay_rates(width=width, height=height, density=density, edge_from=edge_from,
                                                 edge_to=edge_to, medium=medium)[-1]


def viscous_rigid_block_dissipation(*, width, height, density, edge_from, edge_to, medium, initial_velocity, dt,
                                    time):
    """Work the dashpots have taken after `time` (on the step grid) from the free block of
    viscous_rigid_block_velocity_discrete, no input: the kinetic energy lost,
    (q0^T M q0 - q_n^T M q_n) / 2. Exact for the recurrence, since with the midpoint velocity
    qbar = (q_{n-1/2} + q_{n+1/2}) / 2 the change of q^T M q / 2 over a step is dt F . qbar, F the
    dashpots' generalised force."""
    m = rectangle_mass_matrix(width=width, height=height, density=density)
    q0 = np.asarray(initial_velocity, dtype=float)
    common = dict(width=width, height=height, density=density, edge_from=edge_from, edge_to=edge_to, medium=medium,
                  initial_velocity=initial_velocity, dt=dt)
    qn = np.array([float(viscous_rigid_block_velocity_discrete(time, dof=d, **common)) for d in ("vx", "vy", "w")])
    return 0.5 * (q0 @ m @ q0 - qn @ m @ qn)


def viscous_rigid_block_lag_error_bound(*, width, height, density, edge_from, edge_to, medium, initial_velocity,
                                        dof, dt, input_velocity=None):
    """Bound on max_n |discrete - continuum| of velocity component dof (viscous_rigid_block_velocity
    against its _discrete recurrence), relative to max_t |continuum|: the error of the lagged
    velocity.

    With A = V diag(lambda) V^-1 and c = V^-1 (q0 - q_s), both are sums over the modes of
    V_ki c_i times e^{-lambda_i t} or (1 - x_i)^n, x_i = lambda_i dt < 1, t = n dt. Since
    (1 - x)^n = e^{-s} e^{-s g}, s = n x, g = -ln(1 - x) / x - 1 = x / 2 + x^2 / 3 + ..., the
    difference e^{-s} (1 - e^{-s g}) <= s e^{-s} g <= g / e; so |error_k| <= sum_i |V_ki c_i| g_i / e,
    first order in dt. The maximum of |q_k| is taken over 20 000 points of the first 10 slowest
    time constants (the continuum decays monotonically past its extremes there)."""
    a, q0, qs = _viscous_block_system(width, height, density, edge_from, edge_to, medium, initial_velocity,
                                      input_velocity)
    rates, vectors = np.linalg.eig(a)
    rates, vectors = rates.real, vectors.real
    x = rates * dt
    if np.any(x >= 1.0):
        raise ValueError(f"lambda dt = {x.max()} >= 1: the recurrence oscillates, the bound does not hold")
    g = np.where(x > 0.0, -np.log1p(-x) / np.where(x > 0.0, x, 1.0) - 1.0, 0.0)
    k = _DOF[dof]
    modal = np.abs(vectors[k, :] * np.linalg.solve(vectors, q0 - qs))
    slowest = np.min(rates[rates > 0.0])
    t = np.linspace(0.0, 10.0 / slowest, 20001)
    peak = np.max(np.abs(viscous_rigid_block_velocity(t, width=width, height=height, density=density,
                                                      edge_from=edge_from, edge_to=edge_to, medium=medium,
                                                      initial_velocity=initial_velocity, dof=dof,
                                                      input_velocity=input_velocity)))
    return float(np.sum(modal * g) / math.e / peak)


def viscous_rigid_block_step_limit(*, width, height, density, edge_from, edge_to, medium, joint_stiffness, frac):
    """The step limit the solver puts on a free rigid block with a viscous edge (as documented for
    rigidDashpotTimeStep): the lagged-velocity stability condition (w dt)^2 + 2 lambda dt < 4 of a
    mode of frequency w and decay rate lambda, dt < 4 / (lambda + sqrt(lambda^2 + 4 w^2)), times frac,
    with

        lambda = c_t / m + c_r / I,   c_t = the largest eigenvalue of L (Zn n n + Zs t t),
                 c_r = the integral of Zn (r x n)^2 + Zs (r x t)^2 along the edge (its rotation entry),
        w^2 = k_j 2 R / m,   m = rho W H,  I = m (W^2 + H^2) / 12,

    k_j the largest joint stiffness (kn or ks) and R = sqrt(W^2 + H^2) / 2 the block's bounding
    radius about its centroid: lambda bounds the fastest decay rate of the coupled translation and
    rotation (the largest eigenvalue of a positive semi-definite block matrix is at most the sum of
    its diagonal blocks'), w^2 is the springs' estimate of 1.3-28."""
    zn, zs = medium_impedances(**medium)
    m = density * width * height
    inertia = m * (width ** 2 + height ** 2) / 12.0
    k = joint_stiffness * math.hypot(width, height)  # k_j 2 R
    c = rigid_edge_dashpot_matrix(edge_from=edge_from, edge_to=edge_to, centroid=(0.0, 0.0), normal_impedance=zn,
                                  shear_impedance=zs)
    rate = float(np.linalg.eigvalsh(c[:2, :2]).max()) / m + float(c[2, 2]) / inertia
    return frac * 4.0 / (rate + math.sqrt(rate * rate + 4.0 * k / m))

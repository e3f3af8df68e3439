"""Dispersion of a plane S wave in a column of crossed constant-strain triangles, under the
explicit central-difference scheme with lumped masses (DY-DISPERSION).

Independent of the solver (math and numpy only); the lattice and its dispersion relation are
derived here from the triangles' strain energy and the lumping rule.

The column. Cells of height h and width w, each crossed by its diagonals into four triangles that
meet at a centre node; masses lumped as a third of each triangle's mass at each of its vertices;
every node held in y; the x motion u the same for every node of a row (the column's free sides and
the periodic cells allow it: the force from the cell right of a node equals the one from the cell
left of it, so an edge node, with half of each, moves with the interior ones). Per unit width the
column is then a chain of corner rows (y = j h, mass m_c = 2 rho h / 3) with centre nodes between
them (y = (j + 1/2) h, mass m_C = rho h / 3). Strain energy per cell and unit width, from the four
triangles of area w h / 4 (u_j, u_j+1 the corner rows, u_C the centre, ubar = (u_j + u_j+1) / 2,
M = lam + 2 G):

    lower and upper triangle   (G / h) / 2 [(u_C - u_j)^2 + (u_j+1 - u_C)^2]        (shear only)
    side triangles             G (u_j+1 - u_j)^2 / (4 h) + (h / w^2) M (ubar - u_C)^2

(the side triangles strain in shear, du/dy = (u_j+1 - u_j) / h, and in e_xx = 2 (ubar - u_C) / w).
So three springs per unit width: K1 = G / h from the centre to each corner row, K2 = G / (2 h)
between the corner rows, K3 = 2 h M / w^2 from the centre to the corners' mean. A plane wave
u_j = U exp(i(w t - k j h)), u_C = V exp(i(w t - k (j + 1/2) h)) gives with kappa = k h,
Omega^2 for the angular frequency squared:

    centre:   (a - m_C Omega^2) V = a cos(kappa / 2) U,        a = 2 K1 + K3
    corner:   m_c Omega^2 = 2 K1 + K3 cos^2(kappa/2) + 4 K2 sin^2(kappa/2) - a^2 cos^2(kappa/2) / (a - m_C Omega^2)

which is linear in cos(kappa) (cos^2(kappa/2) = (1 + cos kappa) / 2, sin^2 = (1 - cos kappa) / 2),
so kappa has a closed form. Central differences in time turn the second time derivative of every
degree of freedom into -Omega^2 with Omega = (2 / dt) sin(w dt / 2) (the harmonic exp(i w n dt) in
u_n+1 - 2 u_n + u_n-1 = dt^2 a_n), so the fully discrete relation is the one above with that Omega.

Long waves: with Omega -> 0 the centre follows the corners' mean and the chain's stiffness is
(2 K1 + 4 K2) sin^2(kappa/2) = 4 (G / h) sin^2(kappa/2), the shear spring G / h of a layer. The
chain of such springs with the lumped mass rho h per row, sin(w dt / 2) = (c dt / h) sin(k h / 2)
(lumped_chain_wavenumber), is not this scheme's relation: it leaves out the centre node, which
carries a third of the mass between the rows. For thin cells (K3 -> infinity) the crossed
relation becomes rho h (1 - sin^2(kappa/2) / 3) Omega^2 = 4 (G / h) sin^2(kappa/2), a mass
between the lumped and the consistent one whose spatial error is fourth order in kappa; the side
triangles' finite stiffness K3 and the time step bring it back to second order.
"""
import math

import numpy as np


def _moduli(E, nu):
    """(M = lam + 2 G, G) from Young's modulus and Poisson's ratio (plane strain, isotropic)."""
    if not (E > 0.0 and -1.0 < nu < 0.5):
        raise ValueError(f"E = {E}, nu = {nu}: need E > 0 and -1 < nu < 1/2")
    G = E / (2.0 * (1.0 + nu))
    return E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)) + 2.0 * G, G


def _positive(**values):
    for name, value in values.items():
        if not (value > 0.0 and math.isfinite(value)):
            raise ValueError(f"{name} = {value}: must be positive and finite")


def crossed_column_shear_wavenumber(*, frequency, h, width, dt, E, nu, rho):
    """Wavenumber k (rad/m) of a plane S wave of the given frequency (Hz) in the column of crossed
    triangles described above (cells h tall and `width` wide), integrated by central differences at
    the step dt. Raises ValueError above the acoustic branch's cut-off (no real k)."""
    _positive(frequency=frequency, h=h, width=width, dt=dt, rho=rho)
    M, G = _moduli(E, nu)
    omega = 2.0 * math.pi * frequency
    half = omega * dt / 2.0
    if half >= math.pi / 2.0:
        raise ValueError(f"w dt / 2 = {half}: at or beyond pi / 2 the central-difference step has no harmonic")
    omega2 = (2.0 / dt * math.sin(half)) ** 2
    K1, K2, K3 = G / h, G / (2.0 * h), 2.0 * h * M / width**2
    corner_mass, centre_mass = 2.0 * rho * h / 3.0, rho * h / 3.0
    a = 2.0 * K1 + K3
    # The centre node's condensed term a^2 cos^2(kappa/2) / (a - m_C Omega^2) is B (1 + cos kappa),
    # B = a^2 / (2 (a - m_C Omega^2)); it enters with -K3 (1 + cos kappa) / 2, and
    # B - K3 / 2 = (2 K1 a + K3 m_C Omega^2) / (2 (a - m_C Omega^2)) is formed without the
    # cancellation of two large terms when the cells are thin (K3 large).
    condensed = (2.0 * K1 * a + K3 * centre_mass * omega2) / (2.0 * (a - centre_mass * omega2))
    constant = corner_mass * omega2 - 2.0 * K1 - 2.0 * K2 + condensed
    slope = 2.0 * K2 + condensed
    cos_kappa = -constant / slope
    if not -1.0 <= cos_kappa <= 1.0:
        raise ValueError(f"cos(k h) = {cos_kappa}: frequency {frequency} Hz lies beyond the lattice's acoustic branch")
    return math.acos(cos_kappa) / h


def lumped_chain_wavenumber(*, frequency, h, dt, c):
    """Wavenumber of the one-dimensional chain of springs G / h and lumped masses rho h at the step
    dt: sin(w dt / 2) = (c dt / h) sin(k h / 2). Not the crossed column's relation (see the module
    text); kept to show how far it lies from the scheme."""
    _positive(frequency=frequency, h=h, dt=dt, c=c)
    s = math.sin(math.pi * frequency * dt) * h / (c * dt)
    if s > 1.0:
        raise ValueError(f"sin(k h / 2) = {s}: frequency {frequency} Hz lies beyond the chain's cut-off")
    return 2.0 / h * math.asin(s)


def crossed_column_phase_error(*, frequency, h, width, dt, E, nu, rho, distance):
    """Phase lag (rad) the crossed column's dispersion builds over `distance`, (k - w / c_s) distance."""
    _, G = _moduli(E, nu)
    c = math.sqrt(G / rho)
    k = crossed_column_shear_wavenumber(frequency=frequency, h=h, width=width, dt=dt, E=E, nu=nu, rho=rho)
    return (k - 2.0 * math.pi * frequency / c) * distance


def driven_sine_displacement_gain(*, frequency, dt):
    """Amplitude factor of a boundary driven at the velocity amplitude sin(w (t_n + dt/2)) over each
    step (the midpoint of the step): its displacement at t_n is the sum
    dt sum_k sin(w (k + 1/2) dt) = (1 - cos(w t_n)) / (2 sin(w dt / 2)) / (1 / dt), that is
    (1 - cos w t_n) / w times (w dt / 2) / sin(w dt / 2): the exact phase, an amplitude 1 + (w dt)^2 / 24."""
    half = math.pi * frequency * dt
    return half / math.sin(half) if half > 0.0 else 1.0


def crossed_column_sine_displacement(t, *, distance, h, width, dt, E, nu, rho, amplitude, frequency):
    """x displacement of a corner row at `distance` above a base whose velocity is
    amplitude sin(2 pi f t) from t = 0, as the discrete steady wave of the crossed column carries it:
    gain (amplitude / w) (1 - cos(w t - k distance)), k = crossed_column_shear_wavenumber and gain =
    driven_sine_displacement_gain. The lattice driven at one end carries the Bloch wave at the
    base's amplitude (it satisfies every interior equation); what it leaves out is the start-up
    transient behind the front. Zero before the continuum's arrival distance / c_s."""
    t = np.asarray(t, dtype=float)
    omega = 2.0 * math.pi * frequency
    k = crossed_column_shear_wavenumber(frequency=frequency, h=h, width=width, dt=dt, E=E, nu=nu, rho=rho)
    gain = driven_sine_displacement_gain(frequency=frequency, dt=dt)
    delay = distance / math.sqrt(_moduli(E, nu)[1] / rho)
    steady = gain * amplitude / omega * (1.0 - np.cos(omega * t - k * distance))
    return np.where(t >= delay, steady, 0.0)

"""Closed forms for elastic, perfectly plastic Mohr-Coulomb rock (tension positive, plane strain).

Mohr-Coulomb in principal stresses s1 <= s2 <= s3 (s1 the most compressive): failure when
s1 = s3 N_phi - 2 c sqrt(N_phi), N_phi = (1 + sin phi) / (1 - sin phi) (e.g. Jaeger, Cook and
Zimmerman, Fundamentals of Rock Mechanics, 4th ed., section 4.5; Itasca's FLAC manual, the
Mohr-Coulomb model).
"""
import math

import numpy as np


def n_phi(*, friction_deg):
    """N_phi = (1 + sin phi) / (1 - sin phi) for phi in degrees, 0 < phi < 90."""
    phi = np.radians(np.asarray(friction_deg, dtype=float))
    if np.any((phi <= 0.0) | (phi >= math.pi / 2)):
        raise ValueError("friction must lie in (0, 90) degrees")
    return (1.0 + np.sin(phi)) / (1.0 - np.sin(phi))


def biaxial_peak_stress(*, confining_pressure, cohesion, friction_deg):
    """The axial stress (tension positive, so negative in compression) at which a sample under
    the lateral pressure `confining_pressure` (compression positive) fails:

        s1 = -p N_phi - 2 c sqrt(N_phi),

    with s3 = -p the lateral stress, the intermediate (out-of-plane) stress between the two.
    """
    n = n_phi(friction_deg=friction_deg)
    return -np.asarray(confining_pressure, dtype=float) * n - 2.0 * np.asarray(cohesion, dtype=float) * np.sqrt(n)


def single_plane_of_weakness_peak_stress(*, confining_pressure, cohesion, friction_deg, joint_cohesion,
                                        joint_friction_deg, joint_angle_deg):
    """The axial stress (tension positive) at which a sample cut by one plane of weakness fails
    under the lateral pressure `confining_pressure` (compression positive): the weaker of slip
    on the plane and failure of the intact rock. With compression positive, sigma3 = p and beta
    the angle between the plane's normal and the axial (major) stress, i.e. the plane's dip from
    the lateral direction, the plane slips when (Jaeger 1960; Jaeger, Cook and Zimmerman,
    Fundamentals of Rock Mechanics, 4th ed., section 4.8)

        sigma1 = sigma3 + 2 (c_w + sigma3 tan phi_w) / ((1 - tan phi_w cot beta) sin 2 beta),

    which needs phi_w < beta < 90 degrees (elsewhere the plane cannot slip whatever the load);
    the intact rock fails at sigma1 = sigma3 N_phi + 2 c sqrt(N_phi) (biaxial_peak_stress).
    """
    beta = math.radians(float(joint_angle_deg))
    phi_w = math.radians(float(joint_friction_deg))
    if not 0.0 < phi_w < math.pi / 2:
        raise ValueError(f"joint friction {joint_friction_deg} degrees must lie in (0, 90)")
    p = float(confining_pressure)
    rock = -float(biaxial_peak_stress(confining_pressure=p, cohesion=cohesion, friction_deg=friction_deg))
    if not phi_w < beta < math.pi / 2:
        return -rock
    slip = p + 2.0 * (float(joint_cohesion) + p * math.tan(phi_w)) / (
        (1.0 - math.tan(phi_w) / math.tan(beta)) * math.sin(2.0 * beta))
    return -min(slip, rock)


def plastic_strain_rate_ratio(*, dilation_deg):
    """d e3_p / d e1_p = -N_psi for Mohr-Coulomb flow on the face of s1 and s3, with the plastic
    potential g = s1 - s3 N_psi (non-associated when psi < phi): the minor principal direction
    extends N_psi times as fast as the major one shortens, and the intermediate one carries no
    plastic strain. Once a sample under constant confinement flows at constant stress, its
    elastic strains stop changing and this is the ratio of the total strain rates."""
    psi = math.radians(float(dilation_deg))
    if not 0.0 <= psi < math.pi / 2:
        raise ValueError(f"dilation {dilation_deg} degrees must lie in [0, 90)")
    return -(1.0 + math.sin(psi)) / (1.0 - math.sin(psi))


def _check_young_poisson(E, nu):
    if not E > 0.0:
        raise ValueError(f"E = {E}: Young's modulus must be positive")
    if not -1.0 < nu < 0.5:
        raise ValueError(f"nu = {nu}: Poisson's ratio must lie in (-1, 1/2) for a stable isotropic solid")


WALL_ROUNDOFF = 1e-12  # relative: how far inside the wall a point of it may lie by round-off


def salencon_tunnel(*, r, a, p0, pi, E, nu, cohesion, friction_deg, dilation_deg):
    """Stresses and radial displacement around a circular tunnel (radius a) in an infinite,
    elastic, perfectly plastic Mohr-Coulomb medium under plane strain, hydrostatic in-situ stress
    p0 and internal support pressure pi (both compressive pressures, positive), with the
    non-associated flow rule of dilation angle psi (0 <= psi <= phi).

    Sources: J. Salencon, "Contraction quasi-statique d'une cavite a symetrie spherique ou
    cylindrique dans un milieu elastoplastique", Annales des Ponts et Chaussees 4 (1969) 231-236;
    restated (same notation as below, K_p = N_phi, q = sigma_c, K_ps = N_psi) in Itasca's FLAC and
    3DEC verification problem "Cylindrical hole in an infinite Mohr-Coulomb medium"; the
    displacement with dilation also follows C. Carranza-Torres and C. Fairhurst, "The elasto-plastic
    response of underground excavations in rock masses that satisfy the Hoek-Brown failure
    criterion", Int. J. Rock Mech. Min. Sci. 36 (1999) 777-809 (their Mohr-Coulomb special case).
    The displacement is re-derived below and checked in the tests.

    Inside the derivation stresses are COMPRESSION POSITIVE (sigma_r, sigma_t) and u is the
    displacement INWARD; the returned values are converted (see Returns). With
        N_phi = (1 + sin phi) / (1 - sin phi),  N_psi = (1 + sin psi) / (1 - sin psi),
        sigma_c = 2 c sqrt(N_phi)  (unconfined strength),  A = sigma_c / (N_phi - 1),
    the yield condition in the plastic zone is sigma_t = N_phi sigma_r + sigma_c (sigma_t the
    major, sigma_r the minor principal stress; the out-of-plane stress is taken as intermediate).

    Onset of yield: the wall yields when pi < p_crit = (2 p0 - sigma_c) / (1 + N_phi).

    Plastic radius (R_p = a when pi >= p_crit):
        R_p = a [ 2 (p0 (N_phi - 1) + sigma_c) / ((1 + N_phi) ((N_phi - 1) pi + sigma_c)) ]^(1/(N_phi - 1))

    Plastic zone, a <= r <= R_p (equilibrium with the yield condition, sigma_r(a) = pi):
        sigma_r = -A + (pi + A) (r/a)^(N_phi - 1)
        sigma_t = -A + N_phi (pi + A) (r/a)^(N_phi - 1)

    Elastic zone, r >= R_p (Lame, sigma_r(R_p) = sigma_re, sigma -> p0 far away):
        sigma_re = (2 p0 - sigma_c) / (1 + N_phi)   (= p_crit)
        sigma_r = p0 - (p0 - sigma_re) (R_p/r)^2,  sigma_t = p0 + (p0 - sigma_re) (R_p/r)^2
        u = (p0 - sigma_re) R_p^2 / (2 G r)

    Plastic-zone displacement. Strains measured from the in-situ state, extension positive:
    e_r = du_out/dr, e_t = u_out/r (u_out = -u). Elastic strains from plane-strain Hooke with the
    stress change from the in-situ state (tension positive ds = p0 - sigma):
        2 G e_r^e = (1 - nu) ds_r - nu ds_t,   2 G e_t^e = (1 - nu) ds_t - nu ds_r,
    the out-of-plane plastic strain being zero (sigma_z intermediate), so e_z^e = 0 too. The flow
    rule of the potential g = sigma_t - N_psi sigma_r gives e_r^p + N_psi e_t^p = 0 (integrated
    in total strains, as the ratio is fixed). Then
        du_out/dr + N_psi u_out/r = e_r^e + N_psi e_t^e,
    a linear first-order equation whose right side is a constant plus a multiple of
    (r/a)^(N_phi - 1); solved with u continuous at R_p, and with
    sigma_re + A = (pi + A) (R_p/a)^(N_phi - 1) = 2 (p0 + A) / (1 + N_phi):
        2 G u / r = -(1 - 2 nu) (p0 + A)
                    + (1 - nu) (N_phi^2 - 1) / (N_phi + N_psi) (pi + A) (R_p/a)^(N_phi - 1) (R_p/r)^(N_psi + 1)
                    + [ (1 - nu) (N_phi N_psi + 1) / (N_phi + N_psi) - nu ] (pi + A) (r/a)^(N_phi - 1)
    (u inward), which is the FLAC/Salencon expression; at r = R_p it equals the elastic-zone
    (p0 - sigma_re) R_p / (2 G).

    Valid for 0 <= pi <= (2 N_phi p0 + sigma_c) / (1 + N_phi) (beyond that the wall fails with the
    radial stress as the major one, a cavity expansion not covered here), (N_phi - 1) pi +
    sigma_c > 0 (a finite plastic zone) and r >= a (points within a relative 1e-12 inside the wall,
    coordinates' round-off, are taken at the wall). Displacements are those caused by the
    unloading from p0 to pi (zero in the in-situ state).

    Parameters: r (m, array), a (m), p0, pi (Pa, compression positive), E (Pa), nu, cohesion (Pa),
    friction_deg, dilation_deg (degrees).

    Returns a dict:
        srr, stt: radial and tangential stress, TENSION POSITIVE (so srr = -sigma_r, negative in
            compression), arrays shaped like r;
        ur: radial displacement, positive OUTWARD (negative for convergence), array;
        plastic_radius: R_p (m), equal to a when the rock stays elastic;
        wall_displacement: ur at r = a (m, outward positive).
    """
    r = np.asarray(r, dtype=float)
    a, p0, pi = float(a), float(p0), float(pi)
    E, nu, c = float(E), float(nu), float(cohesion)
    phi_deg, psi_deg = float(friction_deg), float(dilation_deg)
    _check_young_poisson(E, nu)
    if not a > 0.0:
        raise ValueError(f"a = {a}: the tunnel radius must be positive")
    # A point of the wall whose coordinates carry round-off (r = a (1 - 1e-16) from a polygon's
    # vertex) is on the wall; inside it by more is an error.
    if np.any(~(r >= a * (1.0 - WALL_ROUNDOFF))):
        raise ValueError("r must lie at or outside the tunnel wall (r >= a)")
    r = np.maximum(r, a)
    if not p0 > 0.0:
        raise ValueError(f"p0 = {p0}: the in-situ stress must be a positive (compressive) pressure")
    if not pi >= 0.0:
        raise ValueError(f"pi = {pi}: the support pressure must not be negative")
    if not c >= 0.0:
        raise ValueError(f"cohesion = {c}: must not be negative")
    if not 0.0 <= psi_deg <= phi_deg:
        raise ValueError(f"dilation {psi_deg} deg must lie in [0, friction = {phi_deg} deg]")
    n = float(n_phi(friction_deg=phi_deg))
    s_psi = math.sin(math.radians(psi_deg))
    n_psi = (1.0 + s_psi) / (1.0 - s_psi)
    sigma_c = 2.0 * c * math.sqrt(n)
    if not (n - 1.0) * pi + sigma_c > 0.0:
        raise ValueError("no cohesion and no support pressure: the plastic zone would be unbounded")
    if pi > (2.0 * n * p0 + sigma_c) / (1.0 + n):
        raise ValueError(f"pi = {pi}: above (2 N_phi p0 + sigma_c) / (1 + N_phi) the wall fails in "
                         "expansion, which this solution does not cover")
    G = E / (2.0 * (1.0 + nu))
    A = sigma_c / (n - 1.0)
    p_crit = (2.0 * p0 - sigma_c) / (1.0 + n)

    if pi >= p_crit:
        # Elastic throughout: Lame's hole in an infinite medium, radial stress pi at the wall.
        rp, sigma_re = a, pi
    else:
        rp = a * (2.0 * (p0 * (n - 1.0) + sigma_c) / ((1.0 + n) * ((n - 1.0) * pi + sigma_c))) ** (1.0 / (n - 1.0))
        sigma_re = p_crit

    def displacement_inward(x):
        x = np.asarray(x, dtype=float)
        elastic = (p0 - sigma_re) * rp * rp / (2.0 * G * x)
        rho = (x / a) ** (n - 1.0)
        q = (1.0 - nu) * (n * n_psi + 1.0) / (n + n_psi) - nu
        plastic = x / (2.0 * G) * (
            -(1.0 - 2.0 * nu) * (p0 + A)
            + (1.0 - nu) * (n * n - 1.0) / (n + n_psi) * (pi + A) * (rp / a) ** (n - 1.0) * (rp / x) ** (n_psi + 1.0)
            + q * (pi + A) * rho)
        return np.where(x < rp, plastic, elastic)

    in_plastic = r < rp
    rho = (r / a) ** (n - 1.0)
    ratio2 = (rp / r) ** 2
    sigma_r = np.where(in_plastic, -A + (pi + A) * rho, p0 - (p0 - sigma_re) * ratio2)
    sigma_t = np.where(in_plastic, -A + n * (pi + A) * rho, p0 + (p0 - sigma_re) * ratio2)
    return {
        "srr": -sigma_r,
        "stt": -sigma_t,
        "ur": -displacement_inward(r),
        "plastic_radius": float(rp),
        "wall_displacement": float(-displacement_inward(a)),
    }

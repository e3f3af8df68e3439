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

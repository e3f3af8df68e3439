"""Mohr-Coulomb closed forms (verification/analytic/plasticity.py) at known values."""
import math

import pytest

from analytic import plasticity as pl

REQ = pytest.mark.requirements("REQ-QA-003")


@REQ
def test_n_phi_known_values():
    # phi = 30 deg: (1 + 0.5) / (1 - 0.5) = 3; phi = 45 deg: (1 + 0.7071) / (1 - 0.7071) = 5.8284.
    assert pl.n_phi(friction_deg=30.0) == pytest.approx(3.0, rel=1e-14)
    assert pl.n_phi(friction_deg=45.0) == pytest.approx(3.0 + 2.0 * math.sqrt(2.0), rel=1e-14)
    with pytest.raises(ValueError):
        pl.n_phi(friction_deg=0.0)


@REQ
def test_biaxial_peak_stress_known_values():
    # c = 1 MPa, phi = 30 deg: unconfined strength 2 c sqrt(3) = 3.4641 MPa; under 1 MPa of
    # confinement 1 x 3 + 3.4641 = 6.4641 MPa (compression, so negative).
    assert pl.biaxial_peak_stress(confining_pressure=0.0, cohesion=1e6, friction_deg=30.0) == \
        pytest.approx(-2e6 * math.sqrt(3.0), rel=1e-14)
    assert pl.biaxial_peak_stress(confining_pressure=1e6, cohesion=1e6, friction_deg=30.0) == \
        pytest.approx(-6.464101615e6, rel=1e-9)

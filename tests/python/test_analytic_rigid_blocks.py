import math

import numpy as np
import pytest

from analytic import rigid_blocks as rb


@pytest.mark.requirements("REQ-QA-003")
def test_known_values():
    # m g / (kn L) = 2500 * 10 / 1e8 = 2.5e-4 m; T = 2 pi / sqrt(1e8 / 2500) = 2 pi / 200
    assert rb.resting_settlement(mass=2500, g=10, kn=1e8, contact_length=1) == pytest.approx(2.5e-4, rel=1e-15)
    assert rb.oscillator_period(mass=2500, kn=1e8, contact_length=1) == pytest.approx(math.pi / 100, rel=1e-15)
    # 45 degrees, phi = 20: g (sin45 - cos45 tan20) = 9.81 * 0.70711 * (1 - 0.36397) = 4.41196
    assert rb.incline_acceleration(g=9.81, theta_deg=45, phi_deg=20) == pytest.approx(4.411958821, rel=1e-9)
    assert rb.incline_acceleration(g=9.81, theta_deg=20, phi_deg=30) == 0.0
    # constant normal displacement: post-yield slope ks kn tp ts / (ks + kn tp ts)
    us = np.array([1e-3, 2e-3])
    tau, _ = rb.direct_shear_constant_normal_displacement(us, ks=1e9, kn=1e9, sn0=0, cohesion=2e5, phi_deg=30,
                                                          psi_deg=10)
    k = 1e9 * math.tan(math.radians(30)) * math.tan(math.radians(10))
    assert (tau[1] - tau[0]) / 1e-3 == pytest.approx(1e9 * k / (1e9 + k), rel=1e-12)


@pytest.mark.requirements("REQ-QA-003")
def test_central_difference_closed_form_matches_the_recurrence():
    dt, alpha, w2 = 5e-4, 40.0, 4e4
    n = np.arange(300)
    y = rb.central_difference_settlement_history(n * dt, mass=2500, g=10, kn=1e8, contact_length=1, alpha=alpha, dt=dt)
    loop, v = [0.0], 0.0
    for _ in range(299):
        v = (v * (1 - alpha * dt / 2) + (10 - w2 * loop[-1]) * dt) / (1 + alpha * dt / 2)
        loop.append(loop[-1] + v * dt)
    assert np.max(np.abs(y - loop)) <= 1e-12 * 2.5e-4 * 10
    # and tends to the continuous solution as dt -> 0
    coarse = rb.central_difference_settlement_history(np.array([0.05]), mass=2500, g=10, kn=1e8, contact_length=1,
                                                      alpha=0.0, dt=1e-4)
    exact = rb.oscillator_settlement_history(np.array([0.05]), mass=2500, g=10, kn=1e8, contact_length=1)
    assert abs(coarse[0] - exact[0]) < 0.05 * 2.5e-4

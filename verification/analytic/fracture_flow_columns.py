"""The steady deformable-joint profile sampled as a row of rigid columns samples it: the
reference for the hydraulic apertures of FL-DEFORMABLE-JOINT's knots. Only numpy is used.

A joint whose aperture follows the pressure, a(p) = a_out + (p - p_out) / kn, modelled by a row
of `columns` rigid blocks of width w = L / columns on a fixed base: each column's joint has one
aperture, and every knot of the column (at either end of its base) reports it. A knot therefore
stands for the column holding it, not for its own point: comparing it with the closed form at
its own x would measure the first-order step of a piecewise-constant function (w / 2 times the
slope da/dx), not the model's error. The closed form at the column's centre is what the
column's aperture converges to at second order in w (the midpoint rule; see
FL-DEFORMABLE-JOINT's problem.toml).

The closed form is fracture_flow.deformable_joint_steady_profile's (derived there): a^4 falls
linearly along the joint, a(x) = [a_in^4 - (a_in^4 - a_out^4) x / L]^(1/4), a_in = a_out +
(p_in - p_out) / kn. It is evaluated here from that formula, the module importing nothing but
numpy (tests/python/test_analytic_independence.py); the tests check it against fracture_flow.
"""
import numpy as np


def column_centre_aperture(x, *, columns, p_in, p_out, outlet_aperture, normal_stiffness, viscosity, length):
    """a(x_c) (m), x_c = (floor(x / w) + 1/2) w the centre of the column of width w = length /
    columns that holds x (0 <= x <= length; x = length counts as the last column's), a(x) the
    steady profile of a joint whose aperture grows with pressure (module docstring). viscosity
    (Pa s) does not change the profile; it is taken, and checked, so that the parameters are
    those of fracture_flow's deformable-joint functions."""
    if isinstance(columns, bool) or not isinstance(columns, int) or columns < 1:
        raise ValueError(f"columns = {columns!r}: must be a whole number >= 1")
    for name, value in (("outlet_aperture", outlet_aperture), ("normal_stiffness", normal_stiffness),
                        ("viscosity", viscosity), ("length", length)):
        if not value > 0.0:
            raise ValueError(f"{name} = {value!r}: must be positive")
    a_in = outlet_aperture + (p_in - p_out) / normal_stiffness
    if not a_in > 0.0:
        raise ValueError(f"p_in = {p_in} Pa, p_out = {p_out} Pa: the inlet aperture a_out + (p_in - p_out) / kn = "
                         f"{a_in} m closes the joint; raise p_in or outlet_aperture")
    x = np.asarray(x, dtype=float)
    if np.any(~((x >= 0.0) & (x <= length))):
        raise ValueError(f"x = {x} m: a point of the joint lies in [0, length = {length}] m")
    w = length / columns
    centre = (np.minimum(np.floor(x / w), columns - 1) + 0.5) * w
    return (a_in ** 4 - (a_in ** 4 - outlet_aperture ** 4) * centre / length) ** 0.25

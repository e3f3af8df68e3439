"""verification/analytic/fracture_flow_columns.py at known values.

The deformable joint of these tests: a_out = 5e-5 m, p_in - p_out = 5e5 Pa, kn = 1e10 Pa/m, so
a_in = 1e-4 m and a^4 falls linearly from 1e-16 to 6.25e-18 m^4 over L = 1 m.
"""
import numpy as np
import pytest

from analytic import fracture_flow_columns as fc

REQ = pytest.mark.requirements("REQ-QA-003")
JOINT = dict(p_in=5e5, p_out=0.0, outlet_aperture=5e-5, normal_stiffness=1e10, viscosity=1e-3, length=1.0)


@REQ
def test_every_point_of_a_column_takes_the_closed_form_at_its_centre():
    # 4 columns of 0.25 m: x = 0.3 and 0.49 lie in the second, centre 0.375 m, where
    # a^4 = 1e-16 - 9.375e-17 x 0.375 = 6.484375e-17 m^4, a = 8.9736e-5 m.
    expected = (1e-16 - 9.375e-17 * 0.375) ** 0.25
    a = fc.column_centre_aperture(np.array([0.3, 0.49]), columns=4, **JOINT)
    assert a == pytest.approx([expected, expected], rel=1e-12, abs=0)


@REQ
def test_the_joint_ends_belong_to_the_first_and_last_columns():
    a = fc.column_centre_aperture(np.array([0.0, 1.0]), columns=2, **JOINT)
    assert a == pytest.approx([(1e-16 - 9.375e-17 * 0.25) ** 0.25, (1e-16 - 9.375e-17 * 0.75) ** 0.25], rel=1e-12, abs=0)


@REQ
@pytest.mark.parametrize("bad", [dict(columns=0), dict(columns=2.0), dict(x=1.5), dict(length=0.0), dict(p_in=-6e5)])
def test_bad_input_is_refused(bad):
    args = dict(x=0.5, columns=2, **JOINT)
    args.update(bad)
    with pytest.raises(ValueError):
        fc.column_centre_aperture(**args)


@REQ
def test_it_is_fracture_flows_profile_at_the_column_centres():
    from analytic import fracture_flow as ff
    x = np.linspace(0.0, 1.0, 101)
    centres = (np.minimum(np.floor(x / 0.1), 9) + 0.5) * 0.1
    expected, _ = ff.deformable_joint_steady_profile(centres, **JOINT)
    assert fc.column_centre_aperture(x, columns=10, **JOINT) == pytest.approx(expected, rel=1e-14, abs=0)

"""Field extractors (zones and gridpoints of deformable blocks) on synthetic results with known
answers, and field references called with the samples' coordinates."""
import math

import numpy as np
import pytest

from vdec_verify.extract import ExtractError, Series, extract
from vdec_verify.norms import ReferenceProblem, compare, evaluate_reference
from vdec_verify.problem import Reference, find_reference_function

REQ = pytest.mark.requirements("REQ-QA-006")

# Two zones on the x axis and one on the y axis (initial centroids), and three gridpoints.
RESULTS = {
    "blocks": [{"name": "plate"}],
    "zones": {"block": [0, 0, 0], "x0": [1.0, 2.0, 0.0], "y0": [0.0, 0.0, 3.0], "area": [1.0, 3.0, 2.0],
              "sxx": [-1.0, -2.0, -5.0], "syy": [-4.0, -6.0, -7.0], "sxy": [0.5, 0.0, 1.0], "szz": [0.0, 0.0, 0.0]},
    "gridpoints": {"block": [0, 0, 0], "x0": [1.0, 0.0, 3.0], "y0": [0.0, 2.0, 4.0],
                   "displacement_x": [1e-3, 0.0, 3e-3], "displacement_y": [0.0, 2e-3, 4e-3]},
}


@REQ
def test_polar_zone_stress_about_a_centre():
    # On the x axis (theta = 0) stt = syy and srr = sxx; on the y axis (theta = 90 deg) stt = sxx.
    s = extract({"kind": "field", "of": "zones", "quantity": "stt"}, RESULTS, 0)
    assert isinstance(s, Series) and s.x_label == "r"
    assert list(s.x) == [1.0, 2.0, 3.0]  # sorted by r
    assert s.y == pytest.approx([-4.0, -6.0, -5.0])
    assert s.weights == pytest.approx([1.0, 3.0, 2.0])
    assert s.coordinates["theta"] == pytest.approx([0.0, 0.0, math.pi / 2])
    srr = extract({"kind": "field", "of": "zones", "quantity": "srr"}, RESULTS, 0)
    assert srr.y == pytest.approx([-1.0, -2.0, -7.0])
    srt = extract({"kind": "field", "of": "zones", "quantity": "srt"}, RESULTS, 0)
    # theta = 0: srt = sxy; theta = 90 deg: srt = -sxy.
    assert srt.y == pytest.approx([0.5, 0.0, -1.0])


@REQ
def test_selection_ranges_and_means():
    s = extract({"kind": "field", "of": "zones", "quantity": "sxx", "y": [0.0, 0.0]}, RESULTS, 0)
    assert s.x_label == "x" and list(s.y) == [-1.0, -2.0]
    # Area-weighted mean of the zones in the angle range [0, 45] degrees: (1 * -1 + 3 * -2) / 4.
    assert extract({"kind": "field_mean", "of": "zones", "quantity": "sxx", "angle": [0.0, 45.0]}, RESULTS, 0) == \
        pytest.approx(-1.75)
    # Gridpoints: radial displacement of the gridpoint at (3, 4): (3e-3 * 3 + 4e-3 * 4) / 5 = 5e-3.
    ur = extract({"kind": "field", "of": "gridpoints", "quantity": "ur", "r": [4.5, 5.5]}, RESULTS, 0)
    assert ur.y == pytest.approx([5e-3]) and ur.weights is None
    with pytest.raises(ExtractError, match="no zones in the selection"):
        extract({"kind": "field", "of": "zones", "quantity": "sxx", "x": [10.0, 11.0]}, RESULTS, 0)
    with pytest.raises(ExtractError, match="zones have no quantity 'ux'"):
        extract({"kind": "field", "of": "zones", "quantity": "ux"}, RESULTS, 0)
    with pytest.raises(ExtractError, match="no 'zones'"):
        extract({"kind": "field", "of": "zones", "quantity": "sxx"}, {"histories": {}}, 0)


@REQ
def test_field_reference_takes_coordinates_and_a_named_component():
    # A Kirsch reference, called with the zones' r and theta, returning a dict of fields.
    s = extract({"kind": "field", "of": "zones", "quantity": "stt"}, RESULTS, 0)
    reference = Reference("elastic.kirsch", {"a": 0.5, "S_x": -1.0, "S_y": 0.0}, "stt", None)
    values = evaluate_reference(reference, s, find_reference_function("elastic.kirsch"))
    assert values.shape == s.y.shape and np.all(np.isfinite(values))
    missing = Reference("elastic.kirsch", {"a": 0.5, "S_x": -1.0, "S_y": 0.0}, "hoop", None)
    with pytest.raises(ReferenceProblem, match="name one with component"):
        evaluate_reference(missing, s, find_reference_function("elastic.kirsch"))


@REQ
def test_area_weighted_l2_norm():
    # Errors 1, 0, 0 with areas 1, 3, 2 over references 1, 1, 1: e = sqrt(1 / 6), scale 1.
    s = Series(np.array([1.0, 2.0, 3.0]), np.array([2.0, 1.0, 1.0]), "r", "f", None, np.array([1.0, 3.0, 2.0]))
    c = compare("L2", s, np.ones(3), rtol=0.5, atol=0.0)
    assert c.error == pytest.approx(math.sqrt(1.0 / 6.0)) and c.passed


@REQ
def test_derived_quantity_from_scalar_extracts():
    # E and nu from a plane-strain uniaxial test: e_xx = 3.125e-5 (right), e_yy = -9.375e-5 (top),
    # sigma_yy = -1 MPa give E = 10 GPa, nu = 0.25 (the inverse of the closed form).
    results = {"blocks": [{"name": "s"}],
               "gridpoints": {"block": [0, 0], "x0": [1.0, 0.0], "y0": [0.0, 1.0],
                              "displacement_x": [3.125e-5, 0.0], "displacement_y": [0.0, -9.375e-5]}}
    table = {"kind": "derived", "function": "elastic.young_poisson_from_plane_strain_uniaxial",
             "params": {"sigma_yy": -1e6},
             "inputs": {"exx": {"kind": "field_mean", "of": "gridpoints", "quantity": "ux", "x": [1.0, 1.0]},
                        "eyy": {"kind": "field_mean", "of": "gridpoints", "quantity": "uy", "y": [1.0, 1.0]}}}
    assert extract({**table, "component": 0}, results, 0) == pytest.approx(10e9, rel=1e-12, abs=0)
    assert extract({**table, "component": 1}, results, 0) == pytest.approx(0.25, rel=1e-12, abs=0)


@REQ
def test_derived_ratio_of_two_runs():
    # 300 cycles in this run over 1200 in the run "slow": 0.25.
    this = {"run": {"cycles": 300}}
    runs = {"": this, "slow": {"run": {"cycles": 1200}}}
    table = {"kind": "derived", "function": "ratio",
             "inputs": {"numerator": {"kind": "run_meta", "path": "run.cycles"},
                        "denominator": {"kind": "run_meta", "path": "run.cycles", "variant": "slow"}}}
    assert extract(table, this, 0, runs) == pytest.approx(0.25, rel=1e-15, abs=0)
    # A scale turns a ratio of displacement rates into one of strain rates (lengths 1 m / 2 m).
    assert extract({**table, "params": {"scale": 2.0}}, this, 0, runs) == pytest.approx(0.5, rel=1e-15, abs=0)
    with pytest.raises(ExtractError, match="reads run 'fast', which did not run"):
        extract({**table, "inputs": {**table["inputs"], "denominator": {"kind": "run_meta", "path": "run.cycles",
                                                                        "variant": "fast"}}}, this, 0, runs)


@REQ
def test_derived_difference_of_two_histories():
    results = {"histories": {"far": {"t": [0.0, 1.0], "value": [0.0, -2.5]}, "near": {"t": [0.0, 1.0], "value": [0.0, -4.0]}}}
    table = {"kind": "derived", "function": "difference",
             "inputs": {"minuend": {"kind": "final", "history": "far"}, "subtrahend": {"kind": "final", "history": "near"}}}
    assert extract(table, results, 0) == pytest.approx(1.5, rel=1e-15, abs=0)


@REQ
def test_field_peak_is_the_value_of_largest_magnitude():
    # syy over the zones: -4, -6, -7 -> -7; sxy: 0.5, 0, 1 -> 1.
    assert extract({"kind": "field_peak", "of": "zones", "quantity": "syy"}, RESULTS, 0) == -7.0
    assert extract({"kind": "field_peak", "of": "zones", "quantity": "sxy"}, RESULTS, 0) == 1.0


@REQ
def test_field_extent_is_the_reach_of_the_nonzero_samples():
    # Zones at r = 1, 2, 3 with plastic states 4, 1, 0: the plastic zone reaches r = 2.
    results = {**RESULTS, "zones": {**RESULTS["zones"], "plastic_state": [4, 1, 0]}}
    assert extract({"kind": "field_extent", "of": "zones", "quantity": "plastic"}, results, 0) == pytest.approx(2.0)
    with pytest.raises(ExtractError, match="nonzero plastic"):
        extract({"kind": "field_extent", "of": "zones", "quantity": "plastic"},
                {**RESULTS, "zones": {**RESULTS["zones"], "plastic_state": [0, 0, 0]}}, 0)


@REQ
def test_contact_stresses_are_forces_over_lengths_of_the_closed_contacts():
    results = dict(RESULTS, blocks=[{"name": "plate"}, {"name": "lid"}], contacts=[
        {"block_a": "lid", "point": [1.0, 1.0], "normal_force": 2.0e3, "shear_force": -0.5e3, "length": 0.5, "open": False},
        {"block_a": "plate", "point": [2.0, 2.0], "normal_force": 3.0e3, "shear_force": 1.0e3, "length": 1.5, "open": False},
        {"block_a": "plate", "point": [3.0, 3.0], "normal_force": 0.0, "shear_force": 0.0, "length": 1.0, "open": True},
    ])
    sn = extract({"kind": "field", "of": "contacts", "quantity": "sn", "centre": [0.0, 0.0]}, results, 0)
    assert list(sn.x) == [1.0, 2.0]  # the open contact left out
    assert sn.coordinates["r"] == pytest.approx([math.sqrt(2.0), 2.0 * math.sqrt(2.0)])
    assert sn.y == pytest.approx([4.0e3, 2.0e3])
    tau = extract({"kind": "field_mean", "of": "contacts", "quantity": "tau", "block": "plate"}, results, 0)
    assert tau == pytest.approx(1.0e3 / 1.5)
    with pytest.raises(ExtractError, match="contacts have no quantity 'sxx'"):
        extract({"kind": "field", "of": "contacts", "quantity": "sxx"}, results, 0)

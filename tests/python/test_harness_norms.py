"""The pass rule and the error norms of the verification harness (REQ-QA-001), and references
that cannot serve as one (REQ-QA-002)."""
import math

import numpy as np
import pytest

from vdec_verify import PASS_RULE
from vdec_verify.extract import Series
from vdec_verify.norms import ReferenceProblem, compare, evaluate_reference, trapezoid_weights
from vdec_verify.problem import Reference


@pytest.mark.requirements("REQ-QA-001")
def test_scalar_rule_at_and_beyond_the_tolerance():
    # e_abs = 0.5 against atol + rtol s = 0.25 + 0.0025 * 100
    at_limit = compare("scalar", 100.5, 100.0, rtol=0.0025, atol=0.25)
    assert at_limit.passed and at_limit.e_abs == 0.5
    assert at_limit.error == pytest.approx(0.005) and at_limit.tolerance == pytest.approx(0.005)
    beyond = compare("scalar", 100.5000001, 100.0, rtol=0.0025, atol=0.25)
    assert not beyond.passed
    below = compare("scalar", 99.5, 100.0, rtol=0.0025, atol=0.25)
    assert below.passed and (below.numerical, below.reference) == (99.5, 100.0)


@pytest.mark.requirements("REQ-QA-001")
def test_zero_reference_reports_absolute_error_and_tolerance():
    result = compare("scalar", 3e-13, 0.0, rtol=1e-3, atol=1e-12)
    assert result.passed and result.error == 3e-13 and result.tolerance == 1e-12
    assert not compare("scalar", 3e-12, 0.0, rtol=1e-3, atol=1e-12).passed


@pytest.mark.requirements("REQ-QA-001")
def test_l2_uses_trapezoid_weights_of_the_sample_spacing():
    x = np.array([0.0, 1.0, 3.0])                     # uneven: weights 0.5, 1.5, 1.0
    numerical = Series(x, np.array([1.0, 1.0, 2.0]), "t", "f")
    result = compare("L2", numerical, np.array([1.0, 1.0, 1.0]), rtol=0.6, atol=0.0)
    assert result.e_abs == pytest.approx(math.sqrt(1.0 / 3.0))
    assert result.scale == pytest.approx(1.0)
    assert result.numerical == pytest.approx(math.sqrt((0.5 + 1.5 + 4.0) / 3.0))
    assert result.passed
    assert not compare("L2", numerical, np.ones(3), rtol=0.57, atol=0.0).passed


@pytest.mark.requirements("REQ-QA-001")
def test_linf_takes_the_largest_difference():
    x = np.linspace(0.0, 1.0, 5)
    numerical = Series(x, np.array([0.0, 1.0, 2.0, 3.1, 4.0]), "t", "f")
    result = compare("Linf", numerical, np.array([0.0, 1.0, 2.0, 3.0, 4.0]), rtol=0.026, atol=0.0)
    assert result.e_abs == pytest.approx(0.1) and result.scale == 4.0
    assert result.error == pytest.approx(0.025) and result.passed
    assert not compare("Linf", numerical, np.arange(5.0), rtol=0.024, atol=0.0).passed


@pytest.mark.requirements("REQ-QA-001")
def test_trapezoid_weights_take_absolute_spacing_and_fall_back_to_equal_weights():
    assert trapezoid_weights([0.0, 2.0, 1.0]).tolist() == [1.0, 1.5, 0.5]   # a curve may turn back
    assert trapezoid_weights([5.0, 5.0, 5.0]).tolist() == [1.0, 1.0, 1.0]
    assert trapezoid_weights([2.0]).tolist() == [1.0]


@pytest.mark.requirements("REQ-QA-001")
def test_upper_bound_and_equal():
    below = compare("upper_bound", 1.5, 1.0, rtol=1.0, atol=0.0)
    assert below.passed and below.error == pytest.approx(0.5) and below.tolerance == pytest.approx(1.0)
    assert compare("upper_bound", 0.2, 1.0, rtol=0.0, atol=0.0).error == pytest.approx(-0.8)
    assert not compare("upper_bound", 2.0000001, 1.0, rtol=1.0, atol=0.0).passed
    assert compare("equal", 5.0, 5.0, rtol=0.0, atol=0.0).passed
    assert not compare("equal", 0.0, 5.0, rtol=0.0, atol=0.0).passed


@pytest.mark.requirements("REQ-QA-001")
def test_not_a_number_fails():
    assert not compare("scalar", math.nan, 1.0, rtol=1e9, atol=1e9).passed
    assert not compare("upper_bound", math.nan, 1.0, rtol=1.0, atol=0.0).passed
    x = np.linspace(0.0, 1.0, 3)
    assert not compare("L2", Series(x, np.array([0.0, math.nan, 1.0]), "t", "f"), x, rtol=1e9, atol=0.0).passed


@pytest.mark.requirements("REQ-QA-001")
def test_the_pass_rule_text_names_every_norm():
    for norm in ("scalar", "L2", "Linf", "upper_bound", "equal"):
        assert norm + ":" in PASS_RULE
    assert "e_abs <= atol + rtol * s" in PASS_RULE


def _function_reference(name, component=None, **params):
    return Reference(name, params, component, None)


@pytest.mark.requirements("REQ-QA-001")
def test_array_reference_is_called_on_the_abscissa_and_component_picks_one():
    x = np.linspace(0.0, 1.0, 4)
    numerical = Series(x, 3.0 * x + 0.1, "us", "tau")

    def pair(us, *, k):
        return k * us, -us

    values = evaluate_reference(_function_reference("m.pair", component=0, k=3.0), numerical, pair)
    assert values.tolist() == pytest.approx((3.0 * x).tolist())
    values = evaluate_reference(_function_reference("m.pair", component=1, k=3.0), numerical, pair)
    assert values.tolist() == pytest.approx((-x).tolist())
    assert evaluate_reference(_function_reference("m.f", a=2.0), 1.0, lambda *, a: a * 2) == 4.0
    # A scalar from an array reference applies to every sample.
    assert evaluate_reference(_function_reference("m.c"), numerical, lambda us: 7.0).tolist() == [7.0] * 4


@pytest.mark.requirements("REQ-QA-002")
@pytest.mark.parametrize("function, component, phrase", [
    (lambda us: (us, us), None, "returns 2 components; name one with component"),
    (lambda us: (us + 1, us), 2, "has no component 2"),
    (lambda us: np.ones(3), None, r"returned \(3,\) values for 4 samples"),
    (lambda us: np.full(us.shape, np.nan), None, "not finite"),
    (lambda us: 1.0 / 0.0, None, "raised ZeroDivisionError"),
    (lambda us: "one", None, "returned"),
])
def test_unusable_references_are_rejected(function, component, phrase):
    x = np.linspace(0.0, 1.0, 4)
    with pytest.raises(ReferenceProblem, match=phrase):
        evaluate_reference(_function_reference("m.bad", component=component), Series(x, x + 0.5, "t", "h"), function)

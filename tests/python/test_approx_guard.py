"""The guard of conftest.py: a pytest.approx whose hidden absolute tolerance (1e-12) would decide
instead of the stated relative one is refused, so that every tolerance here is the one written."""
import pytest


@pytest.mark.requirements("REQ-QA-003")
def test_a_small_value_without_abs_is_refused():
    with pytest.raises(AssertionError, match="give abs="):
        pytest.approx(5e-12, rel=1e-3)
    with pytest.raises(AssertionError, match="give abs="):
        pytest.approx([1.0, 1e-7])  # the default rel of 1e-6 on 1e-7


@pytest.mark.requirements("REQ-QA-003")
def test_with_abs_stated_the_relative_tolerance_decides():
    assert 5.004e-12 == pytest.approx(5e-12, rel=1e-3, abs=0)
    assert 6e-12 != pytest.approx(5e-12, rel=1e-3, abs=0)  # within 1e-12, but 20 % off
    assert 1e-13 == pytest.approx(0.0, rel=1e-3)  # zero has no relative scale: 1e-12 applies as before

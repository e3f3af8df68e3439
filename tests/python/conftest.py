"""Shared pytest set-up: import paths and the requirement marker.

Every test names the requirement(s) it shows with
    @pytest.mark.requirements("REQ-AREA-NNN", ...)
The ids are written into the JUnit XML as the property "requirements", which is what
qa/traceability/audit.py reads to build the traceability matrix.
"""
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
for sub in ("verification", "verification/harness", "qa/traceability", "python"):
    path = str(ROOT / sub)
    if path not in sys.path:
        sys.path.insert(0, path)


def pytest_configure(config):
    config.addinivalue_line(
        "markers", "requirements(*ids): requirement ids (REQ-AREA-NNN) this test shows")


def pytest_collection_modifyitems(items):
    # Set at collection rather than by a fixture, so that a test skipped before its fixtures run
    # (one that needs a Slurm cluster) still names its requirements and reads as skipped, not as
    # a test of no requirement.
    for item in items:
        marker = item.get_closest_marker("requirements")
        if marker is not None:
            item.user_properties.append(("requirements", ",".join(marker.args)))


# pytest.approx without `abs` also accepts any difference below 1e-12: for expected values below
# 1e-12 / rel that hidden bound, not the stated rel, decides (approx(5e-12, rel=1e-3) accepts a
# 20 % error). Every comparison here must state the tolerance it means, so such a call is an error.
_approx = pytest.approx
HIDDEN_ABS = 1e-12


def _stated_approx(expected, rel=None, abs=None, nan_ok=False):
    if abs is None:
        import numpy as np
        values = np.abs(np.asarray(expected, dtype=float)).ravel()
        small = values[(values > 0) & (values * (1e-6 if rel is None else rel) < HIDDEN_ABS)]
        if small.size:
            raise AssertionError(f"pytest.approx({expected!r}, rel={rel}): below {HIDDEN_ABS:g} / rel the hidden "
                                 "absolute tolerance of 1e-12 decides, not rel; give abs= as well (abs=0 for none)")
    return _approx(expected, rel=rel, abs=abs, nan_ok=nan_ok)


pytest.approx = _stated_approx

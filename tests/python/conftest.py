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
for sub in ("verification", "verification/harness", "qa/traceability"):
    path = str(ROOT / sub)
    if path not in sys.path:
        sys.path.insert(0, path)


def pytest_configure(config):
    config.addinivalue_line(
        "markers", "requirements(*ids): requirement ids (REQ-AREA-NNN) this test shows")


@pytest.fixture(autouse=True)
def _record_requirements(request, record_property):
    marker = request.node.get_closest_marker("requirements")
    if marker is not None:
        record_property("requirements", ",".join(marker.args))

"""Every closed-form reference module stands apart from the solver: it imports nothing but the
standard math module, numpy and scipy (no vdec code, no harness, no results files)."""
import ast
from pathlib import Path

import pytest

ANALYTIC = Path(__file__).resolve().parents[2] / "verification" / "analytic"
MODULES = sorted(p for p in ANALYTIC.glob("*.py") if p.name != "__init__.py")


@pytest.mark.requirements("REQ-QA-003")
@pytest.mark.parametrize("module", MODULES, ids=lambda p: p.stem)
def test_module_imports_nothing_but_math_numpy_scipy(module):
    imported = set()
    for node in ast.walk(ast.parse(module.read_text())):
        if isinstance(node, ast.Import):
            imported |= {a.name.split(".")[0] for a in node.names}
        elif isinstance(node, ast.ImportFrom):
            imported.add((node.module or "").split(".")[0] if node.level == 0 else "<relative>")
    assert imported <= {"math", "numpy", "scipy"}


@pytest.mark.requirements("REQ-QA-003")
def test_every_module_is_checked():
    assert {p.stem for p in MODULES} >= {"rigid_blocks", "elastic"}

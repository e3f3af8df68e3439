"""Every closed-form reference module stands apart from the solver: it imports nothing but the
standard math module, numpy and scipy (no vdec code, no harness, no results files). The one
exception is joints.py, which runs the independent 50-digit program of verification/reference/;
that program in turn includes no header from src/ and links no vdec library."""
import ast
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
ANALYTIC = ROOT / "verification" / "analytic"
REFERENCE = ROOT / "verification" / "reference"
MODULES = sorted(p for p in ANALYTIC.glob("*.py") if p.name != "__init__.py")
SOURCES = sorted(p for p in REFERENCE.iterdir() if p.suffix in {".cpp", ".hpp", ".h", ".cc"})

ALLOWED = {"math", "numpy", "scipy"}
# joints.py has no closed form for the softening CY joint: it runs vdec_cy_reference (the
# 50-digit integrator in verification/reference/), so it alone may also use subprocess (to run
# it), os (to read VDEC_CY_REFERENCE / VDEC_EXECUTABLE and check the file) and shutil (to find a
# bare VDEC_EXECUTABLE on PATH). The program's own independence is checked below.
EXTRA = {"joints": {"subprocess", "os", "shutil"}}


@pytest.mark.requirements("REQ-QA-003")
@pytest.mark.parametrize("module", MODULES, ids=lambda p: p.stem)
def test_module_imports_nothing_but_math_numpy_scipy(module):
    imported = set()
    for node in ast.walk(ast.parse(module.read_text())):
        if isinstance(node, ast.Import):
            imported |= {a.name.split(".")[0] for a in node.names}
        elif isinstance(node, ast.ImportFrom):
            imported.add((node.module or "").split(".")[0] if node.level == 0 else "<relative>")
    assert imported <= ALLOWED | EXTRA.get(module.stem, set())


@pytest.mark.requirements("REQ-QA-003")
def test_every_module_is_checked():
    assert {p.stem for p in MODULES} >= {"rigid_blocks", "elastic", "joints"}


def _solver_folders():
    """The top-level folders of src/ (core, contact, joint, ...), the roots of the solver's
    include paths."""
    return {p.name for p in (ROOT / "src").iterdir() if p.is_dir()}


@pytest.mark.requirements("REQ-QA-003")
@pytest.mark.parametrize("source", SOURCES, ids=lambda p: p.name)
def test_reference_program_includes_no_solver_header(source):
    solver = _solver_folders()
    assert {"core", "contact", "joint"} <= solver
    for line in source.read_text().splitlines():
        m = re.match(r'\s*#\s*include\s*([<"])([^">]+)[">]', line)
        if not m:
            continue
        quoted, path = m.group(1) == '"', m.group(2)
        assert path.split("/")[0] not in solver | {"src", "vdec"}, f"{source.name}: {line.strip()}"
        assert "src/" not in path, f"{source.name}: {line.strip()}"
        if quoted:
            # A local header is fine, if it is one of verification/reference's own.
            local = (REFERENCE / path).resolve()
            assert local.parent == REFERENCE.resolve() and local.is_file(), f"{source.name}: {line.strip()}"


@pytest.mark.requirements("REQ-QA-003")
def test_reference_programs_exist_and_link_no_vdec_library():
    assert "cy_joint_reference.cpp" in {p.name for p in SOURCES}
    cmake = (REFERENCE / "CMakeLists.txt").read_text()
    code = "\n".join(line.split("#", 1)[0] for line in cmake.splitlines())   # comments out
    assert "add_executable(vdec_cy_reference" in code
    assert "vdec_core" not in code and not re.search(r"\bvdec\b", code)   # vdec_cy_reference is one word
    assert "src/" not in code and "CMAKE_SOURCE_DIR" not in code
    for call in re.findall(r"target_link_libraries\(([^)]*)\)", code):
        assert set(call.split()[2:]) <= {"Boost::headers", "Boost::boost"}, call
    # And the top-level build adds it.
    top = (ROOT / "CMakeLists.txt").read_text()
    assert "add_subdirectory(verification/reference)" in top

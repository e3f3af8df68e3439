"""Grouted cables through a scene (docs/models/support.md#cables, docs/user-manual/scene-format.md#cable):
the scene errors of their keys, a cable in a deformable block, yield, VTK, restart and threads."""
import json
import os
import re
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
VDEC = os.environ.get("VDEC_EXECUTABLE", str(ROOT / "build" / "vdec"))
PULLOUT = ROOT / "verification" / "problems" / "ST-CABLE-PULLOUT" / "scene.toml"
pytestmark = pytest.mark.skipif(not Path(VDEC).is_file(), reason="vdec is not built")


def run(tmp_path, text, *extra, name="scene"):
    scene = tmp_path / f"{name}.toml"
    scene.write_text(text)
    out = tmp_path / f"{name}-out"
    done = subprocess.run([VDEC, "run", str(scene), "--out", str(out), *extra], capture_output=True, text=True,
                          timeout=120)
    results = out / "results.json"
    return done, json.loads(results.read_text()) if results.is_file() else None


BASE = PULLOUT.read_text()

BAD = [
    ("no bond stiffness", BASE.replace("bond_stiffness = 1e8\n", ""), "bond_stiffness", "is required"),
    ("negative area", BASE.replace("area = 5e-4", "area = -5e-4"), "area", "> 0"),
    ("zero yield", BASE.replace("density = 7850.0\n", "density = 7850.0\nyield_tension = 0.0\n"), "yield_tension", "> 0"),
    ("unknown material", BASE.replace('material = "strand"', 'material = "rope"'), "material",
     "no [[cable_material]] is named 'rope'"),
    ("three points", BASE.replace("points = [[0.0, 0.0], [2.0, 0.0]]", "points = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]"),
     "points", "a cable is straight"),
    ("one point twice", BASE.replace("points = [[0.0, 0.0], [2.0, 0.0]]", "points = [[0.0, 0.0], [0.0, 0.0]]"), "points",
     "the same point"),
    ("zero elements", BASE.replace("elements = 20", "elements = 0"), "elements", "must be an integer in [1,"),
    ("two cables of one name", BASE + '[[cable]]\nname = "cable"\nmaterial = "strand"\npoints = [[0.0, 0.1], [1.0, 0.1]]\nelements = 2\n',
     "name", "is defined twice"),
    ("node of no cable", BASE.replace('cable = "cable"\npoint = [0.0, 0.0]\nforce', 'cable = "rope"\npoint = [0.0, 0.0]\nforce'),
     "cable", "no [[cable]] is named 'rope'"),
    ("node far from the cable", BASE.replace("point = [0.0, 0.0]\nforce", "point = [0.0, 1.0]\nforce"), "point",
     "from the nearest node of cable 'cable'"),
    ("node given nothing", BASE.replace("force = -1e4\n", ""), "cable_node", "gives the node nothing"),
    ("history of no cable", BASE.replace('name = "head"\nquantity = "cable.displacement"\ncable = "cable"',
                                         'name = "head"\nquantity = "cable.displacement"\ncable = "rope"'), "cable",
     "no [[cable]] is named 'rope'"),
    ("unknown cable key", BASE.replace("elements = 20", "elements = 20\npretension = 1e3"), "pretension", "unknown"),
]


@pytest.mark.requirements("REQ-STRUCT-008")
@pytest.mark.parametrize("what, text, key, phrase", BAD, ids=[b[0] for b in BAD])
def test_bad_cable_input_is_a_scene_error_naming_the_key(tmp_path, what, text, key, phrase):
    done, _ = run(tmp_path, text)
    assert done.returncode == 3, (what, done.stderr)
    assert key in done.stderr and phrase in done.stderr, (what, done.stderr)
    assert re.search(r"scene\.toml:\d+", done.stderr), ("the message names the file and line", done.stderr)


ZONED = BASE.replace('fix = ["x", "y", "rotation"]', "zoning = { nx = 12, ny = 4 }") + \
    '[[boundary]]\nblock = "rock"\nx = [3.0, 3.0]\nfix = ["x", "y"]\n'


@pytest.mark.requirements("REQ-STRUCT-007")
def test_a_cable_in_a_deformable_block_passes_its_pull_to_the_zones(tmp_path):
    # Grouted in zones: the grout's reactions load the gridpoints; at rest they carry the head's
    # pull (statics), and a stiff block leaves the cable's forces as in rigid rock.
    done, results = run(tmp_path, ZONED.replace("young", "young").replace('density = 2500.0\n', 'density = 2500.0\nyoung = 1e13\npoisson = 0.25\n', 1),
                        name="zoned")
    assert done.returncode == 0, done.stderr
    nodes = results["cables"]["nodes"]
    assert all(nodes["grouted"])
    assert sum(nodes["bond_force"]) == pytest.approx(1e4, rel=1e-6)
    # the grout pulls the rock towards the head (-x), the far face held
    assert min(results["gridpoints"]["displacement_x"]) < -1e-12
    done, rigid = run(tmp_path, BASE, name="rigid")
    assert results["histories"]["force_middle"]["value"][-1] == pytest.approx(
        rigid["histories"]["force_middle"]["value"][-1], rel=1e-3)


@pytest.mark.requirements("REQ-STRUCT-007")
def test_an_element_yields_at_its_tensile_strength(tmp_path):
    # The head's element would carry 9.48 kN elastically; capped at 3 kN it holds 3 kN while it
    # stretches plastically, never more, and the yield's work is dissipated. (The load comes at once:
    # after the overshoot the element unloads elastically below its cap.)
    capped = BASE.replace("density = 7850.0\n", "density = 7850.0\nyield_tension = 3000.0\n")
    done, results = run(tmp_path, capped)
    assert done.returncode == 0, done.stderr
    history = results["histories"]["force_first"]["value"]
    assert max(history) == 3000.0, "it reached its cap and went no further"
    assert max(results["cables"]["elements"]["axial_force"]) <= 3000.0
    assert results["energy"]["plastic_dissipation"] > 0.0
    done, elastic = run(tmp_path, BASE, name="elastic")
    assert max(elastic["histories"]["force_first"]["value"]) > 9000.0
    assert elastic["energy"]["plastic_dissipation"] == 0.0


@pytest.mark.requirements("REQ-STRUCT-007")
def test_a_run_restarted_with_cables_is_the_run_that_did_not_stop(tmp_path):
    text = BASE.replace("[stop]\nratio = 1e-7\ncycles = 500000\n", "") + \
        '[[phase]]\nname = "one"\nstop = { cycles = 300 }\n[[phase]]\nname = "two"\nstop = { cycles = 300 }\n'
    done, whole = run(tmp_path, text, "--save", "one", name="whole")
    assert done.returncode == 0, done.stderr
    state = tmp_path / "whole-out" / "after-phase-1.vdecstate"
    resumed = subprocess.run([VDEC, "run", str(tmp_path / "whole.toml"), "--out", str(tmp_path / "resumed"),
                              "--restart", str(state)], capture_output=True, text=True, timeout=120)
    assert resumed.returncode == 0, resumed.stderr
    again = json.loads((tmp_path / "resumed" / "results.json").read_text())
    for key in ("cables", "histories", "energy"):
        assert again[key] == whole[key], key


@pytest.mark.requirements("REQ-STRUCT-007")
def test_cable_results_do_not_depend_on_the_thread_count(tmp_path):
    text = ZONED.replace('density = 2500.0\n', 'density = 2500.0\nyoung = 10e9\npoisson = 0.25\n', 1)
    text = text.replace("[stop]\nratio = 1e-7\ncycles = 500000\n", "[stop]\ncycles = 2000\n")
    one, a = run(tmp_path, text, "--threads", "1", name="one")
    two, b = run(tmp_path, text, "--threads", "2", name="two")
    assert one.returncode == 0 and two.returncode == 0, (one.stderr, two.stderr)
    for key in ("cables", "gridpoints", "histories"):
        assert a[key] == b[key], key


@pytest.mark.requirements("REQ-STRUCT-007")
def test_vtk_snapshots_hold_the_cable_elements(tmp_path):
    import xml.etree.ElementTree as ET
    done, results = run(tmp_path, BASE + "\n[output]\nvtk_every = 100000\n")
    assert done.returncode == 0, done.stderr
    last = sorted((tmp_path / "scene-out" / "vtk").glob("snapshot_*.vtu"))[-1]
    piece = ET.parse(last).getroot().find("UnstructuredGrid/Piece")
    arrays = {a.get("Name"): [float(x) for x in (a.text or "").split()] for a in piece.iter("DataArray")}
    kind_name = next(name for name in arrays if name.startswith("kind"))
    assert "6 cable element" in kind_name
    cables = [i for i, k in enumerate(arrays[kind_name]) if k == 6]
    assert [arrays["axial_force"][i] for i in cables] == results["cables"]["elements"]["axial_force"]

"""Grouted cables through a scene (docs/models/support.md#cables, docs/user-manual/scene-format.md#cable):
the scene errors of their keys, a cable in a deformable block, yield, VTK, restart and threads."""
import math
import re

import pytest

from scene_runs import ROOT, last_vtk_cell_arrays, needs_vdec, restart, run

PULLOUT = ROOT / "verification" / "problems" / "ST-CABLE-PULLOUT" / "scene.toml"
pytestmark = needs_vdec


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
    ("unknown cable key", BASE.replace("elements = 20", "elements = 20\nprestress = 1e3"), "prestress", "unknown"),
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
    resumed, again = restart(tmp_path, "whole", tmp_path / "whole-out" / "after-phase-1.vdecstate", "resumed")
    assert resumed.returncode == 0, resumed.stderr
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
    done, results = run(tmp_path, BASE + "\n[output]\nvtk_every = 100000\n")
    assert done.returncode == 0, done.stderr
    arrays, kind_name = last_vtk_cell_arrays(tmp_path / "scene-out")
    assert "6 cable element" in kind_name
    cables = [i for i, k in enumerate(arrays[kind_name]) if k == 6]
    assert [arrays["axial_force"][i] for i in cables] == results["cables"]["elements"]["axial_force"]


PRETENSION = (ROOT / "verification" / "problems" / "ST-CABLE-PRETENSION" / "scene.toml").read_text()
BAD_ANCHOR = [
    ("pretension without a head", PRETENSION.replace("head = true\n", ""), "pretension", "give head = true and a free_length > 0"),
    ("pretension without a free length", PRETENSION.replace("free_length = 2.5\n", ""), "pretension",
     "give head = true and a free_length > 0"),
    ("free length the whole cable", PRETENSION.replace("free_length = 2.5", "free_length = 4.0"), "free_length",
     "must be shorter than the cable (4 m)"),
    ("negative pretension", PRETENSION.replace("pretension = 2e4", "pretension = -1.0"), "pretension", ">= 0"),
    ("head off the rock", PRETENSION.replace("points = [[0.0, 0.0], [4.0, 0.0]]", "points = [[-0.5, 0.0], [4.0, 0.0]]"),
     "head", "its head at (-0.5, 0) lies on no block"),
]


@pytest.mark.requirements("REQ-STRUCT-012")
@pytest.mark.parametrize("what,text,key,phrase", BAD_ANCHOR, ids=[b[0] for b in BAD_ANCHOR])
def test_bad_anchor_input_is_a_scene_error_naming_the_key(tmp_path, what, text, key, phrase):
    assert text != PRETENSION
    done, _ = run(tmp_path, text)
    assert done.returncode == 3, (what, done.stderr)
    assert f".{key}'" in done.stderr and phrase in done.stderr, (what, done.stderr)
    assert re.search(r"scene\.toml:\d+", done.stderr), done.stderr


@pytest.mark.requirements("REQ-STRUCT-012")
def test_a_tensioned_anchor_in_zones_passes_its_pretension_to_the_rock(tmp_path):
    # In a deformable block held at its far face: the plate pushes the face in, the anchor's grout
    # pulls the rock out; at rest the plate's and the grout's forces balance the free length's, and
    # the pretension's elastic energy was supplied at the start.
    zoned = PRETENSION.replace('fix = ["x", "y", "rotation"]', "zoning = { nx = 25, ny = 4 }").replace(
        'density = 2500.0\n', 'density = 2500.0\nyoung = 1e10\npoisson = 0.25\n', 1) + \
        '[[boundary]]\nblock = "rock"\nx = [5.0, 5.0]\nfix = ["x", "y"]\n'
    done, results = run(tmp_path, zoned)
    assert done.returncode == 0, done.stderr
    nodes, elements = results["cables"]["nodes"], results["cables"]["elements"]
    free = elements["axial_force"][0]
    assert 0.5 * 2e4 < free < 2e4, "some pretension lost to the anchor's give and the rock's"
    assert nodes["bond_force"][0] == pytest.approx(-free, rel=1e-6)
    assert sum(nodes["bond_force"][25:]) == pytest.approx(free, rel=1e-6)
    assert all(f == 0.0 for f in nodes["bond_force"][1:25]), "the free length is not grouted"
    assert results["energy"]["initial"] == pytest.approx(0.5 * 2e4 ** 2 * 2.5 / 1e8, rel=1e-12)
    # the face under the plate moved into the rock (+x), the anchor's rock towards the face
    gp = results["gridpoints"]
    face = [u for x, u in zip(gp["x0"], gp["displacement_x"]) if x == 0.0]
    assert min(face) > 0.0


@pytest.mark.requirements("REQ-STRUCT-013")
def test_the_grout_from_its_annulus_is_the_spring_slider_of_the_reference(tmp_path):
    # 1.4-42 to 1.4-44: K_bond = 2 pi G / ln(1 + 2t / D), S_bond = pi (D + 2t) tau_peak; the pull-out
    # with the bond capped, given either way, is the same run.
    D, t = 0.025, 0.0125
    G = 1e8 * math.log(1.0 + 2.0 * t / D) / (2.0 * math.pi)
    tau = 8000.0 / (math.pi * (D + 2.0 * t))
    capped = BASE.replace("bond_stiffness = 1e8\n", "bond_stiffness = 1e8\nbond_strength = 8000.0\n")
    annulus = BASE.replace("bond_stiffness = 1e8\n", f"diameter = {D!r}\ngrout_thickness = {t!r}\n"
                           f"grout_shear_modulus = {G!r}\ngrout_shear_strength = {tau!r}\n")
    done, given = run(tmp_path, capped, name="given")
    assert done.returncode == 0, done.stderr
    done, derived = run(tmp_path, annulus, name="annulus")
    assert done.returncode == 0, done.stderr
    assert any(derived["cables"]["nodes"]["slipping"]), "the bond slips near the head"
    for name in ("force_first", "force_middle", "head"):
        assert derived["histories"][name]["value"][-1] == pytest.approx(given["histories"][name]["value"][-1], rel=1e-9, abs=0)
    both = annulus.replace("grout_thickness", "bond_stiffness = 1e8\ngrout_thickness")
    done, _ = run(tmp_path, both, name="both")
    assert done.returncode == 3 and "'cable_material[0].bond_stiffness'" in done.stderr and "not both" in done.stderr, done.stderr
    half = BASE.replace("bond_stiffness = 1e8\n", "bond_stiffness = 1e8\ndiameter = 0.025\n")
    done, _ = run(tmp_path, half, name="half")
    assert done.returncode == 3 and "'cable_material[0].diameter'" in done.stderr and "give grout_shear_modulus" in done.stderr, done.stderr
    no_modulus = annulus.replace(f"grout_shear_modulus = {G!r}\n", "")
    done, _ = run(tmp_path, no_modulus, name="no-modulus")
    assert done.returncode == 3 and "'cable_material[0].grout_shear_modulus'" in done.stderr and "is required" in done.stderr, done.stderr

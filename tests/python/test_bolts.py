"""Local reinforcement across joints through a scene (docs/models/support.md#local-reinforcement-across-joints,
docs/user-manual/scene-format.md#bolt): the scene errors of its keys, reinforcements at every joint a bolt
crosses, rigid and zoned blocks, installation and removal by phases (bolts and cables), excavation and
restart."""
import re

import pytest

from scene_runs import ROOT, last_vtk_cell_arrays, needs_vdec, restart, run

SHEAR = ROOT / "verification" / "problems" / "ST-BOLT-SHEAR" / "scene.toml"
pytestmark = needs_vdec


BASE = SHEAR.read_text()
BOLT = '[[phase.bolt]]\nname = "b"\nmaterial = "bar"\npoints = [[-0.3, -0.3], [0.3, 0.3]]\n'

BAD = [
    ("no axial stiffness", BASE.replace("axial_stiffness = 1e8\n", ""), "axial_stiffness", "is required"),
    ("no shear stiffness", BASE.replace("shear_stiffness = 2e7\n", ""), "shear_stiffness", "is required"),
    ("negative shear stiffness", BASE.replace("shear_stiffness = 2e7", "shear_stiffness = -1.0"), "shear_stiffness",
     ">= 0"),
    ("zero active length", BASE.replace("active_length = 0.2", "active_length = 0.0"), "active_length", "> 0"),
    ("zero axial strength", BASE.replace("axial_strength = 1e5", "axial_strength = 0.0"), "axial_strength", "> 0"),
    ("zero spacing", BASE.replace("crushing = false", "crushing = false\nspacing = 0.0"), "spacing", "> 0"),
    ("unknown key", BASE.replace("crushing = false", "crushing = false\ndiameter = 0.025"), "diameter", "unknown key"),
    ("material twice", BASE.replace("[[phase]]", '[[bolt_material]]\nname = "bar"\naxial_stiffness = 1.0\n'
                                    'shear_stiffness = 0.0\nactive_length = 0.1\n\n[[phase]]', 1),
     "name", "bolt material 'bar' is defined twice"),
    ("unknown material", BASE.replace('material = "bar"', 'material = "rope"'), "material",
     "no [[bolt_material]] is named 'rope'"),
    ("three points", BASE.replace("points = [[-0.3, -0.3], [0.3, 0.3]]", "points = [[-0.3, -0.3], [0.0, 0.0], [0.3, 0.3]]"),
     "points", "a bolt is straight"),
    ("one point twice", BASE.replace("points = [[-0.3, -0.3], [0.3, 0.3]]", "points = [[0.3, 0.3], [0.3, 0.3]]"),
     "points", "the same point"),
    ("two bolts of one name in a phase", BASE + BOLT, "name", "'b' names a support or boundary active when the phase starts"),
    ("two bolts of one name", BASE.replace("[[phase]]", '[[bolt]]\nname = "a"\nmaterial = "bar"\npoints = [[0.0, -0.5], [0.0, 0.5]]\n'
                                           '[[bolt]]\nname = "a"\nmaterial = "bar"\npoints = [[0.1, -0.5], [0.1, 0.5]]\n\n[[phase]]', 1),
     "name", "bolt 'a' is defined twice"),
    ("crossing nothing at the start", BASE.replace("[[phase]]", '[[bolt]]\nname = "inside"\nmaterial = "bar"\n'
                                                   'points = [[-1.0, -0.8], [1.0, -0.2]]\n\n[[phase]]', 1),
     "points", "bolt 'inside' from (-1, -0.8) to (1, -0.2) crosses no joint between two blocks"),
    ("a bolt named as a cable", BASE.replace("[[phase]]", '[[cable_material]]\nname = "strand"\nyoung = 2e11\narea = 1e-4\n'
                                             'density = 7850.0\nbond_stiffness = 1e8\n[[cable]]\nname = "b0"\n'
                                             'material = "strand"\npoints = [[-1.0, -0.5], [1.0, -0.5]]\nelements = 4\n'
                                             '[[bolt]]\nname = "b0"\nmaterial = "bar"\npoints = [[0.0, -0.5], [0.0, 0.5]]\n'
                                             '\n[[phase]]', 1),
     "name", "bolt 'b0' has the name of a boundary, beam or cable"),
    ("history of an unknown bolt", BASE.replace('bolt = "b"\npoint = [0.0, 0.0]\nevery = 100\n[[history]]\nname = "Fs"',
                                                'bolt = "c"\npoint = [0.0, 0.0]\nevery = 100\n[[history]]\nname = "Fs"'),
     "bolt", "no [[bolt]] or [[phase.bolt]] is named 'c'"),
]


@pytest.mark.requirements("REQ-STRUCT-010")
@pytest.mark.parametrize("what,text,key,phrase", BAD, ids=[b[0] for b in BAD])
def test_bad_bolt_input_is_a_scene_error_naming_the_key(tmp_path, what, text, key, phrase):
    assert text != BASE, "the case changes the scene"
    done, _ = run(tmp_path, text)
    assert done.returncode == 3, (what, done.stderr)
    assert f"'{key}'" in done.stderr or f".{key}'" in done.stderr, (what, done.stderr)
    assert phrase in done.stderr, (what, done.stderr)
    assert re.search(r"scene\.toml:\d+", done.stderr), ("the message names the file and line", done.stderr)


@pytest.mark.requirements("REQ-STRUCT-010")
def test_a_phase_bolt_that_crosses_no_joint_stops_the_run_naming_the_phase(tmp_path):
    text = BASE.replace("points = [[-0.3, -0.3], [0.3, 0.3]]", "points = [[-1.0, -0.8], [1.0, -0.2]]")
    done, _ = run(tmp_path, text)
    assert done.returncode == 3, done.stderr
    assert "phase 'shear': bolt 'b'" in done.stderr and "crosses no joint" in done.stderr, done.stderr


# A roof (fixed) and two blocks hanging below it, one under the other, held by one vertical bolt
# through both joints: the joints open (no tension) and the bolt carries the blocks' weight.
HANGING = """
title = "Two blocks hanging from a roof on one bolt"
[model]
gravity = [0.0, -10.0]
rounding = 0.01
[solver]
local_damping = 0.8
[stop]
ratio = 1e-8
cycles = 400000
[[block_material]]
name = "rock"
density = 2500.0
young = 1e10
poisson = 0.25
[[joint_material]]
name = "joint"
law = "coulomb-slip"
kn = 1e10
ks = 1e10
friction = 30.0
[[block]]
name = "roof"
material = "rock"
vertices = [[-1.0, 0.0], [1.0, 0.0], [1.0, 1.0], [-1.0, 1.0]]
fix = ["x", "y", "rotation"]
[[block]]
name = "upper"
material = "rock"
vertices = [[-0.5, -1.0], [0.5, -1.0], [0.5, 0.0], [-0.5, 0.0]]
[[block]]
name = "lower"
material = "rock"
vertices = [[-0.5, -2.0], [0.5, -2.0], [0.5, -1.0], [-0.5, -1.0]]
[[bolt_material]]
name = "bar"
axial_stiffness = 1e8
shear_stiffness = 1e7
axial_strength = 1e6
active_length = 0.2
[[bolt]]
name = "b"
material = "bar"
points = [[0.0, -1.7], [0.0, 0.5]]
[[history]]
name = "drop"
quantity = "block.displacement_y"
block = "lower"
"""
WEIGHT = 2500.0 * 1.0 * 10.0  # N/m a block


def stretch(force, *, K=1e8, bound=1e6):
    # inverse of F = K u F_max / (F_max + K u)
    return force * bound / (K * (bound - force))


@pytest.mark.requirements("REQ-STRUCT-009")
def test_a_bolt_reinforces_every_joint_it_crosses(tmp_path):
    done, results = run(tmp_path, HANGING)
    assert done.returncode == 0, done.stderr
    bolts = results["bolts"]
    assert bolts["names"] == ["b"] and bolts["installed"] == [1]
    x = bolts["reinforcements"]
    blocks = [b["name"] for b in results["blocks"]]
    # From the lowest point up: out of `lower` into `upper` at y = -1, out of `upper` into `roof` at y = 0.
    assert [(blocks[a], blocks[b]) for a, b in zip(x["block_0"], x["block_1"])] == [("lower", "upper"), ("upper", "roof")]
    assert x["y"] == pytest.approx([-1.0, 0.0], abs=1e-9)
    # Statics: the lower joint carries one block's weight, the upper two; the joints hold no
    # tension, so each opens by its reinforcement's axial displacement, and the lower block drops by
    # both. The law is hysteretic (it reloads softer than it unloads): the blocks' oscillation while
    # they settle leaves each opening beyond the monotonic stretch F F_max / (K (F_max - F)).
    assert x["axial_force"] == pytest.approx([WEIGHT, 2 * WEIGHT], rel=1e-6)
    assert x["shear_force"] == pytest.approx([0.0, 0.0], abs=1e-6)
    assert results["histories"]["drop"]["value"][-1] == pytest.approx(-sum(x["axial_displacement"]), rel=1e-9, abs=0)
    assert x["axial_displacement"][0] > stretch(WEIGHT) and x["axial_displacement"][1] > stretch(2 * WEIGHT)
    assert x["axial_displacement"] == pytest.approx([stretch(WEIGHT), stretch(2 * WEIGHT)], rel=0.15)


@pytest.mark.requirements("REQ-STRUCT-009")
def test_a_bolt_across_zoned_blocks_loads_their_gridpoints(tmp_path):
    zoned = HANGING.replace('name = "upper"\nmaterial = "rock"\n', 'name = "upper"\nmaterial = "rock"\nzoning = { nx = 4, ny = 4 }\n')
    zoned = zoned.replace('name = "lower"\nmaterial = "rock"\n', 'name = "lower"\nmaterial = "rock"\nzoning = { nx = 4, ny = 4 }\n')
    zoned = zoned.replace('[[history]]\nname = "drop"\nquantity = "block.displacement_y"\nblock = "lower"\n', "")
    done, results = run(tmp_path, zoned)
    assert done.returncode == 0, done.stderr
    x = results["bolts"]["reinforcements"]
    assert len(x["bolt"]) == 2
    # The same statics through the zones' gridpoints: the weights the bolt carries.
    assert x["axial_force"] == pytest.approx([WEIGHT, 2 * WEIGHT], rel=1e-5)
    # The lower block hangs below the upper: its gridpoints dropped by at least the lower joint's opening.
    assert min(results["gridpoints"]["displacement_y"]) < -stretch(WEIGHT)


PHASED = HANGING.replace("[stop]\nratio = 1e-8\ncycles = 400000\n", "").replace(
    '[[bolt]]\nname = "b"\nmaterial = "bar"\npoints = [[0.0, -1.7], [0.0, 0.5]]\n', "").replace(
    'name = "upper"\nmaterial = "rock"\n', 'name = "upper"\nmaterial = "rock"\nfix = ["x", "y", "rotation"]\n').replace(
    'name = "lower"\nmaterial = "rock"\n', 'name = "lower"\nmaterial = "rock"\nfix = ["x", "y", "rotation"]\n') + """
[[cable_material]]
name = "strand"
young = 2e11
area = 1e-4
density = 7850.0
bond_stiffness = 1e9
[[phase]]
name = "held"
stop = { cycles = 10 }
[[phase]]
name = "supported"
stop = { ratio = 1e-8, cycles = 400000 }
[[phase.block]]
name = "upper"
free = ["x", "y", "rotation"]
[[phase.block]]
name = "lower"
free = ["x", "y", "rotation"]
SUPPORT
[[phase]]
name = "released"
free = ["s"]
local_damping = 0.0
stop = { time = 0.05 }
"""
PHASE_BOLT = '[[phase.bolt]]\nname = "s"\nmaterial = "bar"\npoints = [[0.0, -1.7], [0.0, 0.5]]\n'
PHASE_CABLE = '[[phase.cable]]\nname = "s"\nmaterial = "strand"\npoints = [[0.0, -1.9], [0.0, 0.9]]\nelements = 28\n'


@pytest.mark.requirements("REQ-STRUCT-011")
def test_phases_install_and_free_bolts_and_cables(tmp_path):
    for support in (PHASE_BOLT, PHASE_CABLE):
        text = PHASED.replace("SUPPORT\n", support)
        done, results = run(tmp_path, text, name="bolt" if "bolt" in support else "cable")
        assert done.returncode == 0, done.stderr
        stops = [p["stop_reason"] for p in results["phases"]]
        assert stops == ["cycles", "ratio", "time"], stops
        # Freed in the last phase (undamped): it holds nothing, and the blocks fall freely.
        kind = "bolts" if "bolt" in support else "cables"
        assert results[kind]["installed"] == [0]
        drop = results["histories"]["drop"]["value"][-1]
        assert drop < -0.5 * 10.0 * 0.05 ** 2 * 0.9, drop
    # While it was in (the run stopped at the end of "supported"), it carried both blocks.
    held = PHASED.replace("SUPPORT\n", PHASE_BOLT).split('[[phase]]\nname = "released"')[0]
    done, results = run(tmp_path, held, name="held")
    assert done.returncode == 0, done.stderr
    assert results["bolts"]["installed"] == [1]
    assert results["bolts"]["reinforcements"]["axial_force"] == pytest.approx([WEIGHT, 2 * WEIGHT], rel=1e-6)
    done, results = run(tmp_path, PHASED.replace("SUPPORT\n", PHASE_CABLE).split('[[phase]]\nname = "released"')[0],
                        name="cable-held")
    assert done.returncode == 0, done.stderr
    assert results["cables"]["installed"] == [1]
    assert max(results["cables"]["elements"]["axial_force"]) == pytest.approx(2 * WEIGHT, rel=1e-3)


@pytest.mark.requirements("REQ-STRUCT-011")
def test_an_excavated_side_breaks_the_reinforcement(tmp_path):
    text = HANGING.replace("[stop]\nratio = 1e-8\ncycles = 400000\n", "") + """
[[phase]]
name = "hung"
stop = { ratio = 1e-8, cycles = 400000 }
[[phase]]
name = "dug"
stop = { ratio = 1e-8, cycles = 400000 }
[[phase.excavation]]
polygon = [[-0.6, -2.1], [0.6, -2.1], [0.6, -1.2], [-0.6, -1.2]]
"""
    done, results = run(tmp_path, text.replace('block = "lower"', 'block = "upper"'))
    assert done.returncode == 0, done.stderr
    x = results["bolts"]["reinforcements"]
    assert x["broken"] == [1, 0]
    # The lower block gone, the upper joint carries the upper block alone.
    assert x["axial_force"] == pytest.approx([0.0, WEIGHT], rel=1e-6, abs=1e-9)


@pytest.mark.requirements("REQ-STRUCT-011")
def test_a_restart_continues_a_bolted_run_bitwise(tmp_path):
    text = BASE.replace("time = 1.0", "time = 0.2")
    done, whole = run(tmp_path, text, "--save", "load", name="whole")
    assert done.returncode == 0, done.stderr
    resumed, again = restart(tmp_path, "whole", tmp_path / "whole-out" / "after-phase-1.vdecstate", "resumed")
    assert resumed.returncode == 0, resumed.stderr
    for key in ("bolts", "histories", "blocks"):
        assert again[key] == whole[key], key
    # and from a state saved with the bolt in, mid-shear
    text2 = text + '[[phase]]\nname = "more"\nstop = { time = 0.1 }\n'
    done, whole2 = run(tmp_path, text2, "--save", "shear", name="whole2")
    assert done.returncode == 0, done.stderr
    resumed, again = restart(tmp_path, "whole2", tmp_path / "whole2-out" / "after-phase-2.vdecstate", "resumed2")
    assert resumed.returncode == 0, resumed.stderr
    assert again["bolts"] == whole2["bolts"] and again["histories"] == whole2["histories"]


@pytest.mark.requirements("REQ-STRUCT-009")
def test_vtk_snapshots_hold_the_reinforcements(tmp_path):
    done, results = run(tmp_path, HANGING + "\n[output]\nvtk_every = 1000000\n")
    assert done.returncode == 0, done.stderr
    arrays, kind_name = last_vtk_cell_arrays(tmp_path / "scene-out")
    assert "7 bolt reinforcement" in kind_name
    cells = [i for i, k in enumerate(arrays[kind_name]) if k == 7]
    assert [arrays["axial_force"][i] for i in cells] == results["bolts"]["reinforcements"]["axial_force"]

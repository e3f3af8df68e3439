"""Simply-deformable blocks through a scene (docs/models/simply-deformable.md): their scene errors,
their strain under large rotation, the energy account, phases, excavation, restart and threads."""
import math

import pytest

from scene_runs import ROOT, needs_vdec, restart, run

pytestmark = needs_vdec
PLATEN = (ROOT / "verification" / "problems" / "SD-PLATEN" / "scene.toml").read_text()
COLUMN = (ROOT / "verification" / "problems" / "SD-COLUMN-FREQUENCY" / "scene.toml").read_text()

BAD = [
    ("unknown kind", PLATEN.replace('\nkind = "simply-deformable"\n', '\nkind = "elastic"\n'), "block[1].kind", "unknown block kind 'elastic'"),
    ("kind on a zoned block", PLATEN.replace('\nkind = "simply-deformable"\n', '\nkind = "simply-deformable"\nzoning = { nx = 2, ny = 2 }\n'),
     "block[1].kind", "a zoned block is fully deformable"),
    ("material without elasticity", PLATEN.replace('material = "rock"\nkind = "simply-deformable"',
                                                   'material = "steel"\nkind = "simply-deformable"'),
     "block[1].material", "strains elastically"),
    ("with a fluid", PLATEN.replace("friction = 0.0", "friction = 0.0\naperture = 1e-4\nresidual_aperture = 1e-5") +
     "[fluid]\nbulk_modulus = 2e9\nviscosity = 1e-3\n", "block[1].kind", "fluid pressures in the joints"),
    ("strain history of a rigid block", PLATEN + '[[history]]\nname = "p"\nquantity = "block.syy"\nblock = "platen"\n',
     "history[4].block", "is rigid: block.syy is the stress or strain of a simply-deformable block"),
    ("plastic material", PLATEN.replace("poisson = 0.25", "poisson = 0.25\nfriction = 30.0\ncohesion = 1e6"),
     "block[1].material", "has a Mohr-Coulomb strength"),
    ("viscous boundary on it", PLATEN + '[[boundary]]\nblock = "sample"\nx = [0.0, 0.0]\nviscous = true\n',
     "boundary[0].block", "is simply deformable: a viscous boundary"),
    ("phase strength on its material", PLATEN.split("[stop]")[0] + "[[phase]]\nname = \"weaken\"\nstop = { cycles = 10 }\n"
                                                                   "[[phase.block_material]]\nname = \"rock\"\nfriction = 30.0\ncohesion = 1e5\n",
     "phase[0].block_material[0].name", "which is elastic"),
]


@pytest.mark.requirements("REQ-SD-004")
@pytest.mark.parametrize("what,text,key,phrase", BAD, ids=[b[0] for b in BAD])
def test_bad_simply_deformable_input_is_a_scene_error_naming_the_key(tmp_path, what, text, key, phrase):
    done, _ = run(tmp_path, text)
    assert done.returncode == 3, (what, done.stderr)
    assert key in done.stderr and phrase in done.stderr, (what, done.stderr)


SPINNER = """[model]
rounding = 0.01
gravity = [0.0, 0.0]
[[block_material]]
name = "rock"
density = 2500.0
young = 10e9
poisson = 0.25
[[joint_material]]
name = "joint"
kn = 1e10
ks = 1e10
[[block]]
name = "spinner"
material = "rock"
kind = "simply-deformable"
vertices = [[0.0, 0.0], [3.0, 0.0], [3.0, 1.0], [0.0, 1.0]]
angular_velocity = 10.0
[[history]]
name = "exx"
quantity = "block.exx"
block = "spinner"
[[history]]
name = "rotation"
quantity = "block.rotation"
block = "spinner"
[stop]
time = 2.0
"""


@pytest.mark.requirements("REQ-SD-001")
def test_a_spinning_block_stays_unstrained_through_large_rotations(tmp_path):
    # A free 3 m x 1 m block turning at 10 rad/s for 2 s (three turns), nothing on it: its
    # strain is measured in its own frame, so the rotation strains nothing (an unobjective strain,
    # the displacement gradient of the world's axes, would reach order one), its outline keeps
    # its shape and its angular velocity stays.
    done, results = run(tmp_path, SPINNER)
    assert done.returncode == 0, done.stderr
    assert results["histories"]["rotation"]["value"][-1] == pytest.approx(10.0 * results["run"]["time"], rel=1e-9, abs=0)
    [block] = results["blocks"]
    assert block["kind"] == "simply-deformable"
    assert max(abs(v) for v in block["strain"].values()) == 0.0
    assert max(abs(v) for v in results["histories"]["exx"]["value"]) == 0.0
    assert block["angular_velocity"] == 10.0


@pytest.mark.requirements("REQ-SD-003")
def test_the_undamped_column_keeps_its_energy_as_the_rigid_column_does(tmp_path):
    # The column of SD-COLUMN-FREQUENCY, undamped: gravity's work is its kinetic and elastic energy
    # (blocks and joints), up to the explicit scheme's error in the contacts' springs, which the
    # same column of rigid blocks shows too (2e-5 of the work): the blocks' strain adds none.
    rigid_text = (ROOT / "verification" / "problems" / "SD-COLUMN-FREQUENCY" / "rigid.toml").read_text()
    balance = {}
    for name, text in (("strained", COLUMN), ("rigid", rigid_text)):
        done, results = run(tmp_path, text, name=name)
        assert done.returncode == 0, done.stderr
        e = results["energy"]
        assert e["external_work"] > 0.0 and e["kinetic"] > 0.0 and e["strain"] > 0.0
        balance[name] = (abs((e["kinetic"] + e["strain"] + e["joint_release"]) / e["external_work"] - 1.0), e["largest_excess"])
    assert balance["strained"][0] < 1e-5 and balance["strained"][0] <= balance["rigid"][0]
    assert balance["strained"][1] <= balance["rigid"][1]


PHASED = PLATEN.split("[solver]")[0] + """[solver]
local_damping = 0.8
[[phase]]
name = "load"
stop = { cycles = 3000 }
[[phase]]
name = "settle"
stop = { cycles = 3000 }
"""


@pytest.mark.requirements("REQ-SD-003")
def test_a_phased_run_restarts_bitwise(tmp_path):
    done, whole = run(tmp_path, PHASED, "--save", "load", name="platen")
    assert done.returncode == 0, done.stderr
    resumed, again = restart(tmp_path, "platen", tmp_path / "platen-out" / "after-phase-1.vdecstate", "resumed")
    assert resumed.returncode == 0, resumed.stderr
    assert again["blocks"] == whole["blocks"] and again["histories"] == whole["histories"]
    assert whole["blocks"][1]["strain"]["yy"] < -1e-5


@pytest.mark.requirements("REQ-SD-003")
def test_a_phase_that_excavates_a_strained_block_takes_its_energy_out(tmp_path):
    # The platen's sample, strained under the load, dug out by the second phase: its elastic
    # energy leaves with it (withdrawn, not dissipated), its strain is gone, and the run goes on.
    text = PHASED + '[[phase.excavation]]\ncircle = { centre = [0.5, 0.5], radius = 0.1 }\n'
    done, results = run(tmp_path, text)
    assert done.returncode == 0, done.stderr
    sample = results["blocks"][1]
    assert sample["excavated"] and max(abs(v) for v in sample["strain"].values()) == 0.0
    assert results["energy"]["largest_excess"] < 1e-6


@pytest.mark.requirements("REQ-SD-003")
def test_one_and_two_threads_give_bitwise_identical_results_in_a_mixed_column(tmp_path):
    # Simply-deformable, rigid and zoned blocks in one column.
    mixed = COLUMN.replace('name = "b2"\nmaterial = "rock"\nvertices = [[0.0, 1.0], [1.0, 1.0], [1.0, 2.0], [0.0, 2.0]]\nkind = "simply-deformable"',
                           'name = "b2"\nmaterial = "rock"\nvertices = [[0.0, 1.0], [1.0, 1.0], [1.0, 2.0], [0.0, 2.0]]\nzoning = { nx = 4, ny = 4 }')
    mixed = mixed.replace('name = "b3"\nmaterial = "rock"\nvertices = [[0.0, 2.0], [1.0, 2.0], [1.0, 3.0], [0.0, 3.0]]\nkind = "simply-deformable"',
                          'name = "b3"\nmaterial = "rock"\nvertices = [[0.0, 2.0], [1.0, 2.0], [1.0, 3.0], [0.0, 3.0]]')
    assert mixed.count('kind = "simply-deformable"') == 6 and "zoning" in mixed
    mixed = mixed.replace("time = 0.2", "time = 0.02")
    one_done, one = run(tmp_path, mixed, "--threads", "1", name="one")
    two_done, two = run(tmp_path, mixed, "--threads", "2", name="two")
    assert one_done.returncode == 0 and two_done.returncode == 0, one_done.stderr + two_done.stderr
    for key in ("blocks", "gridpoints", "zones", "histories", "energy", "contacts"):
        assert one[key] == two[key], key


@pytest.mark.requirements("REQ-SD-002")
def test_frictional_platens_hold_back_the_blocks_widening(tmp_path):
    # The platen problem with platens of friction 30 degrees and stiff shear springs (ks = 1e12):
    # the block's widening under the load slides its corners along the platens, which their shear
    # springs resist (the corners' velocity includes the strain rate's), so the block's sides take
    # a lateral compression near the held sides' nu s / (1 - nu) = 333 kPa, and the work of the
    # load is the elastic energy, the damping and the slip, to 1e-6.
    text = PLATEN.replace("ks = 1e6", "ks = 1e12").replace("friction = 0.0", "friction = 30.0")
    done, results = run(tmp_path, text)
    assert done.returncode == 0, done.stderr
    sxx = results["histories"]["sxx"]["value"][-1]
    assert -333334.0 < sxx < -250000.0
    assert results["histories"]["exx"]["value"][-1] < 0.1 * 3.125e-5   # the free block's widening
    e = results["energy"]
    spent = e["damping_dissipation"] + e["strain"] + e["slip_dissipation"] + e["joint_release"] + e["kinetic"]
    assert spent == pytest.approx(e["external_work"], rel=1e-5, abs=0)


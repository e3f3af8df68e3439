"""The boundary-element far field through a scene (docs/models/boundary-elements.md,
docs/user-manual/scene-format.md#boundary_elements): its scene errors, the interface it picks, the
stress it holds at installation, and the direct solve with it."""
import math
from pathlib import Path

import pytest

from scene_runs import ROOT, needs_vdec, restart, run

KIRSCH = ROOT / "verification" / "problems" / "BE-KIRSCH" / "scene.toml"
pytestmark = needs_vdec
BASE = KIRSCH.read_text()

BAD = [
    ("no young", BASE.replace("[boundary_elements]\nyoung = 10e9\n", "[boundary_elements]\n"), "young", "is required"),
    ("poisson out of range", BASE.replace("poisson = 0.25\nr = [3.0, 3.0]", "poisson = 0.5\nr = [3.0, 3.0]"), "poisson",
     "must lie in [0, 0.5)"),
    ("negative poisson", BASE.replace("poisson = 0.25\nr = [3.0, 3.0]", "poisson = -0.1\nr = [3.0, 3.0]"), "poisson",
     "must lie in [0, 0.5)"),
    ("surface without half-plane", BASE.replace("r = [3.0, 3.0]", "r = [3.0, 3.0]\nsurface_y = 0.0"), "surface_y",
     "give half_plane = true"),
    ("gravity", BASE.replace("gravity = [0.0, 0.0]", "gravity = [0.0, -9.81]"), "boundary_elements",
     "needs gravity = [0, 0]"),
    ("nothing selected", BASE.replace("r = [3.0, 3.0]", "r = [7.0, 7.0]"), "boundary_elements", "selects 0 outer edges"),
    ("half the loop", BASE.replace("r = [3.0, 3.0]", 'r = [3.0, 3.0]\nblock = "north"'), "boundary_elements",
     "do not close round the model"),
    ("both rings", BASE.replace("young = 10e9\npoisson = 0.25\nr = [3.0, 3.0]", "young = 10e9\npoisson = 0.25\nr = [0.5, 3.5]"),
     "boundary_elements", "do not form one loop"),
    ("the hole", BASE.replace("young = 10e9\npoisson = 0.25\nr = [3.0, 3.0]", "young = 10e9\npoisson = 0.25\nr = [1.0, 1.0]"),
     "boundary_elements", "runs clockwise"),
    ("rigid block", BASE.replace("r = [3.0, 3.0]", 'r = [3.0, 3.0]\nblock = "nowhere"'), "block", "no block"),
    ("unknown key", BASE.replace("r = [3.0, 3.0]", "r = [3.0, 3.0]\nthickness = 1.0"), "thickness", "unknown key"),
]


@pytest.mark.requirements("REQ-BEM-007")
@pytest.mark.parametrize("what,text,key,phrase", BAD, ids=[b[0] for b in BAD])
def test_bad_boundary_element_input_is_a_scene_error_naming_the_key(tmp_path, what, text, key, phrase):
    assert text != BASE
    done, _ = run(tmp_path, text)
    assert done.returncode == 3, (what, done.stderr)
    assert key in done.stderr and phrase in done.stderr, (what, done.stderr)


@pytest.mark.requirements("REQ-BEM-005")
def test_the_far_field_holds_the_in_situ_stress_of_an_unexcavated_state(tmp_path):
    # The two half rings with the hole's face loaded by the in-situ stress itself: nothing is out of
    # balance, so nothing moves; the interface's nodes carry sigma n over their edges.
    loaded = BASE.replace("pressure = 0.0", "stress = [-10e3, 0.0, 0.0]")
    loaded = loaded.replace("ratio = 1e-8\ncycles = 2000000", "cycles = 200")
    done, results = run(tmp_path, loaded)
    assert done.returncode == 0, done.stderr
    be = results["boundary_elements"]
    assert be["nodes"] == 32 and be["closed"] and not be["half_plane"]
    interface = be["interface"]
    assert max(map(abs, interface["displacement_x"] + interface["displacement_y"])) < 1e-12
    # The nodes' forces add up to nothing (a self-balanced in-situ stress) and each is sigma n times its length.
    assert abs(sum(interface["force_x"])) < 1e-6 and abs(sum(interface["force_y"])) < 1e-6
    # At 0 degrees: the two edges either side (32 chords of r = 3), normals at +-pi/32.
    chord = 2.0 * 3.0 * math.sin(math.pi / 32)
    assert max(abs(f) for f in interface["force_x"]) == pytest.approx(10e3 * math.cos(math.pi / 32) * chord, rel=1e-9)
    assert set(interface["points"]) == {1, 2}, "the joints' ends join a gridpoint of each half ring"


PHASED = BASE.replace("[stop]\nratio = 1e-8\ncycles = 2000000\n", "").replace("[boundary_elements]", "[phase.boundary_elements]")
PHASED = PHASED.replace("pressure = 0.0", "stress = [-10e3, 0.0, 0.0]").replace('block = "north"\nr = [1.0, 1.0]', 'name = "hole-n"\nblock = "north"\nr = [1.0, 1.0]').replace('block = "south"\nr = [1.0, 1.0]', 'name = "hole-s"\nblock = "south"\nr = [1.0, 1.0]')
PHASED = PHASED.replace("[phase.boundary_elements]", """[[boundary]]
name = "outer-n"
block = "north"
r = [3.0, 3.0]
fix = ["x", "y"]
[[boundary]]
name = "outer-s"
block = "south"
r = [3.0, 3.0]
fix = ["x", "y"]
[[phase]]
name = "in-situ"
stop = { cycles = 50 }
[[phase]]
name = "excavated"
free = ["outer-n", "outer-s", "hole-n", "hole-s"]
stop = { ratio = 1e-8, cycles = 2000000 }
[phase.boundary_elements]""")


@pytest.mark.requirements("REQ-BEM-006")
def test_a_phase_puts_the_far_field_in_place_and_a_restart_continues_it(tmp_path):
    done, phased = run(tmp_path, PHASED, "--save", "in-situ", name="phased")
    assert done.returncode == 0, done.stderr
    assert [p["stop_reason"] for p in phased["phases"]] == ["cycles", "ratio"]
    done, whole = run(tmp_path, BASE, name="whole")
    assert done.returncode == 0, done.stderr
    # The same equilibrium, reached from the in-situ state held by fixed rock, then by the region.
    wall = [i for i, (x, y) in enumerate(zip(whole["gridpoints"]["x0"], whole["gridpoints"]["y0"])) if abs(math.hypot(x, y) - 1.0) < 1e-9]
    for key in ("displacement_x", "displacement_y"):
        a = [phased["gridpoints"][key][i] for i in wall]
        b = [whole["gridpoints"][key][i] for i in wall]
        scale = max(map(abs, b))
        assert max(abs(p - q) for p, q in zip(a, b)) < 1e-5 * scale, key
    resumed, again = restart(tmp_path, "phased", tmp_path / "phased-out" / "after-phase-1.vdecstate", "resumed")
    assert resumed.returncode == 0, resumed.stderr
    for key in ("gridpoints", "histories", "energy"):
        assert again[key] == phased[key], key
    for run_ in (again, phased):
        run_["boundary_elements"].pop("build_seconds")  # a wall time: the restart forms K again
    assert again["boundary_elements"] == phased["boundary_elements"]
    twice = PHASED.replace(
        '[[phase]]\nname = "in-situ"', '[boundary_elements]\nyoung = 10e9\npoisson = 0.25\nr = [3.0, 3.0]\n[[phase]]\nname = "in-situ"')
    done, _ = run(tmp_path, twice, name="twice")
    assert done.returncode == 3 and "one is already there" in done.stderr, done.stderr


RING = (ROOT / "verification" / "problems" / "BE-RIGID-BLOCKS" / "ring.toml").read_text()


@pytest.mark.requirements("REQ-BEM-009")
def test_a_rigid_ring_restarts_bitwise_and_its_in_situ_stress_needs_the_far_field(tmp_path):
    # The ring of rigid blocks held by the far field, relaxed in two phases: a restart after the
    # first continues it bit for bit (the far field's points, weights and in-situ stress are saved).
    phased = RING.replace("[stop]\ncycles = 40000\n", "").replace("[stop]\nratio = 1e-8\ncycles = 2000000\n", "")
    phased += '[[phase]]\nname = "first"\nstop = { cycles = 500 }\n[[phase]]\nname = "rest"\nstop = { ratio = 1e-8, cycles = 200000 }\n'
    done, whole = run(tmp_path, phased, "--save", "first", name="ring")
    assert done.returncode == 0, done.stderr
    assert set(whole["boundary_elements"]["interface"]["points"]) == {1, 2}, "a vertex of each of two blocks at a joint"
    assert whole["histories"]["hoop_force"]["value"][-1] == pytest.approx(2e6, rel=3e-4, abs=0)
    resumed, again = restart(tmp_path, "ring", tmp_path / "ring-out" / "after-phase-1.vdecstate", "resumed")
    assert resumed.returncode == 0, resumed.stderr
    for key in ("blocks", "contacts", "histories", "energy"):
        assert again[key] == whole[key], key
    for results in (again, whole):
        results["boundary_elements"].pop("build_seconds")
    assert again["boundary_elements"] == whole["boundary_elements"]
    # Without the far field, rigid blocks have nothing to hold an in-situ stress.
    alone = RING[:RING.index("[boundary_elements]")]
    done, _ = run(tmp_path, alone, name="alone")
    assert done.returncode == 3 and "[initial_stress]" in done.stderr and "or a far field" in done.stderr, done.stderr


@pytest.mark.requirements("REQ-BEM-009")
def test_rigid_and_deformable_blocks_share_one_interface(tmp_path):
    # BE-KIRSCH's north half ring zoned, and in place of the south one two rigid convex quarters
    # (the outer arc as 8 chords each, the inner one as a chord): the interface joins the north
    # ring's gridpoints and the quarters' vertices, two points at each of its three joints.
    quarters = ""
    for name, start in (("south-west", math.pi), ("south-east", 1.5 * math.pi)):
        arc = [(3.0 * math.cos(start + 0.5 * math.pi * k / 8), 3.0 * math.sin(start + 0.5 * math.pi * k / 8)) for k in range(9)]
        inner = [(math.cos(start + 0.5 * math.pi), math.sin(start + 0.5 * math.pi)), (math.cos(start), math.sin(start))]
        vertices = ", ".join(f"[{x:.15g}, {y:.15g}]" for x, y in arc + inner)
        quarters += f'[[block]]\nname = "{name}"\nmaterial = "rock"\nvertices = [{vertices}]\nfix = ["x", "y", "rotation"]\n'
    south = BASE.index('[[block]]\nname = "south"')
    rigid = BASE[:south] + quarters + BASE[BASE.index("[initial_stress]"):]
    rigid = rigid.replace('[[boundary]]\nblock = "south"\nr = [1.0, 1.0]\npressure = 0.0\n', "")
    rigid = rigid.replace("ratio = 1e-8\ncycles = 2000000", "cycles = 10")
    done, results = run(tmp_path, rigid)
    assert done.returncode == 0, done.stderr
    interface = results["boundary_elements"]["interface"]
    assert results["boundary_elements"]["nodes"] == 32 and interface["points"].count(2) == 3
    # The in-situ stress held on both kinds of edge: the nodes' forces balance (a uniform stress on
    # a closed outline) before anything moves.
    assert abs(sum(interface["force_x"])) < 1e-6 * 3e4 and abs(sum(interface["force_y"])) < 1e-6 * 3e4


@pytest.mark.requirements("REQ-BEM-006")
def test_an_excavation_inside_the_far_field_after_it_is_in_place(tmp_path):
    # A zoned square in the far field, at the in-situ stress the region holds; a phase then digs a
    # square opening in its middle. Elastic and at rest when the phase starts, it must end where
    # the same square excavated before the run ends: the region does not care when the rock inside
    # it was dug.
    phased = (Path(__file__).parent / "fixtures" / "far_field_excavated_in_a_phase.toml").read_text()
    opening = "polygon = [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]]\n"
    whole = phased[:phased.index("[[phase]]")].replace("[boundary_elements]", "[[excavation]]\n" + opening + "[boundary_elements]")
    whole += "[stop]\nratio = 1e-9\ncycles = 2000000\n"
    done, later = run(tmp_path, phased, name="phased")
    assert done.returncode == 0, done.stderr
    assert [p["stop_reason"] for p in later["phases"]] == ["cycles", "ratio"]
    done, first = run(tmp_path, whole, name="whole")
    assert done.returncode == 0, done.stderr
    assert len(later["zones"]["x0"]) == len(first["zones"]["x0"]) == 256 - 16
    moved = {(x, y): (u, v) for x, y, u, v in zip(*(later["gridpoints"][k] for k in ("x0", "y0", "displacement_x", "displacement_y")))}
    for x, y, u, v in zip(*(first["gridpoints"][k] for k in ("x0", "y0", "displacement_x", "displacement_y"))):
        assert moved[(x, y)] == (u, v)
    assert later["histories"]["crown_uy"]["value"][-1] < -1e-7, "the opening's roof comes down"

"""Beams through a scene (docs/models/support.md, docs/user-manual/scene-format.md#beam): the scene
errors of their keys, ties to a deformable block, self-weight, a restart across phases and the
independence of the thread count."""
import json
import math
import re
import subprocess

import pytest

from scene_runs import last_vtk_cell_arrays, VDEC, needs_vdec, run

pytestmark = needs_vdec


# A beam lying on a base block, tied to it; a point load at its middle.
BASE = """[model]
rounding = 0.01
gravity = [0.0, 0.0]
[solver]
local_damping = 0.8
[stop]
ratio = 1e-6
cycles = 100000
[[joint_material]]
name = "j"
kn = 1e10
ks = 1e10
[[block_material]]
name = "rock"
density = 2500.0
young = 10e9
poisson = 0.25
[[block]]
name = "base"
material = "rock"
vertices = [[-0.5, -1.0], [2.5, -1.0], [2.5, 0.0], [-0.5, 0.0]]
fix = ["x", "y", "rotation"]
[[beam_material]]
name = "steel"
young = 200e9
area = 0.01
inertia = 1e-5
density = 7850.0
tie_normal_stiffness = 1e8
tie_shear_stiffness = 1e8
[[beam]]
name = "b"
material = "steel"
points = [[0.0, 0.0], [2.0, 0.0]]
elements = 8
tied = true
[[beam_node]]
beam = "b"
point = [1.0, 0.0]
force = [0.0, -1000.0]
[[history]]
name = "m"
quantity = "beam.moment"
beam = "b"
point = [1.001, 0.0]
"""

# (what is wrong, the scene, the key the message must name, a phrase of the message)
BAD = [
    ("no young", BASE.replace("young = 200e9\n", ""), "young", "is required"),
    ("negative area", BASE.replace("area = 0.01", "area = -0.01"), "area", "> 0"),
    ("zero spacing", BASE.replace("density = 7850.0", "density = 7850.0\nspacing = 0.0"), "spacing", "> 0"),
    ("friction without cohesion", BASE.replace("tie_shear_stiffness = 1e8", "tie_shear_stiffness = 1e8\ntie_friction = 30.0"),
     "tie_friction", "give tie_cohesion too"),
    ("unknown material", BASE.replace('material = "steel"', 'material = "iron"'), "material", "no [[beam_material]] is named 'iron'"),
    ("points and arc", BASE.replace("elements = 8\n", "elements = 8\narc = { centre = [0.0, 0.0], radius = 1.0, from = 0.0, to = 90.0, elements = 4 }\n"),
     "beam", "one of the two"),
    ("one point", BASE.replace("points = [[0.0, 0.0], [2.0, 0.0]]", "points = [[0.0, 0.0]]"), "points", "at least two points"),
    ("repeated point", BASE.replace("points = [[0.0, 0.0], [2.0, 0.0]]", "points = [[0.0, 0.0], [0.0, 0.0], [2.0, 0.0]]"),
     "points", "repeats the one before it"),
    ("zero elements", BASE.replace("elements = 8\n", "elements = 0\n"), "elements", "must be an integer in [1,"),
    ("arc backwards", BASE.replace("points = [[0.0, 0.0], [2.0, 0.0]]\nelements = 8\n",
                                   "arc = { centre = [1.0, 1.0], radius = 1.0, from = 90.0, to = 0.0, elements = 4 }\n"),
     "to", "must exceed `from`"),
    ("tied without springs", BASE.replace("tie_normal_stiffness = 1e8\n", ""), "tied", "gives no tie springs"),
    ("tied off the rock", BASE.replace("points = [[0.0, 0.0], [2.0, 0.0]]", "points = [[0.0, 0.5], [2.0, 0.5]]"), "tied",
     "lies on no block"),
    ("two beams of one name", BASE + '[[beam]]\nname = "b"\nmaterial = "steel"\npoints = [[0.0, 0.0], [1.0, 0.0]]\nelements = 1\n', "name",
     "is defined twice"),
    ("node of no beam", BASE.replace('beam = "b"\npoint = [1.0, 0.0]\nforce', 'beam = "c"\npoint = [1.0, 0.0]\nforce'), "beam",
     "no [[beam]] is named 'c'"),
    ("node given nothing", BASE.replace("force = [0.0, -1000.0]\n", ""), "beam_node", "gives the node nothing"),
    ("node far from the beam", BASE.replace("point = [1.0, 0.0]\nforce", "point = [1.0, 5.0]\nforce"), "point",
     "from the nearest node of beam 'b'"),
    ("unknown dof", BASE.replace("force = [0.0, -1000.0]", 'fix = ["z"]'), "fix", "unknown degree of freedom"),
    ("history of no beam", BASE.replace('beam = "b"\npoint = [1.001, 0.0]', 'beam = "x"\npoint = [1.001, 0.0]'), "beam",
     "no [[beam]] is named 'x'"),
    ("history without a point", BASE.replace('beam = "b"\npoint = [1.001, 0.0]\n', 'beam = "b"\n'), "point",
     "is required"),
    ("unknown beam key", BASE.replace("tied = true", "tied = true\nthickness = 0.2"), "thickness", "unknown"),
]


@pytest.mark.requirements("REQ-STRUCT-005")
@pytest.mark.parametrize("what, text, key, phrase", BAD, ids=[b[0] for b in BAD])
def test_bad_beam_input_is_a_scene_error_naming_the_key(tmp_path, what, text, key, phrase):
    done, _ = run(tmp_path, text)
    assert done.returncode == 3, (what, done.stderr)
    assert key in done.stderr and phrase in done.stderr, (what, done.stderr)
    assert re.search(r"scene\.toml:\d+", done.stderr), ("the message names the file and line", done.stderr)


@pytest.mark.requirements("REQ-STRUCT-003")
def test_a_beam_tied_to_a_deformable_block_loads_its_gridpoints_with_the_ties_reaction(tmp_path):
    # The base zoned: the ties hold points of its zones. At rest the ties carry the load (statics),
    # and the stiff base barely moves, so the beam bends nearly as on the rigid base.
    zoned = BASE.replace('fix = ["x", "y", "rotation"]', "zoning = { nx = 12, ny = 4 }")
    zoned += '[[boundary]]\nblock = "base"\ny = [-1.0, -1.0]\nfix = ["x", "y"]\n'
    done, results = run(tmp_path, zoned.replace("young = 10e9", "young = 1e13"), name="zoned")
    assert done.returncode == 0, done.stderr
    ties = results["beams"]["ties"]
    assert all(z >= 0 for z in ties["zone"]), "every tie holds a zone's point"
    assert sum(ties["force_y"]) == pytest.approx(1000.0, rel=1e-5)
    done, rigid = run(tmp_path, BASE, name="rigid")
    assert all(z == -1 for z in rigid["beams"]["ties"]["zone"])
    centre = results["beams"]["nodes"]["displacement_y"][4]
    assert centre == pytest.approx(rigid["beams"]["nodes"]["displacement_y"][4], rel=2e-3)
    assert results["histories"]["m"]["value"][-1] == pytest.approx(rigid["histories"]["m"]["value"][-1], rel=2e-3)


@pytest.mark.requirements("REQ-STRUCT-002")
def test_an_untied_beam_on_two_supports_carries_its_own_weight(tmp_path):
    # Self-weight: rho A g per unit length, lumped; the supports' reactions are not output, but
    # the midspan moment is statics, w L^2 / 8 with w = rho A g, exact for the lumped load.
    text = BASE.replace("gravity = [0.0, 0.0]", "gravity = [0.0, -9.81]").replace("tied = true\n", "")
    text = text.replace('[[beam_node]]\nbeam = "b"\npoint = [1.0, 0.0]\nforce = [0.0, -1000.0]\n',
                        '[[beam_node]]\nbeam = "b"\npoint = [0.0, 0.0]\nfix = ["x", "y"]\n'
                        '[[beam_node]]\nbeam = "b"\npoint = [2.0, 0.0]\nfix = ["y"]\n')
    text = text.replace("point = [1.001, 0.0]", "point = [1.0, 0.0]")  # the midspan node
    done, results = run(tmp_path, text.replace("ratio = 1e-6", "ratio = 1e-7"))
    assert done.returncode == 0, done.stderr
    w = 7850.0 * 0.01 * 9.81
    assert results["histories"]["m"]["value"][-1] == pytest.approx(w * 2.0 ** 2 / 8.0, rel=1e-6)
    assert sum(results["beams"]["nodes"]["mass"]) == pytest.approx(7850.0 * 0.01 * 2.0, rel=1e-14)


PHASES = '[[phase]]\nname = "one"\nstop = { cycles = 300 }\n[[phase]]\nname = "two"\nstop = { cycles = 300 }\n'


@pytest.mark.requirements("REQ-STRUCT-001")
def test_a_run_restarted_with_beams_is_the_run_that_did_not_stop(tmp_path):
    text = BASE.replace("[stop]\nratio = 1e-6\ncycles = 100000\n", "") + PHASES
    done, whole = run(tmp_path, text, "--save", "one", name="whole")
    assert done.returncode == 0, done.stderr
    state = tmp_path / "whole-out" / "after-phase-1.vdecstate"
    resumed = subprocess.run([VDEC, "run", str(tmp_path / "whole.toml"), "--out", str(tmp_path / "resumed"),
                              "--restart", str(state)], capture_output=True, text=True, timeout=120)
    assert resumed.returncode == 0, resumed.stderr
    again = json.loads((tmp_path / "resumed" / "results.json").read_text())
    for key in ("beams", "histories", "energy"):
        assert again[key] == whole[key], key


@pytest.mark.requirements("REQ-STRUCT-001")
def test_beam_results_do_not_depend_on_the_thread_count(tmp_path):
    zoned = BASE.replace('fix = ["x", "y", "rotation"]', "zoning = { nx = 12, ny = 4 }")
    zoned += '[[boundary]]\nblock = "base"\ny = [-1.0, -1.0]\nfix = ["x", "y"]\n'
    one, a = run(tmp_path, zoned, "--threads", "1", name="one")
    two, b = run(tmp_path, zoned, "--threads", "2", name="two")
    assert one.returncode == 0 and two.returncode == 0, (one.stderr, two.stderr)
    for key in ("beams", "gridpoints", "histories"):
        assert a[key] == b[key], key


@pytest.mark.requirements("REQ-STRUCT-004")
def test_vtk_snapshots_hold_the_beam_elements_of_results_json(tmp_path):
    done, results = run(tmp_path, BASE + "\n[output]\nvtk_every = 100000\n")
    assert done.returncode == 0, done.stderr
    arrays, kind_name = last_vtk_cell_arrays(tmp_path / "scene-out")
    assert "5 beam element" in kind_name
    kind = arrays[kind_name]
    beams = [i for i, k in enumerate(kind) if k == 5]
    elements = results["beams"]["elements"]
    assert len(beams) == len(elements["axial_force"]) == 8
    assert [arrays["axial_force"][i] for i in beams] == elements["axial_force"]
    assert [arrays["moment_0"][i] for i in beams] == elements["moment_0"]
    assert [arrays["moment_1"][i] for i in beams] == elements["moment_1"]
    assert [arrays["beam_shear_force"][i] for i in beams] == elements["shear_force"]
    # line cells (VTK type 3) between the nodes' points, which carry their displacement
    assert [arrays["types"][i] for i in beams] == [3.0] * 8
    connectivity, offsets = arrays["connectivity"], arrays["offsets"]
    first = beams[0]
    start = int(offsets[first - 1]) if first > 0 else 0
    node0 = int(connectivity[start])
    points = arrays["position"]
    displacement = arrays["displacement"]
    assert points[3 * node0] == pytest.approx(results["beams"]["nodes"]["x0"][0] + results["beams"]["nodes"]["displacement_x"][0], abs=1e-15)
    assert displacement[3 * node0 + 1] == results["beams"]["nodes"]["displacement_y"][0]


@pytest.mark.requirements("REQ-STRUCT-003")
def test_an_excavation_breaks_the_ties_to_the_zones_it_removes_and_renumbers_the_others(tmp_path):
    zoned = BASE.replace('fix = ["x", "y", "rotation"]', "zoning = { nx = 12, ny = 4 }")
    zoned = zoned.replace("[stop]\nratio = 1e-6\ncycles = 100000\n", "")
    zoned += '[[boundary]]\nblock = "base"\ny = [-1.0, -1.0]\nfix = ["x", "y"]\n'
    zoned += ('[[phase]]\nname = "load"\nstop = { cycles = 200 }\n'
              '[[phase]]\nname = "dig"\nstop = { cycles = 200 }\n'
              '[[phase.excavation]]\npolygon = [[-1.0, -0.6], [0.6, -0.6], [0.6, 0.1], [-1.0, 0.1]]\n')
    done, results = run(tmp_path, zoned)
    assert done.returncode == 0, done.stderr
    ties, nodes = results["beams"]["ties"], results["beams"]["nodes"]
    zones = len(results["zones"]["sxx"])
    for zone, broken, node in zip(ties["zone"], ties["broken"], ties["node"]):
        assert zone < zones, "a tie names a zone that exists"
        dug = nodes["x0"][node] < 0.5
        assert bool(broken) == dug, (nodes["x0"][node], zone, broken)


@pytest.mark.requirements("REQ-STRUCT-004")
def test_beam_position_histories_are_sampled_from_the_start_and_forces_a_step_behind(tmp_path):
    text = BASE + ('[[history]]\nname = "w"\nquantity = "beam.displacement_y"\nbeam = "b"\npoint = [1.0, 0.0]\n')
    done, results = run(tmp_path, text.replace("ratio = 1e-6", "ratio = 1e-3"))
    assert done.returncode == 0, done.stderr
    w, m = results["histories"]["w"], results["histories"]["m"]
    assert w["t"][0] == 0.0 and w["value"][0] == 0.0, "the input position, at t = 0"
    assert len(w["t"]) == len(m["t"]) + 1 and w["t"][1:] == [t + (w["t"][1] - 0.0) for t in m["t"]]


# The zoned base pressed by a load on its top (no beam yet), then a beam installed on the
# pressed face, then loaded; finally the beam freed.
STAGED = """[model]
rounding = 0.01
gravity = [0.0, 0.0]
[solver]
local_damping = 0.8
[[joint_material]]
name = "j"
kn = 1e10
ks = 1e10
[[block_material]]
name = "rock"
density = 2500.0
young = 1e9
poisson = 0.25
[[block]]
name = "base"
material = "rock"
vertices = [[-0.5, -1.0], [2.5, -1.0], [2.5, 0.0], [-0.5, 0.0]]
zoning = { nx = 12, ny = 4 }
[[boundary]]
block = "base"
y = [-1.0, -1.0]
fix = ["x", "y"]
[[boundary]]
name = "press"
block = "base"
y = [0.0, 0.0]
stress = [0.0, -1e6, 0.0]
[[beam_material]]
name = "steel"
young = 200e9
area = 0.01
inertia = 1e-5
density = 7850.0
tie_normal_stiffness = 1e8
tie_shear_stiffness = 1e8
[[phase]]
name = "press"
stop = { ratio = 1e-6, cycles = 50000 }
[[phase]]
name = "support"
stop = { cycles = 1 }
[[phase.beam]]
name = "b"
material = "steel"
points = [[0.0, 0.0], [2.0, 0.0]]
elements = 8
tied = true
[[phase]]
name = "load"
stop = { ratio = 1e-6, cycles = 50000 }
[[phase.beam_node]]
beam = "b"
point = [1.0, 0.0]
force = [0.0, -1000.0]
"""


@pytest.mark.requirements("REQ-STRUCT-006")
def test_a_phase_installs_a_beam_stress_free_on_the_rock_as_it_has_moved_and_a_later_phase_frees_it(tmp_path):
    # Installed after the press: on the pressed face, stress-free (one cycle later its forces are
    # still those of one step's motion, nothing of the press's 1e-4 m settlement).
    done, installed = run(tmp_path, STAGED.replace('[[phase]]\nname = "load"', '[[phase]]\nname = "unused"')
                          .split('[[phase]]\nname = "unused"')[0], name="installed")
    assert done.returncode == 0, done.stderr
    beams, gridpoints = installed["beams"], installed["gridpoints"]
    assert beams["installed"] == [1]
    settled = min(gridpoints["displacement_y"])
    assert settled < -1e-4, "the press settled the face"
    for x0, uy in zip(beams["nodes"]["x0"], beams["nodes"]["displacement_y"]):
        assert abs(uy) < 1e-9, "displacements count from the installation"
    # the nodes were placed on the face as it had settled
    face = [(x + ux, y + uy) for x, y, ux, uy in zip(gridpoints["x0"], gridpoints["y0"], gridpoints["displacement_x"],
                                                     gridpoints["displacement_y"]) if y == 0.0]
    for x, y in zip(beams["nodes"]["x0"], beams["nodes"]["y0"]):
        gap = min(math.hypot(x - fx, y - fy) for fx, fy in face)
        assert gap < 1e-9 and y < -1e-5, (x, y, gap)  # the face moves a little in the phase's one cycle
    assert max(abs(f) for f in beams["elements"]["axial_force"]) < 1.0
    assert max(abs(m) for m in beams["elements"]["moment_0"] + beams["elements"]["moment_1"]) < 1e-2
    # Then loaded: the beam carries the load to the rock through its ties; a later phase frees it.
    freed = STAGED + '[[phase]]\nname = "free"\nstop = { cycles = 10 }\nfree = ["b"]\n'
    done, results = run(tmp_path, freed, name="freed")
    assert done.returncode == 0, done.stderr
    assert results["beams"]["installed"] == [0]
    assert all(results["beams"]["ties"]["broken"])
    assert results["energy"]["removed"] > 0.0
    done, loaded = run(tmp_path, STAGED, name="loaded")
    # Statics, to the stop's residue: the ratio 1e-6 is of the mean force, which the press's zone
    # forces (some 1e5 N per gridpoint) set, so each of the nine nodes may be out of balance by
    # about 0.1 N: 1e-3 of the load.
    assert sum(loaded["beams"]["ties"]["force_y"]) == pytest.approx(1000.0, rel=1e-3)


STAGED_BAD = [
    ("phase beam of a boundary's name", STAGED.replace('[[phase.beam]]\nname = "b"', '[[phase.beam]]\nname = "press"'), "name",
     "names a support or boundary active"),
    ("free of nothing", STAGED + '[[phase]]\nname = "free"\nstop = { cycles = 10 }\nfree = ["c"]\n', "free",
     "no boundary, beam, cable or bolt named 'c'"),
    ("phase beam node of no beam", STAGED.replace('[[phase.beam_node]]\nbeam = "b"', '[[phase.beam_node]]\nbeam = "c"'), "beam",
     "no [[beam]] is named 'c'"),
    ("scene beam of a boundary's name", STAGED.replace("[[phase]]\nname = \"press\"",
                                                       '[[beam]]\nname = "press"\nmaterial = "steel"\npoints = [[0.0, 0.5], [1.0, 0.5]]\nelements = 1\n[[phase]]\nname = "press"'),
     "name", "has the name of a boundary"),
]


@pytest.mark.requirements("REQ-STRUCT-006")
@pytest.mark.parametrize("what, text, key, phrase", STAGED_BAD, ids=[b[0] for b in STAGED_BAD])
def test_bad_phase_beams_are_scene_errors_naming_the_key(tmp_path, what, text, key, phrase):
    done, _ = run(tmp_path, text)
    assert done.returncode == 3, (what, done.stderr)
    assert key in done.stderr and phrase in done.stderr, (what, done.stderr)


@pytest.mark.requirements("REQ-STRUCT-006")
def test_a_phase_beam_on_rock_dug_out_before_it_is_refused_when_the_phase_starts(tmp_path):
    dug = STAGED.replace('[[phase]]\nname = "support"',
                         '[[phase]]\nname = "dig"\nstop = { cycles = 1 }\n[[phase.excavation]]\n'
                         'polygon = [[-1.0, -0.5], [3.0, -0.5], [3.0, 0.5], [-1.0, 0.5]]\n[[phase]]\nname = "support"')
    done, _ = run(tmp_path, dug)
    assert done.returncode == 3, done.stderr
    assert "phase 'support'" in done.stderr and "lies on no block" in done.stderr, done.stderr

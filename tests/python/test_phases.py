"""Phases: changes at a phase's start, per-phase results, require_equilibrium, and the scene
errors of [[phase]] tables (docs/user-manual/scene-format.md#phase)."""
import json
import math
import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
VDEC = os.environ.get("VDEC_EXECUTABLE", str(ROOT / "build" / "vdec"))
pytestmark = pytest.mark.skipif(not Path(VDEC).is_file(), reason="vdec is not built")
REQ = pytest.mark.requirements("REQ-RUN-004")

BLOCKS = """
title = "a block resting on a base"
[model]
gravity = [0.0, -9.81]
rounding = 0.01
[[block_material]]
name = "rock"
density = 2500.0
[[joint_material]]
name = "j"
kn = 1e10
ks = 1e10
friction = 30.0
[[block]]
name = "base"
material = "rock"
vertices = [[-3.0, -1.0], [3.0, -1.0], [3.0, 0.0], [-3.0, 0.0]]
fix = ["x", "y", "rotation"]
[[block]]
name = "top"
material = "rock"
vertices = [[-1.0, 0.0], [1.0, 0.0], [1.0, 0.5], [-1.0, 0.5]]
[[history]]
name = "x"
quantity = "block.displacement_x"
block = "top"
every = 1
"""


def run(tmp_path, text):
    scene = tmp_path / "scene.toml"
    scene.write_text(text)
    out = tmp_path / "out"
    done = subprocess.run([VDEC, "run", str(scene), "--out", str(out)], capture_output=True, text=True, timeout=120)
    results = out / "results.json"
    return done, json.loads(results.read_text()) if results.is_file() else None


@REQ
def test_phases_run_in_order_and_report_each(tmp_path):
    done, results = run(tmp_path, BLOCKS + """
[[phase]]
name = "settle"
stop = { ratio = 1e-5, cycles = 100000 }
require_equilibrium = true
adaptive_damping = true
[[phase]]
name = "pushed sideways"
stop = { time = 0.2 }
gravity = [2.0, -9.81]
mass_damping = 0.0
reset = ["displacements"]
[[phase.joint_material]]
name = "j"
friction = 5.0
""")
    assert done.returncode == 0, done.stderr
    first, second = results["phases"]
    assert (first["name"], first["stop_reason"]) == ("settle", "ratio")
    assert first["unbalanced_ratio"] <= 1e-5
    assert (second["name"], second["stop_reason"]) == ("pushed sideways", "time")
    assert second["time"] == pytest.approx(0.2, abs=results["run"]["dt"])
    assert second["start_cycle"] == first["cycles"] and results["run"]["cycles"] == first["cycles"] + second["cycles"]
    x = results["histories"]["x"]["value"]
    # one series across both phases: the reset puts x back to zero at the second phase's start,
    # and the weakened joint then lets the block slide in +x under the tilted gravity, from rest,
    # at 2 - 9.81 tan 5 = 1.142 m/s2 (the normal force stays m g: gravity's y part is unchanged)
    start = first["cycles"]
    acceleration = 2.0 - 9.81 * math.tan(math.radians(5.0))
    assert x[start] == 0.0
    assert x[-1] == pytest.approx(0.5 * acceleration * second["time"] ** 2, rel=0.02, abs=0)
    assert results["energy"]["slip_dissipation"] > 0.0


@REQ
def test_a_phase_short_of_the_equilibrium_it_requires_stops_the_run(tmp_path):
    done, results = run(tmp_path, BLOCKS + """
[[phase]]
name = "settle"
stop = { ratio = 1e-9, cycles = 20 }
require_equilibrium = true
[[phase]]
name = "never"
stop = { cycles = 10 }
""")
    assert done.returncode == 9, done.stderr
    assert "phase 'settle' has require_equilibrium = true but ended on its cycles limit" in done.stderr
    assert [p["name"] for p in results["phases"]] == ["settle"]
    assert results["phases"][0]["stop_reason"] == "error" and results["phases"][0]["cycles"] == 20


@REQ
def test_a_phase_short_of_its_ratio_without_the_requirement_warns_and_goes_on(tmp_path):
    done, results = run(tmp_path, BLOCKS + """
[[phase]]
name = "settle"
stop = { ratio = 1e-9, cycles = 20 }
[[phase]]
name = "next"
stop = { cycles = 10 }
""")
    assert done.returncode == 0, done.stderr
    assert "warning: phase 'settle' stopped on cycles before the unbalanced-force ratio fell to 1e-09" in done.stderr
    assert [p["stop_reason"] for p in results["phases"]] == ["cycles", "cycles"]


@REQ
@pytest.mark.parametrize("extra, message", [
    ("[stop]\ncycles = 5\n[[phase]]\nname = \"a\"\nstop = { cycles = 5 }\n", "key 'stop': with [[phase]] tables each phase has its own stop"),
    ("[[phase]]\nname = \"a\"\n", "key 'phase[0].stop': is required: each phase sets stop"),
    ("[[phase]]\nname = \"a\"\nstop = { cycles = 5 }\n[[phase]]\nname = \"a\"\nstop = { cycles = 5 }\n", "key 'phase[1].name': phase 'a' is defined twice"),
    ("[[phase]]\nname = \"a\"\nstop = { cycles = 5 }\nrequire_equilibrium = true\n", "key 'phase[0].require_equilibrium': needs stop.ratio"),
    ("[[phase]]\nname = \"a\"\nstop = { ratio = 1e-3 }\n", "key 'phase[0].stop.ratio': needs a limit as well"),
    ("[[phase]]\nname = \"a\"\nstop = { cycles = 5 }\nreset = [\"stresses\"]\n", "key 'phase[0].reset': unknown item 'stresses'"),
    ("[[phase]]\nname = \"a\"\nstop = { cycles = 5 }\nmass_damping = 1.0\nadaptive_damping = true\n", "key 'phase[0].mass_damping': give mass_damping or adaptive_damping, not both"),
    ("[[phase]]\nname = \"a\"\nstop = { cycles = 5 }\n[[phase.joint_material]]\nname = \"k\"\nfriction = 5.0\n", "key 'phase[0].joint_material[0].name': no joint material named 'k'"),
    ("[[phase]]\nname = \"a\"\nstop = { cycles = 5 }\n[[phase.joint_material]]\nname = \"j\"\n", "[phase[0].joint_material[0]]: changes nothing"),
    ("[[phase]]\nname = \"a\"\nstop = { cycles = 5 }\n[[phase.joint_material]]\nname = \"j\"\nkn = 5.0\n", "phase[0].joint_material[0].kn"),
    ("[[phase]]\nname = \"a\"\nstop = { cycles = 5 }\nfriction = 5.0\n", "phase[0].friction"),
    ("[[phase]]\nname = \"a\"\nstop = { cycles = 5 }\nmass_damping = 1e9\n", "phase 'a': mass_damping = 1e+09 1/s times the time step"),
    ('[[phase]]\nname = "a"\nstop = { cycles = 5 }\n[[phase.block]]\nname = "top"\n', "[phase[0].block[0]]: changes nothing"),
    ('[[phase]]\nname = "a"\nstop = { cycles = 5 }\n[[phase.block]]\nname = "top"\nfix = ["x"]\nfree = ["x"]\n', "key 'phase[0].block[0].free': a degree of freedom is both fixed and freed"),
    ('[[phase]]\nname = "a"\nstop = { cycles = 5 }\n[[phase.block]]\nname = "top"\nvelocity = [1.0, 0.0]\n', "key 'phase[0].block[0].velocity': drives the components given in fix"),
    ('[[phase]]\nname = "a"\nstop = { cycles = 5 }\n[[phase.block]]\nname = "top"\nfix = ["z"]\n', "key 'phase[0].block[0].fix': unknown degree of freedom 'z'"),
    ('[[phase]]\nname = "a"\nstop = { cycles = 5 }\n[[phase.block]]\nname = "nonesuch"\nfree = ["x"]\n', "phase[0].block[0].name"),
    ('[[phase]]\nname = "a"\nstop = { cycles = 5 }\n[[phase.block_material]]\nname = "rock"\n', "[phase[0].block_material[0]]: changes nothing"),
    ('[[phase]]\nname = "a"\nstop = { cycles = 5 }\n[[phase.block_material]]\nname = "stone"\nfriction = 30.0\ncohesion = 1.0\n', "key 'phase[0].block_material[0].name': no block material named 'stone'"),
    ('[[phase]]\nname = "a"\nstop = { cycles = 5 }\n[[phase.block_material]]\nname = "rock"\nfriction = 30.0\ncohesion = 1.0\n', "key 'phase[0].block_material[0].friction': Mohr-Coulomb plasticity needs the elastic constants too"),
])
def test_bad_phase_tables_are_scene_errors_naming_the_key(tmp_path, extra, message):
    done, results = run(tmp_path, BLOCKS + extra)
    assert done.returncode == 3, done.stderr
    assert message in done.stderr, done.stderr
    assert results is None  # found before the first step: no results


@REQ
def test_a_zone_history_in_a_zone_a_phase_excavates_is_a_scene_error(tmp_path):
    folder = tmp_path / "problem"
    shutil.copytree(ROOT / "verification" / "problems" / "RUN-EXCAVATION-KIRSCH", folder)
    scene = folder / "scene.toml"
    scene.write_text(scene.read_text() + '[[history]]\nname = "inner"\nquantity = "zone.sxx"\nblock = "plate"\n'
                                          'point = [0.5, 0.1]\n')
    done = subprocess.run([VDEC, "run", str(scene), "--out", str(tmp_path / "out")], capture_output=True, text=True)
    assert done.returncode == 3
    assert "key 'history[0].point': lies in a zone that" in done.stderr and "of phase 'excavate' excavates" in done.stderr
    assert not (tmp_path / "out" / "results.json").exists()


@REQ
def test_resets_measure_displacements_from_the_phase_start_and_stop_the_block(tmp_path):
    done, results = run(tmp_path, BLOCKS + """
[[phase]]
name = "slide"
stop = { time = 0.1 }
gravity = [2.0, -9.81]
[[phase.joint_material]]
name = "j"
friction = 5.0
[[phase]]
name = "held"
stop = { cycles = 20 }
gravity = [0.0, -9.81]
reset = ["displacements", "velocities"]
[[phase.joint_material]]
name = "j"
friction = 30.0
""")
    assert done.returncode == 0, done.stderr
    first = results["phases"][0]
    x = results["histories"]["x"]["value"]
    slid = x[first["cycles"]]  # the last sample of the first phase, before the reset
    assert slid == pytest.approx(0.5 * (2.0 - 9.81 * math.tan(math.radians(5.0))) * first["time"] ** 2, rel=0.05, abs=0)
    # from rest at the reset, held by friction 30 degrees under upright gravity, it stays put
    # but for the shear spring unloading the friction force it held while sliding:
    # m g tan 5 / (ks L) = 5000 * 9.81 * 0.0875 / (1e10 * 2) = 2.1e-7 m
    assert max(abs(v) for v in x[first["cycles"] + 1:]) < 5e-7
    # ... and its velocity is that spring's vibration, at most w 2.1e-7 = 4.2e-4 m/s
    # (w = sqrt(ks L / m) = 2000 rad/s), against 0.11 m/s had the velocities not been reset
    assert abs(results["blocks"][1]["velocity"][0]) < 1e-3


INCLINE = BLOCKS.replace('gravity = [0.0, -9.81]', 'gravity = [6.936717523440031, -6.9367175234400325]').replace(
    'friction = 30.0', 'friction = 20.0')


@REQ
def test_a_rigid_block_held_then_released_then_driven(tmp_path):
    # On a 45 degree incline (gravity turned) with friction 20 degrees: held in the first phase,
    # released in the second, where it slides at g (sin 45 - cos 45 tan 20), and driven up the
    # slope at 0.5 m/s in the third.
    done, results = run(tmp_path, INCLINE + """
[[phase]]
name = "held"
stop = { time = 0.1 }
[[phase.block]]
name = "top"
fix = ["x", "y", "rotation"]
[[phase]]
name = "released"
stop = { time = 0.3 }
[[phase.block]]
name = "top"
free = ["x", "y", "rotation"]
[[phase]]
name = "pulled back"
stop = { time = 0.2 }
[[phase.block]]
name = "top"
fix = ["x"]
velocity = [-0.5, 0.0]
""")
    assert done.returncode == 0, done.stderr
    held, released, pulled = results["phases"]
    t = results["histories"]["x"]["t"]
    x = results["histories"]["x"]["value"]
    assert max(abs(v) for v in x[: held["cycles"] + 1]) == 0.0
    a = 9.81 * (math.sin(math.radians(45.0)) - math.cos(math.radians(45.0)) * math.tan(math.radians(20.0)))
    end = held["cycles"] + released["cycles"]
    # The release starts from rest with the joint's springs unloaded by the hold: a slide of
    # a t^2 / 2 within 2 % (the normal spring settles in the first milliseconds)
    assert x[end] == pytest.approx(0.5 * a * released["time"] ** 2, rel=0.02, abs=0)
    # driven at -0.5 m/s in x: x falls by 0.5 m/s times the phase's time
    assert x[-1] - x[end] == pytest.approx(-0.5 * (t[-1] - t[end]), rel=1e-9, abs=0)
    assert results["energy"]["removed"] != 0.0


@REQ
def test_a_strength_reduction_in_a_phase_yields_the_rock_to_the_closed_form(tmp_path):
    # RUN-GROUND-REACTION's tunnel with rock too strong to yield (c = 100 MPa), unloaded to p_i = 0
    # (elastic), then weakened to c = 3.45 MPa in a phase of its own: the wall moves on to
    # Salencon's displacement for that strength, as the monotonic path of RUN-GROUND-REACTION
    # does (within its 2 % band at this zoning).
    import sys
    sys.path.insert(0, str(ROOT / "verification"))
    from analytic import plasticity
    scene = (ROOT / "verification" / "problems" / "RUN-GROUND-REACTION" / "scene.toml").read_text()
    head, *phases = scene.split("\n[[phase]]\n")
    last, history = phases[-1].split("\n[[history]]", 1)
    text = head.replace("cohesion = 3.45e6\n[[block]]", "cohesion = 100e6\n[[block]]")
    text += "\n[[phase]]\n" + phases[0] + "\n[[phase]]\n" + last + """
[[phase]]
name = "weakened"
stop = { ratio = 1e-6, cycles = 2000000 }
require_equilibrium = true
[[phase.block_material]]
name = "rock"
friction = 30.0
cohesion = 3.45e6
""" + "\n[[history]]" + history
    done, results = run(tmp_path, text)
    assert done.returncode == 0, done.stderr
    wall = results["histories"]["wall_ur"]["value"][-1]
    closed = plasticity.salencon_tunnel(r=1.0, a=1.0, p0=30e6, pi=0.0, E=677793103448.2759, nu=0.2103448275862069,
                                        cohesion=3.45e6, friction_deg=30.0, dilation_deg=0.0)["wall_displacement"]
    assert wall == pytest.approx(closed, rel=0.02, abs=0)
    unloaded = results["phases"][1]
    h = results["histories"]["wall_ur"]
    elastic = [v for t, v in zip(h["t"], h["value"]) if t <= unloaded["start_time"] + unloaded["time"]][-1]
    assert abs(elastic) < 0.5 * abs(closed)  # before the weakening the rock had not yielded


@REQ
def test_a_phase_may_not_excavate_at_an_outline_that_touches_other_blocks(tmp_path):
    # DB-JOINT-STACK's two blocks: a phase excavating the zones of the upper block next to the
    # joint would cut the outline its contacts follow; exit code 4 naming the gridpoint.
    scene = (ROOT / "verification" / "problems" / "DB-JOINT-STACK" / "scene.toml").read_text()
    scene = re.sub(r"(?ms)^\[stop\]\n(?:[^\[].*?\n)*", "", scene)
    done, _ = run(tmp_path, scene + """
[[phase]]
name = "settle"
stop = { cycles = 50 }
[[phase]]
name = "cut"
stop = { cycles = 50 }
[[phase.excavation]]
circle = { centre = [0.5, 1.1], radius = 0.15 }
""")
    assert done.returncode == 4, done.stderr
    assert "[phase[1].excavation[0]] removes a zone of block 'upper' at the block's outline" in done.stderr


COLUMN = """
title = "an elastic column under its own weight, held in uniaxial strain"
[model]
rounding = 0.01
[[block_material]]
name = "rock"
density = 2000.0
bulk = 5e9
shear = 3e9
[[block]]
name = "column"
material = "rock"
vertices = [[0.0, 0.0], [1.0, 0.0], [1.0, 4.0], [0.0, 4.0]]
zoning = { nx = 2, ny = 8 }
[[boundary]]
block = "column"
y = [0.0, 0.0]
fix = ["y"]
[[boundary]]
block = "column"
x = [0.0, 0.0]
fix = ["x"]
[[boundary]]
block = "column"
x = [1.0, 1.0]
fix = ["x"]
[[history]]
name = "top"
quantity = "gridpoint.displacement_y"
block = "column"
point = [0.5, 4.0]
every = 1
"""
# The top of a column of height H held laterally and at its base sinks rho g H^2 / (2 M) under its
# own weight, M = K + 4 G / 3 (uniaxial strain). The crossed zoning represents the column's linear
# stress; the solver works on the moving configuration, the closed form on the initial one, so
# they differ by the order of the largest strain, rho g H / M = 9e-6: the checks allow 1e-5.
COLUMN_SETTLEMENT = 2000.0 * 10.0 * 4.0 ** 2 / (2 * (5e9 + 4 * 3e9 / 3))


@REQ
def test_a_phase_may_solve_the_elastic_zones_directly(tmp_path):
    done, results = run(tmp_path, COLUMN + """
[[phase]]
name = "weightless"
stop = { cycles = 2 }
[[phase]]
name = "loaded"
gravity = [0.0, -10.0]
static_solve = true
stop = { ratio = 1e-6, cycles = 50 }
require_equilibrium = true
""")
    assert done.returncode == 0, done.stderr
    loaded = results["phases"][1]
    # The direct solve leaves nothing to relax: the ratio is met on the phase's first step.
    assert loaded["stop_reason"] == "ratio" and loaded["cycles"] == 1
    top = results["histories"]["top"]["value"][-1]
    assert top == pytest.approx(-COLUMN_SETTLEMENT, rel=1e-5, abs=0)
    # The elastic energy the solve set up is supplied without its work: the account still closes.
    energy = results["energy"]
    stored = COLUMN_SETTLEMENT * 2000.0 * 10.0 * 4.0 / 3.0  # integral of s^2 / (2 M) over the column
    # Constant stress per zone holds less energy than the linear stress: at most (h / H)^2 / 4 of it
    # for cells of height h = 0.5 m (the energy of s - mean(s) over each cell, summed).
    deficit = (0.5 / 4.0) ** 2 / 4
    assert stored * (1 - deficit) <= energy["static_solve"] <= stored * (1 + 1e-5)
    assert energy["strain"] == pytest.approx(energy["static_solve"], rel=1e-9, abs=0)
    assert results["run"]["static_solve_seconds"] >= 0.0
    # The solve and its passes: each pass on the configuration the one before reached, the last at
    # round-off of the loads; two unknowns per free gridpoint, fewer than two per gridpoint (the
    # base is held).
    run_ = results["run"]
    assert 1 <= run_["static_solve_passes"] <= 6 and run_["static_solve_residual"] < 1e-10
    assert run_["static_solve_factorisations"] == 1   # the later passes solve with the first factor
    assert 0 < run_["static_solve_unknowns"] < 2 * len(results["gridpoints"]["x0"])


@REQ
def test_a_phase_switches_to_local_damping_and_the_step_shrinks_for_it(tmp_path):
    phases = """
[[phase]]
name = "start"
mass_damping = 10.0
stop = { cycles = 5 }
"""
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    done, before = run(tmp_path / "a", COLUMN + phases)
    assert done.returncode == 0, done.stderr
    done, after = run(tmp_path / "b", COLUMN + phases + """
[[phase]]
name = "relax"
gravity = [0.0, -10.0]
local_damping = 0.8
stop = { ratio = 1e-5, cycles = 20000 }
require_equilibrium = true
""")
    assert done.returncode == 0, done.stderr
    # dt / sqrt(1 + alpha_L), the critical step of central differences under local damping.
    assert after["run"]["dt"] == pytest.approx(before["run"]["dt"] / math.sqrt(1.8), rel=1e-12, abs=0)
    assert after["phases"][1]["stop_reason"] == "ratio"
    assert after["histories"]["top"]["value"][-1] == pytest.approx(-COLUMN_SETTLEMENT, rel=1e-3, abs=0)


@pytest.mark.requirements("REQ-RUN-004", "REQ-QA-007")
@pytest.mark.parametrize("change, key, message", [
    ("local_damping = 1.0\n", "phase[0].local_damping", "must lie in [0, 1)"),
    ("local_damping = 0.8\nmass_damping = 5.0\n", "phase[0].local_damping", "replaces mass damping"),
])
def test_bad_solver_switches_in_a_phase_are_scene_errors(tmp_path, change, key, message):
    done, _ = run(tmp_path, COLUMN + '[[phase]]\nname = "p"\nstop = { cycles = 2 }\n' + change)
    assert done.returncode == 3, done.stderr
    assert f"key '{key}'" in done.stderr and message in done.stderr, done.stderr


@pytest.mark.requirements("REQ-RUN-004", "REQ-QA-007")
def test_a_direct_solve_with_rigid_blocks_is_a_scene_error(tmp_path):
    done, _ = run(tmp_path, BLOCKS + '[[phase]]\nname = "p"\nstatic_solve = true\nstop = { cycles = 2 }\n')
    assert done.returncode == 3 and "key 'phase[0].static_solve'" in done.stderr and "rigid" in done.stderr, done.stderr


STACK = BLOCKS.replace("""[[history]]""", """[[block]]
name = "cap"
material = "rock"
vertices = [[-0.5, 0.5], [0.5, 0.5], [0.5, 1.0], [-0.5, 1.0]]
[[history]]
name = "cap_y"
quantity = "block.displacement_y"
block = "cap"
every = 1
[[history]]""")


@REQ
def test_a_phase_excavates_a_rigid_block_and_the_block_above_falls_freely(tmp_path):
    done, results = run(tmp_path, STACK + """
[[phase]]
name = "settle"
mass_damping = 20.0
stop = { cycles = 2000 }
[[phase]]
name = "remove the middle block"
mass_damping = 0.0
reset = ["displacements", "velocities"]
stop = { time = 0.2 }
[[phase.excavation]]
circle = { centre = [0.0, 0.25], radius = 0.3 }
""")
    assert done.returncode == 0, done.stderr
    blocks = {b["name"]: b for b in results["blocks"]}
    assert blocks["top"].get("excavated") is True and "excavated" not in blocks["cap"]
    # The cap rests on nothing now: it falls from rest, y = -g t^2 / 2, for 0.2 s (0.196 m, less
    # than the 0.5 m to the base). Central differences from rest put the block at
    # -g dt^2 n (n + 1) / 2 after n steps: within g dt t of the closed form at time t.
    start = results["phases"][1]["start_time"]
    t = results["histories"]["cap_y"]["t"]
    y = results["histories"]["cap_y"]["value"]
    dt = results["run"]["dt"]
    for ti, yi in zip(t, y):
        if ti > start + dt:
            tau = ti - start
            assert yi == pytest.approx(-0.5 * 9.81 * tau ** 2, abs=9.81 * dt * tau + 1e-9)
    assert y[-1] < -0.19
    # The joints' elastic energy left with the block: the account closes (the fall's work is
    # the cap's kinetic energy).
    energy = results["energy"]
    supplied = energy["initial"] + energy["external_work"]
    held = (energy["kinetic"] + energy["strain"] + energy["slip_dissipation"] + energy["damping_dissipation"]
            + energy["joint_release"] + energy["removed"])
    assert held == pytest.approx(supplied, rel=2e-3, abs=0)
    assert energy["removed"] > 0.0


@pytest.mark.requirements("REQ-RUN-004", "REQ-QA-007")
@pytest.mark.parametrize("region, message", [
    ("circle = { centre = [10.0, 10.0], radius = 0.1 }", "removes nothing"),
    ("polygon = [[-4.0, -2.0], [4.0, -2.0], [4.0, 2.0], [-4.0, 2.0]]", "removes every block"),
])
def test_a_phase_excavation_that_removes_nothing_or_everything_is_a_scene_error(tmp_path, region, message):
    done, _ = run(tmp_path, BLOCKS + f"""
[[phase]]
name = "p"
stop = {{ cycles = 2 }}
[[phase.excavation]]
{region}
""")
    assert done.returncode == 3 and "phase[0].excavation[0]" in done.stderr and message in done.stderr, done.stderr


@pytest.mark.requirements("REQ-RUN-004", "REQ-QA-007")
def test_a_phase_may_not_drive_or_load_a_block_an_earlier_phase_excavated(tmp_path):
    done, _ = run(tmp_path, STACK + """
[[phase]]
name = "dig"
stop = { cycles = 2 }
[[phase.excavation]]
circle = { centre = [0.0, 0.25], radius = 0.3 }
[[phase]]
name = "release"
stop = { cycles = 2 }
[[phase.block]]
name = "top"
free = ["x", "y", "rotation"]
""")
    assert done.returncode == 3, done.stderr
    assert "key 'phase[1].block[0].name'" in done.stderr and "was excavated by an earlier phase" in done.stderr


@pytest.mark.requirements("REQ-RUN-004", "REQ-QA-007")
def test_a_direct_solve_with_a_velocity_drive_in_force_is_a_scene_error(tmp_path):
    driven = COLUMN + """
[[boundary]]
name = "push"
block = "column"
y = [4.0, 4.0]
velocity_y = -0.001
[[phase]]
name = "push"
stop = { cycles = 20 }
[[phase]]
name = "solve"
static_solve = true
stop = { cycles = 2 }
"""
    done, _ = run(tmp_path, driven)
    assert done.returncode == 3, done.stderr
    assert "key 'phase[1].static_solve'" in done.stderr and "drives gridpoints at a velocity" in done.stderr
    # Freed in the same phase, the drive is gone before the solve.
    (tmp_path / "freed").mkdir()
    done, _ = run(tmp_path / "freed", driven.replace('static_solve = true\n', 'static_solve = true\nfree = ["push"]\n'))
    assert done.returncode == 0, done.stderr


@pytest.mark.requirements("REQ-RUN-004", "REQ-MOTION-009")
def test_accelerations_start_again_after_a_phase_changes_the_velocities(tmp_path):
    # The cap, moving at 1 m/s, has its velocity reset by the second phase: its acceleration is
    # that of the forces (g while it falls free of the excavated block), not the reset's jump.
    done, results = run(tmp_path, STACK.replace('name = "cap"\nmaterial = "rock"\n',
                                                'name = "cap"\nmaterial = "rock"\nvelocity = [0.0, 1.0]\n')
                        + """
[[history]]
name = "cap_ay"
quantity = "block.acceleration_y"
block = "cap"
every = 1
[[phase]]
name = "rise"
stop = { cycles = 3 }
[[phase]]
name = "dig"
reset = ["velocities"]
stop = { cycles = 20 }
[[phase.excavation]]
circle = { centre = [0.0, 0.25], radius = 0.3 }
""")
    assert done.returncode == 0, done.stderr
    a = results["histories"]["cap_ay"]["value"]
    assert a[3:] == pytest.approx([-9.81] * len(a[3:]), rel=1e-9, abs=0)


@pytest.mark.requirements("REQ-RUN-004", "REQ-QA-007")
def test_an_excavation_that_finds_every_block_in_its_region_when_the_phase_starts_stops_the_run(tmp_path):
    # The driven block is outside the region in the scene, inside it when the phase starts.
    done, _ = run(tmp_path, BLOCKS + """
[[block]]
name = "runner"
material = "rock"
vertices = [[10.0, 0.5], [11.0, 0.5], [11.0, 1.5], [10.0, 1.5]]
fix = ["x", "y", "rotation"]
velocity = [-20.0, 0.0]
[[phase]]
name = "run in"
stop = { time = 0.4 }
[[phase]]
name = "dig"
stop = { cycles = 2 }
[[phase.excavation]]
polygon = [[-4.0, -2.0], [4.0, -2.0], [4.0, 3.0], [-4.0, 3.0]]
""")
    assert done.returncode == 3, done.stderr
    assert "[phase[1].excavation[0]]" in done.stderr and "removes every block when the phase starts" in done.stderr


@REQ
def test_a_displacement_reset_leaves_a_turned_rigid_block_where_it_stands(tmp_path):
    # A block spinning at 1 rad/s turns 0.5 rad in the first phase; the reset counts rotations from
    # there, and the block must stay turned (its rotation was once simply zeroed, which turned it back).
    import xml.etree.ElementTree as ET
    text = """[model]
rounding = 0.01
gravity = [0.0, 0.0]
[output]
vtk_every = 1000000
[[joint_material]]
name = "j"
kn = 1e10
ks = 1e10
[[block_material]]
name = "rock"
density = 2500.0
[[block]]
name = "a"
material = "rock"
vertices = [[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]]
angular_velocity = 1.0
[[block]]
name = "far"
material = "rock"
vertices = [[10.0, 0.0], [11.0, 0.0], [11.0, 1.0], [10.0, 1.0]]
fix = ["x", "y", "rotation"]
[[phase]]
name = "spin"
stop = { time = 0.5 }
[[phase]]
name = "reset"
stop = { cycles = 1 }
reset = ["displacements"]
"""
    done, results = run(tmp_path, text)
    assert done.returncode == 0, done.stderr
    turned = 0.5 + results["blocks"][0]["angular_velocity"] * results["run"]["dt"]
    assert results["blocks"][0]["rotation"] == pytest.approx(results["run"]["dt"], rel=1e-9, abs=0)
    last = sorted((tmp_path / "out" / "vtk").glob("snapshot_*.vtu"))[-1]
    piece = ET.parse(last).getroot().find("UnstructuredGrid/Piece")
    position = next(a for a in piece.iter("DataArray") if a.get("Name") == "position")
    xy = [float(v) for v in position.text.split()]
    first, second = (xy[0], xy[1]), (xy[3], xy[4])
    # the block's first edge, from vertex 0 to vertex 1, 2 m long along the block's turned axis
    assert math.atan2(second[1] - first[1], second[0] - first[0]) == pytest.approx(turned, abs=1e-9)

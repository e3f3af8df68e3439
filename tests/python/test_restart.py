"""Save and restart (vdec run --save, --restart): a run continued from a state file is the run
that did not stop, bitwise; a state file that cannot be continued is refused with exit code 10
(docs/user-manual/command-line.md#save-and-restart)."""
import json
import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PROBLEMS = ROOT / "verification" / "problems"
VDEC = os.environ.get("VDEC_EXECUTABLE", str(ROOT / "build" / "vdec"))
pytestmark = pytest.mark.skipif(not Path(VDEC).is_file(), reason="vdec is not built")
REQ = pytest.mark.requirements("REQ-RUN-005")

# A scene of each kind, its [stop] replaced by two phases: (problem, phases). The second phase
# changes something, so that a restart that lost a phase's changes would show.
PHASED = {
    "rigid": ("RUN-PHASE-WEAKENING", None),
    "mohr-coulomb": ("MC-TUNNEL", '[[phase]]\nname = "first"\nstop = { time = 0.04 }\n'
                                  '[[phase]]\nname = "second"\nstop = { time = 0.04 }\nmass_damping = 20.0\n'),
    "jointed-deformable": ("DB-JOINT-STACK", '[[phase]]\nname = "first"\nstop = { cycles = 300 }\n'
                                             '[[phase]]\nname = "second"\nstop = { ratio = 1e-10, cycles = 200000 }\n'
                                             'reset = ["displacements"]\n'),
    "continuously-yielding": ("CY-SHEAR", '[[phase]]\nname = "first"\nstop = { time = 4.0 }\n'
                                          '[[phase]]\nname = "second"\nstop = { time = 6.0 }\nreset = ["velocities"]\n'),
}
# What must be equal: everything the run computes (not its timings, environment or provenance).
COMPARED = ("histories", "blocks", "contacts", "gridpoints", "zones", "energy")


def phased_scene(tmp_path, kind):
    problem, phases = PHASED[kind]
    folder = tmp_path / problem
    shutil.copytree(PROBLEMS / problem, folder)
    scene = folder / "scene.toml"
    if phases:
        text = re.sub(r"(?ms)^\[stop\]\n(?:[^\[].*?\n)*", "", scene.read_text())
        scene.write_text(text + "\n" + phases)
    return scene


def run(scene, out, *extra):
    done = subprocess.run([VDEC, "run", str(scene), "--out", str(out), *extra], capture_output=True, text=True,
                          timeout=300)
    results = Path(out) / "results.json"
    return done, json.loads(results.read_text()) if results.is_file() else None


def computed(results):
    phases = [{k: v for k, v in p.items() if k != "wall_seconds"} for p in results["phases"]]
    return {key: results.get(key) for key in COMPARED}, phases


@REQ
@pytest.mark.parametrize("threads", ["1", "2"])
@pytest.mark.parametrize("kind", sorted(PHASED))
def test_a_restarted_run_is_the_run_that_did_not_stop(tmp_path, kind, threads):
    scene = phased_scene(tmp_path, kind)
    done, whole = run(scene, tmp_path / "whole", "--threads", "1")
    assert done.returncode == 0, done.stderr
    first_phase = whole["phases"][0]["name"]
    done, _ = run(scene, tmp_path / "first", "--threads", threads, "--save", first_phase)
    assert done.returncode == 0, done.stderr
    state = tmp_path / "first" / "after-phase-1.vdecstate"
    assert state.is_file()
    done, rest = run(scene, tmp_path / "rest", "--threads", threads, "--restart", str(state))
    assert done.returncode == 0, done.stderr
    assert rest["scene"]["restart"] == {"file": str(state), "phases_done": 1}
    assert computed(rest) == computed(whole)


@pytest.fixture(scope="module")
def saved(tmp_path_factory):
    tmp_path = tmp_path_factory.mktemp("saved")
    scene = phased_scene(tmp_path, "continuously-yielding")
    done, _ = run(scene, tmp_path / "first", "--save", "first")
    assert done.returncode == 0, done.stderr
    return scene, (tmp_path / "first" / "after-phase-1.vdecstate").read_bytes()


def refused(tmp_path, scene, content, *extra):
    state = tmp_path / "state.vdecstate"
    state.write_bytes(content)
    done, _ = run(scene, tmp_path / "out", "--restart", str(state), *extra)
    assert done.returncode == 10, done.stderr
    return done.stderr


@REQ
def test_a_truncated_state_is_refused(tmp_path, saved):
    scene, content = saved
    assert "truncated" in refused(tmp_path, scene, content[: len(content) // 2])


@REQ
def test_a_damaged_state_is_refused_by_its_checksum(tmp_path, saved):
    scene, content = saved
    damaged = bytearray(content)
    damaged[len(damaged) // 2] ^= 0x40
    assert "damaged (its checksum does not match" in refused(tmp_path, scene, bytes(damaged))


@REQ
def test_a_foreign_file_is_refused(tmp_path, saved):
    scene, _ = saved
    assert "not a vdec state file" in refused(tmp_path, scene, b"PK\x03\x04 a zip archive, not a state")


@REQ
def test_an_older_format_is_refused(tmp_path, saved):
    scene, content = saved
    current = int.from_bytes(content[8:12], "little")
    older = content[:8] + (current - 1).to_bytes(4, "little") + content[12:]
    assert f"state file format {current - 1}, this vdec reads format {current}" in refused(tmp_path, scene, older)


@REQ
@pytest.mark.parametrize("edit", [
    ('name = "first"\nstop = { time = 4.0 }', 'name = "first"\nstop = { time = 4.5 }'),
    ("[[phase]]", "[[history]]\nname = \"extra\"\nquantity = \"model.kinetic_energy\"\n[[phase]]"),
])
def test_a_scene_whose_saved_phases_differ_is_refused(tmp_path, saved, edit):
    scene, content = saved
    changed = tmp_path / "changed.toml"
    changed.write_text(scene.read_text().replace(*edit, 1))
    assert "of a scene that differs from" in refused(tmp_path, changed, content)


@REQ
def test_phases_may_be_appended_after_the_saved_one(tmp_path, saved):
    scene, content = saved
    longer = tmp_path / "longer.toml"
    longer.write_text(scene.read_text() + '[[phase]]\nname = "third"\nstop = { time = 1.0 }\n')
    state = tmp_path / "state.vdecstate"
    state.write_bytes(content)
    done, results = run(longer, tmp_path / "out", "--restart", str(state))
    assert done.returncode == 0, done.stderr
    assert [p["name"] for p in results["phases"]] == ["first", "second", "third"]


@REQ
def test_save_names_a_phase_of_the_scene(tmp_path, saved):
    scene, _ = saved
    done, _ = run(scene, tmp_path / "out", "--save", "nonesuch")
    assert done.returncode == 2
    assert "--save nonesuch: " in done.stderr and "has no phase of that name (its phases: 'first', 'second')" in done.stderr


# A boundary condition added by a phase that was saved: a restart must apply it (its stage is
# formed from the loaded model, not from the scene's start).
ADDED_IN_A_PHASE = """
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
fix = ["x", "y"]
[[history]]
name = "uy"
quantity = "gridpoint.displacement_y"
block = "column"
point = [0.5, 4.0]
every = 1
[[history]]
name = "ay"
quantity = "gridpoint.acceleration_y"
block = "column"
point = [0.5, 4.0]
every = 3
[[phase]]
name = "quiet"
stop = { cycles = 5 }
[[phase]]
name = "load"
stop = { cycles = 50 }
[[phase.boundary]]
name = "p"
block = "column"
y = [4.0, 4.0]
stress = [0.0, -1e6, 0.0]
[[phase.boundary]]
name = "wave"
block = "column"
x = [0.0, 0.0]
viscous = true
input_velocity = [0.001, 0.0]
history = { kind = "sine", frequency = 200.0 }
[[phase]]
name = "more"
stop = { cycles = 50 }
"""


@REQ
def test_a_restart_applies_the_boundary_conditions_a_saved_phase_added(tmp_path):
    scene = tmp_path / "scene.toml"
    scene.write_text(ADDED_IN_A_PHASE)
    done, whole = run(scene, tmp_path / "whole")
    assert done.returncode == 0, done.stderr
    done, _ = run(scene, tmp_path / "first", "--save", "load")
    assert done.returncode == 0, done.stderr
    done, rest = run(scene, tmp_path / "rest", "--restart", str(tmp_path / "first" / "after-phase-2.vdecstate"))
    assert done.returncode == 0, done.stderr
    assert rest["run"]["stages"] == whole["run"]["stages"]
    assert computed(rest) == computed(whole)

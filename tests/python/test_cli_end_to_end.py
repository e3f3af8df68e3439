"""The vdec executable end to end: exit codes, diagnostics and repeatable results."""
import json
import re
import os
import subprocess
from pathlib import Path

import pytest
from scene_runs import lattice

ROOT = Path(__file__).resolve().parents[2]
VDEC = os.environ.get("VDEC_EXECUTABLE", str(ROOT / "build" / "vdec"))
SCENE = (ROOT / "verification/problems/RB-STABILITY-FRAC/scene.toml").read_text()

pytestmark = pytest.mark.skipif(not Path(VDEC).is_file(), reason="vdec is not built")


def run(tmp_path, text, *extra, name="scene.toml"):
    scene = tmp_path / name
    scene.write_text(text)
    out = tmp_path / "out"
    done = subprocess.run([VDEC, "run", str(scene), "--out", str(out), *extra], capture_output=True, text=True,
                          timeout=120)
    results = json.loads((out / "results.json").read_text()) if (out / "results.json").is_file() else None
    return done, results


@pytest.mark.requirements("REQ-RUN-002")
def test_second_run_of_the_same_scene_gives_identical_results(tmp_path):
    _, first = run(tmp_path, SCENE, "--set", "stop.time=0.5")
    _, second = run(tmp_path, SCENE, "--set", "stop.time=0.5")
    for r in (first, second):
        for key in ("wall_seconds", "setup_seconds", "stage_seconds"):
            r["run"].pop(key)
        assert r.pop("environment")["written_utc"].endswith("Z")
    assert first == second
    assert first["histories"]["energy_ratio"]["value"]


@pytest.mark.requirements("REQ-IO-001")
def test_results_record_provenance_and_the_scene_hash(tmp_path):
    import hashlib
    done, results = run(tmp_path, SCENE)
    assert done.returncode == 0, done.stderr
    assert results["schema"] == "vdec.results/1"
    for key in ("version", "git_commit", "build_type", "compiler"):
        assert results["software"][key]
    assert results["scene"]["sha256"] == hashlib.sha256(SCENE.encode()).hexdigest()
    assert results["run"]["stages"] == ["contact-detection", "contact-forces", "rigid-block-motion", "histories"]


@pytest.mark.requirements("REQ-IO-002")
def test_bad_scene_exits_3_naming_file_line_and_key(tmp_path):
    text = SCENE.replace("friction = 30.0", "frictoin = 30.0")
    line = text.splitlines().index("frictoin = 30.0") + 1
    done, _ = run(tmp_path, text, name="bad.toml")
    assert done.returncode == 3
    assert f"bad.toml:{line}: key 'joint_material[0].frictoin': unknown key" in done.stderr


@pytest.mark.requirements("REQ-GEOM-002")
def test_invalid_polygon_exits_4_naming_the_block(tmp_path):
    text = SCENE.replace("[[-0.5, 0.0], [0.5, 0.0], [0.5, 1.0], [-0.5, 1.0]]",
                         "[[-0.5, 0.0], [0.5, 1.0], [0.5, 0.0], [-0.5, 1.0]]")
    done, _ = run(tmp_path, text)
    assert done.returncode == 4
    assert "block 'top'" in done.stderr and "self-intersecting" in done.stderr


@pytest.mark.requirements("REQ-MOTION-005")
def test_unstable_time_step_exits_5_and_says_what_to_change(tmp_path):
    done, results = run(tmp_path, SCENE, "--set", "solver.frac=1.8")
    assert done.returncode == 5
    assert "lower solver.frac" in done.stderr
    assert results["run"]["stop_reason"] == "error" and results["run"]["exit_code"] == 5


@pytest.mark.requirements("REQ-CONTACT-003")
def test_overlap_beyond_half_the_rounding_length_exits_6_naming_the_contact(tmp_path):
    done, _ = run(tmp_path, SCENE.replace("kn = 1e8", "kn = 1e5"))
    assert done.returncode == 6
    assert "block 'top' on block 'base'" in done.stderr and "raise the joint stiffness kn" in done.stderr


@pytest.mark.requirements("REQ-IO-003")
def test_usage_error_exits_2(tmp_path):
    done = subprocess.run([VDEC, "run"], capture_output=True, text=True)
    assert done.returncode == 2


@pytest.mark.requirements("REQ-RUN-001")
def test_run_stops_when_the_unbalanced_force_ratio_is_reached(tmp_path):
    done, results = run(tmp_path, SCENE, "--set", "solver.mass_damping=200.0", "--set", "stop.ratio=1e-4",
                        "--set", "stop.cycles=100000", "--set", "stop.time=1e3")
    assert done.returncode == 0, done.stderr
    assert results["run"]["stop_reason"] == "ratio"
    assert results["run"]["unbalanced_ratio"] <= 1e-4
    assert results["run"]["cycles"] < 100000
    assert "warning" not in done.stderr


@pytest.mark.requirements("REQ-RUN-001")
def test_run_that_reaches_its_limit_before_the_ratio_says_so(tmp_path):
    done, results = run(tmp_path, SCENE, "--set", "stop.ratio=1e-12", "--set", "stop.cycles=50",
                        "--set", "stop.time=1e3")
    assert done.returncode == 0, done.stderr
    assert results["run"]["stop_reason"] == "cycles" and results["run"]["cycles"] == 50
    assert "warning: stopped on cycles before the unbalanced-force ratio fell to 1e-12" in done.stderr


@pytest.mark.requirements("REQ-MOTION-003")
def test_first_history_sample_of_a_driven_block_shows_its_velocity_history_at_time_zero(tmp_path):
    # sin(2 pi 2 t) is 0 at t = 0: the block starts at rest and the first sample must say so,
    # not the unscaled velocity of the scene.
    text = (ROOT / "verification/problems/RB-REST-SETTLE/scene.toml").read_text().replace(
        'name = "top"\nmaterial = "rock"\n',
        'name = "top"\nmaterial = "rock"\nfix = ["x"]\nvelocity = [1e-3, 0.0]\n'
        'velocity_history = { kind = "sine", frequency = 2.0 }\n')
    text += '[[history]]\nname = "vx"\nquantity = "block.velocity_x"\nblock = "top"\nevery = 10\n'
    done, results = run(tmp_path, text, "--set", "stop.time=0.01")
    assert done.returncode == 0, done.stderr
    h = results["histories"]["vx"]
    assert h["t"][0] == 0.0 and h["value"][0] == 0.0
    # Later samples: the velocity of the half step just taken, 1e-3 sin(2 pi 2 (t - dt/2)).
    import math
    dt = results["run"]["dt"]
    for t, v in zip(h["t"][1:], h["value"][1:]):
        assert v == pytest.approx(1e-3 * math.sin(2 * math.pi * 2.0 * (t - 0.5 * dt)), rel=1e-9, abs=0)


FALLING_BLOCK = """
[model]
gravity = [0.0, -9.81]
rounding = 0.01
[stop]
cycles = 250001
[[block_material]]
name = "rock"
density = 2500.0
[[joint_material]]
name = "joint"
kn = 1e9
ks = 1e9
[[block]]
name = "b"
material = "rock"
vertices = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
[[history]]
name = "y"
quantity = "block.y"
block = "b"
[[history]]
name = "ke"
quantity = "model.kinetic_energy"
"""


@pytest.mark.requirements("REQ-IO-006")
def test_histories_longer_than_the_sample_limit_are_halved_to_what_a_doubled_every_records(tmp_path):
    # 250001 cycles sampled every cycle: 100000 samples (the limit) halve the series to every 2,
    # then again to every 4; what is left must be exactly the run sampled every 4 from the start.
    done, every_cycle = run(tmp_path, FALLING_BLOCK)
    assert done.returncode == 0, done.stderr
    for name, cycle in (("y", 99999), ("ke", 100000)):
        assert (f"vdec: warning: history '{name}' reached 100000 samples at cycle {cycle}: it now keeps every other "
                f"sample and samples every 2 cycles") in done.stderr
    text = FALLING_BLOCK.replace('block = "b"\n', 'block = "b"\nevery = 4\n') + "every = 4\n"
    done, every_fourth = run(tmp_path, text)
    assert done.returncode == 0, done.stderr
    assert "warning" not in done.stderr
    for name, count in (("y", 62501), ("ke", 62500)):
        halved, direct = every_cycle["histories"][name], every_fourth["histories"][name]
        assert halved["every"] == 4 and direct["every"] == 4
        assert len(halved["t"]) == count
        assert halved["t"] == direct["t"] and halved["value"] == direct["value"]


LARGE_SETUP = """
[model]
rounding = 0.01
[stop]
cycles = 1
[[block_material]]
name = "rock"
density = 2500.0
young = 1e9
poisson = 0.25
[[joint_material]]
name = "joint"
kn = 1e9
ks = 1e9
[[block]]
name = "slab"
material = "rock"
vertices = [[0.0, -10.0], [10.0, -10.0], [10.0, 0.0], [0.0, 0.0]]
zoning = { nx = 256, ny = 256 }
[[region]]
name = "mass"
material = "rock"
vertices = [[0.0, 0.0], [100.0, 0.0], [100.0, 100.0], [0.0, 100.0]]
[[region.joint_set]]
angle = 0.0
spacing = 0.25
trace = 0.01
gap = 100.0
[[region.joint_set]]
angle = 90.0
spacing = 0.25
trace = 0.01
gap = 100.0
"""


def run_with_terminal(tmp_path, text):
    """Runs vdec with stderr on a pseudo-terminal (stdout a pipe); returns the exit code and stderr."""
    import pty
    scene = tmp_path / "scene.toml"
    scene.write_text(text)
    primary, secondary = pty.openpty()
    process = subprocess.Popen([VDEC, "run", str(scene), "--out", str(tmp_path / "out")], stdout=subprocess.PIPE,
                               stderr=secondary)
    os.close(secondary)
    output = b""
    while True:
        try:
            chunk = os.read(primary, 4096)
        except OSError:  # the terminal closes when vdec exits
            break
        if not chunk:
            break
        output += chunk
    os.close(primary)
    return process.wait(timeout=120), output.decode()


@pytest.mark.requirements("REQ-IO-005")
def test_large_setups_show_progress_on_a_terminal_and_nothing_on_a_pipe(tmp_path):
    code, terminal = run_with_terminal(tmp_path, LARGE_SETUP)
    assert code == 0, terminal
    assert f"zoning {tmp_path / 'scene.toml'}:15: [block[0]]: about 262144 zones" in terminal
    assert "cutting region 'mass' into up to 161604 blocks: 0" in terminal
    done, _ = run(tmp_path, LARGE_SETUP)
    assert done.returncode == 0, done.stderr
    assert "zoning" not in done.stderr and "cutting" not in done.stderr


@pytest.mark.requirements("REQ-IO-005")
@pytest.mark.parametrize("change, replacement, key, message", [
    ("nx = 256, ny = 256", "nx = 4096, ny = 4096", "block[0].zoning",
     "makes 4 nx ny = 67108864 zones, more than the 2000000 left of the scene's limit of 2000000 zones"),
    ("spacing = 0.25\ntrace = 0.01\ngap = 100.0", "spacing = 1e-9", "region[0].joint_set",
     "region 'mass' would be cut into up to"),
    ("trace = 0.01\ngap = 100.0", "trace = 1e-9", "region[0].joint_set", "region 'mass' would be cut with up to"),
])
def test_setups_beyond_the_limits_are_refused_before_the_work(tmp_path, change, replacement, key, message):
    import time
    start = time.monotonic()
    done, results = run(tmp_path, LARGE_SETUP.replace(change, replacement))
    assert time.monotonic() - start < 5.0
    assert done.returncode == 3 and results is None
    assert f"key '{key}': {message}" in done.stderr, done.stderr


@pytest.mark.requirements("REQ-IO-002")
def test_mass_damping_past_two_over_the_step_is_an_input_error(tmp_path):
    # 1e308 1/s made the damping dissipation overflow and wrote null into results.json.
    text = (ROOT / "verification/problems/RB-REST-SETTLE/scene.toml").read_text()
    done, _ = run(tmp_path, text, "--set", "solver.mass_damping=1e308")
    assert done.returncode == 3, done.stderr
    assert "solver.mass_damping = 1e+308 1/s times the time step" in done.stderr
    assert "give at most" in done.stderr
    done, _ = run(tmp_path, text, "--set", "solver.mass_damping=1000", "--set", "stop.cycles=10")
    assert done.returncode == 0, done.stderr  # alpha dt = 1 at dt = 1e-3 s: heavy but valid


@pytest.mark.requirements("REQ-IO-013")
def test_check_prints_what_a_run_would_do_without_running(tmp_path):
    # The column of SD-COLUMN-FREQUENCY, zoned: check builds it and prints its blocks, zones,
    # contacts, time step and stages, the same step and stages the run then takes, and writes nothing.
    scene = ROOT / "verification" / "problems" / "SD-COLUMN-FREQUENCY" / "zoned.toml"
    done = subprocess.run([VDEC, "check", str(scene)], capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert "blocks 9: 1 rigid, 0 simply-deformable, 8 zoned; 0 free to move" in lines
    assert "zones 128, gridpoints 104" in lines
    assert "run: stop at time 0.2 s" in lines
    assert list(tmp_path.iterdir()) == []
    ran = subprocess.run([VDEC, "run", str(scene), "--out", str(tmp_path / "out"), "--set", "stop.time=0.001"],
                         capture_output=True, text=True, timeout=120)
    assert ran.returncode == 0, ran.stderr
    results = json.loads((tmp_path / "out" / "results.json").read_text())
    step = next(float(l.split()[2]) for l in lines if l.startswith("time step "))
    assert step == pytest.approx(results["run"]["dt"], rel=1e-5, abs=0)   # printed with six digits
    assert next(l for l in lines if l.startswith("stages ")) == "stages " + ", ".join(results["run"]["stages"])


@pytest.mark.requirements("REQ-IO-013")
def test_check_refuses_a_bad_scene_as_a_run_does(tmp_path):
    scene = tmp_path / "scene.toml"
    scene.write_text(SCENE)
    done = subprocess.run([VDEC, "check", str(scene), "--set", "solver.frac=-1"], capture_output=True, text=True, timeout=60)
    ran = subprocess.run([VDEC, "run", str(scene), "--out", str(tmp_path / "out"), "--set", "solver.frac=-1"],
                         capture_output=True, text=True, timeout=60)
    assert done.returncode == ran.returncode == 3
    assert "solver.frac" in done.stderr and done.stderr == ran.stderr


@pytest.mark.requirements("REQ-IO-005")
def test_the_progress_line_shows_the_energy_error_and_the_time_left_to_a_cycle_limit(tmp_path):
    # 1 000 blocks for 6 000 cycles (a few seconds): the line is rewritten every 0.25 s with the
    # energy error and, the run having a cycle limit, the seconds left; the last line, at the
    # stop, has nothing left to estimate.
    code, terminal = run_with_terminal(tmp_path, lattice(50, 20, 6000))
    assert code == 0, terminal
    lines = [line for line in terminal.replace("\r\n", "\n").split("\r") if line.strip()]
    assert len(lines) >= 3, terminal
    assert all(re.search(r"energy error -?\d\.\de[+-]\d+", line) for line in lines), terminal
    assert all(re.search(r"left \d+ s", line) for line in lines[:-1]), terminal
    assert "cycle 6000 " in lines[-1] and "left" not in lines[-1]

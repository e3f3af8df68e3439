"""Stiffness-proportional and Rayleigh damping: the scene keys, their errors, the step factor
(docs/models/rigid-block-motion.md#stiffness-proportional-and-rayleigh-damping)."""
import json
import math
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
VDEC = os.environ.get("VDEC_EXECUTABLE", str(ROOT / "build" / "vdec"))
pytestmark = pytest.mark.skipif(not Path(VDEC).is_file(), reason="vdec is not built")
REQ = pytest.mark.requirements("REQ-MOTION-008")
SCENE = (ROOT / "verification" / "problems" / "RB-RAYLEIGH" / "scene.toml").read_text()


def run(tmp_path, text, *sets):
    scene = tmp_path / "scene.toml"
    scene.write_text(text)
    args = [VDEC, "run", str(scene), "--out", str(tmp_path / "out")]
    for s in sets:
        args += ["--set", s]
    done = subprocess.run(args, capture_output=True, text=True, timeout=120)
    results = tmp_path / "out" / "results.json"
    return done, json.loads(results.read_text()) if results.is_file() else None


@REQ
def test_rayleigh_sets_alpha_and_beta_and_reduces_the_step(tmp_path):
    done, results = run(tmp_path, SCENE, "stop.time=0.01")
    assert done.returncode == 0, done.stderr
    # w_min = 200 rad/s, beta = 0.05 / 200; the block's mode w = sqrt(1e8 * 1 / 2500) = 200
    xi = 0.5 * (0.05 / 200.0) * 200.0
    assert results["run"]["stiffness_damping_step_factor"] == pytest.approx(math.sqrt(1 + xi * xi) - xi, rel=1e-12, abs=0)
    # FRAC 0.05 times the undamped critical step 2 / w = 0.01 s, times the factor
    assert results["run"]["dt"] == pytest.approx(0.05 * 0.01 * results["run"]["stiffness_damping_step_factor"], rel=1e-12, abs=0)
    assert results["energy"]["damping_dissipation"] > 0.0


@REQ
@pytest.mark.parametrize("sets, message", [
    (["solver.stiffness_damping=1e-4"], "key 'solver.rayleigh': sets the stiffness damping itself; give rayleigh or stiffness_damping, not both"),
    (["solver.mass_damping=5.0"], "key 'solver.rayleigh': sets the mass damping itself"),
    (["solver.rayleigh.ratio=1.5"], "key 'solver.rayleigh.ratio': must be in (0, 1)"),
    (["solver.rayleigh.frequency=-1.0"], "solver.rayleigh.frequency"),
    (["solver.adaptive_damping=true"], "key 'solver.rayleigh': goes with mass damping (Rayleigh damping), not with adaptive or local damping"),
])
def test_rayleigh_damping_scene_errors(tmp_path, sets, message):
    done, results = run(tmp_path, SCENE, *sets)
    assert done.returncode == 3, done.stderr
    if message:
        assert message in done.stderr, done.stderr
    assert results is None


@pytest.mark.requirements("REQ-ZONE-018")
def test_zones_take_stiffness_damping_and_their_step_shrinks_as_belytschko_says(tmp_path):
    scene = (ROOT / "verification" / "problems" / "DB-RAYLEIGH" / "scene.toml").read_text()
    done, results = run(tmp_path, scene.replace("[stop]", "[solver]\nstiffness_damping = 2.9e-4\n[stop]"))
    assert done.returncode == 0, done.stderr
    factor, dt = results["run"]["stiffness_damping_step_factor"], results["run"]["dt"]
    # The zones' step estimate 2 sqrt(m / k) is dt / factor; their stiffest mode has w <= 2 / that,
    # xi = beta w / 2 = beta factor / dt, and the factor must be sqrt(1 + xi^2) - xi.
    xi = 2.9e-4 * factor / dt
    assert factor == pytest.approx(math.sqrt(1 + xi * xi) - xi, rel=1e-12, abs=0)
    assert factor < 0.1  # the damping of the stiffest zone mode costs a tenth of the step here
    # The viscous stress's work is booked as damping: the account closes.
    e = results["energy"]
    assert e["damping_dissipation"] > 0.0
    assert e["kinetic"] + e["strain"] + e["damping_dissipation"] == pytest.approx(
        e["initial"] + e["external_work"], rel=1e-3, abs=0)


@REQ
def test_a_phase_that_frees_a_lighter_block_forms_the_step_factor_again(tmp_path):
    # A free 2 m block and a held 0.5 m block on a fixed base, kn = 1e8 Pa/m, beta = 1e-3 s. The
    # rigid-block step takes the lightest free block and the longest edge among the free blocks
    # (2 m): w = sqrt(kn 2 / m) is 141.4 rad/s with only the heavy block free, 565.7 once the
    # light one (625 kg/m) is freed, and the factor sqrt(1 + xi^2) - xi, xi = beta w / 2, must
    # follow it down (a step left at the heavy block's factor would be too long for the light one).
    scene = """
[model]
gravity = [0.0, -10.0]
rounding = 0.01
[solver]
stiffness_damping = 1e-3
[[block_material]]
name = "rock"
density = 2500.0
[[joint_material]]
name = "joint"
kn = 1e8
ks = 1e8
friction = 30.0
[[block]]
name = "base"
material = "rock"
vertices = [[-4.0, -1.0], [4.0, -1.0], [4.0, 0.0], [-4.0, 0.0]]
fix = ["x", "y", "rotation"]
[[block]]
name = "heavy"
material = "rock"
vertices = [[-3.0, 0.0], [-1.0, 0.0], [-1.0, 2.0], [-3.0, 2.0]]
[[block]]
name = "light"
material = "rock"
vertices = [[1.0, 0.0], [1.5, 0.0], [1.5, 0.5], [1.0, 0.5]]
fix = ["x", "y", "rotation"]
[[phase]]
name = "held"
stop = { cycles = 10 }
[[phase]]
name = "freed"
stop = { cycles = 10 }
[[phase.block]]
name = "light"
free = ["x", "y", "rotation"]
"""
    done, results = run(tmp_path, scene)
    assert done.returncode == 0, done.stderr
    w = math.sqrt(1e8 * 2.0 / 625.0)
    xi = 0.5 * 1e-3 * w
    factor = math.sqrt(1 + xi * xi) - xi
    assert results["run"]["stiffness_damping_step_factor"] == pytest.approx(factor, rel=1e-12, abs=0)
    assert results["run"]["dt"] == pytest.approx(0.1 * 2 * math.sqrt(625.0 / 2e8) * factor, rel=1e-12, abs=0)

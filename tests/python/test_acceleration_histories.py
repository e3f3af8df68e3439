"""Acceleration histories (block.acceleration_*, gridpoint.acceleration_*): the change of
velocity over a step divided by the step, at the step's start."""
import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
VDEC = os.environ.get("VDEC_EXECUTABLE", str(ROOT / "build" / "vdec"))
pytestmark = pytest.mark.skipif(not Path(VDEC).is_file(), reason="vdec is not built")

# A rigid block and a zoned block falling freely side by side, apart, under g = 10 m/s^2, and a
# joint material for the time step; the rigid block also turns.
SCENE = """
[model]
gravity = [0.0, -10.0]
rounding = 0.01
[stop]
cycles = 40
[[block_material]]
name = "rock"
density = 2500.0
young = 10e9
poisson = 0.25
[[joint_material]]
name = "j"
kn = 1e9
ks = 1e9
[[block]]
name = "rigid"
material = "rock"
vertices = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
angular_velocity = 2.0
[[block]]
name = "zoned"
material = "rock"
vertices = [[5.0, 0.0], [6.0, 0.0], [6.0, 1.0], [5.0, 1.0]]
zoning = { nx = 2, ny = 2 }
[[history]]
name = "a_block"
quantity = "block.acceleration_y"
block = "rigid"
every = 3
[[history]]
name = "ax_block"
quantity = "block.acceleration_x"
block = "rigid"
[[history]]
name = "a_gridpoint"
quantity = "gridpoint.acceleration_y"
block = "zoned"
point = [5.0, 1.0]
[[history]]
name = "v_block"
quantity = "block.velocity_y"
block = "rigid"
"""


@pytest.mark.requirements("REQ-MOTION-009")
def test_a_falling_block_and_gridpoint_accelerate_at_g(tmp_path):
    scene = tmp_path / "scene.toml"
    scene.write_text(SCENE)
    done = subprocess.run([VDEC, "run", str(scene), "--out", str(tmp_path / "out")], capture_output=True, text=True,
                          timeout=60)
    assert done.returncode == 0, done.stderr
    results = json.loads((tmp_path / "out" / "results.json").read_text())
    h = results["histories"]
    dt = results["run"]["dt"]
    # Central differences give a free body exactly g dt more velocity per step: a = -g to round-off
    # (v ~ 40 g dt, so the difference of two velocities over dt loses about 40 ulp of g).
    for name in ("a_block", "a_gridpoint"):
        assert np.allclose(h[name]["value"], -10.0, rtol=1e-9, atol=0.0), name
    assert np.allclose(h["ax_block"]["value"], 0.0, rtol=0.0, atol=1e-9)
    # Sampled from the first step on, at the step's start, `every` cycles apart.
    assert len(h["a_gridpoint"]["t"]) == 40 and h["a_gridpoint"]["t"][0] == 0.0
    assert np.allclose(np.diff(h["a_gridpoint"]["t"]), dt, rtol=1e-9, atol=0.0)
    assert np.allclose(h["a_block"]["t"], [k * dt for k in range(2, 40, 3)], rtol=1e-9, atol=1e-15)
    # The velocity history is its integral: v(t + dt/2) - v(t - dt/2) = a dt.
    v = np.array(h["v_block"]["value"])
    assert np.allclose(np.diff(v) / dt, -10.0, rtol=1e-9, atol=0.0)

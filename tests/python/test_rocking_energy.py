"""Contact forces create no energy when a contact's length changes with the geometry.

A rigid block released tilted on a fixed base rocks about one corner, lands on the other and
rocks back, undamped: at each tilt past the contact tolerance a face contact becomes a corner
contact and back. The joints' account of the energy (`energy.joint_release`, what they gave up
without work) must never be negative beyond the trapezoidal rule's error of the springs' work,
and the run must not stop. Before the stresses were scaled to keep the springs' energy across a
change of length (and the length made continuous in the tilt), the stress was held while the
length jumped: the pivot force dropped by most of its value, the joints created thousands of
joules and the runs stopped on overlap.
"""
import json
import math
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
VDEC = os.environ.get("VDEC_EXECUTABLE", str(ROOT / "build" / "vdec"))
pytestmark = pytest.mark.skipif(not Path(VDEC).is_file(), reason="vdec is not built")

WIDTH, HEIGHT = 1.0, 2.0
ALPHA = math.atan(WIDTH / HEIGHT)  # the block's slenderness angle


def rocking_scene(tilt, friction, kn=1e10, time=3.0):
    """The block tilted by `tilt` about its right-hand bottom corner, touching the base there."""
    px = WIDTH / 2
    c, s = math.cos(-tilt), math.sin(-tilt)
    corners = [(-WIDTH / 2, 0.0), (WIDTH / 2, 0.0), (WIDTH / 2, HEIGHT), (-WIDTH / 2, HEIGHT)]
    placed = [(px + c * (x - px) - s * y, s * (x - px) + c * y) for x, y in corners]
    vertices = ", ".join(f"[{x!r}, {y!r}]" for x, y in placed)
    return f"""
title = "rocking block"
[model]
gravity = [0.0, -9.81]
rounding = 0.01
[stop]
time = {time}
[[block_material]]
name = "rock"
density = 2500.0
[[joint_material]]
name = "j"
kn = {kn}
ks = {kn}
friction = {friction}
[[block]]
name = "base"
material = "rock"
vertices = [[-3.0, -1.0], [3.0, -1.0], [3.0, 0.0], [-3.0, 0.0]]
fix = ["x", "y", "rotation"]
[[block]]
name = "b"
material = "rock"
vertices = [{vertices}]
"""


@pytest.mark.requirements("REQ-CONTACT-006")
@pytest.mark.parametrize("share", [0.25, 0.5, 0.9])
@pytest.mark.parametrize("friction", [60.0, 89.0])
def test_an_undamped_rocking_block_gets_no_energy_from_its_joints(tmp_path, share, friction):
    scene = tmp_path / "scene.toml"
    scene.write_text(rocking_scene(share * ALPHA, friction))
    out = tmp_path / "out"
    done = subprocess.run([VDEC, "run", str(scene), "--out", str(out)], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    energy = json.loads((out / "results.json").read_text())["energy"]
    # The joints' springs store what their forces' work put in, less slip: the trapezoidal rule
    # of that work errs by O(kn L dun^2) a step, far below 1e-4 of the gravity work here.
    assert energy["joint_release"] > -1e-4 * abs(energy["external_work"]), energy
    # Nothing created anywhere: the mechanical energy never exceeded what gravity supplied.
    assert energy["largest_excess"] < 0.01, energy

"""Viscous boundaries on a rigid block's edges (docs/user-manual/scene-format.md#boundary): the
dashpots of any edge against the closed form of verification/analytic/rigid_blocks.py, the energy
they take, and the scene errors of the selection and the impedances."""
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "verification"))
from analytic import rigid_blocks as rb  # noqa: E402

VDEC = os.environ.get("VDEC_EXECUTABLE", str(ROOT / "build" / "vdec"))
SCENE = ROOT / "verification" / "problems" / "BND-VISCOUS-RIGID" / "scene.toml"
pytestmark = pytest.mark.skipif(not Path(VDEC).is_file(), reason="vdec is not built")
MEDIUM = dict(density=2000.0, young=5e7, poisson=0.25)
BLOCK = dict(width=2.0, height=1.0, density=2500.0, medium=MEDIUM)


def run(tmp_path, *overrides):
    """vdec on the BND-VISCOUS-RIGID scene with --set overrides: (the process, results.json or None)."""
    sets = [word for override in overrides for word in ("--set", override)]
    done = subprocess.run([VDEC, "run", str(SCENE), "--out", str(tmp_path / "out"), *sets], capture_output=True,
                          text=True, timeout=60)
    results = tmp_path / "out" / "results.json"
    return done, json.loads(results.read_text()) if results.is_file() else None


@pytest.mark.requirements("REQ-BOUNDARY-005")
def test_the_dashpots_of_a_side_edge_follow_its_dashpot_matrix(tmp_path):
    # The right side (x = 1 m, the centroid at y = 0.5 m): the normal dashpots stop vx, the shear
    # ones vy and, being 1 m to the right of the centroid, couple vy and w.
    q0 = (1e-12, -1e-12, 1e-12)
    done, results = run(tmp_path, "boundary[0].y=[0.0,1.0]", "boundary[0].x=[1.0,1.0]")
    assert done.returncode == 0, done.stderr
    dt, steps = results["run"]["dt"], results["run"]["cycles"]
    # Round-off: eps of q per step, forgotten at the slowest mode's rate (here 3.8 /s, slow beside
    # the run's 0.1 s): at most eps min(n, 1 / (lambda_min dt)) = 2.1e-13 of the largest velocity.
    slowest = rb.viscous_rigid_block_decay_rates(edge_from=(1.0, -0.5), edge_to=(1.0, 0.5), **BLOCK)[0]
    tolerance = np.finfo(float).eps / 2.0 * min(steps, 1.0 / (slowest * dt))
    for dof in ("vx", "vy", "w"):
        h = results["histories"][dof]
        expected = rb.viscous_rigid_block_velocity_discrete(np.array(h["t"]), edge_from=(1.0, -0.5), edge_to=(1.0, 0.5),
                                                            initial_velocity=q0, dof=dof, dt=dt, **BLOCK)
        assert np.max(np.abs(np.array(h["value"]) - expected)) <= tolerance * np.max(np.abs(expected)), dof


@pytest.mark.requirements("REQ-BOUNDARY-005")
def test_the_dashpots_work_is_the_kinetic_energy_the_block_loses(tmp_path):
    # At 1 mm/s the block turns (by 2e-5 rad) and the closed form no longer holds to round-off,
    # but the energy account does: after 0.4 s (e^-37 of the kinetic energy left) the dashpots
    # have taken what the block had.
    done, results = run(tmp_path, "block[0].velocity=[1e-3,-1e-3]", "block[0].angular_velocity=1e-3", "stop.time=0.4")
    assert done.returncode == 0, done.stderr
    energy = results["energy"]
    assert energy["initial"] == pytest.approx(0.5 * (5000.0 * 2e-6 + 2500.0 * 10.0 / 12.0 * 1e-6), rel=1e-14, abs=0)
    assert energy["boundary_dissipation"] == pytest.approx(energy["initial"], rel=1e-12, abs=0)
    assert energy["external_work"] == 0.0


@pytest.mark.requirements("REQ-BOUNDARY-005", "REQ-QA-007")
def test_a_rigid_viscous_boundary_that_selects_no_edge_is_a_scene_error(tmp_path):
    done, _ = run(tmp_path, "boundary[0].y=[0.0,0.5]", "boundary[0].x=[-1.0,0.0]")
    assert done.returncode == 3, done.stderr
    assert "[boundary[0]]" in done.stderr and "selects no edge of rigid block 'block'" in done.stderr, done.stderr


@pytest.mark.requirements("REQ-BOUNDARY-005", "REQ-QA-007")
def test_a_rigid_viscous_boundary_needs_the_wave_speeds_of_some_material(tmp_path):
    # Without material = "...", the block's own material, which has no elastic constants here.
    text = SCENE.read_text()
    assert 'material = "soil"\n' in text
    scene = tmp_path / "scene.toml"
    scene.write_text(text.replace('material = "soil"\n', "", 1))
    done = subprocess.run([VDEC, "run", str(scene), "--out", str(tmp_path / "out")], capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 3, done.stderr
    assert "key 'boundary[0].block'" in done.stderr and "name the medium beyond the boundary" in done.stderr, done.stderr
    # An empty name is no name: refused rather than taken for the block's own.
    done, _ = run(tmp_path, 'boundary[0].material=""')
    assert done.returncode == 3, done.stderr
    assert "key 'boundary[0].material'" in done.stderr and "is empty" in done.stderr, done.stderr

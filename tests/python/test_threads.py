"""Threads: --threads, the count chosen from the work, bitwise-identical results at any count,
the count recorded in results.json (the team itself: tests/unit/test_thread_team.cpp)."""
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))
import thread_threshold  # noqa: E402  the benchmark's scene
from scene_runs import lattice  # noqa: E402

VDEC = os.environ.get("VDEC_EXECUTABLE", str(ROOT / "build" / "vdec"))

pytestmark = pytest.mark.skipif(not Path(VDEC).is_file(), reason="vdec is not built")

# The automatic count's threshold, zones + gridpoints per step (src/core/parallel.hpp).
WORK_FOR_THREADS = 8000


def block(n, cycles):
    """The elastic block of bench/thread_threshold.py (4 n^2 zones, (n + 1)^2 + n^2 gridpoints,
    fixed at its base, under gravity and a top load: every zone strains from the first step),
    with a history of its top corner."""
    return thread_threshold.block(n, cycles) + """[[history]]
name = "corner"
quantity = "gridpoint.displacement_x"
block = "block"
point = [10.0, 10.0]
"""


def run(tmp_path, text, *extra, env=None, name="out"):
    scene = tmp_path / "scene.toml"
    scene.write_text(text)
    out = tmp_path / name
    environment = {k: v for k, v in os.environ.items() if k != "OMP_NUM_THREADS"}
    environment.update(env or {})
    done = subprocess.run([VDEC, "run", str(scene), "--out", str(out), *extra], capture_output=True, text=True,
                          timeout=300, env=environment)
    results = json.loads((out / "results.json").read_text()) if (out / "results.json").is_file() else None
    return done, results


def zones_and_gridpoints(n):
    return 4 * n * n + (n + 1) ** 2 + n * n


@pytest.mark.requirements("REQ-RUN-010")
def test_one_and_two_threads_give_bitwise_identical_results(tmp_path):
    # 2 304 zones and 1 201 gridpoints: nine and five chunks of 256, so both loops do split.
    text = block(24, 400)
    one_done, one = run(tmp_path, text, "--threads", "1", name="one")
    two_done, two = run(tmp_path, text, "--threads", "2", name="two")
    assert one_done.returncode == 0, one_done.stderr
    assert two_done.returncode == 0, two_done.stderr
    assert one["environment"]["threads"] == 1 and two["environment"]["threads"] == 2
    assert one["environment"]["threads_option"] == 1 and two["environment"]["threads_option"] == 2
    for r in (one, two):
        r.pop("environment")
        for key in ("wall_seconds", "setup_seconds", "stage_seconds"):
            r["run"].pop(key)
    assert one["histories"]["corner"]["value"][-1] != 0.0
    assert one == two


@pytest.mark.requirements("REQ-RUN-010")
def test_automatic_count_is_one_thread_below_the_threshold_and_all_above(tmp_path):
    small, large = 24, 80
    assert zones_and_gridpoints(small) < WORK_FOR_THREADS < zones_and_gridpoints(large)
    done, results = run(tmp_path, block(small, 2), env={"OMP_NUM_THREADS": "2"}, name="small")
    assert done.returncode == 0, done.stderr
    assert results["environment"]["threads"] == 1 and results["environment"]["threads_option"] == 0
    done, results = run(tmp_path, block(large, 2), env={"OMP_NUM_THREADS": "2"}, name="large")
    assert done.returncode == 0, done.stderr
    assert results["environment"]["threads"] == 2
    # OMP_NUM_THREADS bounds the automatic count; --threads overrides it.
    done, results = run(tmp_path, block(large, 2), env={"OMP_NUM_THREADS": "1"}, name="bounded")
    assert results["environment"]["threads"] == 1
    done, results = run(tmp_path, block(small, 2), "--threads", "3", env={"OMP_NUM_THREADS": "1"}, name="given")
    assert results["environment"]["threads"] == 3


@pytest.mark.requirements("REQ-RUN-010")
@pytest.mark.parametrize("value", ["-1", "1025", "two"])
def test_bad_thread_count_is_a_usage_error(tmp_path, value):
    done, results = run(tmp_path, block(4, 2), "--threads", value)
    assert done.returncode == 2
    assert "--threads" in done.stderr
    assert results is None


def lattice_with_history(columns, rows, cycles, zoning=""):
    """scene_runs.lattice with a history of a top block's vertical velocity."""
    quantity, point = ("gridpoint.velocity_y", f"point = [{columns // 2}.5, {rows}.0]\n") if zoning else ("block.velocity_y", "")
    return lattice(columns, rows, cycles, zoning) + (f'[[history]]\nname = "top"\nquantity = "{quantity}"\n'
                                                     f'block = "b{columns // 2}_{rows - 1}"\n{point}')


@pytest.mark.requirements("REQ-RUN-010")
@pytest.mark.parametrize("zoning", ["", "{ nx = 2, ny = 2 }"], ids=["rigid", "deformable"])
def test_contacts_on_one_and_two_threads_give_bitwise_identical_results(tmp_path, zoning):
    # 200 blocks, over 1 000 contacts: several chunks of 256, so the contact updates split; on
    # deformable blocks the forces go to the outlines' gridpoints.
    text = lattice_with_history(20, 10, 300, zoning)
    one_done, one = run(tmp_path, text, "--threads", "1", name="one")
    two_done, two = run(tmp_path, text, "--threads", "2", name="two")
    assert one_done.returncode == 0, one_done.stderr
    assert two_done.returncode == 0, two_done.stderr
    assert len(one["contacts"]) > 2 * 256
    for r in (one, two):
        r.pop("environment")
        for key in ("wall_seconds", "setup_seconds", "stage_seconds"):
            r["run"].pop(key)
    assert one["histories"]["top"]["value"][-1] != 0.0
    assert one == two


@pytest.mark.requirements("REQ-RUN-010")
def test_automatic_count_counts_the_corners_of_touching_blocks(tmp_path):
    # Three work elements per block corner: 100 blocks (1 200) stay on one thread, 1 000 blocks
    # (12 000) take two.
    for (columns, rows), threads in (((20, 5), 1), ((50, 20), 2)):
        done, results = run(tmp_path, lattice(columns, rows, 2), env={"OMP_NUM_THREADS": "2"}, name=f"l{columns}")
        assert done.returncode == 0, done.stderr
        assert results["environment"]["threads"] == threads

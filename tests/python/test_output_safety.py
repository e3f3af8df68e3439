"""What vdec writes, and when: the output directory is checked before the scene is read, results
of an earlier run do not survive a failed one, results.json replaces a symlink instead of writing
through it, and SIGINT or SIGTERM stop a run with its results so far written (exit code 8)."""
import json
import os
import signal
import subprocess
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
VDEC = os.environ.get("VDEC_EXECUTABLE", str(ROOT / "build" / "vdec"))
SCENE = (ROOT / "verification/problems/RB-STABILITY-FRAC/scene.toml").read_text()

pytestmark = pytest.mark.skipif(not Path(VDEC).is_file(), reason="vdec is not built")


def vdec(*args, cwd=None):
    return subprocess.run([VDEC, "run", *map(str, args)], capture_output=True, text=True, timeout=120, cwd=cwd)


@pytest.mark.requirements("REQ-IO-010")
def test_empty_output_directory_is_a_usage_error_and_writes_nothing(tmp_path):
    scene = tmp_path / "scene.toml"
    scene.write_text(SCENE)
    precious = tmp_path / "results.json"
    precious.write_text("results of another program\n")
    done = vdec(scene, "--out", "", cwd=tmp_path)
    assert done.returncode == 2
    assert "--out" in done.stderr and "empty" in done.stderr
    assert precious.read_text() == "results of another program\n"


@pytest.mark.requirements("REQ-IO-010")
@pytest.mark.parametrize("case", ["file as directory", "file as parent", "directory as results.json"])
def test_bad_output_directory_fails_with_exit_7_before_the_scene_is_read(tmp_path, case):
    (tmp_path / "a_file").write_text("x")
    out = {"file as directory": tmp_path / "a_file", "file as parent": tmp_path / "a_file" / "out",
           "directory as results.json": tmp_path / "out"}[case]
    named = out
    if case == "directory as results.json":
        named = out / "results.json"
        named.mkdir(parents=True)
    # The scene does not exist: reading it first would end in exit code 3.
    done = vdec(tmp_path / "no_such_scene.toml", "--out", out)
    assert done.returncode == 7, done.stderr
    assert f"vdec: error: {named}: " in done.stderr
    assert "no_such_scene" not in done.stderr


@pytest.mark.requirements("REQ-IO-010")
def test_results_of_an_earlier_run_are_removed_when_the_next_run_fails_at_setup(tmp_path):
    scene = tmp_path / "scene.toml"
    scene.write_text(SCENE + "\n[output]\nvtk_every = 100\n")
    out = tmp_path / "out"
    first = vdec(scene, "--out", out, "--set", "stop.time=0.01")
    assert first.returncode == 0, first.stderr
    assert (out / "results.json").is_file() and (out / "vtk" / "model.pvd").is_file()
    assert list((out / "vtk").glob("snapshot_*.vtu"))
    (out / "vtk" / "notes.txt").write_text("the user's own file\n")
    bad = tmp_path / "bad.toml"
    bad.write_text(SCENE.replace("friction = 30.0", "frictoin = 30.0"))
    second = vdec(bad, "--out", out)
    assert second.returncode == 3
    assert not (out / "results.json").exists()
    assert sorted(p.name for p in (out / "vtk").iterdir()) == ["notes.txt"]


@pytest.mark.requirements("REQ-IO-010")
def test_symlinked_results_json_is_replaced_not_followed(tmp_path):
    scene = tmp_path / "scene.toml"
    scene.write_text(SCENE)
    out = tmp_path / "out"
    out.mkdir()
    elsewhere = tmp_path / "elsewhere.json"
    elsewhere.write_text("not vdec's\n")
    (out / "results.json").symlink_to(elsewhere)
    done = vdec(scene, "--out", out, "--set", "stop.time=0.01")
    assert done.returncode == 0, done.stderr
    assert elsewhere.read_text() == "not vdec's\n"
    assert not (out / "results.json").is_symlink()
    assert json.loads((out / "results.json").read_text())["schema"] == "vdec.results/1"
    # No temporary file is left behind.
    assert [p.name for p in out.iterdir()] == ["results.json"]


@pytest.mark.requirements("REQ-IO-011")
@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM])
def test_signal_stops_the_run_between_steps_writes_results_marked_interrupted_and_exits_8(tmp_path, signum):
    # A run that would go on for hours; the snapshot of cycle 0 shows that the time loop has begun.
    scene = tmp_path / "scene.toml"
    scene.write_text(SCENE.replace("time = 0.3", "time = 1e9")
                     + '\nevery = 1000\n[[history]]\nname = "y"\nquantity = "block.y"\nblock = "top"\nevery = 1000\n'
                     + "[output]\nvtk_every = 1000000000\n")
    out = tmp_path / "out"
    process = subprocess.Popen([VDEC, "run", str(scene), "--out", str(out)], stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 60
        while not (out / "vtk" / "snapshot_000000000.vtu").exists():
            assert process.poll() is None, process.stderr.read()
            assert time.monotonic() < deadline, "the run did not start"
            time.sleep(0.01)
        time.sleep(0.5)
        process.send_signal(signum)
        stderr = process.communicate(timeout=60)[1]
    finally:
        process.kill()
    name = signal.Signals(signum).name
    assert process.returncode == 8, stderr
    assert f"vdec: interrupted by {name} at cycle" in stderr
    results = json.loads((out / "results.json").read_text())
    run = results["run"]
    assert run["stop_reason"] == "interrupted" and run["interrupted"] is True and run["signal"] == name
    assert run["exit_code"] == 8 and run["error"] == ""
    assert run["cycles"] > 1000
    # The histories up to the last whole step: every 1000th cycle, the block's also at the start.
    assert len(results["histories"]["energy_ratio"]["value"]) == run["cycles"] // 1000
    y = results["histories"]["y"]
    assert len(y["t"]) == run["cycles"] // 1000 + 1 and y["t"][-1] <= run["time"]
    # The snapshot series ends with the state written to results.json.
    assert (out / "vtk" / f"snapshot_{run['cycles']:09d}.vtu").is_file()

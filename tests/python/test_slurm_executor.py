"""The slurm executor on a real cluster: a sweep and a verification subset submitted as job arrays
give what the local pool gives, bit for bit, outside timings, host names and run folders.

Needs a Slurm cluster that `sinfo` reaches, with the working tree and /tmp on file systems its
nodes mount at the same paths; on this machine: `scripts/slurm_local.sh start` (a one-node
cluster), then run this file. Skipped when no cluster answers (CI has none)."""
import json
import shutil
import subprocess
from pathlib import Path

import pytest
from scene_runs import ROOT, VDEC, needs_vdec

from vdec_sweep.sweep import main as sweep_main
from vdec_verify.__main__ import main as verify_main


def _cluster_answers():
    # A controller that answers does so in milliseconds; an installed Slurm without one retries for
    # about ten seconds.
    if shutil.which("sinfo") is None:
        return False
    try:
        return subprocess.run(["sinfo", "-h"], capture_output=True, timeout=3).returncode == 0
    except (OSError, subprocess.TimeoutExpired):
        return False


pytestmark = [pytest.mark.skipif(not _cluster_answers(),
                                 reason="no Slurm cluster answers (sinfo fails); start one on this machine "
                                        "with scripts/slurm_local.sh start"),
              needs_vdec]

INCLINE = ROOT / "verification" / "problems" / "RB-INCLINE-SLIP" / "scene.toml"
# Fields of results.json that differ between two executions of the same run.
TIMINGS = {"environment": None, "run": ("wall_seconds", "setup_seconds", "stage_seconds", "static_solve_seconds")}


def _without_timings(results):
    results = dict(results)
    results.pop("environment")
    results["run"] = {k: v for k, v in results["run"].items() if k not in TIMINGS["run"]}
    return results


@pytest.mark.requirements("REQ-QA-015")
def test_sweep_on_slurm_gives_the_local_sweeps_results(tmp_path):
    args = [str(INCLINE), "--set", "stop.time=0.05", "--set", "joint_material[0].friction=10.0,20.0,30.0",
            "--set", "solver.frac=0.1,0.2", "--output", "histories.slide.last", "--output", "blocks.top.centroid.1",
            "--vdec", VDEC]
    assert sweep_main([*args, "--out", str(tmp_path / "local")]) == 0
    assert sweep_main([*args, "--out", str(tmp_path / "slurm"), "--executor", "slurm"]) == 0
    tables = [json.loads((tmp_path / e / "table.json").read_text()) for e in ("local", "slurm")]
    assert tables[0] == tables[1] and len(tables[0]["rows"]) == 6
    for run in range(6):
        pair = [json.loads((tmp_path / e / "runs" / f"{run:04d}" / "results.json").read_text())
                for e in ("local", "slurm")]
        assert _without_timings(pair[0]) == _without_timings(pair[1])
    logs = list((tmp_path / "slurm" / "slurm").glob("batch-*/logs/*.out"))
    assert len(logs) == 6   # one array task a run


def _comparable(problem):
    problem = dict(problem)
    problem.pop("wall_seconds")
    problem["runs"] = [{k: v for k, v in run.items() if k not in ("wall_seconds", "folder", "command")}
                       for run in problem["runs"]]
    return problem


@pytest.mark.requirements("REQ-QA-015")
def test_verification_subset_on_slurm_gives_the_local_verdicts_and_numbers(tmp_path):
    summaries = []
    for executor in ("local", "slurm"):
        out = tmp_path / executor
        code = verify_main(["run", "--vdec", VDEC, "--problems", str(ROOT / "verification" / "problems"),
                            "--filter", "RB-INCLINE-SLIP", "DB-UNIAXIAL", "--level", "base", "--out", str(out),
                            "--executor", executor])
        assert code == 0
        summaries.append(json.loads((out / "summary.json").read_text()))
    local, slurm = ([_comparable(p) for p in s["problems"]] for s in summaries)
    assert [p["id"] for p in local] == ["DB-UNIAXIAL", "RB-INCLINE-SLIP"]
    assert slurm == local
    assert summaries[1]["counts"] == {"passed": 2, "failed": 0}
    assert any(Path(tmp_path / "slurm" / "slurm").glob("batch-*/results/0.json"))

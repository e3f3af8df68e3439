"""The executors of vdec_verify.executors without a cluster: the sbatch script, the gathering of
values, the retry of a lost task and the report of one lost twice, against stand-ins for sbatch,
sacct and scontrol on PATH that run the array tasks here, one after another."""
import json
import os
import stat
from pathlib import Path

import pytest
from scene_runs import ROOT, VDEC, needs_vdec

from vdec_sweep.errors import EXECUTOR
from vdec_sweep.sweep import main as sweep_main
from vdec_verify.__main__ import main as verify_main
from vdec_verify.executors import (ExecutorError, LocalExecutor, SlurmExecutor, SlurmOptions, array_ranges,
                                   job_script)
from vdec_verify.runner import discover, run_suite, select

FAKE_SBATCH = r'''#!/usr/bin/python3
import os, re, subprocess, sys
from pathlib import Path
state = Path(os.environ["FAKE_SLURM_DIR"])
args = sys.argv[1:]
with open(state / "sbatch-calls.txt", "a") as calls:
    calls.write(" ".join(args) + "\n")
if os.environ.get("FAKE_SBATCH_REFUSE"):
    sys.exit("sbatch: error: invalid partition specified: nope")
counter = state / "next-job"
job = int(counter.read_text()) if counter.exists() else 100
counter.write_text(str(job + 1))
print(job, flush=True)
indices = []
for part in next(a for a in args if a.startswith("--array=")).split("=", 1)[1].split(","):
    first, _, last = part.partition("-")
    indices += range(int(first), int(last or first) + 1)
lose = os.environ.get("FAKE_SLURM_LOSE", "")
lost = {int(i) for i in lose.split(",") if i} if job == 100 or os.environ.get("FAKE_SLURM_LOSE_ALWAYS") else set()
script = args[-1]
log = re.search(r"#SBATCH --output=(\S+)", Path(script).read_text()).group(1)
states, worst = [], 0
for i in indices:
    if i in lost:
        states.append(f"{job}_{i}|{os.environ.get('FAKE_SLURM_LOST_STATE', 'TIMEOUT')}")
        continue
    with open(log.replace("%A", str(job)).replace("%a", str(i)), "w") as out:
        code = subprocess.run(["sh", script], env={**os.environ, "SLURM_ARRAY_TASK_ID": str(i)},
                              stdout=out, stderr=subprocess.STDOUT).returncode
    states.append(f"{job}_{i}|{'COMPLETED' if code == 0 else 'FAILED'}")
    worst = max(worst, code)
(state / f"{job}.states").write_text("\n".join(states) + "\n")
sys.exit(worst)
'''
FAKE_SACCT = r'''#!/usr/bin/python3
import os, sys
from pathlib import Path
if os.environ.get("FAKE_SACCT_DISABLED"):
    sys.exit("Slurm accounting storage is disabled")
job = sys.argv[sys.argv.index("-j") + 1]
print((Path(os.environ["FAKE_SLURM_DIR"]) / f"{job}.states").read_text(), end="")
'''
FAKE_SCONTROL = r'''#!/usr/bin/python3
import os, sys
from pathlib import Path
job = sys.argv[-1]
for line in (Path(os.environ["FAKE_SLURM_DIR"]) / f"{job}.states").read_text().split():
    task, state = line.split("|")
    print(f"JobId=9{task.split('_')[1]} ArrayJobId={job} ArrayTaskId={task.split('_')[1]} JobState={state} Reason=None")
'''


@pytest.fixture
def fake_slurm(tmp_path, monkeypatch):
    """sbatch, sacct and scontrol stand-ins first on PATH; their record folder."""
    bin_dir, state = tmp_path / "fake-bin", tmp_path / "fake-slurm"
    bin_dir.mkdir()
    state.mkdir()
    for name, text in (("sbatch", FAKE_SBATCH), ("sacct", FAKE_SACCT), ("scontrol", FAKE_SCONTROL)):
        (bin_dir / name).write_text(text)
        (bin_dir / name).chmod(stat.S_IRWXU)
    monkeypatch.setenv("PATH", f"{bin_dir}{os.pathsep}{os.environ['PATH']}")
    monkeypatch.setenv("FAKE_SLURM_DIR", str(state))
    return state


def sbatch_calls(state):
    return (state / "sbatch-calls.txt").read_text().splitlines()


# json.loads is a module-level function an array task can import: each spec a JSON text, each
# value what it holds, and a spec that is not JSON a task that raises.
SPECS = ["[1, 2.5]", '{"a": 0.1}', "3", "null", '"text"']


@pytest.mark.requirements("REQ-QA-015")
def test_job_script_holds_the_slurm_options_and_runs_one_task_of_the_array(tmp_path):
    options = SlurmOptions(shared_dir=tmp_path, partition="short", account="rock", time_limit="10:00",
                           sbatch_args=["--qos=low"], job_name="vdec-sweep")
    script = job_script(tmp_path / "batch-1", options, python="/opt/py/bin/python3", python_path="/a:/b")
    lines = script.splitlines()
    assert lines[0] == "#!/bin/sh"
    for line in ("#SBATCH --partition=short", "#SBATCH --account=rock", "#SBATCH --time=10:00",
                 "#SBATCH --cpus-per-task=1", "#SBATCH --job-name=vdec-sweep",
                 f"#SBATCH --output={tmp_path / 'batch-1' / 'logs' / '%A_%a.out'}",
                 "export PYTHONPATH='/a:/b'", "export OMP_NUM_THREADS=1"):
        assert line in lines
    assert lines[-1] == (f"exec '/opt/py/bin/python3' -m vdec_verify.executors '{tmp_path / 'batch-1' / 'tasks.json'}' "
                         '"$SLURM_ARRAY_TASK_ID"')
    assert "--qos" not in script   # further arguments go on sbatch's command line
    plain = job_script(tmp_path, SlurmOptions(shared_dir=tmp_path), python="p", python_path="")
    assert "--partition" not in plain and "--account" not in plain and "--time" not in plain
    assert array_ranges([0, 1, 2, 3, 7, 9, 10]) == "0-3,7,9-10"
    assert array_ranges([5]) == "5"


@pytest.mark.requirements("REQ-QA-015")
def test_slurm_executor_gathers_the_values_the_local_pool_returns(tmp_path, fake_slurm):
    local = LocalExecutor(2).run(json.loads, SPECS)
    seen = []
    options = SlurmOptions(shared_dir=tmp_path / "shared", sbatch_args=["--qos=low"])
    slurm = SlurmExecutor(options).run(json.loads, SPECS, lambda i, o: seen.append(i))
    assert [o.value for o in slurm] == [o.value for o in local] == [[1, 2.5], {"a": 0.1}, 3, None, "text"]
    assert all(o.ok and o.attempts == 1 for o in slurm)
    assert sorted(seen) == list(range(len(SPECS)))
    [call] = sbatch_calls(fake_slurm)
    assert call.startswith("--parsable --wait --array=0-4 --qos=low ") and call.endswith("job.sh")


@pytest.mark.requirements("REQ-QA-015")
def test_a_lost_task_is_submitted_once_more(tmp_path, fake_slurm, monkeypatch):
    monkeypatch.setenv("FAKE_SLURM_LOSE", "1,3")
    outcomes = SlurmExecutor(SlurmOptions(shared_dir=tmp_path)).run(json.loads, SPECS)
    assert [o.value for o in outcomes] == [[1, 2.5], {"a": 0.1}, 3, None, "text"]
    assert [o.attempts for o in outcomes] == [1, 2, 1, 2, 1]
    assert [c.split()[2] for c in sbatch_calls(fake_slurm)] == ["--array=0-4", "--array=1,3"]


@pytest.mark.parametrize("accounting", ["sacct", "scontrol"])
@pytest.mark.requirements("REQ-QA-015")
def test_a_task_lost_twice_is_reported_with_its_slurm_state(tmp_path, fake_slurm, monkeypatch, accounting):
    monkeypatch.setenv("FAKE_SLURM_LOSE", "2")
    monkeypatch.setenv("FAKE_SLURM_LOSE_ALWAYS", "1")
    if accounting == "scontrol":   # a cluster without accounting: sacct fails, scontrol still knows
        monkeypatch.setenv("FAKE_SACCT_DISABLED", "1")
    outcomes = SlurmExecutor(SlurmOptions(shared_dir=tmp_path)).run(json.loads, [*SPECS[:2], "not json", "4"])
    assert [o.ok for o in outcomes] == [True, True, False, True]
    lost = outcomes[2]
    assert (lost.state, lost.attempts) == ("TIMEOUT", 2)
    assert "Slurm task 101_2 ended TIMEOUT without a result (attempt 2 of 2)" in lost.error
    assert len(sbatch_calls(fake_slurm)) == 2


@pytest.mark.requirements("REQ-QA-015")
def test_a_failing_task_is_retried_then_reported_with_its_log_and_a_cancelled_one_is_not_retried(
        tmp_path, fake_slurm, monkeypatch):
    outcomes = SlurmExecutor(SlurmOptions(shared_dir=tmp_path)).run(json.loads, ["1", "not json"])
    assert outcomes[0].value == 1
    assert (outcomes[1].ok, outcomes[1].state, outcomes[1].attempts) == (False, "FAILED", 2)
    assert "JSONDecodeError" in outcomes[1].error     # the traceback's last lines, from the task's log
    monkeypatch.setenv("FAKE_SLURM_LOSE", "0")
    monkeypatch.setenv("FAKE_SLURM_LOST_STATE", "CANCELLED by 0")
    (fake_slurm / "next-job").write_text("100")
    (fake_slurm / "sbatch-calls.txt").unlink()
    outcomes = SlurmExecutor(SlurmOptions(shared_dir=tmp_path)).run(json.loads, ["1", "2"])
    assert (outcomes[0].ok, outcomes[0].state, outcomes[0].attempts) == (False, "CANCELLED", 1)
    assert len(sbatch_calls(fake_slurm)) == 1


@pytest.mark.requirements("REQ-QA-015")
def test_a_task_function_a_slurm_task_cannot_import_is_refused(tmp_path):
    with pytest.raises(ExecutorError, match="module-level function"):
        SlurmExecutor(SlurmOptions(shared_dir=tmp_path)).run(lambda spec: spec, ["1"])


@needs_vdec
@pytest.mark.requirements("REQ-QA-015", "REQ-RUN-013")
def test_sbatch_refusing_the_array_is_the_sweeps_executor_error(tmp_path, fake_slurm, monkeypatch, capsys):
    monkeypatch.setenv("FAKE_SBATCH_REFUSE", "1")
    scene = ROOT / "verification" / "problems" / "RB-INCLINE-SLIP" / "scene.toml"
    code = sweep_main([str(scene), "--set", "stop.time=0.01", "--output", "run.cycles", "--out", str(tmp_path / "s"),
                       "--vdec", VDEC, "--executor", "slurm", "--slurm-partition", "nope"])
    assert code == EXECUTOR
    err = capsys.readouterr().err
    assert "--executor slurm: sbatch refused the job array" in err and "invalid partition specified" in err
    assert "--partition=nope" in (next((tmp_path / "s" / "slurm").glob("batch-*")) / "job.sh").read_text()


def _comparable(record):
    """A harness record without what differs between two executions of the same runs."""
    record = json.loads(json.dumps(record, default=str))
    record.pop("wall_seconds")
    for run in record["runs"]:
        for key in ("wall_seconds", "folder", "command"):
            run.pop(key)
    return record


@needs_vdec
@pytest.mark.requirements("REQ-QA-015")
def test_harness_runs_on_the_slurm_executor_as_on_the_pool(tmp_path, fake_slurm, monkeypatch, capsys):
    entries = select(discover(ROOT / "verification" / "problems"), "base", ["RB-INCLINE-SLIP"])
    local = run_suite(entries, Path(VDEC), tmp_path / "local", jobs=1, progress=None, level="base")
    slurm = run_suite(entries, Path(VDEC), tmp_path / "slurm", progress=None, level="base",
                      executor=SlurmExecutor(SlurmOptions(shared_dir=tmp_path / "shared")))
    assert local[0]["status"] == "pass"
    assert [_comparable(r) for r in slurm] == [_comparable(r) for r in local]
    assert len(sbatch_calls(fake_slurm)) == 1
    monkeypatch.setenv("FAKE_SBATCH_REFUSE", "1")
    code = verify_main(["run", "--vdec", VDEC, "--problems", str(ROOT / "verification" / "problems"),
                        "--filter", "RB-INCLINE-SLIP", "--level", "base", "--out", str(tmp_path / "cli"),
                        "--executor", "slurm", "--slurm-account", "rock"])
    assert code == 2
    assert "--executor slurm: sbatch refused the job array" in capsys.readouterr().err
    assert "#SBATCH --account=rock" in next((tmp_path / "cli" / "slurm").glob("batch-*/job.sh")).read_text()

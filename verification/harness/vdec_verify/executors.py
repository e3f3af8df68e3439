"""Where a batch of independent tasks runs: on this machine, or as one Slurm job array.

Both the verification harness (its solver runs) and `vdec sweep` (the runs of a sweep) hand
their work to an executor as a task function and a list of specs:

    executor.run(function, specs, progress) -> [TaskOutcome, ...]   (in the order of specs)

`function(spec)` does one task and returns its value; spec and value are JSON-able (dicts of
strings, numbers, lists), and function is a module-level function, so that a Slurm task on
another machine can import it by name and call it on its spec. A function that raises has no
value: its outcome says why.

- LocalExecutor(jobs): a pool of `jobs` threads in this process (the tasks start solver
  processes, so threads suffice).
- SlurmExecutor(SlurmOptions): writes the specs to tasks.json in a new folder under the shared
  directory, and submits one job array (`sbatch --array=0-(N-1) --wait`), one array task per
  spec. Each task runs `python -m vdec_verify.executors TASKS.JSON INDEX`, which calls the
  function and writes its value to results/INDEX.json in that folder. When the array has ended,
  the values are gathered from there. A task without a value (failed, timed out, node lost) is
  looked up in Slurm (sacct, or scontrol when the cluster keeps no accounting), and the missing
  tasks are submitted once more as a second array; those that fail again, and those cancelled
  (scancel: someone meant them to stop), are reported with their Slurm state and the tail of
  their log. Slurm alone decides where and when tasks run. sbatch runs in the caller's working
  directory, so relative paths in specs hold when the nodes mount it at the same place.
"""
import argparse
import importlib
import json
import os
import socket
import subprocess
import sys
import tempfile
import time
import traceback
from concurrent.futures import ThreadPoolExecutor, as_completed
from dataclasses import dataclass, field
from pathlib import Path

# Lines of a failed task's Slurm log quoted in its outcome.
LOG_TAIL_LINES = 10


class ExecutorError(RuntimeError):
    """The executor itself cannot run the batch (sbatch refused it, no Slurm on PATH)."""


@dataclass
class TaskOutcome:
    value: object = None          # what the function returned; None when the task did not finish
    ok: bool = True               # False: no value (the function raised, or the Slurm task failed)
    state: str = "COMPLETED"      # Slurm's state of the task's last attempt; local: COMPLETED or FAILED
    error: str = ""               # why there is no value
    attempts: int = 1


def function_name(function):
    """"module:qualname", by which a Slurm task imports the function."""
    if function.__module__ == "__main__" or "<locals>" in function.__qualname__:
        raise ExecutorError(f"{function.__qualname__} cannot be imported by a Slurm task: "
                            "it must be a module-level function of an importable module")
    return f"{function.__module__}:{function.__qualname__}"


def import_function(name):
    module, _, qualname = name.partition(":")
    target = importlib.import_module(module)
    for part in qualname.split("."):
        target = getattr(target, part)
    return target


def _failure(exception):
    return f"{type(exception).__name__}: {exception}"


class LocalExecutor:
    name = "local"

    def __init__(self, jobs=2):
        self.jobs = max(1, int(jobs))

    def run(self, function, specs, progress=None):
        outcomes = [None] * len(specs)

        def call(spec):
            try:
                return TaskOutcome(value=function(spec))
            except Exception as e:  # a broken task is reported, the others go on
                return TaskOutcome(ok=False, state="FAILED", error=_failure(e))

        with ThreadPoolExecutor(max_workers=self.jobs) as pool:
            futures = {pool.submit(call, spec): index for index, spec in enumerate(specs)}
            for future in as_completed(futures):
                index = futures[future]
                outcomes[index] = future.result()
                if progress:
                    progress(index, outcomes[index])
        return outcomes


@dataclass
class SlurmOptions:
    shared_dir: Path                  # seen by the compute nodes: task lists, logs, values
    partition: str = ""
    account: str = ""
    time_limit: str = ""              # Slurm's --time, e.g. "30:00"; "" the partition's default
    sbatch_args: list = field(default_factory=list)   # further sbatch arguments, as given
    job_name: str = "vdec"


def _python_path():
    """PYTHONPATH for the tasks: this process's own import path (its folders), so that a task
    imports what the submitting process would: vdec_verify, the task's package and what they
    import (the closed forms of verification/analytic, found through a folder a test or a
    script put on sys.path rather than on PYTHONPATH), then the caller's own PYTHONPATH."""
    here = [str(Path(p).resolve()) for p in sys.path if p and Path(p).is_dir()]
    inherited = [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]
    return os.pathsep.join(dict.fromkeys(here + inherited))


def _shell_quote(text):
    return "'" + str(text).replace("'", "'\\''") + "'"


def job_script(batch, options, python=sys.executable, python_path=None):
    """The sbatch script of a batch folder: each array task calls the task function on its spec."""
    lines = ["#!/bin/sh",
             f"#SBATCH --job-name={options.job_name}",
             f"#SBATCH --output={batch / 'logs' / '%A_%a.out'}",
             "#SBATCH --cpus-per-task=1"]
    if options.partition:
        lines.append(f"#SBATCH --partition={options.partition}")
    if options.account:
        lines.append(f"#SBATCH --account={options.account}")
    if options.time_limit:
        lines.append(f"#SBATCH --time={options.time_limit}")
    lines += ["# One CPU a task: the solver's zone loops keep to one thread.",
              "export OMP_NUM_THREADS=1",
              f"export PYTHONPATH={_shell_quote(python_path if python_path is not None else _python_path())}",
              f"exec {_shell_quote(python)} -m vdec_verify.executors {_shell_quote(batch / 'tasks.json')} "
              '"$SLURM_ARRAY_TASK_ID"']
    return "\n".join(lines) + "\n"


def array_ranges(indices):
    """sbatch's --array text for sorted indices: runs of consecutive ones as ranges, "0-4,7,9-10"."""
    parts, start = [], None
    for k, index in enumerate(indices):
        if start is None:
            start = index
        if k + 1 == len(indices) or indices[k + 1] != index + 1:
            parts.append(str(start) if start == index else f"{start}-{index}")
            start = None
    return ",".join(parts)


def _command(args):
    try:
        return subprocess.run(args, capture_output=True, text=True, stdin=subprocess.DEVNULL)
    except OSError as e:
        return subprocess.CompletedProcess(args, 127, "", str(e))


def task_states(job_id):
    """{array index: state} of a job array's tasks: from sacct, or from scontrol when the
    cluster keeps no accounting (scontrol remembers finished jobs for MinJobAge seconds)."""
    done = _command(["sacct", "-j", job_id, "-X", "-n", "-P", "-o", "JobID,State"])
    states = {}
    if done.returncode == 0:
        for line in done.stdout.splitlines():
            job, _, state = line.partition("|")
            array_job, _, index = job.partition("_")
            if array_job == job_id and index.isdigit():
                # "CANCELLED by 0" names who cancelled; the state is the first word
                states[int(index)] = state.split()[0] if state.strip() else "UNKNOWN"
        if states:
            return states
    done = _command(["scontrol", "show", "job", "-o", job_id])
    if done.returncode == 0:
        for line in done.stdout.splitlines():
            fields = dict(item.partition("=")[::2] for item in line.split())
            if fields.get("ArrayJobId") == job_id and fields.get("ArrayTaskId", "").isdigit():
                states[int(fields["ArrayTaskId"])] = fields.get("JobState", "UNKNOWN")
    return states


def _log_tail(path):
    try:
        lines = path.read_text(errors="replace").splitlines()
    except OSError:
        return "(no log)"
    return "\n".join(lines[-LOG_TAIL_LINES:]) or "(empty log)"


class SlurmExecutor:
    name = "slurm"

    def __init__(self, options):
        self.options = options

    def _submit(self, batch, indices):
        """Submits the array tasks `indices` of the batch and waits for them all to end; returns
        the job id."""
        command = ["sbatch", "--parsable", "--wait", f"--array={array_ranges(indices)}",
                   *self.options.sbatch_args, str(batch / "job.sh")]
        try:
            process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                       stdin=subprocess.DEVNULL)
        except OSError as e:
            raise ExecutorError(f"cannot run sbatch: {e}") from e
        job_id = process.stdout.readline().strip().split(";")[0]
        try:
            _, stderr = process.communicate()
        except KeyboardInterrupt:
            if job_id:
                _command(["scancel", job_id])
            raise
        if not job_id.isdigit():
            raise ExecutorError(f"sbatch refused the job array ({' '.join(command)}): "
                                f"{stderr.strip() or 'exit code ' + str(process.returncode)}")
        return job_id

    def run(self, function, specs, progress=None):
        name = function_name(function)
        if not specs:
            return []
        shared = Path(self.options.shared_dir).resolve()
        shared.mkdir(parents=True, exist_ok=True)
        batch = Path(tempfile.mkdtemp(prefix="batch-", dir=shared))
        (batch / "logs").mkdir()
        (batch / "results").mkdir()
        (batch / "tasks.json").write_text(json.dumps({"function": name, "tasks": specs}))
        (batch / "job.sh").write_text(job_script(batch, self.options))
        outcomes = [None] * len(specs)
        pending = list(range(len(specs)))
        for attempt in (1, 2):
            job_id = self._submit(batch, pending)
            states = None
            missing = []
            for index in pending:
                value_file = batch / "results" / f"{index}.json"
                if value_file.is_file():
                    outcomes[index] = TaskOutcome(value=json.loads(value_file.read_text())["value"], attempts=attempt)
                    if progress:
                        progress(index, outcomes[index])
                    continue
                if states is None:
                    states = task_states(job_id)
                state = states.get(index, "UNKNOWN")
                log = batch / "logs" / f"{job_id}_{index}.out"
                outcomes[index] = TaskOutcome(ok=False, state=state, attempts=attempt,
                                              error=f"Slurm task {job_id}_{index} ended {state} without a result "
                                                    f"(attempt {attempt} of 2); log {log}:\n{_log_tail(log)}")
                if not state.startswith("CANCELLED"):   # cancelled by someone: not ours to redo
                    missing.append(index)
            pending = missing
            if not pending:
                break
        if progress:
            for index, outcome in enumerate(outcomes):
                if not outcome.ok:
                    progress(index, outcome)
        return outcomes


def make_executor(kind, jobs=2, slurm=None):
    """The executor named by --executor: "local" (a pool of jobs) or "slurm" (SlurmOptions)."""
    if kind == "local":
        return LocalExecutor(jobs)
    if kind == "slurm":
        return SlurmExecutor(slurm)
    raise ValueError(f"unknown executor {kind!r}: local or slurm")


def add_executor_options(parser, shared_dir_default):
    """The executor's command-line options, the same for `vdec sweep` and `vdec_verify run`."""
    group = parser.add_argument_group("executor")
    group.add_argument("--executor", choices=("local", "slurm"), default=None,
                       help="where the runs go: local (a pool of --jobs processes on this machine, the default) "
                            "or slurm (one job array, one task a run)")
    group.add_argument("--slurm-partition", default=None, metavar="NAME", help="sbatch --partition")
    group.add_argument("--slurm-account", default=None, metavar="NAME", help="sbatch --account")
    group.add_argument("--slurm-time", default=None, metavar="LIMIT",
                       help="sbatch --time for each task, e.g. 30:00 (default: the partition's)")
    group.add_argument("--slurm-shared-dir", default=None, metavar="DIR",
                       help=f"folder the compute nodes see, for task lists, logs and values (default {shared_dir_default})")
    group.add_argument("--sbatch-arg", dest="sbatch_args", action="append", default=None, metavar="ARG",
                       help="a further argument to sbatch, e.g. --sbatch-arg=--qos=short (repeatable)")
    return group


def slurm_options_from(args, shared_dir_default, base=None):
    """SlurmOptions from the parsed options of add_executor_options, over `base` (e.g. a sweep
    file's [executor] table) where an option was not given."""
    base = base or SlurmOptions(shared_dir=shared_dir_default)

    def pick(value, fallback):
        return fallback if value is None else value

    return SlurmOptions(shared_dir=Path(pick(args.slurm_shared_dir, base.shared_dir)),
                        partition=pick(args.slurm_partition, base.partition),
                        account=pick(args.slurm_account, base.account),
                        time_limit=pick(args.slurm_time, base.time_limit),
                        sbatch_args=list(pick(args.sbatch_args, base.sbatch_args)),
                        job_name=base.job_name)


def run_task(tasks_file, index):
    """One array task: calls the batch's function on spec `index` and writes the value, under a
    temporary name renamed into place, so that a value file is always whole."""
    batch = json.loads(Path(tasks_file).read_text())
    function = import_function(batch["function"])
    start = time.monotonic()
    value = function(batch["tasks"][index])
    target = Path(tasks_file).parent / "results" / f"{index}.json"
    temporary = target.with_name(f".{index}.json.tmp-{os.getpid()}")
    temporary.write_text(json.dumps({"value": value, "host": socket.gethostname(),
                                     "seconds": time.monotonic() - start}))
    os.replace(temporary, target)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m vdec_verify.executors",
                                     description="run one task of a Slurm job array (called by the job script)")
    parser.add_argument("tasks", help="the batch's tasks.json")
    parser.add_argument("index", type=int, help="the array task's index ($SLURM_ARRAY_TASK_ID)")
    args = parser.parse_args(argv)
    try:
        run_task(args.tasks, args.index)
    except Exception:
        traceback.print_exc()
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

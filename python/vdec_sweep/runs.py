"""One run of a sweep, as an executor's task (vdec_verify.executors): vdec run into the run's
folder, which keeps results.json, command.txt, stdout.txt and stderr.txt."""
import os
import shlex
import subprocess
import time
from pathlib import Path

# Lines of a failed run's standard error kept in the sweep's report.
STDERR_TAIL_LINES = 5
# Runs side by side on the cores keep to one thread each (as the verification harness's), unless
# the caller says otherwise: threads of two runs contending for two cores only slow both.
RUN_ENVIRONMENT = {**os.environ, "OMP_NUM_THREADS": os.environ.get("OMP_NUM_THREADS", "1")}


def run_spec(vdec, scene, folder, overrides, timeout):
    """The task spec of a run (JSON-able, for a Slurm task as much as for the local pool)."""
    return {"vdec": str(vdec), "scene": str(scene), "folder": str(folder), "overrides": list(overrides),
            "timeout": timeout}


def stderr_tail(text):
    return "\n".join(text.rstrip().splitlines()[-STDERR_TAIL_LINES:])


def run_one(spec):
    """Runs vdec on one spec; returns exit_code (None when it did not finish), wall_seconds and
    the tail of standard error, with the reason when it did not finish."""
    folder = Path(spec["folder"])
    folder.mkdir(parents=True, exist_ok=True)
    command = [spec["vdec"], "run", spec["scene"], "--out", str(folder)] + [f"--set={o}" for o in spec["overrides"]]
    (folder / "command.txt").write_text(shlex.join(command) + "\n")
    start = time.monotonic()
    exit_code, stdout, stderr, reason = None, "", "", ""
    try:
        done = subprocess.run(command, capture_output=True, text=True, stdin=subprocess.DEVNULL,
                              timeout=spec["timeout"], env=RUN_ENVIRONMENT)
        exit_code, stdout, stderr = done.returncode, done.stdout, done.stderr
    except subprocess.TimeoutExpired as e:
        stdout, stderr = _text(e.stdout), _text(e.stderr)
        reason = f"timed out after {spec['timeout']:g} s (--timeout) and was stopped"
    except OSError as e:
        reason = f"cannot start {spec['vdec']}: {e}"
    wall = time.monotonic() - start
    (folder / "stdout.txt").write_text(stdout)
    (folder / "stderr.txt").write_text(stderr)
    return {"exit_code": exit_code, "wall_seconds": wall, "stderr_tail": stderr_tail(stderr), "reason": reason}


def _text(stream):
    return stream.decode(errors="replace") if isinstance(stream, bytes) else (stream or "")

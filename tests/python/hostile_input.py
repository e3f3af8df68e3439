"""Hostile input for vdec: what every run must do with any scene, and the tools to run many.

A run of vdec must end with an exit code the manual documents (the table in
docs/user-manual/command-line.md, less 1, the internal error), never with a signal, within a
time limit; a run that ends 0 must have written a results.json that parses and holds no null
number (JSON's null is what a NaN or an infinity becomes) outside the fields documented as
null. Used by test_mutated_scenes.py and test_fuzz_regressions.py.

KNOWN_FAILURES lists the cases that fail today, by patterns of test ids, with the cause; the
tests mark them xfail(strict=True), so that a case that starts to pass fails until its pattern
is deleted.
"""
import json
import os
import re
import shutil
import signal
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PROBLEMS = ROOT / "verification" / "problems"
COMMAND_LINE_DOC = ROOT / "docs" / "user-manual" / "command-line.md"
INTERNAL_ERROR = 1
RUN_TIMEOUT_SECONDS = 60
# Fields results.json documents as null (docs/user-manual/outputs.md).
DOCUMENTED_NULLS = {("run", "static_solve_seconds"), ("run", "static_solve_residual")}

# (pattern, cause): a case whose id (BASE:key.path:mutation for a mutated scene, the file name
# for a fuzz regression input) matches a pattern in full is expected to fail, for that cause.
# Delete a pattern when its fix lands: its cases then pass, and strict xfail fails until then.
_UNCHECKED = "issue 10, unchecked input: a non-finite number in a point or an array is not an input error"
_RANGE_BOUND = ("issue 10, unchecked input: an infinite bound of a [[boundary]] range (x, y, r) is taken "
                "as no bound, a NaN one as selecting nothing, instead of an input error")
KNOWN_FAILURES = [
]


def known_failure(case_id):
    """The cause of the first KNOWN_FAILURES pattern that matches case_id, or None."""
    for pattern, cause in KNOWN_FAILURES:
        if re.fullmatch(pattern, case_id):
            return cause
    return None


def known_failure_marks(pytest, case_id):
    """The xfail mark of a case KNOWN_FAILURES expects to fail, else none."""
    cause = known_failure(case_id)
    return [pytest.mark.xfail(reason=cause, strict=True)] if cause else []


def documented_exit_codes():
    """The codes of the manual's exit-code table, 1 (internal error) left out."""
    text = COMMAND_LINE_DOC.read_text()
    section = text.split("## Exit codes", 1)[1].split("\n## ", 1)[0]
    codes = {int(m) for m in re.findall(r"^\| (\d+) \|", section, flags=re.MULTILINE)}
    assert 0 in codes and 3 in codes, f"no exit-code table found in {COMMAND_LINE_DOC}"
    return codes - {INTERNAL_ERROR}


def run_vdec(executable, scene, out_dir, overrides=(), timeout=RUN_TIMEOUT_SECONDS):
    """Runs `vdec run` on one thread; (exit code, stderr), exit code None on a timeout."""
    command = [str(executable), "run", str(scene), "--out", str(out_dir)]
    for override in overrides:
        command += ["--set", override]
    env = dict(os.environ, OMP_NUM_THREADS="1")
    try:
        proc = subprocess.run(command, capture_output=True, text=True, errors="replace", timeout=timeout, env=env)
    except subprocess.TimeoutExpired:
        return None, f"no end within {timeout} s"
    return proc.returncode, proc.stderr


def _nulls(node, path=()):
    if node is None:
        if path not in DOCUMENTED_NULLS:
            yield ".".join(str(p) for p in path)
    elif isinstance(node, dict):
        for key, value in node.items():
            yield from _nulls(value, path + (key,))
    elif isinstance(node, list):
        for index, value in enumerate(node):
            yield from _nulls(value, path + (index,))


def _reject_constant(token):
    raise ValueError(f"{token} is not JSON")


def run_verdict(code, stderr, out_dir, documented):
    """'' when the run ended as every run must; else what went wrong."""
    last = stderr.strip().splitlines()[-1] if stderr.strip() else "(no message)"
    if code is None:
        return stderr
    if code < 0:
        return f"killed by {signal.Signals(-code).name}: {last}"
    if code == INTERNAL_ERROR:
        return f"internal error, exit code 1: {last}"
    if code not in documented:
        return f"exit code {code}, not in the manual's table: {last}"
    if code != 0:
        return ""
    results = Path(out_dir) / "results.json"
    if not results.is_file():
        return "exit code 0 without results.json"
    try:
        data = json.loads(results.read_text(), parse_constant=_reject_constant)
    except ValueError as e:
        return f"exit code 0, results.json does not parse: {e}"
    nulls = list(_nulls(data))
    if nulls:
        return f"exit code 0, results.json holds null numbers at {', '.join(nulls[:5])}"
    return ""


def make_scene_sandbox(folder):
    """A folder `folder/scene` in which a scene may name the data files of the verification
    problems as their own scenes do: "unloading.csv" (copied beside it) or
    "../DB-KIRSCH/far_field.csv" (each problem's files under its own name). scripts/fuzz.sh
    builds the same layout for the fuzzer."""
    scene_dir = Path(folder) / "scene"
    scene_dir.mkdir(parents=True, exist_ok=True)
    for data in sorted(PROBLEMS.glob("*/*")):
        if data.suffix in (".toml", ".py") or not data.is_file():
            continue
        mirror = Path(folder) / data.parent.name
        mirror.mkdir(exist_ok=True)
        shutil.copy(data, mirror / data.name)
        if not (scene_dir / data.name).exists():
            shutil.copy(data, scene_dir / data.name)
    return scene_dir

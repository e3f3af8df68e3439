"""Replays every input the scene-reader fuzzer kept (tests/fuzz/regressions; scripts/fuzz.sh
adds the ones that fail), twice: through the fuzz target's own oracle in an ordinary build
(vdec_fuzz_replay: the reader throws a documented error or returns a model whose numbers are
all finite), and through vdec itself for a few cycles (a documented exit code, never a signal
or an internal error, and at exit 0 a results.json without null numbers). Each input is read
from a folder beside copies of the problems' data files, as the fuzzer read it. Known failures
are xfail by hostile_input.KNOWN_FAILURES, by case id FILE:reader and FILE:run.
"""
import os
import shutil
import subprocess

import pytest

import hostile_input

REGRESSIONS = hostile_input.ROOT / "tests" / "fuzz" / "regressions"
CYCLES = 20
# Any scene the fuzzer makes reads in well under a second, and 20 cycles take as little; an input
# kept because it hung the fuzzer's reader (20 s there, with sanitizers) needs no longer to fail.
TIMEOUT_SECONDS = 10
INPUTS = sorted(p for p in REGRESSIONS.iterdir() if p.is_file() and not p.name.startswith("."))


def _cases(kind):
    return [pytest.param(p, id=f"{p.name}:{kind}", marks=hostile_input.known_failure_marks(pytest, f"{p.name}:{kind}"))
            for p in INPUTS]


@pytest.fixture(scope="module")
def sandbox(tmp_path_factory):
    return hostile_input.make_scene_sandbox(tmp_path_factory.mktemp("fuzz-sandbox"))


def _placed(path, sandbox):
    scene = sandbox / (path.name if path.suffix == ".toml" else f"{path.name}.toml")
    shutil.copy(path, scene)
    return scene


@pytest.mark.requirements("REQ-QA-007")
@pytest.mark.parametrize("path", _cases("reader"))
def test_fuzz_input_reads_as_documented(path, sandbox):
    try:
        proc = subprocess.run([os.environ["VDEC_FUZZ_REPLAY"], str(_placed(path, sandbox))],
                              capture_output=True, text=True, errors="replace", timeout=TIMEOUT_SECONDS)
    except subprocess.TimeoutExpired:
        pytest.fail(f"{path.name}: the reader did not finish within {TIMEOUT_SECONDS} s")
    assert proc.returncode == 0, f"{path.name}: exit code {proc.returncode}: {proc.stderr.strip()}"


@pytest.mark.requirements("REQ-QA-007")
@pytest.mark.parametrize("path", _cases("run"))
def test_fuzz_input_runs_to_a_documented_exit_code(path, sandbox, tmp_path):
    code, stderr = hostile_input.run_vdec(os.environ["VDEC_EXECUTABLE"], _placed(path, sandbox), tmp_path / "out",
                                          [f"stop.cycles={CYCLES}"], timeout=TIMEOUT_SECONDS)
    verdict = hostile_input.run_verdict(code, stderr, tmp_path / "out", hostile_input.documented_exit_codes())
    assert verdict == "", f"{path.name}: {verdict}"


@pytest.mark.requirements("REQ-QA-007")
def test_the_corpus_is_not_empty_and_holds_only_files():
    assert INPUTS, f"{REGRESSIONS} holds no input: its inputs are regression tests, never deleted"
    assert all(p.is_file() for p in REGRESSIONS.iterdir())

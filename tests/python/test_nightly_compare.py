"""`vdec_verify compare` (REQ-QA-012): one case per class of change, built from the hand-made
fixture tests/python/fixtures/compare/baseline-summary.json (three problems: A-STEADY with a
scalar, an L2 and an upper-bound check; B-SLOW, 2 s and 1000 cycles; C-GONE), changed in the
test to make the current run."""
import copy
import json
import os
from pathlib import Path

import pytest

from vdec_verify.__main__ import main
from vdec_verify.compare import CheckFactors, RepeatNeeded, SuiteRepeater, Thresholds, compare, error_beyond
from vdec_verify.history import entry_of_summary
from problem_files import write_problem

FIXTURE = Path(__file__).parent / "fixtures" / "compare" / "baseline-summary.json"
REQ = pytest.mark.requirements("REQ-QA-012")
NO_REPEAT = Thresholds(repeats=0)


@pytest.fixture
def base():
    return json.loads(FIXTURE.read_text())


def problem(summary, problem_id):
    return next(p for p in summary["problems"] if p["id"] == problem_id)


def changes_of(base, current, thresholds=NO_REPEAT, **kwargs):
    return compare(entry_of_summary(base), entry_of_summary(current), thresholds, **kwargs)


def kinds(changes):
    return sorted((c.kind, c.problem, c.regression) for c in changes)


@REQ
def test_the_same_run_has_no_change(base):
    assert changes_of(base, copy.deepcopy(base)) == []


@REQ
def test_a_status_that_is_no_longer_pass_is_a_regression_and_the_failing_check_is_named(base):
    current = copy.deepcopy(base)
    problem(current, "B-SLOW")["status"] = "fail"
    problem(current, "B-SLOW")["metrics"][0].update({"pass": False, "error": 2e-2})
    changes = changes_of(base, current)
    assert ("status", "B-SLOW", True) in kinds(changes)
    check = next(c for c in changes if c.kind == "check")
    assert (check.check, check.regression) == ("peak stress (relative)", True)
    # The way back is a change, not a regression.
    assert all(not c.regression for c in changes_of(current, base))


@REQ
@pytest.mark.parametrize("index, error, flagged", [
    (1, 8.1e-3, True),     # L2: 4e-3 -> 8.1e-3, beyond twice
    (1, 7.9e-3, False),    # within twice
    (0, 3e-7, True),       # scalar 1e-7 -> 3e-7 against 1e-5: above the floor 1e-7
    (0, 9e-8, False),      # shrank
    (2, 0.01, True),       # an upper bound met with room (-0.5) now exceeded (above the floor 0)
    (2, -0.1, False),      # closer to the bound, still below it
])
def test_an_error_grown_beyond_the_factor_is_a_regression(base, index, error, flagged):
    current = copy.deepcopy(base)
    problem(current, "A-STEADY")["metrics"][index]["error"] = error
    changes = [c for c in changes_of(base, current) if c.kind == "error"]
    assert bool(changes) == flagged
    if flagged:
        assert changes[0].regression and changes[0].problem == "A-STEADY"
        assert changes[0].baseline == problem(base, "A-STEADY")["metrics"][index]["error"]


@REQ
def test_round_off_growth_below_the_floor_is_not_a_regression(base):
    """1e-12 -> 3e-12 against a tolerance of 1e-5 is round-off moving: below 1 % of the tolerance."""
    problem(base, "A-STEADY")["metrics"][0]["error"] = 1e-12
    current = copy.deepcopy(base)
    problem(current, "A-STEADY")["metrics"][0]["error"] = 3e-12
    assert changes_of(base, current) == []
    assert error_beyond(1e-12, 3e-12, 1e-5, 2.0, 0.0)        # without the floor it would be
    # An upper bound met with room counts as an error of zero: nearer the bound is not growth.
    assert not error_beyond(-0.5, -0.1, 0.0, 2.0, 0.0)


@REQ
def test_a_per_check_factor_in_problem_toml_overrides_the_default(base, tmp_path):
    current = copy.deepcopy(base)
    problem(current, "A-STEADY")["metrics"][1]["error"] = 1.5e-2 * 0.6     # x2.25
    text = (Path(__file__).parent / "fixtures" / "compare" / "A-STEADY.toml").read_text()
    write_problem(tmp_path, text, folder="A-STEADY")
    factors = CheckFactors(tmp_path, NO_REPEAT.error_factor)
    assert [c.kind for c in changes_of(base, current, factors=factors)] == []    # its factor is 3
    assert factors.factor("A-STEADY", 2) == 3.0 and factors.factor("A-STEADY", 1) == 2.0
    broken = tmp_path / "broken"
    write_problem(broken, text.replace("regression_factor = 3.0", "regression_factor = 0.5"), folder="A-STEADY")
    factors = CheckFactors(broken, NO_REPEAT.error_factor)
    assert [c.kind for c in changes_of(base, current, factors=factors)] == ["error"]
    assert "check[1].regression_factor" in factors.notes[0] and "problem.toml" in factors.notes[0]


class Repeats:
    """A stand-in for the runner: the wall seconds the repetitions take."""

    def __init__(self, seconds):
        self.seconds, self.asked = seconds, []

    def __call__(self, problem_id, count):
        self.asked.append((problem_id, count))
        return self.seconds[:count]


@REQ
def test_a_slower_run_is_repeated_and_flagged_only_when_the_fastest_is_still_slow(base):
    current = copy.deepcopy(base)
    problem(current, "B-SLOW")["wall_seconds"] = 3.5
    noise = Repeats([2.1, 3.6])
    changes = changes_of(base, current, Thresholds(repeats=2), repeat=noise)
    assert noise.asked == [("B-SLOW", 2)]
    assert [(c.kind, c.regression, c.current) for c in changes] == [("time", False, 2.1)]
    slow = Repeats([3.4, 3.3])
    assert [(c.kind, c.regression, c.current) for c in changes_of(base, current, Thresholds(repeats=2), repeat=slow)] \
        == [("time", True, 3.3)]
    # Without repeats, the recorded time decides; with repeats and no runner, compare says so.
    assert [c.regression for c in changes_of(base, current, NO_REPEAT)] == [True]
    with pytest.raises(RepeatNeeded, match="B-SLOW"):
        changes_of(base, current, Thresholds(repeats=2))


@REQ
def test_a_short_run_slower_by_less_than_the_time_floor_is_noise(base):
    current = copy.deepcopy(base)
    problem(current, "C-GONE")["wall_seconds"] = 0.3     # x3, but 0.2 s
    assert changes_of(base, current) == []
    problem(current, "C-GONE")["wall_seconds"] = 0.4     # x4 and 0.3 s
    assert kinds(changes_of(base, current)) == [("time", "C-GONE", True)]


@REQ
def test_more_cycles_beyond_the_factor_is_a_regression(base):
    current = copy.deepcopy(base)
    problem(current, "B-SLOW")["cycles"] = 1400
    assert changes_of(base, current) == []
    problem(current, "B-SLOW")["cycles"] = 1600
    assert kinds(changes_of(base, current)) == [("cycles", "B-SLOW", True)]


@REQ
def test_problems_added_and_removed(base):
    current = copy.deepcopy(base)
    gone = problem(current, "C-GONE")
    current["problems"].remove(gone)
    current["problems"].append(dict(copy.deepcopy(gone), id="D-NEW"))
    assert kinds(changes_of(base, current)) == [("added", "D-NEW", False), ("removed", "C-GONE", True)]
    # A filtered run leaves out what its filter does not select; a run of another level differs by design.
    current["harness"]["filter"] = ["A-STEADY", "B-*", "D-NEW"]
    assert kinds(changes_of(base, current)) == [("added", "D-NEW", False)]
    current["harness"]["filter"] = ["GONE"]
    assert ("removed", "C-GONE", True) in kinds(changes_of(base, current))
    current["harness"].update(filter=[], level="full")
    assert ("removed", "C-GONE", False) in kinds(changes_of(base, current))


@REQ
def test_software_harness_and_input_changes_are_reported_not_flagged(base):
    current = copy.deepcopy(base)
    current["software"]["git_commit"] = "2" * 40
    current["harness"]["vdec"]["sha256"] = "9" * 64
    current["harness"]["files"]["verification/harness/vdec_verify/runner.py"] = "8" * 64
    for p in current["problems"]:
        if "verification/analytic/elastic.py" in p["inputs"]:
            p["inputs"]["verification/analytic/elastic.py"] = "7" * 64
    changes = {c.kind: c for c in changes_of(base, current)}
    assert sorted(changes) == ["harness", "inputs", "software"]
    assert not any(c.regression for c in changes.values())
    assert set(changes["software"].data["fields"]) == {"git_commit", "vdec binary sha256"}
    assert changes["inputs"].data == {"files": {"verification/analytic/elastic.py": ["e" * 64, "7" * 64]},
                                      "problems": ["A-STEADY", "B-SLOW"]}
    assert list(changes["harness"].data["files"]) == ["verification/harness/vdec_verify/runner.py"]


@REQ
def test_the_command_prints_text_or_json_and_exits_1_on_a_regression(base, tmp_path, capsys):
    current = copy.deepcopy(base)
    problem(current, "A-STEADY")["metrics"][1]["error"] = 9e-3
    (tmp_path / "current.json").write_text(json.dumps(current))
    assert main(["compare", str(FIXTURE), str(FIXTURE), "--no-repeat"]) == 0
    assert capsys.readouterr().out.strip().endswith("no change")
    assert main(["compare", str(FIXTURE), str(tmp_path / "current.json"), "--no-repeat"]) == 1
    text = capsys.readouterr().out
    assert "REGRESSION error" in text and "A-STEADY check 'velocity history (relative L2)'" in text
    assert main(["compare", str(FIXTURE), str(tmp_path / "current.json"), "--no-repeat", "--json",
                 "--error-factor", "3"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["regressions"] == 0 and report["thresholds"]["error_factor"] == 3.0


@REQ
@pytest.mark.parametrize("arguments, phrase", [
    (["MISSING.json", "FIXTURE"], "MISSING.json: no such file"),
    (["FIXTURE", "BAD"], "BAD: not readable JSON"),
    (["FIXTURE", "OTHER"], "OTHER: schema 'vdec.results/1': neither a summary.json"),
    (["FIXTURE", "FIXTURE", "--error-factor", "0.5"], "--error-factor 0.5: must be a finite number >= 1"),
    (["FIXTURE", "SLOW"], "B-SLOW ran slower than the time factor; repeating them needs the vdec executable"),
    (["FIXTURE", "FIXTURE", "--vdec", "NOWHERE"], "--vdec NOWHERE: no such file"),
])
def test_bad_input_exits_2_naming_the_file_or_option(base, tmp_path, capsys, arguments, phrase):
    (tmp_path / "BAD").write_text('{"schema": ')
    (tmp_path / "OTHER").write_text('{"schema": "vdec.results/1"}')
    slow = copy.deepcopy(base)
    problem(slow, "B-SLOW")["wall_seconds"] = 9.0
    (tmp_path / "SLOW").write_text(json.dumps(slow))
    paths = {"FIXTURE": str(FIXTURE), "BAD": str(tmp_path / "BAD"), "OTHER": str(tmp_path / "OTHER"),
             "SLOW": str(tmp_path / "SLOW")}
    assert main(["compare", *[paths.get(a, a) for a in arguments]]) == 2
    assert phrase in capsys.readouterr().err


@REQ
def test_slower_problems_are_repeated_with_the_harness_runner(tmp_path):
    """The repeat runs the problem's runs with runner.execute, here the quick RB-INCLINE-SLIP."""
    vdec = os.environ.get("VDEC_EXECUTABLE")
    if not vdec or not Path(vdec).is_file():
        pytest.skip("VDEC_EXECUTABLE (the built vdec) is not set")
    problems = Path(__file__).resolve().parents[2] / "verification" / "problems"
    seconds = SuiteRepeater(vdec, problems, "base")("RB-INCLINE-SLIP", 2)
    assert len(seconds) == 2 and all(0.0 < s < 10.0 for s in seconds)

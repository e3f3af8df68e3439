"""The nightly run (REQ-QA-011), its trend page (REQ-QA-013) and the baseline's acceptance
(REQ-QA-014): the history file, the page and the baseline record on hand-made entries, then
`vdec_verify nightly` and scripts/nightly.sh end to end with the fake vdec of the harness tests."""
import hashlib
import json
import os
import subprocess
from pathlib import Path

import pytest

from vdec_verify.__main__ import main
from vdec_verify.compare import Thresholds, compare
from vdec_verify.history import (HISTORY_SCHEMA, RecordError, append_entry, entry_of_summary, load_record,
                                 read_history)
from vdec_verify.trend import streak_start, write_trend_page
from problem_files import write_problem

ROOT = Path(__file__).resolve().parents[2]
FIXTURE = Path(__file__).parent / "fixtures" / "compare" / "baseline-summary.json"
FAKE_VDEC = Path(__file__).parent / "fixtures" / "harness" / "fake_vdec.py"
HISTORY = pytest.mark.requirements("REQ-QA-011")
TREND = pytest.mark.requirements("REQ-QA-013")
BASELINE = pytest.mark.requirements("REQ-QA-014")


def entry(l2_error=4e-3, wall=2.0, commit="1", date=None):
    summary = json.loads(FIXTURE.read_text())
    summary["software"]["git_commit"] = commit * 40
    summary["harness"]["date"] = date or summary["harness"]["date"]
    summary["problems"][0]["metrics"][1]["error"] = l2_error
    summary["problems"][1]["wall_seconds"] = wall
    return entry_of_summary(summary)


@HISTORY
def test_a_history_line_holds_status_errors_times_cycles_and_hashes():
    line = entry()
    assert line["schema"] == HISTORY_SCHEMA and line["commit"] == "1" * 40 and line["level"] == "base"
    steady = line["problems"]["A-STEADY"]
    assert (steady["status"], steady["wall_seconds"], steady["cycles"]) == ("pass", 0.5, 2000)
    assert [(c["n"], c["check"], c["error"], c["tolerance"]) for c in steady["checks"]][:2] == \
        [(1, "settlement (relative)", 1e-7, 1e-5), (2, "velocity history (relative L2)", 4e-3, 1e-2)]
    assert line["inputs"]["verification/analytic/elastic.py"] == "e" * 64 and len(steady["inputs"]) == 64
    assert line["vdec_sha256"] == "b" * 64 and list(line["harness_files"]) == ["verification/harness/vdec_verify/runner.py"]


@HISTORY
def test_appending_keeps_one_line_per_run_and_reports_a_cut_line(tmp_path):
    path = tmp_path / "history" / "nightly.jsonl"
    assert append_entry(path, entry(commit="1")) == ""
    assert append_entry(path, entry(commit="2")) == ""
    assert [e["commit"][0] for _, e in read_history(path).entries] == ["1", "2"]
    with open(path, "ab") as f:          # a crash in the middle of a write
        f.write(b'{"schema": "vdec.nightly-history/1", "commit": "33')
    warning = append_entry(path, entry(commit="4"))
    assert "the last line was cut short" in warning
    history = read_history(path)
    assert [(n, e["commit"][0]) for n, e in history.entries] == [(1, "1"), (2, "2"), (4, "4")]
    assert len(history.corrupt) == 1 and history.corrupt[0].startswith(f"{path}:3: not valid JSON")
    path.write_text(path.read_text() + '{"schema": "other/1"}\n[1, 2]\n')
    corrupt = read_history(path).corrupt
    assert corrupt[1:] == [f"{path}:5: schema 'other/1', not {HISTORY_SCHEMA}", f"{path}:6: not a JSON object"]


@HISTORY
def test_a_record_is_a_summary_a_history_file_or_one_of_its_lines(tmp_path):
    path = tmp_path / "nightly.jsonl"
    for commit in "123":
        append_entry(path, entry(commit=commit))
    assert load_record(path)["commit"][0] == "3"
    assert load_record(f"{path}:1")["commit"][0] == "1"
    assert load_record(f"{path}:-2")["commit"][0] == "2"
    assert load_record(FIXTURE) == entry()
    with pytest.raises(RecordError, match=r"nightly.jsonl: line 7 is not an entry \(lines 1 to 3"):
        load_record(f"{path}:7")
    with pytest.raises(RecordError, match="has 3 entries, so no entry -4"):
        load_record(f"{path}:-4")


def write_history(path, errors):
    for i, error in enumerate(errors):
        append_entry(path, entry(l2_error=error, commit=str(i + 1), date=f"2026-01-0{i + 1}"))
    return read_history(path)


@TREND
@pytest.mark.parametrize("errors, start", [
    ([4e-3, 4e-3, 9e-3, 1e-2], 3),        # beyond twice the baseline's 4e-3 from the third run
    ([9e-3, 4e-3, 9e-3, 9e-3], 3),        # an earlier excursion does not belong to the streak
    ([9e-3, 9e-3, 9e-3, 9e-3], 1),
])
def test_a_regression_is_dated_from_the_first_run_of_its_streak(tmp_path, errors, start):
    history = write_history(tmp_path / "h.jsonl", errors)
    baseline = entry()
    change = next(c for c in compare(baseline, history.entries[-1][1], Thresholds(repeats=0)) if c.kind == "error")
    line, first = streak_start(change, baseline, history.entries, Thresholds())
    assert line == start and first["commit"][0] == str(start)


@TREND
def test_the_trend_page_lists_the_changes_first_and_draws_each_problem(tmp_path):
    history = write_history(tmp_path / "h.jsonl", [4e-3, 9e-3, 9e-3])
    with open(history.path, "ab") as f:
        f.write(b"not json\n")
    history = read_history(history.path)
    baseline = entry()
    comparison = type("Comparison", (), {"changes": compare(baseline, history.entries[-1][1], Thresholds(repeats=0))})
    acceptance = {"commit": "1" * 40, "run_date": "2026-01-01", "date": "2026-01-02", "by": "A. Reviewer",
                  "note": "issue 21 baseline"}
    page = write_trend_page(tmp_path / "page", history, baseline, acceptance, comparison, Thresholds())
    text = page.read_text()
    assert text.index("1 regression,") < text.index("<h2>Problems") < text.index("<h2>Trends")
    assert "h.jsonl:4: not valid JSON" in text and "A. Reviewer" in text and "issue 21 baseline" in text
    row = text[text.index("<tr class='regression'>"):]
    row = row[:row.index("</tr>")]
    assert "velocity history (relative L2)" in row and "2222222222" in row and "(history line 2)" in row
    assert sorted(p.name for p in (tmp_path / "page").glob("*.png")) == ["A-STEADY.png", "B-SLOW.png", "C-GONE.png"]
    assert text.index("id='A-STEADY'") < text.index("id='B-SLOW'")


@BASELINE
def test_accepting_a_baseline_records_who_and_why_and_keeps_earlier_acceptances(tmp_path, capsys):
    folder = str(tmp_path / "baseline")
    assert main(["baseline", "show", "--baseline", folder]) == 2
    assert "no baseline in" in capsys.readouterr().err
    assert main(["baseline", "accept", str(FIXTURE), "--note", "first nightly", "--by", "A. Lead",
                 "--baseline", folder]) == 0
    changed = json.loads(FIXTURE.read_text())
    changed["software"]["git_commit"] = "2" * 40
    (tmp_path / "second.json").write_text(json.dumps(changed))
    assert main(["baseline", "accept", str(tmp_path / "second.json"), "--note", "Kirsch error grew: finer zoning",
                 "--by", "B. Reviewer", "--baseline", folder]) == 0
    capsys.readouterr()
    assert main(["baseline", "show", "--baseline", folder, "--json"]) == 0
    acceptances = json.loads(capsys.readouterr().out)["acceptances"]
    assert [(a["by"], a["note"], a["commit"][0]) for a in acceptances] == \
        [("A. Lead", "first nightly", "1"), ("B. Reviewer", "Kirsch error grew: finer zoning", "2")]
    assert acceptances[1]["summary_sha256"] == hashlib.sha256((tmp_path / "second.json").read_bytes()).hexdigest()
    assert json.loads((tmp_path / "baseline" / "summary.json").read_text())["software"]["git_commit"] == "2" * 40
    assert main(["baseline", "show", "--baseline", folder]) == 0
    shown = capsys.readouterr().out
    assert shown.index("B. Reviewer") < shown.index("earlier acceptances") < shown.index("A. Lead")


@BASELINE
@pytest.mark.parametrize("arguments, phrase", [
    (["FIXTURE", "--note", "  "], "--note: say why"),
    (["MISSING", "--note", "x"], "MISSING: not a readable summary.json"),
    (["HISTORY", "--note", "x"], "only a summary.json can be accepted"),
])
def test_a_baseline_needs_a_note_and_a_summary(tmp_path, capsys, arguments, phrase):
    append_entry(tmp_path / "h.jsonl", entry())
    paths = {"FIXTURE": str(FIXTURE), "MISSING": str(tmp_path / "MISSING"), "HISTORY": str(tmp_path / "h.jsonl")}
    assert main(["baseline", "accept", *[paths.get(a, a) for a in arguments], "--baseline", str(tmp_path / "b")]) == 2
    assert phrase in capsys.readouterr().err
    assert not (tmp_path / "b" / "summary.json").exists()


PROBLEM = '''id = "N-1"
title = "nightly"
requirements = ["REQ-QA-011"]
scene = "scene.toml"
expect_stop = "time"

[[check]]
quantity = "normal force"
extract = { kind = "final", history = "normal_force" }
reference = { function = "rigid_blocks.resting_normal_force", params = { mass = 2500.0, g = 10.0 } }
norm = "scalar"
rtol = 1e-5
justification = "j"
tolerance_basis = "derived"

[[mutation]]
name = "mass-up"
overrides = ["oscillator.mass=2600.0"]
why = "4 % more mass"
'''


def nightly_arguments(tmp_path):
    return ["--problems", str(tmp_path / "problems"), "--out", str(tmp_path / "suite"), "--history",
            str(tmp_path / "history.jsonl"), "--baseline", str(tmp_path / "baseline"), "--page", str(tmp_path / "page"),
            "--jobs", "1"]


@HISTORY
def test_the_nightly_appends_compares_and_fails_on_a_regression(tmp_path, capsys):
    write_problem(tmp_path / "problems", PROBLEM, folder="N-1")
    scene = tmp_path / "problems" / "N-1" / "scene.toml"
    # The fake's final sample is off by 0.043 of its error setting: 8.6e-7 here, 4.3e-6 below, against 1e-5.
    scene.write_text("[fake]\nerror = 2e-5\n")
    arguments = ["nightly", "--vdec", str(FAKE_VDEC), *nightly_arguments(tmp_path)]
    assert main(arguments) == 2                      # no baseline yet: the history and the page are written
    assert "no baseline in" in capsys.readouterr().err and (tmp_path / "page" / "index.html").is_file()
    assert main(["baseline", "accept", str(tmp_path / "suite" / "summary.json"), "--note", "n", "--by", "me",
                 "--baseline", str(tmp_path / "baseline")]) == 0
    assert main(arguments) == 0
    scene.write_text("[fake]\nerror = 1e-4\n")     # the error grows five-fold and still passes
    assert main(arguments) == 1
    out = capsys.readouterr().out
    assert "REGRESSION error    N-1 check 'normal force'" in out
    history = read_history(tmp_path / "history.jsonl")
    assert len(history.entries) == 3 and not history.corrupt
    assert "(history line 3)" in (tmp_path / "page" / "index.html").read_text()


@HISTORY
def test_the_nightly_script_builds_then_passes_its_options_through(tmp_path):
    """scripts/nightly.sh with a stand-in cmake on PATH that 'builds' the fake vdec."""
    write_problem(tmp_path / "problems", PROBLEM, folder="N-1")
    (tmp_path / "problems" / "N-1" / "scene.toml").write_text("[fake]\nerror = 1e-7\n")
    tools = tmp_path / "tools"
    tools.mkdir()
    log = tmp_path / "cmake.log"
    (tools / "cmake").write_text(f'#!/bin/sh\necho "$@" >> {log}\n'
                                 f'[ "$1" = --build ] && cp {FAKE_VDEC} "$2/vdec"\n'
                                 f'[ -n "$CMAKE_FAILS" ] && exit 1\nexit 0\n')
    (tools / "cmake").chmod(0o755)
    build = tmp_path / "build"
    build.mkdir()
    environment = dict(os.environ, PATH=f"{tools}:{os.environ['PATH']}", VDEC_BUILD_DIR=str(build))
    script = [str(ROOT / "scripts" / "nightly.sh"), *nightly_arguments(tmp_path), "--filter", "N-1"]
    done = subprocess.run(script, env=environment, capture_output=True, text=True, timeout=120)
    assert done.returncode == 2 and "no baseline in" in done.stderr, done.stderr
    assert "-DCMAKE_BUILD_TYPE=Release" in log.read_text() and f"--build {build}" in log.read_text()
    assert load_record(tmp_path / "history.jsonl")["filter"] == ["N-1"]
    failing = subprocess.run(script, env=dict(environment, CMAKE_FAILS="1"), capture_output=True, text=True,
                             timeout=60)
    assert failing.returncode == 3 and "vdec did not build" in failing.stderr

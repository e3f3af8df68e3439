"""The committed work-precision baseline (REQ-QA-018): `vdec_verify baseline work-precision` takes
the curves of a hand-made full-suite summary into the file with the right numbers; the report
compares each refinable problem with it (the ratios at the finest common level, a figure with
both curves) and says when a problem has no entry; a corrupt baseline stops `run` with exit 2
naming the file."""
import contextlib
import copy
import hashlib
import html
import io
import json
import shutil
import subprocess
import tomllib
from pathlib import Path

import pytest
from matplotlib.figure import Figure

from vdec_verify.__main__ import main
from vdec_verify.work_precision import (DEFAULT_FILE, SCHEMA, BaselineError, comparison, read_baseline,
                                        update_baseline)
from vdec_verify.figures import draw_methods, draw_work_precision

FIXTURES = Path(__file__).parent / "fixtures" / "harness"
FAKE_VDEC = FIXTURES / "fake_vdec.py"
STUDIES = FIXTURES / "convergence"
PROBLEMS = Path(__file__).resolve().parents[2] / "verification" / "problems"
COMMIT = "abcdef0123456789abcdef0123456789abcdef01"
REQ = pytest.mark.requirements("REQ-QA-018")


def run_main(*args):
    stdout, stderr = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(stdout), contextlib.redirect_stderr(stderr):
        code = main(list(map(str, args)))
    return code, stdout.getvalue(), stderr.getvalue()


def study_record(levels):
    """A convergence record of summary.json from (name, h, error, wall seconds, cycles) per level."""
    names, h, error, seconds, cycles = (list(column) for column in zip(*levels))
    return {"levels": names, "h": h, "error": error, "wall_seconds": seconds, "cycles": cycles, "pass": True,
            "quantity": "tip deflection", "norm": "scalar", "observed_order": 2.0, "expected_order": 2.0,
            "order_tolerance": 0.3, "gci": None, "asymptotic_ratio": None, "fit_levels": names, "message": ""}


STUDY_LEVELS = [("L1", 0.5, 4e-3, 1.0, 100), ("L2", 0.25, 1e-3, 4.0, 200), ("L3", 0.125, 2.5e-4, 16.0, 400)]


def methods_record():
    return [{"title": "error of two methods", "norm": "L2", "series": [
        {"label": "A", "points": [{"check": 1, "run": "plain", "error": 1e-2, "pass": True, "wall_seconds": 0.5},
                                  {"check": 2, "run": "fine", "error": 1e-3, "pass": True, "wall_seconds": 2.0}]},
        {"label": "B", "points": [{"check": 3, "run": "b1", "error": 3e-3, "pass": True, "wall_seconds": 1.5}]}]}]


def hand_summary(level="full"):
    """A full-suite summary.json of three problems: a study, a [[work_precision]] figure, neither."""
    return {"schema": "vdec.verification/1",
            "software": {"version": "0.1.0", "git_commit": COMMIT, "build_type": "Release", "compiler": "GNU 12.2.0"},
            "harness": {"level": level, "date": "2026-01-02T03:04:05+00:00", "host": "bench-host", "python": "3.11.2",
                        "qualified": True},
            "counts": {"passed": 3, "failed": 0},
            "problems": [
                {"id": "P-STUDY", "status": "pass", "runs": [], "convergence": study_record(STUDY_LEVELS)},
                {"id": "P-METHODS", "status": "pass", "work_precision": methods_record(),
                 "runs": [{"variant": "", "cycles": 10}, {"variant": "fine", "cycles": 40},
                          {"variant": "b1", "cycles": 7}]},
                {"id": "P-PLAIN", "status": "pass", "runs": []}]}


def write_json(path, value):
    path.write_text(json.dumps(value, indent=1))
    return path


@pytest.fixture
def baseline_file(tmp_path):
    summary = write_json(tmp_path / "summary.json", hand_summary())
    out = tmp_path / "baselines" / "work-precision.json"
    update_baseline(summary, out, "first baseline", "tester")
    return out


# ---------------------------------------------------------------- making the file

@REQ
def test_the_baseline_file_holds_each_levels_numbers_and_where_they_came_from(tmp_path):
    summary = write_json(tmp_path / "summary.json", hand_summary())
    out = tmp_path / "baselines" / "work-precision.json"
    code, stdout, stderr = run_main("baseline", "work-precision", summary, "--out", out, "--note", "first baseline",
                                    "--by", "tester")
    assert code == 0, stderr
    assert "2 problems from commit abcdef012345" in stdout
    data = json.loads(out.read_text())
    assert data["schema"] == SCHEMA
    (update,) = data["updates"]
    assert (update["commit"], update["run_date"], update["level"], update["note"], update["by"]) == \
        (COMMIT, "2026-01-02T03:04:05+00:00", "full", "first baseline", "tester")
    assert update["machine"] == {"host": "bench-host", "python": "3.11.2", "compiler": "GNU 12.2.0",
                                 "build_type": "Release"}
    assert update["summary_sha256"] == hashlib.sha256(summary.read_bytes()).hexdigest()
    assert update["problems"] == ["P-METHODS", "P-STUDY"] and set(data["problems"]) == {"P-METHODS", "P-STUDY"}
    study = data["problems"]["P-STUDY"]
    assert study["update"] == 0 and study["study"]["quantity"] == "tip deflection"
    assert [(level["name"], level["h"], level["error"], level["wall_seconds"], level["cycles"])
            for level in study["study"]["levels"]] == STUDY_LEVELS
    series = data["problems"]["P-METHODS"]["figures"][0]["series"]
    assert [(s["label"], [(p["run"], p["error"], p["wall_seconds"], p["cycles"]) for p in s["points"]])
            for s in series] == [("A", [("plain", 1e-2, 0.5, 10), ("fine", 1e-3, 2.0, 40)]),
                                 ("B", [("b1", 3e-3, 1.5, 7)])]
    assert read_baseline(out).problems == data["problems"]


@REQ
def test_an_update_renews_the_summarys_problems_and_keeps_the_others(tmp_path, baseline_file):
    later = hand_summary()
    later["software"]["git_commit"] = "f" * 40
    later["problems"] = [later["problems"][0]]
    later["problems"][0]["convergence"]["error"][2] = 2e-4
    summary = write_json(tmp_path / "later.json", later)
    assert run_main("baseline", "work-precision", summary, "--out", baseline_file, "--note", "finer error",
                    "--by", "tester")[0] == 0
    data = json.loads(baseline_file.read_text())
    assert [u["note"] for u in data["updates"]] == ["first baseline", "finer error"]
    assert data["problems"]["P-STUDY"]["update"] == 1 and data["problems"]["P-METHODS"]["update"] == 0
    assert data["problems"]["P-STUDY"]["study"]["levels"][2]["error"] == 2e-4


@REQ
def test_a_summary_that_cannot_give_a_baseline_is_refused(tmp_path):
    out = tmp_path / "work-precision.json"
    base = write_json(tmp_path / "base.json", hand_summary(level="base"))
    code, _, stderr = run_main("baseline", "work-precision", base, "--out", out, "--note", "n")
    assert code == 2 and f"{base}: harness.level is 'base'" in stderr
    other = write_json(tmp_path / "other.json", {"schema": "something else"})
    code, _, stderr = run_main("baseline", "work-precision", other, "--out", out, "--note", "n")
    assert code == 2 and f"{other}: key 'schema'" in stderr
    full = write_json(tmp_path / "full.json", hand_summary())
    code, _, stderr = run_main("baseline", "work-precision", full, "--out", out, "--note", "  ")
    assert code == 2 and "--note" in stderr
    assert not out.exists()


# ---------------------------------------------------------------- the comparison

def current_record(problem_id="P-STUDY", levels=None):
    return {"id": problem_id, "convergence": study_record(levels or STUDY_LEVELS), "runs": []}


@REQ
def test_the_ratios_are_taken_at_the_finest_common_level(baseline_file):
    baseline = read_baseline(baseline_file)
    # L3 twice the error in half the time; L4 is finer but not in the baseline; L2 has another h.
    levels = [("L1", 0.5, 8e-3, 1.0, 100), ("L2", 0.3, 1e-3, 4.0, 200), ("L3", 0.125, 5e-4, 8.0, 400),
              ("L4", 0.0625, 1e-4, 30.0, 800)]
    compared = comparison(current_record(levels=levels), baseline, {"host": "bench-host"})
    study = compared["study"]
    assert (study["common_level"], study["error_ratio"], study["time_ratio"]) == ("L3", 2.0, 0.5)
    assert [r["level"] for r in study["ratios"]] == ["L1", "L3"] and study["changed_h"] == ["L2"]
    assert compared["message"] == ("at the finest common level L3: error ratio 2.000, time ratio 0.500 against the "
                                   "baseline of abcdef012345; levels with another h than in the baseline, not "
                                   "compared: L2")
    assert compared["commit"] == COMMIT and compared["study"]["levels"][0]["name"] == "L1"
    # Another host: the time ratio is said to compare machines.
    assert "the baseline ran on host bench-host, this run on other" in \
        comparison(current_record(levels=levels), baseline, {"host": "other"})["message"]
    # A [[work_precision]] series: at the run the baseline spent longest on.
    methods = methods_record()
    methods[0]["series"][0]["points"][1].update(error=3e-3, wall_seconds=1.0)
    compared = comparison({"id": "P-METHODS", "work_precision": methods, "runs": []}, baseline)
    series_a, series_b = compared["figures"][0]["series"]
    assert (series_a["common_run"], series_a["error_ratio"], series_a["time_ratio"]) == ("fine", 3.0, 0.5)
    assert (series_b["common_run"], series_b["error_ratio"], series_b["time_ratio"]) == ("b1", 1.0, 1.0)
    assert compared["message"].startswith("A at fine: error ratio 3.000, time ratio 0.500 against the baseline of "
                                          "abcdef012345; B at b1: error ratio 1.000, time ratio 1.000")


@REQ
def test_a_problem_missing_from_the_baseline_is_stated(baseline_file):
    baseline = read_baseline(baseline_file)
    compared = comparison(current_record("P-NEW"), baseline)
    assert compared["commit"] is None and compared["study"] is None
    assert compared["message"].startswith(f"no baseline entry for this problem in {baseline_file}")
    assert comparison({"id": "P-PLAIN", "runs": []}, baseline) is None     # no curve, nothing to compare
    assert comparison(current_record("P-NEW"), None)["message"].startswith("no work-precision baseline:")


# ---------------------------------------------------------------- the figures

def lines_by_label(ax):
    return {line.get_label(): line for line in ax.get_lines()}


@REQ
def test_the_work_precision_panels_draw_the_baseline_curve_in_grey_dashed(baseline_file):
    baseline = read_baseline(baseline_file)
    levels = [("L1", 0.5, 8e-3, 2.0, 100), ("L2", 0.25, 2e-3, 8.0, 200), ("L3", 0.125, 5e-4, 32.0, 400)]
    record = current_record(levels=levels)
    ax = Figure().add_subplot()
    draw_work_precision(ax, record["convergence"], comparison(record, baseline))
    lines = lines_by_label(ax)
    assert set(lines) == {"vdec", "baseline abcdef012345"}
    assert list(lines["vdec"].get_xdata()) == [2.0, 8.0, 32.0]
    base = lines["baseline abcdef012345"]
    assert list(base.get_xdata()) == [1.0, 4.0, 16.0] and list(base.get_ydata()) == [4e-3, 1e-3, 2.5e-4]
    assert (base.get_color(), base.get_linestyle()) == ("grey", "--")
    assert "the baseline of abcdef012345" in ax.get_title()
    # Without an entry: one curve, and the panel says so.
    ax = Figure().add_subplot()
    draw_work_precision(ax, record["convergence"], comparison(current_record("P-NEW"), baseline))
    assert set(lines_by_label(ax)) == {"vdec"} and "no baseline entry" in ax.get_title()
    # A [[work_precision]] figure: each method beside its baseline.
    compared = comparison({"id": "P-METHODS", "work_precision": methods_record(), "runs": []}, baseline)
    ax = Figure().add_subplot()
    draw_methods(ax, methods_record()[0], dict(compared["figures"][0], commit=compared["commit"]))
    lines = lines_by_label(ax)
    assert set(lines) == {"A", "A, baseline abcdef012345", "B", "B, baseline abcdef012345"}
    assert lines["A, baseline abcdef012345"].get_color() == "grey"


# ---------------------------------------------------------------- through the suite

@REQ
def test_the_reports_compare_each_study_with_the_baseline_or_say_it_has_none(tmp_path):
    """FX-ORDER-TWO (fake error 0.01 h^2) against a baseline with twice its error at h0.25;
    FX-ORDER-ONE (which fails its study by design) has no entry."""
    summary = hand_summary()
    summary["problems"] = [{"id": "FX-ORDER-TWO", "runs": [], "convergence": study_record(
        [("h0.5", 0.5, 2 * 0.01 * 0.5 ** 2, 0.5, 4), ("h0.25", 0.25, 2 * 0.01 * 0.25 ** 2, 0.5, 16)])}]
    baseline = tmp_path / "work-precision.json"
    update_baseline(write_json(tmp_path / "summary.json", summary), baseline, "for the test", "tester")
    out = tmp_path / "out"
    code, stdout, stderr = run_main("run", "--vdec", FAKE_VDEC, "--problems", STUDIES, "--out", out, "--level", "base",
                                    "--work-precision-baseline", baseline)
    assert code == 1 and stdout.strip().endswith("1 passed, 1 failed"), stdout + stderr
    written = json.loads((out / "summary.json").read_text())
    problems = {p["id"]: p for p in written["problems"]}
    two = problems["FX-ORDER-TWO"]["work_precision_baseline"]
    study = problems["FX-ORDER-TWO"]["convergence"]
    assert two["study"]["common_level"] == "h0.25"
    assert two["study"]["error_ratio"] == pytest.approx(0.5, rel=1e-5, abs=0)
    assert two["study"]["time_ratio"] == pytest.approx(study["wall_seconds"][1] / 0.5, rel=1e-12, abs=0)
    one = problems["FX-ORDER-ONE"]["work_precision_baseline"]
    assert one["commit"] is None and one["message"].startswith(f"no baseline entry for this problem in {baseline}")
    assert written["harness"]["work_precision_baseline"]["sha256"] == hashlib.sha256(baseline.read_bytes()).hexdigest()
    page = (out / "index.html").read_text()
    assert "at the finest common level h0.25: error ratio 0.500, time ratio" in page
    caption = page[page.index('src="FX-ORDER-TWO-convergence.png"'):]
    assert "Against the baseline: at the finest common level h0.25" in caption[:caption.index("</figcaption>")]
    assert html.escape(one["message"]) in page
    if shutil.which("pdftotext") is None:
        pytest.skip("pdftotext (poppler-utils) is not installed")
    text = " ".join(subprocess.run(["pdftotext", str(out / "report.pdf"), "-"], capture_output=True, text=True,
                                   check=True).stdout.split())
    assert "at the finest common level h0.25: error ratio 0.500, time ratio" in text
    assert "no baseline entry for this problem" in text
    assert "at h0.25 (abcdef012345)" in text      # the ratios column of the convergence studies' table


@REQ
@pytest.mark.parametrize("corrupt, named", [
    (lambda text, data: text[:-40], "line "),
    (lambda text, data: json.dumps(dict(data, schema="vdec.nightly-baseline/1")), "schema"),
    (lambda text, data: json.dumps(data).replace('"h": 0.25', '"h": -0.25'), "problems.P-STUDY.study.levels[1].h"),
    (lambda text, data: json.dumps(data).replace('"wall_seconds": 2.0', '"wall_seconds": "2"'),
     "problems.P-METHODS.figures[0].series[0].points[1].wall_seconds"),
    (lambda text, data: json.dumps(data).replace('"update": 0', '"update": 3'), ".update"),
], ids=["not JSON", "another schema", "negative h", "seconds as text", "no such update"])
def test_a_corrupt_baseline_stops_the_run_naming_the_file_and_key(tmp_path, baseline_file, corrupt, named):
    text = baseline_file.read_text()
    baseline_file.write_text(corrupt(text, json.loads(text)))
    with pytest.raises(BaselineError, match=named.replace("[", r"\[").replace("]", r"\]").replace(".", r"\.")):
        read_baseline(baseline_file)
    out = tmp_path / "out"
    code, _, stderr = run_main("run", "--vdec", FAKE_VDEC, "--problems", STUDIES, "--out", out, "--level", "base",
                               "--work-precision-baseline", baseline_file)
    assert code == 2 and f"--work-precision-baseline: {baseline_file}: " in stderr and named in stderr
    assert not out.exists()          # refused before the suite ran


@REQ
def test_the_committed_baseline_reads_and_names_only_problems_that_exist():
    baseline = read_baseline(DEFAULT_FILE)
    assert baseline.updates[0]["level"] == "full"
    for pid, entry in baseline.problems.items():
        data = tomllib.loads((PROBLEMS / pid / "problem.toml").read_text())
        assert ("study" in entry) == ("refinement" in data), pid
        assert ("figures" in entry) == ("work_precision" in data), pid

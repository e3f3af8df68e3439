"""The verification harness end to end with a fake vdec (tests/python/fixtures/harness/fake_vdec.py):
runs, statuses, exit codes and the report files (REQ-QA-001); a deliberately wrong or circular
problem makes the suite fail (REQ-QA-002)."""
import contextlib
import html
import io
import json
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from vdec_verify import PASS_RULE
from vdec_verify.__main__ import main
from vdec_verify.runner import discover, matches, select

ROOT = Path(__file__).resolve().parents[2]
FIXTURES = Path(__file__).parent / "fixtures" / "harness"
FAKE_VDEC = FIXTURES / "fake_vdec.py"
PROBLEMS = FIXTURES / "problems"
EXPECTED_STATUS = {"FX-BAD-TOML": "invalid", "FX-CRASH": "fail", "FX-FULL-ONLY": "pass", "FX-IDENTICAL": "invalid",
                   "FX-SCALARS": "pass", "FX-SERIES": "pass", "FX-SWEEP": "pass", "FX-TIMEOUT": "fail",
                   "FX-WRONG-REFERENCE": "fail"}


def run_main(*args):
    stdout, stderr = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(stdout), contextlib.redirect_stderr(stderr):
        code = main(list(map(str, args)))
    return code, stdout.getvalue(), stderr.getvalue()


@pytest.fixture(scope="module")
def suite(tmp_path_factory):
    """The whole fixture suite, run once in process."""
    out = tmp_path_factory.mktemp("verification")
    # A stale results.json from an earlier run must not pass for this one's.
    stale = out / "runs" / "FX-CRASH"
    stale.mkdir(parents=True)
    (stale / "results.json").write_text(json.dumps({"schema": "vdec.results/1", "histories": {
        "normal_force": {"t": [0.0], "value": [25000.0]}}}))
    code, stdout, stderr = run_main("run", "--vdec", FAKE_VDEC, "--problems", PROBLEMS, "--out", out,
                                    "--level", "full", "--jobs", "2")
    summary = json.loads((out / "summary.json").read_text())
    return {"code": code, "stdout": stdout, "stderr": stderr, "out": out, "summary": summary,
            "problems": {p["id"]: p for p in summary["problems"]}}


@pytest.mark.requirements("REQ-QA-001")
def test_statuses_exit_code_and_the_last_line(suite):
    assert {pid: p["status"] for pid, p in suite["problems"].items()} == EXPECTED_STATUS
    assert suite["code"] == 1
    lines = suite["stdout"].strip().splitlines()
    assert lines[-1] == "4 passed, 5 failed"
    for pid, status in EXPECTED_STATUS.items():
        assert any(line.split()[:2] == [status, pid] for line in lines), pid
    assert "[17/17]" in suite["stderr"]     # progress, one line per run: 9 runs, 8 of the mutations


@pytest.mark.requirements("REQ-QA-001")
def test_summary_json_schema_and_provenance(suite):
    summary = suite["summary"]
    assert summary["schema"] == "vdec.verification/1"
    assert summary["software"] == {"version": "0.9.0", "git_commit": "f" * 40, "build_type": "Release",
                                   "compiler": "fake 1.0"}
    harness = summary["harness"]
    assert {"git_commit", "date", "host", "python", "pass_rule"} <= set(harness)
    assert harness["pass_rule"] == PASS_RULE
    assert re.fullmatch(r"[0-9a-f]{40}|unknown", harness["git_commit"])
    assert harness["software_consistent"] is True and harness["software_disagreements"] == []
    assert [p["id"] for p in summary["problems"]] == sorted(EXPECTED_STATUS)
    for p in summary["problems"]:
        assert {"id", "title", "requirements", "status", "metrics", "wall_seconds", "cycles", "scene_sha256",
                "exit_code", "message"} <= set(p)
        for m in p["metrics"]:
            assert {"quantity", "norm", "error", "tolerance", "pass", "numerical", "reference",
                    "justification"} <= set(m)
            assert "plot" not in m
    scalars = suite["problems"]["FX-SCALARS"]
    assert len(scalars["metrics"]) == 9 and all(m["pass"] for m in scalars["metrics"])
    assert scalars["cycles"] == 4010 and scalars["exit_code"] == 0 and len(scalars["scene_sha256"]) == 64
    # Series checks report the norms' s values, not the samples.
    series = suite["problems"]["FX-SERIES"]["metrics"][0]
    assert isinstance(series["numerical"], float) and isinstance(series["reference"], float)
    assert series["error"] < 1e-6
    # Strict JSON: no NaN or Infinity anywhere.
    json.loads((suite["out"] / "summary.json").read_text(), parse_constant=lambda c: pytest.fail(c))


@pytest.mark.requirements("REQ-QA-002")
def test_wrong_reference_fails_and_circular_reference_is_invalid(suite):
    wrong = suite["problems"]["FX-WRONG-REFERENCE"]
    metric = wrong["metrics"][0]
    assert not metric["pass"] and metric["numerical"] == pytest.approx(25000.0, rel=1e-6, abs=0)
    assert metric["reference"] == 26000.0 and metric["error"] == pytest.approx(1000.0 / 26000.0, rel=1e-5, abs=0)
    assert "failed: normal force against a reference with the wrong mass" in wrong["message"]
    identical = suite["problems"]["FX-IDENTICAL"]
    assert "reference identical to the numerical output: the reference must be independent" in identical["message"]
    bad = suite["problems"]["FX-BAD-TOML"]
    assert "key 'tolerance': unknown key" in bad["message"]
    assert "key 'check[0].justification'" in bad["message"]


@pytest.mark.requirements("REQ-QA-001")
def test_run_failures_are_reported_with_the_solver_diagnostic(suite):
    crash = suite["problems"]["FX-CRASH"]
    assert crash["exit_code"] == 4
    assert "exited 4 (geometry error), expected 0" in crash["message"]
    assert "fake failure with exit code 4" in crash["message"]
    assert "the run wrote no results.json" in crash["metrics"][0]["message"]   # the stale file was removed
    timeout = suite["problems"]["FX-TIMEOUT"]
    assert "timed out after 1 s" in timeout["message"] and timeout["exit_code"] is None
    assert timeout["wall_seconds"] < 10


@pytest.mark.requirements("REQ-QA-001")
def test_variants_run_in_their_own_folders(suite):
    runs = suite["out"] / "runs"
    sweep = suite["problems"]["FX-SWEEP"]
    assert [(r["variant"], r["exit_code"], r["expect_exit"]) for r in sweep["runs"]] == [("frac-0.5", 0, 0),
                                                                                         ("frac-3.0", 5, 5)]
    assert [m["variant"] for m in sweep["metrics"]] == ["frac-0.5", "frac-3.0"]
    # Every check names a variant, so there is no plain run.
    assert not (runs / "FX-SWEEP" / "results.json").exists()
    for variant, frac in (("frac-0.5", "0.5"), ("frac-3.0", "3.0")):
        results = json.loads((runs / "FX-SWEEP" / variant / "results.json").read_text())
        assert results["scene"]["overrides"][-1 if variant == "frac-0.5" else -2] == f"solver.frac={frac}"
        assert f"--set solver.frac={frac}" in (runs / "FX-SWEEP" / variant / "command.txt").read_text()
    assert (runs / "FX-SCALARS" / "results.json").is_file()
    assert "fake failure" in (runs / "FX-CRASH" / "stderr.txt").read_text()


@pytest.mark.requirements("REQ-QA-001")
def test_junit_has_one_testcase_per_check_with_requirements(suite):
    root = ET.parse(suite["out"] / "junit.xml").getroot()
    assert root.tag == "testsuite" and root.get("name") == "verification"
    properties = {p.get("name"): p.get("value") for p in root.find("properties")}
    assert properties["vdec_version"] == "0.9.0" and properties["vdec_commit"] == "f" * 40
    cases = root.findall("testcase")
    assert root.get("tests") == str(len(cases))
    assert root.get("failures") == str(sum(c.find("failure") is not None for c in cases))
    for pid, problem in suite["problems"].items():
        own = [c for c in cases if c.get("classname") == f"verification.{pid}"]
        checks = [c for c in own if c.get("name").startswith("#")]
        assert [c.get("name").split()[0] for c in checks] == [f"#{n}" for n in range(1, len(problem["metrics"]) + 1)]
        for case, metric in zip(checks, problem["metrics"]):
            assert metric["quantity"] in case.get("name")
            assert (case.find("failure") is None) == metric["pass"], (pid, metric["quantity"])
        runs_failed = any(run["message"] for run in problem["runs"])
        assert [c.get("name") for c in own if c not in checks] == (["runs"] if runs_failed or not checks else [])
        assert any(c.find("failure") is not None for c in own) == (EXPECTED_STATUS[pid] != "pass"), pid
        for case in own:
            requirements = case.find(".//property[@name='requirements']").get("value")
            assert requirements == ",".join(problem["requirements"])
    wrong = next(c for c in cases if c.get("classname") == "verification.FX-WRONG-REFERENCE").find("failure")
    assert "numerical 25000" in wrong.text and "analytic 26000" in wrong.text
    crash = next(c for c in cases if c.get("classname") == "verification.FX-CRASH" and c.get("name") == "runs")
    assert "exited 4" in crash.find("failure").text


@pytest.mark.requirements("REQ-QA-001")
def test_index_html_is_self_contained_with_provenance_and_plots(suite):
    out = suite["out"]
    page = (out / "index.html").read_text()
    assert html.escape(PASS_RULE) in page
    for text in ("0.9.0", "f" * 40, "Release", "fake 1.0", suite["summary"]["harness"]["host"],
                 suite["summary"]["harness"]["date"], "4 passed, 5 failed"):
        assert text in page
    assert "<script" not in page and "<link" not in page and "<style>" in page
    for pid in EXPECTED_STATUS:
        assert f'id="{pid}"' in page
    images = re.findall(r'<img src="([^"]+)"', page)
    assert sorted({re.sub(r"-(check\d+|scalars|convergence|work-precision\d+)\.png$", "", image) for image in images}) == ["FX-FULL-ONLY", "FX-SCALARS", "FX-SERIES",
                                                                    "FX-SWEEP", "FX-WRONG-REFERENCE"]
    assert "FX-SERIES-check1.png" in images and "FX-SCALARS-scalars.png" in images
    assert '<a href="report.pdf">' in page and "traceability/rtm.html" in page
    for image in images:
        assert (out / image).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # Three failed problems in the overview, and the checks of FX-WRONG-REFERENCE, FX-CRASH and FX-TIMEOUT.
    assert page.count('class="fail">FAIL</td>') == 3 + 3
    # Two invalid problems in the overview, and the circular check of FX-IDENTICAL.
    assert page.count('class="invalid">INVALID</td>') == 2 + 1
    assert "shear stress against shear displacement" in page


@pytest.mark.requirements("REQ-QA-005")
def test_a_work_precision_figure_draws_each_check_at_its_runs_wall_time(suite):
    record = suite["problems"]["FX-SCALARS"]
    [figure] = record["work_precision"]
    assert figure["title"] == "two checks of the plain run against its wall time" and figure["norm"] == "scalar"
    assert [s["label"] for s in figure["series"]] == ["force", "settlement"]
    [force], [settlement] = (s["points"] for s in figure["series"])
    assert (force["check"], force["run"], settlement["check"]) == (1, "plain", 5)
    assert force["error"] == record["metrics"][0]["error"] and settlement["error"] == record["metrics"][4]["error"]
    assert force["wall_seconds"] == record["runs"][0]["wall_seconds"] > 0.0
    assert "FX-SCALARS-work-precision1.png" in (suite["out"] / "index.html").read_text()


@pytest.mark.requirements("REQ-QA-001")
def test_report_pdf_has_a_section_per_problem(suite):
    pdf = (suite["out"] / "report.pdf").read_bytes()
    assert pdf.startswith(b"%PDF")
    if shutil.which("pdftotext") is None:
        pytest.skip("pdftotext (poppler-utils) is not installed")
    text = subprocess.run(["pdftotext", str(suite["out"] / "report.pdf"), "-"], capture_output=True, text=True,
                          check=True).stdout
    for n, pid in enumerate(sorted(EXPECTED_STATUS), start=1):
        assert re.search(rf"^4\.{n} {pid}: {EXPECTED_STATUS[pid].upper()}$", text, re.M), pid
    assert "4 of 9 problems passed, 5 failed" in " ".join(text.split())


@pytest.mark.requirements("REQ-QA-001")
def test_selection_by_level_and_filter():
    entries = discover(PROBLEMS)
    base = [e.id for e in select(entries, "base", [])]
    assert "FX-FULL-ONLY" not in base and "FX-BAD-TOML" in base
    assert "FX-FULL-ONLY" in [e.id for e in select(entries, "full", [])]
    assert [e.id for e in select(entries, "full", ["wrong", "FX-S*S"])] == ["FX-SCALARS", "FX-SERIES",
                                                                               "FX-WRONG-REFERENCE"]
    assert matches("RB-INCLINE-SLIP", ["incline"]) and matches("RB-INCLINE-SLIP", ["rb-*-slip"])
    assert not matches("RB-INCLINE-SLIP", ["STICK", "RB-*-STICK"])


@pytest.mark.requirements("REQ-QA-001")
def test_runs_by_different_vdec_builds_are_flagged(tmp_path):
    problems = tmp_path / "problems"
    for pid, version in (("V-1", "0.9.0"), ("V-2", "1.0.0")):
        folder = problems / pid
        folder.mkdir(parents=True)
        (folder / "scene.toml").write_text(f'title = "fake"\n[fake]\nversion = "{version}"\n')
        text = (PROBLEMS / "FX-FULL-ONLY" / "problem.toml").read_text()
        (folder / "problem.toml").write_text(text.replace('"FX-FULL-ONLY"', f'"{pid}"').replace('level = "full"\n', ""))
    code, stdout, _ = run_main("run", "--vdec", FAKE_VDEC, "--problems", problems, "--out", tmp_path / "out",
                               "--jobs", "1")
    assert code == 0 and stdout.strip().splitlines()[-1] == "2 passed, 0 failed"
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["software"]["version"] == "0.9.0"
    assert summary["harness"]["software_consistent"] is False
    assert "V-2: version 1.0.0 (not 0.9.0)" in summary["harness"]["software_disagreements"][0]
    assert "WARNING: runs by different vdec builds" in (tmp_path / "out" / "index.html").read_text()


@pytest.mark.requirements("REQ-QA-001")
@pytest.mark.parametrize("args, phrase", [
    (["run"], "--vdec"),
    (["run", "--vdec", "/no/such/vdec"], "no executable file"),
    (["run", "--vdec", FAKE_VDEC, "--problems", "/no/such/folder"], "no such folder"),
    (["run", "--vdec", FAKE_VDEC, "--problems", PROBLEMS, "--filter", "NOTHING-MATCHES"], "no problems"),
    (["run", "--vdec", FAKE_VDEC, "--level", "nightly"], "invalid choice"),
    (["run", "--vdec", FAKE_VDEC, "--jobs", "0"], "--jobs"),
    (["frobnicate"], "invalid choice"),
])
def test_usage_errors_exit_2(args, phrase):
    code, _, stderr = run_main(*args)
    assert code == 2 and phrase in stderr


def _python_m(*args, cwd=ROOT):
    env = dict(os.environ, PYTHONPATH=f"{ROOT / 'verification/harness'}{os.pathsep}{ROOT / 'verification'}")
    return subprocess.run([sys.executable, "-m", "vdec_verify", *map(str, args)], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=120)


@pytest.mark.requirements("REQ-QA-002")
def test_a_deliberately_wrong_problem_makes_the_suite_exit_nonzero(tmp_path):
    completed = _python_m("run", "--vdec", FAKE_VDEC, "--problems", PROBLEMS, "--filter", "FX-WRONG",
                          "--out", tmp_path / "out")
    assert completed.returncode == 1, completed.stderr
    assert completed.stdout.strip().splitlines()[-1] == "0 passed, 1 failed"


@pytest.mark.requirements("REQ-QA-001")
def test_a_passing_selection_exits_zero(tmp_path):
    completed = _python_m("run", "--vdec", FAKE_VDEC, "--problems", PROBLEMS, "--filter", "FX-SCALARS", "FX-SERIES",
                          "FX-SWEEP", "--level", "base", "--out", tmp_path / "out")
    assert completed.returncode == 0, completed.stdout + completed.stderr
    assert completed.stdout.strip().splitlines()[-1] == "3 passed, 0 failed"


@pytest.mark.requirements("REQ-QA-002")
def test_check_command_validates_without_running(tmp_path):
    code, stdout, _ = run_main("check", "--problems", PROBLEMS)
    assert code == 1
    assert "invalid  FX-BAD-TOML" in stdout and stdout.strip().splitlines()[-1] == "8 valid, 1 invalid"
    code, stdout, _ = run_main("check", "--problems", PROBLEMS, "--filter", "FX-S")
    assert code == 0 and stdout.strip().splitlines()[-1] == "3 valid, 0 invalid"

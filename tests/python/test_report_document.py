"""report.pdf read as a reader would (through pdftotext), junit.xml per check, and index.html's
links (REQ-QA-001).

The records are built from every real problem.toml with made-up numbers, so that every check
of every problem, its quantity, justification and variant, goes through the typesetting without
running vdec: the test then finds each check's numbers in the PDF's text. pdftotext is
poppler-utils (scripts/setup.sh installs it); without it the PDF tests are skipped.
"""
import json
import re
import shutil
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from vdec_verify.problem import ProblemError, load_problem
from vdec_verify.report import write_reports

ROOT = Path(__file__).resolve().parents[2]
PROBLEMS = ROOT / "verification" / "problems"
SOFTWARE = {"version": "9.8.7", "git_commit": "c0ffee" + "0" * 34, "build_type": "Release", "compiler": "GNU 12.2.0"}
pdftotext = pytest.mark.skipif(shutil.which("pdftotext") is None, reason="pdftotext (poppler-utils) is not installed")


def made_up_metric(check, serial):
    """A metric with numbers that cannot occur by accident in the rest of the document."""
    reference = 1.0 + serial * 0.013579
    numerical = reference * (1.0 + 1e-6 * (serial % 7 + 1))
    error = abs(numerical - reference) / reference
    tolerance = max(check.rtol, 1e-9) + check.atol
    return {"quantity": check.quantity, "variant": check.variant or None, "extract": check.extract["kind"],
            "norm": check.norm, "rtol": check.rtol, "atol": check.atol, "error": error, "tolerance": tolerance,
            "pass": error <= tolerance, "numerical": numerical, "reference": reference,
            "justification": check.justification, "message": ""}


def made_up_record(problem, serial):
    metrics = [made_up_metric(check, serial + i) for i, check in enumerate(problem.checks)]
    runs = [{"variant": run.name, "folder": "", "command": "", "exit_code": run.expect_exit,
             "expect_exit": run.expect_exit, "wall_seconds": 0.01, "cycles": 10, "stop_reason": "time",
             "software": dict(SOFTWARE), "message": ""} for run in problem.runs]
    status = "pass" if all(m["pass"] for m in metrics) else "fail"
    return {"id": problem.id, "title": problem.title, "requirements": problem.requirements, "level": problem.level,
            "status": status, "metrics": metrics, "runs": runs, "wall_seconds": 0.01 * len(runs), "cycles": 10,
            "scene_sha256": "ab" * 32, "exit_code": 0, "message": "", "messages": [],
            "inputs": {"verification/problems/" + problem.id + "/problem.toml": "cd" * 32}}


@pytest.fixture(scope="module")
def document(tmp_path_factory):
    records, serial = [], 0
    for folder in sorted(p for p in PROBLEMS.iterdir() if (p / "problem.toml").is_file()):
        try:
            problem = load_problem(folder / "problem.toml")
        except ProblemError as e:
            pytest.fail(f"the repository's problem does not load: {e}")
        records.append(made_up_record(problem, serial))
        serial += len(problem.checks)
    out = tmp_path_factory.mktemp("report")
    write_reports(records, out, level="full", problems_dir=PROBLEMS, revision="B")
    return {"records": records, "out": out}


def pdf_text(path):
    completed = subprocess.run(["pdftotext", str(path), "-"], capture_output=True, text=True, check=True)
    return completed.stdout


def flat(value):
    return re.sub(r"\s+", " ", value).strip()


def body_text(text):
    """The document's text without the running header and footer, whose lines fall between any two
    lines of a table or paragraph that continues on the next page."""
    kept = [line for line in text.splitlines()
            if not re.fullmatch(r"VDEC-VR-\S+|vdec verification report|page \d+ of \d+", line.strip())]
    return flat("\n".join(kept))


def wrapped_in(phrase, text, gap=40):
    """True when the words of phrase occur in text in order, each within `gap` characters of the
    one before: a table cell's wrapped lines come out with the next cells' words between them, and
    pdftotext drops a hyphen that ends a line and spaces between narrow glyphs (so both are
    compared without spaces and hyphens)."""
    def bare(value):
        return re.sub(r"[\s-]", "", value)

    flat_text = bare(text)
    words = [bare(w) for w in phrase.split() if bare(w)]
    start = flat_text.find(words[0])
    while start >= 0:
        at = start + len(words[0])
        for word in words[1:]:
            found = flat_text.find(word, at, at + gap + len(word))
            if found < 0:
                break
            at = found + len(word)
        else:
            return True
        start = flat_text.find(words[0], start + 1)
    return False


@pdftotext
@pytest.mark.requirements("REQ-QA-001")
def test_every_check_of_every_problem_appears_in_the_pdf_with_its_numbers(document):
    """pdftotext gives a table's cells in no fixed order, so each problem's section (from its heading
    to the next) must hold each check's quantity, justification and four numbers."""
    records = document["records"]
    assert len(records) >= 30 and max(len(r["metrics"]) for r in records) >= 20   # long tables must split
    text = body_text(pdf_text(document["out"] / "report.pdf"))
    text = text[text.index("4 Problems One section per problem"):]
    starts = [text.index(f"4.{n} {r['id']}: {r['status'].upper()} ") for n, r in enumerate(records, start=1)]
    starts.append(text.index("5 Convergence studies"))
    missing = []
    for r, start, end in zip(records, starts, starts[1:]):
        section = text[start:end]
        for n, m in enumerate(r["metrics"], start=1):
            wanted = {"quantity": flat(m["quantity"]), "justification": flat(m["justification"]),
                      "numerical": f"{m['numerical']:.10g}", "reference": f"{m['reference']:.10g}",
                      "error": f"{m['error']:.3e}", "tolerance": f"{m['tolerance']:.3e}"}
            if m["variant"]:
                wanted["variant"] = f"[{m['variant']}]"
            missing += [f"{r['id']} #{n} {key}: {value}" for key, value in wanted.items()
                        if value not in section and not (key == "quantity" and wrapped_in(value, section))]
    assert not missing, f"{len(missing)} missing, e.g. {missing[:5]}"


@pdftotext
@pytest.mark.requirements("REQ-QA-001")
def test_the_pdf_has_its_id_and_page_numbers_on_every_page_and_its_parts(document):
    text = pdf_text(document["out"] / "report.pdf")
    pages = [p for p in text.split("\f") if p.strip()]
    doc_id = f"VDEC-VR-FULL-{SOFTWARE['git_commit'][:12]}"
    for n, page in enumerate(pages, start=1):
        assert doc_id in page and f"page {n} of {len(pages)}" in page, n
    title = flat(pages[0])
    for field in ("document id", "revision B", "vdec 9.8.7", SOFTWARE["git_commit"], "summary.json SHA-256",
                  "operating system", "Python", "numpy", "scipy", "matplotlib", "prepared", "reviewed", "approved"):
        assert field in title, field
    whole = flat(text)
    assert "Contents" in whole
    for heading in ("1 Scope and pass rule", "2 Summary of results", "3 Requirement-to-evidence matrix",
                    "4 Problems", "5 Convergence studies", "6 Deviations and known limitations"):
        assert whole.count(heading) >= 2, heading      # in the contents and as a heading
    assert flat("A check passes when e_abs <= atol + rtol * s") in whole
    for requirement in ("REQ-GEOM-001", "REQ-QA-005", "REQ-ZONE-011"):
        assert requirement in whole
    # The known limitations come from docs/known-limitations.md, each with its source.
    assert "docs/models/" in whole and "Barton-Bandis" in whole


@pytest.mark.requirements("REQ-QA-001")
def test_junit_has_one_case_per_check_and_the_version_and_commit(document):
    root = ET.parse(document["out"] / "junit.xml").getroot()
    properties = {p.get("name"): p.get("value") for p in root.find("properties")}
    assert properties["vdec_version"] == "9.8.7" and properties["vdec_commit"] == SOFTWARE["git_commit"]
    assert properties["harness_commit"] and properties["level"] == "full"
    cases = root.findall("testcase")
    expected = [(f"verification.{r['id']}", n) for r in document["records"] for n in range(1, len(r["metrics"]) + 1)]
    assert [(c.get("classname"), int(c.get("name").split()[0][1:])) for c in cases] == expected
    assert root.get("tests") == str(len(expected))
    failing = [c for c in cases if c.find("failure") is not None]
    assert root.get("failures") == str(len(failing))
    wanted = sum(not m["pass"] for r in document["records"] for m in r["metrics"])
    assert len(failing) == wanted


@pytest.mark.requirements("REQ-QA-001")
def test_index_html_links_the_pdf_and_the_traceability_matrix(document):
    out = document["out"]
    page = (out / "index.html").read_text()
    assert '<a href="report.pdf">' in page
    link = re.search(r'<a href="([^"]*rtm\.html)">', page).group(1)
    assert (out / link).resolve() == ROOT / "reports" / "traceability" / "rtm.html"
    summary = json.loads((out / "summary.json").read_text())
    assert summary["harness"]["level"] == "full"


@pdftotext
@pytest.mark.requirements("REQ-QA-001")
def test_fields_other_parts_of_the_harness_add_are_shown(tmp_path, monkeypatch):
    """Tolerance basis, mutations and input hashes: fields the report does not know by name still
    reach the reader."""
    import vdec_verify.report as report
    problem = load_problem(PROBLEMS / "RB-TENSION" / "problem.toml")
    record = made_up_record(problem, 0)
    record["metrics"][0]["tolerance_basis"] = "derived"
    record["mutations"] = [{"name": "ks-half", "overrides": ["joint_material[0].ks=5e8"], "caught": True,
                            "rejected_by": ["#1"], "message": ""}]
    digest = "0123456789abcdef" * 4
    harness = report.harness_info()
    monkeypatch.setattr(report, "harness_info",
                        lambda configuration=None: dict(harness, inputs={"verification/problems/x": digest}))
    write_reports([record], tmp_path, level="full", problems_dir=PROBLEMS)
    whole = flat(pdf_text(tmp_path / "report.pdf"))
    assert "tolerance_basis: derived" in whole
    assert "name: ks-half; overrides: joint_material[0].ks=5e8; caught: True" in whole
    assert wrapped_in("harness.inputs.verification/problems/x", whole) and digest in whole


@pytest.mark.requirements("REQ-QA-001")
def test_a_failure_message_longer_than_a_page_does_not_stop_the_report(tmp_path):
    problem = load_problem(PROBLEMS / "RB-TENSION" / "problem.toml")
    record = made_up_record(problem, 0)
    record["status"], record["message"] = "fail", "run: exited 5 " + "(the energy monitor stopped it) " * 400
    record["metrics"][0].update(message="cannot extract: " + "no such history " * 500, **{"pass": False})
    write_reports([record], tmp_path, level="full", problems_dir=PROBLEMS)
    assert (tmp_path / "report.pdf").read_bytes().startswith(b"%PDF")
    if shutil.which("pdftotext") is not None:    # cut in the tables, given in full after them
        whole = flat(pdf_text(tmp_path / "report.pdf"))
        assert "(in full in section 4.1)" in whole and "(in full below the table)" in whole
        assert "no such history " * 499 in whole + " "

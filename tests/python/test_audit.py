"""Tests of the traceability audit (qa/traceability/audit.py).

Each test copies the clean fixture repository tests/python/fixtures/audit/clean into tmp_path,
breaks one link, runs the audit and looks for the gap. The clean fixture has one component
(docs with the ten NUREG-0856 subsections), three requirements, one verification problem, a
summary.json and two JUnit files (GoogleTest and pytest, with a parametrized case).
"""
import json
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

import audit

FIXTURE = Path(__file__).parent / "fixtures" / "audit" / "clean"
AUDIT = Path(audit.__file__)
REQS = "qa/traceability/requirements.toml"
DOCS = "docs/models/widget.md"
SUMMARY = "reports/verification/summary.json"
GTEST = "reports/tests/gtest-unit.xml"
PYTEST = "reports/tests/pytest.xml"
PROBLEM = "verification/problems/WID-SWING/problem.toml"

pytestmark = pytest.mark.requirements("REQ-QA-004")
CONFIGURATION_CONTROL = pytest.mark.requirements("REQ-CM-001")
COMPONENT_TABLE = pytest.mark.requirements("REQ-QA-009")


def as_test_suite(root):
    """Options that judge the fixture's summary as the test suite's base-level evidence."""
    return ("--mode", "test-suite", "--summary", str(root / SUMMARY), "--junit", str(root / "reports/tests/*.xml"),
            "--out", str(root / "reports/traceability"))


FIXTURE_COMMIT = "1111111111111111111111111111111111111111"


def git(root, *args):
    command = ["git", "-C", str(root), "-c", "user.name=t", "-c", "user.email=t@t", "-c", "commit.gpgsign=false"]
    return subprocess.run(command + list(args), capture_output=True, text=True, check=True).stdout.strip()


@pytest.fixture
def repo(tmp_path):
    """The clean fixture as a git checkout whose summary.json names its HEAD: evidence of the
    current commit, as the configuration-control rules demand. The reports are ignored, as in
    the real repository, so that writing them leaves the checkout clean."""
    root = tmp_path / "repo"
    shutil.copytree(FIXTURE, root)
    git(root, "init", "-q")
    (root / ".git/info/exclude").write_text("/reports/\n")
    git(root, "add", "-A")
    git(root, "commit", "-qm", "fixture")
    edit(root, SUMMARY, FIXTURE_COMMIT, git(root, "rev-parse", "HEAD"), count=2)
    return root


def edit(root, rel, old, new, count=1):
    """Replace text in a fixture file, insisting the text is there (a silent no-op would make
    a gap test pass for the wrong reason)."""
    path = root / rel
    text = path.read_text()
    assert text.count(old) >= count, f"{old!r} not in {rel}"
    path.write_text(text.replace(old, new, count))


def run(root, capsys, *extra):
    code = audit.main(["--root", str(root), *extra])
    out = capsys.readouterr()
    return code, out.out + out.err


def gaps_of(root, capsys, *extra):
    """Run the audit, expect failure, and return the full gap list from rtm.html."""
    code, out = run(root, capsys, *extra)
    assert code == 1, out
    assert "audit: FAIL (" in out
    page = (root / "reports/traceability/rtm.html").read_text()
    return out, page


def test_clean_fixture_passes_and_writes_both_reports(repo, capsys):
    code, out = run(repo, capsys)
    assert code == 0, out
    assert out.rstrip().splitlines()[-1] == "audit: PASS (3 requirements, 1 problems, 5 tests, 0 gaps)"
    rows = (repo / "reports/traceability/rtm.csv").read_text().splitlines()
    assert rows[0] == "requirement,component,text,source,docs,code,evidence_kind,evidence_id,status"
    assert len(rows) == 1 + 5
    assert all(row.endswith(",pass") for row in rows[1:])
    assert any(",problem,WID-SWING,pass" in row for row in rows)
    # The parametrized pytest case is listed under its base name.
    assert any(",test,pytest:test_widget.test_step_sizes,pass" in row for row in rows)
    page = (repo / "reports/traceability/rtm.html").read_text()
    assert "<h2>Gaps</h2><ul><li>none</li></ul>" in page
    assert "REQ-WIDGET-001" in page and "Derivation of the numerical method" in page
    assert git(repo, "rev-parse", "HEAD") in page     # the summary's commit is stated
    assert "<link" not in page and "<script" not in page          # self-contained


def test_command_line_exit_codes_and_speed(repo, tmp_path):
    start = time.monotonic()
    ok = subprocess.run([sys.executable, str(AUDIT), "--root", str(repo), "--out", str(tmp_path / "o")],
                        capture_output=True, text=True)
    assert ok.returncode == 0, ok.stdout + ok.stderr
    assert (tmp_path / "o/rtm.csv").is_file() and (tmp_path / "o/rtm.html").is_file()
    edit(repo, SUMMARY, '"status": "pass"', '"status": "fail"')
    bad = subprocess.run([sys.executable, str(AUDIT), "--root", str(repo)], capture_output=True, text=True)
    assert bad.returncode == 1
    assert "audit: FAIL (" in bad.stdout
    assert time.monotonic() - start < 10


def test_unreadable_requirements_file_is_an_input_error_naming_file_and_line(repo, capsys):
    edit(repo, REQS, 'title = "Widget model"', 'title = "Widget model')
    code, out = run(repo, capsys)
    assert code == 2
    assert "requirements.toml" in out and "line 5" in out
    assert not (repo / "reports/traceability/rtm.csv").exists()


def test_missing_requirements_file_is_an_input_error(repo, capsys):
    code, out = run(repo, capsys, "--requirements", str(repo / "nope.toml"))
    assert code == 2 and "nope.toml" in out


# ------------------------------------------------------------ requirement gaps

REQ1_DOCS = 'docs = "docs/models/widget.md#law-of-swing"'

REQUIREMENT_GAPS = {
    "bad id": ('id = "REQ-WIDGET-001"', 'id = "REQ-Widget-1"', "REQ-Widget-1: bad id"),
    "duplicate id": ('id = "REQ-WIDGET-002"', 'id = "REQ-WIDGET-001"', "REQ-WIDGET-001: duplicate id"),
    # Case and white space are folded before comparing texts.
    "duplicate text": ('"The widget time step is FRAC 2 sqrt(m / k)."',
                       '"the widget  SWINGS by the central-difference law."',
                       "REQ-WIDGET-002: same text as REQ-WIDGET-001"),
    "empty source": ('source = "NUREG/CR-5429 1.3-10"', 'source = "  "', "REQ-WIDGET-001: no source"),
    "unknown component": ('component = "widget"', 'component = "gadget"',
                          "REQ-WIDGET-001: unknown component 'gadget'"),
    "docs file missing": (REQ1_DOCS, 'docs = "docs/models/gadget.md#law-of-swing"',
                          "REQ-WIDGET-001: docs file docs/models/gadget.md does not exist"),
    "docs anchor missing": (REQ1_DOCS, 'docs = "docs/models/widget.md#law-of-motion"',
                            "REQ-WIDGET-001: docs anchor #law-of-motion not found"),
    "code file missing": ('code = ["src/widget.cpp", ', 'code = ["src/gadget.cpp", ',
                          "REQ-WIDGET-001: code file src/gadget.cpp does not exist"),
    "code symbol missing": ('"src/widget.cpp:swingWidget"', '"src/widget.cpp:swingGadget"',
                            "REQ-WIDGET-001: symbol 'swingGadget' not found in src/widget.cpp"),
    # A symbol must occur as a whole word, not inside a longer name.
    "code symbol only as part of a name": ('"src/widget.cpp:swingWidget"', '"src/widget.cpp:swingWid"',
                                           "REQ-WIDGET-001: symbol 'swingWid' not found"),
    "problem does not exist": ('problems = ["WID-SWING"]', 'problems = ["WID-SWING", "WID-NONE"]',
                               "REQ-WIDGET-001: problem WID-NONE does not exist"),
    "test not in the results": ('tests = ["gtest:Widget.SwingsByCentralDifference"]',
                                'tests = ["gtest:Widget.SwingsByCentralDifference", "gtest:Widget.Missing"]',
                                "REQ-WIDGET-001: test gtest:Widget.Missing not found in the test results"),
    "test does not name the requirement": (
        'tests = ["pytest:test_widget.test_known_values"]',
        'tests = ["pytest:test_widget.test_known_values", "gtest:Widget.TimeStep"]',
        "REQ-QA-001: test gtest:Widget.TimeStep does not name it"),
    "no evidence listed": ('tests = ["pytest:test_widget.test_known_values"]', 'tests = []',
                           "REQ-QA-001: no evidence"),
}


def assert_edit_gives_gap(repo, capsys, old, new, gap):
    """Edit the requirements file and expect the audit to fail with the gap."""
    edit(repo, REQS, old, new)
    out, _ = gaps_of(repo, capsys)
    assert gap in out


@pytest.mark.parametrize("old,new,gap", REQUIREMENT_GAPS.values(), ids=REQUIREMENT_GAPS.keys())
def test_requirement_gap_is_detected(repo, capsys, old, new, gap):
    assert_edit_gives_gap(repo, capsys, old, new, gap)


def test_problem_that_does_not_list_the_requirement_back(repo, capsys):
    edit(repo, PROBLEM, 'requirements = ["REQ-WIDGET-001"]', 'requirements = ["REQ-WIDGET-002"]')
    out, _ = gaps_of(repo, capsys)
    assert "REQ-WIDGET-001: problem WID-SWING does not list it" in out


def test_requirement_whose_only_evidence_failed(repo, capsys):
    # REQ-QA-001's only evidence is one pytest case; make it fail.
    edit(repo, PYTEST, 'name="test_known_values" file="tests/python/test_widget.py" line="8" time="0.001">',
         'name="test_known_values" file="tests/python/test_widget.py" line="8" time="0.001">'
         '<failure message="assert 1 == 2">assert 1 == 2</failure>')
    out, page = gaps_of(repo, capsys)
    assert "REQ-QA-001: no passing evidence" in out
    assert "test pytest:test_widget.test_known_values: failed (REQ-QA-001)" in out
    rows = (repo / "reports/traceability/rtm.csv").read_text().splitlines()
    assert any(r.startswith("REQ-QA-001,") and r.endswith(",test,pytest:test_widget.test_known_values,fail")
               for r in rows)


def test_requirement_whose_only_problem_failed(repo, capsys):
    edit(repo, REQS, 'tests = ["gtest:Widget.SwingsByCentralDifference"]', "tests = []")
    edit(repo, SUMMARY, '"status": "pass"', '"status": "invalid"')
    out, _ = gaps_of(repo, capsys)
    assert "REQ-WIDGET-001: no passing evidence" in out
    assert "problem WID-SWING: status invalid in summary.json (REQ-WIDGET-001)" in out
    assert "REQ-WIDGET-001,widget" in (repo / "reports/traceability/rtm.csv").read_text()


def test_one_failed_instance_fails_a_parametrized_test(repo, capsys):
    edit(repo, PYTEST, 'name="test_step_sizes[0.5]" file="tests/python/test_widget.py" line="20" time="0.001">',
         'name="test_step_sizes[0.5]" file="tests/python/test_widget.py" line="20" time="0.001">'
         '<failure message="x">x</failure>')
    edit(repo, REQS, '"gtest:Widget.TimeStep", ', "")
    out, _ = gaps_of(repo, capsys)
    assert "test pytest:test_widget.test_step_sizes[0.5]: failed (REQ-WIDGET-002)" in out
    assert "REQ-WIDGET-002: no passing evidence" in out
    assert ",test,pytest:test_widget.test_step_sizes,fail" in (repo / "reports/traceability/rtm.csv").read_text()


def test_skipped_test_is_not_passing_evidence(repo, capsys):
    edit(repo, PYTEST, 'line="8" time="0.001">', 'line="8" time="0.001"><skipped message="no data"/>')
    out, _ = gaps_of(repo, capsys)
    assert "REQ-QA-001: no passing evidence" in out
    assert "warning: test pytest:test_widget.test_known_values was skipped" in out
    assert ",test,pytest:test_widget.test_known_values,not run" in (repo / "reports/traceability/rtm.csv").read_text()


# ------------------------------------------------------------ problem gaps

@pytest.mark.parametrize("old,new,gap", [
    ('requirements = ["REQ-WIDGET-001"]', "requirements = []", "problem WID-SWING: names no requirement"),
    ('requirements = ["REQ-WIDGET-001"]', 'requirements = ["REQ-WIDGET-001", "REQ-WIDGET-009"]',
     "problem WID-SWING: names requirement REQ-WIDGET-009, which does not exist"),
], ids=["names no requirement", "names a nonexistent requirement"])
def test_problem_gap_is_detected(repo, capsys, old, new, gap):
    edit(repo, PROBLEM, old, new)
    out, _ = gaps_of(repo, capsys)
    assert gap in out


@pytest.mark.requirements("REQ-QA-004", "REQ-CM-001")
def test_problem_missing_from_summary_is_not_run(repo, capsys):
    folder = repo / "verification/problems/WID-EXTRA"
    folder.mkdir()
    (folder / "problem.toml").write_text('id = "WID-EXTRA"\nrequirements = ["REQ-WIDGET-001"]\nlevel = "full"\n')
    edit(repo, REQS, 'problems = ["WID-SWING"]', 'problems = ["WID-SWING", "WID-EXTRA"]')
    out, _ = gaps_of(repo, capsys)
    assert "problem WID-EXTRA: not in summary.json: not run (level = 'full')" in out
    assert ",problem,WID-EXTRA,not run" in (repo / "reports/traceability/rtm.csv").read_text()
    # The test suite's base level leaves a full-level problem out by design: a warning there.
    edit(repo, SUMMARY, '"level": "full"', '"level": "base"')
    code, out = run(repo, capsys, *as_test_suite(repo))
    assert code == 0, out
    assert "warning: problem WID-EXTRA (level 'full') is not in this base-level summary" in out


# ------------------------------------------------------------ test gaps

def test_test_naming_no_requirement(repo, capsys):
    edit(repo, GTEST, """
      <properties>
        <property name="requirements" value="REQ-WIDGET-002"/>
      </properties>""", "")
    out, _ = gaps_of(repo, capsys)
    assert "test gtest:Widget.TimeStep: names no requirement" in out
    assert "REQ-WIDGET-002: test gtest:Widget.TimeStep does not name it" in out


def test_test_naming_a_nonexistent_requirement(repo, capsys):
    edit(repo, GTEST, 'value="REQ-WIDGET-002"', 'value="REQ-WIDGET-002, REQ-WIDGET-077"')
    out, _ = gaps_of(repo, capsys)
    assert "test gtest:Widget.TimeStep: names requirement REQ-WIDGET-077, which does not exist" in out


def test_failed_gtest_is_reported_against_its_requirements(repo, capsys):
    edit(repo, GTEST, 'line="12" status="run" result="completed" time="0" classname="Widget">',
         'line="12" status="run" result="completed" time="0" classname="Widget">'
         '<failure message="Expected equality" type=""/>')
    out, page = gaps_of(repo, capsys)
    assert "test gtest:Widget.TimeStep: failed (REQ-WIDGET-002)" in out
    # REQ-WIDGET-002 still has a passing pytest case, so the failure is its only gap there.
    assert "REQ-WIDGET-002: no passing evidence" not in out
    assert "<span class='gap'>1 gap</span>" in page


# ------------------------------------------------------------ component gaps

@pytest.mark.parametrize("heading", ["## 1. Purpose", "## 2. Assumptions and limitations", "## 3. Notation",
                                     "## 4. Derivation", "## 5. Application", "## 6. Numerical method type",
                                     "## 7. Derivation of the numerical method", "## 8. Location in the code",
                                     "## 9. Numerical stability and accuracy",
                                     "## 10. Alternatives {#custom-anchor}"],
                         ids=lambda h: h.split(". ", 1)[1].split(" {#")[0])
def test_missing_docs_subsection(repo, capsys, heading):
    # Demote the heading to plain text so the section's words stay but the heading is gone.
    edit(repo, DOCS, heading + "\n", heading.lstrip("# ").split(" {#")[0] + " (not a heading)\n")
    edit(repo, REQS, "#custom-anchor", "#widget-step")     # keep requirement anchors valid
    out, page = gaps_of(repo, capsys)
    name = heading.split(". ", 1)[1].split(" {#")[0]
    assert f"component widget: {DOCS} lacks the subsection '{name}'" in out
    assert out.count("lacks the subsection") == 1     # "Derivation" and its numerical twin stay distinct


def test_empty_docs_subsection(repo, capsys):
    edit(repo, DOCS, "Rigid widget.\n", "")
    out, page = gaps_of(repo, capsys)
    assert "component widget: docs/models/widget.md line 7: empty report section '2. Assumptions and limitations'" \
        in out
    assert "Assumptions and limitations: <span class='gap'>empty</span>" in page


def test_section_with_an_empty_subsection_only_is_empty_too(repo, capsys):
    edit(repo, DOCS, "v(t + dt/2) = v(t - dt/2) + a dt.\n", "<!-- to do -->\n")
    out, _ = gaps_of(repo, capsys)
    assert "empty report section 'Law of swing'" in out
    assert "empty report section '7. Derivation of the numerical method'" in out


def test_component_docs_file_missing(repo, capsys):
    edit(repo, REQS, 'docs = "docs/models/widget.md"\n', 'docs = "docs/models/gadget.md"\n')
    out, _ = gaps_of(repo, capsys)
    assert "component widget: docs file docs/models/gadget.md does not exist" in out


def test_component_with_no_requirement(repo, capsys):
    edit(repo, REQS, '[[requirement]]', '[[component]]\nid = "spare"\ntitle = "Spare"\n'
         'docs = "docs/models/widget.md"\nsource = ["src"]\nrequirement_prefixes = ["REQ-SPARE"]\n'
         'problem_prefixes = []\n\n[[requirement]]')
    out, _ = gaps_of(repo, capsys)
    assert "component spare: no requirement names this component" in out


# ------------------------------------------------------------ the component table
# The fixture's table: widget (a component model: source src, REQ-WIDGET, WID-), qa
# (cross-cutting: REQ-QA, no problem prefix, docs/qa.md without the ten subsections) and flow
# (reserved: REQ-FLOW, FLOW-, its folder and docs page do not exist).

WIDGET_TABLE = 'docs = "docs/models/widget.md"\nsource = ["src"]\nrequirement_prefixes = ["REQ-WIDGET"]\nproblem_prefixes = ["WID-"]\n'
QA_TABLE = 'requirement_prefixes = ["REQ-QA"]\nproblem_prefixes = []\ncross_cutting = true\n'
FLOW_TABLE = 'problem_prefixes = ["FLOW-"]\nreserved = true\n'


def add_problem(root, pid, requirements):
    folder = root / "verification/problems" / pid
    folder.mkdir()
    (folder / "problem.toml").write_text(f'id = "{pid}"\nrequirements = {json.dumps(requirements)}\n')


def add_requirement(root, rid, component):
    path = root / REQS
    path.write_text(path.read_text() + f'\n[[requirement]]\nid = "{rid}"\ncomponent = "{component}"\n'
                    'text = "Joint apertures follow the cubic law."\nsource = "NUREG/CR-5429 1.4.2"\n'
                    'docs = "docs/models/widget.md#law-of-swing"\ncode = ["src/widget.cpp:swingWidget"]\n'
                    'problems = []\ntests = ["gtest:Widget.TimeStep"]\n')


@COMPONENT_TABLE
def test_the_clean_table_has_no_gap_and_no_warning(repo, capsys):
    code, out = run(repo, capsys)
    assert code == 0, out
    assert "warning" not in out
    page = (repo / "reports/traceability/rtm.html").read_text()
    # The reserved component is listed, with its prefixes, and its missing page and folder are no gap.
    assert "<b>flow</b>" in page and "<code>REQ-FLOW</code>" in page and "reserved: not checked" in page
    assert "cross-cutting: not a component model" in page


@COMPONENT_TABLE
@pytest.mark.parametrize("line", ['title = "Widget model"\n', 'docs = "docs/models/widget.md"\n', 'source = ["src"]\n',
                                  'requirement_prefixes = ["REQ-WIDGET"]\n', 'problem_prefixes = ["WID-"]\n'],
                         ids=lambda line: line.split(" =")[0])
def test_component_lacking_a_key(repo, capsys, line):
    edit(repo, REQS, line, "")          # the first occurrence is the widget component's
    out, _ = gaps_of(repo, capsys)
    key = line.split(" =")[0]
    assert f"component widget: no '{key}': add it, giving " in out


# Edits of the fixture's requirements.toml, each with the gap it must give.
COMPONENT_TABLE_GAPS = {
    "source not a list": ('source = ["src"]', 'source = "src"', "component widget: 'source' must be a list of strings"),
    "source empty": ('source = ["src"]', "source = []", "component widget: 'source' is empty: give the folders it owns"),
    "no requirement prefix": ('requirement_prefixes = ["REQ-WIDGET"]', "requirement_prefixes = []",
                              "component widget: 'requirement_prefixes' is empty: give the REQ-AREA"),
    "cross_cutting not a boolean": ("cross_cutting = true", 'cross_cutting = "yes"',
                                    "component qa: 'cross_cutting' must be true or false"),
    "reserved not a boolean": ("reserved = true", "reserved = 1", "component flow: 'reserved' must be true or false"),
    "requirement prefix in lower case": ('["REQ-WIDGET"]', '["REQ-WIDGET", "REQ-Gizmo"]',
                                         "component widget: requirement prefix 'REQ-Gizmo' is not of the form "
                                         "'REQ-FLOW'"),
    "requirement prefix ending in a hyphen": ('["REQ-WIDGET"]', '["REQ-WIDGET", "REQ-GIZMO-"]',
                                              "component widget: requirement prefix 'REQ-GIZMO-' is not of the form"),
    "problem prefix without hyphen": ('["WID-"]', '["WID-", "GIZ"]',
                                      "component widget: problem prefix 'GIZ' is not of the form 'FLOW-'"),
    "problem prefix of two words": ('["WID-"]', '["WID-", "GIZ-SPIN-"]',
                                    "component widget: problem prefix 'GIZ-SPIN-' is not of the form 'FLOW-'"),
    "requirement prefix of two components": ('requirement_prefixes = ["REQ-QA"]',
                                             'requirement_prefixes = ["REQ-QA", "REQ-WIDGET"]',
                                             "component qa: requirement prefix REQ-WIDGET is also component widget's"),
    "problem prefix of two components": ('problem_prefixes = ["FLOW-"]', 'problem_prefixes = ["FLOW-", "WID-"]',
                                         "component flow: problem prefix WID- is also component widget's"),
    "requirement in another prefix's component": (
        'id = "REQ-QA-001"\ncomponent = "qa"', 'id = "REQ-QA-001"\ncomponent = "widget"',
        "REQ-QA-001: its id prefix REQ-QA is component qa's, but it is component widget's: set component = \"qa\""),
    "requirement with no component": (
        'id = "REQ-QA-001"\ncomponent = "qa"\n', 'id = "REQ-QA-001"\n',
        "REQ-QA-001: its id prefix REQ-QA is component qa's, but it names no component: set component = \"qa\""),
    "requirement with a bad id and no component": (
        'id = "REQ-QA-001"\ncomponent = "qa"\n', 'id = "REQ-QA-1"\n',
        "REQ-QA-1: no component: set component to the id of the component it belongs to"),
    "requirement prefix no component's": (
        'requirement_prefixes = ["REQ-QA"]', 'requirement_prefixes = ["REQ-CM"]',
        "REQ-QA-001: its id prefix REQ-QA is no component's: add 'REQ-QA' to the requirement_prefixes of the "
        "component it belongs to"),
    "source folder missing": ('source = ["src"]', 'source = ["src", "src/gizmo"]',
                              "component widget: source folder src/gizmo does not exist"),
    "uses names no component": (WIDGET_TABLE, WIDGET_TABLE + 'uses = ["gizmo"]\n',
                                "component widget: 'uses' names 'gizmo', which is not another component"),
    "uses names itself": (WIDGET_TABLE, WIDGET_TABLE + 'uses = ["widget"]\n',
                          "component widget: 'uses' names 'widget', which is not another component"),
    # Only a cross-cutting component's page is exempt from the ten subsections.
    "not cross-cutting": (QA_TABLE, QA_TABLE.replace("cross_cutting = true\n", ""),
                          "component qa: docs/qa.md lacks the subsection 'Purpose'"),
    "source folder a file": ('source = ["src"]', 'source = ["src/widget.cpp"]',
                             "component widget: source folder src/widget.cpp does not exist"),
}


@COMPONENT_TABLE
@pytest.mark.parametrize("old,new,gap", COMPONENT_TABLE_GAPS.values(), ids=COMPONENT_TABLE_GAPS.keys())
def test_component_table_gap_is_detected(repo, capsys, old, new, gap):
    assert_edit_gives_gap(repo, capsys, old, new, gap)


@COMPONENT_TABLE
def test_requirement_of_a_reserved_prefix_says_to_unreserve(repo, capsys):
    add_requirement(repo, "REQ-FLOW-001", "flow")
    out, _ = gaps_of(repo, capsys)
    assert ("REQ-FLOW-001: its id prefix REQ-FLOW is reserved: un-reserve component flow (delete reserved = true) "
            "and complete its entry") in out
    edit(repo, REQS, 'id = "REQ-FLOW-001"\ncomponent = "flow"', 'id = "REQ-FLOW-001"\ncomponent = "widget"')
    out, _ = gaps_of(repo, capsys)
    assert 'REQ-FLOW-001: its id prefix REQ-FLOW is reserved: un-reserve component flow' in out
    assert 'then set component = "flow"' in out


@COMPONENT_TABLE
def test_unreserving_a_component_asks_for_its_folders_page_and_requirements(repo, capsys):
    edit(repo, REQS, FLOW_TABLE, FLOW_TABLE.replace("reserved = true\n", ""))
    out, _ = gaps_of(repo, capsys)
    assert "component flow: no requirement names this component" in out
    assert "component flow: source folder src/flow does not exist: create it or correct 'source'" in out
    assert "component flow: docs file docs/models/flow.md does not exist" in out


@COMPONENT_TABLE
@pytest.mark.parametrize("pid,gap", [
    ("GIZ-SPIN", "problem GIZ-SPIN: its id starts with no component's problem prefix (FLOW-, WID-): name it with "
                 "the prefix of the component it verifies"),
    ("FLOW-SEEP", "problem FLOW-SEEP: its id prefix FLOW- is reserved: un-reserve component flow"),
], ids=["prefix no component's", "reserved prefix"])
def test_problem_prefix_gap(repo, capsys, pid, gap):
    add_problem(repo, pid, ["REQ-WIDGET-001"])
    out, _ = gaps_of(repo, capsys)
    assert gap in out


@COMPONENT_TABLE
def test_problem_naming_a_requirement_of_another_component(repo, capsys):
    # qa is cross-cutting: any problem may name its requirements. (The edit changes an input of
    # the stored run, which is a gap of its own.)
    edit(repo, PROBLEM, 'requirements = ["REQ-WIDGET-001"]', 'requirements = ["REQ-WIDGET-001", "REQ-QA-001"]')
    out, _ = gaps_of(repo, capsys)
    assert "problem WID-SWING: input verification/problems/WID-SWING/problem.toml differs" in out
    assert "problem WID-SWING: names REQ-QA-001" not in out
    # A component model's requirements: only the component's own problems, or those of a component using it.
    edit(repo, REQS, QA_TABLE, QA_TABLE.replace("cross_cutting = true\n", ""))
    out, _ = gaps_of(repo, capsys)
    assert ("problem WID-SWING: names REQ-QA-001 of component qa, but its prefix WID- is component widget's: "
            "add \"qa\" to widget's uses") in out
    edit(repo, REQS, WIDGET_TABLE, WIDGET_TABLE + 'uses = ["qa"]\n')
    out, page = gaps_of(repo, capsys)       # qa's docs still lack the ten subsections
    assert "problem WID-SWING: names REQ-QA-001" not in out
    assert "(model)<br>uses qa</td>" in page


@COMPONENT_TABLE
def test_legacy_requirement_keeps_its_id_in_another_component(repo, capsys):
    edit(repo, REQS, 'id = "REQ-WIDGET-002"\ncomponent = "widget"', 'id = "REQ-WIDGET-002"\ncomponent = "qa"')
    out, _ = gaps_of(repo, capsys)
    assert "REQ-WIDGET-002: its id prefix REQ-WIDGET is component widget's, but it is component qa's" in out
    edit(repo, REQS, QA_TABLE, QA_TABLE + 'legacy_requirements = ["REQ-WIDGET-002"]\n')
    code, out = run(repo, capsys)
    assert code == 0, out
    assert "<br>legacy REQ-WIDGET-002</td>" in (repo / "reports/traceability/rtm.html").read_text()
    # Listed, but left in the component of its prefix.
    edit(repo, REQS, 'id = "REQ-WIDGET-002"\ncomponent = "qa"', 'id = "REQ-WIDGET-002"\ncomponent = "widget"')
    out, _ = gaps_of(repo, capsys)
    assert ("REQ-WIDGET-002: component qa lists it in legacy_requirements, but it is component widget's: "
            "set component = \"qa\"") in out


@COMPONENT_TABLE
@pytest.mark.parametrize("legacy,gap", [
    ('["REQ-WIDGET-009"]', "component qa: legacy_requirements names REQ-WIDGET-009, which does not exist"),
    ('["REQ-QA-001"]', "component qa: legacy_requirements names REQ-QA-001, whose prefix REQ-QA is the "
                       "component's own: remove it"),
], ids=["nonexistent", "own prefix"])
def test_legacy_requirement_gaps(repo, capsys, legacy, gap):
    edit(repo, REQS, QA_TABLE, QA_TABLE + f"legacy_requirements = {legacy}\n")
    out, _ = gaps_of(repo, capsys)
    assert gap in out


@COMPONENT_TABLE
def test_legacy_requirement_claimed_by_two_components(repo, capsys):
    edit(repo, REQS, QA_TABLE, QA_TABLE + 'legacy_requirements = ["REQ-WIDGET-002"]\n')
    edit(repo, REQS, FLOW_TABLE, FLOW_TABLE + 'legacy_requirements = ["REQ-WIDGET-002"]\n')
    edit(repo, REQS, 'id = "REQ-WIDGET-002"\ncomponent = "widget"', 'id = "REQ-WIDGET-002"\ncomponent = "qa"')
    out, _ = gaps_of(repo, capsys)
    assert "component flow: legacy_requirements names REQ-WIDGET-002, which component qa lists too" in out


@COMPONENT_TABLE
def test_code_outside_the_components_folders_is_a_warning(repo, capsys):
    edit(repo, REQS, 'code = ["src/widget.cpp", ', 'code = ["verification/harness/vdec_verify/__init__.py", '
         '"verification/harness/vdec_verify/__init__.py:stand-in", "src/widget.cpp", ')
    code, out = run(repo, capsys)
    assert code == 0, out
    warning = ("warning: REQ-WIDGET-001: code verification/harness/vdec_verify/__init__.py lies outside the source "
               "folders of component widget (src)")
    assert out.count(warning) == 1      # once per file, however many symbols it lists
    # A folder is matched whole: src/widget.cpp does not lie in a folder named "src/wid".
    edit(repo, REQS, 'source = ["src"]', 'source = ["src/wid"]')
    out, _ = gaps_of(repo, capsys)
    assert "warning: REQ-WIDGET-001: code src/widget.cpp lies outside the source folders of component widget" in out


# ------------------------------------------------------------ summary and commits

@pytest.mark.parametrize("content", [None, '{"schema": "vdec.verification/0", "problems": []}', "{not json"],
                         ids=["missing", "wrong schema", "unreadable"])
def test_summary_missing_or_wrong_schema(repo, capsys, content):
    if content is None:
        (repo / SUMMARY).unlink()
    else:
        (repo / SUMMARY).write_text(content)
    out, page = gaps_of(repo, capsys)
    assert "verification summary: reports/verification/summary.json" in out
    assert ",problem,WID-SWING,not run" in (repo / "reports/traceability/rtm.csv").read_text()


@CONFIGURATION_CONTROL
def test_summary_from_another_commit_is_a_gap_in_both_modes(repo, capsys):
    head = git(repo, "rev-parse", "HEAD")
    edit(repo, SUMMARY, head, FIXTURE_COMMIT, count=2)
    out, _ = gaps_of(repo, capsys)
    assert f"summary.json software.git_commit {FIXTURE_COMMIT} differs from HEAD {head}" in out
    assert f"summary.json harness.git_commit {FIXTURE_COMMIT} differs from HEAD {head}" in out
    edit(repo, SUMMARY, '"level": "full"', '"level": "base"')
    out, _ = gaps_of(repo, capsys, *as_test_suite(repo))
    assert f"software.git_commit {FIXTURE_COMMIT} differs from HEAD {head}" in out


@CONFIGURATION_CONTROL
def test_summary_of_the_other_level_is_a_gap(repo, capsys):
    edit(repo, SUMMARY, '"level": "full"', '"level": "base"')
    out, _ = gaps_of(repo, capsys)
    assert "summary.json is of level 'base'; the qualification audit judges level 'full' evidence" in out
    edit(repo, SUMMARY, '"level": "base"', '"level": "full"')
    out, _ = gaps_of(repo, capsys, *as_test_suite(repo))
    assert "summary.json is of level 'full'; the test-suite audit judges level 'base' evidence" in out


@CONFIGURATION_CONTROL
@pytest.mark.parametrize("old,new,gap", [
    ('"git_dirty": false', '"git_dirty": true', "harness.git_dirty is True: the suite ran with uncommitted changes"),
    ('"compiler"', '"git_dirty_note": "x", "compiler"', None),   # no change of meaning: still clean
], ids=["dirty harness", "control"])
def test_evidence_of_uncommitted_work_fails_qualification_and_warns_the_test_suite(repo, capsys, old, new, gap):
    edit(repo, SUMMARY, old, new)
    if gap is None:
        code, out = run(repo, capsys)
        assert code == 0, out
        return
    out, _ = gaps_of(repo, capsys)
    assert gap in out
    edit(repo, SUMMARY, '"level": "full"', '"level": "base"')
    code, out = run(repo, capsys, *as_test_suite(repo))
    assert code == 0, out
    assert "warning: verification summary: summary.json " + gap.split(": ", 1)[0] in out


@CONFIGURATION_CONTROL
def test_evidence_outside_a_git_checkout_fails_qualification_and_warns_the_test_suite(repo, capsys):
    shutil.rmtree(repo / ".git")
    edit(repo, SUMMARY, '"git_commit": "', '"git_commit": "unknown", "old_commit": "')
    out, _ = gaps_of(repo, capsys)
    assert "harness.git_commit" in out and "cannot be compared: current commit unknown (not a git checkout)" in out
    assert "summary.json software.git_commit is 'unknown': no commit identifies the evidence" in out
    edit(repo, SUMMARY, '"level": "full"', '"level": "base"')
    code, out = run(repo, capsys, *as_test_suite(repo))
    assert code == 0, out
    assert "cannot be compared: current commit unknown" in out and "is 'unknown'" in out


@CONFIGURATION_CONTROL
def test_software_built_from_uncommitted_changes_fails_qualification(repo, capsys):
    head = git(repo, "rev-parse", "HEAD")
    edit(repo, SUMMARY, f'"git_commit": "{head}",\n  "build_type"', f'"git_commit": "{head}-dirty",\n  "build_type"')
    out, _ = gaps_of(repo, capsys)
    assert f"summary.json software.git_commit {head}-dirty: built from uncommitted changes" in out


CONFIGURATION_GAPS = {
    "problems folder outside the repository": (
        '"problems_dir": "verification/problems", "problems_dir_in_repository": true',
        '"problems_dir": "/tmp/copy/problems", "problems_dir_in_repository": false',
        "verification summary: the problems folder /tmp/copy/problems is outside the repository"),
    "filter": ('"filter": []', '"filter": ["WID"]',
               "verification summary: the suite ran only the problems matching the filter ['WID']"),
    "no configuration recorded (an older harness)": (
        '"problems_dir_in_repository": true,', '',
        "summary.json does not record the run's configuration"),
    "no inputs recorded for a problem": ('"inputs": {', '"inputs_old": {',
                                         "problem WID-SWING: summary.json records no input hashes"),
    "input not readable when the suite ran": (
        '"verification/problems/WID-SWING/swing.csv": "', '"verification/problems/WID-SWING/swing.csv": null, "x": "',
        "problem WID-SWING: input verification/problems/WID-SWING/swing.csv was not found"),
}


def compact(repo):
    """The fixture summary on one line per object, so that edits can span keys."""
    path = repo / SUMMARY
    text = json.dumps(json.loads(path.read_text()))
    path.write_text(text)


@CONFIGURATION_CONTROL
@pytest.mark.parametrize("old,new,gap", CONFIGURATION_GAPS.values(), ids=CONFIGURATION_GAPS.keys())
def test_configuration_gap_is_detected(repo, capsys, old, new, gap):
    compact(repo)
    edit(repo, SUMMARY, old, new)
    out, _ = gaps_of(repo, capsys)
    assert gap in out


CHANGED_INPUTS = {
    "scene": ("verification/problems/WID-SWING/scene.toml", "ks = 1.0e9", "ks = 0.55e9", "problem WID-SWING"),
    "table the scene reads": ("verification/problems/WID-SWING/swing.csv", "1,0.5", "1,0.6", "problem WID-SWING"),
    "problem.toml": (PROBLEM, 'title = "Widget swings"', 'title = "Widget swung"', "problem WID-SWING"),
    "harness module": ("verification/harness/vdec_verify/__init__.py", "stand-in", "stand in", "harness"),
    "vdec binary": ("bin/vdec", "stand-in", "stand in", "vdec binary"),
}


@CONFIGURATION_CONTROL
@pytest.mark.parametrize("path,old,new,subject", CHANGED_INPUTS.values(), ids=CHANGED_INPUTS.keys())
def test_an_input_changed_since_the_run_is_a_gap(repo, capsys, path, old, new, subject):
    edit(repo, path, old, new)
    out, page = gaps_of(repo, capsys)
    assert f"{subject}: input {path} differs from the file that ran (SHA-256 " in out
    (repo / path).unlink()
    out, _ = gaps_of(repo, capsys)
    assert f"{subject}: input {path} no longer exists" in out


@CONFIGURATION_CONTROL
def test_a_harness_module_not_recorded_is_a_gap(repo, capsys):
    (repo / "verification/harness/vdec_verify/extra.py").write_text("")
    out, _ = gaps_of(repo, capsys)
    assert "harness: verification/harness/vdec_verify/extra.py is not among the harness files recorded" in out


@CONFIGURATION_CONTROL
def test_a_copy_of_the_problems_outside_the_repository_is_caught(repo, capsys, tmp_path):
    """The issue's case: a copy of the problems with a changed stiffness, run with the same
    commit and a clean checkout, recorded the same commit; its inputs are not the repository's."""
    copy = tmp_path / "copy"
    shutil.copytree(repo / "verification/problems", copy)
    edit(copy, "WID-SWING/scene.toml", "ks = 1.0e9", "ks = 0.55e9")
    summary = json.loads((repo / SUMMARY).read_text())
    summary["harness"].update(problems_dir=str(copy), problems_dir_in_repository=False)
    summary["problems"][0]["inputs"] = {str(p): audit.sha256_of(p) for p in sorted((copy / "WID-SWING").iterdir())}
    (repo / SUMMARY).write_text(json.dumps(summary))
    out, _ = gaps_of(repo, capsys)
    assert f"the problems folder {copy} is outside the repository" in out
    assert ("problem WID-SWING: its runs did not read the repository's verification/problems/WID-SWING/problem.toml"
            f" (read {copy}/WID-SWING/problem.toml)") in out


def test_junit_glob_option_and_unmatched_glob(repo, capsys):
    # Only the GoogleTest file: the pytest ids are then missing.
    out, _ = gaps_of(repo, capsys, "--junit", str(repo / "reports/tests/gtest*.xml"))
    assert "REQ-QA-001: test pytest:test_widget.test_known_values not found in the test results" in out
    out, _ = gaps_of(repo, capsys, "--junit", str(repo / "nothing/*.xml"))
    assert "no JUnit XML file matches" in out


# ------------------------------------------------------------ Markdown details

def test_anchors_follow_github_slugs_and_explicit_ids():
    text = ("# Title\n## Coulomb slip (model 2)\nx\n## Coulomb slip (model 2)\ny\n"
            "## Time step {#dt}\nz\n<a id=\"here\"></a>\n```\n## Not a heading\n```\n")
    anchors = audit.markdown_anchors(text)
    assert {"title", "coulomb-slip-model-2", "coulomb-slip-model-2-1", "time-step", "dt", "here"} <= anchors
    assert "not-a-heading" not in anchors


def test_subsection_names_ignore_case_and_numbering():
    assert audit.subsection_key("3.2. DERIVATION (of the model)") == "derivation of the model"
    assert audit.subsection_key("Location (in the code)") == "location in the code"
    assert audit.subsection_key("a) Assumptions & Limitations") == "assumptions and limitations"

#!/usr/bin/env python3
"""Traceability audit: requirements <-> docs, code, verification problems and tests.

Reads qa/traceability/requirements.toml, verification/problems/*/problem.toml, a stored
verification summary and the JUnit XML of the unit and Python tests; writes the requirements
traceability matrix (rtm.csv, rtm.html) and prints a verdict. Two modes (MODES): the
qualification audit judges the full suite's evidence in reports/ (scripts/qualify.sh); the
test-suite audit judges the base-level evidence ctest wrote under build/reports/. Both
recompute the SHA-256 of every input the summary records (configuration control).

The component table at the top of requirements.toml says which component owns which source
folders and requirement and problem id prefixes; requirements and problems are checked against
it. Every inconsistency is a "gap"; all gaps are listed, none stops the audit early. Exit status:
0 no gaps, 1 gaps, 2 usage or input error (requirements.toml unreadable, output not writable).
Standard library only, so it runs wherever the QA harness runs. See README.md next to this file.
"""
import argparse
import csv
import datetime
import glob
import hashlib
import html
import json
import os
import re
import subprocess
import sys
import tomllib
import xml.etree.ElementTree as ET
from pathlib import Path

SCHEMA = "vdec.verification/1"
HARNESS_FOLDER = "verification/harness/vdec_verify"
# What each mode judges, and where its evidence is by default (paths relative to --root).
MODES = {
    "qualification": {"level": "full", "summary": "reports/verification/summary.json",
                      "junit": "reports/tests/*.xml", "out": "reports/traceability",
                      "writer": "scripts/qualify.sh, the README's first command"},
    "test-suite": {"level": "base", "summary": "build/reports/verification-base/summary.json",
                   "junit": "build/reports/tests/*.xml", "out": "build/reports/traceability",
                   "writer": "ctest's verification test"},
}
REQ_ID = re.compile(r"^REQ-[A-Z]+-\d{3}$")
REQUIREMENT_KEYS = {"id", "component", "text", "source", "docs", "code", "problems", "tests"}
# The component table (README.md, "Components"): every component names the folders it owns, the
# id prefixes of its requirements and verification problems, and its docs page. The optional keys
# default to false or empty.
COMPONENT_KEYS = {"id", "title", "docs", "source", "requirement_prefixes", "problem_prefixes"}
COMPONENT_OPTIONAL_KEYS = {"reserved", "cross_cutting", "uses", "legacy_requirements"}
REQUIREMENT_PREFIX = re.compile(r"^REQ-[A-Z]+$")
PROBLEM_PREFIX = re.compile(r"^[A-Z]+-$")
TOP_KEYS = {"component", "requirement"}

# The ten subsections NUREG-0856 asks of each component-model description: the name shown in
# reports, and the normalised headings accepted for it. Matching is exact after normalising, so
# "Derivation" (of the model) and "Derivation of the numerical method" stay distinct.
SUBSECTIONS = [
    ("Purpose", {"purpose"}),
    ("Assumptions and limitations", {"assumptions and limitations"}),
    ("Notation", {"notation"}),
    ("Derivation", {"derivation", "derivation of the model"}),
    ("Application", {"application"}),
    ("Numerical method type", {"numerical method type"}),
    ("Derivation of the numerical method", {"derivation of the numerical method"}),
    ("Location in the code", {"location", "location in the code"}),
    ("Numerical stability and accuracy", {"numerical stability and accuracy"}),
    ("Alternatives", {"alternatives"}),
]

# Evidence states, worst first: combining several results of one test keeps the worst, so a
# test that failed once, or was skipped in one run, never reads as passed.
WORST_FIRST = ["fail", "not run", "pass"]


class InputError(Exception):
    """An input the audit cannot work without (exit 2)."""


class Audit:
    """Collects gaps (which fail the audit) and warnings (which are only reported)."""

    def __init__(self, root):
        self.root = root
        self.gaps = []        # dicts: subject, text, requirements (ids the gap is held against)
        self.warnings = []
        self._texts = {}

    def gap(self, subject, text, requirements=()):
        self.gaps.append({"subject": subject, "text": text, "requirements": set(requirements)})

    def warn(self, text):
        self.warnings.append(text)

    def gap_or_warn(self, is_gap, subject, text):
        """A finding that fails one mode of the audit and is only reported by the other."""
        if is_gap:
            self.gap(subject, text)
        else:
            self.warn(f"{subject}: {text}")

    def rel(self, path):
        """A path as written relative to the repository root when it lies inside it."""
        try:
            return Path(path).resolve().relative_to(self.root.resolve()).as_posix()
        except ValueError:
            return str(path)

    def repo_file(self, relpath):
        """(path, None) for an existing file inside the repository, else (None, reason)."""
        if not relpath:
            return None, "no path given"
        path = self.root / relpath
        # A file outside the repository is not under the project's configuration control.
        if Path(relpath).is_absolute() or not path.resolve().is_relative_to(self.root.resolve()):
            return None, f"{relpath} is outside the repository"
        if not path.is_file():
            return None, f"{relpath} does not exist"
        return path, None

    def repo_dir(self, relpath):
        """None for an existing folder inside the repository, else the reason it is not one."""
        if not relpath:
            return "no path given"
        path = self.root / relpath
        if Path(relpath).is_absolute() or not path.resolve().is_relative_to(self.root.resolve()):
            return f"{relpath} is outside the repository"
        if not path.is_dir():
            return f"{relpath} does not exist"
        return None

    def text(self, path):
        # Several requirements point into the same files; read each once.
        if path not in self._texts:
            self._texts[path] = path.read_text(encoding="utf-8", errors="replace")
        return self._texts[path]


def worst(states):
    states = list(states)
    return next((s for s in WORST_FIRST if s in states), "pass")


# ---------------------------------------------------------------- Markdown

ATX_HEADING = re.compile(r"^ {0,3}(#{1,6})(?:[ \t]+(.*?))?(?:[ \t]+#+)?[ \t]*$")
FENCE = re.compile(r"^ {0,3}(`{3,}|~{3,})")
HTML_COMMENT = re.compile(r"<!--.*?-->", re.S)
ATTRIBUTE_ID = re.compile(r"\{[^}]*?#([^\s}]+)[^}]*\}")
ANCHOR_TAG = re.compile(r"<a\s[^>]*?\b(?:id|name)\s*=\s*[\"']([^\"']+)[\"'][^>]*>(?:\s*</a>)?", re.I)


def markdown_sections(text):
    """Headings of a Markdown text as dicts: level, title, explicit ids, has_text.

    ATX headings only (# to ######), outside fenced code. HTML comments are not text: a
    section holding only "<!-- TODO -->" is empty. A section has text when some non-blank,
    non-heading line stands before the next heading of the same or a higher level, so a
    section whose text sits in its subsections is not empty.
    """
    # Blank out comments but keep their newlines, so line numbers stay right.
    text = HTML_COMMENT.sub(lambda m: "\n" * m.group().count("\n"), text)
    lines = text.splitlines()
    heads, fence = [], None
    for i, line in enumerate(lines):
        m = FENCE.match(line)
        if fence:
            if m and m.group(1)[0] == fence[0] and len(m.group(1)) >= len(fence) and not line.strip(" `~"):
                fence = None
            continue
        if m:
            fence = m.group(1)
            continue
        m = ATX_HEADING.match(line)
        if m:
            title = m.group(2) or ""
            ids = ATTRIBUTE_ID.findall(title)
            heads.append({"line": i, "level": len(m.group(1)), "title": ATTRIBUTE_ID.sub("", title).strip(),
                          "ids": ids})
    heading_lines = {h["line"] for h in heads}
    for k, h in enumerate(heads):
        end = next((n["line"] for n in heads[k + 1:] if n["level"] <= h["level"]), len(lines))
        body = "\n".join(lines[j] for j in range(h["line"] + 1, end) if j not in heading_lines)
        # An anchor tag alone (<a id="x"></a>) is a link target, not report text.
        h["has_text"] = bool(ANCHOR_TAG.sub("", body).strip())
    return heads


def github_slug(title):
    """The anchor GitHub gives a heading: rendered text, lower case, punctuation dropped,
    each space a hyphen (github-slugger). Links count by their text, inline code by its
    content, HTML tags not at all."""
    title = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", title)
    title = re.sub(r"<[^>]+>", "", title)
    return re.sub(r"[^\w\- ]", "", title.strip().lower()).replace(" ", "-")


def markdown_anchors(text):
    anchors, seen = set(), {}
    for h in markdown_sections(text):
        slug = github_slug(h["title"])
        # GitHub numbers repeated headings: x, x-1, x-2, ...
        n = seen.get(slug, 0)
        seen[slug] = n + 1
        anchors.add(slug if n == 0 else f"{slug}-{n}")
        anchors.update(h["ids"])
    anchors.update(ANCHOR_TAG.findall(HTML_COMMENT.sub("", text)))
    return anchors


def subsection_key(title):
    """Heading text normalised for the ten-subsection check: case folded, leading numbering
    ("3", "3.2.", "a)") dropped, parentheses and trailing punctuation ignored, '&' read as 'and'."""
    s = title.casefold().strip()
    s = re.sub(r"^(?:\d+(?:\.\d+)*\.?|[a-z][.)])\s+", "", s)
    s = s.replace("&", " and ")
    s = re.sub(r"[()\[\]:.,*_`]", " ", s)
    return " ".join(s.split())


# ---------------------------------------------------------------- inputs

def load_requirements(path):
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as e:
        raise InputError(f"{path}: cannot read: {e.strerror or e}")
    except UnicodeDecodeError as e:
        raise InputError(f"{path}: not UTF-8 text: {e}")
    except tomllib.TOMLDecodeError as e:
        # tomllib's message ends with "(at line L, column C)".
        raise InputError(f"{path}: TOML error: {e}")
    for key in ("component", "requirement"):
        entries = data.get(key, [])
        if not isinstance(entries, list) or not all(isinstance(e, dict) for e in entries):
            raise InputError(f"{path}: '{key}' must be an array of tables ([[{key}]])")
    return data


def string_field(audit, subject, record, key, reqs=()):
    value = record.get(key, "")
    if not isinstance(value, str):
        audit.gap(subject, f"'{key}' must be a string", reqs)
        return ""
    return value


def list_field(audit, subject, record, key, reqs=()):
    value = record.get(key, [])
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        audit.gap(subject, f"'{key}' must be a list of strings", reqs)
        return [v for v in value if isinstance(v, str)] if isinstance(value, list) else []
    return value


def load_problems(audit, folder):
    """Verification problems by id: requirements, level and the file they came from."""
    problems = {}
    for path in sorted(folder.glob("*/problem.toml")):
        subject = f"problem {path.parent.name}"
        try:
            data = tomllib.loads(path.read_text(encoding="utf-8"))
        except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as e:
            audit.gap(subject, f"{audit.rel(path)} unreadable: {e}")
            continue
        pid = data.get("id")
        if not isinstance(pid, str) or not pid:
            audit.gap(subject, f"{audit.rel(path)} has no id")
            pid = path.parent.name
        elif pid != path.parent.name:
            audit.gap(f"problem {pid}", f"id differs from its folder name {path.parent.name}")
        if pid in problems:
            audit.gap(f"problem {pid}", f"duplicate problem id ({audit.rel(path)})")
            continue
        problems[pid] = {"requirements": list_field(audit, f"problem {pid}", data, "requirements"),
                         "level": data.get("level", "base"), "path": path}
    return problems


def load_summary(audit, path):
    """(problem statuses, info) from summary.json; statuses None when there is no usable summary.
    info keeps the commits, the level and the whole summary for check_configuration."""
    info = {"software_commit": None, "harness_commit": None, "version": None, "level": None, "summary": None}
    try:
        summary = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        audit.gap("verification summary", f"{audit.rel(path)} missing (run the verification suite); "
                  "every problem shows 'not run'")
        return None, info
    except (OSError, UnicodeDecodeError, ValueError) as e:
        audit.gap("verification summary", f"{audit.rel(path)} unreadable: {e}; every problem shows 'not run'")
        return None, info
    if not isinstance(summary, dict) or summary.get("schema") != SCHEMA:
        found = summary.get("schema") if isinstance(summary, dict) else type(summary).__name__
        audit.gap("verification summary", f"{audit.rel(path)} is not a {SCHEMA} summary (schema {found!r}); "
                  "every problem shows 'not run'")
        return None, info
    software = summary.get("software") if isinstance(summary.get("software"), dict) else {}
    harness = summary.get("harness") if isinstance(summary.get("harness"), dict) else {}
    info = {"software_commit": software.get("git_commit"), "harness_commit": harness.get("git_commit"),
            "version": software.get("version"), "level": harness.get("level"), "summary": summary}
    statuses = {}
    entries = summary.get("problems")
    if not isinstance(entries, list):
        audit.gap("verification summary", f"{audit.rel(path)} has no 'problems' list")
        return statuses, info
    for n, p in enumerate(entries):
        if not isinstance(p, dict) or not isinstance(p.get("id"), str) \
                or p.get("status") not in ("pass", "fail", "invalid"):
            audit.gap("verification summary", f"{audit.rel(path)}: problems[{n}] lacks an id or a status "
                      "pass|fail|invalid")
            continue
        # A problem listed twice keeps its worse status; a failure is never hidden by a pass.
        old = statuses.get(p["id"])
        statuses[p["id"]] = p["status"] if old in (None, "pass") else old
    return statuses, info


def pytest_class_path(classname, file):
    """The classname of a pytest case from its test module on: 'tests.python.test_m.TestC'
    becomes 'test_m.TestC'. The module is the case's file stem when the XML gives the file,
    else the last component named test_* or *_test."""
    parts = classname.split(".")
    stem = Path(file).stem if file else None
    if stem and stem in parts:
        start = len(parts) - 1 - parts[::-1].index(stem)
    else:
        found = [i for i, p in enumerate(parts) if p.startswith("test_") or p.endswith("_test")]
        start = found[-1] if found else 0
    return ".".join(parts[start:])


def case_status(case):
    if case.find("failure") is not None or case.find("error") is not None:
        return "fail"
    # GoogleTest marks disabled tests status="notrun" and GTEST_SKIP result="skipped".
    if case.find("skipped") is not None or case.get("status") == "notrun" \
            or case.get("result") in ("skipped", "suppressed"):
        return "not run"
    return "pass"


class TestResults:
    """Test cases from JUnit XML by id, "gtest:<classname>.<name>" / "pytest:<module...>.<name>".

    A parametrized pytest case test_x[a] is also gathered under its base id test_x, which
    passes only when every instance passed. The full dotted pytest classname
    (tests.python.test_m.test_x) is accepted as another spelling of the same id.
    """

    def __init__(self):
        self.cases = {}      # id -> {"status", "requirements", "files"}
        self.groups = {}     # parametrized base id -> instance ids
        self.aliases = {}    # other spelling -> id
        self.files = []

    def add(self, test_id, status, requirements, file):
        case = self.cases.setdefault(test_id, {"status": "pass", "requirements": set(), "files": set()})
        case["status"] = worst([case["status"], status])
        case["requirements"] |= requirements
        case["files"].add(file)

    def lookup(self, test_id):
        test_id = self.aliases.get(test_id, test_id)
        if test_id in self.cases:
            return self.cases[test_id]
        if test_id in self.groups:
            instances = [self.cases[i] for i in sorted(self.groups[test_id])]
            return {"status": worst(c["status"] for c in instances),
                    "requirements": set().union(*(c["requirements"] for c in instances))}
        return None


def load_junit(audit, patterns, default_pattern):
    results = TestResults()
    files = []
    for pattern in patterns or [default_pattern]:
        matched = sorted(glob.glob(pattern))
        if not matched:
            audit.gap("test results", f"no JUnit XML file matches {pattern}")
        files += [f for f in matched if f not in files]
    results.files = files
    for file in files:
        name = Path(file).name
        kind = "gtest" if name.startswith("gtest") else "pytest" if name.startswith("pytest") else None
        if kind is None:
            # The test-id prefix comes from the file name; a file that gives none cannot be traced.
            audit.gap("test results", f"{audit.rel(file)}: name starts with neither 'gtest' nor 'pytest'")
            continue
        try:
            top = ET.parse(file).getroot()
        except (OSError, ET.ParseError) as e:
            audit.gap("test results", f"{audit.rel(file)} unreadable: {e}")
            continue
        for suite in top.iter("testsuite"):
            for case in suite.findall("testcase"):
                classname = case.get("classname") or suite.get("name", "")
                case_name = case.get("name", "")
                short = pytest_class_path(classname, case.get("file")) if kind == "pytest" else classname
                reqs = set()
                props = case.find("properties")
                for prop in props.findall("property") if props is not None else []:
                    if prop.get("name") == "requirements":
                        reqs |= {r.strip() for r in (prop.get("value") or "").split(",") if r.strip()}
                test_id = f"{kind}:{short}.{case_name}"
                results.add(test_id, case_status(case), reqs, audit.rel(file))
                if short != classname:
                    results.aliases[f"{kind}:{classname}.{case_name}"] = test_id
                if kind == "pytest" and case_name.endswith("]") and "[" in case_name:
                    base = case_name[:case_name.index("[")]
                    results.groups.setdefault(f"{kind}:{short}.{base}", set()).add(test_id)
                    if short != classname:
                        results.aliases[f"{kind}:{classname}.{base}"] = f"{kind}:{short}.{base}"
    return results


def git_head(root):
    try:
        r = subprocess.run(["git", "-C", str(root), "rev-parse", "HEAD"], capture_output=True, text=True,
                           timeout=20)
    except (OSError, subprocess.SubprocessError):
        return None
    return r.stdout.strip() if r.returncode == 0 and r.stdout.strip() else None


# ---------------------------------------------------------------- checks

def check_requirements(audit, requirements, components, problems, statuses, tests):
    ids = [r.get("id") for r in requirements]
    first_text = {}
    for n, r in enumerate(requirements):
        rid = r.get("id")
        subject = rid if isinstance(rid, str) and rid else f"requirement #{n + 1}"
        mine = [subject]
        for key in sorted(set(r) - REQUIREMENT_KEYS):
            audit.gap(subject, f"unknown key '{key}'", mine)
        if not isinstance(rid, str) or not REQ_ID.match(rid):
            audit.gap(subject, f"bad id {rid!r} (want REQ-AREA-NNN)", mine)
        elif ids.index(rid) != n:
            audit.gap(subject, f"duplicate id (also requirement #{ids.index(rid) + 1})", mine)
        text = string_field(audit, subject, r, "text", mine)
        norm = " ".join(text.casefold().split())
        if not norm:
            audit.gap(subject, "no text", mine)
        elif norm in first_text:
            audit.gap(subject, f"same text as {first_text[norm]}", mine)
        else:
            first_text[norm] = subject
        if not string_field(audit, subject, r, "source", mine).strip():
            audit.gap(subject, "no source", mine)
        component = string_field(audit, subject, r, "component", mine)
        if component and component not in components:
            audit.gap(subject, f"unknown component '{component}'", mine)
        check_docs_reference(audit, subject, string_field(audit, subject, r, "docs", mine))
        code = list_field(audit, subject, r, "code", mine)
        if not code:
            audit.gap(subject, "no code location", mine)
        for loc in code:
            file, _, symbol = loc.partition(":")
            path, why = audit.repo_file(file)
            if path is None:
                audit.gap(subject, f"code file {why}", mine)
            elif symbol and not re.search(r"(?<![\w])" + re.escape(symbol) + r"(?![\w])", audit.text(path)):
                # Whole-word match, so a listed symbol is not satisfied by a longer name containing it.
                audit.gap(subject, f"symbol '{symbol}' not found in {file}", mine)
        passed = False
        listed_problems = list_field(audit, subject, r, "problems", mine)
        listed_tests = list_field(audit, subject, r, "tests", mine)
        for pid in listed_problems:
            if pid not in problems:
                audit.gap(subject, f"problem {pid} does not exist", mine)
                continue
            if subject not in problems[pid]["requirements"]:
                audit.gap(subject, f"problem {pid} does not list it in its requirements", mine)
            passed |= (statuses or {}).get(pid) == "pass"
        for tid in listed_tests:
            case = tests.lookup(tid)
            if case is None:
                audit.gap(subject, f"test {tid} not found in the test results", mine)
                continue
            if subject not in case["requirements"]:
                audit.gap(subject, f"test {tid} does not name it in its 'requirements' property", mine)
            passed |= case["status"] == "pass"
        if not listed_problems and not listed_tests:
            audit.gap(subject, "no evidence: lists no verification problem and no test", mine)
        elif not passed:
            audit.gap(subject, "no passing evidence: no listed problem passed in summary.json and no "
                      "listed test passed", mine)


def check_docs_reference(audit, subject, docs):
    if not docs:
        audit.gap(subject, "no docs reference", [subject])
        return
    file, sep, anchor = docs.partition("#")
    path, why = audit.repo_file(file)
    if path is None:
        audit.gap(subject, f"docs file {why}", [subject])
    elif not sep or not anchor:
        audit.gap(subject, f"docs reference {docs} names no #anchor", [subject])
    elif anchor not in markdown_anchors(audit.text(path)):
        audit.gap(subject, f"docs anchor #{anchor} not found in {file}", [subject])


def check_problems(audit, problems, statuses, req_ids, requirements, level="full"):
    listed_by = {}
    for r in requirements:
        for pid in r.get("problems", []) if isinstance(r.get("problems"), list) else []:
            listed_by.setdefault(pid, set()).add(r.get("id"))
    for pid, p in problems.items():
        subject = f"problem {pid}"
        known = [q for q in p["requirements"] if q in req_ids]
        if not p["requirements"]:
            audit.gap(subject, "names no requirement")
        for q in p["requirements"]:
            if q not in req_ids:
                audit.gap(subject, f"names requirement {q}, which does not exist")
            elif q not in listed_by.get(pid, ()):
                audit.warn(f"problem {pid} names {q}, which does not list it (evidence not in the matrix)")
        if statuses is None:
            continue        # one gap already says the summary is missing
        status = statuses.get(pid)
        if status is None:
            if p["level"] == "full" and level == "base":
                # The test suite's base-level run leaves the full-suite problems out by design;
                # the qualification audit judges the full suite's own summary for them.
                audit.warn(f"problem {pid} (level 'full') is not in this base-level summary")
            else:
                level = f" (level = {p['level']!r})" if p["level"] != "base" else ""
                audit.gap(subject, f"not in summary.json: not run{level}", known)
        elif status != "pass":
            audit.gap(subject, f"status {status} in summary.json ({', '.join(known) or 'no requirement'})", known)
    for pid in sorted(set(statuses or {}) - set(problems)):
        audit.warn(f"summary.json reports problem {pid}, which is not in verification/problems (stale summary?)")


def check_tests(audit, tests, req_ids, requirements):
    listed = {}
    for r in requirements:
        for tid in r.get("tests", []) if isinstance(r.get("tests"), list) else []:
            listed.setdefault(tests.aliases.get(tid, tid), set()).add(r.get("id"))
    for tid, case in sorted(tests.cases.items()):
        subject = f"test {tid}"
        reqs = case["requirements"]
        known = sorted(reqs & req_ids)
        if not reqs:
            audit.gap(subject, "names no requirement (no 'requirements' property)")
        for q in sorted(reqs - req_ids):
            audit.gap(subject, f"names requirement {q}, which does not exist")
        base = tid[:tid.index("[")] if tid.endswith("]") and "[" in tid else tid
        for q in known:
            if q not in listed.get(tid, set()) | listed.get(base, set()):
                audit.warn(f"test {tid} names {q}, which does not list it (evidence not in the matrix)")
        if case["status"] == "fail":
            audit.gap(subject, f"failed ({', '.join(known) or 'no requirement'})", known)
        elif case["status"] == "not run":
            audit.warn(f"test {tid} was skipped or not run ({', '.join(known) or 'no requirement'})")


# What to write for a component key that is missing.
COMPONENT_KEY_HINTS = {
    "title": "what the component models",
    "docs": "its page, docs/models/NAME.md for a component model",
    "source": 'the folders it owns, e.g. ["src/contact"]',
    "requirement_prefixes": 'the REQ-AREA its requirement ids start with, e.g. ["REQ-CONTACT"]',
    "problem_prefixes": 'the prefix of its verification problems\' ids, e.g. ["RB-"], or [] when it has none',
}


def unreserve(cid):
    return (f"un-reserve component {cid} (delete reserved = true) and complete its entry: source folders "
            "that exist and a docs page with the ten NUREG-0856 subsections")


def requirement_area(rid):
    """'REQ-CONTACT' of 'REQ-CONTACT-006'; None for an id not of the form REQ-AREA-NNN."""
    return rid.rsplit("-", 1)[0] if isinstance(rid, str) and REQ_ID.match(rid) else None


def bool_field(audit, subject, record, key):
    value = record.get(key, False)
    if not isinstance(value, bool):
        audit.gap(subject, f"'{key}' must be true or false")
        return False
    return value


class ComponentTable:
    """The [[component]] entries as read: which component owns which id prefix and folder."""

    def __init__(self):
        self.entries = {}               # component id -> its keys, defaults filled in
        self.requirement_prefix = {}    # "REQ-AREA" -> component id
        self.problem_prefix = {}        # "AREA-" -> component id
        self.legacy = {}                # requirement id -> the component whose legacy_requirements list it

    def owner_of_requirement(self, rid):
        return self.legacy.get(rid) or self.requirement_prefix.get(requirement_area(rid))

    def owner_of_problem(self, pid):
        """(component id, prefix) for the problem prefix pid starts with, else (None, None). A
        prefix is capitals and one hyphen, so only the id's first word can match."""
        prefix = pid.split("-", 1)[0] + "-"
        owner = self.problem_prefix.get(prefix)
        return (owner, prefix) if owner else (None, None)


def read_component_table(audit, components, requirements):
    """Reads and checks the component entries: keys, prefix formats, one owner per prefix,
    'uses' naming components, legacy_requirements naming existing requirements of another
    component's prefix."""
    table = ComponentTable()
    req_ids = {r.get("id") for r in requirements if isinstance(r.get("id"), str)}
    for cid, c in components.items():
        subject = f"component {cid}"
        for key in sorted(set(c) - COMPONENT_KEYS - COMPONENT_OPTIONAL_KEYS):
            audit.gap(subject, f"unknown key '{key}'")
        for key in sorted(COMPONENT_KEYS - set(c)):
            audit.gap(subject, f"no '{key}': add it, giving {COMPONENT_KEY_HINTS[key]}")
        entry = {key: list_field(audit, subject, c, key)
                 for key in ("source", "requirement_prefixes", "problem_prefixes", "uses", "legacy_requirements")}
        entry["reserved"] = bool_field(audit, subject, c, "reserved")
        entry["cross_cutting"] = bool_field(audit, subject, c, "cross_cutting")
        table.entries[cid] = entry
        for key in ("source", "requirement_prefixes"):
            if key in c and not entry[key]:
                audit.gap(subject, f"'{key}' is empty: give {COMPONENT_KEY_HINTS[key]}")
        for key, pattern, owners, example in (
                ("requirement_prefixes", REQUIREMENT_PREFIX, table.requirement_prefix, "REQ-FLOW"),
                ("problem_prefixes", PROBLEM_PREFIX, table.problem_prefix, "FLOW-")):
            kind = key.split("_")[0]
            for prefix in entry[key]:
                if not pattern.match(prefix):
                    audit.gap(subject, f"{kind} prefix {prefix!r} is not of the form {example!r} (capital letters)")
                elif prefix in owners:
                    audit.gap(subject, f"{kind} prefix {prefix} is also component {owners[prefix]}'s: a prefix "
                              "belongs to one component; give this one its own")
                else:
                    owners[prefix] = cid
    for cid, entry in table.entries.items():
        subject = f"component {cid}"
        for other in entry["uses"]:
            if other == cid or other not in components:
                audit.gap(subject, f"'uses' names {other!r}, which is not another component")
        for rid in entry["legacy_requirements"]:
            area = requirement_area(rid)
            if rid not in req_ids:
                audit.gap(subject, f"legacy_requirements names {rid}, which does not exist")
            elif rid in table.legacy:
                audit.gap(subject, f"legacy_requirements names {rid}, which component {table.legacy[rid]} lists too")
            elif area in entry["requirement_prefixes"]:
                audit.gap(subject, f"legacy_requirements names {rid}, whose prefix {area} is the component's own: "
                          "remove it from legacy_requirements")
            else:
                table.legacy[rid] = cid
    return table


def check_requirement_components(audit, requirements, table):
    """Each requirement sits in the component its id belongs to by the table, one that is not
    reserved. Its code lying outside that component's source folders is only a warning: some
    requirements rightly span components (a model and the run stage that calls it)."""
    for n, r in enumerate(requirements):
        rid = r.get("id")
        subject = rid if isinstance(rid, str) and rid else f"requirement #{n + 1}"
        component = r.get("component", "")
        area = requirement_area(rid)
        if not isinstance(component, str) or (component and component not in table.entries):
            continue        # a gap already says the component is not a string or unknown
        owner = table.owner_of_requirement(rid)
        if area is None:
            if not component:
                audit.gap(subject, "no component: set component to the id of the component it belongs to", [subject])
        elif owner is None:
            audit.gap(subject, f"its id prefix {area} is no component's: add '{area}' to the requirement_prefixes "
                      f"of the component it belongs to{'' if component else ', and set component to that id'}",
                      [subject])
        elif table.entries[owner]["reserved"]:
            then = "" if component == owner else f'; then set component = "{owner}"'
            audit.gap(subject, f"its id prefix {area} is reserved: {unreserve(owner)}{then}", [subject])
        elif component != owner:
            why = f"component {owner} lists it in legacy_requirements" if rid in table.legacy else \
                f"its id prefix {area} is component {owner}'s"
            now = f"it is component {component}'s" if component else "it names no component"
            audit.gap(subject, f"{why}, but {now}: set component = \"{owner}\"", [subject])
        if not component or table.entries[component]["reserved"]:
            continue
        folders = table.entries[component]["source"]
        code = r.get("code") if isinstance(r.get("code"), list) else []
        files = dict.fromkeys(loc.partition(":")[0] for loc in code if isinstance(loc, str))
        for file in files:
            if file and folders and not any(file.startswith(f.rstrip("/") + "/") for f in folders):
                audit.warn(f"{subject}: code {file} lies outside the source folders of component {component} "
                           f"({', '.join(folders)})")


def check_problem_components(audit, problems, requirements, table):
    """A problem's id starts with the problem prefix of a component that is not reserved, and
    the requirements it names are that component's, of a component it uses, or cross-cutting."""
    component_of = {r.get("id"): r.get("component") for r in requirements if isinstance(r.get("id"), str)}
    for pid, p in problems.items():
        subject = f"problem {pid}"
        owner, prefix = table.owner_of_problem(pid)
        if owner is None:
            audit.gap(subject, "its id starts with no component's problem prefix "
                      f"({', '.join(sorted(table.problem_prefix)) or 'none'}): name it with the prefix of the "
                      "component it verifies, or add its prefix to that component's problem_prefixes")
            continue
        entry = table.entries[owner]
        if entry["reserved"]:
            audit.gap(subject, f"its id prefix {prefix} is reserved: {unreserve(owner)}")
            continue
        for q in p["requirements"]:
            qc = component_of.get(q)
            if not isinstance(qc, str) or qc not in table.entries:
                continue    # an unknown requirement or component is a gap already
            if qc != owner and qc not in entry["uses"] and not table.entries[qc]["cross_cutting"]:
                audit.gap(subject, f"names {q} of component {qc}, but its prefix {prefix} is component {owner}'s: "
                          f"add \"{qc}\" to {owner}'s uses if {owner}'s problems run on {qc}'s model, "
                          f"or drop {q} from the problem's requirements", [q])


def check_components(audit, components, requirements, table):
    """Each component that is not reserved: a requirement names it, its source folders exist,
    its docs page exists and, for a component model (not cross-cutting), has the ten NUREG-0856
    subsections, none empty. Returns per-component rows for the report."""
    rows = []
    for cid, c in components.items():
        subject = f"component {cid}"
        entry = table.entries[cid]
        row = {"id": cid, "title": c.get("title", ""), "docs": c.get("docs", ""), "subsections": [],
               "source": entry["source"], "prefixes": entry["requirement_prefixes"] + entry["problem_prefixes"],
               "kind": "reserved" if entry["reserved"] else "cross-cutting" if entry["cross_cutting"] else "model",
               "uses": entry["uses"], "legacy": entry["legacy_requirements"],
               "requirements": [r.get("id") for r in requirements if r.get("component") == cid]}
        rows.append(row)
        if entry["reserved"]:
            continue        # its docs and folders come when it is un-reserved; requirements naming it are gaps
        if not row["requirements"]:
            audit.gap(subject, "no requirement names this component")
        for folder in entry["source"]:
            why = audit.repo_dir(folder)
            if why:
                audit.gap(subject, f"source folder {why}: create it or correct 'source'")
        docs = c.get("docs", "")
        path, why = audit.repo_file(docs if isinstance(docs, str) else "")
        if path is None:
            audit.gap(subject, f"docs file {why}")
            row["subsections"] = [(name, "no docs") for name, _ in SUBSECTIONS]
            continue
        if entry["cross_cutting"]:
            continue        # not a component model: its page is not held to the ten subsections
        sections = markdown_sections(audit.text(path))
        for name, accepted in SUBSECTIONS:
            found = [s for s in sections if subsection_key(s["title"]) in accepted]
            if not found:
                audit.gap(subject, f"{docs} lacks the subsection '{name}'")
                row["subsections"].append((name, "missing"))
            else:
                row["subsections"].append((name, "present" if any(s["has_text"] for s in found) else "empty"))
        for s in sections:
            if not s["has_text"]:
                audit.gap(subject, f"{docs} line {s['line'] + 1}: empty report section '{s['title']}'")
    return rows


# ---------------------------------------------------------------- reports

def evidence_rows(requirements, problems, statuses, tests):
    """Per requirement: [(kind, id, status)]; status pass|fail|not run|missing."""
    out = []
    for r in requirements:
        ev = []
        for pid in r.get("problems", []) if isinstance(r.get("problems"), list) else []:
            if pid not in problems:
                ev.append(("problem", pid, "missing"))
            else:
                s = (statuses or {}).get(pid)
                ev.append(("problem", pid, "not run" if s is None else "pass" if s == "pass" else "fail"))
        for tid in r.get("tests", []) if isinstance(r.get("tests"), list) else []:
            case = tests.lookup(tid)
            ev.append(("test", tid, "missing" if case is None else case["status"]))
        out.append(ev)
    return out


def as_text(value):
    if isinstance(value, list):
        return "; ".join(str(v) for v in value)
    return "" if value is None else str(value)


def write_csv(path, requirements, evidence):
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(["requirement", "component", "text", "source", "docs", "code", "evidence_kind", "evidence_id",
                    "status"])
        for r, ev in zip(requirements, evidence):
            fixed = [as_text(r.get(k)) for k in ("id", "component", "text", "source", "docs", "code")]
            for kind, eid, status in ev or [("", "", "missing")]:
                w.writerow(fixed + [kind, eid, status])


STYLE = """
body{font-family:sans-serif;font-size:13px;margin:1.5em}
table{border-collapse:collapse;margin-bottom:1em}
td,th{border:1px solid #aaa;padding:3px 6px;vertical-align:top;text-align:left}
th{background:#eee}
.pass{color:#075f07}.fail,.missing,.gap,.empty{color:#b00000;font-weight:bold}
.not-run{color:#8a5a00;font-weight:bold}
ul.ev{margin:0;padding-left:1.1em}
code{font-size:12px}
"""


def status_span(status):
    return f"<span class='{status.replace(' ', '-')}'>{html.escape(status)}</span>"


def write_html(path, audit, ctx):
    e = html.escape
    out_dir = path.parent
    req_gaps = {}
    for g in audit.gaps:
        for q in g["requirements"]:
            req_gaps[q] = req_gaps.get(q, 0) + 1

    def docs_link(docs):
        if not isinstance(docs, str) or not docs:
            return ""
        file, _, anchor = docs.partition("#")
        href = Path(os.path.relpath(audit.root / file, out_dir)).as_posix() + (f"#{anchor}" if anchor else "")
        return f"<a href='{e(href, quote=True)}'>{e(docs)}</a>"

    def ev_list(items):
        return "<ul class='ev'>" + "".join(f"<li><code>{e(i)}</code>: {status_span(s)}</li>"
                                           for _, i, s in items) + "</ul>" if items else "none"

    rows = []
    for n, (r, ev) in enumerate(zip(ctx["requirements"], ctx["evidence"])):
        rid = r.get("id") if isinstance(r.get("id"), str) and r.get("id") else f"requirement #{n + 1}"
        count = req_gaps.get(rid, 0)
        verdict = "<span class='pass'>verified</span>" if count == 0 else \
            f"<span class='gap'>{count} gap{'s' if count > 1 else ''}</span>"
        code = "<br>".join(f"<code>{e(c)}</code>" for c in r.get("code", []) if isinstance(c, str)) \
            if isinstance(r.get("code"), list) else ""
        rows.append(
            f"<tr id='{e(rid, quote=True)}'><td><b>{e(rid)}</b><br>{e(as_text(r.get('component')))}</td>"
            f"<td>{e(as_text(r.get('text')))}</td><td>{e(as_text(r.get('source')))}</td>"
            f"<td>{docs_link(r.get('docs'))}</td><td>{code}</td>"
            f"<td>{ev_list([x for x in ev if x[0] == 'problem'])}</td>"
            f"<td>{ev_list([x for x in ev if x[0] == 'test'])}</td><td>{verdict}</td></tr>")
    gaps = "".join(f"<li><b>{e(g['subject'])}</b>: {e(g['text'])}</li>" for g in audit.gaps) or "<li>none</li>"
    warnings = "".join(f"<li>{e(w)}</li>" for w in audit.warnings) or "<li>none</li>"
    comps = []
    not_checked = {"reserved": "reserved: not checked until un-reserved",
                   "cross-cutting": "cross-cutting: not a component model, not checked"}
    for c in ctx["components"]:
        checks = "".join(f"<li>{e(name)}: <span class='{'pass' if s == 'present' else 'gap'}'>{e(s)}</span></li>"
                         for name, s in c["subsections"]) or f"<li>{e(not_checked.get(c['kind'], ''))}</li>"
        reqs = e(', '.join(str(q) for q in c['requirements'])) or \
            ("none" if c["kind"] == "reserved" else status_span('missing'))
        comps.append(
            f"<tr><td><b>{e(c['id'])}</b><br>{e(as_text(c['title']))}<br>({e(c['kind'])})"
            f"{'<br>uses ' + e(', '.join(c['uses'])) if c['uses'] else ''}</td>"
            f"<td>{'<br>'.join(f'<code>{e(f)}</code>' for f in c['source'])}</td>"
            f"<td>{'<br>'.join(f'<code>{e(x)}</code>' for x in c['prefixes'])}"
            f"{'<br>legacy ' + e(', '.join(c['legacy'])) if c['legacy'] else ''}</td><td>{docs_link(c['docs'])}</td>"
            f"<td>{reqs}</td><td><ul class='ev'>{checks}</ul></td></tr>")
    s = ctx["summary_info"]
    verdict = "PASS" if not audit.gaps else f"FAIL ({len(audit.gaps)} gaps)"
    page = f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>vdec requirements traceability matrix</title>
<style>{STYLE}</style></head><body>
<h1>vdec requirements traceability matrix</h1>
<table>
<tr><th>audit date</th><td>{e(ctx['date'])}</td></tr>
<tr><th>current commit (HEAD)</th><td><code>{e(ctx['head'] or 'unknown (not a git checkout)')}</code></td></tr>
<tr><th>audit mode</th><td>{e(ctx['mode'])} (judges level {e(MODES[ctx['mode']]['level'])} evidence)</td></tr>
<tr><th>verification summary</th><td>{e(ctx['summary_rel'])} (level {e(str(s['level']))}): software commit <code>{e(str(s['software_commit']))}</code>
(version {e(str(s['version']))}), harness commit <code>{e(str(s['harness_commit']))}</code></td></tr>
<tr><th>test results</th><td>{e(', '.join(ctx['junit_files']) or 'none')}</td></tr>
<tr><th>counts</th><td>{len(ctx['requirements'])} requirements, {len(ctx['components'])} components,
{ctx['n_problems']} verification problems, {ctx['n_tests']} tests, {len(audit.gaps)} gaps</td></tr>
<tr><th>verdict</th><td>{status_span('pass') if not audit.gaps else f"<span class='gap'>{e(verdict)}</span>"}</td></tr>
</table>
<h2>Warnings</h2><p>Reported, not counted as gaps.</p><ul>{warnings}</ul>
<h2>Matrix</h2>
<p>Status: pass; fail (problem fail or invalid, test failed); not run (not in the verification summary,
or skipped); missing (the problem or test does not exist). A requirement is verified when at least one
listed problem or test passed and no gap is held against it.</p>
<table><tr><th>requirement</th><th>text</th><th>source</th><th>docs</th><th>code</th>
<th>verification problems</th><th>tests</th><th>verdict</th></tr>
{''.join(rows)}
</table>
<h2>Gaps</h2><ul>{gaps}</ul>
<h2>Components</h2>
<p>Each component model's docs must have the ten NUREG-0856 subsections, none empty. A requirement
belongs to the component that owns its id prefix; a problem to the component that owns its id prefix.</p>
<table><tr><th>component</th><th>source folders</th><th>requirement and problem prefixes</th><th>docs</th>
<th>requirements</th><th>subsections</th></tr>
{''.join(comps)}
</table>
</body></html>
"""
    path.write_text(page, encoding="utf-8")


# ---------------------------------------------------------------- configuration control

def sha256_of(path):
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()
    except OSError:
        return None


def recorded_file(root, recorded):
    """The file a path in summary.json names: relative to the repository root, or absolute."""
    path = Path(recorded)
    return path if path.is_absolute() else root / path


def check_hashes(audit, subject, recorded, reqs=()):
    """Recomputes each recorded SHA-256; a file that changed, vanished or was unreadable when
    the suite ran is a gap: the evidence is not of the files there now."""
    if not isinstance(recorded, dict) or not recorded:
        audit.gap(subject, "summary.json records no input hashes (rerun the suite with the current harness)", reqs)
        return
    for path, sha in sorted(recorded.items()):
        if not isinstance(sha, str):
            audit.gap(subject, f"input {path} was not found or not readable when the suite ran", reqs)
            continue
        now = sha256_of(recorded_file(audit.root, path))
        if now is None:
            audit.gap(subject, f"input {path} no longer exists or is unreadable", reqs)
        elif now != sha:
            audit.gap(subject, f"input {path} differs from the file that ran (SHA-256 {sha[:16]}... in "
                      f"summary.json, {now[:16]}... now)", reqs)


def check_commits(audit, mode, head, info, harness):
    """Commit and cleanliness of the evidence: a commit other than HEAD is a gap in both modes;
    no commit at all, uncommitted or untracked files are a gap for qualification, a warning in
    the test suite (which a developer runs on work in progress, or on a copy outside git)."""
    strict = mode == "qualification"
    for label, commit in (("software.git_commit", info["software_commit"]),
                          ("harness.git_commit", info["harness_commit"])):
        if not commit or commit == "unknown":
            audit.gap_or_warn(strict, "verification summary",
                              f"summary.json {label} is {commit!r}: no commit identifies the evidence")
            continue
        sha = str(commit).removesuffix("-dirty")
        if str(commit).endswith("-dirty"):
            audit.gap_or_warn(strict, "verification summary",
                              f"summary.json {label} {commit}: built from uncommitted changes")
        if head is None:
            audit.gap_or_warn(strict, "verification summary", f"summary.json {label} {commit} cannot be "
                              "compared: current commit unknown (not a git checkout)")
        elif not (len(sha) >= 7 and head.startswith(sha)):
            audit.gap("verification summary", f"summary.json {label} {commit} differs from HEAD {head}: the "
                      "verification evidence is not from the current commit")
    if harness.get("git_dirty") is not False:
        text = (f"summary.json harness.git_dirty is {harness.get('git_dirty')!r}: the suite ran with uncommitted "
                "changes or untracked files in the repository")
        audit.gap_or_warn(strict, "verification summary", text)


def check_configuration(audit, mode, head, info, problems):
    """The gaps of configuration control: evidence of the wrong level, from another commit, from
    files outside the repository or from files that have changed since (see README.md)."""
    summary = info["summary"]
    if summary is None:
        return          # one gap already says the summary is missing or unusable
    harness = summary.get("harness") if isinstance(summary.get("harness"), dict) else {}
    want = MODES[mode]["level"]
    if info["level"] != want:
        audit.gap("verification summary", f"summary.json is of level {info['level']!r}; the {mode} audit judges "
                  f"level '{want}' evidence ({MODES[mode]['writer']})")
    check_commits(audit, mode, head, info, harness)
    if "problems_dir_in_repository" not in harness:
        audit.gap("verification summary", "summary.json does not record the run's configuration (problems folder, "
                  "filter, vdec binary, harness files): rerun the suite with the current harness")
        return
    if harness.get("problems_dir_in_repository") is not True:
        audit.gap("verification summary", f"the problems folder {harness.get('problems_dir')} is outside the "
                  "repository: not qualified")
    if harness.get("filter"):
        audit.gap("verification summary", f"the suite ran only the problems matching the filter "
                  f"{harness.get('filter')}")
    vdec = harness.get("vdec") if isinstance(harness.get("vdec"), dict) else {}
    check_hashes(audit, "vdec binary", {vdec.get("path"): vdec.get("sha256")} if vdec.get("path") else {})
    files = harness.get("files") if isinstance(harness.get("files"), dict) else {}
    check_hashes(audit, "harness", files)
    current = {audit.rel(p) for p in (audit.root / HARNESS_FOLDER).glob("*.py")}
    for path in sorted(current - set(files)):
        audit.gap("harness", f"{path} is not among the harness files recorded in summary.json")
    for entry in summary.get("problems") if isinstance(summary.get("problems"), list) else []:
        if not isinstance(entry, dict) or not isinstance(entry.get("id"), str):
            continue    # load_summary has a gap for it
        pid = entry["id"]
        reqs = problems[pid]["requirements"] if pid in problems else ()
        inputs = entry.get("inputs")
        check_hashes(audit, f"problem {pid}", inputs, reqs)
        mine = f"verification/problems/{pid}/problem.toml"
        if isinstance(inputs, dict) and inputs and mine not in inputs:
            audit.gap(f"problem {pid}", f"its runs did not read the repository's {mine} (read "
                      f"{', '.join(k for k in inputs if k.endswith('problem.toml')) or 'none'})", reqs)


# ---------------------------------------------------------------- main


def main(argv=None):
    here = Path(__file__).resolve()
    parser = argparse.ArgumentParser(description="vdec requirements traceability audit")
    parser.add_argument("--root", default=str(here.parents[2]), help="repository root (default: %(default)s)")
    parser.add_argument("--requirements", help="requirements file (default: ROOT/qa/traceability/requirements.toml)")
    parser.add_argument("--mode", choices=sorted(MODES), default="qualification",
                        help="qualification (default): judge the full suite's evidence; test-suite: judge "
                        "the base-level evidence ctest just produced")
    parser.add_argument("--summary", help="verification summary (default: ROOT/reports/verification/summary.json; "
                        "test-suite mode: ROOT/build/reports/verification-base/summary.json)")
    parser.add_argument("--junit", nargs="+", action="extend", metavar="GLOB",
                        help="JUnit XML files or globs (default: ROOT/reports/tests/*.xml; test-suite mode: "
                        "ROOT/build/reports/tests/*.xml)")
    parser.add_argument("--out", help="output folder (default: ROOT/reports/traceability; test-suite mode: "
                        "ROOT/build/reports/traceability)")
    args = parser.parse_args(argv)
    defaults = MODES[args.mode]

    root = Path(args.root)
    if not root.is_dir():
        print(f"audit: error: --root {root} is not a directory", file=sys.stderr)
        return 2
    audit = Audit(root)
    req_path = Path(args.requirements) if args.requirements else root / "qa/traceability/requirements.toml"
    try:
        data = load_requirements(req_path)
    except InputError as err:
        print(f"audit: error: {err}", file=sys.stderr)
        return 2

    for key in sorted(set(data) - TOP_KEYS):
        audit.gap("requirements file", f"unknown top-level key '{key}'")
    components = {}
    for n, c in enumerate(data.get("component", [])):
        cid = c.get("id")
        if not isinstance(cid, str) or not cid:
            audit.gap("requirements file", f"component #{n + 1} has no id")
        elif cid in components:
            audit.gap(f"component {cid}", "duplicate component id")
        else:
            components[cid] = c
    requirements = data.get("requirement", [])
    if not requirements:
        audit.gap("requirements file", "no requirements")

    problems = load_problems(audit, root / "verification/problems")
    summary_path = Path(args.summary) if args.summary else root / defaults["summary"]
    statuses, summary_info = load_summary(audit, summary_path)
    tests = load_junit(audit, args.junit, str(root / defaults["junit"]))
    req_ids = {r.get("id") for r in requirements if isinstance(r.get("id"), str)}

    check_requirements(audit, requirements, components, problems, statuses, tests)
    check_problems(audit, problems, statuses, req_ids, requirements, defaults["level"])
    check_tests(audit, tests, req_ids, requirements)
    table = read_component_table(audit, components, requirements)
    check_requirement_components(audit, requirements, table)
    check_problem_components(audit, problems, requirements, table)
    component_rows = check_components(audit, components, requirements, table)
    head = git_head(root)
    check_configuration(audit, args.mode, head, summary_info, problems)

    out = Path(args.out) if args.out else root / defaults["out"]
    evidence = evidence_rows(requirements, problems, statuses, tests)
    ctx = {"mode": args.mode, "requirements": requirements, "evidence": evidence, "components": component_rows, "head": head,
           "summary_info": summary_info, "summary_rel": audit.rel(summary_path),
           "junit_files": [audit.rel(f) for f in tests.files], "n_problems": len(problems),
           "n_tests": len(tests.cases),
           "date": datetime.datetime.now().astimezone().isoformat(timespec="seconds")}
    try:
        out.mkdir(parents=True, exist_ok=True)
        write_csv(out / "rtm.csv", requirements, evidence)
        write_html(out / "rtm.html", audit, ctx)
    except OSError as err:
        print(f"audit: error: cannot write the reports to {out}: {err}", file=sys.stderr)
        return 2

    print(f"audit: {args.mode} audit of {audit.rel(summary_path)} (level {summary_info['level']})")
    print(f"audit: HEAD {head or 'unknown'}; verification summary software commit "
          f"{summary_info['software_commit']}, harness commit {summary_info['harness_commit']}")
    for w in audit.warnings:
        print(f"audit: warning: {w}")
    print(f"audit: wrote {audit.rel(out / 'rtm.csv')} and {audit.rel(out / 'rtm.html')}")
    if not audit.gaps:
        print(f"audit: PASS ({len(requirements)} requirements, {len(problems)} problems, "
              f"{len(tests.cases)} tests, 0 gaps)")
        return 0
    print(f"audit: FAIL ({len(audit.gaps)} gaps)")
    shown = 20
    for g in audit.gaps[:shown]:
        print(f"  {g['subject']}: {g['text']}")
    if len(audit.gaps) > shown:
        print(f"  ... and {len(audit.gaps) - shown} more (see {audit.rel(out / 'rtm.html')})")
    return 1


if __name__ == "__main__":
    sys.exit(main())

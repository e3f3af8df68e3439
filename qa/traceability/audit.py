#!/usr/bin/env python3
"""Traceability audit: requirements <-> docs, code, verification problems and tests.

Reads qa/traceability/requirements.toml, verification/problems/*/problem.toml, the stored
reports/verification/summary.json and the JUnit XML in reports/tests/. Writes
reports/traceability/rtm.csv and rtm.html. Exits 1 on any gap, 2 on unreadable input.
"""
import argparse
import csv
import glob
import html
import re
import subprocess
import sys
import tomllib
import xml.etree.ElementTree as ET
from pathlib import Path

SUBSECTIONS = ["purpose", "assumptions and limitations", "notation", "derivation", "application",
               "numerical method type", "derivation of the numerical method", "location in the code",
               "numerical stability and accuracy", "alternatives"]
REQ_ID = re.compile(r"^REQ-[A-Z]+-\d{3}$")


def slug(heading):
    return re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-")


def headings(text):
    return [(len(m.group(1)), m.group(2).strip()) for m in re.finditer(r"^(#+)\s+(.*)$", text, re.M)]


def read_junit(paths):
    tests = {}
    for path in paths:
        prefix = "gtest" if Path(path).name.startswith("gtest") else "pytest"
        for case in ET.parse(path).getroot().iter("testcase"):
            name = re.sub(r"\[.*\]$", "", case.get("name", ""))
            test_id = f"{prefix}:{case.get('classname', '').split('.')[-1]}.{name}"
            failed = case.find("failure") is not None or case.find("error") is not None
            skipped = case.find("skipped") is not None or case.get("result") == "skipped"
            reqs = set()
            for prop in case.iter("property"):
                if prop.get("name") == "requirements":
                    reqs |= {r.strip() for r in prop.get("value", "").split(",") if r.strip()}
            old = tests.get(test_id, {"passed": True, "requirements": set()})
            tests[test_id] = {"passed": old["passed"] and not failed and not skipped,
                              "requirements": old["requirements"] | reqs}
    return tests


def main(argv=None):
    here = Path(__file__).resolve()
    parser = argparse.ArgumentParser()
    parser.add_argument("--root", default=str(here.parents[2]))
    parser.add_argument("--requirements")
    parser.add_argument("--summary")
    parser.add_argument("--junit", nargs="*")
    parser.add_argument("--out")
    args = parser.parse_args(argv)
    root = Path(args.root)
    req_path = Path(args.requirements or root / "qa/traceability/requirements.toml")
    try:
        data = tomllib.loads(req_path.read_text())
    except (OSError, tomllib.TOMLDecodeError) as e:
        print(f"audit: {req_path}: {e}", file=sys.stderr)
        return 2
    gaps = []
    components = {c["id"]: c for c in data.get("component", [])}
    requirements = data.get("requirement", [])
    problems, full_only = {}, set()
    for p in sorted((root / "verification/problems").glob("*/problem.toml")):
        problem = tomllib.loads(p.read_text())
        problems[p.parent.name] = problem.get("requirements", [])
        if problem.get("level") == "full":
            full_only.add(p.parent.name)
    summary_path = Path(args.summary or root / "reports/verification/summary.json")
    status, summary_commit = {}, "none"
    try:
        import json
        summary = json.loads(summary_path.read_text())
        if summary.get("schema") != "vdec.verification/1":
            gaps.append(f"{summary_path}: not a vdec.verification/1 summary")
        status = {p["id"]: p["status"] for p in summary.get("problems", [])}
        summary_commit = summary.get("software", {}).get("git_commit", "?")
    except (OSError, ValueError):
        gaps.append(f"{summary_path}: missing or unreadable (run the verification suite)")
    junit = args.junit or sorted(glob.glob(str(root / "reports/tests/*.xml")))
    tests = read_junit(junit)
    ids = [r.get("id", "") for r in requirements]
    texts = {}
    for r in requirements:
        rid = r.get("id", "")
        if not REQ_ID.match(rid):
            gaps.append(f"{rid}: bad requirement id")
        if ids.count(rid) > 1:
            gaps.append(f"{rid}: duplicate id")
        norm = " ".join(r.get("text", "").lower().split())
        if norm in texts:
            gaps.append(f"{rid}: same text as {texts[norm]}")
        texts[norm] = rid
        if not r.get("source", "").strip():
            gaps.append(f"{rid}: no source")
        if r.get("component") and r["component"] not in components:
            gaps.append(f"{rid}: unknown component {r['component']}")
        doc, _, anchor = r.get("docs", "").partition("#")
        doc_path = root / doc
        if not doc or not doc_path.is_file():
            gaps.append(f"{rid}: docs file {doc} missing")
        elif anchor and anchor not in {slug(h) for _, h in headings(doc_path.read_text())}:
            gaps.append(f"{rid}: docs anchor #{anchor} not in {doc}")
        for loc in r.get("code", []):
            file, _, symbol = loc.partition(":")
            if not (root / file).is_file():
                gaps.append(f"{rid}: code file {file} missing")
            elif symbol and symbol not in (root / file).read_text():
                gaps.append(f"{rid}: symbol {symbol} not in {file}")
        evidence = False
        for pid in r.get("problems", []):
            if pid not in problems:
                gaps.append(f"{rid}: problem {pid} does not exist")
            elif rid not in problems[pid]:
                gaps.append(f"{rid}: problem {pid} does not name it back")
            evidence |= status.get(pid) == "pass"
        for tid in r.get("tests", []):
            if tid not in tests:
                gaps.append(f"{rid}: test {tid} not found in the test results")
                continue
            if rid not in tests[tid]["requirements"]:
                gaps.append(f"{rid}: test {tid} does not name it")
            evidence |= tests[tid]["passed"]
        if not evidence:
            gaps.append(f"{rid}: no passing problem or test")
    for pid, reqs in problems.items():
        if not reqs:
            gaps.append(f"problem {pid}: names no requirement")
        for q in reqs:
            if q not in ids:
                gaps.append(f"problem {pid}: names unknown requirement {q}")
        if status and pid not in status:
            if pid in full_only:
                print(f"audit: note: full-suite problem {pid} is not in this (base-level) summary")
            else:
                gaps.append(f"problem {pid}: not in summary.json (not run)")
    for tid, t in tests.items():
        if not t["requirements"]:
            gaps.append(f"test {tid}: names no requirement")
        for q in t["requirements"] - set(ids):
            gaps.append(f"test {tid}: names unknown requirement {q}")
        if not t["passed"]:
            gaps.append(f"test {tid}: failed ({', '.join(sorted(t['requirements']))})")
    for cid, c in components.items():
        doc = root / c.get("docs", "")
        if not doc.is_file():
            gaps.append(f"component {cid}: docs file missing")
            continue
        hs = headings(doc.read_text())
        names = [h.lower() for _, h in hs]
        for s in SUBSECTIONS:
            if s not in names:
                gaps.append(f"component {cid}: docs lack the subsection '{s}'")
        lines = doc.read_text().splitlines()
        for i, line in enumerate(lines):
            m = re.match(r"^(#+)\s", line)
            if m:
                level = len(m.group(1))
                body = []
                for nxt in lines[i + 1:]:
                    n = re.match(r"^(#+)\s", nxt)
                    if n and len(n.group(1)) <= level:
                        break
                    body.append(nxt)
                if not "".join(body).strip():
                    gaps.append(f"component {cid}: empty section '{line.strip()}'")
        if not any(r.get("component") == cid for r in requirements):
            gaps.append(f"component {cid}: no requirement")
    out = Path(args.out or root / "reports/traceability")
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for r in requirements:
        ev = [("problem", p, status.get(p, "not run")) for p in r.get("problems", [])]
        ev += [("test", t, ("pass" if tests[t]["passed"] else "fail") if t in tests else "missing")
               for t in r.get("tests", [])]
        for kind, eid, st in ev or [("", "", "missing")]:
            rows.append([r["id"], r.get("component", ""), r["text"], r["source"], r["docs"], ";".join(r["code"]),
                         kind, eid, st])
    with open(out / "rtm.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["requirement", "component", "text", "source", "docs", "code", "evidence_kind", "evidence_id",
                    "status"])
        w.writerows(rows)
    try:
        head = subprocess.run(["git", "-C", str(root), "rev-parse", "HEAD"], capture_output=True, text=True).stdout.strip()
    except OSError:
        head = "unknown"
    table = "".join("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in row) + "</tr>" for row in rows)
    (out / "rtm.html").write_text(
        f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>vdec traceability matrix</title><style>"
        f"td,th{{border:1px solid #999;padding:2px 5px;font-size:12px}}table{{border-collapse:collapse}}</style>"
        f"</head><body><h1>vdec requirements traceability matrix</h1><p>HEAD {head}; verification summary from "
        f"commit {html.escape(summary_commit)}{' (differs from HEAD)' if not summary_commit.startswith(head or '-') else ''}"
        f"; {len(requirements)} requirements, {len(problems)} problems, {len(tests)} tests.</p>"
        f"<table><tr><th>requirement</th><th>component</th><th>text</th><th>source</th><th>docs</th><th>code</th>"
        f"<th>evidence</th><th>id</th><th>status</th></tr>{table}</table><h2>Gaps</h2><ul>"
        + ("".join(f"<li>{html.escape(g)}</li>" for g in gaps) or "<li>none</li>") + "</ul></body></html>")
    if gaps:
        print(f"audit: FAIL ({len(gaps)} gaps)")
        for g in gaps[:20]:
            print("  " + g)
        return 1
    print(f"audit: PASS ({len(requirements)} requirements, {len(problems)} problems, {len(tests)} tests, 0 gaps)")
    return 0


if __name__ == "__main__":
    sys.exit(main())

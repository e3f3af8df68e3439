"""Report files: summary.json (schema vdec.verification/1), junit.xml (one test case per check),
index.html (the quick view, with the PNG figures of vdec_verify.figures beside it and links to
report.pdf and the traceability matrix) and report.pdf (typeset by vdec_verify.pdf_report).

A problem with a convergence study keeps its "convergence" record in summary.json (an optional
key of the same schema) and gets a figure of two panels: error against zone size h on log-log
axes with a line of the expected slope, and error against wall seconds (work-precision) with the
committed baseline's curve (vdec_verify.work_precision); its comparison with that baseline is the
problem's "work_precision_baseline" record, as are those of its [[work_precision]] figures.
"""
import html
import json
import math
import os
import xml.etree.ElementTree as ET
from pathlib import Path


from vdec_verify import PASS_RULE
from vdec_verify.figures import problem_figures, setup_models
from vdec_verify.pdf_report import write_pdf
from vdec_verify.provenance import harness_info, software_of_runs
from vdec_verify.work_precision import comparison, load_for_report

SUMMARY_SCHEMA = "vdec.verification/1"
PROBLEM_FIELDS = ("id", "title", "requirements", "level", "status", "metrics", "runs", "wall_seconds", "cycles",
                  "scene_sha256", "exit_code", "message", "inputs")
# The audit writes the traceability matrix here (qa/traceability/audit.py --out default).
RTM_FILE = Path(__file__).resolve().parents[3] / "reports" / "traceability" / "rtm.html"
STATUS_COLOURS = {"pass": "#c8f0c8", "fail": "#f4b8b8", "invalid": "#f8d49a"}


def counts(records):
    passed = sum(r["status"] == "pass" for r in records)
    return passed, len(records) - passed


def _finite_or_none(value):
    """JSON has no NaN or infinity: such values are written as null (the metric's message says why)."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {k: _finite_or_none(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_finite_or_none(v) for v in value]
    return value


def public_record(record):
    """The record as summary.json keeps it: plot data stays out (it goes to the PNG files)."""
    kept = {key: record[key] for key in PROBLEM_FIELDS}
    kept["metrics"] = [{k: v for k, v in m.items() if k != "plot"} for m in record["metrics"]]
    if record.get("convergence") is not None:   # optional: only problems with a [refinement] study
        kept["convergence"] = record["convergence"]
    if record.get("work_precision") is not None:  # optional: only problems with [[work_precision]] figures
        kept["work_precision"] = record["work_precision"]
    if record.get("mutations") is not None:     # only when the suite ran the mutations (level full)
        kept["mutations"] = record["mutations"]
    if record.get("work_precision_baseline") is not None:   # only problems with a curve
        kept["work_precision_baseline"] = record["work_precision_baseline"]
    return _finite_or_none(kept)


def write_summary(records, out, harness, software, disagreements):
    harness = dict(harness, software_consistent=not disagreements, software_disagreements=disagreements)
    summary = {"schema": SUMMARY_SCHEMA, "software": software, "harness": harness,
               "counts": dict(zip(("passed", "failed"), counts(records))),
               "problems": [public_record(r) for r in records]}
    path = out / "summary.json"
    path.write_text(json.dumps(summary, indent=1, allow_nan=False) + "\n")
    return path


def _failure_text(record):
    """The problem's messages, then every failing metric with its numbers."""
    lines = list(record["messages"])
    for m in record["metrics"]:
        if not m["pass"] and m["error"] is not None:
            lines.append(f"{'[' + m['variant'] + '] ' if m['variant'] else ''}{m['quantity']}: {m['norm']}, "
                         f"numerical {_number(m['numerical'])}, analytic {_number(m['reference'])}, "
                         f"error {m['error']:.6g}, tolerance {m['tolerance']:.6g}")
    return "\n".join(lines)


def _check_name(number, metric):
    variant = f"[{metric['variant']}] " if metric.get("variant") else ""
    return f"#{number} {variant}{metric['quantity']}"


def _check_failure_text(metric):
    if metric["error"] is None:
        return metric["message"] or "not evaluated"
    text = (f"{metric['norm']}: numerical {_number(metric['numerical'])}, analytic {_number(metric['reference'])}, "
            f"error {metric['error']:.6g}, tolerance {metric['tolerance']:.6g}")
    return text + (f"\n{metric['message']}" if metric["message"] else "")


def write_junit(records, out, harness, software=None):
    """junit.xml: one test case per check (classname "verification.<problem id>", name "#N quantity"),
    and one more per problem whose runs failed or that has no check to carry the failure; the
    suite's properties give the vdec version and commit and the harness commit."""
    software = software or {}
    cases = []
    for r in records:
        seconds = r["wall_seconds"] / max(len(r["metrics"]), 1)
        for n, m in enumerate(r["metrics"], start=1):
            failure = None if m["pass"] else (_result_label(m).lower(), _check_failure_text(m))
            cases.append((r, _check_name(n, m), seconds, failure))
        run_failures = [run for run in r["runs"] if run.get("message")]
        if run_failures or (r["status"] != "pass" and not any(not m["pass"] for m in r["metrics"])):
            cases.append((r, "runs", 0.0 if r["metrics"] else r["wall_seconds"],
                          (r["status"], _failure_text(r) or r["message"] or r["status"])))
    failed = sum(c[3] is not None for c in cases)
    suite = ET.Element("testsuite", name="verification", tests=str(len(cases)), failures=str(failed), errors="0",
                       skipped="0", time=f"{sum(r['wall_seconds'] for r in records):.3f}",
                       timestamp=harness["date"], hostname=harness["host"])
    properties = ET.SubElement(suite, "properties")
    for name, value in (("vdec_version", software.get("version")), ("vdec_commit", software.get("git_commit")),
                        ("vdec_build_type", software.get("build_type")), ("compiler", software.get("compiler")),
                        ("harness_version", harness.get("version")), ("harness_commit", harness.get("git_commit")),
                        ("harness_dirty", harness.get("git_dirty")), ("level", harness.get("level"))):
        ET.SubElement(properties, "property", name=name, value=str(value))
    for r, name, seconds, failure in cases:
        case = ET.SubElement(suite, "testcase", classname=f"verification.{r['id']}", name=name, time=f"{seconds:.3f}")
        case_properties = ET.SubElement(case, "properties")
        ET.SubElement(case_properties, "property", name="requirements", value=",".join(r["requirements"]))
        ET.SubElement(case_properties, "property", name="problem_status", value=r["status"])
        if failure is not None:
            kind, text = failure
            element = ET.SubElement(case, "failure", type=kind, message=text.splitlines()[0][:1000] if text else kind)
            element.text = text
    ET.indent(suite)
    path = out / "junit.xml"
    ET.ElementTree(suite).write(path, encoding="utf-8", xml_declaration=True)
    return path


def _result_label(metric):
    if metric["pass"]:
        return "PASS"
    return "INVALID" if metric["message"].startswith("invalid reference") else "FAIL"


def _number(value):
    return "" if value is None else f"{value:.10g}"


def _ratio(value):
    return "" if value is None else f"{value:.3e}"


def _review_note(metric):
    """The tolerance's basis and, for review, its ratio to the error met (LOOSE above 20)."""
    basis = metric.get("tolerance_basis")
    if not basis:
        return ""
    ratio = metric.get("tolerance_over_error")
    ratio_text = "" if ratio is None else f", tolerance/error {ratio:.3g}"
    return f"tolerance {basis}{ratio_text}" + (" LOOSE (for review)" if metric.get("loose") else "")


def _mutation_lines(record):
    """One line per mutation of a full suite: its overrides and whether the checks caught it."""
    lines = []
    for m in record.get("mutations") or ():
        verdict = "caught by " + m["rejected_by"][0] if m["caught"] else "NOT CAUGHT: " + m["message"]
        lines.append(f"mutation {m['name']} ({', '.join(m['overrides'])}): {verdict}")
    return lines


def _provenance_lines(software, harness, disagreements):
    dirty = {True: " (uncommitted changes)", False: "", None: ""}[harness["git_dirty"]]
    lines = [f"vdec {software['version']}, commit {software['git_commit']}, build {software['build_type']}, "
             f"compiler {software['compiler']}",
             f"harness {harness['version']}, commit {harness['git_commit']}{dirty}, python {harness['python']}",
             f"date {harness['date']}, host {harness['host']}"]
    lines += [f"WARNING: runs by different vdec builds: {d}" for d in disagreements]
    return lines


def _order(value):
    return "" if value is None else f"{value:.3f}"


def _study_rows(records):
    """Rows of the HTML table of convergence studies."""
    e = html.escape
    rows = []
    for r in records:
        study = r.get("convergence")
        if study is None:
            continue
        fit = set(study.get("fit_levels", study["levels"]))
        levels = "<br>".join(
            f"{'<b>' if name in fit else ''}{e(name)}{'</b>' if name in fit else ''}: h {h:.4g}, error "
            f"{_ratio(error) or 'none'}, {seconds:.3g} s"
            for name, h, error, seconds in zip(study["levels"], study["h"], study["error"], study["wall_seconds"]))
        result = "PASS" if study["pass"] else "FAIL"
        compared = r.get("work_precision_baseline") or {}
        rows.append(f'<tr><td><a href="#{e(r["id"])}">{e(r["id"])}</a></td><td>{e(study.get("quantity", ""))}'
                    f'<br><small class="note">{e(study["message"])}</small></td><td class="num">{levels}</td>'
                    f'<td class="num">{_order(study["observed_order"])}</td>'
                    f'<td class="num">{study["expected_order"]:g}</td>'
                    f'<td class="num">+- {study["order_tolerance"]:g}</td><td class="num">{_ratio(study["gci"])}</td>'
                    f'<td class="num">{_order(study["asymptotic_ratio"])}</td>'
                    f'<td class="{result.lower()}">{result}</td>'
                    f'<td><small>{e(compared.get("message", ""))}</small></td></tr>')
    return rows


def write_html(records, out, harness, software, disagreements, images):
    passed, failed = counts(records)
    e = html.escape
    overview = "".join(f'<tr><td><a href="#{e(r["id"])}">{e(r["id"])}</a></td><td class="{r["status"]}">'
                       f'{r["status"].upper()}</td><td>{e(", ".join(r["requirements"]))}</td>'
                       f'<td>{e(r["message"])}</td></tr>' for r in records)
    rows = []
    for r in records:
        metrics = r["metrics"] or [None]
        span = len(metrics)
        for i, m in enumerate(metrics):
            cells = ""
            if i == 0:
                cells += (f'<td rowspan="{span}" id="{e(r["id"])}" class="{r["status"]}"><b>{e(r["id"])}</b><br>'
                          f'{r["status"].upper()}<br><small>{e(r["title"])}</small></td>'
                          f'<td rowspan="{span}">{"<br>".join(e(q) for q in r["requirements"])}</td>')
            if m is None:
                cells += f'<td colspan="7">{e(r["message"])}</td>'
            else:
                variant = f'<i>[{e(m["variant"])}]</i> ' if m["variant"] else ""
                note = "".join(f'<br><small class="note">{e(text)}</small>' for text in (m["message"], _review_note(m))
                               if text)
                result = _result_label(m)
                cells += (f'<td>{variant}{e(m["quantity"])}{note}<details><summary>justification</summary>'
                          f'{e(m["justification"])}</details></td><td>{e(str(m["norm"]))}</td>'
                          f'<td class="num">{_number(m["numerical"])}</td><td class="num">{_number(m["reference"])}</td>'
                          f'<td class="num">{_ratio(m["error"])}</td><td class="num">{_ratio(m["tolerance"])}</td>'
                          f'<td class="{result.lower()}">{result}</td>')
            rows.append(f"<tr>{cells}</tr>")
        if r["status"] != "pass" and r["message"] and r["metrics"]:
            rows.append(f'<tr><td colspan="9" class="note">{e(r["message"])}</td></tr>')
        for line in _mutation_lines(r):
            rows.append(f'<tr><td colspan="9" class="note">{e(line)}</td></tr>')
        if images.get(r["id"]):
            shown = "".join(f'<figure><img src="{e(f["name"])}" alt="{e(f["caption"])}"><figcaption>'
                            f'{e(f["caption"])}</figcaption></figure>' for f in images[r["id"]])
            rows.append(f'<tr><td colspan="9" class="plot">{shown}</td></tr>')
    studies = _study_rows(records)
    study_table = "" if not studies else f"""<h2>Convergence studies</h2>
<table><tr><th>problem</th><th>studied quantity</th><th>levels (bold: fitted)</th><th>observed order</th>
<th>expected order</th><th>band</th><th>GCI (fine)</th><th>asymptotic ratio</th><th>result</th>
<th>against the work-precision baseline</th></tr>
{chr(10).join(studies)}
</table>
<p class="note">Observed order: least-squares slope of ln(error) against ln(h) over the fitted levels; it passes when
|observed - expected| is within the band. GCI: Roache's Grid Convergence Index of the finest level from the three finest
fitted levels (Celik et al. 2008, Fs = 1.25), a fraction of the finest value; asymptotic ratio GCI_23 / (r21^p GCI_12),
about 1 in the asymptotic range. The plots show error against h (with the expected slope) and against wall time, with
the committed baseline's curve in grey dashed. Error ratio and time ratio: this run's error and wall seconds over the
baseline's, at the finest level both have (above 1: larger or slower than the baseline).</p>
"""
    provenance = "<br>".join(e(line) for line in _provenance_lines(software, harness, disagreements))
    rtm = Path(os.path.relpath(RTM_FILE, Path(out).resolve())).as_posix()
    links = (f'<p>The full report: <a href="report.pdf">report.pdf</a> (typeset, with descriptions, set-up, '
             f'error plots, requirement-to-evidence matrix and known limitations). Requirement traceability: '
             f'<a href="{e(rtm)}">{e(rtm)}</a> (written by qa/traceability/audit.py).</p>')
    page = f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>vdec verification report</title>
<style>
body {{ font-family: sans-serif; margin: 1.5em; }}
table {{ border-collapse: collapse; margin-bottom: 1.5em; }}
th, td {{ border: 1px solid #999; padding: 3px 6px; font-size: 13px; vertical-align: top; text-align: left; }}
th {{ background: #e8e8e8; }}
td.num {{ text-align: right; font-family: monospace; white-space: nowrap; }}
.pass {{ background: {STATUS_COLOURS["pass"]}; }} .fail {{ background: {STATUS_COLOURS["fail"]}; }}
.invalid {{ background: {STATUS_COLOURS["invalid"]}; }}
.note {{ color: #555; }} details {{ font-size: 12px; color: #333; }}
td.plot {{ text-align: center; }} img {{ max-width: 100%; }}
figure {{ display: inline-block; vertical-align: top; max-width: 46em; margin: 0.4em; }}
figcaption {{ font-size: 12px; color: #333; text-align: left; }}
pre {{ background: #f4f4f4; padding: 0.6em; }}
</style></head><body>
<h1>vdec verification report</h1>
<p>{provenance}</p>
<p><b>{passed} passed, {failed} failed</b> ({len(records)} problems)</p>
{links}
<h2>Pass rule</h2>
<pre>{e(PASS_RULE)}</pre>
<h2>Problems</h2>
<table><tr><th>problem</th><th>status</th><th>requirements</th><th>message</th></tr>{overview}</table>
<h2>Checks</h2>
<table><tr><th>problem</th><th>requirement(s)</th><th>quantity</th><th>norm</th><th>numerical</th><th>analytic</th>
<th>error</th><th>tolerance</th><th>result</th></tr>
{chr(10).join(rows)}
</table>
<p class="note">For L2 and Linf checks, "numerical" and "analytic" are the norms of the two series (s);
error and tolerance are relative to s as the pass rule states.</p>
{study_table}</body></html>
"""
    path = out / "index.html"
    path.write_text(page, encoding="utf-8")
    return path


def _problem_of(problems_dir, problem_id):
    """The loaded problem.toml of a problem, or None (no problems folder, or an invalid problem)."""
    from vdec_verify.problem import ProblemError, load_problem
    path = Path(problems_dir or "") / problem_id / "problem.toml"
    try:
        return load_problem(path) if problems_dir and path.is_file() else None
    except ProblemError:
        return None


def write_reports(records, out, level="full", configuration=None, problems_dir=None, revision="1",
                  work_precision_baseline=None):
    """Writes every report file into out; returns the summary as written. `level` is the suite
    level that was run: the traceability audit expects full-level problems only in a full run.
    `configuration` (provenance.run_configuration) adds the vdec binary, problems folder, filter
    and harness files, and the verdict on whether the run qualifies its commit. problems_dir: the
    folder of problem folders (their problem.toml gives each problem's description and set-up in
    report.pdf); revision: report.pdf's revision. work_precision_baseline: the work_precision.Baseline
    the curves are compared with (None: the committed file, when there is one)."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    harness = dict(harness_info(configuration), level=level)
    baseline = work_precision_baseline if work_precision_baseline is not None else load_for_report()
    if baseline is not None:
        harness["work_precision_baseline"] = {"file": baseline.shown, "sha256": baseline.sha256}
    for r in records:
        compared = comparison(r, baseline, harness)
        if compared is not None:
            r["work_precision_baseline"] = compared
    software, disagreements = software_of_runs(records)
    setups = setup_models(records)
    figures = {r["id"]: problem_figures(r, setups[r["id"]], _problem_of(problems_dir, r["id"])) for r in records}
    for figure in (f for listed in figures.values() for f in listed):
        (out / figure["name"]).write_bytes(figure["png"])
    write_summary(records, out, harness, software, disagreements)
    write_junit(records, out, harness, software)
    write_html(records, out, harness, software, disagreements, figures)
    summary = json.loads((out / "summary.json").read_text())
    write_pdf(records, out, summary, figures, problems_dir=problems_dir, revision=revision)
    return summary


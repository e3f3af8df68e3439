"""Report files: summary.json (schema vdec.verification/1), junit.xml, index.html (with one PNG
plot per problem beside it) and report.pdf."""
import html
import json
import math
import textwrap
import xml.etree.ElementTree as ET
from pathlib import Path

from matplotlib.backends.backend_pdf import PdfPages
from matplotlib.figure import Figure  # Figure objects, not pyplot: no global state, no display needed

from vdec_verify import PASS_RULE
from vdec_verify.provenance import harness_info, software_of_runs

SUMMARY_SCHEMA = "vdec.verification/1"
PROBLEM_FIELDS = ("id", "title", "requirements", "level", "status", "metrics", "runs", "wall_seconds", "cycles",
                  "scene_sha256", "exit_code", "message")
STATUS_COLOURS = {"pass": "#c8f0c8", "fail": "#f4b8b8", "invalid": "#f8d49a"}
A4_PORTRAIT = (8.27, 11.69)
A4_LANDSCAPE = (11.69, 8.27)


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


def write_junit(records, out, harness):
    passed, failed = counts(records)
    suite = ET.Element("testsuite", name="verification", tests=str(len(records)), failures=str(failed), errors="0",
                       skipped="0", time=f"{sum(r['wall_seconds'] for r in records):.3f}",
                       timestamp=harness["date"], hostname=harness["host"])
    for r in records:
        case = ET.SubElement(suite, "testcase", classname="verification", name=r["id"], time=f"{r['wall_seconds']:.3f}")
        properties = ET.SubElement(case, "properties")
        ET.SubElement(properties, "property", name="requirements", value=",".join(r["requirements"]))
        ET.SubElement(properties, "property", name="status", value=r["status"])
        if r["status"] != "pass":
            failure = ET.SubElement(case, "failure", type=r["status"], message=(r["message"] or r["status"])[:1000])
            failure.text = _failure_text(r)
    ET.indent(suite)
    path = out / "junit.xml"
    ET.ElementTree(suite).write(path, encoding="utf-8", xml_declaration=True)
    return path


def _plotted(record):
    return [m for m in record["metrics"] if "plot" in m]


def _draw_metric(ax, metric):
    plot = metric["plot"]
    colour = "tab:green" if metric["pass"] else "tab:red"
    title = (f"[{metric['variant']}] " if metric["variant"] else "") + metric["quantity"]
    lines = textwrap.wrap(title, 52)[:2]
    lines.append(f"{'PASS' if metric['pass'] else 'FAIL'}: error {metric['error']:.2e}, tolerance {metric['tolerance']:.2e}")
    ax.set_title("\n".join(lines), fontsize=7, color="black" if metric["pass"] else "tab:red")
    if plot["kind"] == "series":
        ax.plot(plot["x"], plot["reference"], color="black", lw=2.5, alpha=0.4, label="analytic")
        ax.plot(plot["x"], plot["numerical"], color=colour, lw=1.0, ls="--", label="vdec")
        ax.set_xlabel(plot["x_label"], fontsize=7)
        ax.set_ylabel(plot["y_label"], fontsize=7)
    else:
        reference, numerical = plot["reference"], plot["numerical"]
        if plot["norm"] == "upper_bound":
            ax.axhline(reference + plot["allowed"], color="black", ls=":", lw=1, label="bound")
            ax.plot([0], [reference], "ks", ms=8, alpha=0.5, label="analytic")
        elif plot["norm"] == "scalar":
            ax.errorbar([0], [reference], yerr=[plot["allowed"]], fmt="ks", ms=8, alpha=0.5, capsize=6,
                        label="analytic +- tolerance")
        else:
            ax.plot([0], [reference], "ks", ms=8, alpha=0.5, label="analytic")
        ax.plot([1], [numerical], marker="o", color=colour, ms=8, ls="none", label="vdec")
        ax.set_xticks([0, 1], ["analytic", "vdec"], fontsize=7)
        ax.set_xlim(-0.7, 1.7)
    ax.tick_params(labelsize=6)
    ax.legend(fontsize=6, loc="best")


def _draw_metrics(fig, metrics, columns, top, bottom):
    rows = math.ceil(len(metrics) / columns)
    grid = fig.add_gridspec(rows, columns, top=top, bottom=bottom, left=0.08, right=0.97, hspace=0.75, wspace=0.35)
    for i, metric in enumerate(metrics):
        _draw_metric(fig.add_subplot(grid[i // columns, i % columns]), metric)


def write_plot(record, out):
    """OUT/<ID>.png with one panel per evaluated check; None when nothing could be evaluated."""
    metrics = _plotted(record)
    if not metrics:
        return None
    columns = min(len(metrics), 3)
    rows = math.ceil(len(metrics) / columns)
    fig = Figure(figsize=(4.4 * columns, 3.4 * rows + 0.5))
    fig.suptitle(f"{record['id']}: {record['title']}", fontsize=9)
    _draw_metrics(fig, metrics, columns, top=1 - 0.75 / (3.4 * rows + 0.5), bottom=0.6 / (3.4 * rows + 0.5))
    name = f"{record['id']}.png"
    fig.savefig(out / name, dpi=90)
    return name


def _result_label(metric):
    if metric["pass"]:
        return "PASS"
    return "INVALID" if metric["message"].startswith("invalid reference") else "FAIL"


def _number(value):
    return "" if value is None else f"{value:.10g}"


def _ratio(value):
    return "" if value is None else f"{value:.3e}"


def _provenance_lines(software, harness, disagreements):
    dirty = {True: " (uncommitted changes)", False: "", None: ""}[harness["git_dirty"]]
    lines = [f"vdec {software['version']}, commit {software['git_commit']}, build {software['build_type']}, "
             f"compiler {software['compiler']}",
             f"harness {harness['version']}, commit {harness['git_commit']}{dirty}, python {harness['python']}",
             f"date {harness['date']}, host {harness['host']}"]
    lines += [f"WARNING: runs by different vdec builds: {d}" for d in disagreements]
    return lines


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
                note = f'<br><small class="note">{e(m["message"])}</small>' if m["message"] else ""
                result = _result_label(m)
                cells += (f'<td>{variant}{e(m["quantity"])}{note}<details><summary>justification</summary>'
                          f'{e(m["justification"])}</details></td><td>{e(str(m["norm"]))}</td>'
                          f'<td class="num">{_number(m["numerical"])}</td><td class="num">{_number(m["reference"])}</td>'
                          f'<td class="num">{_ratio(m["error"])}</td><td class="num">{_ratio(m["tolerance"])}</td>'
                          f'<td class="{result.lower()}">{result}</td>')
            rows.append(f"<tr>{cells}</tr>")
        if r["status"] != "pass" and r["message"] and r["metrics"]:
            rows.append(f'<tr><td colspan="9" class="note">{e(r["message"])}</td></tr>')
        if images.get(r["id"]):
            rows.append(f'<tr><td colspan="9" class="plot"><img src="{e(images[r["id"]])}" '
                        f'alt="{e(r["id"])}: vdec against the closed form"></td></tr>')
    provenance = "<br>".join(e(line) for line in _provenance_lines(software, harness, disagreements))
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
pre {{ background: #f4f4f4; padding: 0.6em; }}
</style></head><body>
<h1>vdec verification report</h1>
<p>{provenance}</p>
<p><b>{passed} passed, {failed} failed</b> ({len(records)} problems)</p>
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
</body></html>
"""
    path = out / "index.html"
    path.write_text(page, encoding="utf-8")
    return path


def _text_page(pdf, lines, landscape=False, fontsize=8):
    fig = Figure(figsize=A4_LANDSCAPE if landscape else A4_PORTRAIT)
    fig.text(0.05, 0.96, "\n".join(lines), va="top", ha="left", family="monospace", fontsize=fontsize)
    pdf.savefig(fig)


def _metric_lines(metric, width):
    result = _result_label(metric)
    head = (f"[{metric['variant']}] " if metric["variant"] else "") + metric["quantity"]
    lines = textwrap.wrap(f"{result}  {head}", width)
    if metric["error"] is not None:
        lines.append(f"      {metric['norm']}: numerical {_number(metric['numerical'])}, analytic "
                     f"{_number(metric['reference'])}, error {_ratio(metric['error'])}, "
                     f"tolerance {_ratio(metric['tolerance'])}")
    if metric["message"]:
        lines += textwrap.wrap(metric["message"], width, initial_indent="      ", subsequent_indent="      ")
    lines += textwrap.wrap("justification: " + metric["justification"], width, initial_indent="      ",
                           subsequent_indent="      ")
    return lines


def write_pdf(records, out, harness, software, disagreements):
    passed, failed = counts(records)
    path = out / "report.pdf"
    with PdfPages(path) as pdf:
        title = ["vdec verification report", ""] + _provenance_lines(software, harness, disagreements)
        title += ["", f"{passed} passed, {failed} failed ({len(records)} problems)", "", "Pass rule:", ""]
        title += PASS_RULE.splitlines()
        title += ["", "Problems:"] + [f"  {r['status'].upper():8s} {r['id']}" for r in records]
        _text_page(pdf, title)

        header = f"{'problem':28s} {'requirements':34s} {'quantity':58s} {'error':>10s} {'tolerance':>10s} result"
        table = []
        for r in records:
            for m in r["metrics"] or [None]:
                if m is None:
                    table.append(f"{r['id'][:28]:28s} {', '.join(r['requirements'])[:34]:34s} "
                                 f"{r['message'][:58]:58s} {'':>10s} {'':>10s} {r['status'].upper()}")
                    continue
                quantity = (f"[{m['variant']}] " if m["variant"] else "") + m["quantity"]
                table.append(f"{r['id'][:28]:28s} {', '.join(r['requirements'])[:34]:34s} {quantity[:58]:58s} "
                             f"{_ratio(m['error']):>10s} {_ratio(m['tolerance']):>10s} "
                             f"{_result_label(m)}")
        per_page = 52
        for start in range(0, max(len(table), 1), per_page):
            _text_page(pdf, ["Checks", "", header, "-" * len(header)] + table[start:start + per_page],
                       landscape=True, fontsize=6.5)

        for r in records:
            fig = Figure(figsize=A4_PORTRAIT)
            fig.suptitle(f"{r['id']} ({r['status'].upper()})\n" + "\n".join(textwrap.wrap(r["title"], 90)),
                         fontsize=10)
            metrics = _plotted(r)
            text_top = 0.90
            if metrics:
                columns = min(len(metrics), 2)
                rows = math.ceil(len(metrics) / columns)
                bottom = max(0.90 - 0.2 * rows, 0.42)
                _draw_metrics(fig, metrics, columns, top=0.88, bottom=bottom)
                text_top = bottom - 0.05
            lines = [f"requirements: {', '.join(r['requirements'])}", f"wall {r['wall_seconds']:.2f} s, "
                     f"cycles {r['cycles']}, scene sha256 {r['scene_sha256']}"]
            if r["message"]:
                lines += textwrap.wrap("message: " + r["message"], 110)
            lines.append("")
            for m in r["metrics"]:
                lines += _metric_lines(m, 110)
            fig.text(0.05, text_top, "\n".join(lines[:70]), va="top", ha="left", family="monospace", fontsize=6.5)
            pdf.savefig(fig)
        info = pdf.infodict()
        info["Title"] = "vdec verification report"
        info["Subject"] = f"vdec {software['version']} commit {software['git_commit']}"
    return path


def write_reports(records, out, level="full"):
    """Writes every report file into out; returns the summary as written. `level` is the suite
    level that was run: the traceability audit expects full-level problems only in a full run."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    harness = dict(harness_info(), level=level)
    software, disagreements = software_of_runs(records)
    images = {r["id"]: write_plot(r, out) for r in records}
    write_summary(records, out, harness, software, disagreements)
    write_junit(records, out, harness)
    write_html(records, out, harness, software, disagreements, images)
    write_pdf(records, out, harness, software, disagreements)
    return json.loads((out / "summary.json").read_text())


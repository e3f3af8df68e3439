"""Report files: summary.json (schema vdec.verification/1), junit.xml, index.html (with one PNG
plot per problem beside it) and report.pdf.

A problem with a convergence study keeps its "convergence" record in summary.json (an optional
key of the same schema) and gets two more panels in its plot: error against zone size h on
log-log axes with a line of the expected slope, and error against wall seconds (work-precision).
"""
import html
import json
import math
import textwrap
import xml.etree.ElementTree as ET
from pathlib import Path

from matplotlib.backends.backend_pdf import PdfPages
from matplotlib.figure import Figure  # Figure objects, not pyplot: no global state, no display needed
from matplotlib.ticker import FixedLocator, FuncFormatter, NullFormatter
import numpy as np

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
    if record.get("convergence") is not None:   # optional: only problems with a [refinement] study
        kept["convergence"] = record["convergence"]
    if record.get("mutations") is not None:     # only when the suite ran the mutations (level full)
        kept["mutations"] = record["mutations"]
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


def _study_points(study, abscissa):
    """(x, error, names) of the levels whose error and abscissa can go on log axes."""
    points = [(x, e, name) for x, e, name in zip(study[abscissa], study["error"], study["levels"])
              if x is not None and e is not None and math.isfinite(x) and math.isfinite(e) and x > 0 and e > 0]
    return [p[0] for p in points], [p[1] for p in points], [p[2] for p in points]


def _study_axes(ax, study, x, errors, names, colour, xlabel, title):
    ax.set_title(title, fontsize=7, color="black" if study["pass"] else "tab:red")
    ax.set_xlabel(xlabel, fontsize=7)
    ax.set_ylabel(f"error ({study.get('norm', '')})", fontsize=7)
    ax.tick_params(labelsize=6)
    if not errors:
        ax.text(0.5, 0.5, "no positive finite errors to plot", ha="center", va="center", transform=ax.transAxes,
                fontsize=7, color="tab:red")
        return False
    ax.loglog(x, errors, marker="o", color=colour, lw=0.8, label="vdec")
    for xi, ei, name in zip(x, errors, names):
        ax.annotate(name, (xi, ei), textcoords="offset points", xytext=(4, 4), fontsize=6)
    return True


def _data_ticks(axis, values, at_most=6):
    """Tick labels at the data (at most `at_most` of them, ends kept): a study spans a decade or two,
    where log axes label few decades and their minor labels collide."""
    values = sorted(set(values))
    if len(values) > at_most:
        step = math.ceil((len(values) - 1) / (at_most - 1))
        values = values[::step] + ([values[-1]] if (len(values) - 1) % step else [])
    axis.set_major_locator(FixedLocator(values))
    axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:.3g}"))
    axis.set_minor_formatter(NullFormatter())


def _draw_order(ax, study):
    """Error against zone size on log-log axes, with the expected slope through the finest level and
    the least-squares fit over the asymptotic levels."""
    colour = "tab:green" if study["pass"] else "tab:red"
    observed = study["observed_order"]
    head = f"{'PASS' if study['pass'] else 'FAIL'}: observed order " + \
        ("(none)" if observed is None else f"{observed:.3f}") + \
        f", expected {study['expected_order']:g} +- {study['order_tolerance']:g}"
    gci = "" if study["gci"] is None else f"; GCI {study['gci']:.2e}, ratio {study['asymptotic_ratio']:.3f}"
    title = "\n".join(textwrap.wrap(f"convergence of {study.get('quantity', '')}", 52)[:2] + [head + gci])
    h, errors, names = _study_points(study, "h")
    if _study_axes(ax, study, h, errors, names, colour, "zone size h", title):
        span = np.array([min(h), max(h)])
        expected = study["expected_order"]
        ax.loglog(span, errors[-1] * (span / h[-1]) ** expected, color="black", ls="--", lw=1, alpha=0.6,
                  label=f"slope {expected:g} (expected)")
        fit = [(hi, ei) for hi, ei, n in zip(h, errors, names) if n in study.get("fit_levels", [])]
        if observed is not None and len(fit) >= 2:
            fh = np.array([f[0] for f in fit])
            constant = math.exp(np.mean(np.log([f[1] for f in fit])) - observed * np.mean(np.log(fh)))
            fh = np.array([fh.min(), fh.max()])
            ax.loglog(fh, constant * fh ** observed, color=colour, ls=":", lw=1.5, label=f"fit, slope {observed:.2f}")
        _data_ticks(ax.xaxis, h)
        _data_ticks(ax.yaxis, errors)
        ax.legend(fontsize=6, loc="best")


def _draw_work(ax, study):
    """Work-precision: error against the wall seconds of each level's run."""
    colour = "tab:green" if study["pass"] else "tab:red"
    title = "\n".join(textwrap.wrap(f"work-precision of {study.get('quantity', '')}", 52)[:2]
                      + ["error against wall time per level"])
    seconds, errors, names = _study_points(study, "wall_seconds")
    if _study_axes(ax, study, seconds, errors, names, colour, "wall seconds of the run", title):
        _data_ticks(ax.xaxis, [min(seconds), max(seconds)])
        _data_ticks(ax.yaxis, errors)
        ax.legend(fontsize=6, loc="best")


def _panels(record):
    """What the problem's figure shows: one panel per evaluated check, then the study's two."""
    panels = [(_draw_metric, m) for m in _plotted(record)]
    if record.get("convergence") is not None:
        panels += [(_draw_order, record["convergence"]), (_draw_work, record["convergence"])]
    return panels


def _draw_metrics(fig, panels, columns, top, bottom):
    rows = math.ceil(len(panels) / columns)
    grid = fig.add_gridspec(rows, columns, top=top, bottom=bottom, left=0.08, right=0.97, hspace=0.75, wspace=0.35)
    for i, (draw, data) in enumerate(panels):
        draw(fig.add_subplot(grid[i // columns, i % columns]), data)


def write_plot(record, out):
    """OUT/<ID>.png with one panel per evaluated check (and two per convergence study); None when
    nothing could be evaluated."""
    metrics = _panels(record)
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
        rows.append(f'<tr><td><a href="#{e(r["id"])}">{e(r["id"])}</a></td><td>{e(study.get("quantity", ""))}'
                    f'<br><small class="note">{e(study["message"])}</small></td><td class="num">{levels}</td>'
                    f'<td class="num">{_order(study["observed_order"])}</td>'
                    f'<td class="num">{study["expected_order"]:g}</td>'
                    f'<td class="num">+- {study["order_tolerance"]:g}</td><td class="num">{_ratio(study["gci"])}</td>'
                    f'<td class="num">{_order(study["asymptotic_ratio"])}</td>'
                    f'<td class="{result.lower()}">{result}</td></tr>')
    return rows


def _study_lines(study, width):
    """The convergence study of a problem as text lines for the PDF."""
    lines = [f"{'PASS' if study['pass'] else 'FAIL'}  convergence study of {study.get('quantity', '')}"[:width],
             f"      observed order {_order(study['observed_order']) or 'none'}, expected {study['expected_order']:g} "
             f"+- {study['order_tolerance']:g}, GCI {_ratio(study['gci']) or 'none'}, asymptotic ratio "
             f"{_order(study['asymptotic_ratio']) or 'none'}"]
    for name, h, error, seconds in zip(study["levels"], study["h"], study["error"], study["wall_seconds"]):
        used = "*" if name in study.get("fit_levels", []) else " "
        lines.append(f"    {used} {name:16s} h {h:<12.6g} error {_ratio(error) or 'none':>10s}  {seconds:8.3f} s")
    lines += textwrap.wrap(study["message"], width, initial_indent="      ", subsequent_indent="      ")
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
            rows.append(f'<tr><td colspan="9" class="plot"><img src="{e(images[r["id"]])}" '
                        f'alt="{e(r["id"])}: vdec against the closed form"></td></tr>')
    studies = _study_rows(records)
    study_table = "" if not studies else f"""<h2>Convergence studies</h2>
<table><tr><th>problem</th><th>studied quantity</th><th>levels (bold: fitted)</th><th>observed order</th>
<th>expected order</th><th>band</th><th>GCI (fine)</th><th>asymptotic ratio</th><th>result</th></tr>
{chr(10).join(studies)}
</table>
<p class="note">Observed order: least-squares slope of ln(error) against ln(h) over the fitted levels; it passes when
|observed - expected| is within the band. GCI: Roache's Grid Convergence Index of the finest level from the three finest
fitted levels (Celik et al. 2008, Fs = 1.25), a fraction of the finest value; asymptotic ratio GCI_23 / (r21^p GCI_12),
about 1 in the asymptotic range. The plots show error against h (with the expected slope) and against wall time.</p>
"""
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
{study_table}</body></html>
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
    for text in (metric["message"], _review_note(metric)):
        if text:
            lines += textwrap.wrap(text, width, initial_indent="      ", subsequent_indent="      ")
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
            metrics = _panels(r)
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
            if r.get("convergence") is not None:
                lines += [""] + _study_lines(r["convergence"], 110)
            for line in _mutation_lines(r):
                lines += textwrap.wrap(line, 110)
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


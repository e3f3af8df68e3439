"""Reports: summary.json (vdec.verification/1), junit.xml, index.html and report.pdf."""
import datetime
import html
import json
import platform
import socket
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.backends.backend_pdf import PdfPages  # noqa: E402

from vdec_verify import PASS_RULE  # noqa: E402


def _git_commit():
    try:
        return subprocess.run(["git", "rev-parse", "HEAD"], capture_output=True, text=True,
                              check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def _plot(record, axes_list):
    for plot, ax in zip(record["plots"], axes_list):
        ax.plot(plot["x"], plot["reference"], "k-", lw=2.5, alpha=0.45, label="analytic")
        ax.plot(plot["x"], plot["numerical"], "r--", lw=1.0, label="vdec")
        ax.set_title(plot["quantity"], fontsize=8)
        ax.legend(fontsize=7)
        ax.tick_params(labelsize=7)


def _figure(record):
    plots = record["plots"]
    scalars = [m for m in record["metrics"] if m["numerical"] is not None]
    panels = len(plots) + (1 if scalars else 0)
    if panels == 0:
        return None
    fig, axes = plt.subplots(1, panels, figsize=(4.2 * panels, 3.2), squeeze=False)
    _plot(record, axes[0][:len(plots)])
    if scalars:
        ax = axes[0][-1]
        for i, m in enumerate(scalars):
            ax.plot([i], [m["reference"]], "ks", ms=9, alpha=0.5, label="analytic" if i == 0 else None)
            ax.plot([i], [m["numerical"]], "r+", ms=12, label="vdec" if i == 0 else None)
        ax.set_xticks(range(len(scalars)))
        ax.set_xticklabels([m["quantity"][:28] for m in scalars], rotation=15, fontsize=6)
        ax.legend(fontsize=7)
    fig.suptitle(f"{record['id']}: {record['title']}", fontsize=9)
    fig.tight_layout()
    return fig


def write_reports(records, out):
    out.mkdir(parents=True, exist_ok=True)
    software = next((r["software"] for r in records if r.get("software")), None) or {}
    disagree = any(r.get("software") and r["software"] != software for r in records)
    harness = {"git_commit": _git_commit(), "date": datetime.datetime.now(datetime.timezone.utc).isoformat(),
               "host": socket.gethostname(), "python": platform.python_version(), "pass_rule": PASS_RULE,
               "software_disagreement": disagree}
    problems = [{k: r[k] for k in ("id", "title", "requirements", "status", "metrics", "wall_seconds", "cycles",
                                   "scene_sha256", "exit_code", "message")} for r in records]
    summary = {"schema": "vdec.verification/1", "software": software, "harness": harness, "problems": problems}
    (out / "summary.json").write_text(json.dumps(summary, indent=1) + "\n")

    suite = ET.Element("testsuite", name="verification", tests=str(len(records)),
                       failures=str(sum(r["status"] != "pass" for r in records)))
    for r in records:
        case = ET.SubElement(suite, "testcase", classname="verification", name=r["id"],
                             time=f"{r['wall_seconds']:.3f}")
        props = ET.SubElement(case, "properties")
        ET.SubElement(props, "property", name="requirements", value=",".join(r["requirements"]))
        if r["status"] != "pass":
            ET.SubElement(case, "failure", message=r["message"][:500]).text = json.dumps(
                [m for m in r["metrics"] if not m["pass"]], indent=1)
    ET.ElementTree(suite).write(out / "junit.xml", encoding="utf-8", xml_declaration=True)

    rows = []
    with PdfPages(out / "report.pdf") as pdf:
        fig = plt.figure(figsize=(8.27, 11.69))
        passed = sum(r["status"] == "pass" for r in records)
        lines = ["vdec verification report", "",
                 f"vdec {software.get('version', '?')}  commit {software.get('git_commit', '?')}",
                 f"build {software.get('build_type', '?')}  compiler {software.get('compiler', '?')}",
                 f"harness commit {harness['git_commit']}  host {harness['host']}", f"date {harness['date']}", "",
                 f"{passed} passed, {len(records) - passed} failed", "", "Pass rule:"]
        lines += [PASS_RULE[i:i + 95] for i in range(0, len(PASS_RULE), 95)]
        lines += [""] + [f"{r['status']:7s} {r['id']}" for r in records]
        fig.text(0.08, 0.95, "\n".join(lines), va="top", family="monospace", fontsize=8)
        pdf.savefig(fig)
        plt.close(fig)
        for r in records:
            figure = _figure(r)
            image = ""
            if figure is not None:
                name = f"{r['id']}.png"
                figure.savefig(out / name, dpi=90)
                image = f'<img src="{name}" alt="{html.escape(r["id"])}">'
                table = "\n".join(f"{m['quantity'][:60]}: error {m['error']:.3e} <= {m['tolerance']:.3e} "
                                  f"{'PASS' if m['pass'] else 'FAIL'}" for m in r["metrics"])
                figure.text(0.01, 0.005, table or r["message"][:200], fontsize=6, family="monospace")
                pdf.savefig(figure)
                plt.close(figure)
            metrics = r["metrics"] or [{"quantity": r["message"], "norm": "", "error": float("nan"),
                                        "tolerance": float("nan"), "pass": False, "numerical": None,
                                        "reference": None}]
            for i, m in enumerate(metrics):
                cls = "pass" if m["pass"] else "fail"
                num = "" if m["numerical"] is None else f"{m['numerical']:.9g}"
                ref = "" if m["reference"] is None else f"{m['reference']:.9g}"
                first = (f'<td rowspan="{len(metrics)}">{html.escape(r["id"])}<br><small>{html.escape(r["title"])}'
                         f'</small></td><td rowspan="{len(metrics)}">{html.escape(", ".join(r["requirements"]))}</td>'
                         if i == 0 else "")
                plot = f'<td rowspan="{len(metrics)}">{image}</td>' if i == 0 else ""
                rows.append(f'<tr>{first}<td>{html.escape(m["quantity"])}</td><td>{m["norm"]}</td><td>{num}</td>'
                            f'<td>{ref}</td><td>{m["error"]:.3e}</td><td>{m["tolerance"]:.3e}</td>'
                            f'<td class="{cls}">{"PASS" if m["pass"] else "FAIL"}</td>{plot}</tr>')
    page = f"""<!DOCTYPE html><html><head><meta charset="utf-8"><title>vdec verification report</title>
<style>body{{font-family:sans-serif;margin:1.5em}}table{{border-collapse:collapse}}td,th{{border:1px solid #999;
padding:3px 6px;font-size:13px;vertical-align:top}}.pass{{background:#c8f0c8}}.fail{{background:#f4b8b8}}
img{{max-width:520px}}</style></head><body><h1>vdec verification report</h1>
<p>vdec {html.escape(str(software.get('version')))} &middot; commit {html.escape(str(software.get('git_commit')))}
&middot; {html.escape(str(software.get('build_type')))} &middot; {html.escape(str(software.get('compiler')))}
&middot; harness commit {harness['git_commit']} &middot; {harness['host']} &middot; {harness['date']}</p>
<p><b>{sum(r['status'] == 'pass' for r in records)} passed, {sum(r['status'] != 'pass' for r in records)} failed.</b>
Pass rule: {html.escape(PASS_RULE)}</p>
<table><tr><th>problem</th><th>requirements</th><th>quantity</th><th>norm</th><th>numerical</th><th>analytic</th>
<th>error</th><th>tolerance</th><th>result</th><th>plot</th></tr>
{''.join(rows)}</table></body></html>"""
    (out / "index.html").write_text(page)

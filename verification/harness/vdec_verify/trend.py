"""The nightly trend page: reports/nightly/index.html and one PNG per problem beside it.

The page opens with the verdict and a table of the changes since the baseline, regressions
first, each with the run where it started: the first run of the unbroken streak, up to the
latest, in which the quantity was beyond its factor (runs that left the problem out are passed
over). Below come a table of every problem and, per problem, a figure of two panels against
the runs of the history (labelled by commit): each check's error, with its tolerance dashed in
the same colour, on a log scale; and the wall time with the baseline's and the factor's limit.
The start of a regression is a red line on the panel it concerns.
"""
import html
import io
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from vdec_verify.compare import error_beyond, status_regressed, time_beyond

PAGE_FILE = "index.html"
# The figures show the latest runs; the table's "since" looks back over the whole history.
PLOTTED_RUNS = 60
DPI = 110


def _value_beyond(change, baseline, problem, thresholds):
    """Whether a problem's record of one run shows the change (None: the run says nothing)."""
    if problem is None:
        return change.kind == "removed"
    if change.kind == "removed":
        return False
    base = baseline["problems"].get(change.problem) or {}
    if change.kind == "status":
        return status_regressed(base.get("status"), problem.get("status"))
    if change.kind == "time":
        return time_beyond(base.get("wall_seconds"), problem.get("wall_seconds"), thresholds.time_factor,
                           thresholds.time_floor)
    if change.kind == "cycles":
        cycles = problem.get("cycles")
        return bool(cycles and base.get("cycles") and cycles > thresholds.time_factor * base["cycles"])
    check = next((c for c in problem.get("checks") or [] if c["check"] == change.check), None)
    if check is None:
        return None
    if change.kind == "check":
        return not check["pass"]
    return error_beyond(change.baseline, check["error"], check["tolerance"], change.data["factor"],
                        thresholds.error_floor)


def streak_start(change, baseline, entries, thresholds):
    """The (line, entry) of the history where the regression's current streak began, or None
    when the latest run that speaks of it does not show it."""
    start = None
    for line, entry in reversed(entries):
        beyond = _value_beyond(change, baseline, entry["problems"].get(change.problem), thresholds)
        if beyond is None:
            continue
        if not beyond:
            break
        start = (line, entry)
    return start


def _run_label(entry):
    return f"{str(entry.get('commit'))[:7]}\n{str(entry.get('date'))[:10]}"


def problem_figure(problem_id, entries, baseline, thresholds, marks):
    """The PNG bytes of a problem's two panels over the runs that include it. marks: {kind: line
    of the history where a regression started}."""
    runs = [(line, entry) for line, entry in entries if problem_id in entry["problems"]][-PLOTTED_RUNS:]
    x = np.arange(len(runs))
    fig = Figure(figsize=(10.0, 3.4))
    grid = fig.add_gridspec(1, 3, width_ratios=(3.2, 1.1, 2.0), left=0.06, right=0.99, top=0.9, bottom=0.25,
                            wspace=0.35)
    errors, times, legend = fig.add_subplot(grid[0]), fig.add_subplot(grid[2]), fig.add_subplot(grid[1])
    labels = {}
    for _, entry in runs:
        for check in entry["problems"][problem_id]["checks"]:
            labels.setdefault(check["check"], check["n"])
    colours = [f"C{i % 10}" for i in range(len(labels))]
    for colour, (label, number) in zip(colours, labels.items()):
        error, tolerance = np.full(len(runs), np.nan), np.full(len(runs), np.nan)
        for i, (_, entry) in enumerate(runs):
            check = next((c for c in entry["problems"][problem_id]["checks"] if c["check"] == label), None)
            if check is not None:
                error[i] = check["error"] if check["error"] is not None and check["error"] > 0 else np.nan
                tolerance[i] = check["tolerance"] if check["tolerance"] else np.nan
        errors.plot(x, error, "o-", color=colour, ms=3, lw=1, label=f"#{number} {label[:60]}")
        errors.plot(x, tolerance, "--", color=colour, lw=0.8)
    if np.isfinite(errors.get_ylim()).all() and labels:
        errors.set_yscale("log")
    errors.set_title(f"{problem_id}: error (solid) and tolerance (dashed) of each check", fontsize=8)
    handles, names = errors.get_legend_handles_labels()
    legend.axis("off")
    if handles:
        legend.legend(handles, names, loc="center", fontsize=5.5, frameon=False)
    wall = [entry["problems"][problem_id].get("wall_seconds") for _, entry in runs]
    times.plot(x, [np.nan if w is None else w for w in wall], "o-", color="black", ms=3, lw=1, label="wall")
    base = (baseline or {}).get("problems", {}).get(problem_id) if baseline else None
    if base and base.get("wall_seconds") is not None:
        times.axhline(base["wall_seconds"], color="grey", ls=":", lw=1, label="baseline")
        limit = max(thresholds.time_factor * base["wall_seconds"], base["wall_seconds"] + thresholds.time_floor)
        times.axhline(limit, color="tab:red", ls=":", lw=1, label="limit")
    times.set_ylim(bottom=0.0)
    times.set_title("wall seconds", fontsize=8)
    times.legend(fontsize=6, loc="best")
    lines = [line for line, _ in runs]
    for kind, line in marks.items():
        if line in lines:
            axes = times if kind in ("time", "cycles") else errors
            axes.axvline(lines.index(line), color="tab:red", lw=1.5)
            axes.annotate(f"{kind} regression", (lines.index(line), 1.0), xycoords=("data", "axes fraction"),
                          fontsize=6, color="tab:red", va="bottom")
    step = max(1, len(runs) // 12)
    for axes in (errors, times):
        axes.set_xticks(x[::step], [_run_label(entry) for _, entry in runs][::step], fontsize=5.5, rotation=60)
        axes.tick_params(axis="y", labelsize=6)
        axes.set_xlim(-0.5, max(len(runs) - 0.5, 0.5))
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=DPI)
    return buffer.getvalue()


def _e(text):
    return html.escape(str(text))


STYLE = """<style>
body { font-family: sans-serif; font-size: 13px; margin: 1.5em; }
table { border-collapse: collapse; margin-bottom: 1.5em; }
th, td { border: 1px solid #bbb; padding: 2px 6px; text-align: left; vertical-align: top; }
.regression { background: #f4b8b8; } .change { background: #f4f4f4; } .pass { background: #c8f0c8; }
.fail, .invalid { background: #f4b8b8; } .corrupt { background: #f8d49a; padding: 0.5em; }
img { max-width: 100%; }
</style>"""


def write_trend_page(out, history, baseline, acceptance, comparison, thresholds, message=""):
    """Writes out/index.html and out/ID.png for every problem of the latest history entry;
    returns the page's path. comparison: the latest run against the baseline (None without one)."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    entries = history.entries
    latest = entries[-1][1] if entries else None
    changes = comparison.changes if comparison else []
    since, marks = {}, {}
    for change in changes:
        if change.regression and change.problem and baseline is not None:
            start = streak_start(change, baseline, entries, thresholds)
            if start is not None:
                since[id(change)] = start
                marks.setdefault(change.problem, {})[change.kind] = start[0]
    regressions = sum(c.regression for c in changes)
    parts = ["<!DOCTYPE html><html><head><meta charset='utf-8'><title>vdec nightly</title>", STYLE, "</head><body>",
             "<h1>vdec nightly verification</h1>"]
    if message:
        parts.append(f"<p class='corrupt'>{_e(message)}</p>")
    if latest is not None:
        parts.append(f"<p>Latest run: commit {_e(latest.get('commit'))}, {_e(latest.get('date'))}, level "
                     f"{_e(latest.get('level'))}" + (f", filter {_e(latest['filter'])}" if latest.get("filter") else "")
                     + f", {len(latest['problems'])} problems; history {_e(history.path)} ({len(entries)} runs).</p>")
    if acceptance is not None:
        parts.append(f"<p>Baseline: commit {_e(acceptance.get('commit'))}, run {_e(acceptance.get('run_date'))}, "
                     f"accepted {_e(acceptance.get('date'))} by {_e(acceptance.get('by'))}: "
                     f"<em>{_e(acceptance.get('note'))}</em></p>")
    parts.append(f"<p>Factors: a check's error x{thresholds.error_factor:g} (or its regression_factor) and above "
                 f"{thresholds.error_floor:g} of its tolerance; wall time x{thresholds.time_factor:g} and "
                 f"+{thresholds.time_floor:g} s, the fastest of the run and {thresholds.repeats} repeats; cycles "
                 f"x{thresholds.time_factor:g}.</p>")
    if comparison is not None:
        parts.append(f"<h2>{regressions} regression{'s' if regressions != 1 else ''}, "
                     f"{len(changes) - regressions} other changes since the baseline</h2>")
    if history.corrupt:
        parts.append("<div class='corrupt'><b>Lines of the history that are not entries (left out of the figures; "
                     "repair or remove them):</b><ul>" + "".join(f"<li>{_e(c)}</li>" for c in history.corrupt)
                     + "</ul></div>")
    if changes:
        parts.append("<table><tr><th></th><th>kind</th><th>problem</th><th>check</th><th>what</th>"
                     "<th>since (first run of the streak)</th></tr>")
        for change in changes:
            start = since.get(id(change))
            started = f"{_e(str(start[1].get('commit'))[:12])}, {_e(start[1].get('date'))} (history line {start[0]})" \
                if start else ""
            problem = f"<a href='#{_e(change.problem)}'>{_e(change.problem)}</a>" if change.problem else ""
            parts.append(f"<tr class='{'regression' if change.regression else 'change'}'>"
                         f"<td>{'REGRESSION' if change.regression else 'change'}</td><td>{_e(change.kind)}</td>"
                         f"<td>{problem}</td><td>{_e(change.check or '')}</td><td>{_e(change.detail)}</td>"
                         f"<td>{started}</td></tr>")
        parts.append("</table>")
    if latest is not None:
        flagged = {c.problem for c in changes if c.regression and c.problem}
        order = sorted(latest["problems"], key=lambda p: (p not in flagged, p))
        parts.append("<h2>Problems</h2><table><tr><th>problem</th><th>status</th><th>checks passed</th>"
                     "<th>wall seconds</th><th>cycles</th></tr>")
        for problem_id in order:
            record = latest["problems"][problem_id]
            good = sum(c["pass"] for c in record["checks"])
            parts.append(f"<tr><td><a href='#{_e(problem_id)}'>{_e(problem_id)}</a></td>"
                         f"<td class='{_e(record.get('status'))}'>{_e(record.get('status'))}</td>"
                         f"<td>{good}/{len(record['checks'])}</td><td>{_e(_seconds(record.get('wall_seconds')))}</td>"
                         f"<td>{_e(record.get('cycles'))}</td></tr>")
        parts.append("</table><h2>Trends</h2>")
        for problem_id in order:
            image = f"{problem_id}.png"
            (out / image).write_bytes(problem_figure(problem_id, entries, baseline, thresholds,
                                                     marks.get(problem_id, {})))
            parts.append(f"<h3 id='{_e(problem_id)}'>{_e(problem_id)}</h3>"
                         f"<img src='{_e(image)}' loading='lazy' alt='trend of {_e(problem_id)}'>")
    parts.append("</body></html>\n")
    page = out / PAGE_FILE
    page.write_text("\n".join(parts), encoding="utf-8")
    return page


def _seconds(value):
    return "" if value is None else f"{value:.3g}"

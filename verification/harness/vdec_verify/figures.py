"""The figures of the reports, drawn with matplotlib's Figure objects (no pyplot, no display) into
PNG files beside index.html, which report.pdf places with the same captions.

Each problem's figures start with its set-up (set_up_figure): the model vdec builds from the first
run's scene and overrides, at cycle 0, written by `vdec check SCENE --vtk DIR` into
<run folder>/setup/ and drawn by vdec_plot (geometry, driven boundaries, loads, where the
histories and the field checks sample).

Every figure shows the error as well as the values: a series check gets the two curves and,
below them on the same abscissa, vdec minus the closed form; the scalar checks of a problem get
one panel of error over tolerance (1 is the limit of the pass rule); a convergence study gets
error against zone size and error against wall time (work-precision). The work-precision panels
also draw the committed baseline's curve (grey, dashed; vdec_verify.work_precision).
"""
import io
import json
import math
import shlex
import subprocess
import sys
import textwrap
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure
from matplotlib.ticker import FixedLocator, FuncFormatter, NullFormatter

try:
    import vdec_plot  # noqa: F401  (python/ is on PYTHONPATH when the tests or `vdec plot` run us)
except ImportError:
    sys.path.append(str(Path(__file__).resolve().parents[3] / "python"))
from vdec_plot.errors import PlotError
from vdec_plot.figures import plastic_result_figure, read_scene, setup_figure
from vdec_plot.snapshot import read_snapshot

DPI = 150
PASS_COLOUR, FAIL_COLOUR = "tab:green", "tab:red"


def png_bytes(fig):
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=DPI)
    return buffer.getvalue()


def series_figure(metric):
    """Two stacked panels on one abscissa: both curves, then vdec minus the closed form."""
    plot = metric["plot"]
    x = np.asarray(plot["x"], dtype=float)
    numerical = np.asarray(plot["numerical"], dtype=float)
    reference = np.asarray(plot["reference"], dtype=float)
    colour = PASS_COLOUR if metric["pass"] else FAIL_COLOUR
    fig = Figure(figsize=(3.5, 3.3))
    grid = fig.add_gridspec(2, 1, height_ratios=(3, 2), hspace=0.2, left=0.2, right=0.97, top=0.93, bottom=0.14)
    top = fig.add_subplot(grid[0])
    bottom = fig.add_subplot(grid[1], sharex=top)
    top.plot(x, reference, color="black", lw=2.5, alpha=0.35, label="closed form")
    top.plot(x, numerical, color=colour, lw=1.0, ls="--", label="vdec")
    top.set_ylabel(plot["y_label"], fontsize=7)
    top.legend(fontsize=6, loc="best")
    top.tick_params(labelsize=6, labelbottom=False)
    bottom.plot(x, numerical - reference, color=colour, lw=1.0)
    bottom.axhline(0.0, color="black", lw=0.6, alpha=0.6)
    bottom.set_ylabel("vdec - closed form", fontsize=7)
    bottom.set_xlabel(plot["x_label"], fontsize=7)
    bottom.tick_params(labelsize=6)
    bottom.yaxis.get_offset_text().set_fontsize(6)
    return png_bytes(fig)


def ratio_of(metric):
    """error / tolerance, the fraction of its allowance a check uses (1 is the limit); None when
    the check has no numbers or no allowance (an exact `equal` check)."""
    error, tolerance = metric.get("error"), metric.get("tolerance")
    if error is None or tolerance is None or not (math.isfinite(error) and math.isfinite(tolerance)):
        return None
    if tolerance == 0.0:
        return None
    return error / tolerance


def scalar_figure(numbered):
    """One horizontal bar per scalar check (numbered: [(number, metric)]) of |error| / tolerance on a
    log axis, the scalar checks' error panel: the ratios span decades. An upper bound met with room
    (signed error below 0) is hatched."""
    rows = [(n, m, ratio_of(m)) for n, m in numbered]
    shown = [abs(r) for _, _, r in rows if r]
    low = 10.0 ** math.floor(math.log10(min(shown + [1e-3]))) / 3
    high = max(shown + [3.0]) * 3
    height = 1.0 + 0.17 * len(rows)
    fig = Figure(figsize=(6.6, height))
    ax = fig.add_axes([0.08, 0.6 / height, 0.88, 1 - 0.72 / height])
    for i, (n, m, ratio) in enumerate(rows):
        colour = PASS_COLOUR if m["pass"] else FAIL_COLOUR
        if not ratio:
            if m.get("error") is None:
                label = "no value"
            elif m["norm"] == "equal":
                label = "exact (equal)"
            elif ratio == 0.0:
                label = "error 0"
            else:
                label = f"error {m['error']:.3g} against a tolerance of 0"
            ax.text(low * 1.3, i, label, va="center", fontsize=6, color=colour)
            continue
        ax.barh(i, abs(ratio) - low, left=low, color="white" if ratio < 0 else colour, edgecolor=colour,
                hatch="////" if ratio < 0 else None, height=0.6)
    ax.set_xscale("log")
    ax.axvline(1.0, color="black", ls="--", lw=0.8)
    ax.set_yticks(range(len(rows)), [f"#{n}" for n, _, _ in rows], fontsize=6)
    ax.set_ylim(len(rows) - 0.5, -0.5)
    ax.set_xlim(low, high)
    ax.set_xlabel("|error| / tolerance (the pass rule's limit is 1; hatched: an upper bound with room below it)",
                  fontsize=7)
    ax.tick_params(axis="x", labelsize=6)
    return png_bytes(fig)


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


BASELINE_STYLE = dict(color="grey", ls="--", lw=1.0, alpha=0.9)


def _baseline_label(compared, what=""):
    return f"{what}baseline {str(compared.get('commit'))[:12]}"


def _draw_baseline_points(ax, points, name_key, marker, label):
    """A baseline curve (grey, dashed) of the points with a positive error and time; their x values."""
    kept = sorted((p["wall_seconds"], p["error"], p[name_key]) for p in points
                  if p.get("error") is not None and p["error"] > 0 and math.isfinite(p["error"]) and p["wall_seconds"] > 0)
    if not kept:
        return [], []
    seconds, errors, names = zip(*kept)
    ax.loglog(seconds, errors, marker=marker, mfc="none", label=label, **BASELINE_STYLE)
    for x, e, name in kept:
        ax.annotate(name, (x, e), textcoords="offset points", xytext=(4, -9), fontsize=5.5, color="grey")
    return list(seconds), list(errors)


def draw_work_precision(ax, study, compared=None):
    """Work-precision: error against the wall seconds of each level's run, with the baseline's curve
    (compared: the problem's work_precision_baseline record) when it has one."""
    colour = "tab:green" if study["pass"] else "tab:red"
    base = (compared or {}).get("study")
    against = "error against wall time per level" if compared is None else \
        f"grey dashed: the baseline of {str(compared['commit'])[:12]}" if base else "no baseline entry"
    title = "\n".join(textwrap.wrap(f"work-precision of {study.get('quantity', '')}", 52)[:2] + [against])
    seconds, errors, names = _study_points(study, "wall_seconds")
    if _study_axes(ax, study, seconds, errors, names, colour, "wall seconds of the run", title):
        base_seconds, base_errors = _draw_baseline_points(ax, base["levels"], "name", "s", _baseline_label(compared)) \
            if base else ([], [])
        _data_ticks(ax.xaxis, [min(seconds + base_seconds), max(seconds + base_seconds)])
        _data_ticks(ax.yaxis, errors + base_errors)
        ax.legend(fontsize=6, loc="best")


def study_figure(study, compared=None):
    """Error against zone size (with the expected slope) and against wall time (with the baseline's curve)."""
    fig = Figure(figsize=(6.8, 2.9))
    grid = fig.add_gridspec(1, 2, left=0.09, right=0.98, top=0.80, bottom=0.16, wspace=0.3)
    _draw_order(fig.add_subplot(grid[0]), study)
    draw_work_precision(fig.add_subplot(grid[1]), study, compared)
    return png_bytes(fig)


def draw_methods(ax, figure, compared=None):
    """Error against wall seconds, one marked line per series (method), each point labelled with its run;
    with each series' baseline curve in grey (compared: this figure's entry of the baseline comparison)."""
    ax.set_title("\n".join(textwrap.wrap(figure["title"], 70)[:2]), fontsize=7)
    ax.set_xlabel("wall seconds of the run", fontsize=7)
    ax.set_ylabel(f"error ({figure.get('norm', '')})", fontsize=7)
    ax.tick_params(labelsize=6)
    baseline_of = {s["label"]: s for s in (compared or {}).get("series", [])}
    drawn, all_errors = False, []
    for number, series in enumerate(figure["series"]):
        marker = "os^vD"[number % 5]
        points = sorted((p["wall_seconds"], p["error"], p["run"]) for p in series["points"]
                        if p["error"] is not None and p["wall_seconds"] and math.isfinite(p["error"]) and p["error"] > 0)
        base = baseline_of.get(series["label"])
        if base and base["points"]:
            all_errors += _draw_baseline_points(ax, base["points"], "run", marker,
                                                _baseline_label(compared, f"{series['label']}, "))[1]
        if not points:
            continue
        drawn = True
        seconds, errors, runs = zip(*points)
        all_errors += errors
        ax.loglog(seconds, errors, marker=marker, lw=0.8, label=series["label"])
        for x, e, run in points:
            ax.annotate(run, (x, e), textcoords="offset points", xytext=(4, 4), fontsize=6)
    if not drawn:
        ax.text(0.5, 0.5, "no positive finite errors to plot", ha="center", va="center", transform=ax.transAxes,
                fontsize=7, color="tab:red")
    else:
        _data_ticks(ax.yaxis, all_errors)
        ax.legend(fontsize=6, loc="best")


def work_precision_figure(figure, compared=None):
    """A [[work_precision]] figure (draw_methods) as PNG bytes."""
    fig = Figure(figsize=(5.0, 3.2))
    draw_methods(fig.add_axes([0.13, 0.15, 0.84, 0.72]), figure, compared)
    return png_bytes(fig)


def _result(metric):
    if metric["pass"]:
        return "PASS"
    return "INVALID" if (metric.get("message") or "").startswith("invalid reference") else "FAIL"


def _ratio(value):
    return "" if value is None else f"{value:.3e}"


SETUP_FOLDER = "setup"
SETUP_SECONDS = 60
FIELD_EXTRACTS = ("field", "field_mean", "field_peak", "field_extent")


def _check_command(run):
    """`vdec check` of a run's scene with its overrides, writing the cycle-0 model into
    <run folder>/setup; None when the run's command is not a `vdec run` one."""
    words = shlex.split(run.get("command") or "")
    if len(words) < 3 or words[1] != "run":
        return None
    command, skip = [words[0], "check", words[2]], False
    for word, following in zip(words[3:], words[4:] + [""]):
        if skip:
            skip = False
        elif word in ("--out", "--save", "--restart", "--threads"):  # run-only options and their values
            skip = True
        elif word == "--set":
            command += ["--set", following]
            skip = True
        elif word == "--profile":
            continue
    return command + ["--vtk", str(Path(run["folder"]) / SETUP_FOLDER)]


def _make_setup_model(record):
    """(snapshot path or None, why not) of the problem's first run."""
    if not record.get("runs"):
        return None, "the problem has no run"
    command = _check_command(record["runs"][0])
    if command is None:
        return None, "its run command is not `vdec run`"
    try:
        done = subprocess.run(command, capture_output=True, text=True, timeout=SETUP_SECONDS, stdin=subprocess.DEVNULL)
    except (OSError, subprocess.TimeoutExpired) as e:
        return None, f"`vdec check --vtk` did not finish: {e}"
    snapshot = Path(command[-1]) / "snapshot_000000000.vtu"
    if done.returncode != 0 or not snapshot.is_file():
        last = (done.stderr.strip().splitlines() or ["no message"])[-1]
        return None, f"`vdec check --vtk` exited {done.returncode}: {last}"
    return snapshot, ""


def setup_models(records, jobs=2):
    """{problem id: (snapshot path or None, why not)}: each problem's model at cycle 0, built by
    `vdec check` (jobs at a time)."""
    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        made = pool.map(_make_setup_model, records)
        return {r["id"]: m for r, m in zip(records, made)}


def _field_samples(problem, record):
    """[(label, x, y)]: the initial positions each field check of the problem samples, from the
    results of the run it reads (the harness's own selection, fields._selected)."""
    from vdec_verify.fields import _selected
    folders = {run["variant"]: Path(run["folder"]) for run in record.get("runs") or []}
    samples = []
    for number, check in enumerate(problem.checks if problem else (), start=1):
        if check.extract.get("kind") not in FIELD_EXTRACTS or check.variant not in folders:
            continue
        try:
            results = json.loads((folders[check.variant] / "results.json").read_text())
            _, mask, x, y, _, _ = _selected(results, check.extract)
        except Exception:  # a check that cannot select says so in its own metric; no dots here
            continue
        samples.append((f"check #{number} samples ({check.extract['of']})", x[mask], y[mask]))
    return samples


def set_up_figure(record, snapshot_path, problem=None):
    """The set-up figure of a problem from its cycle-0 model, or None when it cannot be drawn."""
    run = record["runs"][0]
    command = shlex.split(run["command"])
    try:
        snapshot = read_snapshot(snapshot_path, 0.0)
    except PlotError:
        return None
    try:  # block names and contacts place the block and joint histories; a failed run has none
        results = json.loads((Path(run["folder"]) / "results.json").read_text())
    except (OSError, ValueError):
        results = {}
    names = [b.get("name", "") for b in results.get("blocks") or []]
    variant = f" [{run['variant']}]" if run.get("variant") else ""
    try:
        fig = setup_figure(snapshot, read_scene(command[2]), names, results.get("contacts") or [],
                           _field_samples(problem, record), title=f"{record['id']}{variant}: set-up at cycle 0")
    except PlotError:
        return None
    return png_bytes(fig)


def plastic_figure(record, snapshot_path):
    """The plastic zones at the end of the first run on its cycle-0 mesh, when some zone yielded;
    else None."""
    run = record["runs"][0]
    source = Path(run["folder"]) / "results.json"
    try:
        states = (json.loads(source.read_text()).get("zones") or {}).get("plastic_state") or []
        if not any(states):
            return None
        return png_bytes(plastic_result_figure(read_snapshot(snapshot_path, 0.0), states, source,
                                               title=f"{record['id']}: plastic state at the end"))
    except (OSError, ValueError, PlotError):
        return None


def problem_figures(record, setup=None, problem=None):
    """The figures of one problem, in order: [{"name": file name, "png": bytes, "caption": text,
    "wide": bool}]; the check numbers are those of the problem's check table (1 = first metric).
    setup: (path of its cycle-0 snapshot or None, why not) from setup_models; problem: its loaded
    problem.toml, for where its field checks sample."""
    pid, figures = record["id"], []
    if setup is not None and setup[0] is not None:
        png = set_up_figure(record, setup[0], problem)
        if png is not None:
            run = record["runs"][0]
            figures.append({"name": f"{pid}-setup.png", "png": png, "wide": False, "caption":
                            f"{pid}: set-up of the run {run.get('variant') or '(plain)'} at cycle 0, as "
                            "`vdec check --vtk` builds it: blocks (grey rigid, hatched fixed; zones of deformable "
                            "blocks in thin lines), gridpoints with a driven velocity component (x, y or both; "
                            "zero when fixed), loads at the start (red arrows), where the histories sample "
                            "(stars) and where the field checks sample (dots)."})
        png = plastic_figure(record, setup[0])
        if png is not None:
            figures.append({"name": f"{pid}-plastic.png", "png": png, "wide": False, "caption":
                            f"{pid}: plastic state of the Mohr-Coulomb zones at the end of the run "
                            f"{run.get('variant') or '(plain)'} (results.json zones.plastic_state), drawn on the "
                            "mesh at cycle 0: red yielding in shear in the last step, purple in tension, olive "
                            "yielded before and elastic now, unfilled never yielded."})
    numbered = list(enumerate(record["metrics"], start=1))
    series = [(n, m) for n, m in numbered if (m.get("plot") or {}).get("kind") == "series"]
    scalars = [(n, m) for n, m in numbered if (m.get("plot") or {}).get("kind") == "scalar"]
    for n, m in series:
        variant = f"[{m['variant']}] " if m.get("variant") else ""
        figures.append({"name": f"{pid}-check{n}.png", "png": series_figure(m), "wide": False, "caption":
                        f"{pid} check #{n}, {variant}{m['quantity']}: vdec (dashed) against the closed form (grey); "
                        f"below, vdec minus the closed form. {m['norm']} error {_ratio(m['error'])}, tolerance "
                        f"{_ratio(m['tolerance'])}: {_result(m)}."})
    if scalars:
        figures.append({"name": f"{pid}-scalars.png", "png": scalar_figure(scalars), "wide": True, "caption":
                        f"{pid}: error of each scalar check (numbered as in the check table) over its tolerance, on "
                        "a log scale; the dashed line at 1 is the pass rule's limit, a bar past it fails. An upper "
                        "bound met with room to spare (vdec below the bound) is hatched."})
    compared = record.get("work_precision_baseline")
    against = f" Against the baseline: {compared['message']}." if compared else ""
    for k, figure in enumerate(record.get("work_precision") or [], start=1):
        figure_compared = None
        if compared and compared.get("commit"):
            figure_compared = dict(compared["figures"][k - 1], commit=compared["commit"])
        figures.append({"name": f"{pid}-work-precision{k}.png", "png": work_precision_figure(figure, figure_compared),
                        "wide": False,
                        "caption": f"{pid}: work-precision, {figure['title']}: the error of each check against the "
                                   "wall seconds of the run it reads (set-up included), one line per method; the "
                                   "lower and further left, the better; grey dashed, each method in the committed "
                                   f"baseline.{against}"})
    study = record.get("convergence")
    if study is not None:
        figures.append({"name": f"{pid}-convergence.png", "png": study_figure(study, compared), "wide": True,
                        "caption": f"{pid}: convergence of {study.get('quantity', '')}. Left: error against zone "
                                   "size h on log-log axes, with the expected slope through the finest level and the "
                                   "least-squares fit. Right: work-precision, error against the wall seconds of each "
                                   "level's run, and in grey dashed the committed baseline's curve."
                                   f"{against}"})
    return figures

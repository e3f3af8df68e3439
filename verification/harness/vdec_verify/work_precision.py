"""The committed work-precision baseline: each refinable problem's curve of error against wall
seconds as it stood at an accepted commit, so that a change of the code shows in the report as
a shift of the curve.

    python -m vdec_verify baseline work-precision SUMMARY --note "why" [--by NAME] [--out FILE]

takes the curves of a full-suite summary.json into FILE (default
verification/baselines/work-precision.json, schema vdec.work-precision-baseline/1):

    {"schema": ..., "updates": [{"date", "by", "note", "summary", "summary_sha256", "commit",
                                 "run_date", "level", "qualified", "machine", "problems"}, ...],
     "problems": {ID: {"update": N, "study": {"quantity", "norm", "levels": [LEVEL, ...]},
                       "figures": [{"title", "norm", "series": [{"label", "points": [POINT, ...]}]}]}}}

LEVEL is {"name", "h", "error", "wall_seconds", "cycles"} of a convergence study's level, POINT
{"run", "check", "error", "wall_seconds", "cycles"} of a [[work_precision]] figure; "update" is
the index of the update an entry was taken in. An update replaces the entries of the summary's
problems that have a curve and keeps every other entry, so a filtered full run renews only its
problems; the updates stay, oldest first, each with who made it and why.

The report (report.write_reports) compares every problem that has a curve with its entry
(`comparison`): both curves on one figure, and the ratios current / baseline of the error and
of the wall seconds at the finest level the two share (for a figure's series, at the run the
baseline spent longest on).
"""
import datetime
import getpass
import hashlib
import json
import math
import os
import sys
from dataclasses import dataclass
from pathlib import Path

from vdec_verify.problem import PLAIN_RUN_LABEL

SCHEMA = "vdec.work-precision-baseline/1"
SUMMARY_SCHEMA = "vdec.verification/1"
REPOSITORY = Path(__file__).resolve().parents[3]
DEFAULT_FILE = REPOSITORY / "verification" / "baselines" / "work-precision.json"
MACHINE_FIELDS = (("host", "harness"), ("python", "harness"), ("compiler", "software"), ("build_type", "software"))
USAGE_ERROR = 2


class BaselineError(ValueError):
    """A baseline file or a summary that cannot be used; the message names the file and the key."""


def shown_path(path):
    """The path relative to the repository when it lies inside it (as the reports print it)."""
    path = Path(path)
    try:
        return path.resolve().relative_to(REPOSITORY).as_posix()
    except ValueError:
        return str(path)


# ---------------------------------------------------------------- the curves of a summary

def _positive(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value) and value > 0


def study_levels(study):
    """The levels of a summary's convergence record, coarsest first."""
    n = len(study["levels"])
    cycles = study.get("cycles") or [None] * n
    return [{"name": name, "h": h, "error": error, "wall_seconds": seconds, "cycles": cyc}
            for name, h, error, seconds, cyc in zip(study["levels"], study["h"], study["error"],
                                                    study["wall_seconds"], cycles)]


def figure_curves(problem):
    """The problem's [[work_precision]] figures with each point's cycles (those of the run it reads)."""
    cycles = {run.get("variant") or PLAIN_RUN_LABEL: run.get("cycles") for run in problem.get("runs") or []}
    return [{"title": figure["title"], "norm": figure.get("norm", ""),
             "series": [{"label": series["label"],
                         "points": [{"run": p["run"], "check": p.get("check"), "error": p["error"],
                                     "wall_seconds": p["wall_seconds"], "cycles": cycles.get(p["run"])}
                                    for p in series["points"]]}
                        for series in figure["series"]]}
            for figure in problem.get("work_precision") or []]


def curves_of(problem):
    """{"study": ..., "figures": [...]} of a summary's problem, without the empty ones ({} when it has none)."""
    entry = {}
    if problem.get("convergence") is not None:
        study = problem["convergence"]
        entry["study"] = {"quantity": study.get("quantity", ""), "norm": study.get("norm", ""),
                          "levels": study_levels(study)}
    if problem.get("work_precision"):
        entry["figures"] = figure_curves(problem)
    return entry


# ---------------------------------------------------------------- reading and writing the file

def _fail(path, where, what):
    raise BaselineError(f"{path}: {where}: {what}")


def _check_curve_points(path, where, points, fields):
    if not isinstance(points, list) or not points:
        _fail(path, where, "must be a non-empty list")
    for i, point in enumerate(points):
        here = f"{where}[{i}]"
        if not isinstance(point, dict):
            _fail(path, here, "must be a table")
        for key, kind in fields:
            value = point.get(key)
            if kind == "name" and not (isinstance(value, str) and value):
                _fail(path, f"{here}.{key}", f"must be a non-empty string, found {value!r}")
            if kind == "positive" and not _positive(value):
                _fail(path, f"{here}.{key}", f"must be a positive finite number, found {value!r}")
            if kind == "error" and value is not None and not (isinstance(value, (int, float))
                                                             and not isinstance(value, bool) and math.isfinite(value)):
                _fail(path, f"{here}.{key}", f"must be a finite number or null, found {value!r}")
            if kind == "count" and value is not None and not (isinstance(value, int) and not isinstance(value, bool)
                                                             and value >= 0):
                _fail(path, f"{here}.{key}", f"must be a count (integer >= 0) or null, found {value!r}")


LEVEL_FIELDS = (("name", "name"), ("h", "positive"), ("error", "error"), ("wall_seconds", "positive"),
                ("cycles", "count"))
POINT_FIELDS = (("run", "name"), ("error", "error"), ("wall_seconds", "positive"), ("cycles", "count"))


def validate(data, path):
    """Raises BaselineError naming the file and the key of the first thing wrong with `data`."""
    if not isinstance(data, dict) or data.get("schema") != SCHEMA:
        found = data.get("schema") if isinstance(data, dict) else type(data).__name__
        _fail(path, "schema", f"{found!r}, not {SCHEMA!r}")
    updates, problems = data.get("updates"), data.get("problems")
    if not isinstance(updates, list) or not updates:
        _fail(path, "updates", "must be a non-empty list")
    for i, update in enumerate(updates):
        if not isinstance(update, dict) or not isinstance(update.get("commit"), str) or not update.get("note"):
            _fail(path, f"updates[{i}]", "must be a table with a commit and a note")
    if not isinstance(problems, dict):
        _fail(path, "problems", "must be a table of problem ids")
    for pid, entry in problems.items():
        where = f"problems.{pid}"
        if not isinstance(entry, dict):
            _fail(path, where, "must be a table")
        index = entry.get("update")
        if not (isinstance(index, int) and not isinstance(index, bool) and 0 <= index < len(updates)):
            _fail(path, f"{where}.update", f"must be the index of one of the {len(updates)} updates, found {index!r}")
        if "study" not in entry and "figures" not in entry:
            _fail(path, where, "has neither a study nor figures")
        if "study" in entry:
            if not isinstance(entry["study"], dict):
                _fail(path, f"{where}.study", "must be a table")
            _check_curve_points(path, f"{where}.study.levels", entry["study"].get("levels"), LEVEL_FIELDS)
        if "figures" in entry:
            if not isinstance(entry["figures"], list):
                _fail(path, f"{where}.figures", "must be a list")
            for k, figure in enumerate(entry["figures"]):
                if not isinstance(figure, dict) or not isinstance(figure.get("series"), list):
                    _fail(path, f"{where}.figures[{k}]", "must be a table with a list 'series'")
                for s, series in enumerate(figure["series"]):
                    here = f"{where}.figures[{k}].series[{s}]"
                    if not isinstance(series, dict) or not isinstance(series.get("label"), str):
                        _fail(path, here, "must be a table with a label")
                    _check_curve_points(path, f"{here}.points", series.get("points"), POINT_FIELDS)


@dataclass(frozen=True)
class Baseline:
    path: Path
    sha256: str
    updates: list
    problems: dict

    @property
    def shown(self):
        return shown_path(self.path)


def read_baseline(path):
    """The baseline in `path`, validated; BaselineError naming the file (and line or key) otherwise."""
    path = Path(path)
    try:
        raw = path.read_bytes()
        data = json.loads(raw.decode("utf-8"))
    except OSError as e:
        raise BaselineError(f"{path}: cannot be read: {e.strerror or e}") from e
    except UnicodeDecodeError as e:
        raise BaselineError(f"{path}: not UTF-8 text: {e}") from e
    except json.JSONDecodeError as e:
        raise BaselineError(f"{path}: line {e.lineno} column {e.colno}: not valid JSON: {e.msg}") from e
    validate(data, path)
    return Baseline(path, hashlib.sha256(raw).hexdigest(), data["updates"], data["problems"])


def load_for_report(path=None):
    """The baseline the report compares with: `path` when given (it must exist), else the committed
    file, or None when that is absent (every problem then says so)."""
    if path is None:
        return read_baseline(DEFAULT_FILE) if DEFAULT_FILE.is_file() else None
    return read_baseline(path)


def _read_summary(path):
    path = Path(path)
    try:
        raw = path.read_bytes()
        summary = json.loads(raw.decode("utf-8"))
    except (OSError, UnicodeDecodeError, ValueError) as e:
        raise BaselineError(f"{path}: not a readable summary.json: {e}") from e
    if not isinstance(summary, dict) or summary.get("schema") != SUMMARY_SCHEMA:
        raise BaselineError(f"{path}: key 'schema': not {SUMMARY_SCHEMA!r}: only a summary.json of the suite holds "
                            "the curves")
    level = (summary.get("harness") or {}).get("level")
    if level != "full":
        raise BaselineError(f"{path}: harness.level is {level!r}: the baseline is taken from a full suite "
                            "(vdec_verify run --level full), where every refinement level runs")
    return raw, summary


def update_baseline(summary_path, out, note, by):
    """Takes the curves of the summary.json at `summary_path` into the baseline file `out` (created
    when absent); returns the update recorded."""
    if not note or not note.strip():
        raise BaselineError("--note: say why these curves become the baseline (the note is what makes it traceable)")
    raw, summary = _read_summary(summary_path)
    out = Path(out)
    existing = read_baseline(out) if out.is_file() else None
    updates = list(existing.updates) if existing else []
    problems = dict(existing.problems) if existing else {}
    taken = {p["id"]: curves_of(p) for p in summary.get("problems") or []}
    taken = {pid: entry for pid, entry in taken.items() if entry}
    if not taken:
        raise BaselineError(f"{summary_path}: no problem has a convergence study or a [[work_precision]] figure")
    harness, software = summary.get("harness") or {}, summary.get("software") or {}
    parts = {"harness": harness, "software": software}
    update = {"date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"), "by": by,
              "note": note.strip(), "summary": shown_path(summary_path),
              "summary_sha256": hashlib.sha256(raw).hexdigest(), "commit": str(software.get("git_commit")),
              "run_date": harness.get("date"), "level": harness.get("level"), "qualified": harness.get("qualified"),
              "machine": {key: parts[part].get(key) for key, part in MACHINE_FIELDS},
              "problems": sorted(taken)}
    for pid, entry in taken.items():
        problems[pid] = dict(update=len(updates), **entry)
    record = {"schema": SCHEMA, "updates": updates + [update], "problems": dict(sorted(problems.items()))}
    from vdec_verify.baseline import _replace_atomically  # baseline imports this module for its parser
    out.parent.mkdir(parents=True, exist_ok=True)
    _replace_atomically(out, (json.dumps(record, indent=1, allow_nan=False) + "\n").encode())
    return update


# ---------------------------------------------------------------- the comparison the report shows

def ratio_text(value):
    if value is None:
        return "none"
    return f"{value:.3f}" if 0.01 <= abs(value) < 1000 else f"{value:.3g}"


def _comparable(point):
    return point.get("error") is not None and _positive(point["error"]) and _positive(point.get("wall_seconds"))


def _ratios(current, base):
    return {"error_ratio": current["error"] / base["error"], "time_ratio": current["wall_seconds"] / base["wall_seconds"]}


def compare_study(study, entry):
    """The study's levels against the baseline's: the ratios at every level both have (same name and
    h, both with a positive error and time), and those at the finest of them."""
    mine = {level["name"]: level for level in study_levels(study)}
    result = {"levels": entry["levels"], "ratios": [], "common_level": None, "error_ratio": None, "time_ratio": None,
              "changed_h": []}
    for base in entry["levels"]:
        level = mine.get(base["name"])
        if level is None:
            continue
        if not math.isclose(level["h"], base["h"], rel_tol=1e-9):
            result["changed_h"].append(base["name"])
        elif _comparable(level) and _comparable(base):
            result["ratios"].append(dict(level=base["name"], h=base["h"], **_ratios(level, base)))
    if result["ratios"]:
        finest = min(result["ratios"], key=lambda r: r["h"])
        result.update(common_level=finest["level"], error_ratio=finest["error_ratio"], time_ratio=finest["time_ratio"])
    return result


def compare_figure(figure, entry):
    """Each series of a [[work_precision]] figure against the baseline's series of the same label: the
    ratios at every run both have, and at the run the baseline spent longest on."""
    series_of = {series["label"]: series for series in (entry or {}).get("series", [])}
    compared = []
    for series in figure["series"]:
        base = series_of.get(series["label"])
        mine = {p["run"]: p for p in series["points"]}
        result = {"label": series["label"], "points": base["points"] if base else [], "ratios": [],
                  "common_run": None, "error_ratio": None, "time_ratio": None}
        for point in (base or {}).get("points", []):
            if point["run"] in mine and _comparable(mine[point["run"]]) and _comparable(point):
                result["ratios"].append(dict(run=point["run"], baseline_seconds=point["wall_seconds"],
                                             **_ratios(mine[point["run"]], point)))
        if result["ratios"]:
            costliest = max(result["ratios"], key=lambda r: r["baseline_seconds"])
            result.update(common_run=costliest["run"], error_ratio=costliest["error_ratio"],
                          time_ratio=costliest["time_ratio"])
        compared.append(result)
    return {"title": figure["title"], "series": compared}


def _machine_note(update, harness):
    there, here = (update.get("machine") or {}).get("host"), (harness or {}).get("host")
    if there and here and there != here:
        return (f"the baseline ran on host {there}, this run on {here}: the time ratios compare the machines as "
                "well as the code")
    return ""


def comparison(record, baseline, harness=None):
    """The problem's "work_precision_baseline" record of summary.json, or None when it has no curve.
    baseline: a Baseline, or None when there is no baseline file; harness: this run's provenance
    (its host is compared with the baseline's)."""
    study, figures = record.get("convergence"), record.get("work_precision") or []
    if study is None and not figures:
        return None
    if baseline is None:
        return {"file": shown_path(DEFAULT_FILE), "commit": None, "study": None, "figures": [],
                "message": f"no work-precision baseline: {shown_path(DEFAULT_FILE)} is missing"}
    entry = baseline.problems.get(record["id"])
    if entry is None:
        return {"file": baseline.shown, "commit": None, "study": None, "figures": [],
                "message": f"no baseline entry for this problem in {baseline.shown} (python -m vdec_verify "
                           "baseline work-precision SUMMARY --note WHY adds it from a full suite)"}
    update = baseline.updates[entry["update"]]
    commit = update["commit"][:12]
    result = {"file": baseline.shown, "commit": update["commit"], "run_date": update.get("run_date"),
              "machine": update.get("machine"), "note": update.get("note"), "study": None, "figures": []}
    lines = []
    if study is not None:
        if "study" not in entry:
            lines.append(f"the baseline of {commit} has no convergence study for this problem")
        else:
            result["study"] = compare_study(study, entry["study"])
            compared = result["study"]
            if compared["common_level"] is None:
                lines.append(f"no level in common with the baseline of {commit} (its levels: "
                             f"{', '.join(level['name'] for level in entry['study']['levels'])})")
            else:
                lines.append(f"at the finest common level {compared['common_level']}: error ratio "
                             f"{ratio_text(compared['error_ratio'])}, time ratio {ratio_text(compared['time_ratio'])} "
                             f"against the baseline of {commit}")
            if compared["changed_h"]:
                lines.append(f"levels with another h than in the baseline, not compared: {', '.join(compared['changed_h'])}")
    base_figures = entry.get("figures") or []
    for k, figure in enumerate(figures):
        compared = compare_figure(figure, base_figures[k] if k < len(base_figures) else None)
        result["figures"].append(compared)
        for series in compared["series"]:
            if series["common_run"] is None:
                lines.append(f"{series['label']}: no run in common with the baseline of {commit}")
            else:
                lines.append(f"{series['label']} at {series['common_run']}: error ratio "
                             f"{ratio_text(series['error_ratio'])}, time ratio {ratio_text(series['time_ratio'])} "
                             f"against the baseline of {commit}")
    note = _machine_note(update, harness)
    result["message"] = "; ".join(lines + ([note] if note else []))
    return result


# ---------------------------------------------------------------- the command

def command_work_precision_baseline(args):
    by = args.by or os.environ.get("VDEC_BASELINE_BY") or getpass.getuser()
    try:
        update = update_baseline(args.summary, args.out, args.note, by)
    except BaselineError as e:
        print(f"vdec_verify baseline work-precision: {e}", file=sys.stderr)
        return USAGE_ERROR
    print(f"work-precision baseline {shown_path(args.out)}: {len(update['problems'])} problems from commit "
          f"{update['commit'][:12]} ({update['run_date']}, level {update['level']}, host "
          f"{update['machine']['host']}), by {update['by']}: {update['note']}")
    return 0


def add_work_precision_parser(actions):
    """`baseline work-precision`, an action of the `baseline` command."""
    parser = actions.add_parser("work-precision", help="take the work-precision curves of a full-suite summary.json "
                                                       "into the committed baseline")
    parser.add_argument("summary", help="the summary.json of a full suite (vdec_verify run --level full)")
    parser.add_argument("--note", required=True, help="why these curves become the baseline")
    parser.add_argument("--by", help="who takes it (default $VDEC_BASELINE_BY, else the login name)")
    parser.add_argument("--out", default=str(DEFAULT_FILE),
                        help=f"the baseline file (default {shown_path(DEFAULT_FILE)}; created when absent)")
    return parser

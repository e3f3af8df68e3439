"""Comparing two suite runs (a baseline and the current one): what changed, and which of the
changes are regressions.

    python -m vdec_verify compare BASELINE CURRENT [--json] [--problems DIR] [--vdec PATH]
        [--error-factor F] [--error-floor R] [--time-factor F] [--time-floor S] [--repeat N | --no-repeat]

BASELINE and CURRENT are summary.json files or history entries (vdec_verify.history.load_record:
a history file's last entry, or FILE:LINE). The classes of change, and when each is a regression:

    status    a problem's status changed                   regression when it is no longer pass
    check     a check's result changed                     regression when it no longer passes
    error     a check's error grew beyond its factor       always (see error_beyond: factor and floor)
    time      a problem's wall time grew beyond the factor always, once confirmed by repeating it
    cycles    a problem's cycles grew beyond the factor    always (cycles do not vary from run to run)
    removed   a problem of the baseline did not run        unless the current run's filter left it out
                                                           or the two runs are of different levels
    added     a problem new in the current run             never
    checks    checks added or removed within a problem     never
    software  vdec's version, commit, build, compiler or binary changed     never
    harness   the harness's modules changed                                 never
    inputs    input files (problem.toml, scenes, analytic modules) changed  never
    level     the two runs are of different suite levels                    never

Exit status: 0 no regression, 1 a regression, 2 a usage or input error (the message names the file).
"""
import json
import math
import sys
import tempfile
from dataclasses import asdict, dataclass, field
from pathlib import Path

from vdec_verify.history import RecordError, load_record

# An error may double before it is a regression: discretisation errors move by a few per cent
# when a code changes legitimately, a doubling is a change of behaviour worth a look.
DEFAULT_ERROR_FACTOR = 2.0
# ... and only once it is above this fraction of its tolerance: an error of 1e-12 becoming 3e-12
# against a tolerance of 1e-6 is round-off moving, not the check losing its margin.
DEFAULT_ERROR_FLOOR = 0.01
DEFAULT_TIME_FACTOR = 1.5
# Runs shorter than a fraction of a second vary by more than half their length on a loaded machine.
DEFAULT_TIME_FLOOR_SECONDS = 0.25
DEFAULT_REPEATS = 2
COMPARE_SCHEMA = "vdec.nightly-compare/1"
USAGE_ERROR = 2


@dataclass(frozen=True)
class Thresholds:
    error_factor: float = DEFAULT_ERROR_FACTOR
    error_floor: float = DEFAULT_ERROR_FLOOR
    time_factor: float = DEFAULT_TIME_FACTOR
    time_floor: float = DEFAULT_TIME_FLOOR_SECONDS
    repeats: int = DEFAULT_REPEATS


@dataclass
class Change:
    kind: str
    regression: bool
    detail: str
    problem: str = None
    check: str = None
    baseline: object = None
    current: object = None
    data: dict = field(default_factory=dict)


class RepeatNeeded(Exception):
    """Slow problems to confirm by running them again, and no way to run them was given."""


def error_beyond(baseline_error, error, tolerance, factor, floor):
    """True when an error grew beyond factor times the baseline's and above floor times the
    tolerance. The floor is never below zero, so that an upper bound met with room (a baseline
    error below zero) is flagged once its value passes the bound by more than the floor."""
    if error is None or baseline_error is None or not math.isfinite(error):
        return False
    return error > factor * baseline_error and error > floor * (tolerance or 0.0)


def time_beyond(baseline_seconds, seconds, factor, floor):
    """True when a wall time grew beyond factor times the baseline's by more than floor seconds."""
    if seconds is None or baseline_seconds is None:
        return False
    return seconds > factor * baseline_seconds and seconds - baseline_seconds > floor


def status_regressed(baseline_status, status):
    return status != baseline_status and status != "pass"


def _matches_filter(problem_id, patterns):
    from vdec_verify.runner import matches     # the runner's own rule for --filter
    return matches(problem_id, patterns)


def _identity(entry):
    return {key: entry.get(key) for key in ("date", "commit", "harness_commit", "level", "filter", "host")}


def _dict_changes(before, after):
    """{key: [before, after]} of the keys whose values differ (a missing key is None)."""
    return {k: [before.get(k), after.get(k)] for k in sorted(set(before) | set(after)) if before.get(k) != after.get(k)}


def _provenance_changes(baseline, current):
    changes = []
    software = _dict_changes(baseline.get("software") or {}, current.get("software") or {})
    if baseline.get("vdec_sha256") != current.get("vdec_sha256"):
        software["vdec binary sha256"] = [baseline.get("vdec_sha256"), current.get("vdec_sha256")]
    if software:
        text = "; ".join(f"{k} {_short(a)} -> {_short(b)}" for k, (a, b) in software.items())
        changes.append(Change("software", False, f"vdec changed: {text}", data={"fields": software}))
    harness = _dict_changes(baseline.get("harness_files") or {}, current.get("harness_files") or {})
    if harness:
        changes.append(Change("harness", False, f"harness modules changed: {', '.join(harness)}",
                              data={"files": harness}))
    # Files of problems that only one run has are the added and removed problems' business.
    before, after = baseline.get("inputs") or {}, current.get("inputs") or {}
    inputs = {path: [before[path], after[path]] for path in sorted(set(before) & set(after))
              if before[path] != after[path]}
    both = set(baseline["problems"]) & set(current["problems"])
    touched = sorted(p for p in both if baseline["problems"][p].get("inputs") != current["problems"][p].get("inputs"))
    if inputs or touched:
        changes.append(Change("inputs", False, f"input files changed: {', '.join(inputs) or '(none listed)'}; "
                                               f"problems whose inputs changed: {', '.join(touched) or 'none'}",
                              data={"files": inputs, "problems": touched}))
    return changes


def _short(value):
    text = str(value)
    return text[:12] if len(text) == 64 or len(text) == 40 else text


class CheckFactors:
    """The per-check regression_factor of problem.toml, read only for problems that need it."""

    def __init__(self, problems_dir, default):
        self.problems_dir = Path(problems_dir) if problems_dir else None
        self.default = default
        self.notes = []
        self._by_problem = {}

    def factor(self, problem_id, number):
        """The factor of the metric numbered `number` (from 1) of the problem."""
        if problem_id not in self._by_problem:
            self._by_problem[problem_id] = self._load(problem_id)
        factors = self._by_problem[problem_id]
        value = factors[number - 1] if 0 < number <= len(factors) else None
        return self.default if value is None else value

    def _load(self, problem_id):
        if self.problems_dir is None:
            return []
        from vdec_verify.problem import ProblemError, load_problem
        path = self.problems_dir / problem_id / "problem.toml"
        try:
            problem = load_problem(path)
        except ProblemError as e:
            self.notes.append(f"{path}: the default factor applies: {str(e).splitlines()[0]}")
            return []
        factors = []
        for check in problem.checks:   # a studied check has two metrics: its finest level and the order
            factors += [check.regression_factor] * (2 if check.refinement else 1)
        return factors


def _check_changes(problem_id, before, after, thresholds, factors, compare_errors=True):
    changes = []
    base_checks = {c["check"]: c for c in before.get("checks") or []}
    checks = {c["check"]: c for c in after.get("checks") or []}
    for label, check in checks.items():
        base = base_checks.get(label)
        if base is None:
            continue
        if base["pass"] != check["pass"]:
            changes.append(Change("check", not check["pass"], f"{'passes' if check['pass'] else 'fails'} now "
                                  f"(error {_number(base['error'])} -> {_number(check['error'])}, tolerance "
                                  f"{_number(check['tolerance'])})", problem_id, label, base["pass"], check["pass"]))
            continue
        if not compare_errors or check["error"] is None or base["error"] is None or check["error"] <= base["error"]:
            continue
        factor = factors.factor(problem_id, check["n"])
        if error_beyond(base["error"], check["error"], check["tolerance"], factor, thresholds.error_floor):
            grown = check["error"] / base["error"] if base["error"] > 0 else math.inf
            changes.append(Change(
                "error", True, f"error {_number(base['error'])} -> {_number(check['error'])} (x{grown:.3g}, factor "
                f"{factor:g}; tolerance {_number(check['tolerance'])}, floor {_number(thresholds.error_floor * (check['tolerance'] or 0))})",
                problem_id, label, base["error"], check["error"],
                {"factor": factor, "tolerance": check["tolerance"], "n": check["n"]}))
    added = [label for label in checks if label not in base_checks]
    removed = [label for label in base_checks if label not in checks]
    if added or removed:
        changes.append(Change("checks", False, f"checks added: {added or 'none'}; removed: {removed or 'none'}",
                              problem_id, data={"added": added, "removed": removed}))
    return changes


def _number(value):
    return "none" if value is None else f"{value:.3g}"


def _slow_changes(baseline, current, thresholds, repeat):
    changes, to_repeat = [], []
    for problem_id in sorted(set(baseline["problems"]) & set(current["problems"])):
        before, after = baseline["problems"][problem_id], current["problems"][problem_id]
        if time_beyond(before.get("wall_seconds"), after.get("wall_seconds"), thresholds.time_factor,
                       thresholds.time_floor):
            to_repeat.append(problem_id)
        base_cycles, cycles = before.get("cycles"), after.get("cycles")
        if base_cycles and cycles and cycles > thresholds.time_factor * base_cycles:
            changes.append(Change("cycles", True, f"cycles {base_cycles} -> {cycles} (x{cycles / base_cycles:.3g}, "
                                  f"factor {thresholds.time_factor:g})", problem_id, None, base_cycles, cycles))
    if to_repeat and thresholds.repeats > 0 and repeat is None:
        raise RepeatNeeded(to_repeat)
    for problem_id in to_repeat:
        base_seconds = baseline["problems"][problem_id]["wall_seconds"]
        seconds = current["problems"][problem_id]["wall_seconds"]
        again = repeat(problem_id, thresholds.repeats) if thresholds.repeats > 0 else []
        best = min([seconds, *again])
        confirmed = time_beyond(base_seconds, best, thresholds.time_factor, thresholds.time_floor)
        repeated = f"; again {', '.join(f'{s:.3g}' for s in again)} s, best {best:.3g} s" if again else \
            "; not repeated"
        changes.append(Change(
            "time", confirmed, f"wall {base_seconds:.3g} s -> {seconds:.3g} s (x{seconds / max(base_seconds, 1e-9):.3g}, "
            f"factor {thresholds.time_factor:g}){repeated}" + ("" if confirmed else ": within the factor, noise"),
            problem_id, None, base_seconds, best, {"recorded": seconds, "repeats": again}))
    return changes


def compare(baseline, current, thresholds=Thresholds(), factors=None, repeat=None):
    """The changes from the baseline entry to the current one (history entries, see
    vdec_verify.history), regressions first. factors (CheckFactors) gives the per-check error
    factors; repeat(problem_id, n) runs a problem n more times and returns its wall seconds, and
    is needed when some problem ran slower than the factor and thresholds.repeats > 0
    (RepeatNeeded otherwise)."""
    factors = factors or CheckFactors(None, thresholds.error_factor)
    changes = []
    if baseline.get("level") != current.get("level"):
        changes.append(Change("level", False, f"suite level {baseline.get('level')} -> {current.get('level')}: "
                                              "problems and refinement levels differ by design, so errors, "
                                              "times and cycles are not compared",
                              baseline=baseline.get("level"), current=current.get("level")))
    changes += _provenance_changes(baseline, current)
    same_level = baseline.get("level") == current.get("level")
    patterns = current.get("filter") or []
    for problem_id in sorted(set(baseline["problems"]) - set(current["problems"])):
        if patterns and not _matches_filter(problem_id, patterns):
            continue        # the current run was asked for other problems
        changes.append(Change("removed", same_level, "in the baseline, not in the current run", problem_id,
                              baseline=baseline["problems"][problem_id].get("status")))
    for problem_id in sorted(set(current["problems"]) - set(baseline["problems"])):
        changes.append(Change("added", False, "new in the current run", problem_id,
                              current=current["problems"][problem_id].get("status")))
    for problem_id in sorted(set(baseline["problems"]) & set(current["problems"])):
        before, after = baseline["problems"][problem_id], current["problems"][problem_id]
        if before.get("status") != after.get("status"):
            changes.append(Change("status", status_regressed(before.get("status"), after.get("status")),
                                  f"status {before.get('status')} -> {after.get('status')}", problem_id,
                                  baseline=before.get("status"), current=after.get("status")))
        changes += _check_changes(problem_id, before, after, thresholds, factors, same_level)
    if same_level:
        changes += _slow_changes(baseline, current, thresholds, repeat)
    return sorted(changes, key=lambda c: (not c.regression, c.problem or "", c.kind))


@dataclass
class Comparison:
    baseline: dict
    current: dict
    thresholds: Thresholds
    changes: list
    notes: list

    @property
    def regressions(self):
        return [c for c in self.changes if c.regression]

    def as_json(self):
        return {"schema": COMPARE_SCHEMA, "baseline": _identity(self.baseline), "current": _identity(self.current),
                "thresholds": asdict(self.thresholds), "regressions": len(self.regressions),
                "changes": [asdict(c) for c in self.changes], "notes": self.notes}

    def as_text(self):
        lines = [f"baseline: {_describe(self.baseline)}", f"current:  {_describe(self.current)}",
                 f"factors: error x{self.thresholds.error_factor:g} above {self.thresholds.error_floor:g} of the "
                 f"tolerance; time x{self.thresholds.time_factor:g} and {self.thresholds.time_floor:g} s, "
                 f"repeated {self.thresholds.repeats} times"]
        for c in self.changes:
            where = " ".join(part for part in (c.problem, f"check '{c.check}'" if c.check else None) if part)
            lines.append(f"{'REGRESSION' if c.regression else 'change':10s} {c.kind:8s} {where + ': ' if where else ''}"
                         f"{c.detail}")
        lines += [f"note: {n}" for n in self.notes]
        count = len(self.regressions)
        lines.append(f"{count} regression{'s' if count != 1 else ''}, {len(self.changes) - count} other changes"
                     if count or self.changes else "no change")
        return "\n".join(lines)


def _describe(entry):
    return (f"commit {str(entry.get('commit'))[:12]}, {entry.get('date')}, level {entry.get('level')}"
            + (f", filter {entry['filter']}" if entry.get("filter") else "")
            + f", {len(entry['problems'])} problems")


class SuiteRepeater:
    """Runs a problem's runs again with the harness's own runner (runner.execute), in a scratch
    folder, and returns the wall seconds of each repetition (the sum over its runs)."""

    def __init__(self, vdec, problems_dir, level):
        self.vdec, self.problems_dir, self.level = Path(vdec).resolve(), Path(problems_dir), level

    def __call__(self, problem_id, count):
        from vdec_verify.problem import load_problem
        from vdec_verify.runner import execute
        problem = load_problem(self.problems_dir / problem_id / "problem.toml")
        seconds = []
        with tempfile.TemporaryDirectory(prefix="vdec-repeat-") as scratch:
            for _ in range(count):
                outcomes = [execute(problem, run, self.vdec, scratch) for run in problem.runs_at(self.level)]
                seconds.append(sum(o.wall_seconds for o in outcomes))
        return seconds


def add_threshold_options(parser):
    parser.add_argument("--error-factor", type=float, default=DEFAULT_ERROR_FACTOR, metavar="F",
                        help=f"a check's error may grow F times (default {DEFAULT_ERROR_FACTOR:g}; "
                             "regression_factor in problem.toml overrides it per check)")
    parser.add_argument("--error-floor", type=float, default=DEFAULT_ERROR_FLOOR, metavar="R",
                        help=f"growth counts only above R times the tolerance (default {DEFAULT_ERROR_FLOOR:g})")
    parser.add_argument("--time-factor", type=float, default=DEFAULT_TIME_FACTOR, metavar="F",
                        help=f"wall time and cycles may grow F times (default {DEFAULT_TIME_FACTOR:g})")
    parser.add_argument("--time-floor", type=float, default=DEFAULT_TIME_FLOOR_SECONDS, metavar="S",
                        help=f"and wall time by S seconds (default {DEFAULT_TIME_FLOOR_SECONDS:g})")
    parser.add_argument("--repeat", type=int, default=DEFAULT_REPEATS, metavar="N",
                        help=f"run a slower problem N more times and keep the fastest (default {DEFAULT_REPEATS})")
    parser.add_argument("--no-repeat", dest="repeat", action="store_const", const=0,
                        help="flag slower problems on the recorded times alone")
    parser.add_argument("--problems", default="verification/problems",
                        help="problem folders, for regression_factor and for repeating (default verification/problems)")


def thresholds_of(args):
    """Thresholds from the parsed options, or a message naming the bad option."""
    for option, value, lowest in (("--error-factor", args.error_factor, 1.0), ("--time-factor", args.time_factor, 1.0),
                                  ("--error-floor", args.error_floor, 0.0), ("--time-floor", args.time_floor, 0.0),
                                  ("--repeat", args.repeat, 0)):
        if not (math.isfinite(value) and value >= lowest):
            return f"{option} {value}: must be a finite number >= {lowest:g}"
    return Thresholds(args.error_factor, args.error_floor, args.time_factor, args.time_floor, args.repeat)


def run_comparison(baseline, current, thresholds, problems_dir, vdec):
    """The Comparison of two entries; slower problems are repeated with vdec when given."""
    factors = CheckFactors(problems_dir, thresholds.error_factor)
    repeat = SuiteRepeater(vdec, problems_dir, current.get("level") or "full") if vdec else None
    changes = compare(baseline, current, thresholds, factors, repeat)
    return Comparison(baseline, current, thresholds, changes, factors.notes)


def repeat_needed_message(error):
    return (f"{', '.join(error.args[0])} ran slower than the time factor; repeating them needs the vdec "
            "executable: give --vdec PATH, or --no-repeat to judge the recorded times alone")


def command_compare(args):
    thresholds = thresholds_of(args)
    if isinstance(thresholds, str):
        print(f"vdec_verify compare: {thresholds}", file=sys.stderr)
        return USAGE_ERROR
    if args.vdec and not Path(args.vdec).is_file():
        print(f"vdec_verify compare: --vdec {args.vdec}: no such file", file=sys.stderr)
        return USAGE_ERROR
    try:
        baseline, current = load_record(args.baseline), load_record(args.current)
        comparison = run_comparison(baseline, current, thresholds, args.problems, args.vdec)
    except RecordError as e:
        print(f"vdec_verify compare: {e}", file=sys.stderr)
        return USAGE_ERROR
    except RepeatNeeded as e:
        print(f"vdec_verify compare: {repeat_needed_message(e)}", file=sys.stderr)
        return USAGE_ERROR
    print(json.dumps(comparison.as_json(), indent=1) if args.json else comparison.as_text())
    return 1 if comparison.regressions else 0


def add_compare_parser(commands):
    parser = commands.add_parser("compare", help="compare two suite runs (summary.json or history entries)")
    parser.add_argument("baseline", help="summary.json, history file (its last entry) or FILE:LINE")
    parser.add_argument("current", help="summary.json, history file (its last entry) or FILE:LINE")
    parser.add_argument("--json", action="store_true", help="print the comparison as JSON")
    parser.add_argument("--vdec", help="the vdec executable, to repeat problems that ran slower")
    add_threshold_options(parser)
    return parser

"""Loading and validating problem.toml. Every error names the file and the key.

One folder per problem, verification/problems/<ID>/, holding problem.toml and its scene files.
Keys of problem.toml:

    id = "RB-INCLINE-SLIP"        required; must equal the folder name
    title = "..."                 required
    requirements = ["REQ-JOINT-002"]   required, at least one, each matching ^REQ-[A-Z]+-\\d{3}$
    scene = "scene.toml"          required; relative to the problem folder
    level = "base"                "base" (run in the test suite) or "full" (only in the full suite); default base
    overrides = ["solver.frac=0.2"]    extra `vdec run --set` values for every run of the problem
    expect_exit = 0               the exit code of the plain run (and default for variants); default 0
    expect_stop = "ratio"         how the plain run (and by default every run that exits 0) ends: its
                                  results.json run.stop_reason, "ratio", "cycles" or "time"; required when
                                  some run exits 0. A run expected to exit nonzero must stop on "error".
    timeout_seconds = 600         limit for each run of the problem; default 600

    [[variant]]                   optional further runs of the same scene (e.g. time-step sweeps)
    name = "frac-0.5"             required; letters, digits, ".", "_", "-"; the run goes in runs/<ID>/<name>/
    overrides = ["solver.frac=0.5"]    added after the problem's overrides
    expect_exit = 0               default: the problem's expect_exit
    expect_message = "..."        required with a nonzero expect_exit (and only then): text the run's stderr
                                  must hold, so that a stop counts only when it is for the expected reason
    expect_stop = "time"          default: the problem's expect_stop (with expect_exit 0)
    scene = "large.toml"          optional: another scene file of the problem folder for this run (a
                                  code-to-code comparison within vdec: the same problem modelled
                                  another way); default the problem's scene
    restart_after = "phase"       optional: the run is made in two: vdec run --save PHASE into the run's
                                  saved/ folder, then vdec run --restart with that state file; the
                                  variant's results are the restarted run's (a check of kind
                                  "differences" compares them with the run that did not stop)

    [[mutation]]                  at least one: a wrong model the checks must reject (run by the full suite)
    name = "ks-half"              required, like a variant name; its runs go in mutations/<ID>/<name>/
    overrides = ["joint_material[0].ks=5e9"]   required, non-empty: added after every run's own overrides
    why = "..."                   required: what the change breaks, and which check should see it
    runs = ["plain", "frac-0.5"]  optional: the runs (by variant or level name, "plain" for the plain run)
                                  made again with the change; default every run of the problem. Only the
                                  checks reading these runs are judged.

    [[check]]                     at least one
    quantity = "..."              required, human-readable
    extract = { kind = "...", ... }    required; kinds and their keys: vdec_verify.extract
    reference = { function = "module.function", params = { ... }, component = N }
             or { constant = VALUE }   required; function is looked up in the `analytic` package
                                  run_params = { dt = "run.dt" } (optional, function references): further
                                  keyword arguments read from the results.json of the run the check
                                  reads (a dotted path into run, energy, fluid, heat or phases.NAME), e.g. the time step the
                                  solver chose, for a reference of the discrete scheme
    norm = "scalar"               required: scalar | upper_bound | equal (scalar extracts), L2 | Linf (series)
    rtol = 1e-3                   at least one of rtol, atol (>= 0), not both zero for norms scalar, L2 and
                                  Linf; not used by norm "equal"; both may be zero for upper_bound (the
                                  reference is then the bound itself)
    atol = 0.0
    justification = "..."         required, non-empty: why the tolerance is fair
    tolerance_basis = "derived"   required: "derived" (from an error estimate, stated in the justification)
                                  or "measured" (set from observed errors, with a margin)
    variant = "frac-0.5"          optional: the variant whose run the check reads; default the plain run
    refinement = true             optional, default false: the studied check of the [refinement] study
    regression_factor = 5.0       optional, >= 1: how many times its error may grow over the nightly
                                  baseline's before `vdec_verify compare` calls it a regression (default
                                  vdec_verify.compare.DEFAULT_ERROR_FACTOR); for a check whose error is
                                  round-off or noise that moves more than the default allows

    [refinement]                  optional; a convergence study over zone size (vdec_verify.convergence)
    expected_order = 2.0          required, > 0
    order_tolerance = 0.3         required, > 0: the study passes when |observed - expected| <= this
    justification = "..."         required: why this band (e.g. pre-asymptotic range, norm)
    asymptotic_levels = 3         optional, default all levels: the finest N levels used for the fit and
                                  the GCI (2 <= N <= number of levels; the GCI needs N >= 3). When fewer
                                  levels run (base suite), all that ran are used.
    [[refinement.level]]          at least 2, coarsest first
    name = "n8"                   required, like a variant name; the run goes in runs/<ID>/<name>/
    h = 0.125                     required, > 0, the representative zone size; strictly decreasing in the order given
    overrides = ["block[0].zoning.nx=8"]   added after the problem's overrides
    level = "base"                "base" or "full" (default "full"): a base suite (--level base) runs the
                                  base levels, a full suite all levels

    [[work_precision]]            optional: a figure of error against wall time comparing methods
    title = "..."                 required: what is compared
    series = [{ label = "Crank-Nicolson", checks = [1, 2] }, { label = "explicit", checks = [3] }]
                                  required, one or more: each series a method, its points the listed
                                  [[check]] tables (numbered 1, 2, ... in the file's order), each drawn at
                                  its error and at the wall seconds of the run it reads; the checks use
                                  norm scalar, L2 or Linf and are not the studied check.

Rules of a study (each broken rule is a ProblemError naming the key):
  - exactly one [[check]] has refinement = true when there is a [refinement] table, and none
    when there is not; the studied check names no variant and uses norm scalar, L2 or Linf
    (its error must be >= 0 and shrink with h);
  - level names are unique, and differ from the variant names and the run files;
  - a problem at level "base" has at least two levels with level = "base", so that the test
    suite still checks an order; a problem at level "full" has no level marked "base" (it runs
    only in the full suite, where every level runs);
  - every level run must exit 0 (the study needs its results).
The studied check is evaluated on every level that runs in the suite. Its metric in
summary.json is judged on the finest level that ran (quantity suffixed "(level NAME)"); the
errors of all levels that ran feed the study, which adds the metric "observed order of
QUANTITY" (norm "order": error |observed - expected|, tolerance order_tolerance) and the
problem's "convergence" record. The problem fails when the study fails.

Runs: each [[variant]] and each refinement level of the suite is run; the plain run (scene
plus the problem's overrides) is run when some check other than the studied one names no
variant. Every run must exit with its expected code; a check of kind exit_code compares it
with a constant.
"""
import importlib
import inspect
import math
import re
import tomllib
from dataclasses import dataclass, field, replace
from pathlib import Path

from vdec_verify.extract import KINDS
from vdec_verify.fields import FLOW_QUANTITIES
from vdec_verify.norms import NORMS, SCALAR_NORMS, SERIES_NORMS

REQUIREMENT_ID = re.compile(r"^REQ-[A-Z]+-\d{3}$")
VARIANT_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9._-]*$")
ANALYTIC_PACKAGE = "analytic"
LEVELS = ("base", "full")
DEFAULT_TIMEOUT_SECONDS = 600.0
# Files the runner writes in a run folder; a variant's folder sits beside them.
RUN_FILES = ("results.json", "command.txt", "stdout.txt", "stderr.txt")

PROBLEM_KEYS = ("id", "title", "requirements", "scene", "level", "overrides", "expect_exit", "expect_stop", "work_precision",
                "timeout_seconds", "variant", "refinement", "check", "mutation")
# Tables planned for later work: named here so that using one says so rather than "unknown key".
PLANNED_KEYS = {}
VARIANT_KEYS = ("name", "scene", "overrides", "expect_exit", "expect_message", "expect_stop", "restart_after")
CHECK_KEYS = ("quantity", "extract", "reference", "norm", "rtol", "atol", "justification", "tolerance_basis",
              "variant", "refinement", "regression_factor")
MUTATION_KEYS = ("name", "overrides", "why", "runs")
# run.stop_reason of results.json: the stop criterion met, or "error" for a run that ended on an error.
STOP_REASONS = ("ratio", "cycles", "time")
ERROR_STOP = "error"
TOLERANCE_BASES = ("derived", "measured")
# Norms whose pass rule needs a positive tolerance: with rtol = atol = 0 they would demand bit-for-bit
# equality, which is what norm "equal" says openly.
TOLERANCE_NORMS = ("scalar", "L2", "Linf")
PLAIN_RUN_LABEL = "plain"
REFINEMENT_KEYS = ("expected_order", "order_tolerance", "justification", "asymptotic_levels", "level")
LEVEL_KEYS = ("name", "h", "overrides", "level")
# Norms whose error is >= 0 and shrinks with the zone size: the ones an order can be fitted to.
STUDY_NORMS = ("scalar", "L2", "Linf")
# The results.json objects a run_meta path (or a reference's run_params) may start in; "fluid" holds
# the fracture flow's counts and mass balance, "heat" the thermal clock and heat balance; "phases" a
# phase's start time and length, by name.
RUN_META_ROOTS = ("run", "energy", "fluid", "heat", "phases")
RUN_META_ROOTS_TEXT = "run, energy, fluid, heat or phases (phases.NAME.FIELD)"
# What a field extract reads: deformable-block fields, contacts, and the fluid's domains and knots.
FIELD_SOURCES = ("zones", "gridpoints", "contacts") + tuple(FLOW_QUANTITIES)
REFERENCE_KEYS = ("function", "params", "component", "constant", "run_params")


class ProblemError(Exception):
    """A problem.toml that cannot be run as written."""


@dataclass(frozen=True)
class Run:
    """One solver run of a problem: the plain run (name "") or a [[variant]]."""
    name: str
    overrides: tuple
    expect_exit: int
    expect_message: str = ""
    expect_stop: str = ""     # run.stop_reason expected; "error" for a nonzero expect_exit
    restart_after: str = ""   # a phase: the run saves its state after it, then restarts from the file
    scene: Path = None        # None: the problem's scene

    @property
    def label(self):
        return self.name or "plain"


@dataclass(frozen=True)
class Reference:
    function_name: str   # "module.function" in the analytic package; "" for a constant
    params: dict
    component: int       # None: use the function's value as it is
    constant: float      # None for a function reference
    run_params: dict = field(default_factory=dict)  # keyword -> dotted path into the run's results.json


@dataclass(frozen=True)
class Check:
    index: int
    quantity: str
    extract: dict
    reference: Reference
    norm: str
    rtol: float
    atol: float
    justification: str
    variant: str         # "" for the plain run
    refinement: bool = False   # the studied check of the problem's [refinement] study
    tolerance_basis: str = "derived"   # "derived" or "measured"
    regression_factor: float = None    # None: compare's default error growth factor


@dataclass(frozen=True)
class Mutation:
    """A [[mutation]]: overrides that make the model wrong, which the problem's checks must reject."""
    name: str
    overrides: tuple
    why: str
    runs: tuple          # names of the runs made again ("" the plain run); () every run


@dataclass(frozen=True)
class Level:
    """One [[refinement.level]]: its zone size, suite level and run."""
    name: str
    h: float
    level: str           # "base" or "full"
    run: Run


@dataclass(frozen=True)
class Refinement:
    expected_order: float
    order_tolerance: float
    justification: str
    asymptotic_levels: int   # None: all the levels that ran
    levels: tuple            # of Level, coarsest first (h strictly decreasing)

    def levels_at(self, suite_level):
        """The levels a suite of this level runs: all in a full suite, the base ones in a base suite."""
        return tuple(lv for lv in self.levels if suite_level == "full" or lv.level == "base")


@dataclass(frozen=True)
class WorkPrecision:
    """A [[work_precision]] figure: series (label, indices of the checks drawn) of error against wall time."""
    title: str
    series: tuple        # of (label, tuple of check indices from 0)


@dataclass
class Problem:
    id: str
    title: str
    requirements: list
    path: Path           # the problem.toml
    scene: Path
    level: str
    runs: list           # of Run: plain run first, then variants in file order, then refinement levels
    checks: list
    timeout_seconds: float
    refinement: Refinement = None
    mutations: tuple = ()
    work_precision: tuple = ()   # of WorkPrecision

    @property
    def folder(self):
        return self.path.parent

    @property
    def studied_check(self):
        return next((c for c in self.checks if c.refinement), None)

    def runs_at(self, suite_level):
        """The runs a suite of the given level makes: every run, less the refinement levels
        marked "full" in a base suite."""
        if self.refinement is None:
            return list(self.runs)
        skipped = {lv.name for lv in self.refinement.levels if lv not in self.refinement.levels_at(suite_level)}
        return [run for run in self.runs if run.name not in skipped]

    def mutated_runs(self, mutation, suite_level):
        """The runs of a mutation: those it names (all of the suite's when it names none), each
        with the mutation's overrides added last."""
        chosen = [run for run in self.runs_at(suite_level) if not mutation.runs or run.name in mutation.runs]
        return [replace(run, overrides=run.overrides + mutation.overrides) for run in chosen]


def find_reference_function(name):
    """The analytic function "module.function" (module may be dotted), or raise LookupError."""
    module_name, _, function_name = name.rpartition(".")
    if not module_name or not function_name:
        raise LookupError(f"'{name}' is not of the form module.function")
    try:
        module = importlib.import_module(f"{ANALYTIC_PACKAGE}.{module_name}")
    except Exception as e:  # ImportError, or an error inside the module: either way it cannot be used
        raise LookupError(f"cannot import {ANALYTIC_PACKAGE}.{module_name}: {type(e).__name__}: {e}") from e
    function = getattr(module, function_name, None)
    if not callable(function):
        raise LookupError(f"{ANALYTIC_PACKAGE}.{module_name} has no function '{function_name}'")
    return function


def _is_number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _is_text(value):
    return isinstance(value, str) and value.strip() != ""


class _Errors:
    """Collects every error in a file so that one pass shows them all."""

    def __init__(self, path):
        self.path = path
        self.messages = []

    def add(self, key, message):
        self.messages.append(f"{self.path}: key '{key}': {message}")

    def raise_any(self):
        if self.messages:
            raise ProblemError("\n".join(self.messages))


def _check_unknown(errors, table, allowed, where):
    for key in table:
        if key not in allowed:
            hint = PLANNED_KEYS.get(key) if not where else None
            errors.add(f"{where}{key}", hint or f"unknown key (allowed: {', '.join(allowed)})")


def _overrides(errors, value, key):
    if not isinstance(value, list) or not all(isinstance(o, str) for o in value):
        errors.add(key, "must be a list of strings 'key.path=value'")
        return ()
    for o in value:
        name, equals, _ = o.partition("=")
        if not equals or not name.strip():
            errors.add(key, f"'{o}' is not of the form key.path=value")
    return tuple(value)


def _exit_code(errors, value, key):
    if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= 255:
        errors.add(key, f"{value!r} is not an exit code (an integer 0..255)")
        return 0
    return value


def _extract_table(errors, table, where):
    if not isinstance(table, dict):
        errors.add(where, "must be a table { kind = ..., ... }")
        return None
    kind_name = table.get("kind")
    if kind_name not in KINDS:
        errors.add(f"{where}.kind", f"unknown extract kind {kind_name!r} (known: {', '.join(KINDS)})")
        return None
    kind = KINDS[kind_name]
    _check_unknown(errors, table, ("kind",) + kind.required + kind.optional, f"{where}.")
    for key in kind.required:
        if key not in table:
            errors.add(f"{where}.{key}", f"is required for kind '{kind_name}'")
    for key in ("history",) + (("x", "y") if kind_name == "curve" else ()):
        if key in table and not _is_text(table[key]):
            errors.add(f"{where}.{key}", "must name a history")
    if kind_name == "curve" and ("x" in table) == ("x_rate" in table):
        errors.add(f"{where}.x", "a curve needs exactly one abscissa: x (a history) or x_rate (a prescribed rate "
                                 "times the time)")
    if kind_name == "curve" and "x_rate" in table and "x_scale" in table:
        errors.add(f"{where}.x_scale", "applies to the history x, not to x_rate")
    for key in ("scale", "x_scale", "x_rate"):
        if key in table and not (_is_number(table[key]) and math.isfinite(table[key]) and table[key] != 0):
            errors.add(f"{where}.{key}", f"{table[key]!r} is not a finite nonzero number")
    for key in ("t", "t0", "level"):
        if key in table and not _is_number(table[key]):
            errors.add(f"{where}.{key}", f"{table[key]!r} is not a number")
    if "window" in table:
        w = table["window"]
        if not (isinstance(w, list) and len(w) == 2 and all(_is_number(v) for v in w) and w[0] < w[1]):
            errors.add(f"{where}.window", f"{w!r} is not [t_start, t_end] with t_start < t_end")
    if kind_name in ("field", "field_mean", "field_peak", "field_extent"):
        if table.get("of") not in FIELD_SOURCES:
            errors.add(f"{where}.of", f"{table.get('of')!r} is not one of " + ", ".join(f'"{o}"' for o in FIELD_SOURCES))
        for key in ("x", "y", "r", "angle", "centre"):
            if key in table and not (isinstance(table[key], list) and len(table[key]) == 2
                                     and all(_is_number(v) for v in table[key])):
                errors.add(f"{where}.{key}", f"{table[key]!r} is not a pair of numbers")
    if kind_name == "derived":
        inputs = table.get("inputs")
        if not isinstance(inputs, dict) or not inputs:
            errors.add(f"{where}.inputs", "must be a table of named extract tables")
        else:
            for name, sub in inputs.items():
                if isinstance(sub, dict) and "variant" in sub:
                    sub = {k: v for k, v in sub.items() if k != "variant"}
                inner = _extract_table(errors, sub, f"{where}.inputs.{name}")
                if inner is not None and inner.series:
                    errors.add(f"{where}.inputs.{name}", "must be a scalar extract")
        from vdec_verify.fields import BUILTINS
        try:
            if table.get("function") not in BUILTINS:
                find_reference_function(table.get("function", ""))
        except LookupError as e:
            errors.add(f"{where}.function", str(e))
    if "path" in table:
        path = table["path"]
        if not isinstance(path, str) or path.split(".")[0] not in RUN_META_ROOTS or "." not in path:
            errors.add(f"{where}.path", f"{path!r} is not a dotted path into {RUN_META_ROOTS_TEXT}, e.g. 'energy.initial'")
    return kind


def _reference(errors, table, where, series):
    if not isinstance(table, dict):
        errors.add(where, "must be a table { function = ..., params = {...} } or { constant = ... }")
        return None
    _check_unknown(errors, table, REFERENCE_KEYS, f"{where}.")
    if ("function" in table) == ("constant" in table):
        errors.add(where, "needs exactly one of function (module.function with params) or constant")
        return None
    if "constant" in table:
        for key in ("params", "component", "run_params"):
            if key in table:
                errors.add(f"{where}.{key}", "applies to a function reference, not to a constant")
        if not _is_number(table["constant"]):
            errors.add(f"{where}.constant", f"{table['constant']!r} is not a number")
            return None
        return Reference("", {}, None, float(table["constant"]))
    name, params, component = table["function"], table.get("params", {}), table.get("component")
    if not isinstance(params, dict):
        errors.add(f"{where}.params", "must be a table of keyword arguments")
        params = {}
    run_params = table.get("run_params", {})
    if not isinstance(run_params, dict):
        errors.add(f"{where}.run_params", "must be a table keyword = \"run.PATH\" (a number in the run's results.json)")
        run_params = {}
    for key, path in run_params.items():
        if not isinstance(path, str) or path.split(".")[0] not in RUN_META_ROOTS or "." not in path:
            errors.add(f"{where}.run_params.{key}", f"{path!r} is not a dotted path into {RUN_META_ROOTS_TEXT}, e.g. 'run.dt'")
        if key in params:
            errors.add(f"{where}.run_params.{key}", "is also given in params: give it in one of them")
    if component is not None and not isinstance(component, str) and (
            isinstance(component, bool) or not isinstance(component, int) or component < 0):
        errors.add(f"{where}.component", f"{component!r} is not a component index (0, 1, ...) or a field name")
        component = None
    if not isinstance(name, str):
        errors.add(f"{where}.function", f"{name!r} is not a name module.function")
        return None
    try:
        function = find_reference_function(name)
    except LookupError as e:
        errors.add(f"{where}.function", str(e))
        return None
    # Catch misspelt or missing parameters now rather than at run time.
    try:
        signature = inspect.signature(function)
    except (TypeError, ValueError):
        signature = None
    if signature is not None:
        try:
            if series == "field":
                # A field passes whichever coordinates the function takes, as keywords.
                coordinates = {c: None for c in ("x", "y", "r", "theta") if c in signature.parameters}
                if not coordinates:
                    raise TypeError("a field reference takes coordinates x, y, r or theta")
                signature.bind(**coordinates, **params, **dict.fromkeys(run_params))
            elif series:
                signature.bind(None, **params, **dict.fromkeys(run_params))
            else:
                signature.bind(**params, **dict.fromkeys(run_params))
        except TypeError as e:
            form = {"field": "f(x=..., y=..., r=..., theta=..., **params)"}.get(series, "f(x, **params)" if series else "f(**params)")
            errors.add(f"{where}.params", f"do not fit {ANALYTIC_PACKAGE}.{name}{signature} called as {form}: {e}")
    return Reference(name, dict(params), component, None, dict(run_params))


def _tolerance(errors, check, where, norm):
    values = {}
    for key in ("rtol", "atol"):
        if key in check:
            v = check[key]
            if not _is_number(v) or not math.isfinite(v) or v < 0:
                errors.add(f"{where}.{key}", f"{v!r} is not a tolerance (a finite number >= 0)")
            else:
                values[key] = float(v)
    if norm == "equal":
        if any(values.get(key, 0.0) != 0.0 for key in ("rtol", "atol")):
            errors.add(f"{where}.rtol", "norm 'equal' means exact equality; use norm 'scalar' for a tolerance")
    elif "rtol" not in check and "atol" not in check:
        errors.add(f"{where}.rtol", "the check has no tolerance: give rtol and/or atol")
    elif norm in TOLERANCE_NORMS and not any(values.values()) and len(values) == sum(k in check for k in ("rtol", "atol")):
        errors.add(f"{where}.rtol", f"rtol and atol are both zero: norm '{norm}' would then ask for bit-for-bit "
                                    "equality; give the tolerance the justification derives, or use norm 'equal'")
    return values.get("rtol", 0.0), values.get("atol", 0.0)


def _positive(errors, table, key, where):
    """A required finite number > 0, or None (with the error recorded)."""
    if key not in table:
        errors.add(f"{where}{key}", "is required")
        return None
    value = table[key]
    if not _is_number(value) or not math.isfinite(value) or not value > 0:
        errors.add(f"{where}{key}", f"{value!r} is not a finite number > 0")
        return None
    return float(value)


def _folder_name(errors, value, where):
    """A run's name (it names a folder), or None with the error recorded."""
    if not isinstance(value, str) or not VARIANT_NAME.match(value):
        errors.add(where, f"{value!r} is required: letters, digits, '.', '_' or '-' (it names a folder)")
        return None
    return value


def _refinement(errors, table, overrides, variant_names, problem_level):
    """The [refinement] table as a Refinement, or None when it is unusable (errors recorded)."""
    if not isinstance(table, dict):
        errors.add("refinement", "must be a table [refinement] with [[refinement.level]] tables")
        return None
    _check_unknown(errors, table, REFINEMENT_KEYS, "refinement.")
    expected = _positive(errors, table, "expected_order", "refinement.")
    band = _positive(errors, table, "order_tolerance", "refinement.")
    justification = table.get("justification", "")
    if "justification" not in table:
        errors.add("refinement.justification", "is required: why this band is fair")
    elif not _is_text(justification):
        errors.add("refinement.justification", "must say why the order band is fair (non-empty)")
    raw = table.get("level", [])
    if not isinstance(raw, list) or not all(isinstance(lv, dict) for lv in raw):
        errors.add("refinement.level", "must be an array of tables [[refinement.level]]")
        raw = []
    if len(raw) < 2:
        errors.add("refinement.level", f"a study needs at least two [[refinement.level]] tables (found {len(raw)})")
    asymptotic = table.get("asymptotic_levels")
    if asymptotic is not None and (isinstance(asymptotic, bool) or not isinstance(asymptotic, int)
                                   or not 2 <= asymptotic <= max(len(raw), 2)):
        errors.add("refinement.asymptotic_levels",
                   f"{asymptotic!r} is not a number of levels from 2 to the {len(raw)} levels given")
        asymptotic = None
    levels, previous_h = [], None
    for i, lv in enumerate(raw):
        where = f"refinement.level[{i}]"
        _check_unknown(errors, lv, LEVEL_KEYS, f"{where}.")
        name = _folder_name(errors, lv.get("name"), f"{where}.name")
        if name is None:
            pass
        elif name in RUN_FILES:
            errors.add(f"{where}.name", f"'{name}' is the name of a file in the plain run's folder")
        elif name in variant_names:
            errors.add(f"{where}.name", f"'{name}' is used by a [[variant]] (the runs share runs/<ID>/<name>/)")
        elif any(other.name == name for other in levels):
            errors.add(f"{where}.name", f"'{name}' is used by an earlier level")
        h = _positive(errors, lv, "h", f"{where}.")
        if h is not None:
            if previous_h is not None and not h < previous_h:
                errors.add(f"{where}.h", f"{h:g} is not smaller than the previous level's h {previous_h:g} "
                                         "(levels go from coarse to fine, h strictly decreasing)")
            previous_h = h
        extra = _overrides(errors, lv.get("overrides", []), f"{where}.overrides")
        suite = lv.get("level", "full")
        if suite not in LEVELS:
            errors.add(f"{where}.level", f"{suite!r} must be 'base' or 'full'")
        elif suite == "base" and problem_level == "full":
            errors.add(f"{where}.level", "'base' has no effect: the problem's level is 'full', so it runs only in "
                                         "the full suite, where every level runs")
        if name is not None and h is not None:
            levels.append(Level(name, h, suite, Run(name, overrides + extra, 0)))
    if problem_level == "base" and len(raw) >= 2:
        base = sum(lv.get("level", "full") == "base" for lv in raw)
        if base < 2:
            errors.add("refinement.level", f"the problem's level is 'base' but {base} of its levels are: give at "
                                           "least two levels level = \"base\" so that the test suite still checks "
                                           "an order (or make the problem level = \"full\")")
    if expected is None or band is None:
        return None
    return Refinement(expected, band, justification, asymptotic, tuple(levels))


def load_problem(path):
    """The Problem in problem.toml at path; raises ProblemError listing every error found."""
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as e:
        raise ProblemError(f"{path}: cannot read: {e}") from e
    errors = _Errors(path)
    _check_unknown(errors, data, PROBLEM_KEYS, "")

    for key in ("id", "title", "requirements", "scene", "check"):
        if key not in data:
            errors.add(key, "is required" + (" (at least one [[check]])" if key == "check" else ""))
    problem_id = data.get("id")
    if "id" in data and problem_id != path.parent.name:
        errors.add("id", f"{problem_id!r} must equal the folder name '{path.parent.name}'")
    title = data.get("title", "")
    if "title" in data and not _is_text(title):
        errors.add("title", "must be a non-empty string")
    requirements = data.get("requirements", [])
    if "requirements" in data:
        if not isinstance(requirements, list) or not requirements:
            errors.add("requirements", "must list at least one requirement id")
            requirements = []
        for r in requirements:
            if not isinstance(r, str) or not REQUIREMENT_ID.match(r):
                errors.add("requirements", f"{r!r} is not a requirement id like REQ-JOINT-002 (^REQ-[A-Z]+-\\d{{3}}$)")
    scene = None
    if "scene" in data:
        if not _is_text(data["scene"]):
            errors.add("scene", "must be a file name relative to the problem folder")
        else:
            scene = (path.parent / data["scene"]).resolve()
            if not scene.is_file():
                errors.add("scene", f"no file {scene}")
    level = data.get("level", "base")
    if level not in LEVELS:
        errors.add("level", f"{level!r} must be 'base' or 'full'")
    overrides = _overrides(errors, data.get("overrides", []), "overrides")
    expect_exit = _exit_code(errors, data.get("expect_exit", 0), "expect_exit")
    expect_stop = data.get("expect_stop", "")
    if "expect_stop" in data and expect_stop not in STOP_REASONS:
        errors.add("expect_stop", f"{expect_stop!r} is not a stop reason ({', '.join(STOP_REASONS)})")
        expect_stop = ""
    timeout = data.get("timeout_seconds", DEFAULT_TIMEOUT_SECONDS)
    if not _is_number(timeout) or not timeout > 0:
        errors.add("timeout_seconds", f"{timeout!r} is not a positive number of seconds")
        timeout = DEFAULT_TIMEOUT_SECONDS

    variants = []
    raw_variants = data.get("variant", [])
    if not isinstance(raw_variants, list):
        errors.add("variant", "must be an array of tables [[variant]]")
        raw_variants = []
    for i, v in enumerate(raw_variants):
        where = f"variant[{i}]"
        if not isinstance(v, dict):
            errors.add(where, "must be a table")
            continue
        _check_unknown(errors, v, VARIANT_KEYS, f"{where}.")
        name = _folder_name(errors, v.get("name"), f"{where}.name")
        if name is None:
            continue
        if name in RUN_FILES:
            errors.add(f"{where}.name", f"'{name}' is the name of a file in the plain run's folder")
            continue
        if any(other.name == name for other in variants):
            errors.add(f"{where}.name", f"'{name}' is used by an earlier variant")
            continue
        extra = _overrides(errors, v.get("overrides", []), f"{where}.overrides")
        code = _exit_code(errors, v.get("expect_exit", expect_exit), f"{where}.expect_exit")
        message = v.get("expect_message", "")
        if not isinstance(message, str) or ("expect_message" in v and (not message or code == 0)):
            errors.add(f"{where}.expect_message", "must be non-empty text, and goes with a nonzero expect_exit")
            message = ""
        elif code != 0 and "expect_message" not in v:
            errors.add(f"{where}.expect_message", f"is required with expect_exit = {code}: text of the message the "
                                                  "stop must print (naming the setting to change, e.g. "
                                                  "\"lower solver.frac\"), so that a stop for another reason fails")
        stop = _expected_stop(errors, v.get("expect_stop", expect_stop), code, f"{where}.expect_stop",
                              "expect_stop" in v)
        restart_after = v.get("restart_after", "")
        if not isinstance(restart_after, str) or ("restart_after" in v and not restart_after):
            errors.add(f"{where}.restart_after", "must be the name of a phase of the scene")
            restart_after = ""
        scene_of_run = None
        if "scene" in v:
            if not _is_text(v["scene"]):
                errors.add(f"{where}.scene", "must be a file name relative to the problem folder")
            else:
                scene_of_run = (path.parent / v["scene"]).resolve()
                if not scene_of_run.is_file():
                    errors.add(f"{where}.scene", f"no file {scene_of_run}")
        variants.append(Run(name, overrides + extra, code, message, stop, restart_after, scene_of_run))

    refinement = None
    if "refinement" in data:
        refinement = _refinement(errors, data["refinement"], overrides, {v.name for v in variants}, level)

    checks = []
    raw_checks = data.get("check", [])
    if not isinstance(raw_checks, list) or ("check" in data and not raw_checks):
        errors.add("check", "must be one or more [[check]] tables")
        raw_checks = []
    for i, c in enumerate(raw_checks):
        where = f"check[{i}]"
        if not isinstance(c, dict):
            errors.add(where, "must be a table")
            continue
        _check_unknown(errors, c, CHECK_KEYS, f"{where}.")
        for key in ("quantity", "extract", "reference", "norm", "justification"):
            if key not in c:
                errors.add(f"{where}.{key}", "is required")
        if "quantity" in c and not _is_text(c["quantity"]):
            errors.add(f"{where}.quantity", "must be a non-empty description")
        if "justification" in c and not _is_text(c["justification"]):
            errors.add(f"{where}.justification", "must say why the tolerance is fair (non-empty)")
        kind = _extract_table(errors, c["extract"], f"{where}.extract") if "extract" in c else None
        norm = c.get("norm")
        if "norm" in c:
            if norm not in NORMS:
                errors.add(f"{where}.norm", f"unknown norm {norm!r} (known: {', '.join(NORMS)})")
            elif kind is not None and norm not in (SERIES_NORMS if kind.series else SCALAR_NORMS):
                allowed = SERIES_NORMS if kind.series else SCALAR_NORMS
                errors.add(f"{where}.norm", f"norm '{norm}' does not apply to extract kind '{c['extract']['kind']}' "
                                            f"(use {' or '.join(allowed)})")
        rtol, atol = _tolerance(errors, c, where, norm)
        reference = None
        if "reference" in c:
            series = "field" if kind and c["extract"].get("kind") == "field" else bool(kind and kind.series)
            reference = _reference(errors, c["reference"], f"{where}.reference", series)
        variant = c.get("variant", "")
        if "variant" in c and not any(v.name == variant for v in variants):
            errors.add(f"{where}.variant", f"no [[variant]] named {variant!r}")
        studied = c.get("refinement", False)
        if not isinstance(studied, bool):
            errors.add(f"{where}.refinement", f"{studied!r} is not true or false")
            studied = False
        if studied:
            if "variant" in c:
                errors.add(f"{where}.variant", "a check with refinement = true reads every refinement level's run; "
                                               "it names no variant")
            if norm in NORMS and norm not in STUDY_NORMS:
                errors.add(f"{where}.norm", f"a check with refinement = true needs norm {', '.join(STUDY_NORMS)} "
                                            f"(an error >= 0 that shrinks with h), not '{norm}'")
            if "refinement" not in data:
                errors.add(f"{where}.refinement", "there is no [refinement] table with levels to study")
            earlier = next((other for other in checks if other.refinement), None)
            if earlier is not None:
                errors.add(f"{where}.refinement", f"only one check can be studied over the refinement levels "
                                                  f"(check[{earlier.index}] already is)")
        basis = c.get("tolerance_basis")
        if basis not in TOLERANCE_BASES:
            errors.add(f"{where}.tolerance_basis",
                       ("is required" if "tolerance_basis" not in c else f"{basis!r} is not allowed") +
                       ": \"derived\" (the justification derives the tolerance from an error estimate) or "
                       "\"measured\" (set from the errors observed, with a margin)")
        growth = c.get("regression_factor")
        if "regression_factor" in c and not (_is_number(growth) and math.isfinite(growth) and growth >= 1.0):
            errors.add(f"{where}.regression_factor", f"{growth!r} is not a finite number >= 1 (how many times the "
                                                     "error may grow over the nightly baseline's)")
            growth = None
        checks.append(Check(i, c.get("quantity", ""), c.get("extract"), reference, norm, rtol, atol,
                            c.get("justification", ""), variant, studied, basis,
                            None if growth is None else float(growth)))
    if "refinement" in data and raw_checks and not any(c.refinement for c in checks):
        errors.add("refinement", "no [[check]] has refinement = true: the study has nothing to study")
    runs = list(variants)
    def reads_plain(c):
        extract = c.extract if isinstance(c.extract, dict) else {}
        return (c.variant == "" and not c.refinement) or (extract.get("kind") == "differences"
                                                           and extract.get("against") == "plain")
    if any(reads_plain(c) for c in checks):
        plain_stop = _expected_stop(errors, expect_stop, expect_exit, "expect_stop", "expect_stop" in data)
        runs.insert(0, Run("", overrides, expect_exit, "", plain_stop))
    if refinement is not None:
        stop = _expected_stop(errors, expect_stop, 0, "expect_stop", "expect_stop" in data)
        refinement = replace(refinement, levels=tuple(replace(lv, run=replace(lv.run, expect_stop=stop))
                                                      for lv in refinement.levels))
        runs += [lv.run for lv in refinement.levels]
    mutations = _mutations(errors, data, [run.name for run in runs])
    work_precision = _work_precision(errors, data.get("work_precision", []), checks)
    if scene is not None:
        _check_cycle_bounds(errors, scene, runs, checks)
    errors.raise_any()
    return Problem(problem_id, title, list(requirements), path, scene, level, runs, checks, float(timeout),
                   refinement, mutations, work_precision)


def _work_precision(errors, raw, checks):
    """The [[work_precision]] tables as WorkPrecision records (errors recorded)."""
    if not isinstance(raw, list) or not all(isinstance(t, dict) for t in raw):
        errors.add("work_precision", "must be an array of tables [[work_precision]]")
        return ()
    figures = []
    for i, table in enumerate(raw):
        where = f"work_precision[{i}]"
        _check_unknown(errors, table, ("title", "series"), f"{where}.")
        if not _is_text(table.get("title")):
            errors.add(f"{where}.title", "is required: what the figure compares")
        series = table.get("series")
        if not isinstance(series, list) or not series or not all(isinstance(s, dict) for s in series):
            errors.add(f"{where}.series", "must be one or more tables { label = \"...\", checks = [N, ...] }")
            continue
        kept = []
        for j, s in enumerate(series):
            at = f"{where}.series[{j}]"
            _check_unknown(errors, s, ("label", "checks"), f"{at}.")
            if not _is_text(s.get("label")):
                errors.add(f"{at}.label", "is required: the method the series shows")
            numbers = s.get("checks")
            if not isinstance(numbers, list) or not numbers:
                errors.add(f"{at}.checks", "must be a list of [[check]] numbers (1 = the first)")
                continue
            indices = []
            for n in numbers:
                if isinstance(n, bool) or not isinstance(n, int) or not 1 <= n <= len(checks):
                    errors.add(f"{at}.checks", f"{n!r} is not a [[check]] number from 1 to {len(checks)}")
                    continue
                check = checks[n - 1]
                if check.refinement or check.norm not in STUDY_NORMS:
                    errors.add(f"{at}.checks", f"check {n} is not drawn against time: the checks of a work-precision "
                                               f"figure use norm {', '.join(STUDY_NORMS)} and are not the studied check")
                    continue
                indices.append(n - 1)
            kept.append((s.get("label", ""), tuple(indices)))
        figures.append(WorkPrecision(table.get("title", ""), tuple(kept)))
    return tuple(figures)


def _cycle_limit(scene, overrides):
    """stop.cycles of the scene after the overrides, or None when it has none (or is unreadable)."""
    try:
        limit = tomllib.loads(scene.read_text(encoding="utf-8")).get("stop", {}).get("cycles")
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError, AttributeError):
        return None
    for override in overrides:
        key, _, value = override.partition("=")
        if key.strip() == "stop.cycles":
            try:
                limit = tomllib.loads(f"v = {value}")["v"]
            except tomllib.TOMLDecodeError:
                return None
    return limit if _is_number(limit) else None


def _check_cycle_bounds(errors, scene, runs, checks):
    """A bound on run.cycles must lie strictly below the run's cycle limit: a run stopped by the
    limit has not converged, and a bound at the limit would pass it."""
    overrides = {run.name: run.overrides for run in runs}
    scenes = {run.name: run.scene or scene for run in runs}
    for check in checks:
        if (check.extract or {}).get("kind") != "run_meta" or check.extract.get("path") != "run.cycles":
            continue
        if check.norm != "upper_bound" or check.reference is None or check.reference.constant is None:
            continue
        limit = _cycle_limit(scenes.get(check.variant, scene), overrides.get(check.variant, ()))
        allowed = check.reference.constant * (1.0 + check.rtol) + check.atol
        if limit is not None and not allowed < limit:
            errors.add(f"check[{check.index}].reference", f"the bound on run.cycles ({allowed:g}) is not below the "
                                                          f"run's cycle limit stop.cycles = {limit:g}: a run that "
                                                          "stops on the limit, unconverged, would pass")


def _expected_stop(errors, stop, exit_code, key, given):
    """The stop reason a run must end with: "error" for a nonzero exit, else the one stated."""
    if exit_code != 0:
        if given and stop not in ("", ERROR_STOP) and key != "expect_stop":
            errors.add(key, f"a run expected to exit {exit_code} stops on \"{ERROR_STOP}\", not {stop!r}")
        return ERROR_STOP
    if stop not in STOP_REASONS:
        errors.add(key, f"is required for a run that exits 0: the run.stop_reason it must end with "
                        f"({', '.join(STOP_REASONS)}), so that a run cut short by its limits is not taken "
                        "for one that reached its stop criterion")
        return ""
    return stop


def _mutations(errors, data, run_names):
    """The [[mutation]] tables (at least one) as Mutation records."""
    raw = data.get("mutation", [])
    if not isinstance(raw, list) or not raw or not all(isinstance(m, dict) for m in raw):
        errors.add("mutation", "at least one [[mutation]] table is required: an override that makes the model "
                               "wrong (e.g. a stiffness x 0.5, a friction angle + 3 degrees), which the checks "
                               "must reject")
        return ()
    mutations = []
    for i, m in enumerate(raw):
        where = f"mutation[{i}]"
        _check_unknown(errors, m, MUTATION_KEYS, f"{where}.")
        name = _folder_name(errors, m.get("name"), f"{where}.name")
        if name is None:
            continue
        if any(other.name == name for other in mutations):
            errors.add(f"{where}.name", f"'{name}' is used by an earlier mutation")
        if "overrides" not in m:
            errors.add(f"{where}.overrides", "is required: at least one override, the change that makes the model wrong")
        changes = _overrides(errors, m.get("overrides", []), f"{where}.overrides")
        if "overrides" in m and not changes:
            errors.add(f"{where}.overrides", "must hold at least one override: the change that makes the model wrong")
        why = m.get("why")
        if not _is_text(why):
            errors.add(f"{where}.why", "is required: what the change breaks and which check must see it")
        names = m.get("runs", [])
        if not isinstance(names, list) or not all(isinstance(n, str) for n in names):
            errors.add(f"{where}.runs", "must be a list of run names")
            names = []
        chosen = []
        for label in names:
            run_name = "" if label == PLAIN_RUN_LABEL else label
            if run_name not in run_names:
                known = ", ".join(n or PLAIN_RUN_LABEL for n in run_names)
                errors.add(f"{where}.runs", f"no run named {label!r} (the problem's runs: {known})")
            chosen.append(run_name)
        if "runs" in m and not chosen:
            errors.add(f"{where}.runs", "names no run; leave it out to make every run again")
        mutations.append(Mutation(name, changes, why if isinstance(why, str) else "", tuple(chosen)))
    return tuple(mutations)


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
    timeout_seconds = 600         limit for each run of the problem; default 600

    [[variant]]                   optional further runs of the same scene (e.g. time-step sweeps)
    name = "frac-0.5"             required; letters, digits, ".", "_", "-"; the run goes in runs/<ID>/<name>/
    overrides = ["solver.frac=0.5"]    added after the problem's overrides
    expect_exit = 0               default: the problem's expect_exit

    [[check]]                     at least one
    quantity = "..."              required, human-readable
    extract = { kind = "...", ... }    required; kinds and their keys: vdec_verify.extract
    reference = { function = "module.function", params = { ... }, component = N }
             or { constant = VALUE }   required; function is looked up in the `analytic` package
    norm = "scalar"               required: scalar | upper_bound | equal (scalar extracts), L2 | Linf (series)
    rtol = 1e-3                   at least one of rtol, atol (>= 0); not used by norm "equal"
    atol = 0.0
    justification = "..."         required, non-empty: why the tolerance is fair
    variant = "frac-0.5"          optional: the variant whose run the check reads; default the plain run

Runs: each [[variant]] is run; the plain run (scene plus the problem's overrides) is run when
there are no variants or when some check names no variant. Every run must exit with its
expected code; a check of kind exit_code compares it with a constant.
"""
import importlib
import inspect
import math
import re
import tomllib
from dataclasses import dataclass
from pathlib import Path

from vdec_verify.extract import KINDS
from vdec_verify.norms import NORMS, SCALAR_NORMS, SERIES_NORMS

REQUIREMENT_ID = re.compile(r"^REQ-[A-Z]+-\d{3}$")
VARIANT_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9._-]*$")
ANALYTIC_PACKAGE = "analytic"
LEVELS = ("base", "full")
DEFAULT_TIMEOUT_SECONDS = 600.0
# Files the runner writes in a run folder; a variant's folder sits beside them.
RUN_FILES = ("results.json", "command.txt", "stdout.txt", "stderr.txt")

PROBLEM_KEYS = ("id", "title", "requirements", "scene", "level", "overrides", "expect_exit", "timeout_seconds",
                "variant", "check")
# Tables planned for later work: named here so that using one says so rather than "unknown key".
PLANNED_KEYS = {"refinement": "convergence studies ([refinement]) are not implemented yet"}
VARIANT_KEYS = ("name", "overrides", "expect_exit")
CHECK_KEYS = ("quantity", "extract", "reference", "norm", "rtol", "atol", "justification", "variant")
REFERENCE_KEYS = ("function", "params", "component", "constant")


class ProblemError(Exception):
    """A problem.toml that cannot be run as written."""


@dataclass(frozen=True)
class Run:
    """One solver run of a problem: the plain run (name "") or a [[variant]]."""
    name: str
    overrides: tuple
    expect_exit: int

    @property
    def label(self):
        return self.name or "plain"


@dataclass(frozen=True)
class Reference:
    function_name: str   # "module.function" in the analytic package; "" for a constant
    params: dict
    component: int       # None: use the function's value as it is
    constant: float      # None for a function reference


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


@dataclass
class Problem:
    id: str
    title: str
    requirements: list
    path: Path           # the problem.toml
    scene: Path
    level: str
    runs: list           # of Run, plain run first, then variants in file order
    checks: list
    timeout_seconds: float

    @property
    def folder(self):
        return self.path.parent


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
    for key in ("history", "x", "y"):
        if key in table and not _is_text(table[key]):
            errors.add(f"{where}.{key}", "must name a history")
    for key in ("t", "t0", "level"):
        if key in table and not _is_number(table[key]):
            errors.add(f"{where}.{key}", f"{table[key]!r} is not a number")
    if "window" in table:
        w = table["window"]
        if not (isinstance(w, list) and len(w) == 2 and all(_is_number(v) for v in w) and w[0] < w[1]):
            errors.add(f"{where}.window", f"{w!r} is not [t_start, t_end] with t_start < t_end")
    if "path" in table:
        path = table["path"]
        if not isinstance(path, str) or path.split(".")[0] not in ("run", "energy") or "." not in path:
            errors.add(f"{where}.path", f"{path!r} is not a dotted path into run or energy, e.g. 'energy.initial'")
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
        for key in ("params", "component"):
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
    if component is not None and (isinstance(component, bool) or not isinstance(component, int) or component < 0):
        errors.add(f"{where}.component", f"{component!r} is not a component index (0, 1, ...)")
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
            if series:
                signature.bind(None, **params)
            else:
                signature.bind(**params)
        except TypeError as e:
            form = "f(x, **params)" if series else "f(**params)"
            errors.add(f"{where}.params", f"do not fit {ANALYTIC_PACKAGE}.{name}{signature} called as {form}: {e}")
    return Reference(name, dict(params), component, None)


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
    return values.get("rtol", 0.0), values.get("atol", 0.0)


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
        name = v.get("name")
        if not isinstance(name, str) or not VARIANT_NAME.match(name):
            errors.add(f"{where}.name", f"{name!r} is required: letters, digits, '.', '_' or '-' (it names a folder)")
            continue
        if name in RUN_FILES:
            errors.add(f"{where}.name", f"'{name}' is the name of a file in the plain run's folder")
            continue
        if any(other.name == name for other in variants):
            errors.add(f"{where}.name", f"'{name}' is used by an earlier variant")
            continue
        extra = _overrides(errors, v.get("overrides", []), f"{where}.overrides")
        code = _exit_code(errors, v.get("expect_exit", expect_exit), f"{where}.expect_exit")
        variants.append(Run(name, overrides + extra, code))

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
            reference = _reference(errors, c["reference"], f"{where}.reference", bool(kind and kind.series))
        variant = c.get("variant", "")
        if "variant" in c and not any(v.name == variant for v in variants):
            errors.add(f"{where}.variant", f"no [[variant]] named {variant!r}")
        checks.append(Check(i, c.get("quantity", ""), c.get("extract"), reference, norm, rtol, atol,
                            c.get("justification", ""), variant))
    errors.raise_any()

    runs = list(variants)
    if not variants or any(c.variant == "" for c in checks):
        runs.insert(0, Run("", overrides, expect_exit))
    return Problem(problem_id, title, list(requirements), path, scene, level, runs, checks, float(timeout))


"""problem.toml: loading and validation. Errors name the file and the key."""
import importlib
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

REQUIREMENT_ID = re.compile(r"^REQ-[A-Z]+-\d{3}$")
EXTRACT_KINDS = {"final", "max", "min", "mean", "history", "curve", "slope", "period", "log_decrement",
                 "value_at", "run_meta", "exit_code"}
NORMS = {"scalar", "L2", "Linf", "upper_bound", "equal"}
PROBLEM_KEYS = {"id", "title", "requirements", "scene", "level", "overrides", "expect_exit", "variant", "check",
                "timeout_seconds"}
CHECK_KEYS = {"quantity", "extract", "reference", "norm", "rtol", "atol", "justification", "variant"}
VARIANT_KEYS = {"name", "overrides", "expect_exit"}


class ProblemError(Exception):
    pass


@dataclass
class Variant:
    name: str
    overrides: list
    expect_exit: int


@dataclass
class Check:
    quantity: str
    extract: dict
    reference: dict
    norm: str
    rtol: float
    atol: float
    justification: str
    variant: str


@dataclass
class Problem:
    id: str
    title: str
    requirements: list
    folder: Path
    scene: Path
    level: str
    variants: list = field(default_factory=list)
    checks: list = field(default_factory=list)
    timeout_seconds: float = 600.0


def reference_function(name, where):
    module_name, _, function_name = name.rpartition(".")
    if not module_name:
        raise ProblemError(f"{where}: reference function '{name}' must be module.function")
    try:
        module = importlib.import_module(f"analytic.{module_name}")
    except ImportError as e:
        raise ProblemError(f"{where}: no analytic module '{module_name}' ({e})") from e
    function = getattr(module, function_name, None)
    if function is None:
        raise ProblemError(f"{where}: analytic.{module_name} has no function '{function_name}'")
    return function


def load_problem(path):
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text())
    except (OSError, tomllib.TOMLDecodeError) as e:
        raise ProblemError(f"{path}: {e}") from e

    def fail(key, message):
        raise ProblemError(f"{path}: key '{key}': {message}")

    for key in data:
        if key not in PROBLEM_KEYS:
            fail(key, "unknown key")
    for key in ("id", "title", "requirements", "scene"):
        if key not in data:
            fail(key, "is required")
    if data["id"] != path.parent.name:
        fail("id", f"'{data['id']}' must equal the folder name '{path.parent.name}'")
    requirements = data["requirements"]
    if not isinstance(requirements, list) or not requirements:
        fail("requirements", "must name at least one requirement")
    for r in requirements:
        if not isinstance(r, str) or not REQUIREMENT_ID.match(r):
            fail("requirements", f"'{r}' is not a requirement id like REQ-AREA-001")
    scene = path.parent / data["scene"]
    if not scene.is_file():
        fail("scene", f"no file {scene}")
    level = data.get("level", "base")
    if level not in ("base", "full"):
        fail("level", "must be 'base' or 'full'")
    variants = [Variant("", list(data.get("overrides", [])), int(data.get("expect_exit", 0)))]
    for i, v in enumerate(data.get("variant", [])):
        for key in v:
            if key not in VARIANT_KEYS:
                fail(f"variant[{i}].{key}", "unknown key")
        if "name" not in v:
            fail(f"variant[{i}].name", "is required")
        variants.append(Variant(v["name"], variants[0].overrides + list(v.get("overrides", [])),
                                int(v.get("expect_exit", variants[0].expect_exit))))
    names = {v.name for v in variants}
    checks = []
    if not data.get("check"):
        fail("check", "at least one [[check]] is required")
    for i, c in enumerate(data["check"]):
        where = f"check[{i}]"
        for key in c:
            if key not in CHECK_KEYS:
                fail(f"{where}.{key}", "unknown key")
        for key in ("quantity", "extract", "reference", "norm", "justification"):
            if key not in c:
                fail(f"{where}.{key}", "is required")
        if "rtol" not in c and "atol" not in c:
            fail(f"{where}.rtol", "a check needs a tolerance: rtol and/or atol")
        if not str(c["justification"]).strip():
            fail(f"{where}.justification", "must say why the tolerance is fair")
        if c["norm"] not in NORMS:
            fail(f"{where}.norm", f"unknown norm '{c['norm']}'; use one of {sorted(NORMS)}")
        kind = c["extract"].get("kind")
        if kind not in EXTRACT_KINDS:
            fail(f"{where}.extract.kind", f"unknown extract kind '{kind}'; use one of {sorted(EXTRACT_KINDS)}")
        reference = c["reference"]
        if "function" in reference:
            reference_function(reference["function"], f"{path}: key '{where}.reference.function'")
        elif "constant" not in reference:
            fail(f"{where}.reference", "needs a function (module.function with params) or a constant")
        variant = c.get("variant", "")
        if variant not in names:
            fail(f"{where}.variant", f"no variant named '{variant}'")
        checks.append(Check(c["quantity"], c["extract"], reference, c["norm"], float(c.get("rtol", 0.0)),
                            float(c.get("atol", 0.0)), c["justification"], variant))
    used = {c.variant for c in checks}
    return Problem(data["id"], data["title"], requirements, path.parent, scene, level,
                   [v for v in variants if v.name in used], checks, float(data.get("timeout_seconds", 600)))

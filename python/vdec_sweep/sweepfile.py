"""Reading a sweep file (TOML): the same sweep as the command line's, kept with the study.

    scene = "scene.toml"                 required; relative to the sweep file
    outputs = ["run.cycles", "histories.slide.last"]     output paths (vdec_sweep.paths)
    seeds = 20                           optional: realisations of each combination
    quantiles = [0.05, 0.5, 0.95]        optional: the quantiles of the seed statistics
    timeout = 600                        optional: seconds a run may take
    design = "product"                   "product" (default) or "zip", for [parameters]

    [parameters]                         each key a scene key path (quoted), each value a list
    "solver.frac" = [0.1, 0.2]
    "joint_material[0].friction" = [20.0, 30.0]

    [[run]]                              or, instead of [parameters], the runs one by one
    "solver.frac" = 0.1
    "joint_material[0].friction" = 20.0

    [executor]                           optional; the command line's options win
    kind = "slurm"                       "local" or "slurm"
    jobs = 2                             local: runs at a time
    partition = "short"
    account = "rock"
    time = "10:00"
    shared_dir = "/scratch/me/sweeps"    relative to the sweep file
    sbatch_args = ["--qos=short"]
"""
import tomllib
from pathlib import Path

from vdec_sweep.design import Parameter, check_distinct, toml_text
from vdec_sweep.errors import BAD_SWEEP_FILE, EMPTY_VALUES, SweepError

TOP_KEYS = {"scene", "outputs", "seeds", "quantiles", "timeout", "design", "parameters", "run", "executor"}
EXECUTOR_KEYS = {"kind", "jobs", "partition", "account", "time", "shared_dir", "sbatch_args"}


def _is_number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _strings(value):
    return isinstance(value, list) and all(isinstance(v, str) for v in value)


class _Reader:
    def __init__(self, path):
        self.path = path

    def error(self, key, message, code=BAD_SWEEP_FILE):
        return SweepError(code, f"{self.path}: key '{key}': {message}")

    def unknown(self, table, allowed, prefix=""):
        for key in table:
            if key not in allowed:
                raise self.error(prefix + key, f"unknown key (known: {', '.join(sorted(allowed))})")


def _parameter(reader, key, values):
    where = f"parameters.\"{key}\""
    if not isinstance(values, list):
        raise reader.error(where, "must be a list of the values to sweep")
    if not values:
        raise reader.error(where, "the list of values is empty", EMPTY_VALUES)
    try:
        texts = tuple(toml_text(v) for v in values)
    except ValueError as e:
        raise reader.error(where, str(e)) from None
    return Parameter(key, texts, tuple(values))


def load_sweep_file(path):
    """The sweep file's settings as a dict: scene (Path), parameters, design, runs (listed
    design: a list of dicts key -> (text, value)), outputs, seeds, quantiles, timeout, executor."""
    path = Path(path)
    reader = _Reader(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as e:
        raise SweepError(BAD_SWEEP_FILE, f"{path}: cannot be read: {e.strerror}") from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as e:
        raise SweepError(BAD_SWEEP_FILE, f"{path}: not TOML: {e}") from None
    reader.unknown(data, TOP_KEYS)
    settings = {"parameters": [], "design": "product", "runs": None, "outputs": [], "seeds": None,
                "quantiles": None, "timeout": None, "executor": {}}
    scene = data.get("scene")
    if not isinstance(scene, str) or not scene:
        raise reader.error("scene", "required: the scene file, relative to the sweep file")
    settings["scene"] = path.parent / scene
    outputs = data.get("outputs", [])
    if not _strings(outputs):
        raise reader.error("outputs", "must be a list of output paths (strings)")
    settings["outputs"] = outputs
    seeds = data.get("seeds")
    if seeds is not None and (not isinstance(seeds, int) or isinstance(seeds, bool) or seeds < 1):
        raise reader.error("seeds", f"{seeds!r} is not a whole number of realisations, 1 or more")
    settings["seeds"] = seeds
    quantiles = data.get("quantiles")
    if quantiles is not None and (not isinstance(quantiles, list) or not quantiles
                                  or not all(_is_number(q) and 0.0 < q < 1.0 for q in quantiles)):
        raise reader.error("quantiles", "must be a list of numbers between 0 and 1")
    settings["quantiles"] = quantiles
    timeout = data.get("timeout")
    if timeout is not None and (not _is_number(timeout) or timeout <= 0):
        raise reader.error("timeout", f"{timeout!r} is not a positive number of seconds")
    settings["timeout"] = timeout
    design = data.get("design", "product")
    if design not in ("product", "zip"):
        raise reader.error("design", f"{design!r}: 'product' or 'zip'")
    settings["design"] = design
    if "parameters" in data and "run" in data:
        raise reader.error("run", "give either [parameters] or [[run]] tables, not both")
    parameters = data.get("parameters", {})
    if not isinstance(parameters, dict):
        raise reader.error("parameters", "must be a table: scene key path = [values]")
    settings["parameters"] = [_parameter(reader, key, values) for key, values in parameters.items()]
    check_distinct(settings["parameters"], f"{path}: parameter")
    if "run" in data:
        runs = data["run"]
        if not isinstance(runs, list) or not runs or not all(isinstance(r, dict) for r in runs):
            raise reader.error("run", "must be one or more [[run]] tables", EMPTY_VALUES)
        settings["runs"] = []
        for k, run in enumerate(runs):
            try:
                settings["runs"].append({key: (toml_text(v), v) for key, v in run.items()})
            except ValueError as e:
                raise reader.error(f"run[{k}]", str(e)) from None
    executor = data.get("executor", {})
    if not isinstance(executor, dict):
        raise reader.error("executor", "must be a table")
    reader.unknown(executor, EXECUTOR_KEYS, "executor.")
    if executor.get("kind", "local") not in ("local", "slurm"):
        raise reader.error("executor.kind", f"{executor['kind']!r}: 'local' or 'slurm'")
    if "jobs" in executor and (not isinstance(executor["jobs"], int) or executor["jobs"] < 1):
        raise reader.error("executor.jobs", "must be a whole number, 1 or more")
    for key in ("partition", "account", "time", "shared_dir"):
        if key in executor and not isinstance(executor[key], str):
            raise reader.error(f"executor.{key}", "must be a string")
    if "sbatch_args" in executor and not _strings(executor["sbatch_args"]):
        raise reader.error("executor.sbatch_args", "must be a list of strings")
    if "shared_dir" in executor:
        executor = {**executor, "shared_dir": path.parent / executor["shared_dir"]}
    settings["executor"] = executor
    return settings

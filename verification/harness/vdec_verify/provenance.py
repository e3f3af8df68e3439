"""Provenance: which vdec produced the runs, and which harness judged them, where and when;
and the SHA-256 of every file a run depended on, so that the audit can tell evidence produced
from the repository's files from evidence produced from anything else."""
import datetime
import hashlib
import importlib
import platform
import socket
import subprocess
import tomllib
from pathlib import Path

from vdec_verify import PASS_RULE, __version__

SOFTWARE_FIELDS = ("version", "git_commit", "build_type", "compiler")
UNKNOWN = "unknown"
# The harness's own repository: git is asked about the code that judged the runs.
HARNESS_REPOSITORY = Path(__file__).resolve().parent
# verification/harness/vdec_verify -> the repository root, to which recorded paths are relative.
REPOSITORY_ROOT = HARNESS_REPOSITORY.parents[2]


def _git(*args):
    try:
        completed = subprocess.run(["git", *args], cwd=HARNESS_REPOSITORY, capture_output=True, text=True,
                                   timeout=20, check=True)
    except (OSError, subprocess.SubprocessError):
        return None
    return completed.stdout


def harness_info(configuration=None):
    """The harness's provenance; with a run's configuration (run_configuration) merged in and
    judged: "qualified" is true only for a run whose evidence the commit alone identifies."""
    commit = _git("rev-parse", "HEAD")
    # Uncommitted changes, and files git does not track (an extra problem folder, a stray
    # module the harness imports), mean the commit alone does not identify what ran.
    status = _git("status", "--porcelain", "--untracked-files=all")
    info = {
        "git_commit": commit.strip() if commit else UNKNOWN,
        "git_dirty": None if status is None else status.strip() != "",
        "version": __version__,
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "host": socket.gethostname(),
        "python": platform.python_version(),
        "pass_rule": PASS_RULE,
    }
    if configuration is not None:
        info.update(configuration)
        info["not_qualified_because"] = not_qualified_because(info)
        info["qualified"] = not info["not_qualified_because"]
    return info


def not_qualified_because(info):
    """Why a run's evidence does not qualify the commit it names (empty when it does)."""
    reasons = []
    if info.get("git_commit", UNKNOWN) == UNKNOWN:
        reasons.append("the harness is not in a git checkout: no commit identifies the run")
    if info.get("git_dirty") is not False:
        reasons.append("the repository has uncommitted changes or untracked files (git status --porcelain)")
    if not info.get("problems_dir_in_repository"):
        reasons.append(f"the problems folder {info.get('problems_dir')} is outside the repository")
    if info.get("filter"):
        reasons.append(f"only the problems matching the filter {info['filter']} ran")
    return reasons


# ---------------------------------------------------------------- input hashes

def sha256_of(path):
    """SHA-256 of a file's bytes, or None when it cannot be read."""
    digest = hashlib.sha256()
    try:
        with open(path, "rb") as f:
            for block in iter(lambda: f.read(1 << 20), b""):
                digest.update(block)
    except OSError:
        return None
    return digest.hexdigest()


def recorded_path(path):
    """A path as summary.json records it: relative to the repository root (POSIX separators)
    when it lies inside the repository, else absolute; the audit resolves it the same way."""
    path = Path(path).resolve()
    try:
        return path.relative_to(REPOSITORY_ROOT).as_posix()
    except ValueError:
        return str(path)


def hashes(paths):
    """{recorded path: SHA-256 or None} of the files, sorted by path."""
    return dict(sorted((recorded_path(p), sha256_of(p)) for p in {Path(p).resolve() for p in paths}))


def harness_files():
    """The harness's own modules: what judged the runs."""
    return hashes(HARNESS_REPOSITORY.glob("*.py"))


def run_configuration(vdec, problems_dir, patterns):
    """What a suite run was given: the vdec binary, the problems folder and the filter."""
    problems_dir = Path(problems_dir).resolve()
    return {"vdec": {"path": recorded_path(vdec), "sha256": sha256_of(vdec)},
            "problems_dir": recorded_path(problems_dir),
            "problems_dir_in_repository": problems_dir.is_relative_to(REPOSITORY_ROOT),
            "filter": list(patterns), "files": harness_files()}


def _strings(value):
    if isinstance(value, str):
        yield value
    elif isinstance(value, dict):
        for item in value.values():
            yield from _strings(item)
    elif isinstance(value, list):
        for item in value:
            yield from _strings(item)


def scene_files(scene, overrides=()):
    """The files a scene reads besides itself (stress tables, time-history tables): every string
    of the scene, or value of a --set override, that names a file relative to the scene's folder.
    Any key counts, so a key added to the scene format later is covered without a list here."""
    try:
        data = tomllib.loads(Path(scene).read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
        return []       # the run fails on it and says why; its own hash is still recorded
    values = list(_strings(data)) + [o.partition("=")[2].strip().strip("\"'") for o in overrides]
    found = []
    for value in values:
        if not value or "\n" in value or len(value) > 4096:
            continue
        try:
            candidate = (Path(scene).parent / value).resolve()
            if candidate.is_file() and candidate != Path(scene).resolve():
                found.append(candidate)
        except (OSError, ValueError):
            continue
    return found


def analytic_inputs(function_names, package="analytic"):
    """(module files, programs) behind the reference functions "module.function": each module's
    file, the package's own __init__, the modules of the package it uses, and, as (recorded
    path, path or None when not found), the programs it runs (a module lists them with a
    function reference_programs())."""
    files, programs, seen = [], [], set()
    pending = [f"{package}.{name.rpartition('.')[0]}" for name in function_names if name]
    if pending:
        pending.append(package)
    while pending:
        name = pending.pop()
        if name in seen:
            continue
        seen.add(name)
        try:
            module = importlib.import_module(name)
        except Exception:
            continue    # the check that uses it is invalid and says why
        if getattr(module, "__file__", None):
            files.append(module.__file__)
        if name == package:
            continue    # its attributes are whichever submodules this process has imported so far
        for value in vars(module).values():
            owner = getattr(value, "__name__", "") if isinstance(value, type(module)) \
                else getattr(value, "__module__", "") or ""
            if owner.startswith(package + "."):
                pending.append(owner)
        lister = getattr(module, "reference_programs", None)
        if callable(lister):
            try:
                programs += [(recorded_path(p), p) for p in lister()]
            except OSError:  # not built: recorded without a hash, and the check fails on it
                programs.append((f"{name}.reference_programs()", None))
    return files, programs


def _derived_functions(extract):
    """The analytic functions ("module.function") of a derived extract and of its inputs; the
    harness's own arithmetic (a name without a dot, e.g. "ratio") is in the harness's files."""
    found = []
    if isinstance(extract, dict):
        if extract.get("kind") == "derived" and "." in str(extract.get("function", "")):
            found.append(extract["function"])
        for value in extract.values():
            found += _derived_functions(value)
    return found


def problem_inputs(problem, runs, package="analytic"):
    """{recorded path: SHA-256} of every file the problem's runs and checks depended on: its
    problem.toml, its scene and the files the scene reads, the analytic modules and the
    reference programs of its checks. A file that could not be read has None."""
    overrides = [o for run in runs for o in run.overrides]
    functions = [c.reference.function_name for c in problem.checks]
    functions += [name for c in problem.checks for name in _derived_functions(c.extract)]
    modules, programs = analytic_inputs(functions, package)
    scenes = sorted({problem.scene, *(run.scene for run in runs if run.scene)})
    recorded = hashes([problem.path, *scenes, *(f for scene in scenes for f in scene_files(scene, overrides)), *modules])
    for key, program in programs:
        recorded[key] = sha256_of(program) if program is not None else None
    return dict(sorted(recorded.items()))


def software_of(results):
    """The software fields of one results.json (UNKNOWN where absent)."""
    software = (results or {}).get("software") or {}
    return {key: str(software.get(key, UNKNOWN)) for key in SOFTWARE_FIELDS}


def software_of_runs(records):
    """(software, disagreements): the software of the first run (in problem order) that wrote
    results, and one line for every later run whose software differs from it."""
    first, first_where, disagreements = None, None, []
    for record in records:
        for run in record.get("runs", []):
            if run.get("software") is None:
                continue
            where = f"{record['id']}/{run['variant']}" if run["variant"] else record["id"]
            if first is None:
                first, first_where = run["software"], where
            elif run["software"] != first:
                differences = ", ".join(f"{key} {run['software'][key]} (not {first[key]})"
                                        for key in SOFTWARE_FIELDS if run["software"][key] != first[key])
                disagreements.append(f"{where}: {differences}; first run {first_where}")
    return (first or {key: UNKNOWN for key in SOFTWARE_FIELDS}), disagreements

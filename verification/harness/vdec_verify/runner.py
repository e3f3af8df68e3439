"""Runs the selected problems with vdec (runs in parallel, on an executor) and judges their checks.

Each run is `vdec run SCENE --out OUT/runs/<ID>[/<variant or level>] [--set key=value ...]`;
the run folder keeps results.json, command.txt, stdout.txt and stderr.txt. All runs of all
problems go to one executor (vdec_verify.executors: a local pool of
--jobs workers, or a Slurm job array); the records come back sorted by problem id. A
problem with a [refinement] study runs the levels of the suite's level (problem.runs_at) and
gets a "convergence" record (vdec_verify.convergence).
"""
import fnmatch
import functools
import hashlib
import json
import math
import os
import shlex
import shutil
import subprocess
import sys
import time
import tomllib
from dataclasses import asdict, dataclass, replace
from pathlib import Path

from vdec_verify.convergence import convergence_study
from vdec_verify.executors import LocalExecutor
from vdec_verify.extract import ExtractError, Series, extract
from vdec_verify.norms import ReferenceProblem, compare, evaluate_reference
from vdec_verify.problem import PLAIN_RUN_LABEL, RUN_FILES, ProblemError, find_reference_function, load_problem
from vdec_verify.provenance import hashes, problem_inputs, software_of

RESULTS_SCHEMA = "vdec.results/1"
# The suite runs problems side by side on the cores, so each run keeps to one thread (unless the
# caller says otherwise): threads of two runs contending for two cores would only slow both, and
# one thread per run keeps the wall times of a study comparable.
RUN_ENVIRONMENT = {**os.environ, "OMP_NUM_THREADS": os.environ.get("OMP_NUM_THREADS", "1")}
# A check whose tolerance is more than this many times the error it meets is flagged for review.
LOOSE_TOLERANCE_RATIO = 20.0
EXIT_MEANINGS = {0: "ok", 1: "internal error", 2: "command line error", 3: "scene input error", 4: "geometry error",
                 5: "numerical instability", 6: "contact overlap beyond half the rounding length",
                 7: "output error", 8: "interrupted", 9: "phase not in equilibrium"}


@dataclass
class Entry:
    """A problem folder: its Problem, or why it could not be loaded."""
    id: str
    folder: Path
    problem: object = None
    error: str = ""
    title: str = ""           # of an invalid problem, as far as its file can be read
    requirements: tuple = ()


def _readable_parts(path):
    """Title and requirements of a problem.toml that failed validation, for the reports."""
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except Exception:
        return "", ()
    title = data.get("title") if isinstance(data.get("title"), str) else ""
    requirements = data.get("requirements") if isinstance(data.get("requirements"), list) else []
    return title, tuple(r for r in requirements if isinstance(r, str))


def discover(problems_dir):
    """Every problem folder under problems_dir, sorted by name. A folder whose name starts with
    "." or "_" is skipped (shared files); any other folder without a valid problem.toml becomes
    an invalid entry, so that a broken problem is reported rather than lost."""
    entries = []
    for folder in sorted(p for p in Path(problems_dir).iterdir() if p.is_dir()):
        if folder.name.startswith((".", "_")):
            continue
        path = folder / "problem.toml"
        if not path.is_file():
            entries.append(Entry(folder.name, folder, error=f"{folder}: no problem.toml"))
            continue
        try:
            entries.append(Entry(folder.name, folder, problem=load_problem(path)))
        except ProblemError as e:
            title, requirements = _readable_parts(path)
            entries.append(Entry(folder.name, folder, error=str(e), title=title, requirements=requirements))
    return entries


def matches(problem_id, patterns):
    """True when the id contains a pattern or matches it as a glob (case-insensitive)."""
    problem_id = problem_id.upper()
    for pattern in patterns:
        pattern = pattern.upper()
        if pattern in problem_id or fnmatch.fnmatchcase(problem_id, pattern):
            return True
    return False


def select(entries, level, patterns):
    """The entries to run: those matching the filter, at the level; invalid ones whatever their level."""
    chosen = []
    for entry in entries:
        if patterns and not matches(entry.id, patterns):
            continue
        if entry.problem is not None and level == "base" and entry.problem.level != "base":
            continue
        chosen.append(entry)
    return chosen


@dataclass
class RunOutcome:
    variant: str
    command: list
    folder: Path
    expect_exit: int
    exit_code: int = None      # None: the run did not finish (timeout, could not start)
    results: dict = None       # None: no usable results.json
    wall_seconds: float = 0.0
    failure: str = ""          # why the run is not as expected; "" when it is

    def summary(self):
        run = (self.results or {}).get("run") or {}
        return {"variant": self.variant, "folder": str(self.folder), "command": shlex.join(self.command),
                "exit_code": self.exit_code, "expect_exit": self.expect_exit, "wall_seconds": self.wall_seconds,
                "cycles": run.get("cycles"), "stop_reason": run.get("stop_reason"),
                "software": software_of(self.results) if self.results is not None else None,
                "message": self.failure}


def run_folder(out, problem_id, run, mutation=None):
    """OUT/runs/<ID>[/<run>], or OUT/mutations/<ID>/<mutation>[/<run>] for a run of a mutation."""
    folder = Path(out) / "runs" / problem_id if mutation is None else Path(out) / "mutations" / problem_id / mutation.name
    return folder / run.name if run.name else folder


def _exit_meaning(code):
    if code is not None and code < 0:
        return f"killed by signal {-code}"
    return EXIT_MEANINGS.get(code, "unknown exit code")


def _last_line(text):
    lines = [line for line in (text or "").splitlines() if line.strip()]
    return lines[-1].strip() if lines else ""


def _text(stream):
    return stream.decode(errors="replace") if isinstance(stream, bytes) else (stream or "")


class SaveFailed(OSError):
    """The first half of a restarted run did not write its state."""


def _save_then_restart(command, folder, phase, timeout):
    """Runs `command` with --save PHASE into folder/saved and returns the command that restarts
    from the state it wrote, with the output in folder."""
    saved = folder / "saved"
    shutil.rmtree(saved, ignore_errors=True)
    first = [*command[:4], str(saved), *command[5:], "--save", phase]
    done = subprocess.run(first, capture_output=True, text=True, timeout=timeout, stdin=subprocess.DEVNULL,
                          env=RUN_ENVIRONMENT)
    (folder / "save-stderr.txt").write_text(done.stderr)
    states = sorted(saved.glob("after-phase-*.vdecstate"))
    if done.returncode != 0 or len(states) != 1:
        raise SaveFailed(f"the run saving after phase '{phase}' exited {done.returncode} "
                         f"({_last_line(done.stderr) or 'no message'}) and wrote {len(states)} state files")
    return [*command, "--restart", str(states[0])]


def execute(problem, run, vdec, out, mutation=None):
    """One run of vdec; never raises: anything that goes wrong is in the outcome's failure.
    A run of a mutation goes in mutations/<ID>/<name>/[<run>]."""
    folder = run_folder(out, problem.id, run, mutation)
    command = [str(vdec), "run", str(run.scene or problem.scene), "--out", str(folder)]
    for override in run.overrides:
        command += ["--set", override]
    outcome = RunOutcome(run.name, command, folder, run.expect_exit)
    start = time.monotonic()
    try:
        folder.mkdir(parents=True, exist_ok=True)
        for name in RUN_FILES:  # a stale results.json must not pass for this run's
            (folder / name).unlink(missing_ok=True)
        (folder / "command.txt").write_text(shlex.join(command) + "\n")
        try:
            if run.restart_after:
                command = _save_then_restart(command, folder, run.restart_after, problem.timeout_seconds)
                outcome.command = command
                (folder / "command.txt").write_text(shlex.join(command) + "\n")
            completed = subprocess.run(command, capture_output=True, text=True, timeout=problem.timeout_seconds,
                                       stdin=subprocess.DEVNULL, env=RUN_ENVIRONMENT)
            stdout, stderr = completed.stdout, completed.stderr
            outcome.exit_code = completed.returncode
        except subprocess.TimeoutExpired as e:
            stdout, stderr = _text(e.stdout), _text(e.stderr)
            outcome.failure = f"timed out after {problem.timeout_seconds:g} s (timeout_seconds) and was stopped"
        except SaveFailed as e:
            stdout, stderr = "", ""
            outcome.failure = str(e)
        except OSError as e:
            stdout, stderr = "", ""
            outcome.failure = f"cannot start {vdec}: {e}"
        outcome.wall_seconds = time.monotonic() - start
        (folder / "stdout.txt").write_text(stdout)
        (folder / "stderr.txt").write_text(stderr)
        results_path = folder / "results.json"
        if results_path.is_file():
            try:
                results = json.loads(results_path.read_text())
            except (OSError, ValueError) as e:
                results = None
                outcome.failure = outcome.failure or f"results.json is not readable JSON: {e}"
            if isinstance(results, dict) and results.get("schema") != RESULTS_SCHEMA:
                outcome.failure = outcome.failure or (f"results.json has schema {results.get('schema')!r}, "
                                                      f"not {RESULTS_SCHEMA}")
                results = None
            outcome.results = results if isinstance(results, dict) else None
        if not outcome.failure and outcome.exit_code != run.expect_exit:
            outcome.failure = (f"exited {outcome.exit_code} ({_exit_meaning(outcome.exit_code)}), expected "
                               f"{run.expect_exit} ({_exit_meaning(run.expect_exit)})")
            diagnostic = _last_line(stderr)
            if diagnostic:
                outcome.failure += f": {diagnostic}"
        if not outcome.failure and run.expect_message and run.expect_message not in stderr:
            outcome.failure = (f"exited {outcome.exit_code} as expected, but not with the expected message "
                               f"{run.expect_message!r}: {_last_line(stderr) or 'no message'}")
        if not outcome.failure and run.expect_exit == 0 and outcome.results is None:
            outcome.failure = "exited 0 but wrote no results.json"
        if not outcome.failure and run.expect_stop and outcome.results is not None:
            stop = (outcome.results.get("run") or {}).get("stop_reason")
            if stop != run.expect_stop:
                outcome.failure = (f"stopped on {stop!r} (run.stop_reason), expected {run.expect_stop!r} "
                                   "(expect_stop)")
    except Exception as e:  # e.g. the output folder cannot be written: report it, keep the suite going
        outcome.failure = outcome.failure or f"harness error running {problem.id}: {type(e).__name__}: {e}"
        outcome.wall_seconds = time.monotonic() - start
    return outcome


def _plot_data(numerical, reference, comparison, check):
    if isinstance(numerical, Series):
        return {"kind": "series", "x": numerical.x, "numerical": numerical.y, "reference": reference,
                "x_label": numerical.x_label, "y_label": numerical.y_label}
    return {"kind": "scalar", "numerical": comparison.numerical, "reference": comparison.reference,
            "norm": check.norm, "allowed": check.atol + check.rtol * comparison.scale}


def unevaluated_metric(check, message=""):
    """A check's metric before (or instead of) its evaluation: failing, with no numbers."""
    return {"quantity": check.quantity, "variant": check.variant or None, "extract": check.extract["kind"],
            "norm": check.norm, "rtol": check.rtol, "atol": check.atol, "error": None, "tolerance": None,
            "pass": False, "numerical": None, "reference": None, "justification": check.justification,
            "tolerance_basis": check.tolerance_basis, "message": message}


def judge_check(check, outcome, outcomes=None):
    """The metric of one check against its run; raises ReferenceProblem for an unusable reference.
    outcomes (run name -> outcome) lets a derived extract read other runs of the problem."""
    metric = unevaluated_metric(check)
    runs = {name: o.results for name, o in (outcomes or {}).items()}
    try:
        numerical = extract(check.extract, outcome.results, outcome.exit_code, runs)
    except ExtractError as e:
        metric["message"] = f"cannot extract: {e}"
        return metric
    function = find_reference_function(check.reference.function_name) if check.reference.function_name else None
    reference_spec = check.reference
    if reference_spec.run_params:
        # Values of this run that a reference of the discrete scheme needs, such as the step the
        # solver chose: read like run_meta, so a missing field is an extraction failure.
        try:
            from_run = {key: extract({"kind": "run_meta", "path": path}, outcome.results, outcome.exit_code, runs)
                        for key, path in reference_spec.run_params.items()}
        except ExtractError as e:
            metric["message"] = f"cannot extract the reference's run_params: {e}"
            return metric
        reference_spec = replace(reference_spec, params={**reference_spec.params, **from_run})
    reference = evaluate_reference(reference_spec, numerical, function)
    comparison = compare(check.norm, numerical, reference, check.rtol, check.atol)
    metric.update(error=comparison.error, tolerance=comparison.tolerance, numerical=comparison.numerical,
                  reference=comparison.reference, **{"pass": comparison.passed})
    if isinstance(numerical, Series):
        metric["message"] = f"{check.norm} norms of {numerical.y.size} samples"
    if not math.isfinite(comparison.error):
        metric["message"] = "the numerical value is not finite (NaN or infinity)"
    metric["plot"] = _plot_data(numerical, reference, comparison, check)
    return metric


def order_metric(check, refinement, study):
    """The study's metric: observed against expected order, an absolute band (norm "order")."""
    observed = study["observed_order"]
    error = None if observed is None else abs(observed - refinement.expected_order)
    return {"quantity": f"observed order of {check.quantity}", "variant": None, "extract": check.extract["kind"],
            "norm": "order", "rtol": 0.0, "atol": refinement.order_tolerance, "error": error,
            "tolerance": refinement.order_tolerance, "pass": study["pass"], "numerical": observed,
            "reference": refinement.expected_order, "justification": refinement.justification,
            "tolerance_basis": check.tolerance_basis, "message": study["message"]}


def evaluate_check(check, outcome, outcomes, where=""):
    """(metric, invalid-reference message or None) of one check; never raises."""
    try:
        return judge_check(check, outcome, outcomes), None
    except (ReferenceProblem, LookupError) as e:
        return unevaluated_metric(check, f"invalid reference: {e}"), f"check {check.index + 1}{where}: {e}"
    except Exception as e:  # a harness fault on odd data: report it against this check, not the suite
        return unevaluated_metric(check, f"harness error: {type(e).__name__}: {e}"), None


def judge_study(problem, check, outcomes, level):
    """(metrics, convergence, invalid messages) of the studied check over the levels of the suite.

    The check is evaluated on every level that ran; its metric is that of the finest level (the
    quantity suffixed with the level's name); the errors of all levels feed the study."""
    levels = problem.refinement.levels_at(level)
    per_level, invalid = [], []
    for lv in levels:
        # A derived extract of a level may read another run of the problem (variant = "" the
        # plain run): a level's error measured against a reference run, as FL-SCHEMES does.
        metric, unusable = evaluate_check(check, outcomes[lv.name], outcomes, f" (level {lv.name})")
        per_level.append(metric)
        invalid += [unusable] if unusable else []
    runs = [outcomes[lv.name] for lv in levels]
    study = convergence_study(
        names=[lv.name for lv in levels], h=[lv.h for lv in levels], error=[m["error"] for m in per_level],
        numerical=[m["numerical"] for m in per_level], wall_seconds=[o.wall_seconds for o in runs],
        cycles=[((o.results or {}).get("run") or {}).get("cycles") for o in runs],
        expected_order=problem.refinement.expected_order, order_tolerance=problem.refinement.order_tolerance,
        asymptotic_levels=problem.refinement.asymptotic_levels,
        why=[m["message"] if m["error"] is None else "" for m in per_level])
    study = dict(study, quantity=check.quantity, norm=check.norm)
    finest = dict(per_level[-1], quantity=f"{check.quantity} (level {levels[-1].name})", level=levels[-1].name)
    study_metric = order_metric(check, problem.refinement, study)
    if invalid:
        study_metric = dict(study_metric, error=None, numerical=None, message="invalid reference: " + invalid[0],
                            **{"pass": False})
        study["pass"] = False
    return [finest, study_metric], study, invalid


def judge_checks(problem, checks, outcomes, level):
    """(metrics, convergence record or None, invalid-reference messages) of the given checks of
    problem against the outcomes (run name -> RunOutcome)."""
    metrics, convergence, problems = [], None, []
    for check in checks:
        if check.refinement:
            study_metrics, convergence, invalid = judge_study(problem, check, outcomes, level)
            metrics += study_metrics
            problems += invalid
            continue
        metric, unusable = evaluate_check(check, outcomes[check.variant], outcomes)
        metrics.append(metric)
        problems += [unusable] if unusable else []
    for metric in metrics:
        ratio = tolerance_over_error(metric)
        metric["tolerance_over_error"] = ratio
        metric["loose"] = ratio is not None and ratio > LOOSE_TOLERANCE_RATIO
    return metrics, convergence, problems


def tolerance_over_error(metric):
    """How many times the error the tolerance allows (None when it cannot be said): a check whose
    tolerance is far above the error it meets would pass much worse answers, and is flagged for
    review when this exceeds LOOSE_TOLERANCE_RATIO. For an upper bound it is the room under the
    bound over the room the value used, measured from zero: (reference + allowance) / numerical."""
    error, tolerance = metric.get("error"), metric.get("tolerance")
    if error is None or tolerance is None or not metric.get("pass") or metric["norm"] in ("equal", "order"):
        return None
    if metric["norm"] == "upper_bound":
        bound = metric["reference"] * (1.0 + tolerance) if metric["reference"] else tolerance
        numerical = metric["numerical"]
        if numerical is None or bound <= 0.0:
            return None
        return math.inf if numerical <= 0.0 else bound / numerical
    return math.inf if error == 0.0 else tolerance / error


def judge_mutation(problem, mutation, outcomes, mutated, level):
    """Whether the checks reject a mutation: some run of it ends other than expected, or some check
    reading its runs fails. A check that cannot be evaluated because its reference is unusable
    does not count as a rejection."""
    runs = problem.mutated_runs(mutation, level)
    names = {run.name for run in runs}
    record = {"name": mutation.name, "overrides": list(mutation.overrides), "why": mutation.why,
              "runs": [run.label for run in runs], "caught": False, "rejected_by": [], "message": ""}
    missing = [run.label for run in runs if run.name not in mutated]
    if missing:
        record["message"] = f"the runs {', '.join(missing)} were not made"
        return record
    for run in runs:
        if mutated[run.name].failure:
            record["rejected_by"].append(f"run {run.label}: {mutated[run.name].failure}")
    levels = {lv.name for lv in problem.refinement.levels_at(level)} if problem.refinement else set()
    checks = [c for c in problem.checks if (levels <= names if c.refinement else c.variant in names)]
    metrics, _, problems = judge_checks(problem, checks, {**outcomes, **mutated}, level)
    for m in metrics:
        if not m["pass"] and not m["message"].startswith(("invalid reference", "harness error")):
            why = m["message"] if m["error"] is None or m["norm"] == "order" else \
                f"error {m['error']:.3g} > tolerance {m['tolerance']:.3g}"
            record["rejected_by"].append(f"check: {m['quantity']} ({why})")
    record["caught"] = bool(record["rejected_by"])
    if not record["caught"]:
        record["message"] = (f"all {len(metrics)} checks on its runs passed and every run ended as expected"
                             + (f"; invalid: {problems[0]}" if problems else ""))
    return record


def work_precision_records(problem, metrics, outcomes):
    """The points of the problem's [[work_precision]] figures: per series, each check's error and
    the wall seconds of the run it read."""
    metric_of, k = {}, 0
    for check in problem.checks:
        metric_of[check.index] = metrics[k]
        k += 2 if check.refinement else 1   # a studied check adds its order metric
    figures = []
    for figure in problem.work_precision:
        series = []
        for label, indices in figure.series:
            points = [{"check": i + 1, "run": problem.checks[i].variant or PLAIN_RUN_LABEL,
                       "error": metric_of[i]["error"], "pass": metric_of[i]["pass"],
                       "wall_seconds": outcomes[problem.checks[i].variant].wall_seconds} for i in indices]
            series.append({"label": label, "points": points})
        figures.append({"title": figure.title, "norm": problem.checks[figure.series[0][1][0]].norm
                        if figure.series and figure.series[0][1] else "", "series": series})
    return figures


def judge(entry, outcomes, level="full", mutation_outcomes=None):
    """The record of one problem (see report.write_summary for the fields kept); level is the
    suite's level ("base" or "full"), which decides the refinement levels that ran.
    mutation_outcomes (mutation name -> run name -> RunOutcome), given when the suite ran the
    problem's mutations, adds the record's "mutations": a mutation not caught fails the problem."""
    record = {"id": entry.id, "title": entry.title, "requirements": list(entry.requirements), "level": None,
              "status": "invalid", "metrics": [], "runs": [], "wall_seconds": 0.0, "cycles": 0, "scene_sha256": "",
              "exit_code": None, "message": entry.error, "messages": entry.error.splitlines(),
              "inputs": hashes([p for p in [entry.folder / "problem.toml"] if p.is_file()])}
    problem = entry.problem
    if problem is None:
        return record
    record.update(title=problem.title, requirements=problem.requirements, level=problem.level)
    record["inputs"] = problem_inputs(problem, problem.runs_at(level))
    ordered = [outcomes[run.name] for run in problem.runs_at(level)]
    record["runs"] = [o.summary() for o in ordered]
    record["wall_seconds"] = sum(o.wall_seconds for o in ordered)
    record["cycles"] = sum(int(((o.results or {}).get("run") or {}).get("cycles") or 0) for o in ordered)
    record["exit_code"] = ordered[0].exit_code
    shas = [((o.results or {}).get("scene") or {}).get("sha256") for o in ordered]
    record["scene_sha256"] = next((s for s in shas if s), None) or hashlib.sha256(problem.scene.read_bytes()).hexdigest()

    messages = [f"run {o.variant}: {o.failure}" if o.variant else o.failure for o in ordered if o.failure]
    record["metrics"], convergence, problems = judge_checks(problem, problem.checks, outcomes, level)
    if convergence is not None:
        record["convergence"] = convergence
    if problem.work_precision:
        record["work_precision"] = work_precision_records(problem, record["metrics"], outcomes)
    messages += problems
    invalid = bool(problems)
    failing = [m for m in record["metrics"] if not m["pass"]]
    if mutation_outcomes is not None:
        record["mutations"] = [judge_mutation(problem, m, outcomes, mutation_outcomes.get(m.name, {}), level)
                               for m in problem.mutations]
        for m in record["mutations"]:
            if not m["caught"]:
                messages.append(f"mutation {m['name']} not caught: {m['message']}")
    missed = any(not m["caught"] for m in record.get("mutations", ()))
    if invalid:
        record["status"] = "invalid"
    elif failing or missed or any(o.failure for o in ordered):
        record["status"] = "fail"
    else:
        record["status"] = "pass"
    for m in failing:
        if m["message"].startswith("invalid reference"):
            continue
        if m["error"] is None or m["norm"] == "order":   # a study's message states its numbers
            why = m["message"]
        else:
            why = f"error {m['error']:.3g} > tolerance {m['tolerance']:.3g}"
        messages.append(f"failed: {m['quantity']} ({why})")
    record["messages"] = messages
    record["message"] = "; ".join(messages)
    return record


def _progress(text):
    print(text, file=sys.stderr, flush=True)


def run_suite(entries, vdec, out, jobs=2, progress=_progress, level="full", executor=None):
    """Runs every run of every valid entry and returns the records sorted by id. executor
    (vdec_verify.executors): where the runs go; default a local pool of `jobs`.
    level: the suite's level; a base suite runs only the base refinement levels."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    work = [(entry, run, None) for entry in entries if entry.problem is not None
            for run in entry.problem.runs_at(level)]
    if run_mutations(level):
        work += [(entry, run, mutation) for entry in entries if entry.problem is not None
                 for mutation in entry.problem.mutations for run in entry.problem.mutated_runs(mutation, level)]
    specs = [{"problem": str(entry.problem.path.resolve()), "run": run.name, "level": level,
              "mutation": mutation.name if mutation else None, "vdec": str(vdec), "out": str(out)}
             for entry, run, mutation in work]
    keys = [(entry.id, mutation.name if mutation else None, run.name) for entry, run, mutation in work]
    done = 0

    def report(index, task):
        nonlocal done
        done += 1
        if progress:
            key = keys[index]
            outcome = _outcome_of(task, work[index], out)
            where = key[0] + (f" mutation {key[1]}" if key[1] else "") + (f"/{key[2]}" if key[2] else "")
            ended = "did not finish" if outcome.exit_code is None else f"exit {outcome.exit_code}"
            progress(f"[{done}/{len(work)}] {where}: {ended} in "
                     f"{outcome.wall_seconds:.2f} s, {outcome.failure or 'as expected'}")

    tasks = (executor or LocalExecutor(jobs)).run(execute_task, specs, report)
    outcomes = {key: _outcome_of(task, item, out) for key, task, item in zip(keys, tasks, work)}
    records = []
    for entry in sorted(entries, key=lambda e: e.id):
        mine = {name: o for (problem_id, mutation, name), o in outcomes.items()
                if problem_id == entry.id and mutation is None}
        mutated = None
        if run_mutations(level) and entry.problem is not None:
            mutated = {m.name: {name: o for (problem_id, mutation, name), o in outcomes.items()
                                if problem_id == entry.id and mutation == m.name} for m in entry.problem.mutations}
        records.append(judge(entry, mine, level, mutated))
    return records


@functools.lru_cache(maxsize=None)
def _loaded_problem(path, text):
    return load_problem(Path(path))


def _problem_at(path):
    """The problem of a problem.toml, loaded once for all its runs while its text is the same."""
    return _loaded_problem(path, Path(path).read_text(encoding="utf-8"))


def execute_task(spec):
    """One run of the suite as an executor's task: spec names the problem file, the suite level,
    the run and the mutation (None for none); the value is the RunOutcome's fields as JSON."""
    problem = _problem_at(spec["problem"])
    mutation = None
    runs = problem.runs_at(spec["level"])
    if spec["mutation"] is not None:
        mutation = next(m for m in problem.mutations if m.name == spec["mutation"])
        runs = problem.mutated_runs(mutation, spec["level"])
    run = next(r for r in runs if r.name == spec["run"])
    outcome = execute(problem, run, spec["vdec"], spec["out"], mutation)
    return {**asdict(outcome), "folder": str(outcome.folder), "command": [str(c) for c in outcome.command]}


def _outcome_of(task, item, out):
    """The RunOutcome of an executor's TaskOutcome; a task that did not finish (a Slurm task
    that failed twice) is a failed run with the executor's reason."""
    if task.ok:
        return RunOutcome(**{**task.value, "folder": Path(task.value["folder"])})
    entry, run, mutation = item
    return RunOutcome(run.name, [], run_folder(out, entry.id, run, mutation), run.expect_exit,
                      failure=f"the {task.state} task did not run: {task.error}")


def run_mutations(level):
    """The full suite runs every problem's mutations; the base suite (the test suite) does not,
    to stay fast."""
    return level == "full"


"""Runs problems with the solver, two at a time by default, in a deterministic order."""
import json
import subprocess
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

from vdec_verify.checks import evaluate, extract, reference_value
from vdec_verify.problem import ProblemError, load_problem


def discover(folder, level):
    """Every problem folder, as {"id", "problem" or "error"}; invalid ones are kept, not skipped."""
    found = []
    for path in sorted(Path(folder).glob("*/problem.toml")):
        try:
            problem = load_problem(path)
            if level == "base" and problem.level != "base":
                continue
            found.append({"id": problem.id, "problem": problem})
        except ProblemError as e:
            found.append({"id": path.parent.name, "error": str(e)})
    return found


def _run_variant(problem, variant, vdec, out):
    run_dir = out / "runs" / problem.id / (variant.name or "default")
    command = [str(vdec), "run", str(problem.scene), "--out", str(run_dir)]
    for o in variant.overrides:
        command += ["--set", o]
    completed = subprocess.run(command, capture_output=True, text=True, timeout=problem.timeout_seconds)
    results_path = run_dir / "results.json"
    results = json.loads(results_path.read_text()) if results_path.is_file() else {}
    return completed.returncode, completed.stderr.strip(), results


def run_problem(entry, vdec, out):
    record = {"id": entry["id"], "title": "", "requirements": [], "status": "invalid", "metrics": [],
              "wall_seconds": 0.0, "cycles": 0, "scene_sha256": "", "exit_code": None, "message": "",
              "software": None, "plots": []}
    if "error" in entry:
        record["message"] = entry["error"]
        return record
    problem = entry["problem"]
    record.update(title=problem.title, requirements=problem.requirements)
    start = time.monotonic()
    try:
        runs = {}
        for variant in problem.variants:
            code, stderr, results = _run_variant(problem, variant, vdec, out)
            runs[variant.name] = (code, results)
            record["cycles"] += int(results.get("run", {}).get("cycles", 0))
            record["scene_sha256"] = results.get("scene", {}).get("sha256", record["scene_sha256"])
            record["software"] = record["software"] or results.get("software")
            record["exit_code"] = code
            if code != variant.expect_exit:
                raise ProblemError(f"variant '{variant.name or 'default'}' exited {code}, expected "
                                   f"{variant.expect_exit}: {stderr.splitlines()[-1] if stderr else ''}")
        for check in problem.checks:
            code, results = runs[check.variant]
            numerical = extract(results, code, check.extract)
            reference = reference_value(check.reference, numerical)
            metric = evaluate(check, numerical, reference)
            record["metrics"].append(metric)
            if isinstance(numerical, tuple):
                record["plots"].append({"quantity": check.quantity, "x": numerical[0].tolist(),
                                        "numerical": numerical[1].tolist(),
                                        "reference": (np.asarray(reference) * np.ones_like(numerical[1])).tolist()})
        record["status"] = "pass" if all(m["pass"] for m in record["metrics"]) else "fail"
        failing = [m["quantity"] for m in record["metrics"] if not m["pass"]]
        record["message"] = "" if not failing else "failed: " + "; ".join(failing)
    except (ProblemError, subprocess.TimeoutExpired, KeyError, ValueError) as e:
        record["status"] = "invalid" if isinstance(e, ProblemError) and "identical" in str(e) else "fail"
        record["message"] = str(e)
    record["wall_seconds"] = time.monotonic() - start
    return record


def run_all(entries, vdec, out, jobs):
    out.mkdir(parents=True, exist_ok=True)
    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        records = list(pool.map(lambda e: run_problem(e, vdec, out), entries))
    return sorted(records, key=lambda r: r["id"])

#!/usr/bin/env python3
"""Runs every scene of verification/problems (each variant's overrides too) with two vdec
executables and compares their results.json, outside what differs from run to run by design
(environment, timings, the commit that built them). A refactoring that must not change a
number passes only with every comparison identical.

    /usr/bin/python3 scripts/compare_results.py OLD_VDEC NEW_VDEC [--filter SUBSTRING] [--jobs 2]
"""
import argparse
import json
import subprocess
import sys
import tempfile
import tomllib
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
VOLATILE = {("environment",), ("software", "git_commit"), ("run", "wall_seconds"), ("run", "setup_seconds"),
            ("run", "stage_seconds"), ("run", "static_solve_seconds"), ("run", "threads"),
            ("phases", "wall_seconds")}


def cases(problems, text_filter):
    for folder in sorted(p for p in problems.iterdir() if (p / "problem.toml").is_file()):
        if text_filter and text_filter not in folder.name:
            continue
        problem = tomllib.loads((folder / "problem.toml").read_text())
        variants = problem.get("variant") or [{"name": "", "overrides": []}]
        for v in variants:
            scene = folder / v.get("scene", problem.get("scene", "scene.toml"))
            yield f"{folder.name}/{v['name']}".rstrip("/"), scene, list(v.get("overrides", []))


def strip(value, path=()):
    if path in VOLATILE:
        return None
    if isinstance(value, dict):
        return {k: strip(v, path + (k,)) for k, v in value.items() if path + (k,) not in VOLATILE}
    if isinstance(value, list):  # the entries of a list share their parent's path (each phase's wall time)
        return [strip(v, path) for v in value]
    return value


def run(vdec, scene, overrides, out):
    args = [vdec, "run", str(scene), "--out", str(out)]
    for o in overrides:
        args += ["--set", o]
    done = subprocess.run(args, capture_output=True, text=True, timeout=3600)
    results = out / "results.json"
    return done.returncode, strip(json.loads(results.read_text())) if results.is_file() else None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("--problems", type=Path, default=ROOT / "verification" / "problems")
    parser.add_argument("--filter", default="")
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args()
    todo = list(cases(args.problems, args.filter))
    with tempfile.TemporaryDirectory() as tmp:
        def compare(case):
            name, scene, overrides = case
            base = Path(tmp) / name.replace("/", "__")
            old = run(args.old, scene, overrides, base / "old")
            new = run(args.new, scene, overrides, base / "new")
            return name, old == new, old[0], new[0]
        with ThreadPoolExecutor(args.jobs) as pool:
            outcomes = list(pool.map(compare, todo))
    differ = [o for o in outcomes if not o[1]]
    for name, same, old_code, new_code in outcomes:
        print(f"{'identical' if same else 'DIFFERENT'}  {name}  (exit {old_code} / {new_code})")
    print(f"{len(outcomes) - len(differ)} identical, {len(differ)} different")
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())

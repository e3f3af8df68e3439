"""Command line: run the suite (or a filter of it) and write the reports."""
import argparse
import fnmatch
import sys
from pathlib import Path

from vdec_verify.report import write_reports
from vdec_verify.runner import discover, run_all


def main(argv=None):
    parser = argparse.ArgumentParser(prog="vdec_verify")
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="run verification problems and write reports")
    run.add_argument("--vdec", required=True, help="path to the vdec executable")
    run.add_argument("--problems", default="verification/problems")
    run.add_argument("--filter", nargs="*", default=[], help="substrings or globs of problem ids")
    run.add_argument("--level", choices=["base", "full"], default="full")
    run.add_argument("--jobs", type=int, default=2)
    run.add_argument("--out", default="reports/verification")
    try:
        args = parser.parse_args(argv)
    except SystemExit as e:
        return 2 if e.code else 0
    if not Path(args.vdec).is_file():
        print(f"vdec_verify: no vdec executable at {args.vdec}", file=sys.stderr)
        return 2
    problems = discover(Path(args.problems), args.level)
    if args.filter:
        problems = [p for p in problems
                    if any(f in p["id"] or fnmatch.fnmatch(p["id"], f) for f in args.filter)]
    results = run_all(problems, Path(args.vdec), Path(args.out), args.jobs)
    write_reports(results, Path(args.out))
    passed = sum(r["status"] == "pass" for r in results)
    for r in results:
        print(f"{r['status']:8s} {r['id']:32s} {r['wall_seconds']:7.2f} s  {r['message']}")
    print(f"{passed} passed, {len(results) - passed} failed")
    return 0 if passed == len(results) and results else 1

"""Command line of vdec_verify; see the package docstring (python -m vdec_verify --help)."""
import argparse
import os
import sys
from pathlib import Path

from vdec_verify import __doc__ as PACKAGE_DOC
from vdec_verify.executors import ExecutorError, add_executor_options, make_executor, slurm_options_from
from vdec_verify.provenance import run_configuration
from vdec_verify.report import write_reports
from vdec_verify.runner import discover, run_suite, select
from vdec_verify.baseline import add_baseline_parser, command_baseline
from vdec_verify.compare import add_compare_parser, command_compare
from vdec_verify.nightly import add_nightly_parser, command_nightly
from vdec_verify.work_precision import BaselineError, load_for_report, shown_path, DEFAULT_FILE

USAGE_ERROR = 2


def build_parser():
    parser = argparse.ArgumentParser(prog="python -m vdec_verify", description=PACKAGE_DOC.split("\n\n")[0],
                     epilog="See the package docstring (pydoc vdec_verify) for the pass rule and problem.toml keys.")
    commands = parser.add_subparsers(dest="command", required=True)
    run = commands.add_parser("run", help="run verification problems and write the reports")
    run.add_argument("--vdec", required=True, help="path to the vdec executable")
    run.add_argument("--problems", default="verification/problems", help="folder of problem folders")
    run.add_argument("--filter", nargs="+", action="extend", default=[], metavar="PATTERN",
                     help="keep problems whose id contains PATTERN or matches it as a glob (case-insensitive)")
    run.add_argument("--level", choices=("base", "full"), default="full",
                     help="base: only level = 'base' problems (the test suite); full: all (default)")
    run.add_argument("--jobs", type=int, default=2, help="solver runs at a time (default 2)")
    run.add_argument("--out", default="reports/verification", help="report folder")
    run.add_argument("--revision", default="1", help="revision printed on report.pdf's title page (default 1)")
    run.add_argument("--work-precision-baseline", metavar="FILE",
                     help=f"the work-precision curves the report compares with (default {shown_path(DEFAULT_FILE)})")
    add_executor_options(run, "OUT/slurm")
    check = commands.add_parser("check", help="only load and validate the problem files")
    check.add_argument("--problems", default="verification/problems")
    check.add_argument("--filter", nargs="+", action="extend", default=[], metavar="PATTERN")
    add_compare_parser(commands)
    add_baseline_parser(commands)
    add_nightly_parser(commands)
    return parser


def _usage_error(message):
    print(f"vdec_verify: {message}", file=sys.stderr)
    return USAGE_ERROR


def print_table(records):
    width = max([len(r["id"]) for r in records] + [7])
    print(f"{'status':8s} {'problem':{width}s} {'checks':>7s} {'seconds':>8s}  message")
    for r in records:
        good = sum(m["pass"] for m in r["metrics"])
        message = r["message"].splitlines()[0] if r["message"] else ""
        if len(message) > 110:
            message = message[:107] + "..."
        tally = f"{good}/{len(r['metrics'])}"
        print(f"{r['status']:8s} {r['id']:{width}s} {tally:>7s} "
              f"{r['wall_seconds']:8.2f}  {message}")


def command_run(args):
    vdec = Path(args.vdec)
    if not vdec.is_file() or not os.access(vdec, os.X_OK):
        return _usage_error(f"--vdec {args.vdec}: no executable file there")
    problems = Path(args.problems)
    if not problems.is_dir():
        return _usage_error(f"--problems {args.problems}: no such folder")
    if args.jobs < 1:
        return _usage_error("--jobs must be at least 1")
    entries = select(discover(problems), args.level, args.filter)
    if not entries:
        return _usage_error(f"no problems in {problems} match level {args.level} and filter {args.filter or '(none)'}")
    try:    # read before the suite: a corrupt baseline should not cost a suite's run time
        baseline = load_for_report(args.work_precision_baseline)
    except BaselineError as e:
        return _usage_error(f"--work-precision-baseline: {e}")
    out = Path(args.out)
    # References that run a program of their own (the 50-digit CY joint reference) find it
    # beside the vdec executable the build put it next to.
    os.environ.setdefault("VDEC_EXECUTABLE", str(vdec.resolve()))
    executor = make_executor(args.executor or "local", args.jobs, slurm_options_from(args, out / "slurm"))
    try:
        records = run_suite(entries, vdec.resolve(), out, args.jobs, level=args.level, executor=executor)
    except ExecutorError as e:
        return _usage_error(f"--executor {args.executor}: {e}")
    write_reports(records, out, level=args.level,
                  configuration=run_configuration(vdec.resolve(), problems, args.filter),
                  problems_dir=problems, revision=args.revision, work_precision_baseline=baseline)
    print_table(records)
    print(f"reports in {out}/ (index.html, report.pdf, summary.json, junit.xml)")
    passed = sum(r["status"] == "pass" for r in records)
    print(f"{passed} passed, {len(records) - passed} failed")
    return 0 if passed == len(records) else 1


def command_check(args):
    problems = Path(args.problems)
    if not problems.is_dir():
        return _usage_error(f"--problems {args.problems}: no such folder")
    entries = select(discover(problems), "full", args.filter)
    if not entries:
        return _usage_error(f"no problems in {problems} match the filter {args.filter}")
    for entry in entries:
        if entry.problem is None:
            print(f"invalid  {entry.id}\n  " + entry.error.replace("\n", "\n  "))
        else:
            runs = ", ".join(run.label for run in entry.problem.runs)
            study = entry.problem.refinement
            if study is not None:
                base = len(study.levels_at("base"))
                runs += (f"; refinement: {len(study.levels)} levels ({base} base), expected order "
                         f"{study.expected_order:g} +- {study.order_tolerance:g}")
            print(f"valid    {entry.id} ({entry.problem.level}; {len(entry.problem.checks)} checks; runs: {runs})")
    bad = sum(entry.problem is None for entry in entries)
    print(f"{len(entries) - bad} valid, {bad} invalid")
    return 0 if bad == 0 else 1


def main(argv=None):
    try:
        args = build_parser().parse_args(argv)
    except SystemExit as e:  # argparse: 0 after --help, 2 on a usage error
        return e.code if isinstance(e.code, int) else USAGE_ERROR
    if args.command == "compare":
        return command_compare(args)
    if args.command == "baseline":
        return command_baseline(args)
    if args.command == "nightly":
        return command_nightly(args, lambda argv: command_run(build_parser().parse_args(argv)))
    return command_run(args) if args.command == "run" else command_check(args)


if __name__ == "__main__":
    sys.exit(main())

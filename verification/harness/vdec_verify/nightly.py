"""The nightly run: the suite, its line in the history, the comparison with the baseline and
the trend page.

    python -m vdec_verify nightly --vdec build/vdec [--level full] [--filter PATTERN ...] [--jobs 2]
        [--out reports/nightly/verification] [--history reports/history/nightly.jsonl]
        [--baseline reports/baseline] [--page reports/nightly] [threshold options of compare]

scripts/nightly.sh builds vdec (Release) and runs this. Steps: `vdec_verify run` with the
level, filter and jobs into --out; the summary's entry appended to the history; every history
line that is not an entry reported on stderr and on the page; the entry compared with the
baseline (compare, slower problems repeated with the same vdec); the page written. Exit
status: 0 no regression, 1 a regression (or problems that fail where the baseline's passed),
2 a usage or input error: the suite could not start, or there is no baseline (the history
and the page are still written).
"""
import sys
from pathlib import Path

from vdec_verify.baseline import DEFAULT_BASELINE_DIR, read_acceptances, summary_path
from vdec_verify.compare import RepeatNeeded, add_threshold_options, repeat_needed_message, run_comparison, \
    thresholds_of
from vdec_verify.history import RecordError, append_entry, load_record, read_history
from vdec_verify.trend import write_trend_page

DEFAULT_SUITE_OUT = "reports/nightly/verification"
DEFAULT_HISTORY = "reports/history/nightly.jsonl"
DEFAULT_PAGE = "reports/nightly"
USAGE_ERROR = 2


def _say(text):
    print(f"vdec_verify nightly: {text}", file=sys.stderr)


def command_nightly(args, run_suite_command):
    """run_suite_command(argv) runs `vdec_verify run` with those arguments and returns its exit status."""
    thresholds = thresholds_of(args)
    if isinstance(thresholds, str):
        _say(thresholds)
        return USAGE_ERROR
    run_argv = ["run", "--vdec", args.vdec, "--problems", args.problems, "--level", args.level,
                "--jobs", str(args.jobs), "--out", args.out] + (["--filter", *args.filter] if args.filter else [])
    if run_suite_command(run_argv) == USAGE_ERROR:
        return USAGE_ERROR
    try:
        entry = load_record(Path(args.out) / "summary.json")
        warning = append_entry(args.history, entry)
        if warning:
            _say(warning)
        history = read_history(args.history)
        acceptances = read_acceptances(args.baseline)
    except (RecordError, OSError) as e:
        _say(str(e))
        return USAGE_ERROR
    for line in history.corrupt:
        _say(f"history line not read: {line}")
    if not acceptances or not summary_path(args.baseline).is_file():
        message = (f"no baseline in {args.baseline}: accept one (python -m vdec_verify baseline accept "
                   f"{Path(args.out) / 'summary.json'} --note WHY)")
        write_trend_page(args.page, history, None, None, None, thresholds, message)
        _say(message)
        return USAGE_ERROR
    try:
        baseline = load_record(summary_path(args.baseline))
        comparison = run_comparison(baseline, entry, thresholds, args.problems, args.vdec)
    except RecordError as e:
        _say(str(e))
        return USAGE_ERROR
    except RepeatNeeded as e:      # not reached with --vdec given; kept for a caller that passes none
        _say(repeat_needed_message(e))
        return USAGE_ERROR
    print(comparison.as_text())
    page = write_trend_page(args.page, history, baseline, acceptances[-1], comparison, thresholds)
    print(f"trend page: {page}")
    return 1 if comparison.regressions else 0


def add_nightly_parser(commands):
    parser = commands.add_parser("nightly", help="run the suite, append to the history, compare with the baseline, "
                                                 "write the trend page")
    parser.add_argument("--vdec", required=True, help="the vdec executable")
    parser.add_argument("--level", choices=("base", "full"), default="full", help="suite level (default full)")
    parser.add_argument("--filter", nargs="+", action="extend", default=[], metavar="PATTERN",
                        help="only the problems matching (as vdec_verify run --filter)")
    parser.add_argument("--jobs", type=int, default=2, help="solver runs at a time (default 2)")
    parser.add_argument("--out", default=DEFAULT_SUITE_OUT, help=f"the suite's report folder (default {DEFAULT_SUITE_OUT})")
    parser.add_argument("--history", default=DEFAULT_HISTORY, help=f"history file (default {DEFAULT_HISTORY})")
    parser.add_argument("--baseline", default=DEFAULT_BASELINE_DIR, help=f"baseline folder (default {DEFAULT_BASELINE_DIR})")
    parser.add_argument("--page", default=DEFAULT_PAGE, help=f"trend page folder (default {DEFAULT_PAGE})")
    add_threshold_options(parser)
    return parser

"""The nightly baseline: the summary.json the nightly runs are compared with, and the record of
who accepted it and why.

    python -m vdec_verify baseline accept [SUMMARY] --note "why" [--by NAME] [--baseline DIR]
    python -m vdec_verify baseline show [--baseline DIR] [--json]
    python -m vdec_verify baseline work-precision SUMMARY --note "why" [--by NAME] [--out FILE]

(the last takes the committed work-precision curves: vdec_verify.work_precision).

DIR (default reports/baseline) holds summary.json, a copy of the accepted summary, and
baseline.json (schema vdec.nightly-baseline/1): {"acceptances": [...]}, oldest first, each
with the date, who accepted it, the note, the SHA-256 of the summary accepted, where it came
from, its vdec commit, level and counts. The last acceptance is the baseline in force; the
earlier ones stay, so that every accepted change can be traced to a person and a reason.
Both files are replaced atomically (written beside, then renamed).
"""
import datetime
import getpass
import hashlib
import json
import os
import sys
from pathlib import Path

from vdec_verify.history import RecordError, SUMMARY_SCHEMA
from vdec_verify.work_precision import add_work_precision_parser, command_work_precision_baseline

BASELINE_SCHEMA = "vdec.nightly-baseline/1"
DEFAULT_BASELINE_DIR = "reports/baseline"
DEFAULT_SUMMARY = "reports/nightly/verification/summary.json"
USAGE_ERROR = 2


def _replace_atomically(path, data):
    partial = path.with_name(f".{path.name}.{os.getpid()}.partial")
    with open(partial, "wb") as f:
        f.write(data)
        f.flush()
        os.fsync(f.fileno())
    os.replace(partial, path)


def summary_path(folder):
    return Path(folder) / "summary.json"


def read_acceptances(folder):
    """The acceptances recorded in folder/baseline.json, oldest first ([] when there is none)."""
    path = Path(folder) / "baseline.json"
    if not path.is_file():
        return []
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, ValueError) as e:
        raise RecordError(f"{path}: not readable JSON: {e}") from e
    if not isinstance(data, dict) or data.get("schema") != BASELINE_SCHEMA or \
            not isinstance(data.get("acceptances"), list):
        raise RecordError(f"{path}: not a baseline record (schema {BASELINE_SCHEMA} with a list 'acceptances')")
    return data["acceptances"]


def accept(summary, folder, note, by):
    """Makes the summary.json at `summary` the baseline in `folder`; returns the acceptance."""
    summary, folder = Path(summary), Path(folder)
    if not note or not note.strip():
        raise ValueError("--note: say why this run becomes the baseline (the note is what makes it traceable)")
    try:
        data = summary.read_bytes()
        parsed = json.loads(data)
    except (OSError, UnicodeDecodeError, ValueError) as e:
        raise RecordError(f"{summary}: not a readable summary.json: {e}") from e
    if not isinstance(parsed, dict) or parsed.get("schema") != SUMMARY_SCHEMA:
        raise RecordError(f"{summary}: schema {parsed.get('schema') if isinstance(parsed, dict) else None!r}, "
                          f"not {SUMMARY_SCHEMA}: only a summary.json can be accepted")
    acceptances = read_acceptances(folder)
    harness = parsed.get("harness") or {}
    acceptance = {
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "by": by, "note": note.strip(), "summary_sha256": hashlib.sha256(data).hexdigest(),
        "source": str(summary.resolve()), "commit": (parsed.get("software") or {}).get("git_commit"),
        "run_date": harness.get("date"), "level": harness.get("level"), "filter": harness.get("filter") or [],
        "counts": parsed.get("counts")}
    folder.mkdir(parents=True, exist_ok=True)
    _replace_atomically(summary_path(folder), data)
    record = {"schema": BASELINE_SCHEMA, "acceptances": acceptances + [acceptance]}
    _replace_atomically(folder / "baseline.json", (json.dumps(record, indent=1) + "\n").encode())
    return acceptance


def describe(acceptance):
    counts = acceptance.get("counts") or {}
    return (f"{acceptance['date']} by {acceptance['by']}: commit {str(acceptance.get('commit'))[:12]}, level "
            f"{acceptance.get('level')}, {counts.get('passed')} passed, {counts.get('failed')} failed, "
            f"summary sha256 {acceptance['summary_sha256'][:12]}\n    {acceptance['note']}")


def command_baseline(args):
    if args.action == "work-precision":
        return command_work_precision_baseline(args)
    try:
        if args.action == "accept":
            by = args.by or os.environ.get("VDEC_BASELINE_BY") or getpass.getuser()
            acceptance = accept(args.summary, args.baseline, args.note, by)
            print(f"baseline in {args.baseline}: {describe(acceptance)}")
            return 0
        acceptances = read_acceptances(args.baseline)
    except (RecordError, ValueError) as e:
        print(f"vdec_verify baseline: {e}", file=sys.stderr)
        return USAGE_ERROR
    if not acceptances:
        print(f"vdec_verify baseline: no baseline in {args.baseline} (accept one: python -m vdec_verify baseline "
              "accept SUMMARY --note WHY)", file=sys.stderr)
        return USAGE_ERROR
    if args.json:
        print(json.dumps({"schema": BASELINE_SCHEMA, "acceptances": acceptances}, indent=1))
        return 0
    print(f"baseline in force ({summary_path(args.baseline)}): {describe(acceptances[-1])}")
    if len(acceptances) > 1:
        print("earlier acceptances, newest first:")
        for acceptance in reversed(acceptances[:-1]):
            print(f"  {describe(acceptance)}")
    return 0


def add_baseline_parser(commands):
    parser = commands.add_parser("baseline", help="accept or show the nightly baseline; take the committed "
                                                  "work-precision baseline")
    actions = parser.add_subparsers(dest="action", required=True)
    accept_parser = actions.add_parser("accept", help="make a summary.json the baseline, with who and why")
    accept_parser.add_argument("summary", nargs="?", default=DEFAULT_SUMMARY,
                               help=f"the summary.json to accept (default {DEFAULT_SUMMARY})")
    accept_parser.add_argument("--note", required=True, help="why this run becomes the baseline")
    accept_parser.add_argument("--by", help="who accepts it (default $VDEC_BASELINE_BY, else the login name)")
    show_parser = actions.add_parser("show", help="the baseline in force and every earlier acceptance")
    show_parser.add_argument("--json", action="store_true")
    for sub in (accept_parser, show_parser):
        sub.add_argument("--baseline", default=DEFAULT_BASELINE_DIR, help=f"folder (default {DEFAULT_BASELINE_DIR})")
    add_work_precision_parser(actions)
    return parser

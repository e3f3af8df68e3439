"""The nightly history: one JSON line per suite run, the run's outcome in a compact, stable form.

A line (schema vdec.nightly-history/1) holds what a comparison needs and no more: the date,
the vdec and harness commits, the suite's level and filter, the software fields and the SHA-256
of the vdec binary, of the harness's modules and of every input file, and per problem its
status, wall seconds, cycles, the digest of its inputs and every check's error, tolerance and
result. summary.json (vdec.verification/1) keeps much more (justifications, messages, runs);
a line is some 150 kB for the full suite (95 problems), and a year of nights reads in about a second.

Appending is safe: the line is written with one write() on a file opened for appending, under
an exclusive lock, and synced; a file whose last line was cut short (a crash during an earlier
write) gets a newline first, so that the partial line stays on its own and is reported, not
glued to the new one. Reading reports every line that is not a valid entry, with its number.
"""
import fcntl
import hashlib
import json
import os
from dataclasses import dataclass
from pathlib import Path

HISTORY_SCHEMA = "vdec.nightly-history/1"
SUMMARY_SCHEMA = "vdec.verification/1"


class RecordError(Exception):
    """A summary.json or history line that cannot be read; the message names the file (and line)."""


def check_label(metric):
    """A check as the reports name it, without its number: "[variant] quantity"."""
    variant = metric.get("variant")
    return f"[{variant}] {metric.get('quantity', '')}" if variant else str(metric.get("quantity", ""))


def inputs_digest(inputs):
    """One SHA-256 over a problem's {path: SHA-256} inputs, so that a line records their state
    in 64 characters while the files themselves are listed once for the whole suite."""
    canonical = json.dumps(inputs or {}, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(canonical.encode()).hexdigest()


def _checks(metrics):
    checks, seen = [], {}
    for number, metric in enumerate(metrics, start=1):
        label = check_label(metric)
        seen[label] = seen.get(label, 0) + 1
        if seen[label] > 1:         # two checks of the same wording stay apart by their order
            label = f"{label} ({seen[label]})"
        checks.append({"check": label, "n": number, "norm": metric.get("norm"), "error": metric.get("error"),
                       "tolerance": metric.get("tolerance"), "pass": bool(metric.get("pass"))})
    return checks


def entry_of_summary(summary):
    """The history entry of a summary.json (already parsed)."""
    harness = summary.get("harness") or {}
    software = summary.get("software") or {}
    inputs, problems = {}, {}
    for record in summary.get("problems") or []:
        inputs.update(record.get("inputs") or {})
        problems[record["id"]] = {
            "status": record.get("status"), "wall_seconds": record.get("wall_seconds"),
            "cycles": record.get("cycles"), "inputs": inputs_digest(record.get("inputs")),
            "checks": _checks(record.get("metrics") or [])}
    return {"schema": HISTORY_SCHEMA, "date": harness.get("date"), "commit": software.get("git_commit"),
            "harness_commit": harness.get("git_commit"), "harness_dirty": harness.get("git_dirty"),
            "level": harness.get("level"), "filter": list(harness.get("filter") or []), "host": harness.get("host"),
            "software": dict(software), "vdec_sha256": (harness.get("vdec") or {}).get("sha256"),
            "harness_files": dict(sorted((harness.get("files") or {}).items())),
            "inputs": dict(sorted(inputs.items())), "counts": summary.get("counts"), "problems": problems}


def _entry_problem(entry, where):
    """Why a parsed line is not a history entry ("" when it is one)."""
    if not isinstance(entry, dict):
        return f"{where}: not a JSON object"
    if entry.get("schema") != HISTORY_SCHEMA:
        return f"{where}: schema {entry.get('schema')!r}, not {HISTORY_SCHEMA}"
    if not isinstance(entry.get("problems"), dict):
        return f"{where}: no 'problems' object"
    return ""


def append_entry(path, entry):
    """Appends the entry as one line; returns a warning when the file's last line was cut short."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    line = (json.dumps(entry, separators=(",", ":"), allow_nan=False) + "\n").encode()
    warning = ""
    descriptor = os.open(path, os.O_RDWR | os.O_APPEND | os.O_CREAT, 0o644)
    try:
        fcntl.flock(descriptor, fcntl.LOCK_EX)
        size = os.fstat(descriptor).st_size
        if size and os.pread(descriptor, 1, size - 1) != b"\n":
            line = b"\n" + line
            warning = (f"{path}: the last line was cut short (no newline at its end); it is kept on a line of "
                       "its own and reported as corrupt")
        written = os.write(descriptor, line)
        if written != len(line):
            raise OSError(f"{path}: wrote {written} of {len(line)} bytes")
        os.fsync(descriptor)
    finally:
        os.close(descriptor)
    return warning


@dataclass
class History:
    path: Path
    entries: list        # of (line number, entry), oldest first
    corrupt: list        # of messages "FILE:LINE: why"


def read_history(path):
    """Every entry of a history file with its line number, and a message for every line that is
    not one (unreadable JSON, another schema, a partial line). A missing file is an empty history."""
    path = Path(path)
    entries, corrupt = [], []
    try:
        data = path.read_bytes()
    except FileNotFoundError:
        return History(path, entries, corrupt)
    except OSError as e:
        raise RecordError(f"{path}: cannot be read: {e}") from e
    for number, raw in enumerate(data.split(b"\n"), start=1):
        if not raw.strip():
            continue
        where = f"{path}:{number}"
        try:
            entry = json.loads(raw)
        except ValueError as e:
            corrupt.append(f"{where}: not valid JSON ({e}); {len(raw)} bytes starting {raw[:40]!r}")
            continue
        problem = _entry_problem(entry, where)
        if problem:
            corrupt.append(problem)
        else:
            entries.append((number, entry))
    return History(path, entries, corrupt)


def _history_line(path, spec):
    history = read_history(path)
    if not history.entries:
        raise RecordError(f"{path}: holds no history entry" + (f" ({history.corrupt[0]})" if history.corrupt else ""))
    if spec is None:
        return history.entries[-1][1]
    number = int(spec)
    if number < 0:       # -1: the last entry, -2 the one before
        if -number > len(history.entries):
            raise RecordError(f"{path}: has {len(history.entries)} entries, so no entry {number}")
        return history.entries[number][1]
    for line, entry in history.entries:
        if line == number:
            return entry
    bad = next((c for c in history.corrupt if c.startswith(f"{path}:{number}:")), None)
    raise RecordError(bad or f"{path}: line {number} is not an entry (lines {history.entries[0][0]} to "
                             f"{history.entries[-1][0]} hold entries)")


def load_record(spec):
    """The history entry of a summary.json file, of a history file (its last entry) or of one
    line of it, written FILE:LINE (LINE from 1, or negative from the end: FILE:-2)."""
    path, colon, line = str(spec).rpartition(":")
    if not colon or not line.lstrip("-").isdigit():
        path, line = str(spec), None
    path = Path(path)
    if not path.is_file():
        raise RecordError(f"{path}: no such file")
    if line is not None or path.suffix == ".jsonl":
        return _history_line(path, line)
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, ValueError) as e:
        raise RecordError(f"{path}: not readable JSON: {e}") from e
    if isinstance(data, dict) and data.get("schema") == HISTORY_SCHEMA:
        return data
    if not isinstance(data, dict) or data.get("schema") != SUMMARY_SCHEMA:
        found = data.get("schema") if isinstance(data, dict) else type(data).__name__
        raise RecordError(f"{path}: schema {found!r}: neither a summary.json ({SUMMARY_SCHEMA}) nor a history "
                          f"entry ({HISTORY_SCHEMA})")
    if not all(isinstance(p, dict) and isinstance(p.get("id"), str) for p in data.get("problems") or []):
        raise RecordError(f"{path}: 'problems' must be a list of objects with an 'id'")
    return entry_of_summary(data)

"""Provenance: which vdec produced the runs, and which harness judged them, where and when."""
import datetime
import platform
import socket
import subprocess
from pathlib import Path

from vdec_verify import PASS_RULE, __version__

SOFTWARE_FIELDS = ("version", "git_commit", "build_type", "compiler")
UNKNOWN = "unknown"
# The harness's own repository: git is asked about the code that judged the runs.
HARNESS_REPOSITORY = Path(__file__).resolve().parent


def _git(*args):
    try:
        completed = subprocess.run(["git", *args], cwd=HARNESS_REPOSITORY, capture_output=True, text=True,
                                   timeout=20, check=True)
    except (OSError, subprocess.SubprocessError):
        return None
    return completed.stdout


def harness_info():
    commit = _git("rev-parse", "HEAD")
    # Uncommitted changes to tracked files mean the commit alone does not identify the harness.
    status = _git("status", "--porcelain", "--untracked-files=no")
    return {
        "git_commit": commit.strip() if commit else UNKNOWN,
        "git_dirty": None if status is None else status.strip() != "",
        "version": __version__,
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "host": socket.gethostname(),
        "python": platform.python_version(),
        "pass_rule": PASS_RULE,
    }


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

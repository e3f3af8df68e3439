"""A run's output folder: results.json (docs/user-manual/outputs.md) and the VTK snapshots in
vtk/, with the choice of a snapshot by cycle."""
import json
from dataclasses import dataclass
from pathlib import Path

from vdec_plot.errors import NO_RESULTS, NO_SNAPSHOT, USAGE, PlotError
from vdec_plot.snapshot import list_snapshots, read_snapshot

RESULTS_SCHEMA = "vdec.results/1"
NO_SNAPSHOT_HINT = ("run the scene again with `--set output.vtk_every=N` (N cycles between snapshots; a large N "
                    "gives the start and the end only), or add [output] vtk_every = N to the scene")


@dataclass
class RunOutput:
    folder: Path
    results: dict
    snapshots: list   # [(cycle, time or None, path)], by cycle

    @property
    def last_cycle(self):
        return int(self.results["run"]["cycles"])

    def block_names(self):
        return [b.get("name", "") for b in self.results.get("blocks") or []]

    def simply_deformable(self):
        return {i for i, b in enumerate(self.results.get("blocks") or []) if b.get("kind") == "simply-deformable"}

    def title(self):
        scene = self.results.get("scene") or {}
        return scene.get("title") or scene.get("path") or str(self.folder)

    def snapshot(self, which):
        """The snapshot `which` names: "first", "last" or a cycle number (a string of digits)."""
        if not self.snapshots:
            raise PlotError(NO_SNAPSHOT, f"{self.folder / 'vtk'}: the run wrote no VTK snapshot, and the geometry is "
                                         f"drawn from them; {NO_SNAPSHOT_HINT}")
        if which == "first":
            cycle, time, path = self.snapshots[0]
        elif which == "last":
            cycle, time, path = self.snapshots[-1]
        else:
            wanted = parse_cycle(which)
            chosen = [s for s in self.snapshots if s[0] == wanted]
            if not chosen:
                cycles = [s[0] for s in self.snapshots]
                listed = ", ".join(str(c) for c in cycles[:12]) + (", ..." if len(cycles) > 12 else "")
                raise PlotError(NO_SNAPSHOT, f"--cycle {which}: {self.folder / 'vtk'} has no snapshot of cycle {wanted} "
                                             f"(it has {len(cycles)}: {listed}); give one of them, first or last")
            cycle, time, path = chosen[0]
        return read_snapshot(path, time)

    def is_end(self, snapshot):
        """True when the snapshot holds the state results.json reports (the end of the run)."""
        return snapshot.cycle == self.last_cycle


def parse_cycle(text):
    if text in ("first", "last"):
        return text
    if not text.isdigit():
        raise PlotError(USAGE, f"--cycle {text}: give a cycle number (e.g. 2000), first or last")
    return int(text)


def load_run(folder):
    """The run in folder; raises PlotError(NO_RESULTS) when its results.json is missing or unusable."""
    folder = Path(folder)
    path = folder / "results.json"
    if not folder.is_dir():
        raise PlotError(NO_RESULTS, f"{folder}: no such run folder (give the --out DIR of a `vdec run`)")
    if not path.is_file():
        raise PlotError(NO_RESULTS, f"{path}: no results.json here (give the --out DIR of a `vdec run`; a run that "
                                    "failed before it started writes none)")
    try:
        results = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, ValueError) as e:
        raise PlotError(NO_RESULTS, f"{path}: not readable JSON ({e})") from e
    if not isinstance(results, dict) or results.get("schema") != RESULTS_SCHEMA:
        schema = results.get("schema") if isinstance(results, dict) else None
        raise PlotError(NO_RESULTS, f"{path}: schema {schema!r}, not {RESULTS_SCHEMA!r}: not a vdec results file")
    if not isinstance(results.get("run"), dict) or "cycles" not in results["run"]:
        raise PlotError(NO_RESULTS, f"{path}: no run.cycles: not a complete vdec results file")
    return RunOutput(folder, results, list_snapshots(folder / "vtk"))

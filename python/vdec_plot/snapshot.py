"""Reading vdec's VTK snapshots (ASCII VTK XML unstructured grids, src/io/vtk_writer.cpp) and their
model.pvd collection into numpy arrays: the cells by kind (zone triangles, rigid-block polygons,
contact vertices, structures' lines) with their cell data, and the points with their point data."""
import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from vdec_plot.errors import NO_SNAPSHOT, PlotError

ZONE, RIGID_BLOCK, CONTACT, FLUID_DOMAIN, FLOW_KNOT, BEAM_ELEMENT, CABLE_ELEMENT, BOLT = range(8)
SNAPSHOT_NAME = re.compile(r"snapshot_(\d{9})\.vtu$")


@dataclass
class Snapshot:
    """One snapshot. `cells` is a list of point-index arrays; cell data arrays are keyed by name
    (the kind array as "kind"), point data likewise (vectors as (n, 2) arrays)."""
    path: Path
    cycle: int
    time: float
    points: np.ndarray
    cells: list
    cell_data: dict
    point_data: dict = field(default_factory=dict)

    def of_kind(self, kind):
        """Indices of the cells of one kind, in the order written (zones in zone id order)."""
        return np.flatnonzero(self.cell_data["kind"] == kind)

    def polygons(self, indices):
        """The (k, 2) vertex arrays of the given cells."""
        return [self.points[self.cells[i]] for i in indices]

    def has_boundary_conditions(self):
        """Snapshots of vdec builds before the `driven` and `boundary_load` point arrays lack them."""
        return "driven" in self.point_data and "boundary_load" in self.point_data


def _numbers(element, dtype=float):
    return np.array((element.text or "").split(), dtype=dtype)


def read_snapshot(path, time=None):
    """The snapshot in the .vtu file at path; raises PlotError(NO_SNAPSHOT) when it cannot be read."""
    path = Path(path)
    match = SNAPSHOT_NAME.search(path.name)
    try:
        piece = ET.parse(path).getroot().find("UnstructuredGrid/Piece")
        if piece is None:
            raise ValueError("no UnstructuredGrid/Piece element")
        points = _numbers(piece.find("Points/DataArray")).reshape(-1, 3)[:, :2]
        cell_arrays = {a.get("Name"): a for a in piece.find("Cells").iter("DataArray")}
        connectivity = _numbers(cell_arrays["connectivity"], np.int64)
        offsets = _numbers(cell_arrays["offsets"], np.int64)
        cells = np.split(connectivity, offsets[:-1]) if offsets.size else []
        cell_data = {}
        for array in piece.find("CellData").iter("DataArray"):
            name = array.get("Name")
            cell_data["kind" if name.startswith("kind") else name] = _numbers(array)
        cell_data["kind"] = cell_data["kind"].astype(int)
        cell_data["block"] = cell_data["block"].astype(int)
        point_data = {}
        for array in piece.find("PointData").iter("DataArray"):
            values = _numbers(array)
            components = int(array.get("NumberOfComponents", "1"))
            point_data[array.get("Name")] = values.reshape(-1, components)[:, :2] if components == 3 else values
    except (OSError, ET.ParseError, ValueError, KeyError, AttributeError) as e:
        raise PlotError(NO_SNAPSHOT, f"{path}: not a readable vdec VTK snapshot ({type(e).__name__}: {e})") from e
    return Snapshot(path, int(match.group(1)) if match else 0, 0.0 if time is None else time, points,
                    cells, cell_data, point_data)


def list_snapshots(vtk_dir):
    """[(cycle, time or None, path)] of the snapshots in vtk_dir, by cycle; times from model.pvd."""
    vtk_dir = Path(vtk_dir)
    times = {}
    collection = vtk_dir / "model.pvd"
    if collection.is_file():
        try:
            for entry in ET.parse(collection).getroot().iter("DataSet"):
                times[entry.get("file")] = float(entry.get("timestep"))
        except (ET.ParseError, ValueError, TypeError) as e:
            raise PlotError(NO_SNAPSHOT, f"{collection}: not a readable VTK collection ({e})") from e
    found = []
    for path in vtk_dir.glob("snapshot_*.vtu") if vtk_dir.is_dir() else ():
        match = SNAPSHOT_NAME.search(path.name)
        if match:
            found.append((int(match.group(1)), times.get(path.name), path))
    return sorted(found)

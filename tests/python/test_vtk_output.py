"""VTK snapshots for ParaView: a .pvd collection and .vtu unstructured grids whose arrays agree
with each other and with results.json (read with the standard XML parser, by the VTK XML
format's rules: offsets end at the connectivity's length, one type per cell, point and cell
data the length of points and cells)."""
import json
import os
import shutil
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
VDEC = os.environ.get("VDEC_EXECUTABLE", str(ROOT / "build" / "vdec"))
KIRSCH = ROOT / "verification" / "problems" / "DB-KIRSCH"

pytestmark = pytest.mark.skipif(not Path(VDEC).is_file(), reason="vdec is not built")


def numbers(element):
    return np.array((element.text or "").split(), dtype=float)


@pytest.mark.requirements("REQ-ZONE-010")
def test_snapshots_form_a_consistent_time_series(tmp_path):
    scene = tmp_path / "scene.toml"
    shutil.copy(KIRSCH / "far_field.csv", tmp_path)
    scene.write_text((KIRSCH / "scene.toml").read_text() + "\n[output]\nvtk_every = 1000\n")
    out = tmp_path / "out"
    done = subprocess.run([VDEC, "run", str(scene), "--out", str(out)], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    results = json.loads((out / "results.json").read_text())
    collection = ET.parse(out / "vtk" / "model.pvd").getroot()
    entries = collection.find("Collection").findall("DataSet")
    cycles = results["run"]["cycles"]
    # The start, every 1000 cycles, and the end.
    assert len(entries) == 1 + cycles // 1000 + (1 if cycles % 1000 else 0)
    times = [float(e.get("timestep")) for e in entries]
    assert times[0] == 0.0 and times == sorted(times)
    assert times[-1] == pytest.approx(results["run"]["time"], rel=1e-12, abs=0)
    last = ET.parse(out / "vtk" / entries[-1].get("file")).getroot()
    piece = last.find("UnstructuredGrid/Piece")
    points, cells = int(piece.get("NumberOfPoints")), int(piece.get("NumberOfCells"))
    arrays = {a.get("Name"): a for a in piece.iter("DataArray")}
    assert numbers(arrays["position"]).size == 3 * points
    connectivity, offsets = numbers(arrays["connectivity"]), numbers(arrays["offsets"])
    assert offsets.size == cells and offsets[-1] == connectivity.size and np.all(np.diff(offsets) > 0)
    assert connectivity.max() < points and connectivity.min() >= 0
    assert set(numbers(arrays["types"])) == {5.0}  # triangles only: one deformable block
    for name in ("sxx", "syy", "sxy", "szz"):
        assert numbers(arrays[name]).size == cells
    for name in ("displacement", "velocity"):
        assert numbers(arrays[name]).size == 3 * points
    # The last snapshot holds the state results.json reports.
    assert numbers(arrays["syy"]) == pytest.approx(np.array(results["zones"]["syy"]), rel=1e-15, abs=0.0)
    displacement = numbers(arrays["displacement"]).reshape(-1, 3)
    assert displacement[:, 0] == pytest.approx(np.array(results["gridpoints"]["displacement_x"]), rel=1e-15, abs=0.0)

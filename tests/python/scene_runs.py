"""Running vdec on a scene written into a test's tmp_path: the executable (VDEC_EXECUTABLE, or the
build tree's), a skip mark for when it is not built, run(), and lattice(), a scene of stacked
blocks."""
import json
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
VDEC = os.environ.get("VDEC_EXECUTABLE", str(ROOT / "build" / "vdec"))
needs_vdec = pytest.mark.skipif(not Path(VDEC).is_file(), reason="vdec is not built")


def run(tmp_path, text, *extra, name="scene"):
    """vdec run on `text` saved as NAME.toml, output in NAME-out: (the finished process, results.json or None)."""
    scene = tmp_path / f"{name}.toml"
    scene.write_text(text)
    out = tmp_path / f"{name}-out"
    done = subprocess.run([VDEC, "run", str(scene), "--out", str(out), *extra], capture_output=True, text=True,
                          timeout=120)
    results = out / "results.json"
    return done, json.loads(results.read_text()) if results.is_file() else None


def last_vtk_cell_arrays(out):
    """The cell and point arrays of the last VTK snapshot in OUT/vtk, by name, as lists of floats;
    and the name of the cell-kind array (its legend lists the kinds present)."""
    import xml.etree.ElementTree as ET
    last = sorted((out / "vtk").glob("snapshot_*.vtu"))[-1]
    piece = ET.parse(last).getroot().find("UnstructuredGrid/Piece")
    arrays = {a.get("Name"): [float(x) for x in (a.text or "").split()] for a in piece.iter("DataArray")}
    return arrays, next(name for name in arrays if name.startswith("kind"))


def restart(tmp_path, name, state, out):
    """vdec run NAME.toml (written by run()) from a saved state, output in OUT: (the finished process,
    results.json or None)."""
    done = subprocess.run([VDEC, "run", str(tmp_path / f"{name}.toml"), "--out", str(tmp_path / out),
                           "--restart", str(state)], capture_output=True, text=True, timeout=120)
    results = tmp_path / out / "results.json"
    return done, json.loads(results.read_text()) if results.is_file() else None


def lattice(columns, rows, cycles, zoning=""):
    """1 m square blocks stacked columns x rows on a fixed base 1 m thick, Coulomb joints (kn = ks =
    1e9 Pa/m, 30 degrees), gravity, no damping (as bench/rigid_lattice_bench.cpp), stopped after
    `cycles`; the block in column c, row r is b{c}_{r}. Rigid, or deformable with `zoning` (a
    block's zoning table) and elastic rock."""
    elastic = "young = 10e9\npoisson = 0.25\n" if zoning else ""
    text = f"""[model]
rounding = 0.01
gravity = [0.0, -9.81]
[stop]
cycles = {cycles}
[[block_material]]
name = "rock"
density = 2500.0
{elastic}[[joint_material]]
name = "joint"
kn = 1e9
ks = 1e9
friction = 30.0
[[block]]
name = "base"
material = "rock"
vertices = [[0.0, -1.0], [{columns}.0, -1.0], [{columns}.0, 0.0], [0.0, 0.0]]
fix = ["x", "y", "rotation"]
"""
    for r in range(rows):
        for c in range(columns):
            text += (f'[[block]]\nname = "b{c}_{r}"\nmaterial = "rock"\n'
                     f"vertices = [[{c}.0, {r}.0], [{c + 1}.0, {r}.0], [{c + 1}.0, {r + 1}.0], [{c}.0, {r + 1}.0]]\n")
            if zoning:
                text += f"zoning = {zoning}\n"
    return text

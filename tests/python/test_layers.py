"""The source folders form layers, and no file includes from a layer above its own.

Data flows one way (docs/design.md): the model's types at the bottom, then the geometry and the
joint laws, contacts, motion, zones, boundaries and fluid flow, the run layer that orchestrates them, the
scene definitions and the builder that makes a model of them, the readers and writers, and the
command line on top. An include that
reaches upward ties a component to what is built on it; this test fails on the first one, naming
the file and line, so that CI refuses it as a build would.
"""
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SRC = ROOT / "src"

LAYERS = {
    "core": 0,
    "geometry": 1, "joint": 1,
    "contact": 2,
    "motion": 3,
    "zone": 4, "boundary": 4, "flow": 4, "structure": 4, "bem": 4, "thermal": 4,
    "run": 5,
    "scene": 6,
    "io": 7,
    "cli": 8,
}
# Header-only value types that the model stores, and that include nothing of vdec's own: they
# sit with their component but belong to the bottom layer.
BOTTOM_LAYER_HEADERS = {"boundary/time_function.hpp", "bem/far_field_state.hpp", "thermal/heat_state.hpp", "zone/mohr_coulomb.hpp", "flow/flow_state.hpp",
                        "structure/structure_state.hpp", "motion/strain_modes_state.hpp"}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/([^"]+)"', re.M)


def upward_includes(src):
    found = []
    for path in sorted(src.rglob("*.[ch]pp")):
        folder = path.relative_to(src).parts[0]
        own = LAYERS[folder]
        for match in INCLUDE.finditer(path.read_text()):
            target, header = match.group(1), f"{match.group(1)}/{match.group(2)}"
            level = 0 if header in BOTTOM_LAYER_HEADERS else LAYERS[target]
            if level > own:
                line = path.read_text()[:match.start()].count("\n") + 1
                found.append(f"{path.relative_to(src)}:{line}: {folder} (layer {own}) includes {header} (layer {level})")
    return found


@pytest.mark.requirements("REQ-RUN-003")
def test_no_source_file_includes_from_a_layer_above_its_own():
    assert set(p.name for p in SRC.iterdir() if p.is_dir()) == set(LAYERS), "a source folder has no layer"
    assert upward_includes(SRC) == []


@pytest.mark.requirements("REQ-RUN-003")
def test_an_upward_include_is_found_with_its_file_and_line(tmp_path):
    (tmp_path / "core").mkdir()
    (tmp_path / "run").mkdir()
    (tmp_path / "run" / "cycle.hpp").write_text("#pragma once\n")
    (tmp_path / "core" / "model.hpp").write_text('#pragma once\n#include <vector>\n#include "run/cycle.hpp"\n')
    for header in BOTTOM_LAYER_HEADERS:
        (tmp_path / header).parent.mkdir(exist_ok=True)
        (tmp_path / header).write_text("#pragma once\n")
    (tmp_path / "core" / "types.hpp").write_text('#include "zone/mohr_coulomb.hpp"\n')
    found = upward_includes(tmp_path)
    assert len(found) == 1 and "core/model.hpp:3: core (layer 0) includes run/cycle.hpp (layer 5)" in found[0]

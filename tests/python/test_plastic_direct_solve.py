"""The direct solve of Mohr-Coulomb zones (solver.static_solve on a plastic scene): it reaches the
equilibrium the explicit cycles relax to, records its iterations, and does not depend on the
thread count (docs/models/deformable-blocks.md#direct-solve)."""
import json
import subprocess

import numpy as np
import pytest

from scene_runs import ROOT, VDEC, needs_vdec

pytestmark = [needs_vdec, pytest.mark.requirements("REQ-ZONE-020")]

TUNNEL = ROOT / "verification" / "problems" / "MC-TUNNEL-CONVERGENCE" / "scene.toml"


def _run(out, *sets, threads=1):
    args = [VDEC, "run", str(TUNNEL), "--out", str(out), "--threads", str(threads)]
    for s in sets:
        args += ["--set", s]
    done = subprocess.run(args, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    return json.loads((out / "results.json").read_text())


def _relative_l2(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return np.linalg.norm(a - b) / np.linalg.norm(a)


@pytest.fixture(scope="module")
def tunnel(tmp_path_factory):
    base = tmp_path_factory.mktemp("tunnel")
    # One cycle after the solve: the state compared is the solve's own, not what cycles made of it.
    return _run(base / "explicit"), _run(base / "direct", "solver.static_solve=true", "stop.cycles=1")


def test_the_direct_solve_reaches_the_equilibrium_the_cycles_relax_to(tunnel):
    explicit, direct = tunnel
    # Salencon's tunnel on 32 x 8 zones, the wall unloaded at once. The two paths differ: the
    # cycles' unloading overshoots a little near the wall, where szz, the intermediate stress, is
    # then briefly the largest and the zones flow on another face, while the solve returns each
    # zone once from the in-situ state. Measured: displacements 2.6e-3 apart (relative L2), the
    # in-plane stresses 1.0e-2 to 1.3e-2, below the zoning's own error (2e-2 at the wall).
    ge, gd = explicit["gridpoints"], direct["gridpoints"]
    ue = np.hypot(ge["displacement_x"], ge["displacement_y"])
    ud = np.hypot(gd["displacement_x"], gd["displacement_y"])
    assert _relative_l2(ue, ud) < 5e-3
    for component in ("sxx", "syy", "sxy"):
        assert _relative_l2(explicit["zones"][component], direct["zones"][component]) < 2.5e-2, component
    yielded_explicit = np.count_nonzero(explicit["zones"]["plastic_state"])
    yielded_direct = np.count_nonzero(direct["zones"]["plastic_state"])
    assert yielded_direct > 0 and abs(yielded_direct - yielded_explicit) <= 0.02 * yielded_explicit


def test_the_run_records_the_plastic_iterations_and_a_residual_at_round_off(tunnel):
    explicit, direct = tunnel
    run = direct["run"]
    assert run["static_solve_plastic_iterations"] > 0 and run["static_solve_residual"] < 1e-12
    assert run["static_solve_factorisations"] == 1
    # Balanced at the start: the cycles stop on the ratio at once.
    assert run["cycles"] == 1 and run["stop_reason"] == "ratio"
    assert explicit["run"]["static_solve_plastic_iterations"] == 0
    # The solve's elastic energy is the starting state's, and nothing is lost after it.
    assert direct["energy"]["strain"] == pytest.approx(direct["energy"]["initial"], rel=1e-12, abs=0)


def test_the_plastic_direct_solve_is_the_same_at_one_and_two_threads(tmp_path, tunnel):
    _, one = tunnel
    two = _run(tmp_path / "two", "solver.static_solve=true", "stop.cycles=1", threads=2)
    for table in ("gridpoints", "zones"):
        assert one[table] == two[table]


COLUMN_BEYOND_ITS_STRENGTH = """
[model]
rounding = 0.001
[stop]
cycles = 50
[[block_material]]
name = "rock"
density = 2500.0
bulk = 1e10
shear = 6e9
friction = 30.0
cohesion = 1e6
[[block]]
name = "sample"
material = "rock"
vertices = [[0.0, 0.0], [1.0, 0.0], [1.0, 2.0], [0.0, 2.0]]
zoning = { nx = 4, ny = 8 }
[[boundary]]
block = "sample"
y = [0.0, 0.0]
fix = ["x", "y"]
[[boundary]]
block = "sample"
y = [2.0, 2.0]
pressure = 10e6
"""


def test_a_load_beyond_collapse_is_warned_of_and_left_to_the_cycles(tmp_path):
    # An unconfined column pressed at 10 MPa, above its strength 2 c sqrt(N_phi) = 3.5 MPa: no
    # equilibrium exists. The solve gives up once its residual stops falling, warns, and changes
    # nothing, so the cycles run as they would have without it.
    from scene_runs import run
    solved, with_solve = run(tmp_path, COLUMN_BEYOND_ITS_STRENGTH.replace("[stop]", "[solver]\nstatic_solve = true\n[stop]"),
                             name="solved")
    cycled, without = run(tmp_path, COLUMN_BEYOND_ITS_STRENGTH, name="cycled")
    assert solved.returncode == 0 and cycled.returncode == 0, solved.stderr + cycled.stderr
    assert "found no equilibrium of the plastic zones" in solved.stderr and "collapse" in solved.stderr
    assert 200 < with_solve["run"]["static_solve_plastic_iterations"] < 2000
    assert with_solve["run"]["static_solve_residual"] > 1e-3
    assert with_solve["gridpoints"] == without["gridpoints"]
    assert with_solve["zones"] == without["zones"]

"""Free-field boundaries (free_field = true), the medium beyond a viscous or free-field boundary
(material = ...), viscous edges of rigid blocks, and the dashpots' step limit: the scene errors of
their keys, a static state that stays at rest when a phase brings free-field sides on, and the
step against the stability bound of a dashpot on the lagged velocity."""
import json
import math
import os
import subprocess
from pathlib import Path

import pytest
from test_restart import computed

ROOT = Path(__file__).resolve().parents[2]
VDEC = os.environ.get("VDEC_EXECUTABLE", str(ROOT / "build" / "vdec"))
pytestmark = pytest.mark.skipif(not Path(VDEC).is_file(), reason="vdec is not built")

RHO, YOUNG, POISSON = 2500.0, 10e9, 0.25


def constrained_modulus(young, poisson):
    return young * (1.0 - poisson) / ((1.0 + poisson) * (1.0 - 2.0 * poisson))


ROCK = f"""
[[block_material]]
name = "rock"
density = {RHO}
young = {YOUNG}
poisson = {POISSON}
"""
# A layer 10 m wide and 10 m thick in 2 m crossed cells on a fixed base; "loose" has no elastic
# constants (a rigid block's material).
LAYER = """
[model]
rounding = 0.01
[stop]
cycles = 2
""" + ROCK + """
[[block_material]]
name = "loose"
density = 2000.0
[[block]]
name = "layer"
material = "rock"
vertices = [[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]]
zoning = { nx = 5, ny = 5 }
[[boundary]]
block = "layer"
y = [0.0, 0.0]
fix = ["x", "y"]
"""
JOINT = """
[[joint_material]]
name = "j"
kn = 1e10
ks = 1e10
friction = 30.0
"""
# A rigid block on the layer, of material MATERIAL.
STONE = JOINT + """
[[block]]
name = "stone"
material = "{material}"
vertices = [[0.0, 10.0], [2.0, 10.0], [2.0, 11.0], [0.0, 11.0]]
"""


def run(tmp_path, text, *extra, timeout=300):
    scene = tmp_path / "scene.toml"
    scene.write_text(text)
    done = subprocess.run([VDEC, "run", str(scene), "--out", str(tmp_path / "out"), *extra], capture_output=True,
                          text=True, timeout=timeout)
    results = tmp_path / "out" / "results.json"
    return done, json.loads(results.read_text()) if results.is_file() else None


def line_of(text, needle):
    """The 1-based line of the last occurrence of NEEDLE (the bad table comes last)."""
    lines = text.split("\n")
    return max(i for i, line in enumerate(lines) if line.startswith(needle)) + 1


# (tables added to LAYER, where the error is: "key" (on that key's line) or "table" (on the
# table's [[boundary]] line), the key, what the message says). boundary[1] is the bad table.
BAD = {
    "free field without x": ('[[boundary]]\nfree_field = true\ny = [0.0, 10.0]\n', "free_field = ", "free_field",
                             "needs x = [x0, x0]: the vertical side beside which the column runs"),
    "free field and viscous": ('[[boundary]]\nx = [0.0, 0.0]\nfree_field = true\nviscous = true\n', "free_field = ",
                               "free_field", "a free-field boundary has dashpots of its own: drop viscous = true"),
    "free field with fix": ('[[boundary]]\nx = [0.0, 0.0]\nfree_field = true\nfix = ["x"]\n', "fix = ", "fix",
                            "a free-field boundary applies the free field's motion and stress; give fixities, "
                            "velocities and stresses in other tables"),
    "free field with stress": ('[[boundary]]\nx = [0.0, 0.0]\nfree_field = true\nstress = [0.0, -1e5, 0.0]\n',
                               "stress = ", "stress", "a free-field boundary applies the free field's motion and "
                               "stress; give fixities, velocities and stresses in other tables"),
    "edges not vertical": ('[[boundary]]\nx = [0.0, 2.0]\nfree_field = true\n', "x = ", "x",
                           "selects the edge from (0, 0) to (2, 0) of block 'layer', which is not vertical: a free-field "
                           "column runs beside a vertical side; give x = [x0, x0] at that side"),
    "left and right side": ('[[boundary]]\nx = [0.0, 10.0]\ny = [2.0, 8.0]\nfree_field = true\n', "x = ", "x",
                            "selects vertical edges at x = 0 and at x = 10: a free-field column runs beside one "
                            "straight side; give x = [x0, x0]"),
    "gap in the side": (JOINT + '[[block]]\nname = "upper"\nmaterial = "rock"\n'
                        'vertices = [[0.0, 12.0], [10.0, 12.0], [10.0, 16.0], [0.0, 16.0]]\nzoning = { nx = 5, ny = 2 }\n'
                        '[[boundary]]\nx = [0.0, 0.0]\nfree_field = true\n', "[[boundary]]", None,
                        "leaves the side uncovered between y = 10 and 12 m: a free-field column needs an unbroken "
                        "vertical side; close the gap in the model's side, or give one free-field table per unbroken "
                        "stretch (narrow y)"),
    "free field naming no material": ('[[boundary]]\nx = [0.0, 0.0]\nfree_field = true\nmaterial = "granite"\n',
                                      "material = ", "material", "no block material named 'granite'"),
    "viscous naming no material": ('[[boundary]]\nblock = "layer"\nx = [0.0, 0.0]\nviscous = true\n'
                                   'material = "granite"\n', "material = ", "material",
                                   "no block material named 'granite'"),
    "free field on an inelastic medium": ('[[boundary]]\nx = [0.0, 0.0]\nfree_field = true\nmaterial = "loose"\n',
                                          "material = ", "material", "block material 'loose' has no elastic "
                                          "constants, and the dashpots need its wave speeds: give it young and "
                                          "poisson, or name an elastic material"),
    "viscous on an inelastic medium": ('[[boundary]]\nblock = "layer"\nx = [0.0, 0.0]\nviscous = true\n'
                                       'material = "loose"\n', "material = ", "material",
                                       "block material 'loose' has no elastic constants"),
    "material on a plain boundary": ('[[boundary]]\nblock = "layer"\nx = [0.0, 0.0]\nfix = ["x"]\nmaterial = "rock"\n',
                                     "material = ", "material", "is the medium beyond a viscous or free-field boundary: "
                                     "it needs viscous = true or free_field = true"),
    "input velocity on a plain boundary": ('[[boundary]]\nblock = "layer"\nx = [0.0, 0.0]\nfix = ["x"]\n'
                                           'input_velocity = [0.01, 0.0]\n', "input_velocity = ", "input_velocity",
                                           "is the incoming wave of a viscous or free-field boundary: it needs "
                                           "viscous = true or free_field = true"),
    "rigid block without elastic constants": (STONE.format(material="loose") + '[[boundary]]\nblock = "stone"\n'
                                              'y = [11.0, 11.0]\nviscous = true\n', "block = ", "block",
                                              "block material 'loose' has no elastic constants, and the dashpots need "
                                              "its wave speeds: give it young and poisson, or name the medium beyond "
                                              "the boundary with material = \"...\""),
    "rigid block on an inelastic medium": (STONE.format(material="rock") + '[[boundary]]\nblock = "stone"\n'
                                           'y = [11.0, 11.0]\nviscous = true\nmaterial = "loose"\n', "material = ",
                                           "material", "block material 'loose' has no elastic constants"),
    "rigid block naming no material": (STONE.format(material="rock") + '[[boundary]]\nblock = "stone"\n'
                                       'y = [11.0, 11.0]\nviscous = true\nmaterial = "granite"\n', "material = ",
                                       "material", "no block material named 'granite'"),
    "rigid block edge not selected": (STONE.format(material="rock") + '[[boundary]]\nblock = "stone"\n'
                                      'y = [10.5, 10.5]\nviscous = true\n', "[[boundary]]", None,
                                      "selects no edge of rigid block 'stone': dashpots act on the edges whose two end "
                                      "vertices are both selected; check x, y, r, angle"),
}


@pytest.mark.requirements("REQ-BOUNDARY-002", "REQ-BOUNDARY-003", "REQ-BOUNDARY-004", "REQ-IO-002")
@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_free_field_material_and_rigid_viscous_input_is_a_scene_error_naming_file_line_and_key(tmp_path, case):
    tables, at, key, message = BAD[case]
    text = LAYER + tables
    done, _ = run(tmp_path, text)
    assert done.returncode == 3, done.stderr
    where = f"{tmp_path / 'scene.toml'}:{line_of(text, at)}: "
    expected = where + (f"key 'boundary[1].{key}': " if key else "[boundary[1]]: ") + message
    assert expected in done.stderr, done.stderr


def rollered_layer(width, nx, ny):
    """A layer WIDTH m wide and 10 m thick under gravity in NX x NY crossed cells, on a fixed base
    ("base") with rollers on its sides ("left rollers", "right rollers"), local damping 0.8."""
    return f"""
[model]
rounding = 0.01
gravity = [0.0, -9.81]
[solver]
local_damping = 0.8
{ROCK}
[[block]]
name = "layer"
material = "rock"
vertices = [[0.0, 0.0], [{width}, 0.0], [{width}, 10.0], [0.0, 10.0]]
zoning = {{ nx = {nx}, ny = {ny} }}
[[boundary]]
name = "base"
block = "layer"
y = [0.0, 0.0]
fix = ["x", "y"]
[[boundary]]
name = "left rollers"
block = "layer"
x = [0.0, 0.0]
fix = ["x"]
[[boundary]]
name = "right rollers"
block = "layer"
x = [{width}, {width}]
fix = ["x"]
"""


def side_history(name, quantity, point):
    return f"""
[[history]]
name = "{name}"
quantity = "{quantity}"
block = "layer"
point = [{point[0]}, {point[1]}]
every = 1
"""


# The layer 20 m wide in 2 m cells relaxed to equilibrium (ratio 1e-9); then the rollers go and
# free-field columns with no input come on, undamped.
RELAXED_LAYER = rollered_layer(20.0, 10, 5) + """
[[phase]]
name = "settle"
stop = { ratio = 1e-9, cycles = 200000 }
require_equilibrium = true
[[phase]]
name = "free field"
stop = { time = 0.1 }
mass_damping = 0.0
free = ["left rollers", "right rollers"]
[[phase.boundary]]
name = "left"
x = [0.0, 0.0]
free_field = true
[[phase.boundary]]
name = "right"
x = [20.0, 20.0]
free_field = true
""" + "".join(side_history(f"{side}_{y}", "gridpoint.velocity_x", (x, y))
                for side, x in (("left", 0.0), ("right", 20.0)) for y in (2.0, 4.0, 6.0, 8.0, 10.0))


@pytest.mark.requirements("REQ-BOUNDARY-003", "REQ-RUN-004")
def test_a_relaxed_layer_stays_at_rest_when_a_phase_swaps_its_rollers_for_free_field_sides(tmp_path):
    done, results = run(tmp_path, RELAXED_LAYER)
    assert done.returncode == 0, done.stderr
    settle, free = results["phases"]
    assert settle["stop_reason"] == "ratio" and free["stop_reason"] == "time"
    # The rollers held sxx = K0 rho g d, K0 = nu / (1 - nu) (no lateral strain), on the sides; let
    # go onto the side's dashpots (a column with no gravity carries no stress) that traction would
    # drive the side at about sxx / (rho c_p): 0.015 m/s at the base, 4e-3 m/s measured 4 m down
    # with the reactions dropped. Kept as loads, only the static phase's residual forces remain,
    # at most the ratio (1e-9) times the forces of the zones, and so of the reactions: the side
    # moves at about ratio x that velocity (measured 0.65 to 1.8 ratio). 100 times that is the bound.
    c_p = math.sqrt(constrained_modulus(YOUNG, POISSON) / RHO)
    released = POISSON / (1.0 - POISSON) * RHO * 9.81 * 10.0 / (RHO * c_p)
    bound = 100.0 * 1e-9 * released
    start = settle["cycles"]
    for name, history in results["histories"].items():
        v = history["value"]
        assert len(v) == results["run"]["cycles"] + 1, name
        assert max(abs(x) for x in v[start:]) < bound, name


# One crossed cell carried at 0.01 m/s by a named boundary for one cycle, then let go: it goes on
# at that velocity, with kinetic energy the driver gave it and no work recorded.
CARRIED_CELL = """
[model]
rounding = 0.01
""" + ROCK + """
[[block]]
name = "cell"
material = "rock"
vertices = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
zoning = { nx = 1, ny = 1 }
[[boundary]]
name = "carry"
block = "cell"
velocity_y = 0.01
[[history]]
name = "vy"
quantity = "gridpoint.velocity_y"
block = "cell"
point = [0.5, 0.5]
every = 1
[[phase]]
name = "carried"
stop = { cycles = 1 }
[[phase]]
name = "coasting"
free = ["carry"]
stop = { cycles = 100 }
"""


@pytest.mark.requirements("REQ-RUN-004")
def test_a_phase_that_frees_a_driven_boundary_gives_the_energy_account_its_kinetic_energy(tmp_path):
    done, results = run(tmp_path, CARRIED_CELL)
    # Before the released kinetic energy was entered, the monitor saw 0.125 J/m appear from no
    # supply and stopped the run with exit code 5.
    assert done.returncode == 0, done.stderr
    assert results["histories"]["vy"]["value"][-1] == pytest.approx(0.01, rel=1e-12, abs=0)
    kinetic = 0.5 * RHO * 1.0 * 0.01 ** 2
    energy = results["energy"]
    assert energy["kinetic"] == pytest.approx(kinetic, rel=1e-9, abs=0)
    assert energy["removed"] == pytest.approx(-kinetic, rel=1e-9, abs=0)


# A layer 10 m thick in 1 m crossed cells on a half-space 100 times stiffer (c_p ten times the
# layer's), through a viscous base that names it; SIDES and the [solver] keys SOLVER added.
def layer_on_half_space(solver, sides="", stop="cycles = 1", base_input=""):
    return f"""
[model]
rounding = 0.01
[solver]
{solver}
[stop]
{stop}
[[block_material]]
name = "layer"
density = {RHO}
young = {YOUNG}
poisson = {POISSON}
[[block_material]]
name = "halfspace"
density = {RHO}
young = {100 * YOUNG}
poisson = {POISSON}
[[block]]
name = "layer"
material = "layer"
vertices = [[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]]
zoning = {{ nx = 10, ny = 10 }}
[[boundary]]
name = "base"
block = "layer"
y = [0.0, 0.0]
viscous = true
material = "halfspace"
{base_input}
{sides}"""


FREE_FIELD_SIDES = """
[[boundary]]
name = "left"
x = [0.0, 0.0]
free_field = true
material = "halfspace"
[[boundary]]
name = "right"
x = [10.0, 10.0]
free_field = true
material = "halfspace"
"""
M_LAYER = constrained_modulus(YOUNG, POISSON)
Z_LAYER = math.sqrt(RHO * M_LAYER)  # rho c_p, the larger of the two impedances
ZS_LAYER = math.sqrt(RHO * YOUNG / (2.0 * (1.0 + POISSON)))  # rho c_s
Z_HALF_SPACE = math.sqrt(RHO * constrained_modulus(100 * YOUNG, POISSON))


def dashpot_step(mass, stiffness, dashpot):
    """The largest stable step of a mass on a spring with a dashpot on the lagged velocity:
    (w dt)^2 + 2 c dt / m < 4, w^2 = k / m."""
    return 4.0 * mass / (dashpot + math.sqrt(dashpot ** 2 + 4.0 * stiffness * mass))


def layer_step_limits(zone_fraction, free_field):
    """The step limits of layer_on_half_space, formed here from the cells: each of the four
    triangles of a square cell of side h has area h^2 / 4, longest side h and least height h / 2,
    and gives each of its corners the mass rho h^2 / 12 and the stiffness (8/3) M h / (h / 2) of
    1.3-27; a gridpoint has them from 2 (a corner), 4 (a side) or 8 triangles."""
    h = 1.0
    mass, stiffness = RHO * h * h / 12.0, 16.0 / 3.0 * M_LAYER
    zones = zone_fraction * 2.0 * math.sqrt(mass / stiffness)
    side = Z_LAYER if free_field else 0.0  # the side dashpots take the layer's impedance
    # (triangles, dashpot): base gridpoints, the base corners, the side gridpoints, the top corners.
    gridpoints = [(4, h * Z_HALF_SPACE), (2, 0.5 * h * (Z_HALF_SPACE + side))]
    if free_field:
        gridpoints += [(4, h * side), (2, 0.5 * h * side)]
    limits = {"deformable-blocks": zones,
              "boundaries": zone_fraction * min(dashpot_step(n * mass, n * stiffness, c) for n, c in gridpoints)}
    if free_field:
        # The column: nodes every h, masses rho h (rho h / 2 at its ends), stiffness 2 M / h per
        # element at each node, the half-space's dashpot at its base node.
        limits["free-field"] = min(dashpot_step(RHO * h / 2.0, 2.0 * M_LAYER / h, Z_HALF_SPACE),
                                   dashpot_step(RHO * h, 4.0 * M_LAYER / h, 0.0))
    return limits


REQ_STEP = pytest.mark.requirements("REQ-BOUNDARY-004", "REQ-RUN-006")


@REQ_STEP
def test_the_step_limits_are_each_components_and_the_step_the_smallest_reduced_for_local_damping(tmp_path):
    done, results = run(tmp_path, layer_on_half_space("local_damping = 0.8\nzone_fraction = 0.9", FREE_FIELD_SIDES))
    assert done.returncode == 0, done.stderr
    limits = results["run"]["step_limits"]
    expected = layer_step_limits(0.9, free_field=True)
    assert limits == pytest.approx(expected, rel=1e-12, abs=0)
    # Local damping divides the critical step by sqrt(1 + alpha_L).
    assert results["run"]["dt"] == pytest.approx(min(expected.values()) / math.sqrt(1.8), rel=1e-12, abs=0)


@REQ_STEP
def test_the_step_under_stiffness_damping_is_the_smallest_limit_times_its_factor(tmp_path):
    beta = 2e-5
    done, results = run(tmp_path, layer_on_half_space(f"stiffness_damping = {beta}", FREE_FIELD_SIDES))
    assert done.returncode == 0, done.stderr
    expected = layer_step_limits(1.0, free_field=True)
    assert results["run"]["step_limits"] == pytest.approx(expected, rel=1e-12, abs=0)
    # xi = beta w / 2 of the stiffest mode, w the larger of 2 / dt_z and the column's 2 / dt.
    xi = 0.5 * beta * max(2.0 / expected["deformable-blocks"], 2.0 / expected["free-field"])
    factor = math.sqrt(1.0 + xi * xi) - xi
    assert results["run"]["stiffness_damping_step_factor"] == pytest.approx(factor, rel=1e-12, abs=0)
    assert results["run"]["dt"] == pytest.approx(min(expected.values()) * factor, rel=1e-12, abs=0)


@REQ_STEP
@pytest.mark.parametrize("zone_fraction, exit_code", [(0.9, 0), (1.1, 5)])
def test_a_layer_on_a_stiff_half_space_is_stable_below_the_dashpot_limit_and_not_above(tmp_path, zone_fraction,
                                                                                       exit_code):
    # A P and S wave through the base, 20 Hz, for 0.05 s (1,750 steps at the limit).
    done, results = run(tmp_path, layer_on_half_space(
        f"zone_fraction = {zone_fraction}", stop="time = 0.05",
        base_input='input_velocity = [0.01, 0.01]\nhistory = { kind = "sine", frequency = 20.0 }'))
    # At a base gridpoint (m = rho h^2 / 3, k = 64 M / 3) the dashpot c = h rho c_p of the
    # half-space is x = 3 Z_half-space / (16 Z_layer) = 1.875 times 2 sqrt(k m): c^2 is 3.5 times
    # 4 k m, so the bound is nearer the dashpot's own c dt / m < 2 than the spring's, and
    # 1.3-26's margin on k matters less. The bound is the zones' estimate / (x + sqrt(1 + x^2)),
    # a quarter of it, and the step is zone_fraction times the bound.
    limits = layer_step_limits(zone_fraction, free_field=False)
    assert limits["boundaries"] == pytest.approx(limits["deformable-blocks"] / 4.0, rel=1e-12, abs=0)
    assert done.returncode == exit_code, done.stderr
    assert results["run"]["dt"] == pytest.approx(limits["boundaries"], rel=1e-12, abs=0)
    if exit_code:
        assert "numerical instability" in done.stderr and "lower solver.zone_fraction (now 1.1" in done.stderr


# A rigid block 2 m x 1 m, free, its top edge viscous (its own material's impedances).
RIGID_BLOCK = """
[model]
rounding = 0.01
[stop]
cycles = 1
""" + ROCK + """
[[joint_material]]
name = "j"
kn = 1e10
ks = 1e10
friction = 30.0
[[block]]
name = "stone"
material = "rock"
vertices = [[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]]
[[boundary]]
block = "stone"
y = [1.0, 1.0]
viscous = true
"""


@REQ_STEP
def test_a_rigid_blocks_viscous_edge_limits_the_step_as_a_dashpot_on_its_translation_and_rotation(tmp_path):
    done, results = run(tmp_path, RIGID_BLOCK)
    assert done.returncode == 0, done.stderr
    frac, kn = 0.1, 1e10
    mass, radius = RHO * 2.0, math.hypot(1.0, 0.5)
    inertia = mass * (2.0 ** 2 + 1.0 ** 2) / 12.0
    # The edge from (2, 1) to (0, 1), 0.5 above the centroid, l = 2: its dashpots' matrix on the
    # translation is diag(Zs l, Zn l), on the rotation Zn l^3 / 12 + Zs l 0.5^2; the decay rate is
    # bounded by the larger translation entry over m plus the rotation entry over I.
    rate = Z_LAYER * 2.0 / mass + (Z_LAYER * 8.0 / 12.0 + ZS_LAYER * 2.0 * 0.25) / inertia
    spring = kn * 2.0 * radius / mass  # joint springs along the block, l_typ at most its diameter
    expected = {"rigid-block-motion": frac * 2.0 * math.sqrt(mass / (kn * 2.0)),  # 1.3-28, longest edge 2 m
                "boundaries": frac * 4.0 / (rate + math.sqrt(rate ** 2 + 4.0 * spring))}
    assert results["run"]["step_limits"] == pytest.approx(expected, rel=1e-12, abs=0)
    assert results["run"]["dt"] == pytest.approx(min(expected.values()), rel=1e-12, abs=0)


# The layer 10 m wide in 2 m cells relaxed as above, then shaken by an S wave through a viscous
# base with free-field sides, a rigid cap on it whose top edge is viscous: the columns' motion,
# stresses and kept reactions, and the rigid block's dashpots, must all come back from a state file.
WAVE = 'input_velocity = [0.01, 0.0]\nhistory = { kind = "sine", frequency = 50.0 }'
SHAKEN_LAYER = rollered_layer(10.0, 5, 5) + JOINT + f"""
[[block]]
name = "cap"
material = "rock"
vertices = [[4.0, 10.0], [6.0, 10.0], [6.0, 11.0], [4.0, 11.0]]
[[history]]
name = "cap"
quantity = "block.velocity_x"
block = "cap"
every = 1
{side_history("side", "gridpoint.velocity_x", (0.0, 6.0))}
[[phase]]
name = "settle"
stop = {{ ratio = 1e-6, cycles = 100000 }}
[[phase]]
name = "shake"
stop = {{ time = 0.015 }}
mass_damping = 0.0
free = ["base", "left rollers", "right rollers"]
[[phase.boundary]]
name = "base"
block = "layer"
y = [0.0, 0.0]
viscous = true
{WAVE}
[[phase.boundary]]
name = "left"
x = [0.0, 0.0]
free_field = true
{WAVE}
[[phase.boundary]]
name = "right"
x = [10.0, 10.0]
free_field = true
{WAVE}
[[phase.boundary]]
name = "cap top"
block = "cap"
y = [11.0, 11.0]
viscous = true
[[phase]]
name = "more"
stop = {{ time = 0.015 }}
"""


@pytest.mark.requirements("REQ-RUN-005", "REQ-BOUNDARY-003")
@pytest.mark.parametrize("threads", ["1", "2"])
@pytest.mark.parametrize("saved_phase, number", [("settle", 1), ("shake", 2)])
def test_a_restart_with_free_field_columns_and_a_rigid_viscous_edge_is_the_run_that_did_not_stop(
        tmp_path, saved_phase, number, threads):
    (tmp_path / "whole").mkdir()
    done, whole = run(tmp_path / "whole", SHAKEN_LAYER, "--threads", "1")
    assert done.returncode == 0, done.stderr
    assert {"free-field", "viscous-boundaries", "rigid-viscous-boundaries"} <= set(whole["run"]["stages"])
    # The sides move with the wave: a state that lost the columns would show.
    assert max(abs(v) for v in whole["histories"]["side"]["value"]) > 1e-3
    (tmp_path / "first").mkdir()
    done, _ = run(tmp_path / "first", SHAKEN_LAYER, "--threads", threads, "--save", saved_phase)
    assert done.returncode == 0, done.stderr
    state = tmp_path / "first" / "out" / f"after-phase-{number}.vdecstate"
    (tmp_path / "rest").mkdir()
    done, rest = run(tmp_path / "rest", SHAKEN_LAYER, "--threads", threads, "--restart", str(state))
    assert done.returncode == 0, done.stderr
    assert rest["scene"]["restart"] == {"file": str(state), "phases_done": number}
    assert rest["run"]["stages"] == whole["run"]["stages"]
    assert rest["run"]["step_limits"] == whole["run"]["step_limits"]
    assert computed(rest) == computed(whole)

"""Heat conduction through a scene (docs/models/heat.md, docs/user-manual/scene-format.md#heat):
its scene errors, heat across joints, the conductivity's axes, sources and their decay, the heat
balance, outputs and restart."""
import math

import pytest

from scene_runs import ROOT, last_vtk_cell_arrays, needs_vdec, restart, run

pytestmark = needs_vdec
STRIP = (ROOT / "verification" / "problems" / "TH-SEMI-INFINITE" / "scene.toml").read_text()
SHORT = STRIP.replace("heat_time = 2e4", "heat_time = 2e3").replace("heat_time = 7e4", "heat_time = 7e3").replace(
    "heat_time = 1e4", "heat_time = 1e3")

BAD = [
    ("theta out of range", STRIP.replace("initial_temperature = 0.0", "theta = 1.5"), "heat.theta", "must be in [0, 1]"),
    ("implicit without a step", STRIP.replace("initial_temperature = 0.0", "theta = 0.5"), "heat.step", "is required with theta > 0"),
    ("two conditions", STRIP.replace("temperature = 100.0", "temperature = 100.0\nflux = 1.0"), "heat_boundary[0]", "give one of"),
    ("no condition", STRIP.replace("temperature = 100.0\n", ""), "heat_boundary[0]", "sets nothing"),
    ("emissivity above 1", STRIP.replace("temperature = 100.0", "radiation = { emissivity = 1.2, ambient = 300.0 }"), "emissivity", "must be in (0, 1]"),
    ("radiation without ambient", STRIP.replace("temperature = 100.0", "radiation = { emissivity = 0.5 }"), "ambient", "is required"),
    ("decay of a temperature", STRIP.replace("temperature = 100.0", "temperature = 100.0\ndecay = [[1.0, 10.0]]"), "decay", "applies to a flux"),
    ("bad decay", STRIP.replace("temperature = 100.0", "flux = 1.0\ndecay = [[1.0, -10.0]]"), "decay", "must be > 0"),
    ("no specific heat", STRIP.replace("specific_heat = 1000.0\n", ""), "specific_heat", "is required with [heat]"),
    ("no conductivity", STRIP.replace("conductivity = 3.0\n", ""), "conductivity", "is required with [heat]"),
    ("negative expansion", STRIP.replace("specific_heat = 1000.0", "specific_heat = 1000.0\nexpansion = -1e-5"), "expansion", "must be >= 0"),
    ("huge expansion", STRIP.replace("specific_heat = 1000.0", "specific_heat = 1000.0\nexpansion = 0.5"), "expansion", "must be at most 1e-3"),
    ("expansion without elasticity", STRIP.replace("young = 10e9\npoisson = 0.25\n", "").replace("specific_heat = 1000.0", "specific_heat = 1000.0\nexpansion = 1e-5"), "expansion", "needs the elastic constants"),
    ("both conductivities", STRIP.replace("conductivity = 3.0", "conductivity = 3.0\nconductivity_x = 2.0\nconductivity_y = 1.0"), "conductivity", "give either"),
    ("boundary without heat", STRIP.replace("[heat]\ninitial_temperature = 0.0\n", "").replace('[[history]]\nname = "T_at_0.1"', '[[history]]\nname = "x"'), "heat_boundary[0]", "needs a [heat] table"),
    ("phase heat time without heat", STRIP.replace("[heat]\ninitial_temperature = 0.0\n", "").split("[[heat_boundary]]")[0] + "[[phase]]\nname = \"a\"\nheat_time = 1.0\nstop = { cycles = 1 }\n", "heat_time", "needs a [heat] table"),
    ("run time with phases", STRIP.replace("initial_temperature = 0.0", "time = 10.0"), "heat.time", "with [[phase]] give each phase its heat_time"),
    ("source off the gridpoints", STRIP.replace("[[history]]", "[[heat_source]]\npoint = [0.01, 0.0]\npower = 1.0\n[[history]]", 1), "point", "no gridpoint at"),
    ("source of both kinds", STRIP.replace("[[history]]", "[[heat_source]]\npoint = [0.0, 0.0]\nblock = \"strip\"\npower = 1.0\n[[history]]", 1), "heat_source[0]", "give either point"),
    ("nothing selected", STRIP.replace("x = [0.0, 0.0]\ntemperature", "x = [9.0, 9.0]\ntemperature"), "heat_boundary[0]", "selects no gridpoint"),
    ("excavation in a phase", STRIP + "[[phase.excavation]]\ncircle = { centre = [2.0, 0.025], radius = 0.2 }\n", "excavation", "cannot excavate a model that conducts heat"),
    ("temperature without heat", STRIP.replace("[heat]\ninitial_temperature = 0.0\n", "").split("[[heat_boundary]]")[0] + STRIP[STRIP.index("[[history]]"):STRIP.index("[[phase]]")] + "[stop]\ncycles = 1\n", "quantity", "no [heat] table"),
]


@pytest.mark.requirements("REQ-THERM-006", "REQ-THERM-007")
@pytest.mark.parametrize("what,text,key,phrase", BAD, ids=[b[0] for b in BAD])
def test_bad_heat_input_is_a_scene_error_naming_the_key(tmp_path, what, text, key, phrase):
    assert text != STRIP
    done, _ = run(tmp_path, text)
    assert done.returncode == 3, (what, done.stderr)
    assert key in done.stderr and phrase in done.stderr, (what, done.stderr)


def temperatures(results):
    g = results["gridpoints"]
    return {(round(x, 9), round(y, 9)): t for x, y, t in zip(g["x0"], g["y0"], g["temperature"])}


@pytest.mark.requirements("REQ-THERM-001")
def test_heat_crosses_a_joint_of_matching_zoning_as_if_it_were_not_there(tmp_path):
    # The strip cut at x = 0.1 into two blocks zoned alike: their coincident gridpoints are one
    # thermal node, so the temperatures are those of the single strip (to the order of the sums).
    two = SHORT.replace('''[[block]]
name = "strip"
material = "rock"
vertices = [[0.0, 0.0], [4.0, 0.0], [4.0, 0.05], [0.0, 0.05]]
zoning = { nx = 80, ny = 1 }''', '''[[block]]
name = "strip"
material = "rock"
vertices = [[0.0, 0.0], [0.1, 0.0], [0.1, 0.05], [0.0, 0.05]]
zoning = { nx = 2, ny = 1 }
[[block]]
name = "rest"
material = "rock"
vertices = [[0.1, 0.0], [4.0, 0.0], [4.0, 0.05], [0.1, 0.05]]
zoning = { nx = 78, ny = 1 }
[[boundary]]
block = "rest"
x = [0.0, 4.0]
fix = ["x", "y"]
[[joint_material]]
name = "joint"
kn = 1e10
ks = 1e10''')
    done, split = run(tmp_path, two, name="split")
    assert done.returncode == 0, done.stderr
    done, whole = run(tmp_path, SHORT, name="whole")
    assert done.returncode == 0, done.stderr
    assert split["heat"]["nodes"] == whole["heat"]["nodes"]
    a, b = temperatures(split), temperatures(whole)
    assert a[(0.15, 0.0)] > 10.0, "the heat crossed into the second block"
    for point, t in b.items():
        assert a[point] == pytest.approx(t, rel=1e-11, abs=1e-11)


@pytest.mark.requirements("REQ-THERM-001")
def test_the_conductivity_turns_with_its_angle(tmp_path):
    # k_x = 3 along the material's axis turned by 90 degrees is k = 3 along y: the same tensor as
    # k_x = 1, k_y = 3 unturned; and not the unturned k_x = 3, k_y = 1.
    def strip(kx, ky, angle):
        return SHORT.replace("conductivity = 3.0", f"conductivity_x = {kx}\nconductivity_y = {ky}\nconductivity_angle = {angle}")
    runs = {}
    for name, text in (("turned", strip(3.0, 1.0, 90.0)), ("same", strip(1.0, 3.0, 0.0)), ("other", strip(3.0, 1.0, 0.0))):
        done, runs[name] = run(tmp_path, text, name=name)
        assert done.returncode == 0, done.stderr
    turned, same, other = (temperatures(runs[k]) for k in ("turned", "same", "other"))
    assert all(turned[p] == pytest.approx(same[p], rel=1e-9, abs=1e-9) for p in same)
    assert max(abs(turned[p] - other[p]) for p in other) > 1.0


@pytest.mark.requirements("REQ-THERM-004", "REQ-THERM-005")
def test_a_decaying_line_source_stores_what_it_releases(tmp_path):
    # A source of 100 W/m at a gridpoint inside the strip, decaying as 0.6 exp(-t / 2e3) +
    # 0.4 exp(-t / 2e4), over 1e4 s with Crank-Nicolson (its loads at mid-step): all of it is stored
    # (adiabatic edges, no held node), as sum a tau (1 - exp(-T / tau)) times the power.
    text = STRIP.replace("[[heat_boundary]]\nblock = \"strip\"\nx = [0.0, 0.0]\ntemperature = 100.0\n", "")
    text = text.replace("initial_temperature = 0.0", "initial_temperature = 0.0\ntheta = 0.5\nstep = 50.0")
    text = text.replace("[[history]]", "[[heat_source]]\npoint = [2.0, 0.0]\npower = 100.0\ndecay = [[0.6, 2e3], [0.4, 2e4]]\n[[history]]", 1)
    text = text.replace("heat_time = 2e4", "heat_time = 0.0").replace("heat_time = 7e4", "heat_time = 0.0")
    done, results = run(tmp_path, text)
    assert done.returncode == 0, done.stderr
    balance = results["heat"]["balance"]
    released = 100.0 * sum(a * tau * (1 - math.exp(-1e4 / tau)) for a, tau in ((0.6, 2e3), (0.4, 2e4)))
    assert balance["sources"] == pytest.approx(released, rel=2e-4, abs=0)   # the midpoint rule's O(dt^2 / tau^2)
    assert balance["stored"] == pytest.approx(balance["sources"], rel=1e-12, abs=0)
    assert results["heat"]["factorisations"] == 1 and results["heat"]["steps"] == 200


@pytest.mark.requirements("REQ-THERM-005")
def test_a_phased_thermal_run_restarts_bitwise_and_writes_its_temperatures(tmp_path):
    text = SHORT.replace("[model]", "[output]\nvtk_every = 1\n[model]")
    text = text.replace("[[phase]]", "[[history]]\nname = \"stored\"\nquantity = \"heat.stored\"\n[[phase]]", 1)
    done, whole = run(tmp_path, text, "--save", "t1", name="strip")
    assert done.returncode == 0, done.stderr
    assert [p["stop_reason"] for p in whole["phases"]] == ["cycles"] * 3
    assert whole["heat"]["time"] == pytest.approx(1e4, rel=1e-12, abs=0)
    assert whole["histories"]["heat_time"]["value"][-1] == whole["heat"]["time"]
    assert whole["histories"]["stored"]["value"][-1] == whole["heat"]["balance"]["stored"] > 0.0
    resumed, again = restart(tmp_path, "strip", tmp_path / "strip-out" / "after-phase-1.vdecstate", "resumed")
    assert resumed.returncode == 0, resumed.stderr
    assert again["gridpoints"] == whole["gridpoints"] and again["heat"] == whole["heat"]
    arrays, _ = last_vtk_cell_arrays(tmp_path / "strip-out")
    assert arrays["temperature"][:len(whole["gridpoints"]["temperature"])] == whole["gridpoints"]["temperature"]


@pytest.mark.requirements("REQ-THERM-004")
def test_held_temperatures_and_fluxes_follow_their_histories(tmp_path):
    # A flux ramped linearly from 0 to q0 over the 1e4 s (a table history): Crank-Nicolson takes it at
    # mid-step, exact for a linear load, so the strip stores q0 h T / 2. A held temperature on a
    # sine history: the surface node is at 100 sin(2 pi f t) at the end, and the balance closes.
    (tmp_path / "ramp.csv").write_text("0.0, 0.0\n1e4, 1.0\n")
    ramp = SHORT.replace("initial_temperature = 0.0", "initial_temperature = 0.0\ntheta = 0.5\nstep = 250.0")
    ramp = ramp.replace("temperature = 100.0", 'flux = 50.0\nhistory = { kind = "table", file = "ramp.csv" }')
    done, results = run(tmp_path, ramp, name="ramp")
    assert done.returncode == 0, done.stderr
    assert results["heat"]["balance"]["stored"] == pytest.approx(50.0 * 0.05 * 1e4 / 2, rel=1e-12, abs=0)
    sine = SHORT.replace("temperature = 100.0", 'temperature = 100.0\nhistory = { kind = "sine", frequency = 2.5e-5 }')
    done, results = run(tmp_path, sine, name="sine")
    assert done.returncode == 0, done.stderr
    surface = [t for x, t in zip(results["gridpoints"]["x0"], results["gridpoints"]["temperature"]) if x == 0.0]
    assert surface and all(t == pytest.approx(100.0 * math.sin(2 * math.pi * 2.5e-5 * 1e4), rel=1e-12, abs=0) for t in surface)
    balance = results["heat"]["balance"]
    assert abs(balance["imbalance"]) < 1e-9 * max(abs(balance["fixed"]), 1.0)
    assert balance["fixed"] != 0.0
    convection = SHORT.replace("temperature = 100.0", 'convection = { h = 1.0, ambient = 5.0 }\nhistory = { kind = "sine", frequency = 1.0 }')
    done, _ = run(tmp_path, convection, name="convection")
    assert done.returncode == 3 and "history" in done.stderr and "ambient temperature is constant" in done.stderr


@pytest.mark.requirements("REQ-THERM-008")
def test_radiation_below_absolute_zero_stops_the_run(tmp_path):
    # Radiation needs kelvin: a scene in degrees Celsius below zero stops with the instability code.
    cold = STRIP.replace("initial_temperature = 0.0", "initial_temperature = -10.0").replace(
        "temperature = 100.0", "radiation = { emissivity = 0.5, ambient = 300.0 }")
    done, _ = run(tmp_path, cold)
    assert done.returncode == 5 and "radiation needs absolute temperatures (kelvin)" in done.stderr, done.stderr


PLATE = """[model]
rounding = 0.001
[[block_material]]
name = "rock"
density = 2500.0
young = 10e9
poisson = 0.25
conductivity = 3.0
specific_heat = 1000.0
[[joint_material]]
name = "joint"
kn = 1e10
ks = 1e10
[[block]]
name = "left"
material = "rock"
vertices = [[0.0, 0.0], [0.5, 0.0], [0.5, 0.2], [0.0, 0.2]]
zoning = { nx = 10, ny = 4 }
[[block]]
name = "right"
material = "rock"
vertices = [[0.5, 0.0], [1.0, 0.0], [1.0, 0.2], [0.5, 0.2]]
zoning = { nx = 10, ny = 4 }
[[boundary]]
block = "left"
x = [0.0, 1.0]
fix = ["x", "y"]
[[boundary]]
block = "right"
x = [0.0, 1.0]
fix = ["x", "y"]
[heat]
initial_temperature = 0.0
theta = 1.0
step = 1e9
time = 1e10
[[heat_boundary]]
block = "left"
x = [0.0, 0.0]
temperature = 100.0
[[heat_boundary]]
block = "right"
x = [1.0, 1.0]
temperature = 0.0
[stop]
cycles = 1
"""


def flow_history(name, start, end):
    return f'[[history]]\nname = "{name}"\nquantity = "heat.flow"\nfrom = [{start[0]}, {start[1]}]\nto = [{end[0]}, {end[1]}]\n'


@pytest.mark.requirements("REQ-THERM-005")
def test_the_heat_flow_through_a_line_is_the_conducted_flux_times_its_length(tmp_path):
    # Steady conduction along a plate of two blocks (a joint at x = 0.5 m) held at 100 and 0 degrees
    # at its ends: T is linear, which linear triangles hold exactly, and the flow through any section
    # of its 0.2 m height is k dT/L h = 3 * 100 * 0.2 = 60 W/m in +x, through the held end, a section
    # inside a block and the joint (edges with a zone of each block) alike; backwards it is -60, and
    # along the adiabatic top nothing crosses.
    lines = {"end": ((0.0, 0.0), (0.0, 0.2)), "inside": ((0.25, 0.0), (0.25, 0.2)), "joint": ((0.5, 0.0), (0.5, 0.2)),
             "backwards": ((0.75, 0.2), (0.75, 0.0)), "top": ((0.0, 0.2), (1.0, 0.2)), "half": ((0.85, 0.1), (0.85, 0.2))}
    text = PLATE + "".join(flow_history(name, *ends) for name, ends in lines.items())
    done, results = run(tmp_path, text)
    assert done.returncode == 0, done.stderr
    flow = {name: results["histories"][name]["value"][-1] for name in lines}
    for name in ("end", "inside", "joint"):
        assert flow[name] == pytest.approx(60.0, rel=1e-9, abs=0), name
    assert flow["backwards"] == pytest.approx(-60.0, rel=1e-9, abs=0)
    assert flow["half"] == pytest.approx(30.0, rel=1e-9, abs=0)
    assert abs(flow["top"]) < 1e-9


@pytest.mark.requirements("REQ-THERM-005", "REQ-THERM-006")
def test_a_heat_flow_line_off_the_zone_edges_is_a_scene_error(tmp_path):
    done, _ = run(tmp_path, PLATE + flow_history("off", (0.26, 0.0), (0.26, 0.2)))
    assert done.returncode == 3
    assert "history[0].from" in done.stderr and "runs along no zone edge" in done.stderr, done.stderr
    done, _ = run(tmp_path, PLATE + flow_history("point", (0.25, 0.0), (0.25, 0.0)))
    assert done.returncode == 3 and "history[0].to" in done.stderr and "two distinct ends" in done.stderr, done.stderr

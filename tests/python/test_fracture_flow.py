"""Fracture flow through a scene (docs/models/fracture-flow.md, docs/user-manual/scene-format.md#fluid):
the scene errors of its keys, the instability it detects, phases that switch it on and a restart
across them, and its independence of the thread count."""
import json
import re
import subprocess

import pytest

from scene_runs import ROOT, VDEC, needs_vdec, run

SCENE = ROOT / "tests" / "python" / "fixtures" / "fluid_joint.toml"
pytestmark = needs_vdec


BASE = SCENE.read_text()
NO_FLUID = re.sub(r"(?ms)^\[fluid\]\n.*?(?=^\[)", "", BASE)

# (what is wrong, the scene, the key the message must name, a phrase of the message)
BAD = [
    ("no aperture", BASE.replace("aperture = 1e-4\n", ""), "aperture", "is required with [fluid]"),
    ("no residual aperture", BASE.replace("residual_aperture = 1e-5\n", ""), "residual_aperture", "is required"),
    ("residual above aperture", BASE.replace("residual_aperture = 1e-5", "residual_aperture = 1e-3"),
     "residual_aperture", "must not exceed aperture"),
    ("residual zero", BASE.replace("residual_aperture = 1e-5", "residual_aperture = 0.0"), "residual_aperture", "> 0"),
    ("aperture above a metre", BASE.replace("aperture = 1e-4", "aperture = 1e308"), "aperture", "at most 1 m"),
    ("max below aperture", BASE.replace("residual_aperture = 1e-5", "residual_aperture = 1e-5\nmax_aperture = 1e-5"),
     "max_aperture", "must be at least"),
    ("no bulk modulus", BASE.replace("bulk_modulus = 2e6\n", ""), "bulk_modulus", "is required"),
    ("no viscosity", BASE.replace("viscosity = 1e-3\n", ""), "viscosity", "is required"),
    ("unknown Bingham law", BASE.replace("viscosity = 1e-3", "viscosity = 1e-3\nyield_stress = 1.0\nbingham_law = \"x\""),
     "bingham_law", "use linear or buckingham"),
    ("Bingham law without yield stress", BASE.replace("viscosity = 1e-3", "viscosity = 1e-3\nbingham_law = \"linear\""),
     "bingham_law", "yield_stress > 0"),
    ("unknown scheme", BASE.replace("viscosity = 1e-3", "viscosity = 1e-3\nscheme = \"fast\""), "scheme",
     "use explicit, implicit or steady"),
    ("step fraction out of range", BASE.replace("viscosity = 1e-3", "viscosity = 1e-3\nstep_fraction = 5.0"),
     "step_fraction", "(0, 4]"),
    ("step fraction with a solved scheme",
     BASE.replace("viscosity = 1e-3", "viscosity = 1e-3\nscheme = \"steady\"\nstep_fraction = 0.5"), "step_fraction",
     "takes none"),
    ("water table without gravity", BASE.replace("viscosity = 1e-3", "viscosity = 1e-3\nwater_table = 1.0"),
     "water_table", "needs gravity"),
    ("initial saturation above one", BASE.replace("viscosity = 1e-3", "viscosity = 1e-3\ninitial_saturation = 1.5"),
     "initial_saturation", "[0, 1]"),
    ("initial saturation with an initial pressure",
     BASE.replace("viscosity = 1e-3", "viscosity = 1e-3\ninitial_pressure = 1e4\ninitial_saturation = 0.0"),
     "initial_saturation", "initial_pressure > 0 leaves none"),
    ("negative initial pressure", BASE.replace("viscosity = 1e-3", "viscosity = 1e-3\ninitial_pressure = -1e4"),
     "initial_pressure", ">= 0"),
    ("negative held pressure", BASE.replace("pressure = 1e5", "pressure = -1e5"), "pressure", ">= 0"),
    ("unknown fluid key", BASE.replace("viscosity = 1e-3", "viscosity = 1e-3\nporosity = 0.1"), "porosity", "unknown"),
    ("aperture without fluid", NO_FLUID.split("[[flow_boundary]]")[0], "aperture", "no [fluid] table"),
    ("flow boundary without fluid",
     NO_FLUID.replace("aperture = 1e-4\nresidual_aperture = 1e-5\n", ""), "flow_boundary", "needs a [fluid] table"),
    ("point permeability on a Coulomb joint", BASE.replace("aperture = 1e-4", "aperture = 1e-4\npoint_permeability = 1e-9"),
     "point_permeability", "point-contact joint law"),
    ("two conditions", BASE.replace("pressure = 1e5", "pressure = 1e5\ninflow = 1e-6"), "flow_boundary",
     "give one of pressure, water_table and inflow"),
    ("no condition", BASE.replace("pressure = 1e5\n", ""), "flow_boundary", "gives no condition"),
    ("inverted box", BASE.replace("box = [-0.1, -0.1, 0.05, 0.1]", "box = [0.05, -0.1, -0.1, 0.1]"), "box",
     "x_min <= x_max"),
    ("phase flow without fluid",
     NO_FLUID.replace("aperture = 1e-4\nresidual_aperture = 1e-5\n", "").split("[[flow_boundary]]")[0].replace(
         "[stop]\ncycles = 400\n", "") + "[[phase]]\nname = \"p\"\nstop = { cycles = 10 }\nflow = true\n",
     "flow", "needs a [fluid] table"),
]


@pytest.mark.requirements("REQ-FLOW-009")
@pytest.mark.parametrize("what, text, key, phrase", BAD, ids=[b[0] for b in BAD])
def test_bad_fluid_input_is_a_scene_error_naming_the_key(tmp_path, what, text, key, phrase):
    done, _ = run(tmp_path, text)
    assert done.returncode == 3, (what, done.stderr)
    assert key in done.stderr and phrase in done.stderr, (what, done.stderr)
    assert re.search(r"scene\.toml:\d+", done.stderr), ("the message names the file and line", done.stderr)


@pytest.mark.requirements("REQ-FLOW-008")
def test_an_explicit_fluid_step_beyond_the_limit_stops_the_run_naming_step_fraction(tmp_path):
    # Four domains along the joint, all gridpoints held, a 1 mm aperture and water's bulk modulus:
    # the fluid step of 1.4-11 is some 200 times shorter than the zones' step, so the sub-steps
    # run at the fraction given. The explicit update is stable up to about twice 1.4-11's bound
    # (Gershgorin's margin); at 3.9 times it the highest mode grows.
    held = BASE.replace("[[flow_boundary]]", "[[boundary]]\nblock = \"lower\"\nfix = [\"x\", \"y\"]\n"
                        "[[boundary]]\nblock = \"upper\"\nfix = [\"x\", \"y\"]\n[[flow_boundary]]")
    held = held.replace("aperture = 1e-4", "aperture = 1e-3").replace("bulk_modulus = 2e6", "bulk_modulus = 2e9")
    done, results = run(tmp_path, held.replace("viscosity = 1e-3", "viscosity = 1e-3\nstep_fraction = 3.9"),
                        "--set", "stop.cycles=20000")
    assert done.returncode == 5, done.stderr
    assert "fluid flow unstable" in done.stderr and "step_fraction" in done.stderr, done.stderr
    assert results is not None and results["run"]["exit_code"] == 5
    done, results = run(tmp_path, held.replace("viscosity = 1e-3", "viscosity = 1e-3\nstep_fraction = 1.0"),
                        "--set", "stop.cycles=20000", name="stable")
    assert done.returncode == 0, done.stderr
    assert max(results["domains"]["pressure"]) == pytest.approx(1e5, rel=1e-9)


PHASES = ("[[phase]]\nname = \"dry\"\nstop = { cycles = 150 }\n"
          "[[phase]]\nname = \"wet\"\nstop = { cycles = 200 }\nflow = true\n"
          "[[phase.flow_boundary]]\nname = \"far\"\nbox = [0.95, -0.1, 1.1, 0.1]\npressure = 5e4\n"
          "[[phase]]\nname = \"shut\"\nstop = { cycles = 150 }\nfree = [\"mouth\"]\n")


def phased():
    text = BASE.replace("[stop]\ncycles = 400\n", "").replace("viscosity = 1e-3", "viscosity = 1e-3\nflow = false")
    return text + PHASES


@pytest.mark.requirements("REQ-FLOW-006", "REQ-FLOW-010")
def test_a_phase_switches_the_flow_on_and_adds_and_frees_flow_boundaries(tmp_path):
    done, results = run(tmp_path, phased())
    assert done.returncode == 0, done.stderr
    fluid = results["fluid"]
    assert fluid["flowing"] is True
    # Fluid came in at the mouths while they were held, then the left mouth shut: the balance
    # closes, and no knot is held by the freed boundary.
    balance = fluid["balance"]
    assert balance["inflow"] > 0
    assert abs(balance["imbalance"]) <= 1e-12 * (balance["inflow"] + balance["initial_content"])
    assert "mouth" not in results["knots"]["boundary"] and "far" in results["knots"]["boundary"]
    dry, _ = run(tmp_path, phased().split("[[phase]]\nname = \"wet\"")[0], name="dry")
    assert dry.returncode == 0, dry.stderr


@pytest.mark.requirements("REQ-FLOW-006", "REQ-RUN-005")
def test_a_run_restarted_after_the_flow_came_on_is_the_run_that_did_not_stop(tmp_path):
    done, whole = run(tmp_path, phased(), "--save", "wet", name="whole")
    assert done.returncode == 0, done.stderr
    state = tmp_path / "whole-out" / "after-phase-2.vdecstate"
    scene = tmp_path / "whole.toml"
    resumed = subprocess.run([VDEC, "run", str(scene), "--out", str(tmp_path / "resumed"), "--restart", str(state)],
                             capture_output=True, text=True, timeout=120)
    assert resumed.returncode == 0, resumed.stderr
    again = json.loads((tmp_path / "resumed" / "results.json").read_text())
    for key in ("domains", "knots", "fluid", "gridpoints", "contacts", "energy"):
        assert again[key] == whole[key], key


@pytest.mark.requirements("REQ-FLOW-001")
def test_fluid_results_do_not_depend_on_the_thread_count(tmp_path):
    one, a = run(tmp_path, BASE, "--threads", "1", name="one")
    two, b = run(tmp_path, BASE, "--threads", "2", name="two")
    assert one.returncode == 0 and two.returncode == 0, (one.stderr, two.stderr)
    for key in ("domains", "knots", "fluid", "gridpoints"):
        assert a[key] == b[key], key


HISTORIES = """
[[history]]
name = "p"
quantity = "domain.pressure"
point = [0.9, 0.0]
every = 100
[[history]]
name = "q"
quantity = "knot.flow"
point = [0.0, 0.0]
every = 100
[[history]]
name = "a"
quantity = "knot.aperture"
point = [0.5, 0.0]
every = 100
[[history]]
name = "in"
quantity = "fluid.inflow"
every = 100
[[history]]
name = "out"
quantity = "fluid.outflow"
every = 100
[[history]]
name = "content"
quantity = "fluid.content"
every = 100
[[history]]
name = "balance"
quantity = "fluid.imbalance"
every = 100
"""


@pytest.mark.requirements("REQ-FLOW-010")
def test_fluid_histories_sample_the_domain_and_knot_nearest_their_point_and_the_account(tmp_path):
    done, results = run(tmp_path, BASE + HISTORIES)
    assert done.returncode == 0, done.stderr
    h = {name: series["value"] for name, series in results["histories"].items()}
    assert all(len(v) == 5 for v in h.values()), "cycles 0, 100, ..., 400"
    domains, knots, balance = results["domains"], results["knots"], results["fluid"]["balance"]

    def nearest(table, x, y):
        return min(range(len(table["x0"])), key=lambda i: (table["x0"][i] - x) ** 2 + (table["y0"][i] - y) ** 2)

    assert h["p"][-1] == domains["pressure"][nearest(domains, 0.9, 0.0)]
    assert h["q"][-1] == knots["flow"][nearest(knots, 0.0, 0.0)]
    assert h["a"][-1] == knots["aperture"][nearest(knots, 0.5, 0.0)]
    assert h["in"][-1] == balance["inflow"] and h["out"][-1] == balance["outflow"]
    assert h["content"][-1] == balance["content"] and h["content"][0] == balance["initial_content"]
    assert h["q"][-1] > 0, "the fluid comes in at the held mouth"
    scale = balance["inflow"] + balance["initial_content"]
    assert max(abs(v) for v in h["balance"]) <= 1e-12 * scale


@pytest.mark.requirements("REQ-FLOW-009")
def test_fluid_histories_need_fluid_and_a_point(tmp_path):
    done, _ = run(tmp_path, NO_FLUID.split("[[flow_boundary]]")[0].replace("aperture = 1e-4\nresidual_aperture = 1e-5\n", "")
                  + "[[history]]\nname = \"p\"\nquantity = \"domain.pressure\"\npoint = [0.5, 0.0]\n")
    assert done.returncode == 3 and "domain.pressure is a fluid-flow quantity" in done.stderr, done.stderr
    done, _ = run(tmp_path, BASE + "[[history]]\nname = \"p\"\nquantity = \"knot.flow\"\n", name="nopoint")
    assert done.returncode == 3 and "point" in done.stderr, done.stderr


@pytest.mark.requirements("REQ-FLOW-010")
def test_vtk_snapshots_hold_the_domains_and_knots_of_results_json(tmp_path):
    import xml.etree.ElementTree as ET
    done, results = run(tmp_path, BASE + "\n[output]\nvtk_every = 400\n")
    assert done.returncode == 0, done.stderr
    vtk = tmp_path / "scene-out" / "vtk"
    last = sorted(vtk.glob("snapshot_*.vtu"))[-1]
    piece = ET.parse(last).getroot().find("UnstructuredGrid/Piece")
    arrays = {a.get("Name"): [float(x) for x in (a.text or "").split()] for a in piece.iter("DataArray")}
    kind_name = next(name for name in arrays if name.startswith("kind"))
    kind = arrays[kind_name]
    assert "3 fluid domain" in kind_name and "4 flow knot" in kind_name
    assert len(arrays["pressure"]) == len(kind) == int(piece.get("NumberOfCells"))
    domains = [i for i, k in enumerate(kind) if k == 3]
    knots = [i for i, k in enumerate(kind) if k == 4]
    assert [arrays["pressure"][i] for i in domains] == results["domains"]["pressure"]
    assert [arrays["domain_area"][i] for i in domains] == results["domains"]["area"]
    assert [arrays["flow"][i] for i in knots] == results["knots"]["flow"]
    assert [arrays["aperture"][i] for i in knots] == results["knots"]["aperture"]


SEALED = """
[model]
rounding = 0.01
[stop]
time = 0.05
[fluid]
bulk_modulus = 2e9
viscosity = 1e-3
[[joint_material]]
name = "j"
kn = 1e10
ks = 1e10
friction = 30.0
aperture = 1e-4
residual_aperture = 1e-5
[[block_material]]
name = "rock"
density = 2500.0
[[block]]
name = "lower"
material = "rock"
vertices = [[0.0, -1.0], [2.0, -1.0], [2.0, 0.0], [0.0, 0.0]]
fix = ["x", "y", "rotation"]
[[block]]
name = "upper"
material = "rock"
vertices = [[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]]
fix = ["x", "y", "rotation"]
[[flow_boundary]]
name = "well"
box = [0.5, -0.1, 1.5, 0.1]
inflow = 1e-7
"""


@pytest.mark.requirements("REQ-FLOW-006", "REQ-FLOW-003")
def test_an_inflow_into_a_sealed_joint_raises_its_pressure_as_kw_q_t_over_its_volume(tmp_path):
    # One domain (the joint between two held blocks, L a0 = 2e-4 m^2), both mouths impermeable:
    # content A + Q t, pressure K_w Q t / A, exactly linear in time.
    done, results = run(tmp_path, SEALED)
    assert done.returncode == 0, done.stderr
    t = results["run"]["time"]
    (area,), (pressure,) = results["domains"]["area"], results["domains"]["pressure"]
    assert area == pytest.approx(2.0 * 1e-4, rel=1e-12, abs=0)
    # Round-off: the content A (1 + p / K_w) carries p to K_w eps a step, over the run's steps.
    steps = results["run"]["cycles"]
    assert pressure == pytest.approx(2e9 * 1e-7 * t / area, rel=0, abs=2e9 * 2.2e-16 * steps)
    balance = results["fluid"]["balance"]
    assert balance["inflow"] == pytest.approx(1e-7 * t, rel=1e-12, abs=0) and balance["outflow"] == 0.0
    # A history scales the rate: a linear ramp f = t / (1 s) gives content A + Q t^2 / 2.
    ramp = SEALED.replace("inflow = 1e-7\n", "inflow = 1e-7\nhistory = { kind = \"linear\", start = 0.0, rate = 1.0 }\n")
    done, results = run(tmp_path, ramp, name="ramp")
    assert done.returncode == 0, done.stderr
    t = results["run"]["time"]
    assert results["fluid"]["balance"]["inflow"] == pytest.approx(1e-7 * t * t / 2, rel=2.0 * results["run"]["dt"] / t, abs=0)


FOUR_HELD_BLOCKS = """
[model]
rounding = 0.01
gravity = [0.0, -9.81]
[stop]
cycles = 200
[[block_material]]
name = "rock"
density = 2650.0
[[joint_material]]
name = "joint"
kn = 1e10
ks = 1e10
friction = 30.0
aperture = 1e-4
residual_aperture = 1e-5
[fluid]
bulk_modulus = 2e9
viscosity = 1e-3
scheme = "steady"
""" + "".join(
    f"[[block]]\nname = \"{n}\"\nmaterial = \"rock\"\nvertices = [[{x}, {y}], [{x + 1}, {y}], [{x + 1}, {y + 1}], "
    f"[{x}, {y + 1}]]\nfix = [\"x\", \"y\", \"rotation\"]\n"
    for n, x, y in (("a", 0.0, -1.0), ("b", 1.0, -1.0), ("c", 0.0, 0.0), ("d", 1.0, 0.0)))


@pytest.mark.requirements("REQ-FLOW-003", "REQ-FLOW-005")
def test_the_steady_scheme_brings_a_network_no_held_pressure_reaches_to_rest_holding_its_fluid(tmp_path):
    # Four held blocks, no flow boundary: the joints start full at zero pressure and, under
    # gravity, come to rest holding the fluid they had, filled from the bottom up: the full
    # domains at one piezometric pressure p + rho_w g y, the top one (whose fluid the compression
    # of those below took) partly saturated at zero pressure, no suction (no blow-up either).
    done, results = run(tmp_path, FOUR_HELD_BLOCKS)
    assert done.returncode == 0, done.stderr
    d = results["domains"]
    top = max(range(len(d["y0"])), key=lambda i: d["y0"][i])
    full = [i for i in range(len(d["y0"])) if i != top]
    assert all(d["saturation"][i] == 1.0 for i in full) and 0.99 < d["saturation"][top] < 1.0, d
    assert d["pressure"][top] == 0.0 and min(d["pressure"]) >= 0.0, d
    head = [d["pressure"][i] + 1000.0 * 9.81 * d["y0"][i] for i in full + [top]]
    assert max(head) - min(head) <= 1e-9 * max(d["pressure"])
    assert max(d["pressure"]) == pytest.approx(1000.0 * 9.81 * 1.01, rel=1e-9, abs=0)
    balance = results["fluid"]["balance"]
    assert abs(balance["imbalance"]) <= 1e-15 * balance["initial_content"]
    assert all(q == 0.0 for q in results["knots"]["flow"])


HELD = BASE.replace("[[flow_boundary]]", "[[boundary]]\nblock = \"lower\"\nfix = [\"x\", \"y\"]\n"
                    "[[boundary]]\nblock = \"upper\"\nfix = [\"x\", \"y\"]\n[[flow_boundary]]")


@pytest.mark.requirements("REQ-FLOW-011")
def test_a_dry_joint_fills_from_its_mouth_with_the_domains_ahead_of_the_front_dry_at_zero_pressure(tmp_path):
    # The fixture's joint (four domains of 0.25 m) held still and dry at the start; its left mouth
    # at 1e5 Pa. Density scaling makes the step 1 s (nothing moves); after 2 s the front is in the
    # third domain.
    held = HELD.replace("adaptive_damping = true", "density_scaling = true")
    dry = held.replace("viscosity = 1e-3", "viscosity = 1e-3\ninitial_saturation = 0.0")
    done, results = run(tmp_path, dry, "--set", "stop.cycles=2")
    assert done.returncode == 0, done.stderr
    d = results["domains"]
    order = sorted(range(len(d["x0"])), key=lambda i: d["x0"][i])
    saturation = [d["saturation"][i] for i in order]
    pressure = [d["pressure"][i] for i in order]
    assert saturation[0] == 1.0 and pressure[0] > 0.0, (saturation, pressure)
    assert saturation[-1] == 0.0 and d["content"][order[-1]] == 0.0, saturation
    assert all(p == 0.0 for p, s in zip(pressure, saturation) if s < 1.0), (saturation, pressure)
    assert saturation == sorted(saturation, reverse=True), "the front advances from the mouth"
    # Behind the front the flow is steady (the full domains' storage is a / K_w): the pressure falls
    # linearly from the mouth to zero at the centre of the filling domain, 0.625 m along the knots.
    filling = saturation.index(next(x for x in saturation if x < 1.0))
    assert filling == 2, saturation
    assert pressure[:2] == pytest.approx([1e5 * 0.5 / 0.625, 1e5 * 0.25 / 0.625], rel=1e-6, abs=0)
    assert abs(results["fluid"]["balance"]["imbalance"]) <= 1e-12 * results["fluid"]["balance"]["inflow"]
    # Fully saturated at the start (the default), the same joint takes in only the compression.
    done, full = run(tmp_path, held, "--set", "stop.cycles=2", name="full")
    assert min(full["domains"]["saturation"]) == 1.0
    assert full["fluid"]["balance"]["inflow"] < 0.1 * results["fluid"]["balance"]["inflow"]


VERTICAL = """[model]
gravity = [0.0, -9.81]
rounding = 0.01
[solver]
density_scaling = true
[stop]
cycles = 100
[fluid]
bulk_modulus = 2e6
viscosity = 1e-3
[[joint_material]]
name = "j"
kn = 1e10
ks = 1e10
friction = 30.0
aperture = 1e-4
residual_aperture = 1e-5
[[block_material]]
name = "rock"
density = 2500.0
young = 10e9
poisson = 0.25
[[block]]
name = "left"
material = "rock"
vertices = [[-1.0, 0.0], [0.0, 0.0], [0.0, 1.0], [-1.0, 1.0]]
zoning = { nx = 1, ny = 4 }
[[block]]
name = "right"
material = "rock"
vertices = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
zoning = { nx = 1, ny = 4 }
[[boundary]]
block = "left"
fix = ["x", "y"]
[[boundary]]
block = "right"
fix = ["x", "y"]
[[flow_boundary]]
name = "bottom"
box = [-0.1, -0.1, 0.1, 0.05]
pressure = 0.0
[[history]]
name = "top"
quantity = "domain.pressure"
point = [0.0, 0.875]
"""


@pytest.mark.requirements("REQ-FLOW-011")
def test_a_vertical_joint_drains_through_its_bottom_mouth_and_its_top_domains_empty_without_suction(tmp_path):
    # A vertical joint between held blocks, four domains of 0.25 m, full at zero pressure; under
    # gravity the water leaves through the bottom mouth (held at 0). The domains drain from the
    # top: none holds less than nothing, none takes a suction.
    done, results = run(tmp_path, VERTICAL)
    assert done.returncode == 0, done.stderr
    d = results["domains"]
    assert len(d["x0"]) == 4, d
    order = sorted(range(4), key=lambda i: d["y0"][i])
    saturation = [d["saturation"][i] for i in order]
    assert saturation[-1] == 0.0 and saturation == sorted(saturation, reverse=True), saturation
    assert min(d["content"]) >= 0.0 and min(d["pressure"]) >= 0.0, d
    assert min(results["histories"]["top"]["value"]) >= 0.0
    balance = results["fluid"]["balance"]
    assert balance["outflow"] > 0.5 * balance["initial_content"], balance
    # The drained domains passed on what they held, not more: no content made up for them.
    assert balance["created"] <= 1e-15 * balance["initial_content"], balance
    assert abs(balance["imbalance"]) <= 1e-12 * balance["initial_content"], balance

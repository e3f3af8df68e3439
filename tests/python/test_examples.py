"""The worked examples (examples/*/scene.toml) run, at the reduced size each README names, and give
results consistent with the hand checks their READMEs work out."""
import json
import math
import re
import subprocess

import numpy as np
import pytest

from analytic import elastic, heat
from scene_runs import ROOT, VDEC, needs_vdec

EXAMPLES = ROOT / "examples"
YEAR = 3.15576e7
pytestmark = [needs_vdec, pytest.mark.requirements("REQ-QA-017")]


def run_example(tmp_path, name, *overrides):
    """vdec run examples/NAME/scene.toml with the --set overrides: results.json, after checking the exit code."""
    out = tmp_path / name
    args = [arg for override in overrides for arg in ("--set", override)]
    done = subprocess.run([VDEC, "run", str(EXAMPLES / name / "scene.toml"), "--out", str(out), *args],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return json.loads((out / "results.json").read_text())


def last(results, history):
    return results["histories"][history]["value"][-1]


def phases_at_equilibrium(results, names):
    assert [phase["name"] for phase in results["phases"]] == names
    assert all(phase["stop_reason"] == "ratio" for phase in results["phases"])


def test_jointed_tunnel_converges_inwards_with_kirsch_stress_at_the_wall_and_yield_at_the_crown(tmp_path):
    r = run_example(tmp_path, "jointed-tunnel", "phase[0].stop.ratio=1e-4", "phase[1].stop.ratio=1e-4")
    phases_at_equilibrium(r, ["in-situ", "excavate"])
    S_x, S_y, a, E, nu = -7.5e6, -5.0e6, 2.0, 20e9, 0.25
    wall_ux, _ = elastic.kirsch_excavation_displacement(x=a, y=0.0, a=a, S_x=S_x, S_y=S_y, E=E, nu=nu)
    _, crown_uy = elastic.kirsch_excavation_displacement(x=0.0, y=a, a=a, S_x=S_x, S_y=S_y, E=E, nu=nu)
    convergence = last(r, "wall_east_ux") - last(r, "wall_west_ux")
    # closing, smaller than the elastic plane's 2.2 mm: the rigid jointed far field is stiffer
    assert 0.3 < convergence / (2.0 * float(wall_ux)) < 1.0
    assert 0.3 < last(r, "crown_uy") / float(crown_uy) < 1.0
    # springline: elastic, Kirsch's tangential stress at the history's zone (centroid at r = 2.11 m)
    stt = elastic.kirsch(r=2.11, theta=0.0, a=a, S_x=S_x, S_y=S_y)["stt"]
    assert last(r, "wall_syy") == pytest.approx(float(stt), rel=0.25)
    # crown: Kirsch's elastic 16.1 MPa exceeds the unconfined strength 2 c cos(phi) / (1 - sin(phi)) =
    # 11.5 MPa; the zones round the crown have yielded, and no zone lies outside the Mohr-Coulomb surface
    phi, c = math.radians(35.0), 3e6
    ucs = 2.0 * c * math.cos(phi) / (1.0 - math.sin(phi))
    assert -last(r, "crown_sxx") < ucs
    zones = r["zones"]
    yielded = np.array(zones["plastic_state"]) > 0
    angle = np.degrees(np.arctan2(np.array(zones["y0"])[yielded], np.array(zones["x0"])[yielded]))
    assert np.any(np.abs(angle - 90.0) < 15.0)
    sxx, syy, sxy, szz = (-np.array(zones[k]) for k in ("sxx", "syy", "sxy", "szz"))
    centre, radius = 0.5 * (sxx + syy), np.hypot(0.5 * (sxx - syy), sxy)
    principal = np.sort(np.stack([centre + radius, centre - radius, szz]), axis=0)
    kp = (1.0 + math.sin(phi)) / (1.0 - math.sin(phi))
    assert np.max(principal[2] - kp * principal[0] - ucs) < 0.01 * ucs


def test_rock_slope_slider_follows_the_incline_law_column_topples_stable_block_stays(tmp_path):
    r = run_example(tmp_path, "rock-slope", "stop.time=0.6")
    t = r["run"]["time"]
    alpha, phi = math.radians(35.0), math.radians(25.0)
    along = 0.5 * 9.81 * (math.sin(alpha) - math.cos(alpha) * math.tan(phi)) * t * t
    moved = math.hypot(last(r, "slider_ux"), last(r, "slider_uy"))
    assert moved == pytest.approx(along, rel=0.03)
    assert last(r, "slider_ux") < 0.0 and last(r, "slider_uy") < 0.0
    assert last(r, "column_rotation") > 0.2
    assert max(abs(v) for v in r["histories"]["column_slip"]["value"]) < 1e-3
    assert abs(last(r, "stable_ux")) < 1e-5


def test_bolted_wedge_hangs_on_bolts_that_carry_its_weight(tmp_path):
    r = run_example(tmp_path, "bolted-wedge", "stop.ratio=1e-5")
    weight = 2600.0 * 9.81 * 3.0
    assert last(r, "west_axial") + last(r, "east_axial") == pytest.approx(weight, rel=5e-3)
    assert -1e-3 < last(r, "wedge_uy") < 0.0
    assert abs(last(r, "west_shear")) < 1e-3 * weight


def test_heated_drift_wall_temperature_follows_the_decaying_line_source_and_hoop_stress_rises(tmp_path):
    r = run_example(tmp_path, "heated-drift")
    phases_at_equilibrium(r, ["excavated", "1-year", "3-years", "10-years", "30-years", "100-years"])
    years = np.array([1.0, 3.0, 10.0, 30.0, 100.0])
    kappa = 3.0 / 2.6e6
    wall, at_10m = (heat.decaying_line_source_temperature(r=np.array([radius]), t=years * YEAR,
                                                           q=[700.0, 300.0], tau=[30 * YEAR, 300 * YEAR],
                                                           k=3.0, kappa=kappa, T0=25.0)
                    for radius in (2.5, 12.5))
    # one sample per phase, the first at the start; the phases' temperatures are the 2nd to 6th
    assert np.array(r["histories"]["wall_T"]["value"][2:]) == pytest.approx(wall, rel=0.05)
    assert np.array(r["histories"]["T_at_10m"]["value"][2:]) == pytest.approx(at_10m, rel=0.1)
    hoop = -np.array(r["histories"]["crown_hoop"]["value"])
    kirsch = -elastic.kirsch(r=2.6, theta=math.pi / 2, a=2.5, S_x=-12e6, S_y=-10.4e6)["stt"]
    assert hoop[0] == pytest.approx(float(kirsch), rel=0.1)
    restrained = 40e9 * 8e-6 / 0.75 * (wall[2] - 25.0)
    assert 0.5 * restrained < hoop[3] - hoop[0] < restrained
    assert abs(last(r, "wall_ux")) < 1e-3


def test_grouted_joint_front_stops_at_the_bingham_reach(tmp_path):
    r = run_example(tmp_path, "grouted-joint", "stop.time=2400.0")
    reach = 3e5 * 1e-4 / (2.0 * 10.0)
    domains = r["domains"]
    filled = np.array(domains["x0"])[np.array(domains["saturation"]) > 0.5]
    assert 0.9 * reach < filled.max() < reach
    assert last(r, "grout_take") == pytest.approx(reach * 1e-4, rel=0.05)
    assert abs(last(r, "imbalance")) < 1e-12


def test_dam_foundation_uplift_near_linear_and_sliding_margin_reduced_by_it(tmp_path):
    r = run_example(tmp_path, "dam-foundation")
    phases_at_equilibrium(r, ["dry", "impound"])
    weight = 2400.0 * 9.81 * 20.0 * 25.0 / 2.0
    thrust = 0.5 * 1000.0 * 9.81 * 24.0 ** 2
    linear_uplift = 0.5 * 1000.0 * 9.81 * 24.0 * 20.0
    base = [c for c in r["contacts"] if "dam" in (c["block_a"], c["block_b"])]
    normal = sum(c["normal_force"] * abs(c["normal"][1]) for c in base)
    shear = sum(c["shear_force"] * c["normal"][1] for c in base)
    assert abs(shear) == pytest.approx(thrust, rel=0.01)
    assert weight - normal == pytest.approx(linear_uplift, rel=0.15)
    margin = normal * math.tan(math.radians(45.0)) / thrust
    assert 1.0 < margin < weight / thrust
    assert last(r, "p_heel") == pytest.approx(1000.0 * 9.81 * 24.0 * (1.0 - 2.5 / 20.0), rel=0.05)
    assert last(r, "p_heel") > last(r, "p_middle") > last(r, "p_toe") > 0.0
    assert 0.0 < last(r, "dam_ux") < 1e-3


def test_tutorial_scene_excavates_the_drift_and_its_roof_and_walls_move_in(tmp_path):
    r = run_example(tmp_path, "tutorial", "block[0].zoning.nx=16", "block[0].zoning.ny=16")
    phases_at_equilibrium(r, ["in-situ", "excavate"])
    assert len(r["zones"]["x0"]) == 4 * 16 * 16 - 4 * 8 * 8
    assert last(r, "roof_uy") < 0.0
    assert last(r, "wall_ux") < 0.0
    assert last(r, "ratio") < 1e-3


def test_tutorial_fragments_in_order_make_the_tutorial_scene():
    tutorial = (ROOT / "docs" / "user-manual" / "tutorial.md").read_text()
    fragments = re.findall(r"```toml\n(.*?)```", tutorial, flags=re.S)
    assert "\n".join(fragments) == (EXAMPLES / "tutorial" / "scene.toml").read_text()

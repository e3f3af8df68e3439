"""FL-NETWORK's code-to-code check: vdec's steady flow through a seeded random joint network
(verification/problems/FL-NETWORK/scene.toml) against an independent steady solve of the same
network in Python (scipy sparse, verification/analytic/fracture_flow.steady_network_flow), built
only from what vdec reports in results.json: the domains (which are held, and at what pressure)
and the knots (the two domains each joins, its hydraulic aperture and length, and for a mouth
the name of the flow boundary that holds it, whose pressure is read from the scene).

This is a code-to-code comparison, not a closed form: it shows that vdec solves the network it
reports (each free domain's balance under the cubic law, REQ-FLOW-001, -002, and the steady
scheme with its mass balance, REQ-FLOW-003); whether that network is the right one for the
blocks is shown by the closed-form problems (FL-CUBIC-LAW, FL-DIFFUSION, FL-DEFORMABLE-JOINT).

Tolerances. Both sides solve the same linear system K p = b in double precision (vdec with
Eigen's sparse LDLT, the reference with SuperLU), so they differ by the solves' rounding,
bounded by cond(K) eps relative to the pressure scale; the test computes cond(K) (a dense
estimate: the system has under a hundred unknowns) and allows 10 cond(K) eps, and the
conductances themselves by the rounding of a^3 / (12 mu l) (a few eps, far below that).
"""
import json
import os
import subprocess
import tomllib
from pathlib import Path

import numpy as np
import pytest

from analytic.fracture_flow import steady_network_flow

ROOT = Path(__file__).resolve().parents[2]
VDEC = os.environ.get("VDEC_EXECUTABLE", str(ROOT / "build" / "vdec"))
PROBLEM = ROOT / "verification" / "problems" / "FL-NETWORK"
pytestmark = pytest.mark.skipif(not Path(VDEC).is_file(), reason="vdec is not built")
EPS = np.finfo(float).eps


@pytest.fixture(scope="module")
def solved(tmp_path_factory):
    out = tmp_path_factory.mktemp("fl-network")
    done = subprocess.run([VDEC, "run", str(PROBLEM / "scene.toml"), "--out", str(out)], capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    results = json.loads((out / "results.json").read_text())
    scene = tomllib.loads((PROBLEM / "scene.toml").read_text())
    net, knots = network(results, scene)
    viscosity = scene["fluid"]["viscosity"]
    reference = steady_network_flow(viscosity=viscosity, **net)
    # both solves' rounding: 10 cond(K) eps of the pressure scale (module docstring)
    tolerance = 10.0 * condition(net, viscosity) * EPS
    return results, net, knots, reference, tolerance


def network(results, scene):
    """The reference's input from results.json: domains (vdec's, then one held node per held
    mouth knot) and links (every knot with a domain or a held mouth on both sides), and the
    domains that reach a held pressure (vdec leaves the others' pressures as they were)."""
    held = {b["name"]: b["pressure"] for b in scene["flow_boundary"]}
    dom, kn = results["domains"], results["knots"]
    count = len(dom["pressure"])
    ids = list(range(count))
    fixed = [bool(f) for f in dom["fixed"]]
    fixed_pressure = [p if f else 0.0 for p, f in zip(dom["pressure"], fixed)]
    link_from, link_to, aperture, length, knots = [], [], [], [], []
    for k in range(len(kn["aperture"])):
        ends = []
        for side in ("domain_0", "domain_1"):
            d = kn[side][k]
            if d >= 0:
                ends.append(d)
            elif kn["boundary"][k]:
                ends.append(f"mouth {k}")
                ids.append(f"mouth {k}")
                fixed.append(True)
                fixed_pressure.append(held[kn["boundary"][k]])
            else:
                ends = None  # a mouth no boundary holds: impermeable
                break
        if ends is None:
            continue
        link_from.append(ends[0])
        link_to.append(ends[1])
        aperture.append(kn["aperture"][k])
        length.append(kn["length"][k])
        knots.append(k)
    # Domains joined through links to a held node: the rest have no steady pressure.
    index = {d: i for i, d in enumerate(ids)}
    reached = [f for f in fixed]
    changed = True
    while changed:
        changed = False
        for a, b in zip(link_from, link_to):
            if reached[index[a]] != reached[index[b]]:
                reached[index[a]] = reached[index[b]] = True
                changed = True
    keep = [d for d in ids if reached[index[d]]]
    links = [i for i in range(len(knots)) if reached[index[link_from[i]]]]
    return dict(domain_ids=keep, fixed=[fixed[index[d]] for d in keep],
                fixed_pressure=[fixed_pressure[index[d]] for d in keep],
                link_from=[link_from[i] for i in links], link_to=[link_to[i] for i in links],
                aperture=[aperture[i] for i in links], length=[length[i] for i in links]), [knots[i] for i in links]


def condition(net, viscosity):
    """cond(K) (2-norm) of the free domains' block of the weighted graph Laplacian."""
    ids = net["domain_ids"]
    free = [d for d, f in zip(ids, net["fixed"]) if not f]
    where = {d: i for i, d in enumerate(free)}
    K = np.zeros((len(free), len(free)))
    for a, b, ap, ln in zip(net["link_from"], net["link_to"], net["aperture"], net["length"]):
        c = ap ** 3 / (12.0 * viscosity * ln)
        for u, v in ((a, b), (b, a)):
            if u in where:
                K[where[u], where[u]] += c
                if v in where:
                    K[where[u], where[v]] -= c
    return np.linalg.cond(K)


@pytest.mark.requirements("REQ-FLOW-001", "REQ-FLOW-003")
def test_every_domain_pressure_and_knot_flow_is_the_independent_steady_solve(solved):
    results, net, knots, reference, tolerance = solved
    count = len(results["domains"]["pressure"])
    domains = [i for i, d in enumerate(net["domain_ids"]) if isinstance(d, int)]
    assert len(domains) == count, "every domain of this network reaches a held pressure"
    vdec_pressure = np.array([results["domains"]["pressure"][net["domain_ids"][i]] for i in domains])
    scale = max(abs(p) for p in net["fixed_pressure"])
    error = np.max(np.abs(vdec_pressure - reference["pressure"][domains])) / scale
    assert error <= tolerance, f"largest pressure difference {error:.3e} of the held pressure (tolerance {tolerance:.3e})"
    flow = np.array([results["knots"]["flow"][k] for k in knots])
    flow_error = np.max(np.abs(flow - reference["link_flow"])) / np.max(np.abs(reference["link_flow"]))
    assert flow_error <= tolerance, f"largest knot flow difference {flow_error:.3e} of the largest (tolerance {tolerance:.3e})"


@pytest.mark.requirements("REQ-FLOW-001", "REQ-FLOW-003")
def test_the_total_flow_is_the_independent_solve_and_the_balance_closes(solved):
    results, net, knots, reference, tolerance = solved
    held = np.array(net["fixed_pressure"])
    high = np.array(net["fixed"]) & (held == held.max())
    total = float(np.sum(reference["boundary_inflow"][high]))
    # vdec's flow out of the nodes held at the high pressure, through the knots that leave them
    ids = net["domain_ids"]
    is_high = {d: bool(h) for d, h in zip(ids, high)}
    vdec_total = 0.0
    for a, b, k in zip(net["link_from"], net["link_to"], knots):
        q = results["knots"]["flow"][k]
        if is_high[a] and not is_high[b]:
            vdec_total += q
        elif is_high[b] and not is_high[a]:
            vdec_total -= q
    assert total > 0.0
    assert abs(vdec_total - total) <= tolerance * total, f"vdec {vdec_total!r}, reference {total!r}"
    # the reference's own balance: what enters at the high side leaves at the low side
    low = np.array(net["fixed"]) & ~high
    assert float(np.sum(reference["boundary_inflow"][low])) == pytest.approx(-total, rel=tolerance, abs=0)
    # vdec's account closes to the rounding of the contents it sums (88 domains, about 1.6e-3 m^2
    # in all; each sum rounds by eps / 2 of the total per term, a random walk of sqrt(88) terms
    # over the two steps: under 10 eps of the content)
    balance = results["fluid"]["balance"]
    assert abs(balance["imbalance"]) <= 10.0 * EPS * balance["content"]


# Yield stresses for which the network has many, some and few flowing knots (66, 25 and 4 of 104).
BINGHAM = [0.3, 3.0, 5.0]


@pytest.mark.requirements("REQ-FLOW-003", "REQ-FLOW-007")
@pytest.mark.parametrize("yield_stress", BINGHAM)
def test_a_bingham_fluids_steady_knot_flows_are_the_independent_solve(tmp_path, yield_stress):
    # The same network with a Bingham fluid (the linear law) under the steady scheme: vdec's damped
    # Newton iteration against the reference's (steady_network_flow). The flows are unique, the
    # pressures of domains no flowing knot joins to a held one are not, so the flows are compared.
    # Both balance every free domain to the rounding of its flows, which is set by the largest
    # conductance times the pressures (C_max P eps, a few 1e-15 m^2/s here) and spreads through
    # the solve by at most cond(K): the Newtonian tolerance, taken of the Newtonian network's
    # largest flow, bounds it.
    done = subprocess.run([VDEC, "run", str(PROBLEM / "scene.toml"), "--out", str(tmp_path),
                           "--set", f"fluid.yield_stress={yield_stress}"], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    results = json.loads((tmp_path / "results.json").read_text())
    scene = tomllib.loads((PROBLEM / "scene.toml").read_text())
    net, knots = network(results, scene)
    viscosity = scene["fluid"]["viscosity"]
    reference = steady_network_flow(viscosity=viscosity, yield_stress=yield_stress, **net)
    newtonian = steady_network_flow(viscosity=viscosity, **net)
    tolerance = 10.0 * condition(net, viscosity) * EPS * np.max(np.abs(newtonian["link_flow"]))
    # The reference's own balance (its iteration once accepted a set that left a domain unbalanced)
    index = {d: i for i, d in enumerate(net["domain_ids"])}
    out_of = np.zeros(len(index))
    for a, b, q in zip(net["link_from"], net["link_to"], reference["link_flow"]):
        out_of[index[a]] += q
        out_of[index[b]] -= q
    assert np.max(np.abs(out_of[~np.array(net["fixed"])])) <= tolerance
    flow = np.array([results["knots"]["flow"][k] for k in knots])
    assert np.max(np.abs(flow - reference["link_flow"])) <= tolerance
    assert np.count_nonzero(np.abs(reference["link_flow"]) > tolerance) == np.count_nonzero(np.abs(flow) > tolerance)
    assert results["fluid"]["solve_iterations_last_step"] >= 1
    balance = results["fluid"]["balance"]
    assert abs(balance["imbalance"]) <= 10.0 * EPS * balance["content"]

"""Extractors for deformable blocks: fields over zones or gridpoints, their means, and
quantities derived from extracted values by an inversion formula.

results.json holds, for deformable blocks, columns "zones" {block, x0, y0, area, sxx, syy,
sxy, szz} (positions are the initial zone centroids) and "gridpoints" {block, x0, y0,
displacement_x, displacement_y, ...} (initial positions).

    kind        keys (optional in brackets)                           returns
    field       of, quantity [block] [centre] [x] [y] [r] [angle]      Series over the selected zones or
                [abscissa]                                             gridpoints; the reference is called
                                                                       with their coordinates as keywords
                                                                       (x, y, r, theta: whichever it takes)
    field_mean  of, quantity [block] [centre] [x] [y] [r] [angle]      mean (area-weighted for zones)
    field_peak  of, quantity [block] [centre] [x] [y] [r] [angle]      the value of largest magnitude (a
                                                                       stress concentration's peak)
    field_extent of, quantity [block] [centre] [x] [y] [r] [angle]     the largest radius (about centre) of
                                                                       the samples where the quantity is not
                                                                       zero: e.g. of quantity "plastic", the
                                                                       plastic zone's reach
    derived     function, inputs [params] [component]                 function(**inputs, **params) of the
                                                                       analytic package, inputs being other
                                                                       extract tables: a quantity the run
                                                                       measures only through a formula (E
                                                                       and nu from strains); an input with
                                                                       variant = NAME reads that run of the
                                                                       problem ("" the plain run): a ratio
                                                                       of two runs' cycles

of = "domains" (pressure, area, content; at the domains' present centres) and "knots" (flow,
aperture, length, conductance; at their present points; block selects the knot's block A) for
fracture flow.
of = "zones" (quantities sxx, syy, sxy, szz and, about `centre`, srr, stt, srt), "gridpoints"
(ux, uy, temperature with [heat], and, about `centre`, ur, ut) or "contacts" (sn, the normal stress, compression positive,
and tau, the shear stress: force over contact length; the closed contacts, at their present
points; block selects block A, the side of the contact's corner). Selection ranges on the initial position: x, y, r (about
centre) = [low, high]; angle = [low, high] in degrees about centre. The abscissa (for plots and
the trapezoid weights of a gridpoint L2 norm) is r when a polar quantity or range is used,
else x. Zones weight the L2 norm by their areas.
"""
import math

import numpy as np

def ratio(*, numerator, denominator, scale=1.0):
    """scale x numerator / denominator: e.g. the cycles of one run over another's, or a ratio of
    two displacement rates turned into the ratio of the strain rates (scale = the lengths'
    ratio)."""
    return scale * numerator / denominator


def difference(*, minuend, subtrahend):
    """minuend - subtrahend: e.g. the settlement of one surface point relative to another, the
    quantity a half-plane defines in 2D where each alone is not."""
    return minuend - subtrahend


# Arithmetic a derived extract may use besides the analytic package's inversion formulas.
BUILTINS = {"ratio": ratio, "difference": difference}

ZONE_QUANTITIES = ("sxx", "syy", "sxy", "szz", "srr", "stt", "srt", "plastic")
GRIDPOINT_QUANTITIES = ("ux", "uy", "ur", "ut", "temperature")
CONTACT_QUANTITIES = ("sn", "tau")
# Fracture flow: results["domains"] (pressure, area, content at the domains' present centres) and
# results["knots"] (flow, aperture, length, conductance at the knots' present points).
FLOW_QUANTITIES = {"domains": ("pressure", "area", "content"), "knots": ("flow", "aperture", "length", "conductance")}
POLAR = ("srr", "stt", "srt", "ur", "ut")
SELECTION_KEYS = ("block", "centre", "x", "y", "r", "angle")


def _contact_columns(results):
    """The closed contacts of results["contacts"] as columns, placed at their present points."""
    names = [b.get("name") for b in results.get("blocks") or []]
    closed = [c for c in results.get("contacts") or [] if not c.get("open")]
    return {
        "x0": [c["point"][0] for c in closed],
        "y0": [c["point"][1] for c in closed],
        "block": [names.index(c["block_a"]) if c["block_a"] in names else -1 for c in closed],
        "sn": [c["normal_force"] / c["length"] for c in closed],
        "tau": [c["shear_force"] / c["length"] for c in closed],
    }


def _columns(results, of):
    from vdec_verify.extract import ExtractError
    if of == "contacts":
        return _contact_columns(results)
    table = results.get(of)
    if not isinstance(table, dict):
        raise ExtractError(f"the results have no '{of}' (a scene without deformable blocks has no zones or "
                           "gridpoints; one without [fluid] no domains or knots)")
    return table


def _selected(results, table):
    """(columns, mask, x, y, r, theta) of the selected zones or gridpoints."""
    from vdec_verify.extract import ExtractError
    of = table["of"]
    columns = _columns(results, of)
    x = np.asarray(columns["x0"], dtype=float)
    y = np.asarray(columns["y0"], dtype=float)
    centre = table.get("centre", [0.0, 0.0])
    dx, dy = x - float(centre[0]), y - float(centre[1])
    r, theta = np.hypot(dx, dy), np.arctan2(dy, dx)
    mask = np.ones(x.shape, dtype=bool)
    slack = 1e-9 * max(1.0, float(np.max(np.abs(np.concatenate([x, y])))) if x.size else 1.0)
    for key, values in (("x", x), ("y", y), ("r", r)):
        if key in table:
            low, high = table[key]
            mask &= (values >= low - slack) & (values <= high + slack)
    if "angle" in table:
        low, high = (math.radians(v) for v in table["angle"])
        mask &= (theta >= low - 1e-9) & (theta <= high + 1e-9)
    if "block" in table:
        names = results.get("blocks") or []
        index = next((i for i, b in enumerate(names) if b.get("name") == table["block"]), None)
        if index is None:
            raise ExtractError(f"the results have no block '{table['block']}'")
        mask &= np.asarray(columns["block"]) == index
    if not mask.any():
        raise ExtractError(f"no {of} in the selection {dict((k, table[k]) for k in SELECTION_KEYS if k in table)}")
    return columns, mask, x, y, r, theta


def _values(columns, of, quantity, theta):
    from vdec_verify.extract import ExtractError
    c, s = np.cos(theta), np.sin(theta)
    if of == "zones":
        if quantity not in ZONE_QUANTITIES:
            raise ExtractError(f"zones have no quantity '{quantity}' (known: {', '.join(ZONE_QUANTITIES)})")
        if quantity in ("sxx", "syy", "sxy", "szz"):
            return np.asarray(columns[quantity], dtype=float)
        if quantity == "plastic":  # 1 where the zone has yielded, now or in the past
            return (np.asarray(columns.get("plastic_state", np.zeros(theta.shape)), dtype=float) != 0).astype(float)
        sxx, syy, sxy = (np.asarray(columns[k], dtype=float) for k in ("sxx", "syy", "sxy"))
        if quantity == "srr":
            return sxx * c * c + syy * s * s + 2.0 * sxy * s * c
        if quantity == "stt":
            return sxx * s * s + syy * c * c - 2.0 * sxy * s * c
        return (syy - sxx) * s * c + sxy * (c * c - s * s)
    if of in FLOW_QUANTITIES:
        if quantity not in FLOW_QUANTITIES[of]:
            raise ExtractError(f"{of} have no quantity '{quantity}' (known: {', '.join(FLOW_QUANTITIES[of])})")
        return np.asarray(columns[quantity], dtype=float)
    if of == "contacts":
        if quantity not in CONTACT_QUANTITIES:
            raise ExtractError(f"contacts have no quantity '{quantity}' (known: {', '.join(CONTACT_QUANTITIES)})")
        return np.asarray(columns[quantity], dtype=float)
    if quantity not in GRIDPOINT_QUANTITIES:
        raise ExtractError(f"gridpoints have no quantity '{quantity}' (known: {', '.join(GRIDPOINT_QUANTITIES)})")
    if quantity == "temperature":
        if "temperature" not in columns:
            raise ExtractError("the gridpoints have no temperature (a scene without [heat])")
        return np.asarray(columns["temperature"], dtype=float)
    ux = np.asarray(columns["displacement_x"], dtype=float)
    uy = np.asarray(columns["displacement_y"], dtype=float)
    return {"ux": ux, "uy": uy, "ur": ux * c + uy * s, "ut": -ux * s + uy * c}[quantity]


def _finite(values, of, quantity):
    """values, or an ExtractError when one is not finite: a field that went NaN in some zone must
    not pass on the others (nor count as "not zero" in an extent)."""
    from vdec_verify.extract import ExtractError
    bad = np.flatnonzero(~np.isfinite(values))
    if bad.size:
        raise ExtractError(f"{of}.{quantity} has {bad.size} non-finite values in the selection "
                           f"(the first at selected sample {int(bad[0])})")
    return values


def field(results, table):
    from vdec_verify.extract import Series
    of, quantity = table["of"], table["quantity"]
    columns, mask, x, y, r, theta = _selected(results, table)
    values = _finite(_values(columns, of, quantity, theta)[mask], of, quantity)
    polar = quantity in POLAR or "r" in table or "angle" in table
    abscissa = table.get("abscissa", "r" if polar else "x")
    coordinate = {"x": x, "y": y, "r": r, "theta": theta}[abscissa][mask]
    order = np.argsort(coordinate, kind="stable")
    coordinates = {"x": x[mask][order], "y": y[mask][order], "r": r[mask][order], "theta": theta[mask][order]}
    weights = np.asarray(columns["area"], dtype=float)[mask][order] if of == "zones" else None
    return Series(coordinate[order], values[order], abscissa, f"{of}.{quantity}", coordinates, weights)


def field_mean(results, table):
    of, quantity = table["of"], table["quantity"]
    columns, mask, _, _, _, theta = _selected(results, table)
    values = _finite(_values(columns, of, quantity, theta)[mask], of, quantity)
    if of == "zones":
        area = np.asarray(columns["area"], dtype=float)[mask]
        return float(np.sum(area * values) / np.sum(area))
    return float(np.mean(values))


def field_peak(results, table):
    of, quantity = table["of"], table["quantity"]
    columns, mask, _, _, _, theta = _selected(results, table)
    values = _finite(_values(columns, of, quantity, theta)[mask], of, quantity)
    return float(values[np.argmax(np.abs(values))])


def field_extent(results, table):
    from vdec_verify.extract import ExtractError
    of, quantity = table["of"], table["quantity"]
    columns, mask, _, _, r, theta = _selected(results, table)
    values = _values(columns, of, quantity, theta)
    _finite(values[mask], of, quantity)
    where = mask & (values != 0.0)
    if not where.any():
        raise ExtractError(f"no {of} in the selection has a nonzero {quantity}")
    return float(np.max(r[where]))


def derived(results, table, exit_code=None, runs=None):
    from vdec_verify.extract import ExtractError, extract
    from vdec_verify.problem import find_reference_function
    inputs = {}
    for name, sub in table["inputs"].items():
        source = results
        if "variant" in sub:
            if runs is None or sub["variant"] not in runs:
                raise ExtractError(f"derived input '{name}' reads run '{sub['variant']}', which did not run")
            source = runs[sub["variant"]]
            if source is None:
                raise ExtractError(f"derived input '{name}': run '{sub['variant']}' wrote no results.json")
            sub = {k: v for k, v in sub.items() if k != "variant"}
        inputs[name] = extract(sub, source, exit_code, runs)
    for name, value in inputs.items():
        if not isinstance(value, float):
            raise ExtractError(f"derived input '{name}' must be a scalar extract")
    function = BUILTINS.get(table["function"]) or find_reference_function(table["function"])
    value = function(**inputs, **table.get("params", {}))
    if isinstance(value, tuple):
        value = value[int(table.get("component", 0))]
    return float(value)

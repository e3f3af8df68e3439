"""Extractors: what a check reads from one run of vdec.

Each extractor takes the run's results dict (results.json) and the check's extract table and
returns a scalar (float) or a Series (x, y arrays) compared point by point with the reference.
Histories are results["histories"][NAME] = {"t": [...], "value": [...]}. An optional
window = [t0, t1] keeps the samples with t0 <= t <= t1. A history with any non-finite sample
(NaN or infinity, written as null in results.json), inside the window or not, is an ExtractError.

    kind           keys (optional in brackets)        returns
    final          history [scale]                    last value
    max, min, mean history [window] [scale]           over the (windowed) history
    value_at       history, t [scale]                 value interpolated linearly at time t
    history        history [window] [scale]           Series (t, value); reference f(t, **params)
    curve          x, y [window] [x_scale]            Series (x, y) of two histories; reference f(x, **params)
    curve          x_rate, y [window]                 Series (x_rate t, y): y against a motion prescribed at
                                                      the constant rate x_rate from t = 0 (e.g. a driven
                                                      block's velocity), sampled at y's times

scale (x_scale for a curve's abscissa) multiplies the history's values, e.g. -1 to read a
closure (positive closing) from a block's displacement (positive up); default 1.
    fit_t2         history [window] [t0]              s of the least-squares fit value = c0 + s (t - t0)^2,
                                                      t0 = the given t0, else the window start, else the first time
    slope          history [window]                   least-squares slope of value against t
    period         history [window] [level]           mean period between successive upward crossings of
                                                      level (default: the mean of the windowed values)
    log_decrement  history [window] [level]           mean of ln(p_k / p_k+1) over successive peaks p_k of
                                                      value - level above level (one per period; default
                                                      level: the final value of the whole history)
    crossing_time  history, level                     the first time the history rises through level (linear
                                                      interpolation between samples): a wave's arrival
    phase_end      history, phase [scale]             the last sample of the history at or before the end of the
                                                      phase of that name (results["phases"]): a phased run's
                                                      state after each phase
    run_meta       path                               a number at a dotted path in results["run"],
                                                      results["energy"], results["fluid"], results["heat"]
                                                      or results["phases"] (a phase by its name), e.g.
                                                      "energy.largest_excess", "fluid.balance.imbalance",
                                                      "phases.diffuse.start_time"
    exit_code      (none)                             the exit code of the run
    differences    against, keys                      how many values differ between this run's results.json
                                                      and the run `against` ("plain" or a variant's name), over
                                                      the given top-level keys (every number, string and length,
                                                      compared exactly): 0 when the runs computed the same
    field, field_mean, derived                        deformable-block fields: vdec_verify.fields
"""
from dataclasses import dataclass

import numpy as np

from vdec_verify import fields


class ExtractError(Exception):
    """The run's output does not hold what the check asks for."""


@dataclass(frozen=True)
class Series:
    x: np.ndarray
    y: np.ndarray
    x_label: str
    y_label: str
    # A field's samples: the reference is called with these coordinates (x, y, r, theta) as
    # keywords, and the L2 norm weights samples by `weights` (zone areas) when given.
    coordinates: dict = None
    weights: np.ndarray = None


def read_history(results, name):
    histories = results.get("histories") or {}
    if name not in histories:
        raise ExtractError(f"the results have no history '{name}' (they have: {', '.join(sorted(histories)) or 'none'})")
    try:
        t = np.asarray(histories[name]["t"], dtype=float)
        value = np.asarray(histories[name]["value"], dtype=float)
    except (KeyError, TypeError, ValueError) as e:
        raise ExtractError(f"history '{name}' is not a {{t: [...], value: [...]}} pair of number lists ({e})") from e
    if t.ndim != 1 or t.shape != value.shape:
        raise ExtractError(f"history '{name}': t has {t.size} samples but value has {value.size}")
    bad = np.flatnonzero(~(np.isfinite(t) & np.isfinite(value)))
    if bad.size:
        # A run that went NaN half-way must not pass on its finite part (a crossing before it, a
        # value or period read from it): any non-finite sample makes the whole history unusable.
        i = int(bad[0])
        raise ExtractError(f"history '{name}' has {bad.size} non-finite samples, the first at sample {i} "
                           f"(t = {t[i]}, value = {value[i]})")
    return t, value


def _windowed(t, value, window, name):
    if window is not None:
        keep = (t >= window[0]) & (t <= window[1])
        t, value = t[keep], value[keep]
    if t.size == 0:
        raise ExtractError(f"history '{name}' has no samples in the window {window}")
    return t, value


def _history_in_window(results, table):
    name = table["history"]
    t, value = read_history(results, name)
    return _windowed(t, value * float(table.get("scale", 1.0)), table.get("window"), name)


def final(results, table):
    _, value = _history_in_window(results, table)
    return float(value[-1])


def maximum(results, table):
    return float(np.max(_history_in_window(results, table)[1]))


def minimum(results, table):
    return float(np.min(_history_in_window(results, table)[1]))


def mean(results, table):
    return float(np.mean(_history_in_window(results, table)[1]))


def value_at(results, table):
    name = table["history"]
    t, value = read_history(results, name)
    value = value * float(table.get("scale", 1.0))
    when = float(table["t"])
    if t.size == 0 or not t[0] <= when <= t[-1]:
        span = f"[{t[0]}, {t[-1]}]" if t.size else "(no samples)"
        raise ExtractError(f"history '{name}': t = {when} is outside the sampled times {span}")
    return float(np.interp(when, t, value))


def history(results, table):
    t, value = _history_in_window(results, table)
    return Series(t, value, "t", table["history"])


def curve(results, table):
    ty, y = read_history(results, table["y"])
    if "x_rate" in table:
        # A prescribed motion at a constant rate from t = 0: the abscissa is rate x time, known
        # without reading anything the solver computed.
        x = float(table["x_rate"]) * ty
        window = table.get("window")
        keep = np.ones(ty.shape, dtype=bool) if window is None else (ty >= window[0]) & (ty <= window[1])
        if not keep.any():
            raise ExtractError(f"history '{table['y']}' has no samples in the window {window}")
        return Series(x[keep], y[keep], f"{table['x_rate']:g} t", table["y"])
    tx, x = read_history(results, table["x"])
    x = x * float(table.get("x_scale", 1.0))
    if tx.shape != ty.shape or np.any(tx != ty):
        # Histories of different subjects may be sampled at different times (block positions at
        # the end of a step, joint measures at its start): put y on x's sample times, and keep
        # only the times inside y's sampled span so that nothing is extrapolated.
        inside = (tx >= ty[0]) & (tx <= ty[-1]) if ty.size else np.zeros_like(tx, dtype=bool)
        tx, x = tx[inside], x[inside]
        y = np.interp(tx, ty, y)
    window = table.get("window")
    keep = np.ones(tx.shape, dtype=bool) if window is None else (tx >= window[0]) & (tx <= window[1])
    if not keep.any():
        raise ExtractError(f"histories '{table['x']}' and '{table['y']}' have no common samples in the window {window}")
    return Series(x[keep], y[keep], table["x"], table["y"])


def fit_t2(results, table):
    t, value = _history_in_window(results, table)
    window = table.get("window")
    t0 = float(table["t0"]) if "t0" in table else (float(window[0]) if window else float(t[0]))
    squared = (t - t0) ** 2
    if t.size < 3 or np.ptp(squared) == 0.0:
        raise ExtractError(f"history '{table['history']}': fit_t2 needs at least three samples at distinct |t - t0|")
    design = np.column_stack([np.ones_like(squared), squared])
    coefficients, *_ = np.linalg.lstsq(design, value, rcond=None)
    return float(coefficients[1])


def slope(results, table):
    t, value = _history_in_window(results, table)
    if t.size < 2 or np.ptp(t) == 0.0:
        raise ExtractError(f"history '{table['history']}': a slope needs at least two samples at distinct times")
    return float(np.polyfit(t, value, 1)[0])


def upward_crossings(t, value, level):
    """Times where value rises through level, linearly interpolated between samples."""
    above = value - level
    i = np.nonzero((above[:-1] < 0.0) & (above[1:] >= 0.0))[0]
    return t[i] - above[i] * (t[i + 1] - t[i]) / (above[i + 1] - above[i])


def period(results, table):
    t, value = _history_in_window(results, table)
    level = float(table.get("level", np.mean(value)))
    crossings = upward_crossings(t, value, level)
    if crossings.size < 2:
        raise ExtractError(f"history '{table['history']}' crosses {level:g} upward {crossings.size} times; "
                           "a period needs at least two crossings")
    return float(np.mean(np.diff(crossings)))


def peaks_above(value, level):
    """The largest value - level in each excursion above level that lies wholly inside the
    samples (bounded by samples at or below level on both sides), so a lobe cut by the window
    does not pass for a peak, and sampling noise inside one lobe gives one peak, not several."""
    above = value - level
    peaks, start = [], None
    for i, a in enumerate(above):
        if a > 0.0 and start is None:
            start = i
        elif a <= 0.0 and start is not None:
            if start > 0:
                peaks.append(float(np.max(above[start:i])))
            start = None
    return np.asarray(peaks)


def log_decrement(results, table):
    t, value = _history_in_window(results, table)
    # By default the oscillation is about the history's final value (its settled state), even
    # when the window ends earlier.
    level = float(table.get("level", read_history(results, table["history"])[1][-1]))
    peaks = peaks_above(value, level)
    if peaks.size < 2:
        raise ExtractError(f"history '{table['history']}' has {peaks.size} complete excursions above {level:g}; "
                           "a logarithmic decrement needs at least two")
    return float(np.mean(np.log(peaks[:-1] / peaks[1:])))


def crossing_time(results, table):
    name = table["history"]
    t, value = read_history(results, name)
    crossings = upward_crossings(t, value, float(table["level"]))
    if crossings.size == 0:
        raise ExtractError(f"history '{name}' never rises through {table['level']:g}")
    return float(crossings[0])


def phase_end(results, table):
    name, phase = table["history"], table["phase"]
    found = [p for p in results.get("phases") or [] if p.get("name") == phase]
    if not found:
        raise ExtractError(f"the results have no phase '{phase}' (a scene without it, or a run stopped before it)")
    end = found[0]["start_time"] + found[0]["time"]
    t, value = read_history(results, name)
    # Samples carry the time of the positions just reached; half a step of slack for round-off.
    slack = 0.5 * float(results.get("run", {}).get("dt", 0.0))
    inside = np.nonzero(t <= end + slack)[0]
    if inside.size == 0:
        raise ExtractError(f"history '{name}' has no sample before the end of phase '{phase}' (t = {end})")
    return float(value[inside[-1]]) * float(table.get("scale", 1.0))


def count_differences(a, b):
    """The leaves (numbers, strings, booleans, nulls, and lengths of lists and key sets) that differ."""
    if isinstance(a, dict) and isinstance(b, dict):
        return sum(count_differences(a.get(k), b.get(k)) for k in sorted(set(a) | set(b)))
    if isinstance(a, list) and isinstance(b, list):
        return (len(a) != len(b)) + sum(count_differences(x, y) for x, y in zip(a, b))
    return int(a != b or type(a) is not type(b))


def differences(results, table, runs):
    against = table["against"]
    other = (runs or {}).get("" if against == "plain" else against)
    if other is None:
        raise ExtractError(f"run '{against}' wrote no results.json (or did not run)")
    missing = [k for k in table["keys"] if k not in results or k not in other]
    if missing:
        raise ExtractError(f"the results have no '{missing[0]}' to compare")
    return float(sum(count_differences(results[k], other[k]) for k in table["keys"]))


def run_meta(results, table):
    node = results
    for part in table["path"].split("."):
        if isinstance(node, list):
            # results["phases"] is a list of objects named by "name": "phases.NAME.FIELD".
            named = [item for item in node if isinstance(item, dict) and item.get("name") == part]
            if not named:
                raise ExtractError(f"the results have no field '{table['path']}' (no phase named '{part}')")
            node = named[0]
            continue
        if not isinstance(node, dict) or part not in node:
            raise ExtractError(f"the results have no field '{table['path']}' (missing '{part}')")
        node = node[part]
    if isinstance(node, bool) or not isinstance(node, (int, float)):
        raise ExtractError(f"results field '{table['path']}' is {node!r}, not a number")
    return float(node)


@dataclass(frozen=True)
class Kind:
    function: object
    required: tuple
    optional: tuple
    series: bool  # True: returns a Series, compared with the L2 or Linf norm


KINDS = {
    "final": Kind(final, ("history",), ("scale",), False),
    "max": Kind(maximum, ("history",), ("window", "scale"), False),
    "min": Kind(minimum, ("history",), ("window", "scale"), False),
    "mean": Kind(mean, ("history",), ("window", "scale"), False),
    "value_at": Kind(value_at, ("history", "t"), ("scale",), False),
    "history": Kind(history, ("history",), ("window", "scale"), True),
    "curve": Kind(curve, ("y",), ("x", "window", "x_scale", "x_rate"), True),
    "fit_t2": Kind(fit_t2, ("history",), ("window", "t0"), False),
    "slope": Kind(slope, ("history",), ("window",), False),
    "period": Kind(period, ("history",), ("window", "level"), False),
    "log_decrement": Kind(log_decrement, ("history",), ("window", "level"), False),
    "crossing_time": Kind(crossing_time, ("history", "level"), (), False),
    "phase_end": Kind(phase_end, ("history", "phase"), ("scale",), False),
    "run_meta": Kind(run_meta, ("path",), (), False),
    "exit_code": Kind(None, (), (), False),
    "differences": Kind(None, ("against", "keys"), (), False),
    "field": Kind(fields.field, ("of", "quantity"), fields.SELECTION_KEYS + ("abscissa",), True),
    "field_mean": Kind(fields.field_mean, ("of", "quantity"), fields.SELECTION_KEYS, False),
    "field_peak": Kind(fields.field_peak, ("of", "quantity"), fields.SELECTION_KEYS, False),
    "field_extent": Kind(fields.field_extent, ("of", "quantity"), fields.SELECTION_KEYS, False),
    "derived": Kind(None, ("function", "inputs"), ("params", "component"), False),
}


def extract(table, results, exit_code, runs=None):
    """The value a check compares: a float or a Series. results is None when the run wrote none;
    runs (run name -> results, "" the plain run) serves derived inputs that name a variant."""
    kind = table["kind"]
    if kind == "exit_code":
        if exit_code is None:
            raise ExtractError("the run has no exit code (it did not finish)")
        return float(exit_code)
    if results is None:
        raise ExtractError("the run wrote no results.json")
    if kind == "derived":
        return fields.derived(results, table, exit_code, runs)
    if kind == "differences":
        return differences(results, table, runs)
    return KINDS[kind].function(results, table)

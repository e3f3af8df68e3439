"""Extractors of the verification harness on synthetic results with known answers (REQ-QA-001)."""
import json
import math

import numpy as np
import pytest

from vdec_verify.extract import ExtractError, Series, extract, peaks_above


def results_with(**histories):
    """A results dict whose histories are NAME=(t, value)."""
    return {"schema": "vdec.results/1",
            "run": {"cycles": 120, "dt": 1e-3, "nested": {"value": 2.5}, "stop_reason": "time"},
            "energy": {"largest_excess": 0.125},
            "phases": [{"name": "settle", "start_time": 0.0}, {"name": "flow", "start_time": 0.75}],
            "histories": {name: {"t": list(map(float, t)), "value": list(map(float, v))}
                          for name, (t, v) in histories.items()}}


T = np.linspace(0.0, 1.0, 11)
RAMP = results_with(h=(T, 10.0 * T + 1.0))


@pytest.mark.requirements("REQ-QA-001")
@pytest.mark.parametrize("table, expected", [
    ({"kind": "final", "history": "h"}, 11.0),
    ({"kind": "max", "history": "h"}, 11.0),
    ({"kind": "max", "history": "h", "window": [0.2, 0.5]}, 6.0),
    ({"kind": "min", "history": "h", "window": [0.2, 0.5]}, 3.0),
    ({"kind": "mean", "history": "h", "window": [0.2, 0.5]}, 4.5),
    ({"kind": "mean", "history": "h"}, 6.0),
    ({"kind": "value_at", "history": "h", "t": 0.25}, 3.5),
    ({"kind": "slope", "history": "h", "window": [0.3, 0.9]}, 10.0),
    ({"kind": "run_meta", "path": "run.cycles"}, 120.0),
    ({"kind": "run_meta", "path": "run.nested.value"}, 2.5),
    ({"kind": "run_meta", "path": "energy.largest_excess"}, 0.125),
    ({"kind": "run_meta", "path": "phases.flow.start_time"}, 0.75),
])
def test_scalar_extractors(table, expected):
    assert extract(table, RAMP, 0) == pytest.approx(expected, rel=1e-12, abs=0)


@pytest.mark.requirements("REQ-QA-001")
def test_fit_t2_returns_the_coefficient_of_t_squared_from_the_window_start_or_t0():
    t = np.linspace(0.0, 2.0, 201)
    results = results_with(x=(t, 3.0 + 2.0 * (t - 0.5) ** 2))
    assert extract({"kind": "fit_t2", "history": "x", "window": [0.5, 1.5]}, results, 0) == pytest.approx(2.0, rel=1e-12, abs=0)
    assert extract({"kind": "fit_t2", "history": "x", "t0": 0.5}, results, 0) == pytest.approx(2.0, rel=1e-12, abs=0)
    # Without t0 the fit is about the first sample, t = 0, where the curve is not a pure t^2.
    assert extract({"kind": "fit_t2", "history": "x"}, results, 0) != pytest.approx(2.0, rel=1e-3, abs=0)


@pytest.mark.requirements("REQ-QA-001")
def test_period_from_upward_crossings_with_interpolation():
    t = np.linspace(0.0, 1.0, 1001)
    results = results_with(y=(t, 5.0 + np.sin(2.0 * np.pi * t / 0.3 + 0.4)))
    assert extract({"kind": "period", "history": "y"}, results, 0) == pytest.approx(0.3, rel=1e-4, abs=0)
    assert extract({"kind": "period", "history": "y", "level": 5.5}, results, 0) == pytest.approx(0.3, rel=1e-4, abs=0)
    with pytest.raises(ExtractError, match="a period needs at least two crossings"):
        extract({"kind": "period", "history": "y", "window": [0.0, 0.2]}, results, 0)


@pytest.mark.requirements("REQ-QA-001")
def test_log_decrement_of_a_damped_oscillation():
    a, wd = 3.0, 2.0 * np.pi * 5.0
    t = np.linspace(0.0, 4.0, 80001)
    results = results_with(y=(t, 7.0 + np.exp(-a * t) * np.cos(wd * t)))
    # Peaks of e^{-a t} cos(wd t) one damped period apart have the ratio e^{a 2 pi / wd}.
    expected = a * 2.0 * np.pi / wd
    table = {"kind": "log_decrement", "history": "y", "window": [0.0, 1.0]}
    assert extract(dict(table, level=7.0), results, 0) == pytest.approx(expected, rel=1e-4, abs=0)
    # The default level is the history's final value, 7 + e^-12, even though the window ends at 1 s.
    assert extract(table, results, 0) == pytest.approx(expected, rel=1e-3, abs=0)


@pytest.mark.requirements("REQ-QA-001")
def test_peaks_ignore_excursions_cut_by_the_window_and_noise_within_one():
    # Starts inside an excursion (cut: not a peak); the second excursion has two local maxima.
    value = np.array([3.0, 2.0, -1.0, 1.0, 2.0, 1.5, 1.8, -1.0, 1.0, -1.0, 0.5])
    assert peaks_above(value, 0.0).tolist() == [2.0, 1.0]


@pytest.mark.requirements("REQ-QA-001")
def test_history_and_curve_return_series():
    t = np.linspace(0.0, 1.0, 11)
    results = results_with(x=(t, 2.0 * t), y=(t, t ** 2))
    series = extract({"kind": "history", "history": "y", "window": [0.5, 1.0]}, results, 0)
    assert isinstance(series, Series)
    assert series.x.tolist() == pytest.approx([0.5, 0.6, 0.7, 0.8, 0.9, 1.0])
    curve = extract({"kind": "curve", "x": "x", "y": "y", "window": [0.0, 0.5]}, results, 0)
    assert curve.x.tolist() == pytest.approx(2.0 * t[:6])
    assert curve.y.tolist() == pytest.approx(t[:6] ** 2)
    assert (curve.x_label, curve.y_label) == ("x", "y")


@pytest.mark.requirements("REQ-QA-001")
def test_curve_puts_y_on_the_sample_times_of_x_without_extrapolating():
    tx = np.array([0.0, 0.1, 0.2, 0.3, 0.4])
    ty = np.array([0.05, 0.15, 0.25, 0.35])      # sampled half a step later
    results = results_with(x=(tx, 10.0 * tx), y=(ty, 4.0 * ty))
    curve = extract({"kind": "curve", "x": "x", "y": "y"}, results, 0)
    # x samples at 0.0 and 0.4 lie outside y's span and are dropped, not extrapolated.
    assert curve.x.tolist() == pytest.approx([1.0, 2.0, 3.0])
    assert curve.y.tolist() == pytest.approx([0.4, 0.8, 1.2])


@pytest.mark.requirements("REQ-QA-001")
def test_exit_code_needs_no_results():
    assert extract({"kind": "exit_code"}, None, 5) == 5.0
    with pytest.raises(ExtractError, match="did not finish"):
        extract({"kind": "exit_code"}, None, None)


@pytest.mark.requirements("REQ-QA-001")
@pytest.mark.parametrize("table, results, phrase", [
    ({"kind": "final", "history": "nope"}, RAMP, "no history 'nope' .*they have: h"),
    ({"kind": "final", "history": "h"}, None, "wrote no results.json"),
    ({"kind": "max", "history": "h", "window": [2.0, 3.0]}, RAMP, "no samples in the window"),
    ({"kind": "value_at", "history": "h", "t": 1.5}, RAMP, "outside the sampled times"),
    ({"kind": "run_meta", "path": "energy.nope"}, RAMP, "no field 'energy.nope'"),
    ({"kind": "run_meta", "path": "run.stop_reason"}, RAMP, "not a number"),
    ({"kind": "run_meta", "path": "phases.nope.time"}, RAMP, "no phase named 'nope'"),
    ({"kind": "fit_t2", "history": "h", "window": [0.0, 0.1]}, RAMP, "at least three samples"),
    ({"kind": "log_decrement", "history": "h"}, RAMP, "needs at least two"),
    ({"kind": "final", "history": "bad"}, {"histories": {"bad": {"t": [0, 1], "value": [1]}}}, "t has 2 samples"),
])
def test_extraction_failures_say_what_is_missing(table, results, phrase):
    with pytest.raises(ExtractError, match=phrase):
        extract(table, results, 0)


@pytest.mark.requirements("REQ-QA-001", "REQ-QA-008")
@pytest.mark.parametrize("table", [
    {"kind": "final", "history": "h"},
    {"kind": "max", "history": "h", "window": [0.0, 0.3]},
    {"kind": "value_at", "history": "h", "t": 0.25},
    {"kind": "crossing_time", "history": "h", "level": 0.5},
    {"kind": "period", "history": "h", "window": [0.0, 0.45]},
    {"kind": "history", "history": "h", "window": [0.0, 0.45]},
    {"kind": "curve", "x": "ramp", "y": "h", "window": [0.0, 0.45]},
])
def test_a_history_that_turns_non_finite_is_rejected_whatever_is_read_from_it(table):
    # What is read (a crossing at t = 0.008, a value at 0.25, periods and windows before 0.5) is
    # finite; the run went NaN (or infinite) after t = 0.5, which must not pass for a result.
    t = np.linspace(0.0, 1.0, 101)
    wave = np.sin(2.0 * np.pi * t / 0.2)
    for bad in (math.nan, math.inf, -math.inf):
        results = results_with(h=(t, np.where(t > 0.5, bad, wave)), ramp=(t, t))
        with pytest.raises(ExtractError, match="history 'h' has 50 non-finite samples, the first at sample 51"):
            extract(table, results, 0)
    # null in results.json (how vdec writes a NaN) reads as non-finite too.
    results = results_with(h=(t, wave), ramp=(t, t))
    results["histories"]["h"]["value"][70] = None
    with pytest.raises(ExtractError, match="history 'h' has 1 non-finite samples, the first at sample 70"):
        extract(table, results, 0)
    # The same history without the bad samples is read.
    extract(table, results_with(h=(t, wave), ramp=(t, t)), 0)


@pytest.mark.requirements("REQ-QA-006")
def test_crossing_time_is_the_first_upward_crossing():
    # value = 10 t + 1 on t = 0, 0.1, ...: it rises through 3.5 at t = 0.25 (between samples).
    assert extract({"kind": "crossing_time", "history": "h", "level": 3.5}, RAMP, 0) == pytest.approx(0.25, rel=1e-12, abs=0)
    with pytest.raises(ExtractError, match="never rises through 20"):
        extract({"kind": "crossing_time", "history": "h", "level": 20.0}, RAMP, 0)


@pytest.mark.requirements("REQ-QA-001")
def test_phase_end_reads_the_last_sample_of_the_phase():
    # value = 10 t + 1 sampled every 0.1 s; phase "a" ends at 0.25 + 0.2 = 0.45 s, whose last
    # sample is t = 0.4 (value 5); phase "b" ends at 0.6 exactly, a sample (value 7).
    results = dict(RAMP, phases=[{"name": "a", "start_time": 0.25, "time": 0.2},
                                 {"name": "b", "start_time": 0.45, "time": 0.15}])
    assert extract({"kind": "phase_end", "history": "h", "phase": "a"}, results, 0) == pytest.approx(5.0, rel=1e-12, abs=0)
    assert extract({"kind": "phase_end", "history": "h", "phase": "b", "scale": -1.0}, results, 0) == \
        pytest.approx(-7.0, rel=1e-12, abs=0)
    with pytest.raises(ExtractError, match="no phase 'c'"):
        extract({"kind": "phase_end", "history": "h", "phase": "c"}, results, 0)
    early = dict(RAMP, phases=[{"name": "a", "start_time": -1.0, "time": 0.5}])
    with pytest.raises(ExtractError, match="no sample before the end of phase 'a'"):
        extract({"kind": "phase_end", "history": "h", "phase": "a"}, early, 0)


@pytest.mark.requirements("REQ-QA-001")
def test_differences_counts_every_value_that_differs_between_two_runs():
    plain = {"histories": {"h": {"t": [0.0, 1.0], "value": [1.0, 2.0]}}, "blocks": [{"name": "b", "x": 0.5}]}
    same = json.loads(json.dumps(plain))
    table = {"kind": "differences", "against": "plain", "keys": ["histories", "blocks"]}
    assert extract(table, same, 0, {"": plain}) == 0.0
    other = json.loads(json.dumps(plain))
    other["histories"]["h"]["value"][1] = math.nextafter(2.0, 3.0)  # one ulp is a difference
    other["blocks"].append({"name": "c"})                     # and so is a block more
    other["blocks"][0]["x"] = 0.5
    assert extract(table, other, 0, {"": plain}) == 2.0
    with pytest.raises(ExtractError, match="run 'plain' wrote no results.json"):
        extract(table, same, 0, {})
    with pytest.raises(ExtractError, match="no 'zones' to compare"):
        extract(dict(table, keys=["zones"]), same, 0, {"": plain})

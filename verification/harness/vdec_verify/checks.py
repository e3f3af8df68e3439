"""Extractors (what a check reads from results.json), references and the pass rule."""
import numpy as np

from vdec_verify.problem import ProblemError, reference_function


def _series(results, name):
    try:
        h = results["histories"][name]
    except KeyError as e:
        raise ProblemError(f"results have no history '{name}'") from e
    return np.asarray(h["t"], dtype=float), np.asarray(h["value"], dtype=float)


def _windowed(t, v, window):
    if not window:
        return t, v
    keep = (t >= window[0]) & (t <= window[1])
    return t[keep], v[keep]


def _upward_crossings(t, v, level):
    s = v - level
    idx = np.nonzero((s[:-1] < 0) & (s[1:] >= 0))[0]
    return t[idx] - s[idx] * (t[idx + 1] - t[idx]) / (s[idx + 1] - s[idx])


def extract(results, exit_code, spec):
    """Returns a scalar, or (x, y) arrays for history and curve comparisons."""
    kind = spec["kind"]
    if kind == "exit_code":
        return float(exit_code)
    if kind == "run_meta":
        node = results
        for part in spec["path"].split("."):
            node = node[part]
        return float(node)
    if kind == "curve":
        tx, x = _series(results, spec["x"])
        ty, y = _series(results, spec["y"])
        if len(tx) != len(ty) or np.any(tx != ty):
            # Block positions are sampled at the end of a step, joint measures at its start:
            # put y on x's sample times.
            y = np.interp(tx, ty, y)
        keep = np.ones_like(tx, dtype=bool)
        if spec.get("window"):
            keep = (tx >= spec["window"][0]) & (tx <= spec["window"][1])
        return x[keep], y[keep]
    t, v = _windowed(*_series(results, spec["history"]), spec.get("window"))
    if len(v) == 0:
        raise ProblemError(f"history '{spec['history']}' has no samples in the window")
    if kind == "history":
        return t, v
    if kind == "final":
        return float(v[-1])
    if kind == "max":
        return float(v.max())
    if kind == "min":
        return float(v.min())
    if kind == "mean":
        return float(v.mean())
    if kind == "value_at":
        return float(np.interp(spec["t"], t, v))
    if kind == "slope":
        return float(np.polyfit(t, v, 1)[0])
    if kind == "period":
        crossings = _upward_crossings(t, v, spec.get("level", v.mean()))
        if len(crossings) < 2:
            raise ProblemError(f"history '{spec['history']}' has fewer than two upward crossings")
        return float((crossings[-1] - crossings[0]) / (len(crossings) - 1))
    if kind == "log_decrement":
        level = spec.get("level", v[-1])
        a = np.abs(v - level)
        peaks = [a[i] for i in range(1, len(a) - 1) if a[i] >= a[i - 1] and a[i] > a[i + 1] and v[i] > level]
        if len(peaks) < 2:
            raise ProblemError(f"history '{spec['history']}' has fewer than two peaks")
        return float(np.mean(np.log(np.asarray(peaks[:-1]) / np.asarray(peaks[1:]))))
    raise ProblemError(f"unknown extract kind '{kind}'")


def reference_value(reference, numerical):
    if "constant" in reference:
        return float(reference["constant"])
    function = reference_function(reference["function"], "reference")
    params = reference.get("params", {})
    if isinstance(numerical, tuple):
        x = numerical[0]
        value = function(x, **params)
    else:
        value = function(**params)
    if isinstance(value, tuple):
        value = value[reference.get("component", 0)]
    if isinstance(numerical, tuple) and (value is numerical[1] or value is numerical[0]):
        raise ProblemError("reference identical to the numerical output: the reference must be independent")
    return value


def _trapezoid_weights(x):
    w = np.zeros_like(x)
    if len(x) > 1:
        dx = np.abs(np.diff(x))
        w[:-1] += dx / 2
        w[1:] += dx / 2
    else:
        w[:] = 1.0
    if w.sum() == 0:
        w[:] = 1.0
    return w


def evaluate(check, numerical, reference):
    """Applies the pass rule; returns a metric dict for summary.json."""
    if isinstance(numerical, tuple):
        x, fh = numerical
        f = np.asarray(reference, dtype=float) * np.ones_like(fh)
        if fh.size > 1 and np.array_equal(fh, f):
            raise ProblemError("reference identical to the numerical output: the reference must be independent")
        if check.norm == "L2":
            w = _trapezoid_weights(x)
            e_abs = float(np.sqrt(np.sum(w * (fh - f) ** 2) / np.sum(w)))
            s = float(np.sqrt(np.sum(w * f ** 2) / np.sum(w)))
        elif check.norm == "Linf":
            e_abs, s = float(np.max(np.abs(fh - f))), float(np.max(np.abs(f)))
        else:
            raise ProblemError(f"norm '{check.norm}' does not apply to a series; use L2 or Linf")
        passed = e_abs <= check.atol + check.rtol * s
        num_out, ref_out = None, s
    else:
        xh, xr = float(numerical), float(reference)
        s = abs(xr)
        if check.norm == "upper_bound":
            e_abs = xh - xr
            passed = xh <= xr + check.atol + check.rtol * s
        elif check.norm == "equal":
            e_abs = abs(xh - xr)
            passed = xh == xr
        elif check.norm == "scalar":
            e_abs = abs(xh - xr)
            passed = e_abs <= check.atol + check.rtol * s
        else:
            raise ProblemError(f"norm '{check.norm}' does not apply to a scalar; use scalar, upper_bound or equal")
        num_out, ref_out = xh, xr
    error = e_abs / s if s > 0 else e_abs
    tolerance = (check.atol + check.rtol * s) / s if s > 0 else check.atol
    return {"quantity": check.quantity, "norm": check.norm, "error": error, "tolerance": tolerance,
            "pass": bool(passed), "numerical": num_out, "reference": ref_out, "variant": check.variant,
            "justification": check.justification}

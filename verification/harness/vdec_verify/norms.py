"""Error norms, the pass rule (vdec_verify.PASS_RULE) and the reference-independence guard."""
from dataclasses import dataclass

import numpy as np

from vdec_verify.extract import Series

SCALAR_NORMS = ("scalar", "upper_bound", "equal")
SERIES_NORMS = ("L2", "Linf")
NORMS = SCALAR_NORMS + SERIES_NORMS

NOT_INDEPENDENT = "reference identical to the numerical output: the reference must be independent"


class ReferenceProblem(Exception):
    """The reference cannot serve as one: it fails, returns something unusable, or is not
    independent of the numerical output. The problem is then invalid, not failed."""


def evaluate_reference(reference, numerical, function):
    """The reference value(s) for a numerical value or Series.

    reference: problem.Reference; function: the looked-up analytic function (None for a constant).
    A Series' reference is function(x, **params), evaluated on a read-only copy of x: the
    reference cannot alter the harness's data, and a function that hands back its argument
    (or a view of it) is caught as not independent, as is one whose values equal the
    numerical ones exactly (np.array_equal).
    """
    if reference.constant is not None:
        value = reference.constant
        if isinstance(numerical, Series):
            return np.full(numerical.y.shape, float(value))
        return float(value)
    argument = None
    try:
        if isinstance(numerical, Series) and numerical.coordinates is not None:
            # A field: the coordinates the function takes, as keywords, on read-only copies.
            import inspect
            accepted = inspect.signature(function).parameters
            coordinates = {}
            for name, values in numerical.coordinates.items():
                if name in accepted:
                    copy = np.array(values, dtype=float)
                    copy.flags.writeable = False
                    coordinates[name] = copy
            argument = next(iter(coordinates.values()), None)
            value = function(**coordinates, **reference.params)
        elif isinstance(numerical, Series):
            argument = numerical.x.copy()
            argument.flags.writeable = False
            value = function(argument, **reference.params)
        else:
            value = function(**reference.params)
    except Exception as e:  # any failure of the reference makes the check meaningless
        raise ReferenceProblem(f"reference {reference.function_name} raised {type(e).__name__}: {e}") from e
    if isinstance(value, dict):
        if reference.component not in value:
            raise ReferenceProblem(f"reference {reference.function_name} returns the fields {', '.join(map(str, value))}; "
                                   "name one with component = \"...\"")
        value = value[reference.component]
    elif isinstance(value, tuple):
        if reference.component is None:
            raise ReferenceProblem(f"reference {reference.function_name} returns {len(value)} components; "
                                   "name one with component = N")
        if not 0 <= reference.component < len(value):
            raise ReferenceProblem(f"reference {reference.function_name} has no component {reference.component} "
                                   f"(it returns {len(value)})")
        value = value[reference.component]
    if isinstance(numerical, Series):
        if value is argument or (isinstance(value, np.ndarray) and np.shares_memory(value, argument)):
            raise ReferenceProblem(NOT_INDEPENDENT)
        try:
            values = np.broadcast_to(np.asarray(value, dtype=float), numerical.y.shape).copy()
        except (TypeError, ValueError) as e:
            raise ReferenceProblem(f"reference {reference.function_name} returned {np.shape(value)} values for "
                                   f"{numerical.y.size} samples") from e
        # A closed form that reproduces every sample bit for bit was almost surely computed from
        # the output itself. (A constant reference is exempt: it is typed into problem.toml.)
        if np.array_equal(values, numerical.y):
            raise ReferenceProblem(NOT_INDEPENDENT)
    else:
        try:
            values = float(value)
        except (TypeError, ValueError) as e:
            raise ReferenceProblem(f"reference {reference.function_name} returned {value!r}, not a number") from e
    if not np.all(np.isfinite(values)):
        raise ReferenceProblem(f"reference {reference.function_name or 'constant'} is not finite")
    return values


def trapezoid_weights(x):
    """Weight of each sample: half the spacing to each neighbour (spacing taken as |dx|, since a
    curve's abscissa need not be monotonic); equal weights when the samples have no extent."""
    x = np.asarray(x, dtype=float)
    weights = np.zeros_like(x)
    if x.size > 1:
        spacing = np.abs(np.diff(x))
        weights[:-1] += spacing / 2.0
        weights[1:] += spacing / 2.0
    if not np.sum(weights) > 0.0:
        weights[:] = 1.0
    return weights


@dataclass(frozen=True)
class Comparison:
    error: float       # e_abs / s (e_abs when s == 0)
    tolerance: float   # (atol + rtol s) / s (atol when s == 0)
    passed: bool
    e_abs: float
    scale: float       # s of the reference
    numerical: float   # the numerical scalar, or the same norm of the numerical series
    reference: float   # the reference scalar, or s


def compare(norm, numerical, reference, rtol, atol):
    """Applies the pass rule. numerical: float or Series; reference: float or array of y's shape."""
    if isinstance(numerical, Series):
        y = numerical.y
        f = np.asarray(reference, dtype=float)
        if norm == "L2":
            w = numerical.weights if numerical.weights is not None else trapezoid_weights(numerical.x)
            e_abs = float(np.sqrt(np.sum(w * (y - f) ** 2) / np.sum(w)))
            scale = float(np.sqrt(np.sum(w * f ** 2) / np.sum(w)))
            numerical_size = float(np.sqrt(np.sum(w * y ** 2) / np.sum(w)))
        elif norm == "Linf":
            e_abs = float(np.max(np.abs(y - f)))
            scale = float(np.max(np.abs(f)))
            numerical_size = float(np.max(np.abs(y)))
        else:
            raise ValueError(f"norm '{norm}' does not apply to a series")
        passed = e_abs <= atol + rtol * scale
        return _comparison(e_abs, scale, rtol, atol, passed, numerical_size, scale)
    x_h, x = float(numerical), float(reference)
    scale = abs(x)
    if norm == "scalar":
        e_abs = abs(x_h - x)
        passed = e_abs <= atol + rtol * scale
    elif norm == "upper_bound":
        e_abs = x_h - x
        passed = x_h <= x + atol + rtol * scale
    elif norm == "equal":
        e_abs = abs(x_h - x)
        passed = x_h == x
        rtol = atol = 0.0
    else:
        raise ValueError(f"norm '{norm}' does not apply to a scalar")
    # A NaN anywhere makes every comparison false, so a NaN result fails rather than passes.
    return _comparison(e_abs, scale, rtol, atol, bool(passed), x_h, x)


def _comparison(e_abs, scale, rtol, atol, passed, numerical, reference):
    if scale > 0.0:
        error, tolerance = e_abs / scale, (atol + rtol * scale) / scale
    else:
        error, tolerance = e_abs, atol
    return Comparison(error, tolerance, bool(passed), e_abs, scale, numerical, reference)

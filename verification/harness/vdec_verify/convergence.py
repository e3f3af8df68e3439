"""Convergence studies over zone size: observed order, Grid Convergence Index, asymptotic ratio.

The harness's own arithmetic (numpy only). It does not import the `analytic` package: that
package holds the references vdec is compared with, and a study is a judgement of the
harness, not a reference. (tests/python/test_harness_convergence.py checks gci against
analytic.elastic.gci, which follows the same procedure.)

Levels are given coarsest first (h strictly decreasing); "the finest N" are the last N.

observed_order(h, error)
    Least-squares slope p of ln e = ln C + p ln h over the given levels (error = C h^p).

grid_convergence_index(h, values, safety_factor=1.25)
    Roache's GCI (Roache, Verification and Validation in Computational Science and
    Engineering, Hermosa, 1998) from three grids, in the steps of Celik, Ghia, Roache,
    Freitas, Coleman & Raad, ASME J. Fluids Eng. 130 (2008) 078001. With h1 < h2 < h3
    (grid 1 the finest) and phi_k the numerical values:

        r21 = h2 / h1,  r32 = h3 / h2,  e21 = phi2 - phi1,  e32 = phi3 - phi2,  s = sign(e32 / e21)
        p   = |ln|e32 / e21| + q(p)| / ln r21,   q(p) = ln((r21^p - s) / (r32^p - s))
              (fixed-point iteration from q = 0; q = 0 exactly when r21 = r32)
        extrapolated = (r21^p phi1 - phi2) / (r21^p - 1)
        gci_fine     = Fs |e21 / phi1| / (r21^p - 1)           (a fraction of |phi1|; Fs = 1.25)
        asymptotic_ratio = GCI_23 / (r21^p GCI_12),  GCI_12 = Fs |e21| / (r21^p - 1),
                                                     GCI_23 = Fs |e32| / (r32^p - 1)

    The ratio is Roache's check of the asymptotic range: about 1 there, exactly 1 for
    phi = phi0 + C h^p. s < 0 means oscillatory convergence (reported, not hidden).

convergence_study(...)
    The "convergence" record of a problem in summary.json: the fit over the asymptotic
    levels, the GCI of the three finest of them, the ratio and the verdict
    |observed - expected| <= order_tolerance. A level whose error is missing, zero, negative
    or not finite cannot be fitted on a log scale: the study then fails and says which level.
"""
import math
from dataclasses import dataclass

import numpy as np

SAFETY_FACTOR = 1.25


class ConvergenceError(ValueError):
    """The numbers admit no order (too few levels, repeated h, zero or non-finite errors, ...)."""


def _vector(values, name):
    try:
        array = np.asarray(values, dtype=float).ravel()
    except (TypeError, ValueError) as e:
        raise ConvergenceError(f"{name} must be numbers ({e})") from e
    return array


def observed_order(h, error):
    """Least-squares slope of ln(error) against ln(h) (error = C h^p). ConvergenceError for fewer than
    two levels, h that are not positive and distinct, or an error that is not positive and finite."""
    h, error = _vector(h, "h"), _vector(error, "error")
    if h.size != error.size:
        raise ConvergenceError(f"{h.size} zone sizes but {error.size} errors")
    if h.size < 2:
        raise ConvergenceError(f"an order needs at least two levels ({h.size} given)")
    if not np.all(np.isfinite(h) & (h > 0.0)) or np.unique(h).size != h.size:
        raise ConvergenceError(f"the zone sizes {h.tolist()} must be positive, finite and distinct")
    if not np.all(np.isfinite(error)):
        raise ConvergenceError("an error is not finite (NaN or infinity): no order can be fitted")
    if not np.all(error > 0.0):
        raise ConvergenceError("an error is zero or negative: no order can be fitted on a log scale")
    slope, _ = np.polyfit(np.log(h), np.log(error), 1)
    return float(slope)


@dataclass(frozen=True)
class GCI:
    order: float             # p of the three grids (Celik et al. 2008, eq. for p)
    extrapolated: float      # Richardson extrapolation phi_ext^21
    gci_fine: float          # GCI of the finest grid, a fraction of |phi1|
    asymptotic_ratio: float  # GCI_23 / (r21^p GCI_12), about 1 in the asymptotic range
    oscillatory: bool        # s < 0: the differences change sign


def grid_convergence_index(h, values, safety_factor=SAFETY_FACTOR, tol=1e-12, max_iter=1000):
    """Roache's GCI from exactly three grids (h and values in any order); see the module docstring.
    ConvergenceError when no order can be observed: repeated h, e21 = 0 or e32 = 0, phi1 = 0, values
    that are not finite, or an iteration that does not converge to a positive order."""
    h, values = _vector(h, "h"), _vector(values, "values")
    if h.size != 3 or values.size != 3:
        raise ConvergenceError("the GCI needs exactly three grids: three h and three values")
    if not np.all(np.isfinite(h) & (h > 0.0)) or np.unique(h).size != 3:
        raise ConvergenceError(f"the three zone sizes {h.tolist()} must be positive, finite and distinct")
    if not np.all(np.isfinite(values)):
        raise ConvergenceError("a value is not finite (NaN or infinity)")
    order = np.argsort(h)
    h1, h2, h3 = (float(v) for v in h[order])
    phi1, phi2, phi3 = (float(v) for v in values[order])
    r21, r32 = h2 / h1, h3 / h2
    e21, e32 = phi2 - phi1, phi3 - phi2
    if e21 == 0.0 or e32 == 0.0:
        raise ConvergenceError("two grids give the same value: no order can be observed")
    if phi1 == 0.0:
        raise ConvergenceError("the finest value is 0: the relative GCI is undefined")
    s = math.copysign(1.0, e32 / e21)
    ln_ratio, ln_r21 = math.log(abs(e32 / e21)), math.log(r21)
    p = abs(ln_ratio) / ln_r21
    try:
        for _ in range(max_iter):
            q = math.log((r21 ** p - s) / (r32 ** p - s))
            p_new = abs(ln_ratio + q) / ln_r21
            if abs(p_new - p) <= tol * max(1.0, abs(p_new)):
                p = p_new
                break
            p = p_new
        else:
            raise ConvergenceError(f"the iteration for the order did not converge in {max_iter} steps")
        if not (math.isfinite(p) and p > 0.0):
            raise ConvergenceError(f"the three grids give no positive order (p = {p})")
        f21, f32 = r21 ** p, r32 ** p
        extrapolated = (f21 * phi1 - phi2) / (f21 - 1.0)
        gci_fine = safety_factor * abs(e21 / phi1) / (f21 - 1.0)
        gci_12 = safety_factor * abs(e21) / (f21 - 1.0)
        gci_23 = safety_factor * abs(e32) / (f32 - 1.0)
        ratio = gci_23 / (f21 * gci_12)
    except (ValueError, ZeroDivisionError, OverflowError) as e:
        if isinstance(e, ConvergenceError):
            raise
        raise ConvergenceError(f"the three grids give no order: {type(e).__name__}: {e}") from e
    return GCI(float(p), float(extrapolated), float(gci_fine), float(ratio), s < 0.0)


def _level_problem(name, error, why):
    """Why a level's error cannot be fitted, or "" when it can."""
    if error is None:
        return f"level {name}: no error{' (' + why + ')' if why else ''}"
    if not math.isfinite(error):
        return f"level {name}: the error is not finite (NaN or infinity) and cannot be fitted"
    if error == 0.0:
        return (f"level {name}: the error is exactly 0 and cannot be fitted on a log scale "
                "(is the quantity insensitive to h, or the reference taken from the output?)")
    if error < 0.0:
        return f"level {name}: the error {error:g} is negative and cannot be fitted on a log scale"
    return ""


def convergence_study(names, h, error, numerical, wall_seconds, cycles, expected_order, order_tolerance,
                      asymptotic_levels=None, why=None):
    """The convergence record of a study over the levels that ran (all lists coarsest first).

    error: the studied check's error per level (None when it could not be evaluated; why[i] then
    says why). numerical: its numerical value per level (for the GCI). asymptotic_levels: N, the
    finest N levels used for the fit and the GCI (None: all; more than ran: all that ran). The
    GCI and the ratio come from the three finest of those levels, null when fewer than three.
    """
    n = len(names)
    why = list(why) if why is not None else [""] * n
    used = n if asymptotic_levels is None else max(0, min(int(asymptotic_levels), n))
    record = {"h": [float(v) for v in h], "error": list(error), "wall_seconds": [float(v) for v in wall_seconds],
              "cycles": list(cycles), "numerical": list(numerical), "observed_order": None,
              "expected_order": float(expected_order), "order_tolerance": float(order_tolerance), "gci": None,
              "asymptotic_ratio": None, "levels": list(names), "fit_levels": list(names[n - used:]),
              "gci_order": None, "extrapolated": None, "safety_factor": SAFETY_FACTOR, "pass": False,
              "message": ""}
    notes = []
    problems = [p for p in (_level_problem(names[i], error[i], why[i]) for i in range(n)) if p]
    if n < 2 or used < 2:
        problems.append(f"an order needs at least two levels ({n} ran, {used} used for the fit)")
    if not problems:
        try:
            record["observed_order"] = observed_order(h[n - used:], error[n - used:])
        except ConvergenceError as e:
            problems.append(str(e))
    if used >= 3:
        finest = list(numerical[n - 3:])
        if any(v is None or not math.isfinite(v) for v in finest):
            notes.append("no GCI: a numerical value of the three finest levels is missing or not finite")
        else:
            try:
                result = grid_convergence_index(h[n - 3:], finest)
            except ConvergenceError as e:
                notes.append(f"no GCI: {e}")
            else:
                record.update(gci=result.gci_fine, asymptotic_ratio=result.asymptotic_ratio,
                              gci_order=result.order, extrapolated=result.extrapolated)
                if result.oscillatory:
                    notes.append("oscillatory convergence (the differences of the three finest values change sign)")
    else:
        notes.append(f"no GCI: it needs three levels in the asymptotic range ({used} used)")
    observed = record["observed_order"]
    if problems:
        text = "cannot fit an order: " + "; ".join(problems)
    else:
        record["pass"] = abs(observed - expected_order) <= order_tolerance
        text = (f"observed order {observed:.3f} over levels {', '.join(record['fit_levels'])}; expected "
                f"{expected_order:g} +- {order_tolerance:g}")
        if record["gci"] is not None:
            text += (f"; GCI {record['gci']:.3e} of the finest value (three-grid order {record['gci_order']:.3f}), "
                     f"asymptotic ratio {record['asymptotic_ratio']:.3f}")
    record["message"] = "; ".join([text] + notes)
    return record

"""References for the continuously-yielding (CY) joint: direct shear at constant normal stress and
normal closure.

Sources: P. A. Cundall and R. D. Hart, "Analysis of block test no. 1 inelastic rock mass
behavior: phase 2 - a characterization of joint behavior", Itasca Consulting Group report to
Rockwell Hanford Operations (1984); J. V. Lemos, "A distinct element model for dynamic analysis
of jointed rock with application to dam foundations and fault motion", Ph.D. thesis, University
of Minnesota (1987); NUREG/CR-5429, eqs 1.4-137 to 1.4-145.

Sign conventions: normal stress sn compression positive; normal closure un closing positive;
shear stress tau signed along +us (the shear displacement); the dilatant opening is positive for
opening; us_p is the accumulated plastic shear path (never decreasing). SI units; angles in
degrees where the name ends in _deg.

Direct shear at constant sn (ks constant). Along a monotonic segment of direction d = +-1 and
path length s = |us - us_segment_start|:

    tau_m = d sn tan(phi_eff),   F = (1 - tau/tau_m) / (1 - r)
    dtau/ds = d ks F
    dphi_eff/ds = -(phi_eff - phi) (1 - F) / R
    dus_p/ds = 1 - F
    dopening/ds = (1 - F) tan(max(0, atan(|tau|/sn) - phi))   (dilation with the plastic shear)

from tau = 0, phi_eff = phi0, us_p = 0, opening = 0, r = 0; at each reversal r = min(tau/tau_m,
0.75) with the new direction's tau_m (so F = 1 just after it unless capped). phi is the basic
friction angle, phi0 the initial phi_eff (>= phi), R the roughness (m). With phi0 = phi the
shear stress is tau_m (1 - exp(-ks us / tau_m)) on first loading; with phi0 > phi it peaks
where tau = sn tan(phi_eff) (F = 0), then softens towards sn tan(phi).

There is no closed form for the softening case: it is integrated by vdec_cy_reference
(verification/reference/cy_joint_reference.cpp), a separate program in 50-digit arithmetic with
a high-order extrapolation method, which shares no code with the solver. This module finds it
through $VDEC_CY_REFERENCE (its full path) or, failing that, beside $VDEC_EXECUTABLE (the vdec
binary, next to which the build puts it).

Normal closure. With the stiffness kn(sn) = max(kn0, an sn^en), 0 <= en <= 1, from sn = 0:
dsn/dun = kn(sn). Below s* = (kn0/an)^(1/en) (where an sn^en overtakes kn0), sn = kn0 un; beyond
un* = s*/kn0,

    un - un* = (sn^(1-en) - s*^(1-en)) / (an (1 - en)),
    i.e. sn = (s*^(1-en) + an (1 - en)(un - un*))^(1/(1-en))          (en < 1)
    sn = s* exp(an (un - un*))                                          (en = 1).

For en = 0 the stiffness is the constant max(kn0, an).
"""
import math
import os
import shutil
import subprocess

import numpy as np

CY_COMPONENTS = ("tau", "phi_eff_deg", "us_p", "opening")
# Columns of the reference program's output (see the comment at the top of its source).
_VALUE_COLUMN = {"tau": 1, "phi_eff_deg": 2, "us_p": 3, "opening": 4}
_ERROR_COLUMN = {"tau": 5, "opening": 6, "phi_eff_deg": 7, "us_p": 8}
_REFERENCE_NAME = "vdec_cy_reference"

# The harness asks for several components of one path; each run costs a fraction of a second.
_cache = {}
_CACHE_SIZE = 16


def cy_reference_executable():
    """Full path of vdec_cy_reference: $VDEC_CY_REFERENCE, else the file of that name beside
    $VDEC_EXECUTABLE. Raises FileNotFoundError saying which variable to set when neither works."""
    explicit = os.environ.get("VDEC_CY_REFERENCE")
    if explicit:
        if not (os.path.isfile(explicit) and os.access(explicit, os.X_OK)):
            raise FileNotFoundError(f"VDEC_CY_REFERENCE = {explicit}: no executable file there")
        return explicit
    vdec = os.environ.get("VDEC_EXECUTABLE")
    if vdec:
        # A bare command name is looked up on PATH, as the shell would.
        located = vdec if os.path.dirname(vdec) else (shutil.which(vdec) or vdec)
        candidate = os.path.join(os.path.dirname(os.path.abspath(located)), _REFERENCE_NAME)
        if os.path.isfile(candidate) and os.access(candidate, os.X_OK):
            return candidate
        raise FileNotFoundError(
            f"no {_REFERENCE_NAME} beside VDEC_EXECUTABLE = {vdec} (looked for {candidate}); "
            f"build the CMake target {_REFERENCE_NAME} or set VDEC_CY_REFERENCE")
    raise FileNotFoundError(
        f"the CY joint reference needs the program {_REFERENCE_NAME}: set VDEC_CY_REFERENCE to "
        "its full path, or VDEC_EXECUTABLE to the vdec binary it was built beside")


def reference_programs():
    """The programs this module runs, for the hashes the verification harness records."""
    return [cy_reference_executable()]


def _check_cy_parameters(ks, sn, phi_deg, phi0_deg, roughness):
    if not ks > 0.0:
        raise ValueError(f"ks = {ks}: the shear stiffness must be positive")
    if not sn > 0.0:
        raise ValueError(f"sn = {sn}: the normal stress must be positive (compression)")
    if not 0.0 < phi_deg < 90.0:
        raise ValueError(f"phi = {phi_deg} deg: the basic friction angle must lie in (0, 90)")
    if not phi_deg <= phi0_deg < 90.0:
        raise ValueError(f"phi0 = {phi0_deg} deg: the initial friction angle must lie in "
                         f"[phi = {phi_deg}, 90)")
    if not roughness > 0.0:
        raise ValueError(f"roughness = {roughness}: must be positive (m)")


def _cy_table(us, ks, sn, phi_deg, phi0_deg, roughness, turning_points):
    """The reference program's output for the samples us: one row per sample, the columns
    us tau phi_eff_deg us_p opening err_tau err_opening err_phi_eff_deg err_us_p."""
    us = np.asarray(us, dtype=float)
    ks, sn, phi_deg, phi0_deg, roughness = map(float, (ks, sn, phi_deg, phi0_deg, roughness))
    _check_cy_parameters(ks, sn, phi_deg, phi0_deg, roughness)
    if not np.all(np.isfinite(us)):
        raise ValueError("us must be finite")
    tps = tuple(float(t) for t in turning_points)
    if not all(math.isfinite(t) for t in tps):
        raise ValueError("turning points must be finite")
    flat = us.ravel()
    key = (ks, sn, phi_deg, phi0_deg, roughness, tps, flat.tobytes())
    if key in _cache:
        return _cache[key]
    # repr() is the shortest string that reads back as the same double; the program reads it
    # as an exact decimal, so a sample written like a turning point lands exactly on it.
    args = [cy_reference_executable(), f"--ks={ks!r}", f"--sn={sn!r}", f"--phi={phi_deg!r}",
            f"--phi0={phi0_deg!r}", f"--roughness={roughness!r}"]
    if tps:
        args.append("--turning-points=" + ",".join(repr(t) for t in tps))
    stdin = "".join(f"{float(u)!r}\n" for u in flat)
    done = subprocess.run(args, input=stdin, capture_output=True, text=True, check=False)
    if done.returncode == 2:
        raise ValueError(f"{_REFERENCE_NAME} refused the input: {done.stderr.strip()}")
    if done.returncode != 0:
        raise RuntimeError(f"{_REFERENCE_NAME} failed (exit {done.returncode}): {done.stderr.strip()}")
    table = np.array([[float(x) for x in line.split()] for line in done.stdout.splitlines()],
                     dtype=float).reshape(-1, 9)
    if table.shape[0] != flat.size:
        raise RuntimeError(f"{_REFERENCE_NAME} printed {table.shape[0]} rows for {flat.size} samples")
    if len(_cache) >= _CACHE_SIZE:
        _cache.pop(next(iter(_cache)))
    _cache[key] = table
    return table


def _component_column(component, columns):
    if component not in columns:
        raise ValueError(f"component = {component!r}: must be one of {', '.join(CY_COMPONENTS)}")
    return columns[component]


def continuously_yielding_direct_shear(us, *, ks, sn, phi_deg, phi0_deg, roughness, component,
                                       turning_points=()):
    """One component of the CY joint's response in direct shear at constant normal stress sn
    (equations in the module docstring), at the shear displacements `us` (m), which are samples
    in time order along the path 0 -> turning_points[0] -> turning_points[1] -> ... (from
    us = 0; between two samples the path passes the next turning point when the later sample
    lies beyond it or behind the earlier one).

    Parameters: ks (Pa/m), sn (Pa, compression positive), phi_deg (basic friction),
    phi0_deg (initial phi_eff, >= phi_deg), roughness R (m); component one of
    "tau" (Pa, signed along +us), "phi_eff_deg", "us_p" (accumulated plastic shear path, m),
    "opening" (dilatant normal opening, m, positive = opening).

    Returns an array shaped like us. The values come from the 50-digit reference program;
    continuously_yielding_direct_shear_error gives their error bound (far below double
    precision). Raises ValueError for bad parameters or a path the turning points do not allow,
    FileNotFoundError when the program cannot be found (see cy_reference_executable).
    """
    column = _component_column(component, _VALUE_COLUMN)
    table = _cy_table(us, ks, sn, phi_deg, phi0_deg, roughness, turning_points)
    return table[:, column].reshape(np.shape(us))


def continuously_yielding_direct_shear_error(us, *, ks, sn, phi_deg, phi0_deg, roughness,
                                             component, turning_points=()):
    """The reference's own error estimate for continuously_yielding_direct_shear (same
    arguments), in the component's units: the absolute difference between the printed solution
    (order 24 extrapolation at tolerance 1e-42) and an independent run (order 18 at 1e-32). The
    second run is the less accurate one, so this bounds the printed values' error."""
    column = _component_column(component, _ERROR_COLUMN)
    table = _cy_table(us, ks, sn, phi_deg, phi0_deg, roughness, turning_points)
    return table[:, column].reshape(np.shape(us))


def continuously_yielding_block_rise(us, *, ks, kn, sn, phi_deg, phi0_deg, roughness, turning_points=()):
    """Height of a block sheared under a dead normal load on a joint of constant normal stiffness
    kn (Pa/m), measured from where its face first touched (positive up): the elastic closure
    -sn/kn plus the dilatant opening of continuously_yielding_direct_shear."""
    if not kn > 0.0:
        raise ValueError(f"kn = {kn}: the normal stiffness must be positive")
    opening = continuously_yielding_direct_shear(us, ks=ks, sn=sn, phi_deg=phi_deg, phi0_deg=phi0_deg,
                                                 roughness=roughness, component="opening",
                                                 turning_points=turning_points)
    return -sn / kn + opening


# ---------------------------------------------------------------- normal closure


def _check_closure_parameters(kn0, an, en):
    if not kn0 > 0.0:
        raise ValueError(f"kn0 = {kn0}: the zero-stress normal stiffness must be positive")
    if not an > 0.0:
        raise ValueError(f"an = {an}: the stiffness coefficient must be positive")
    if not 0.0 <= en <= 1.0:
        raise ValueError(f"en = {en}: the stiffness exponent must lie in [0, 1]")


def _closure_threshold(kn0, an, en):
    """(s*, un*): the normal stress where an sn^en overtakes kn0, and the closure there; s* is
    infinite when kn0 stays the larger (en = 0 with an <= kn0, or an overflow)."""
    if en == 0.0:
        s_star = math.inf if an <= kn0 else 0.0
    else:
        log_s = math.log(kn0 / an) / en
        s_star = math.exp(log_s) if log_s < 709.0 else math.inf
    return s_star, s_star / kn0


def continuously_yielding_normal_closure(un, *, kn0, an, en):
    """Normal stress sn (Pa, compression positive) of a CY joint closed by un (m, closing
    positive) from sn = 0, with kn(sn) = max(kn0, an sn^en) (module docstring): sn = kn0 un up to
    un* = s*/kn0, then the power-law (en < 1) or exponential (en = 1) branch.

    Parameters: kn0 (Pa/m), an (Pa^(1-en)/m), en in [0, 1]. Returns an array shaped like un.
    """
    kn0, an, en = float(kn0), float(an), float(en)
    _check_closure_parameters(kn0, an, en)
    un = np.asarray(un, dtype=float)
    if np.any(~(un >= 0.0)):
        raise ValueError("un must be a closure (>= 0, closing positive, from sn = 0)")
    s_star, un_star = _closure_threshold(kn0, an, en)
    sn = np.array(kn0 * un, dtype=float)
    beyond = un > un_star
    extra = un[beyond] - un_star
    if en == 1.0:
        sn[beyond] = s_star * np.exp(an * extra)
    else:
        sn[beyond] = (s_star ** (1.0 - en) + an * (1.0 - en) * extra) ** (1.0 / (1.0 - en))
    return sn


def continuously_yielding_closure_of_stress(sn, *, kn0, an, en):
    """The inverse of continuously_yielding_normal_closure: the closure un (m, closing positive)
    at which the normal stress reaches sn (Pa, >= 0):

        un = sn/kn0 (sn <= s*),  un* + (sn^(1-en) - s*^(1-en)) / (an (1 - en)) (en < 1),
        un* + ln(sn/s*) / an (en = 1).
    """
    kn0, an, en = float(kn0), float(an), float(en)
    _check_closure_parameters(kn0, an, en)
    sn = np.asarray(sn, dtype=float)
    if np.any(~(sn >= 0.0)) or np.any(~np.isfinite(sn)):
        raise ValueError("sn must be a finite compressive normal stress (>= 0)")
    s_star, un_star = _closure_threshold(kn0, an, en)
    un = np.array(sn / kn0, dtype=float)
    beyond = sn > s_star
    high = sn[beyond]
    if en == 1.0:
        un[beyond] = un_star + np.log(high / s_star) / an
    else:
        un[beyond] = un_star + (high ** (1.0 - en) - s_star ** (1.0 - en)) / (an * (1.0 - en))
    return un

"""Closed-form references for rock support (issue 15, "Verification"): grouted cables, frame beams,
beams on an elastic foundation, bolts across a joint, a tunnel lining in an elastic medium and a
roof wedge held by cables.

Independent of the solver: only math, numpy and scipy are used. Every formula is either taken from
the cited text or derived in its docstring in a few lines; where the model the solver integrates is
discrete (springs at nodes, lumped masses), the discrete answer is given next to the continuum one,
in closed form where one exists (the cable's recurrence, the trapezoidal sums of the beams) or by a
small linear or eigenvalue problem solved with numpy/scipy, so that the solver can be held to
round-off at any number of elements and the continuum to a stated discretisation error.

Model (NUREG/CR-5429 1.2.6 and 1.4.4, 1.4-34 to 1.4-59): plane frame elements (Euler-Bernoulli:
no shear deformation, no rotary inertia unless stated), stiffness EA/h, 12EI/h^3, 6EI/h^2, 4EI/h,
2EI/h; masses lumped at the nodes; a cable of axial stiffness EA bonded to the rock by a grout
spring-slider per unit length (stiffness k_bond, strength s_bond); local reinforcement with the
orientation-dependent shear limit of 1.4-40.

Sign conventions (stated again at each function): beam deflection w POSITIVE IN THE DIRECTION OF THE
LOAD, rotation dw/dx, bending moment M = -EI w'' (sagging positive for a downward load); cable
axial force TENSION POSITIVE, cable displacement s positive towards the head (out of the hole);
lining pressures and thrust COMPRESSION POSITIVE, radial displacement positive INWARD (convergence).
SI units: m, N, Pa; per unit length of beam or cable: q and s_bond in N/m, k (Winkler) and k_bond in
N/m per m of length (N/m^2); per unit length of tunnel: thrust in N/m, the wedge weight in N/m.
Angles are in degrees where the argument ends in _deg.
Every function takes keyword arguments only, but the coordinate x along a beam or a cable, which
comes first, as the harness passes it for a series; field functions accept numpy arrays.
Nonsensical input (a negative length, EI <= 0, x off the member, a load beyond the capacity, ...) is a
ValueError naming the argument.

Sources: S. P. Timoshenko and J. M. Gere, Mechanics of Materials (the cantilever and simply supported
beam formulas, any edition: "T&G"); R. D. Blevins, Formulas for Natural Frequency and Mode Shape, 1979,
the chapter on straight beams (the cantilever's beta_n L = 1.87510407, 4.69409113, 7.85475744,
10.99554073); M. Hetenyi, Beams on Elastic Foundation, University of Michigan Press, 1946 (the infinite
beam under a concentrated load); H. H. Einstein and C. W. Schwartz, "Simplified analysis for tunnel
supports", J. Geotech. Eng. Div. ASCE 105(GT4), 1979, 499-518 (the compressibility ratio C); S.
Bjurstrom (cited as 1979 in NUREG/CR-5429; the paper usually cited for the bolt formula is "Shear
strength of hard rock joints reinforced by grouted untensioned bolts", 3rd ISRM Congress, Denver,
1974); NUREG/CR-5429 Vol. 1 1.4.4 (1.4-38 to 1.4-44, the reinforcement and grout laws). Chapter and
table numbers and the exact wording of the books were not checked against them (they were not at
hand): every formula is derived here in a few lines and verified independently in
tests/python/test_analytic_structures.py (a linear solve, an eigenvalue problem on another route,
solve_bvp, quadrature, finite differences of the returned fields, vector equilibrium), so a
misquoted source would show there.
"""
import math

import numpy as np
from scipy import linalg, optimize


def _scalar(name, value):
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {value!r}: must be a number") from None
    if not math.isfinite(value):
        raise ValueError(f"{name} = {value}: must be finite")
    return value


def _positive(name, value):
    value = _scalar(name, value)
    if not value > 0.0:
        raise ValueError(f"{name} = {value}: must be positive")
    return value


def _non_negative(name, value):
    value = _scalar(name, value)
    if not value >= 0.0:
        raise ValueError(f"{name} = {value}: must be zero or positive")
    return value


def _count(name, value, smallest=1):
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < smallest:
        raise ValueError(f"{name} = {value!r}: must be a whole number >= {smallest}")
    return int(value)


def _along(x, length, what="member"):
    """x as an array, refused unless 0 <= x <= length (the member's own coordinate)."""
    x = np.asarray(x, dtype=float)
    if np.any(~((x >= 0.0) & (x <= length))):
        raise ValueError(f"x = {x}: must lie on the {what}, 0 <= x <= L = {length}")
    return x


def _angle(name, degrees, low, high):
    degrees = _scalar(name, degrees)
    if not low <= degrees <= high:
        raise ValueError(f"{name} = {degrees}: must lie in [{low}, {high}] degrees")
    return math.radians(degrees)


# ================================================================ grouted cable, elastic bond
#
# A cable 0 <= x <= L, pulled at its head x = 0 by F0 (tension), in rigid rock. The grout is a
# spring per unit length: the force per unit length on the cable is k_bond s, s(x) the cable's
# displacement towards the head. The axial force F = -EA ds/dx (tension when s falls away from
# the head), and a slice dx in equilibrium: dF/dx = k_bond s, so EA s'' = k_bond s.
# With alpha = sqrt(k_bond / EA) and the far end free, F(L) = 0 and F(0) = F0:
#
#     s(x) = F0 cosh(alpha (L - x)) / (EA alpha sinh(alpha L)),   F(x) = F0 sinh(alpha (L - x)) / sinh(alpha L).
#
# The head stiffness F0 / s(0) = EA alpha tanh(alpha L): the tanh is right for a FREE far
# end (it tends to k_bond L, the bond of a rigid bar, as alpha L -> 0). With the far end ANCHORED
# (s(L) = 0) instead, s = F0 sinh(alpha (L - x)) / (EA alpha cosh(alpha L)),
# F = F0 cosh(alpha (L - x)) / cosh(alpha L) and the head stiffness is EA alpha coth(alpha L)
# (-> EA / L, a bar fixed at its end, as alpha L -> 0). Both tend to EA alpha for a long cable.

_FAR_ENDS = ("free", "anchored")


def _cable(L, EA, k_bond):
    L, EA, k_bond = _positive("L (cable length)", L), _positive("EA", EA), _positive("k_bond", k_bond)
    return L, EA, math.sqrt(k_bond / EA)


def _far_end(far_end):
    if far_end not in _FAR_ENDS:
        raise ValueError(f"far_end = {far_end!r}: must be one of {', '.join(_FAR_ENDS)}")
    return far_end


def cable_alpha(*, EA, k_bond):
    """alpha = sqrt(k_bond / EA) (1/m), the inverse of the length over which the bond takes up an
    elastic cable's load."""
    return math.sqrt(_positive("k_bond", k_bond) / _positive("EA", EA))


def cable_elastic_force(x, *, F0, L, EA, k_bond, far_end="free"):
    """Axial force (tension positive) along a fully grouted elastic cable pulled at x = 0 by F0,
    the grout an elastic spring k_bond per unit length on rigid rock (derivation above):

        far_end = "free":      F(x) = F0 sinh(alpha (L - x)) / sinh(alpha L)
        far_end = "anchored":  F(x) = F0 cosh(alpha (L - x)) / cosh(alpha L)

    alpha = sqrt(k_bond / EA). Computed with exponentials of -alpha x and -alpha (L - x) so that
    long cables (alpha L of hundreds) do not overflow.
    """
    F0 = _scalar("F0", F0)
    L, EA, alpha = _cable(L, EA, k_bond)
    x = _along(x, L, "cable")
    sign = -1.0 if _far_end(far_end) == "free" else 1.0
    # sinh(a(L-x)) / sinh(aL) = (e^{-a x} - e^{-a(2L-x)}) / (1 - e^{-2aL}), and cosh likewise.
    return F0 * (np.exp(-alpha * x) + sign * np.exp(-alpha * (2.0 * L - x))) / (1.0 + sign * math.exp(-2.0 * alpha * L))


def cable_elastic_displacement(x, *, F0, L, EA, k_bond, far_end="free"):
    """Displacement towards the head (pull-out positive) along the elastic cable of
    cable_elastic_force: s = -(1/EA) integral of F, with s(L) from the far end's condition:

        free:      s(x) = F0 cosh(alpha (L - x)) / (EA alpha sinh(alpha L))
        anchored:  s(x) = F0 sinh(alpha (L - x)) / (EA alpha cosh(alpha L))
    """
    F0 = _scalar("F0", F0)
    L, EA, alpha = _cable(L, EA, k_bond)
    x = _along(x, L, "cable")
    sign = 1.0 if _far_end(far_end) == "free" else -1.0
    return F0 / (EA * alpha) * (np.exp(-alpha * x) + sign * np.exp(-alpha * (2.0 * L - x))) \
        / (1.0 - sign * math.exp(-2.0 * alpha * L))


def cable_head_stiffness(*, L, EA, k_bond, far_end="free"):
    """F0 / s(0) of the elastic cable: EA alpha tanh(alpha L) with the far end free (the issue's
    formula), EA alpha coth(alpha L) with it anchored (derivation above)."""
    L, EA, alpha = _cable(L, EA, k_bond)
    t = math.tanh(alpha * L)
    return EA * alpha * (t if _far_end(far_end) == "free" else 1.0 / t)


# ---------------------------------------------------------------- the discrete cable
#
# The model the solver integrates: nodes x_i = i h, h = L / n, i = 0..n; axial springs EA / h
# between neighbours; a bond spring at every node of stiffness k_bond h, HALF (k_bond h / 2) at the
# two end nodes (the trapezoidal rule: each node carries the grout of the half segments beside it);
# F0 at node 0, rigid rock. At an interior node, (EA/h)(s_{i-1} - 2 s_i + s_{i+1}) = k_bond h s_i:
#
#     s_{i-1} + s_{i+1} = 2 cosh(theta) s_i,    cosh(theta) = 1 + alpha^2 h^2 / 2,
#
# solved by cosh(theta (n - i)) and sinh(theta (n - i)). The free end node, (EA/h)(s_{n-1} - s_n) =
# (k_bond h / 2) s_n, is s_{n-1} = cosh(theta) s_n: only the cosh remains, s_i = A cosh(theta (n - i)).
# The head node, F0 = (EA/h)(s_0 - s_1) + (k_bond h / 2) s_0 with k_bond h / 2 = (EA/h)(cosh theta - 1),
# gives F0 = (EA/h) A (cosh theta cosh n theta - cosh (n-1) theta) = (EA/h) A sinh theta sinh n theta:
#
#     s_i = F0 h cosh(theta (n - i)) / (EA sinh(theta) sinh(n theta)),
#     F_{i+1/2} = (EA/h)(s_i - s_{i+1}) = F0 sinh(theta (n - i - 1/2)) / (cosh(theta/2) sinh(n theta)),
#     head stiffness (EA/h) sinh(theta) tanh(n theta).
#
# With n - i = (L - x)/h these are functions of x, exact at the nodes (s) and at the segments'
# midpoints (F). As h -> 0, theta / h -> alpha and they tend to the continuum with an error O(h^2).


def _discrete_cable(L, EA, k_bond, n):
    L, EA, alpha = _cable(L, EA, k_bond)
    n = _count("n (number of cable segments)", n)
    h = L / n
    theta = math.acosh(1.0 + 0.5 * (alpha * h) ** 2)
    return L, EA, h, theta, n


def cable_discrete_theta(*, L, EA, k_bond, n):
    """theta of the discrete cable, cosh(theta) = 1 + alpha^2 h^2 / 2, h = L / n: its decay per segment
    (alpha h for fine segments)."""
    return _discrete_cable(L, EA, k_bond, n)[3]


def cable_discrete_displacement(x, *, F0, L, EA, k_bond, n):
    """Nodal displacement (towards the head) of the discrete elastic cable of n segments, far end
    free, bond springs k_bond h at the nodes and half at the two ends (derivation above):

        s(x) = F0 h cosh(theta (L - x) / h) / (EA sinh(theta) sinh(n theta)),  cosh(theta) = 1 + (alpha h)^2 / 2

    exact at the nodes x = i h (between them it is not the solver's linear interpolation)."""
    F0 = _scalar("F0", F0)
    L, EA, h, theta, n = _discrete_cable(L, EA, k_bond, n)
    x = _along(x, L, "cable")
    # cosh(theta m) / sinh(theta n) with m = (L - x)/h <= n, by exponentials that do not overflow.
    m = (L - x) / h
    ratio = (np.exp(theta * (m - n)) + np.exp(-theta * (m + n))) / (1.0 - math.exp(-2.0 * theta * n))
    return F0 * h / (EA * math.sinh(theta)) * ratio


def cable_discrete_force(x, *, F0, L, EA, k_bond, n):
    """Axial force (tension positive) in the segments of the discrete elastic cable (derivation above):

        F(x) = F0 sinh(theta (L - x) / h) / (cosh(theta / 2) sinh(n theta))

    exact at the segments' midpoints x = (i + 1/2) h, where the solver's segment forces belong."""
    F0 = _scalar("F0", F0)
    L, EA, h, theta, n = _discrete_cable(L, EA, k_bond, n)
    x = _along(x, L, "cable")
    m = (L - x) / h
    ratio = (np.exp(theta * (m - n)) - np.exp(-theta * (m + n))) / (1.0 - math.exp(-2.0 * theta * n))
    return F0 * ratio / math.cosh(0.5 * theta)


def cable_discrete_head_stiffness(*, L, EA, k_bond, n):
    """F0 / s_0 of the discrete elastic cable: (EA / h) sinh(theta) tanh(n theta) (derivation above);
    it tends to EA alpha tanh(alpha L) as n grows."""
    L, EA, h, theta, n = _discrete_cable(L, EA, k_bond, n)
    return EA / h * math.sinh(theta) * math.tanh(n * theta)


# ================================================================ grouted cable, bond that slips
#
# The grout a spring-slider: the bond force per unit length is k_bond s up to s_bond (N/m), then
# stays at s_bond (perfectly plastic). Under a monotonically growing F0 the displacement falls
# monotonically from the head, so the bond has slipped on 0 <= x <= a and is elastic beyond. There:
#   slipped part:  dF/dx = s_bond, F(x) = F_a + s_bond (a - x);
#   elastic part:  the free-end cable of length L - a pulled by F_a (above), its slip starting at a:
#                  k_bond s(a) = s_bond with s(a) = F_a coth(alpha (L - a)) / (EA alpha), so
#                  F_a = (s_bond / alpha) tanh(alpha (L - a))   (EA alpha / k_bond = 1 / alpha).
# Hence F0 = s_bond a + (s_bond / alpha) tanh(alpha (L - a)), whose derivative in a is
# s_bond tanh^2(alpha (L - a)) >= 0: a grows from 0 at the first slip, F0 = (s_bond / alpha) tanh(alpha L),
# to L at the pull-out capacity F0 = s_bond L. The head displacement is the elastic part's
# s(a) = s_bond / k_bond plus the slipped part's stretch (1/EA) integral_0^a F dx:
#
#     s(0) = s_bond / k_bond + (F_a a + s_bond a^2 / 2) / EA.
#
# The bond law is path independent under monotone loading (no node unloads), which is what this is.


def _slipping_cable(F0, L, EA, k_bond, s_bond):
    F0 = _non_negative("F0", F0)
    L, EA, alpha = _cable(L, EA, k_bond)
    s_bond = _positive("s_bond (bond strength per unit length)", s_bond)
    if F0 > s_bond * L:
        raise ValueError(f"F0 = {F0}: beyond the pull-out capacity s_bond L = {s_bond * L}; the cable pulls out")
    return F0, L, EA, alpha, s_bond


def cable_first_slip_force(*, L, EA, k_bond, s_bond):
    """The head force at which the bond first slips (at the head): (s_bond / alpha) tanh(alpha L)."""
    L, EA, alpha = _cable(L, EA, k_bond)
    return _positive("s_bond (bond strength per unit length)", s_bond) / alpha * math.tanh(alpha * L)


def cable_pullout_capacity(*, L, s_bond):
    """The peak pull-out force of the spring-slider bond: s_bond L (the whole length slipping)."""
    return _positive("s_bond (bond strength per unit length)", s_bond) * _positive("L (cable length)", L)


def grout_bond_stiffness(*, G_g, D, t):
    """The grout annulus's bond stiffness per unit length (N/m per m), 1.4-42: 2 pi G_g / ln(1 + 2t/D),
    G_g the grout's shear modulus, D the bar's diameter, t the annulus's thickness. Derivation: a
    force F' per unit length crossing the annulus D/2 <= r <= D/2 + t puts the shear stress
    F' / (2 pi r) on each cylinder r, the strain du/dr = F' / (2 pi r G_g), and the relative displacement
    of bar and rock is (F' / 2 pi G_g) ln((D/2 + t) / (D/2))."""
    D, t = _positive("D (bar diameter)", D), _positive("t (annulus thickness)", t)
    return 2.0 * math.pi * _positive("G_g (grout shear modulus)", G_g) / math.log1p(2.0 * t / D)


def grout_bond_strength(*, D, t, tau_peak):
    """The grout annulus's bond strength per unit length (N/m), 1.4-44: pi (D + 2t) tau_peak, the peak
    shear stress on the grout-rock interface (the annulus's outer perimeter)."""
    D, t = _positive("D (bar diameter)", D), _positive("t (annulus thickness)", t)
    return math.pi * (D + 2.0 * t) * _positive("tau_peak (peak bond shear stress)", tau_peak)


def cable_slip_length(*, F0, L, EA, k_bond, s_bond):
    """The slipped length a from the head, the root of F0 = s_bond a + (s_bond / alpha) tanh(alpha (L - a))
    (derivation above): 0 up to the first slip, L at the capacity s_bond L. Brent's method to round-off."""
    F0, L, EA, alpha, s_bond = _slipping_cable(F0, L, EA, k_bond, s_bond)
    if F0 <= s_bond / alpha * math.tanh(alpha * L):
        return 0.0
    if F0 == s_bond * L:
        return L
    return optimize.brentq(lambda a: s_bond * a + s_bond / alpha * math.tanh(alpha * (L - a)) - F0,
                           0.0, L, xtol=1e-15 * L, rtol=4.0 * np.finfo(float).eps)


def cable_slip_force(x, *, F0, L, EA, k_bond, s_bond):
    """Axial force (tension positive) along the cable with a slipping bond, far end free (derivation
    above): F0 - s_bond x over the slipped length a, F_a sinh(alpha (L - x)) / sinh(alpha (L - a))
    beyond, F_a = (s_bond / alpha) tanh(alpha (L - a)). Below the first slip it is cable_elastic_force."""
    F0, L, EA, alpha, s_bond = _slipping_cable(F0, L, EA, k_bond, s_bond)
    x = _along(x, L, "cable")
    a = cable_slip_length(F0=F0, L=L, EA=EA, k_bond=k_bond, s_bond=s_bond)
    if a == 0.0:
        return cable_elastic_force(x, F0=F0, L=L, EA=EA, k_bond=k_bond)
    slipped = F0 - s_bond * x
    rest = L - a
    if rest == 0.0:
        return slipped
    F_a = s_bond / alpha * math.tanh(alpha * rest)
    xe = np.clip(x - a, 0.0, rest)
    elastic = F_a * (np.exp(-alpha * xe) - np.exp(-alpha * (2.0 * rest - xe))) / (1.0 - math.exp(-2.0 * alpha * rest))
    return np.where(x <= a, slipped, elastic)


def cable_slip_head_displacement(*, F0, L, EA, k_bond, s_bond):
    """Head displacement of the cable with a slipping bond: s_bond / k_bond + (F_a a + s_bond a^2 / 2) / EA
    once it slips (derivation above), F0 / (EA alpha tanh(alpha L)) before."""
    F0, L, EA, alpha, s_bond = _slipping_cable(F0, L, EA, k_bond, s_bond)
    a = cable_slip_length(F0=F0, L=L, EA=EA, k_bond=k_bond, s_bond=s_bond)
    if a == 0.0:
        return F0 / cable_head_stiffness(L=L, EA=EA, k_bond=k_bond)
    F_a = s_bond / alpha * math.tanh(alpha * (L - a))
    return s_bond / _positive("k_bond", k_bond) + (F_a * a + 0.5 * s_bond * a * a) / EA


def cable_discrete_slip(*, F0, L, EA, k_bond, s_bond, n):
    """The discrete cable of cable_discrete_displacement (n segments, far end free, bond springs
    k_bond h at the nodes and half at the two ends) with each bond spring a spring-slider capped at
    s_bond h (half at the ends), under a monotonically applied head force F0 <= s_bond L.

    The nodes that slip are a run from the head (the displacement falls along the cable), so the
    slipped count m is the one for which the linear system with nodes 0..m-1 carrying their cap and
    nodes m..n their elastic spring gives k_bond s_i >= s_bond on the first and <= s_bond on the
    others; m is found by trying m = 0, 1, ..., and each system is tridiagonal (solved by
    scipy.linalg.solve_banded). Returns a dict: "x_nodes", "displacement" (towards the head),
    "x_segments" (midpoints), "force" (segment forces, tension positive), "slipped_nodes" (m),
    "bond_force" (per node, N).
    """
    F0, L, EA, alpha, s_bond = _slipping_cable(F0, L, EA, k_bond, s_bond)
    n = _count("n (number of cable segments)", n)
    h = L / n
    share = np.full(n + 1, h)
    share[[0, -1]] = 0.5 * h
    spring, cap = k_bond * share, s_bond * share
    axial = EA / h
    for m in range(n + 1):
        # Rows of (K) s = f; the slipped nodes' bond forces are loads, their springs gone.
        bands = np.zeros((3, n + 1))
        bands[1] = 2.0 * axial
        bands[1, [0, -1]] = axial
        bands[0, 1:] = -axial
        bands[2, :-1] = -axial
        bands[1, m:] += spring[m:]
        f = -cap.copy()
        f[m:] = 0.0
        f[0] += F0
        s = linalg.solve_banded((1, 1), bands, f)
        slipped_ok = np.all(k_bond * s[:m] >= s_bond * (1.0 - 1e-12))
        elastic_ok = np.all(k_bond * s[m:] <= s_bond * (1.0 + 1e-12))
        if slipped_ok and elastic_ok:
            bond = np.where(np.arange(n + 1) < m, cap, spring * s)
            return {"x_nodes": np.arange(n + 1) * h, "displacement": s, "x_segments": (np.arange(n) + 0.5) * h,
                    "force": axial * (s[:-1] - s[1:]), "slipped_nodes": m, "bond_force": bond}
    raise ValueError(f"F0 = {F0}: no consistent slipped length found (F0 at the capacity s_bond L = {s_bond * L}?)")



def cable_discrete_slip_segment_force(x, *, F0, L, EA, k_bond, s_bond, n):
    """The segment force of cable_discrete_slip in the segment holding x (0 <= x <= L; a node
    belongs to the segment beyond it, the last node to the last segment): the scalar form a
    benchmark compares one element with."""
    x = _scalar("x", x)
    _along(x, _positive("L (cable length)", L), "cable")
    cable = cable_discrete_slip(F0=F0, L=L, EA=EA, k_bond=k_bond, s_bond=s_bond, n=n)
    segment = min(int(x / (L / n)), n - 1)
    return float(cable["force"][segment])


def cable_discrete_slip_head_displacement(*, F0, L, EA, k_bond, s_bond, n):
    """The head's displacement (towards the head) of cable_discrete_slip."""
    return float(cable_discrete_slip(F0=F0, L=L, EA=EA, k_bond=k_bond, s_bond=s_bond, n=n)["displacement"][0])

# ================================================================ frame beams (Euler-Bernoulli)
#
# Deflection w positive in the direction of the load, rotation dw/dx, moment M = -EI w''.
# A cantilever is clamped at x = 0 and free at x = L; a simply supported beam is pinned at both ends.
#
# Point loads and the frame element. The frame element's bending shape functions are the cubic
# Hermite polynomials, and between point loads (and moments) the exact deflection of an
# Euler-Bernoulli beam is a cubic (EI w'''' = 0): the element can represent it, and the nodal values
# of the stiffness method are then exact for any number of elements (the element stiffness is built
# from the exact homogeneous solution). A cantilever of n frame elements under a tip load has the
# continuum's tip deflection P L^3 / 3EI and rotation P L^2 / 2EI, for n = 1 as for n = 100.
#
# Distributed loads lumped at the nodes. The solver applies self-weight and other distributed loads
# as nodal forces (q h at a node, q h / 2 at the ends); the nodal deflections are then exactly those
# of the beam under these point loads, the sum over nodes of q h_j G(x, x_j) with G the influence
# function of a unit point load: the trapezoidal rule for integral q G(x, s) ds. For a cubic G(s) the
# trapezoidal error is exactly (h^2 / 12)(G'(b) - G'(a)) (Euler-Maclaurin, the h^4 term has G''',
# constant, cancelling), which gives the closed forms below.


def _beam(L, E, I):
    return _positive("L (beam length)", L), _positive("E", E), _positive("I (second moment of area)", I)


def cantilever_tip_deflection(*, P, L, E, I):
    """Tip deflection of a cantilever under a tip load P: P L^3 / 3EI (T&G). Exact also at the tip of
    a cantilever of any number of frame elements (module notes above)."""
    L, E, I = _beam(L, E, I)
    return _scalar("P", P) * L ** 3 / (3.0 * E * I)


def cantilever_tip_rotation(*, P, L, E, I):
    """Tip rotation of a cantilever under a tip load P: P L^2 / 2EI (T&G), exact for frame elements."""
    L, E, I = _beam(L, E, I)
    return _scalar("P", P) * L ** 2 / (2.0 * E * I)


def cantilever_point_load_deflection(x, *, P, L, E, I):
    """Deflection along a cantilever under a tip load: w = P x^2 (3L - x) / 6EI (T&G); the nodal values
    of frame elements equal it exactly."""
    L, E, I = _beam(L, E, I)
    x = _along(x, L, "beam")
    return _scalar("P", P) * x * x * (3.0 * L - x) / (6.0 * E * I)


def cantilever_elements_tip(*, P, L, E, I, elements):
    """Tip deflection and rotation (dict "deflection", "rotation") of a cantilever of `elements` equal
    Euler-Bernoulli frame elements under a tip load P: P L^3 / 3EI and P L^2 / 2EI whatever the number
    of elements, since cubic elements hold the exact (cubic) solution (module notes above). The
    number of elements is an argument so that a benchmark states the model it compares; it is
    checked, not used."""
    _count("elements", elements)
    return {"deflection": cantilever_tip_deflection(P=P, L=L, E=E, I=I),
            "rotation": cantilever_tip_rotation(P=P, L=L, E=E, I=I)}


def cantilever_uniform_deflection(x, *, q, L, E, I):
    """Deflection along a cantilever under a uniform load q (N/m): w = q x^2 (6L^2 - 4Lx + x^2) / 24EI
    (T&G); the tip q L^4 / 8EI."""
    L, E, I = _beam(L, E, I)
    x = _along(x, L, "beam")
    return _scalar("q", q) * x * x * (6.0 * L * L - 4.0 * L * x + x * x) / (24.0 * E * I)


def cantilever_uniform_rotation(x, *, q, L, E, I):
    """Rotation dw/dx along a cantilever under a uniform load: q x (3L^2 - 3Lx + x^2) / 6EI; the tip q L^3 / 6EI."""
    L, E, I = _beam(L, E, I)
    x = _along(x, L, "beam")
    return _scalar("q", q) * x * (3.0 * L * L - 3.0 * L * x + x * x) / (6.0 * E * I)


def cantilever_lumped_uniform_tip(*, q, L, E, I, elements):
    """Tip deflection and rotation (dict "deflection", "rotation") of a cantilever of n = `elements`
    equal frame elements whose uniform load q is lumped at the nodes (q h, q h / 2 at the ends, h = L/n):

        deflection = (q L^4 / 8EI) (1 + 1 / (3 n^2)),   rotation = (q L^3 / 6EI) (1 + 1 / (2 n^2)).

    Derivation (module notes above): the tip deflection under a unit load at s is
    G(s) = s^2 (3L - s) / 6EI, G'(L) - G'(0) = L^2 / 2EI, so the trapezoidal sum adds
    q (h^2 / 12) L^2 / 2EI = (q L^4 / 8EI) / (3 n^2); the tip rotation under a unit load at s is
    s^2 / 2EI, derivative L / EI at L, adding q (h^2 / 12) L / EI = (q L^3 / 6EI) / (2 n^2).
    n = 1 (q L / 2 at the tip): q L^4 / 6EI = (q L^4 / 8EI)(4/3). Exact for frame elements."""
    L, E, I = _beam(L, E, I)
    n = _count("elements", elements)
    q = _scalar("q", q)
    return {"deflection": q * L ** 4 / (8.0 * E * I) * (1.0 + 1.0 / (3.0 * n * n)),
            "rotation": q * L ** 3 / (6.0 * E * I) * (1.0 + 1.0 / (2.0 * n * n))}


def simply_supported_uniform_deflection(x, *, q, L, E, I):
    """Deflection of a simply supported beam under a uniform load q: w = q x (L^3 - 2 L x^2 + x^3) / 24EI
    (T&G); at midspan 5 q L^4 / 384EI."""
    L, E, I = _beam(L, E, I)
    x = _along(x, L, "beam")
    return _scalar("q", q) * x * (L ** 3 - 2.0 * L * x * x + x ** 3) / (24.0 * E * I)


def simply_supported_uniform_moment(x, *, q, L):
    """Bending moment (sagging positive, M = -EI w'') of a simply supported beam under a uniform load:
    M = q x (L - x) / 2, q L^2 / 8 at midspan (statics)."""
    L = _positive("L (beam length)", L)
    x = _along(x, L, "beam")
    return _scalar("q", q) * x * (L - x) / 2.0


def simply_supported_midspan_deflection(*, q, L, E, I):
    """5 q L^4 / 384EI (T&G)."""
    L, E, I = _beam(L, E, I)
    return 5.0 * _scalar("q", q) * L ** 4 / (384.0 * E * I)


def simply_supported_lumped_midspan_deflection(*, q, L, E, I, elements):
    """Midspan deflection of a simply supported beam of n = `elements` equal frame elements (n even,
    so that a node sits at midspan) whose uniform load is lumped at the nodes (q h, q h / 2 at the
    supports, where it goes straight into them):

        w(L/2) = (q L^4 / 384EI) (5 - 4 / n^2).

    Derivation (module notes above): the midspan deflection under a unit load at s <= L/2 is
    G(s) = s (3L^2 - 4 s^2) / 48EI, symmetric about L/2; the trapezoidal sum over each half adds
    (h^2 / 12)(G'(L/2) - G'(0)) = (h^2 / 12)(0 - L^2 / 16EI), twice: -q h^2 L^2 / 96EI =
    -(q L^4 / 384EI)(4 / n^2). n = 2 (q L / 2 at midspan): P L^3 / 48EI = q L^4 / 96EI = 4 q L^4 / 384EI.
    Exact for frame elements."""
    L, E, I = _beam(L, E, I)
    n = _count("elements", elements, smallest=2)
    if n % 2:
        raise ValueError(f"elements = {n}: must be even, so that a node lies at midspan")
    return _scalar("q", q) * L ** 4 / (384.0 * E * I) * (5.0 - 4.0 / (n * n))


# ---------------------------------------------------------------- cantilever natural frequencies
#
# Continuum: EI w'''' = rho A omega^2 w with w = w' = 0 at the root and w'' = w''' = 0 at the tip gives
# the characteristic equation 1 + cos(beta L) cosh(beta L) = 0, beta^4 = rho A omega^2 / EI, so
# f_n = (beta_n L)^2 / (2 pi) sqrt(EI / (rho A L^4)) (Blevins table 8-1: 1.87510407, 4.69409113,
# 7.85475744, 10.99554073, then (2n - 1) pi / 2 to within e^{-(2n-1) pi / 2}).
# The roots are found here, not quoted: cos(x) + 1 / cosh(x) = 0 (the equation divided by cosh, which
# cannot overflow) changes sign once in each interval [(n - 1) pi, n pi], where cos is monotonic and
# 1 / cosh is below 1 in size; Brent's method to round-off.


def cantilever_beta_L(*, modes):
    """beta_n L, n = 1..modes, the roots of 1 + cos(x) cosh(x) = 0 (notes above): 1.8751, 4.6941, ..."""
    modes = _count("modes", modes)
    return np.array([optimize.brentq(lambda x: math.cos(x) + 1.0 / math.cosh(x), (n - 1) * math.pi, n * math.pi,
                                     xtol=1e-15, rtol=4.0 * np.finfo(float).eps) for n in range(1, modes + 1)])


def cantilever_frequencies(*, E, I, rho, A, L, modes=1):
    """Natural frequencies (Hz) of a uniform Euler-Bernoulli cantilever, the first `modes`:
    f_n = (beta_n L)^2 / (2 pi) sqrt(EI / (rho A L^4)) (notes above; rho the density, A the section area)."""
    L, E, I = _beam(L, E, I)
    m = _positive("rho", rho) * _positive("A (section area)", A)
    return cantilever_beta_L(modes=modes) ** 2 / (2.0 * math.pi) * math.sqrt(E * I / (m * L ** 4))


def frame_bending_stiffness(*, E, I, L, elements):
    """The bending stiffness matrix of a straight free-free beam of `elements` equal frame elements:
    degrees of freedom (w_0, theta_0, ..., w_n, theta_n) from x = 0, element matrix (EI / h^3)
    [[12, 6h, -12, 6h], [6h, 4h^2, -6h, 2h^2], [-12, -6h, 12, -6h], [6h, 2h^2, -6h, 4h^2]] (the
    reference's 12EI/L^3, 6EI/L^2, 4EI/L, 2EI/L). The axial terms EA/h decouple from bending in a
    straight beam and are left out. Supports are imposed by deleting rows and columns."""
    L, E, I = _beam(L, E, I)
    n = _count("elements", elements)
    h = L / n
    k = E * I / h ** 3 * np.array([[12.0, 6 * h, -12.0, 6 * h], [6 * h, 4 * h * h, -6 * h, 2 * h * h],
                                   [-12.0, -6 * h, 12.0, -6 * h], [6 * h, 2 * h * h, -6 * h, 4 * h * h]])
    full = np.zeros((2 * n + 2, 2 * n + 2))
    for e in range(n):
        full[2 * e:2 * e + 4, 2 * e:2 * e + 4] += k
    return full


def cantilever_frame_stiffness(*, E, I, L, elements):
    """frame_bending_stiffness with the root node (x = 0) clamped and removed: degrees of freedom
    (w_1, theta_1, ..., w_n, theta_n). Used by cantilever_lumped_frequencies."""
    return frame_bending_stiffness(E=E, I=I, L=L, elements=elements)[2:, 2:]


def cantilever_lumped_frequencies(*, E, I, rho, A, L, elements, modes=1, rotary_inertia_ratio=0.0):
    """Natural frequencies (Hz) of the discrete cantilever the solver integrates: `elements` equal
    frame elements (cantilever_frame_stiffness), translational masses lumped at the nodes,
    m = rho A h at the interior nodes and rho A h / 2 at the tip (the root's half goes into the
    clamp), and a rotary inertia J = rotary_inertia_ratio m h^2 at each node (the same ratio at the
    tip, so half there too). The lowest `modes` of K phi = omega^2 M phi by scipy.linalg.eigh.

    rotary_inertia_ratio = 0 (the default) is the Euler-Bernoulli model with no rotary inertia: the
    rotations carry no mass and are condensed out statically, K* = K_ww - K_wt K_tt^-1 K_tw, leaving
    eigh(K*, diag(m)). A ratio of 1/12 is the inertia of each node's share of the beam as a rigid rod
    about its centre; any fixed ratio puts a rotary inertia per unit length of ratio rho A h^2 into
    the model, which vanishes as h -> 0, so every ratio converges to the continuum. The solver's
    choice must be stated as this ratio for a round-off comparison.

    Convergence (ratio 0), relative error of f_1 against cantilever_frequencies: -30.3 % at 1 element
    (sqrt(6) against 1.8751^2: the tip mass rho A L / 2 on the tip stiffness 3EI/L^3), -10.2 % at 2,
    -2.79 % at 4, -0.712 % at 8, -0.179 % at 16, -0.0448 % at 32: second order, from below, about
    -0.459 / n^2 (tests/python/test_analytic_structures.py measures it). With the ratio 1/12:
    -3.89 % at 4, -0.254 % at 16."""
    L, E, I = _beam(L, E, I)
    n = _count("elements", elements)
    modes = _count("modes", modes)
    if modes > n:
        raise ValueError(f"modes = {modes}: a cantilever of {n} elements has {n} translational modes")
    ratio = _non_negative("rotary_inertia_ratio", rotary_inertia_ratio)
    h = L / n
    mass = np.full(n, _positive("rho", rho) * _positive("A (section area)", A) * h)
    mass[-1] *= 0.5
    K = cantilever_frame_stiffness(E=E, I=I, L=L, elements=n)
    if ratio == 0.0:
        w, t = slice(0, None, 2), slice(1, None, 2)
        condensed = K[w, w] - K[w, t] @ np.linalg.solve(K[t, t], K[t, w])
        omega2 = linalg.eigh(0.5 * (condensed + condensed.T), np.diag(mass), eigvals_only=True)
    else:
        M = np.diag(np.column_stack([mass, ratio * mass * h * h]).ravel())
        omega2 = linalg.eigh(K, M, eigvals_only=True)
    return np.sqrt(omega2[:modes]) / (2.0 * math.pi)


def cantilever_first_period(*, E, I, rho, A, L):
    """1 / f_1 (s) of the continuous cantilever (cantilever_frequencies): the form a benchmark that
    measures the period of a tip history compares with."""
    return 1.0 / float(cantilever_frequencies(E=E, I=I, rho=rho, A=A, L=L, modes=1)[0])


def cantilever_lumped_first_period(*, E, I, rho, A, L, elements, rotary_inertia_ratio=0.0):
    """1 / f_1 (s) of the discrete cantilever of cantilever_lumped_frequencies."""
    return 1.0 / float(cantilever_lumped_frequencies(E=E, I=I, rho=rho, A=A, L=L, elements=elements, modes=1,
                                                     rotary_inertia_ratio=rotary_inertia_ratio)[0])


# ================================================================ beam on an elastic (Winkler) foundation
#
# EI w'''' + k w = p(x), k the foundation modulus (N/m of deflection per m of beam), w positive into
# the foundation (the load's direction), M = -EI w'' sagging positive. lambda = (k / 4EI)^(1/4) (1/m).
# Infinite beam under a point load P at x = 0 (Hetenyi 1946):
#
#     w = (P lambda / 2k) e^{-lambda |x|} (cos lambda x + sin lambda |x|),
#     M = (P / 4 lambda) e^{-lambda |x|} (cos lambda x - sin lambda |x|).
#
# Check of the constants: with w = C e^{-lambda x}(cos + sin) for x > 0, w''' = 4 C lambda^3 e^{-lambda x}
# cos lambda x, and the half beam carries half the load, EI w'''(0+) = P / 2: C = P / (8 EI lambda^3)
# = P lambda / 2k since 8 EI lambda^4 = 2k; M(0) = -EI w''(0) = 2 EI C lambda^2 = P / 4 lambda.
#
# A finite beam of length L, free at both ends, the load at its centre: by symmetry the half
# 0 <= x <= c = L/2 with w'(0) = 0, EI w'''(0+) = P / 2 and w''(c) = w'''(c) = 0 (free end). The
# general solution is Re[a e^{(-1+i) lambda x}] + Re[b e^{(1+i) lambda (x - c)}] with complex a, b: four real
# constants from these four conditions, a 4 x 4 linear system (the growing part is written from the
# far end so that nothing overflows for long beams). This is exact; Hetenyi gives the same in closed
# form with hyperbolic-trigonometric sums.


def winkler_lambda(*, k, E, I):
    """lambda = (k / 4EI)^(1/4), 1/m: the inverse of the length over which the foundation takes up a load."""
    return (_positive("k (foundation modulus)", k) / (4.0 * _positive("E", E) * _positive("I (second moment of area)", I))) ** 0.25


def winkler_deflection(x, *, P, k, E, I):
    """Deflection (into the foundation) of an infinite beam on a Winkler foundation under a point load P
    at x = 0: (P lambda / 2k) e^{-lambda |x|} (cos lambda x + sin lambda |x|) (Hetenyi 1946, notes above)."""
    lam = winkler_lambda(k=k, E=E, I=I)
    z = lam * np.abs(np.asarray(x, dtype=float))
    return _scalar("P", P) * lam / (2.0 * k) * np.exp(-z) * (np.cos(z) + np.sin(z))


def winkler_moment(x, *, P, k, E, I):
    """Bending moment (sagging positive) of the infinite beam of winkler_deflection:
    (P / 4 lambda) e^{-lambda |x|} (cos lambda x - sin lambda |x|) (Hetenyi 1946)."""
    lam = winkler_lambda(k=k, E=E, I=I)
    z = lam * np.abs(np.asarray(x, dtype=float))
    return _scalar("P", P) / (4.0 * lam) * np.exp(-z) * (np.cos(z) - np.sin(z))


_WINKLER_ROOTS = (complex(-1.0, 1.0), complex(1.0, 1.0))


def _winkler_finite_constants(lam, c, EI, P):
    """The four real constants (Re a, Im a, Re b, Im b) of the half beam (notes above)."""
    def row(order, x):
        # Re[(a_r + i a_i) z] = a_r Re z - a_i Im z, for z = (root lambda)^order e^{root lambda (x - shift)}
        out = []
        for root, shift in zip(_WINKLER_ROOTS, (0.0, c)):
            z = (root * lam) ** order * np.exp(root * lam * (x - shift))
            out += [z.real, -z.imag]
        return out
    A = np.array([row(1, 0.0), row(3, 0.0), row(2, c), row(3, c)])
    return np.linalg.solve(A, np.array([0.0, 0.5 * P / EI, 0.0, 0.0]))


def winkler_finite_beam(x, *, P, k, E, I, L):
    """Deflection and moment (dict "deflection", "moment"; conventions as winkler_deflection) of a beam
    of length L, free at both ends, on a Winkler foundation, under a point load P at its centre; x is
    measured from the centre, |x| <= L/2. Exact (a 4 x 4 linear system, notes above).

    How long must the beam be for the infinite beam's answer to hold? The relative difference of the
    central deflection, w_finite(0) / w_infinite(0) - 1, is +17.9 % at lambda L = 2, +8.0 % at 4,
    +1.6 % at 6, +0.058 % at 8, and stays below 0.1 % from lambda L = 7.73 on; the central moment's
    (-7.9 %, +5.4 %, -0.34 %, -0.057 % at the same lengths) from lambda L = 7.72 on
    (winkler_length_for_accuracy computes these). A benchmark whose model is finite should compare
    with this function, or make lambda L at least 7.73 to use the infinite beam's at 0.1 %."""
    L = _positive("L (beam length)", L)
    c = 0.5 * L
    lam = winkler_lambda(k=k, E=E, I=I)
    EI = E * I
    x = np.abs(np.asarray(x, dtype=float))
    if np.any(~(x <= c)):
        raise ValueError(f"x = {x}: must lie on the beam, |x| <= L/2 = {c}")
    P = _scalar("P", P)
    ar, ai, br, bi = _winkler_finite_constants(lam, c, EI, P)

    def derivative(order):
        total = 0.0
        for root, shift, re, im in ((_WINKLER_ROOTS[0], 0.0, ar, ai), (_WINKLER_ROOTS[1], c, br, bi)):
            z = (root * lam) ** order * np.exp(root * lam * (x - shift))
            total = total + re * z.real - im * z.imag
        return total

    return {"deflection": derivative(0), "moment": -EI * derivative(2)}


def winkler_discrete_beam(*, P, k, E, I, L, elements):
    """The finite free-free beam of winkler_finite_beam as the solver builds it: `elements` equal frame
    elements (frame_bending_stiffness; n even, so that a node carries the load at the centre), the
    foundation as a spring k h at every node and k h / 2 at the two end nodes (the interface
    springs on a rigid base, lumped by the trapezoidal rule), P at the centre node. Solved exactly
    (a dense linear solve). Returns a dict: "x" (the nodes, measured from the centre), "deflection"
    (nodal, into the foundation), "rotation" (nodal), "spring_force" (k h w per node, summing to P).
    It converges to winkler_finite_beam at second order in h (the lumping of the springs is the
    only approximation: the frame is exact between point forces): the largest nodal difference,
    relative to the largest deflection, is 0.38 %, 0.095 %, 0.024 % at 8, 16, 32 elements for
    lambda L = 2 (lambda h = 0.25, 0.125, 0.0625)."""
    L = _positive("L (beam length)", L)
    k = _positive("k (foundation modulus)", k)
    n = _count("elements", elements, smallest=2)
    if n % 2:
        raise ValueError(f"elements = {n}: must be even, so that a node lies at the centre")
    h = L / n
    K = frame_bending_stiffness(E=E, I=I, L=L, elements=n)
    springs = np.full(n + 1, k * h)
    springs[[0, -1]] *= 0.5
    K[0::2, 0::2] += np.diag(springs)
    f = np.zeros(2 * n + 2)
    f[n] = _scalar("P", P)            # w of node n / 2, the centre
    u = np.linalg.solve(K, f)
    return {"x": np.arange(n + 1) * h - 0.5 * L, "deflection": u[0::2], "rotation": u[1::2],
            "spring_force": springs * u[0::2]}


def winkler_discrete_deflection(x, *, P, k, E, I, L, elements):
    """The nodal deflection of winkler_discrete_beam at the node x (measured from the centre, as its
    "x"; x must be a node, |x| <= L/2, within 1e-9 L of one), into the foundation: the scalar form
    a benchmark compares one node with."""
    beam = winkler_discrete_beam(P=P, k=k, E=E, I=I, L=L, elements=elements)
    x = _scalar("x", x)
    node = int(np.argmin(np.abs(beam["x"] - x)))
    if abs(beam["x"][node] - x) > 1e-9 * L:
        raise ValueError(f"x = {x}: not a node of the {elements}-element beam (nodes every {L / elements} m from -L/2)")
    return float(beam["deflection"][node])


_WINKLER_MEASURES = ("deflection", "moment")


def winkler_length_for_accuracy(*, tolerance=1e-3, measure="deflection"):
    """The shortest lambda L beyond which a free-free beam of length L on a Winkler foundation, loaded
    at its centre, has its central deflection (measure="deflection") or central moment
    (measure="moment") within `tolerance` (relative) of the infinite beam's, for every longer beam.
    The relative difference decays like e^{-lambda L / 2} while oscillating, so it is sampled on a
    grid of 0.01 in lambda L up to 60, the last crossing found, and refined by Brent's method.
    0.1 %: lambda L = 7.73 (deflection), 7.72 (moment)."""
    tolerance = _positive("tolerance", tolerance)
    if tolerance >= 1.0:
        raise ValueError(f"tolerance = {tolerance}: must be below 1 (a relative difference)")
    if measure not in _WINKLER_MEASURES:
        raise ValueError(f"measure = {measure!r}: must be one of {', '.join(_WINKLER_MEASURES)}")
    # lambda = 1 (k = 4, EI = 1) and P = 1: the ratio depends on lambda L alone
    unit = dict(P=1.0, k=4.0, E=1.0, I=1.0)
    infinite = float((winkler_deflection if measure == "deflection" else winkler_moment)(0.0, **unit))

    def excess(lam_L):
        finite = float(winkler_finite_beam(0.0, L=lam_L, **unit)[measure])
        return abs(finite / infinite - 1.0) - tolerance

    grid = np.arange(0.5, 60.0, 0.01)
    above = np.array([excess(v) > 0.0 for v in grid])
    if not above.any():
        return float(grid[0])
    last = int(np.nonzero(above)[0][-1])
    if last == len(grid) - 1:
        raise ValueError(f"tolerance = {tolerance}: not reached by lambda L = 60")
    return optimize.brentq(excess, grid[last], grid[last + 1], xtol=1e-12)


def cable_lock_off_force(*, P, free_length, bond_length, EA, k_bond, n_bond=None):
    """Force left in a tensioned anchor once its grout has taken the pretension up, in rigid rock:
    a head plate fixed to the rock, a free length L_f whose elements start at the tension P, then a
    grouted anchor of length L_b. The anchor's head moves by d towards the plate, so the free length
    shortens: F = P - (EA / L_f) d and F = k_a d, whence

        F = P k_a / (k_a + EA / L_f),

    k_a the anchor's head stiffness: EA alpha tanh(alpha L_b) for the continuous grout (far end free;
    cable_elastic_displacement), or with n_bond elements the discrete chain's
    1 / cable_discrete_displacement(x=0, F0=1) (springs k_bond h at the nodes, half at its ends)."""
    P = _non_negative("P (pretension)", P)
    L_f = _positive("free_length", free_length)
    if n_bond is None:
        head = cable_elastic_displacement(0.0, F0=1.0, L=bond_length, EA=EA, k_bond=k_bond)
    else:
        head = cable_discrete_displacement(0.0, F0=1.0, L=bond_length, EA=EA, k_bond=k_bond, n=n_bond)
    k_a = 1.0 / float(head)
    return P * k_a / (k_a + EA / L_f)


# ================================================================ a bolt across a joint
#
# Bjurstrom (1974): a bolt carrying an axial tension P across a joint of friction angle phi raises the
# joint's shear resistance by
#
#     dT = P (cos alpha + sin alpha tan phi),
#
# alpha the angle between the bolt's axis and the JOINT PLANE (alpha = 90 degrees: the bolt normal to
# the joint), the bolt leaning so that the shear stretches it, i.e. its tension's component along the
# joint opposes the shear. Derivation (the limit equilibrium of the upper block): the bolt pulls it
# with P cos alpha back along the joint and P sin alpha onto the joint; the latter adds P sin alpha
# tan phi to the friction. Written with the angle theta = 90 - alpha from the joint's NORMAL (the
# other convention in the literature) it is P (sin theta + cos theta tan phi). Largest, P / cos phi, at
# alpha = phi; a bolt normal to the joint only clamps it (P tan phi).
#
# The reference's shear limit of local reinforcement (NUREG/CR-5429 1.4-40), with F_s the bar's
# tensile capacity pi d^2 sigma_b / 4:
#
#     F_max = F_s [1 + sign(cos(theta0) du_s) cos(theta0)] / 2,
#
# theta0 the angle of the reinforcement to the discontinuity (Fig. 1.4-12, not legible in the scanned
# text), du_s the shear displacement increment; "sign(cos theta0 du_s) assigns the sign of du_s to
# cos theta0" (the text), Fortran's SIGN(cos theta0, du_s) = |cos theta0| sign(du_s). Both readings
# are the same number: sign(cos theta0 du_s) cos theta0 = |cos theta0| sign(du_s). F_max runs from F_s
# (theta0 = 0, du_s > 0) through F_s / 2 (theta0 = 90 degrees) to 0 (theta0 = 0, du_s < 0). The text
# also quotes Bjurstrom's empirical limit for a bar normal to a joint in granite, 1.4-39:
# 0.67 d^2 sqrt(sigma_b sigma_c).


def bolt_joint_shear_increase(*, P, alpha_deg, phi_deg):
    """Increase of a joint's shear resistance from a bolt of axial tension P (N) crossing it at
    alpha_deg to the joint plane, leaning against the shear, on a joint of friction angle phi_deg:
    P (cos alpha + sin alpha tan phi) (Bjurstrom 1974; derivation and conventions above)."""
    P = _non_negative("P (bolt tension)", P)
    alpha = _angle("alpha_deg", alpha_deg, 0.0, 90.0)
    phi = _angle("phi_deg", phi_deg, 0.0, 89.999)
    return P * (math.cos(alpha) + math.sin(alpha) * math.tan(phi))


def yielding_spring_force(u, *, K, F_max):
    """Force of the reference's continuously-yielding spring (1.4-48, 1.4-49) loaded monotonically from
    zero through a displacement u (either sign): dF = K |du| f(F), f = |F_b - F| (F_b - F) / F_max^2 with
    F_b = F_max sign(du). With y = 1 - F / F_b, dy/du = -(K / F_max) y^2 for 0 <= y <= 1, so 1/y = 1 +
    K |u| / F_max and F = K u F_max / (F_max + K |u|): K u at first, F_max as |u| grows. F_max =
    math.inf gives the linear spring K u."""
    K = _positive("K", K)
    F_max = F_max if F_max == math.inf else _positive("F_max", F_max)
    u = np.asarray(u, dtype=float)
    if math.isinf(F_max):
        return K * u
    return K * u * F_max / (F_max + K * np.abs(u))


def bolt_active_length_stretch(us, *, L, alpha_deg, un=0.0):
    """Elongation |L e0 + u| - L of a bolt's active length L (m) when the joint it crosses moves by us
    along the joint (m, positive the way the bolt leans) and un across it (m, opening positive); e0 =
    (cos alpha, sin alpha) in the joint's (along, across) frame, alpha the bolt's angle to the joint
    plane. The sum of the displacement increments along the turning active length is this elongation
    (d|v| = dv . v / |v|)."""
    L = _positive("L (active length)", L)
    alpha = _angle("alpha_deg", alpha_deg, 1e-6, 179.999)
    us = np.asarray(us, dtype=float)
    return np.hypot(L * math.cos(alpha) + us, L * math.sin(alpha) + un) - L


def bolt_crushed_axial_displacement(us, *, L, alpha_deg):
    """The axial displacement the axial spring of a reinforcement receives when the joint slides by us
    along it (un = 0), with the reference's crushing reduction (1.4-47) applied to the part of each
    increment that comes from the active length turning (docs/models/support.md):

        d u_eff = cos(alpha) ds + r_f (d delta - cos(alpha) ds),  r_f = min(1, delta(s) / s),

    delta(s) = bolt_active_length_stretch(s) (the increments along the active length summed) and
    cos(alpha) ds the increment along the bolt's original direction. Integrated by adaptive quadrature
    (scipy.integrate.quad) of the closed-form integrand. A bolt normal to the joint (alpha = 90 degrees)
    has the closed form us - L asinh(us / L)."""
    from scipy import integrate
    L = _positive("L (active length)", L)
    alpha = _angle("alpha_deg", alpha_deg, 1e-6, 179.999)
    c, s_a = math.cos(alpha), math.sin(alpha)

    def rate(s):
        if s == 0.0:
            return c
        v = math.hypot(L * c + s, L * s_a)
        delta, ddelta = v - L, (L * c + s) / v
        rf = min(1.0, abs(delta) / abs(s))
        return c + rf * (ddelta - c)

    def one(u):
        value, _ = integrate.quad(rate, 0.0, float(u), epsabs=1e-15, epsrel=1e-12, limit=200)
        return value

    us = np.asarray(us, dtype=float)
    return np.vectorize(one)(us) if us.ndim else one(us)


def bolt_direct_shear(us, *, N, phi_deg, L, alpha_deg, Ka, Fa_max, Ks, Fs, crushing, joint_normal_stiffness=math.inf):
    """A joint of friction angle phi (no cohesion) under a normal load N (N/m), sliding by us (m),
    crossed by one reinforcement at alpha_deg to the joint plane (measured from the direction of
    shear: below 90 degrees it leans the way of the shear, which stretches it; above 90, against
    it, which shortens it), installed once N acts. The joint closes further by un = -(Nc - N) / k_j as
    the bolt clamps it (k_j = joint_normal_stiffness, N/m per m: kn times the contact length; the
    default, infinite, keeps un = 0; found by fixed-point iteration, each step a contraction by about
    Ka / k_j; not with crushing, whose integral is taken along un = 0). Returns (R, Fa, Fs_force, Nc):

    - Fa = yielding_spring_force(u_a; Ka, Fa_max), u_a the stretch of the active length
      (bolt_active_length_stretch) or, with crushing, bolt_crushed_axial_displacement;
    - the shear spring lies across the bolt's ORIGINAL direction, n0 = (-sin a, cos a); the joint's
      displacement along it is -us sin(alpha), so Fs_force = yielding_spring_force(-us sin a; Ks,
      F_b) with F_b = Fs (1 + cos alpha) / 2 (1.4-40: Fs (1 + |cos|) / 2 when the shear stretches
      the bolt, Fs (1 - |cos|) / 2 when it shortens it); Ks = 0: none;
    - the bolt acts on the upper block with -(Fa a + Fs_force n0), a = (L e0 + u) / |L e0 + u| the
      active length's direction now; the joint's normal force Nc = N + Fa a_n + Fs_force n0_n and, the
      joint sliding, its shear force Nc tan(phi); the force R that drives the upper block along the
      joint is then Nc tan(phi) + Fa a_s + Fs_force n0_s. R - N tan(phi) with Ks = 0 and a = e0 is
      Bjurstrom's P (cos alpha + sin alpha tan phi) (bolt_joint_shear_increase)."""
    alpha = _angle("alpha_deg", alpha_deg, 1e-6, 179.999)
    tan_phi = math.tan(_angle("phi_deg", phi_deg, 0.0, 89.999))
    k_j = joint_normal_stiffness if joint_normal_stiffness == math.inf else _positive("joint_normal_stiffness", joint_normal_stiffness)
    if crushing and not math.isinf(k_j):
        raise ValueError("crushing is integrated along un = 0: leave joint_normal_stiffness infinite")
    us = np.asarray(us, dtype=float)
    n_s, n_n = -math.sin(alpha), math.cos(alpha)
    un = np.zeros_like(us)
    for _ in range(100):
        if crushing:
            ua = bolt_crushed_axial_displacement(us, L=L, alpha_deg=alpha_deg)
        else:
            ua = bolt_active_length_stretch(us, L=L, alpha_deg=alpha_deg, un=un)
        Fa = yielding_spring_force(ua, K=Ka, F_max=Fa_max)
        w = -us * math.sin(alpha) + un * math.cos(alpha)  # the joint's displacement along n0
        if Ks > 0.0:
            # us > 0 along the joint's s axis: the shear stretches the bolt when cos(alpha) > 0
            bound = Fs * (1.0 + math.cos(alpha)) / 2.0
            Fs_force = yielding_spring_force(w, K=Ks, F_max=bound)
        else:
            Fs_force = np.zeros_like(us)
        vs, vn = L * math.cos(alpha) + us, L * math.sin(alpha) + un
        length = np.hypot(vs, vn)
        a_s, a_n = vs / length, vn / length
        Nc = N + Fa * a_n + Fs_force * n_n
        closing = -(Nc - N) / k_j
        if np.all(np.abs(closing - un) <= 1e-15 * L):
            break
        un = closing
    R = Nc * tan_phi + Fa * a_s + Fs_force * n_s
    return R, Fa, Fs_force, Nc


def bolt_resistance_per_unit_tension(*, R, Fa, N, phi_deg):
    """What a direct shear test with one bolt measures of Bjurstrom's factor: the increase of the
    force that slides the joint, R - N tan(phi), over the bolt's axial tension Fa (all N/m). Equal to
    cos alpha + sin alpha tan phi when the bolt's shear spring carries nothing and its active length
    has not turned (bolt_joint_shear_increase with P = 1)."""
    Fa = _scalar("Fa", Fa)
    if Fa == 0.0:
        raise ValueError("Fa = 0: the bolt carries no tension to measure the increase by")
    return (_scalar("R", R) - _scalar("N", N) * math.tan(_angle("phi_deg", phi_deg, 0.0, 89.999))) / Fa


def reinforcement_capacity(*, d, sigma_b):
    """F_s = pi d^2 sigma_b / 4, the bar's tensile capacity (1.4-40): d the bar's diameter (m),
    sigma_b its yield strength (Pa)."""
    return math.pi * _positive("d (bar diameter)", d) ** 2 * _positive("sigma_b (bar yield strength)", sigma_b) / 4.0


def reinforcement_shear_limit(*, d, sigma_b, theta_deg, shear_increment):
    """The reference's orientation-dependent shear limit of local reinforcement (1.4-40, notes above):
    F_s [1 + sign(cos theta0 du_s) cos theta0] / 2 = F_s (1 + sign(du_s) |cos theta0|) / 2, theta0 =
    theta_deg in [0, 180], du_s = shear_increment (any non-zero number; only its sign counts, and at
    du_s = 0 the limit is not defined by the text: a ValueError)."""
    F_s = reinforcement_capacity(d=d, sigma_b=sigma_b)
    theta = _angle("theta_deg", theta_deg, 0.0, 180.0)
    du = _scalar("shear_increment", shear_increment)
    if du == 0.0:
        raise ValueError("shear_increment = 0: the limit depends on the direction of shear; give its sign")
    return F_s * (1.0 + math.copysign(1.0, math.cos(theta) * du) * math.cos(theta)) / 2.0


def bjurstrom_shear_limit(*, d, sigma_b, sigma_c):
    """Bjurstrom's empirical shear limit of a bar normal to a joint, 0.67 d^2 sqrt(sigma_b sigma_c)
    (1.4-39), sigma_c the rock's uniaxial compressive strength (Pa)."""
    return 0.67 * _positive("d (bar diameter)", d) ** 2 * math.sqrt(
        _positive("sigma_b (bar yield strength)", sigma_b) * _positive("sigma_c (rock strength)", sigma_c))


# ================================================================ circular lining in an elastic medium
#
# A thin circular lining of radius R and thickness t (per unit length of tunnel, plane strain) in an
# elastic medium (E_m, nu_m) under a hydrostatic in-situ stress p0 (compression positive). Radial
# displacements u are positive INWARD.
#   Ring: a support pressure p on it gives the hoop thrust T = p R and the hoop strain T / (E_l' t),
#         E_l' = E_l / (1 - nu_l^2) in plane strain, so u_l = p R^2 / (E_l' t).
#   Hole: lowering the wall's pressure from p0 to p moves it by (p0 - p) R (1 + nu_m) / E_m (Lame, the
#         hole in an infinite plane-strain medium: u = (p0 - p) R / 2G_m).
# The lining is installed after a fraction lam_d (released_fraction) of p0 has been released, with the
# wall at u_0 = lam_d p0 R (1 + nu_m) / E_m; it then shares the rest. Compatibility of the wall and the
# ring from installation on:
#
#     p R^2 / (E_l' t) = ((1 - lam_d) p0 - p) R (1 + nu_m) / E_m
#     p = (1 - lam_d) p0 / (1 + C (1 - nu_m)),     T = p R,
#     C = E_m R (1 - nu_l^2) / (E_l t (1 - nu_m^2)),
#
# since E_m R / (E_l' t (1 + nu_m)) = C (1 - nu_m^2) / (1 + nu_m) = C (1 - nu_m). C is the compressibility
# ratio of Einstein and Schwartz (1979), with A = t the lining's area per unit length; the thrust
# is the issue's T = P R / (1 + C (1 - nu_m)), P = (1 - lam_d) p0, and for lam_d = 0 (the lining "wished
# in place" before any unloading, the whole relaxation acting on the composite: their excavation
# loading) the full-slip and no-slip answers of the hydrostatic case coincide (no shear on the
# interface by symmetry) and equal this. (Loading the unstressed medium with its lining at infinity
# instead, "external loading", gives 2 (1 - nu_m) p0 / (1 + C (1 - nu_m)): another problem.)
# Thin-ring theory holds to O(t / R): the thick cylinder's answer differs by that (tested).


def compressibility_ratio(*, R, t, E_l, nu_l, E_m, nu_m):
    """Einstein and Schwartz's compressibility ratio C = E_m R (1 - nu_l^2) / (E_l t (1 - nu_m^2))
    (notes above), t the lining's thickness (its area per unit length)."""
    R, t = _positive("R (lining radius)", R), _positive("t (lining thickness)", t)
    if t >= R:
        raise ValueError(f"t = {t}: a lining thicker than its radius R = {R} is no ring")
    E_l, E_m = _positive("E_l (lining modulus)", E_l), _positive("E_m (medium modulus)", E_m)
    nu_l, nu_m = _scalar("nu_l", nu_l), _scalar("nu_m", nu_m)
    for name, nu in (("nu_l", nu_l), ("nu_m", nu_m)):
        if not -1.0 < nu < 0.5:
            raise ValueError(f"{name} = {nu}: Poisson's ratio must lie in (-1, 1/2)")
    return E_m * R * (1.0 - nu_l ** 2) / (E_l * t * (1.0 - nu_m ** 2))


def lining_ring(*, R, t, E_l, nu_l, E_m, nu_m, p0, released_fraction=0.0, outer_radius=math.inf,
                interface_stiffness=math.inf):
    """A thin circular lining in an elastic medium under hydrostatic in-situ stress p0 (compression
    positive), installed after released_fraction (lam_d, in [0, 1]) of p0 has been released at the
    wall: 0 is the lining in place before any unloading. Returns a dict (derivation above):

        "compressibility"      C = E_m R (1 - nu_l^2) / (E_l t (1 - nu_m^2))
        "support_pressure"     p = (1 - lam_d) p0 / (1 + C (1 - nu_m))       (Pa, on the lining)
        "thrust"               T = p R                                        (N per m of tunnel, compression)
        "hoop_stress"          T / t                                          (Pa, compression)
        "lining_displacement"  p R^2 (1 - nu_l^2) / (E_l t)                   (m inward, since installation)
        "wall_displacement"    lam_d p0 R (1 + nu_m) / E_m + the above        (m inward, since excavation)

    Two refinements for a model to be compared with, both off by default:
    outer_radius b: the medium a thick cylinder R <= r <= b whose outer face keeps its traction p0
    (plane strain, Lame): a change q of the wall's pressure moves the wall by
    q R (1 + nu_m) ((1 - 2 nu_m) R^2 + b^2) / (E_m (b^2 - R^2)) instead of q R (1 + nu_m) / E_m;
    interface_stiffness k_i (N/m per m of lining): radial springs between lining and wall, adding
    p / k_i to the wall's displacement. With f_m, f_l = R^2 (1 - nu_l^2) / (E_l t) and f_i = 1 / k_i
    the radial compliances of medium, lining and springs, compatibility after installation,
    ((1 - lam_d) p0 - p) f_m = p (f_l + f_i), gives p = (1 - lam_d) p0 f_m / (f_m + f_l + f_i) (the
    formula above when b and k_i are infinite: f_l / f_m = C (1 - nu_m)); the wall then moves
    lam_d p0 f_m + p (f_l + f_i) since excavation."""
    C = compressibility_ratio(R=R, t=t, E_l=E_l, nu_l=nu_l, E_m=E_m, nu_m=nu_m)
    p0 = _non_negative("p0 (in-situ stress)", p0)
    lam_d = _scalar("released_fraction", released_fraction)
    if not 0.0 <= lam_d <= 1.0:
        raise ValueError(f"released_fraction = {lam_d}: must lie in [0, 1]")
    b = float(outer_radius)
    if math.isnan(b) or not b > R:
        raise ValueError(f"outer_radius = {b}: must exceed the lining radius R = {R}")
    k_i = float(interface_stiffness)
    if math.isnan(k_i) or not k_i > 0.0:
        raise ValueError(f"interface_stiffness = {interface_stiffness}: must be > 0 (infinite: rigid)")
    f_m = R * (1.0 + nu_m) / E_m
    if math.isfinite(b):
        f_m *= ((1.0 - 2.0 * nu_m) * R * R + b * b) / (b * b - R * R)
    f_l = R * R * (1.0 - nu_l ** 2) / (E_l * t)
    f_i = 1.0 / k_i
    if math.isinf(b) and math.isinf(k_i):
        p = (1.0 - lam_d) * p0 / (1.0 + C * (1.0 - nu_m))
    else:
        p = (1.0 - lam_d) * p0 * f_m / (f_m + f_l + f_i)
    lining = p * f_l
    return {"compressibility": C, "support_pressure": p, "thrust": p * R, "hoop_stress": p * R / t,
            "lining_displacement": lining, "wall_displacement": lam_d * p0 * f_m + p * (f_l + f_i)}


# ================================================================ a roof wedge held by cables
#
# A symmetric wedge in a horizontal roof, apex up, of weight W per unit length (N/m), its two faces
# (joints) at half_apex_angle alpha from the vertical, dry and cohesionless (friction phi), held by
# vertical cables. Limit equilibrium of the rigid wedge, the wedge about to fall: on each face a normal
# force N (pressing on the wedge, directed inward and downward, vertical part -N sin alpha) and a
# friction force at most N tan phi along the face, upward (vertical part N tan phi cos alpha). With the
# cables' total force T upward:
#
#     T = W - 2 N (tan phi cos alpha - sin alpha)
#
# (horizontal balance holds by symmetry). N is what confines the wedge, from the horizontal stress in
# the roof; it is an input here (normal_force), and with it ignored (N = 0, no confinement: the
# conservative, usual design assumption) friction helps nothing and T = W, the dead weight. With N > 0
# friction helps only when phi > alpha. Assumed: a rigid wedge, no cohesion, no water pressure, cables
# vertical and unpretensioned, the faces' normal forces equal (symmetry).
# How the cables share T: elastic cables of stiffnesses k_i at positions x_i under a rigid wedge that
# translates and rotates but does not slide on the (unloaded) joints: F_i = k_i (v + w (x_i - x_c)),
# with sum F_i = T and sum F_i (x_i - x_c) = 0 (the weight acting at the centroid x_c, the joints
# carrying nothing): two equations for v and w. Equal cables placed symmetrically about x_c carry T / n each.


def wedge_weight(*, unit_weight, span, half_apex_angle_deg):
    """Weight per unit length of a symmetric roof wedge of base `span` (m) and half apex angle alpha:
    unit_weight (N/m^3) times the triangle's area span^2 / (4 tan alpha) (its height is (span/2) / tan alpha)."""
    alpha = _angle("half_apex_angle_deg", half_apex_angle_deg, 1e-6, 89.999)
    span = _positive("span", span)
    return _positive("unit_weight", unit_weight) * span * span / (4.0 * math.tan(alpha))


def wedge_support_force(*, W, half_apex_angle_deg, phi_deg, normal_force=0.0):
    """Total vertical cable force for limit equilibrium of the symmetric roof wedge (notes above):
    W - 2 N (tan phi cos alpha - sin alpha), N = normal_force on each face (N/m; 0, the default: the
    joints' confinement ignored, the answer W). A value <= 0 means the joints hold the wedge unaided."""
    W = _positive("W (wedge weight)", W)
    alpha = _angle("half_apex_angle_deg", half_apex_angle_deg, 1e-6, 89.999)
    phi = _angle("phi_deg", phi_deg, 0.0, 89.999)
    N = _non_negative("normal_force", normal_force)
    return W - 2.0 * N * (math.tan(phi) * math.cos(alpha) - math.sin(alpha))


def wedge_cable_forces(*, total, positions, stiffnesses=None, centroid=0.0):
    """Forces of vertical elastic cables at `positions` (m, along the span) sharing `total` (N/m) under
    a rigid wedge whose weight acts at `centroid` (notes above): F_i = k_i (v + w (x_i - x_c)) with
    sum F_i = total and sum F_i (x_i - x_c) = 0. stiffnesses default to equal. A single cable must sit
    at the centroid; cables all at one place elsewhere cannot stop the wedge rotating (ValueError)."""
    total = _scalar("total", total)
    x = np.atleast_1d(np.asarray(positions, dtype=float))
    if x.ndim != 1 or x.size == 0 or not np.all(np.isfinite(x)):
        raise ValueError(f"positions = {positions}: must be a non-empty list of finite numbers")
    k = np.ones_like(x) if stiffnesses is None else np.atleast_1d(np.asarray(stiffnesses, dtype=float))
    if k.shape != x.shape or np.any(~(k > 0.0)):
        raise ValueError(f"stiffnesses = {stiffnesses}: one positive stiffness per cable")
    arm = x - _scalar("centroid", centroid)
    if np.all(arm == 0.0):       # at the centroid: no moment to resist, the wedge translates
        return total * k / k.sum()
    if x.size == 1:
        raise ValueError(f"positions = {positions}: a single cable must sit at the centroid {centroid}")
    A = np.array([[k.sum(), (k * arm).sum()], [(k * arm).sum(), (k * arm * arm).sum()]])
    if abs(np.linalg.det(A)) <= 1e-12 * A[0, 0] * A[1, 1]:
        raise ValueError(f"positions = {positions}: the cables all sit at one place and cannot stop the wedge rotating")
    v, w = np.linalg.solve(A, np.array([total, 0.0]))
    return k * (v + w * arm)

"""Closed-form references for simply-deformable blocks (NUREG/CR-5429 Vol. 1, 1.3.3.4; Cundall et al. 1978).

Independent of the solver: only math, numpy and scipy are used, and every formula is derived here
from the model below (or from elementary elasticity and beam theory), never from the solver's code.

Model. A simply-deformable block is a polygon whose displacement is the three rigid-body modes plus
three modes of UNIFORM strain about its centroid x_c:

    u(x) = u_c + W (x - x_c) + e (x - x_c),   W antisymmetric (rotation), e symmetric (e11, e22, e12).

Virtual work over these six modes gives everything the functions below use:
  * the generalised force of the strain mode e_ij is sum_k F_k,i (x_k - x_c)_j over the forces F_k on
    the block's boundary, symmetrised (a uniform body force does no work in it, since
    integral (x - x_c) dA = 0); divided by the area A it is the block's MEAN stress,
    sigma_mean = (1/A) sym sum_k F_k (x) (x_k - x_c), and the uniform strain carries it by Hooke's law
    (strain energy A e : D : e / 2, so D e = sigma_mean);
  * the generalised mass of the mode e_yy is the consistent rho integral (y - y_c)^2 dA (rho h^3 / 12
    per unit width for a block of height h), not a lumped value;
  * a uniform strain has no curvature: a block cannot bend (NUREG/CR-5429 Fig. 1.3-5).
Uniform stress is one of its states, so a block under uniform boundary tractions is exact; a stress
varying within the block (self weight, bending, a wave) is represented by its mean only.

Plane strain throughout (e_zz = 0): Young's modulus E and Poisson's ratio nu, shear modulus
G = E / (2 (1 + nu)); for a column the 1D modulus M is E / (1 - nu^2) with the sides free and
K + 4G/3 = E (1 - nu) / ((1 + nu) (1 - 2 nu)) with the sides held (column_modulus).

Sign conventions: normal stress COMPRESSION POSITIVE and normal strain SHORTENING POSITIVE (the
platen test and the column); displacement of the column DOWNWARD POSITIVE (settlement); joint
closure positive; beam deflection positive in the direction of the load. SI units: m, s, kg, Pa,
Pa/m for joint stiffness, Hz for frequencies; a column is per unit width and unit thickness (its
joints' spring kn per unit width is kn x 1 m), a long block per unit thickness (its load in N/m).
Every function takes keyword arguments only; the column's y and the platen's stress may be numpy
arrays (the result is then an array).
Nonsensical input (a non-positive modulus, nu outside (-1, 1/2), y off the column, a fractional
number of blocks, ...) is a ValueError naming the argument.

Sources: NUREG/CR-5429 Vol. 1, 1.3.3.4 and Fig. 1.3-5 (the simply-deformable block, as the solver
documents it); P. A. Cundall et al., 1978, as cited there for the formulation; S. P. Timoshenko and
J. M. Gere, Mechanics of Materials (the cantilever, shear deflection with the coefficient 5/6 of a
rectangle). Section and figure numbers were not checked against the texts: each formula is derived
here and checked in tests/python/test_analytic_simply_deformable.py by another route (a linear or
eigen solve of a model built in the test, quadrature), so a misquoted source would show there.
"""
import math

import numpy as np
import scipy.linalg


def _arr(x):
    return np.asarray(x, dtype=float)


def _scalar(name, value):
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {value!r}: must be a number") from None
    if math.isnan(value):
        raise ValueError(f"{name} = {value}: must be a number")
    return value


def _positive(name, value):
    value = _scalar(name, value)
    if not (value > 0.0 and math.isfinite(value)):
        raise ValueError(f"{name} = {value}: must be positive and finite")
    return value


def _positive_or_inf(name, value):
    value = _scalar(name, value)
    if not value > 0.0:
        raise ValueError(f"{name} = {value}: must be positive (math.inf for a bonded joint)")
    return value


def _non_negative(name, value):
    value = _scalar(name, value)
    if not (value >= 0.0 and math.isfinite(value)):
        raise ValueError(f"{name} = {value}: must be zero or positive, and finite")
    return value


def _count(name, value, smallest=1):
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < smallest:
        raise ValueError(f"{name} = {value!r}: must be a whole number >= {smallest}")
    return int(value)


def _young_poisson(E, nu):
    E, nu = _positive("E (Young's modulus)", E), _scalar("nu (Poisson's ratio)", nu)
    if not -1.0 < nu < 0.5:
        raise ValueError(f"nu = {nu}: Poisson's ratio must lie in (-1, 1/2) for a stable isotropic solid")
    return E, nu


_LATERAL = ("free", "held")


def _lateral(lateral):
    if lateral not in _LATERAL:
        raise ValueError(f"lateral = {lateral!r}: must be one of {', '.join(_LATERAL)}")
    return lateral


# ---------------------------------------------------------------- a block between platens


def platen_compression_strains(*, stress, E, nu, lateral):
    """Strains and stresses of a block compressed between frictionless platens by a uniform vertical
    stress (plane strain, e_zz = 0), as a dict with "exx", "eyy", "ezz" (SHORTENING positive) and
    "sxx", "syy", "szz" (COMPRESSION positive; syy = stress).

    Flipping the sign of every stress and strain leaves Hooke's law unchanged, so in these
    conventions E e_xx = s_xx - nu (s_yy + s_zz) and so on. e_zz = 0 gives s_zz = nu (s_xx + s_yy).
      lateral = "free" (s_xx = 0): s_zz = nu s,  e_yy = (1 - nu^2) s / E,
                                    e_xx = -(nu s + nu^2 s) / E = -nu (1 + nu) s / E (the block widens);
      lateral = "held" (e_xx = 0):  s_xx = nu (s + s_zz) and s_zz = nu (s_xx + s), so
                                    s_xx = s_zz = nu s / (1 - nu),
                                    e_yy = (s - 2 nu^2 s / (1 - nu)) / E = (1 + nu)(1 - 2 nu) s / ((1 - nu) E),
                                    i.e. s / (K + 4G/3), the constrained modulus.
    Exact for a simply-deformable block: the platens load it by uniform tractions, whose mean stress
    is the stress itself, and uniform strain is one of its modes. The displacement of a platen is
    e_yy times the height plus whatever its joints with the platens close (not included here).
    """
    s = _arr(stress)
    if np.any(~np.isfinite(s)):
        raise ValueError(f"stress = {stress}: must be finite")
    E, nu = _young_poisson(E, nu)
    zero = 0.0 * s
    if _lateral(lateral) == "free":
        return {"exx": -nu * (1.0 + nu) * s / E, "eyy": (1.0 - nu * nu) * s / E, "ezz": zero,
                "sxx": zero, "syy": s + zero, "szz": nu * s}
    side = nu * s / (1.0 - nu)
    return {"exx": zero, "eyy": (1.0 + nu) * (1.0 - 2.0 * nu) * s / ((1.0 - nu) * E), "ezz": zero,
            "sxx": side, "syy": s + zero, "szz": side}


# ---------------------------------------------------------------- a column under its own weight


def column_modulus(*, E, nu, lateral):
    """The 1D modulus M = s_yy / e_yy of a plane-strain column loaded vertically:
    E / (1 - nu^2) with the sides free (s_xx = 0), K + 4G/3 = E (1 - nu) / ((1 + nu)(1 - 2 nu)) with
    the sides held (e_xx = 0). See platen_compression_strains for the derivation."""
    E, nu = _young_poisson(E, nu)
    if _lateral(lateral) == "free":
        return E / (1.0 - nu * nu)
    return E * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu))


def _on_column(y, height):
    y = _arr(y)
    if np.any(~((y >= 0.0) & (y <= height))):
        raise ValueError(f"y = {y}: must lie on the column, 0 <= y <= H = {height}")
    return y


def continuum_column_self_weight_displacement(*, y, height, rho, g, modulus):
    """Downward displacement at height y of a continuous column (base y = 0 held, top y = H free)
    under its own weight: u(y) = rho g (H y - y^2 / 2) / M.

    The compressive stress at y is the weight above, rho g (H - y); the shortening strain is that over
    M; integrating from the base, u(y) = integral_0^y rho g (H - s) / M ds. The top settles
    rho g H^2 / (2M). A 1D bar; for a 2D column with free sides it holds on the centreline, with
    sections free to curve (the lateral strain varies with height), and exactly with held sides.
    """
    H = _positive("height", height)
    y = _on_column(y, H)
    rho, g, M = _positive("rho", rho), _non_negative("g", g), _positive("modulus", modulus)
    return rho * g * (H * y - 0.5 * y * y) / M


def column_self_weight_displacement(*, y, height, n_blocks, rho, g, modulus, kn=math.inf):
    """Downward displacement at height y of a column of n equal simply-deformable blocks (height
    h = H / n, base y = 0 held, top free) under its own weight, with joints of normal stiffness kn
    (Pa/m) between blocks and between the lowest block and the base (kn = inf: bonded, no closure).

    Block j (j = 0 at the base) spans j h <= y <= (j + 1) h and has n - j - 1 blocks above it. Its
    strain mode carries its mean stress (module notes): the forces on its faces are the weight above,
    W_a = rho g h (n - j - 1) per unit width, down on its top face (lever +h/2) and W_a + rho g h up on
    its bottom face (lever -h/2), while its own weight, uniform, does no work in the mode. So, with
    A = h per unit width, h sigma_mean = (h / 2)(2 W_a + rho g h), i.e. sigma_j = rho g h (n - j - 1/2)
    -- the weight above plus half its own, over the width -- and its shortening e_j = sigma_j / M. Joint j, under block j,
    carries the weight of n - j blocks and closes by c_j = rho g h (n - j) / kn. Adding up from the
    base, at y = k h + t (0 <= t <= h, block k):

        u(y) = sum_{j<=k} c_j + sum_{j<k} e_j h + e_k t
             = rho g h [(k + 1) n - k (k + 1) / 2] / kn
               + rho g [h^2 (n k - k^2 / 2) + h (n - k - 1/2) t] / M.

    A point at a joint's level (within 1e-9 h of it) belongs to the block above, so that its
    displacement includes that joint's closure; the base's own displacement (0) is not returned.

    What is exact. At every block boundary y = k h the blocks' part equals the continuum's
    rho g (H y - y^2 / 2) / M (continuum_column_self_weight_displacement) for any n, since
    h^2 (n k - k^2 / 2) = (H y - y^2 / 2) there; the top's rho g H^2 / (2M) is exact, plus the
    closures. Within a block the displacement is linear between these exact values, while the
    continuum's is a parabola of curvature -rho g / M: the chord misses it by
    (rho g / 2M) t (h - t), at most rho g h^2 / (8M) at mid-block (t = h / 2). The largest error
    thus converges as h^2: it is 1 / (4 n^2) of the top settlement.

    With free sides the blocks' lateral strains differ (their mean stresses do), so the joints must
    carry no shear (smooth joints, ks = 0) for the column to stay 1D; with held sides (e_xx = 0) the
    result holds whatever the joints' shear stiffness.
    """
    H = _positive("height", height)
    n = _count("n_blocks", n_blocks)
    y = _on_column(y, H)
    rho, g, M = _positive("rho", rho), _non_negative("g", g), _positive("modulus", modulus)
    kn = _positive_or_inf("kn", kn)
    h = H / n
    s = y / h
    nearest = np.rint(s)
    k = np.where(np.abs(s - nearest) <= 1e-9, nearest, np.floor(s))
    k = np.clip(k, 0, n - 1)
    t = y - k * h
    blocks = rho * g * (h * h * (n * k - 0.5 * k * k) + h * (n - k - 0.5) * t) / M
    closures = 0.0 if math.isinf(kn) else rho * g * h * ((k + 1.0) * n - 0.5 * k * (k + 1.0)) / kn
    return blocks + closures


def column_self_weight_settled_height(*, y, height, n_blocks, rho, g, modulus, kn=math.inf):
    """The height to which the point of the simply-deformable column at initial height y settles:
    y - column_self_weight_displacement(...) (the displacement is downward positive)."""
    return _arr(y) - column_self_weight_displacement(y=y, height=height, n_blocks=n_blocks, rho=rho, g=g,
                                                     modulus=modulus, kn=kn)


def continuum_column_self_weight_strain_energy(*, height, width, rho, g, modulus):
    """Elastic energy (J per metre of thickness) of the continuous column under its own weight: the
    stress at y is rho g (H - y), the energy density its square over 2M, so
    U = w integral_0^H (rho g (H - y))^2 / (2M) dy = rho^2 g^2 H^3 w / (6M)."""
    H, w = _positive("height", height), _positive("width", width)
    rho, g, M = _positive("rho", rho), _non_negative("g", g), _positive("modulus", modulus)
    return rho * rho * g * g * H ** 3 * w / (6.0 * M)


def column_self_weight_strain_energy(*, height, width, n_blocks, rho, g, modulus, kn=math.inf):
    """Elastic energy (J per metre of thickness) of the simply-deformable column of
    column_self_weight_displacement, width w: each block holds A sigma_j^2 / (2M) with A = h w and
    sigma_j = rho g h (i - 1/2), i = n - j the blocks from the top down to it, and each joint
    F_j^2 / (2 kn w) with F_j = rho g h w i. With sum_{i=1}^{n} (i - 1/2)^2 = n^3 / 3 - n / 12, the
    blocks hold rho^2 g^2 H^3 w / (6M) (1 - 1 / (4 n^2)): a uniform stress per block misses the
    energy of the stress's variation within it, so the blocks' energy falls short of the continuum's
    (continuum_column_self_weight_strain_energy) by 1 / (4 n^2) of it, converging as h^2."""
    H, w = _positive("height", height), _positive("width", width)
    n = _count("n_blocks", n_blocks)
    rho, g, M = _positive("rho", rho), _non_negative("g", g), _positive("modulus", modulus)
    kn = _positive_or_inf("kn", kn)
    h = H / n
    i = np.arange(1, n + 1, dtype=float)
    blocks = float(np.sum(h * w * (rho * g * h * (i - 0.5)) ** 2 / (2.0 * M)))
    joints = 0.0 if math.isinf(kn) else float(np.sum((rho * g * h * w * i) ** 2 / (2.0 * kn * w)))
    return blocks + joints


# ---------------------------------------------------------------- a column's axial vibration


_BLOCKS = ("simply-deformable", "rigid", "continuum")


def _simply_deformable_chain(n, h, rho, M, kn):
    """Mass and stiffness matrices (per unit width) of n simply-deformable blocks in a column, DOF
    (v_j, e_j) per block: v the centroid's upward displacement, e the extension strain. See
    jointed_column_first_frequency."""
    mass = np.diag(np.tile([rho * h, rho * h ** 3 / 12.0], n))
    stiffness = np.diag(np.tile([0.0, M * h], n))
    # Row j of `gaps`: the opening of joint j, the bottom face of block j (v_j - e_j h/2) less the
    # top face of block j - 1 (v_{j-1} + e_{j-1} h/2), or the base (0).
    gaps = np.zeros((n, 2 * n))
    for j in range(n):
        gaps[j, 2 * j:2 * j + 2] = (1.0, -0.5 * h)
        if j > 0:
            gaps[j, 2 * j - 2:2 * j] = (-1.0, -0.5 * h)
    if math.isinf(kn):
        # Bonded: the faces move together, so the column is described by its n nodal displacements
        # a_1..a_n (a_0 = 0 at the base), with v_j = (a_j + a_{j+1}) / 2, e_j = (a_{j+1} - a_j) / h.
        to_blocks = np.zeros((2 * n, n))
        for j in range(n):
            if j > 0:
                to_blocks[2 * j, j - 1], to_blocks[2 * j + 1, j - 1] = 0.5, -1.0 / h
            to_blocks[2 * j, j], to_blocks[2 * j + 1, j] = 0.5, 1.0 / h
        return to_blocks.T @ mass @ to_blocks, to_blocks.T @ stiffness @ to_blocks
    return mass, stiffness + kn * gaps.T @ gaps


def jointed_column_first_frequency(*, height, n_blocks, rho, modulus, kn, blocks="simply-deformable"):
    """First natural frequency (Hz) of the axial (vertical) vibration of a column of height H made
    of n equal blocks (h = H / n), fixed at its base through a joint of normal stiffness kn (Pa/m),
    the blocks joined by joints kn, free at its top; no gravity. `modulus` is the block's 1D modulus M
    (column_modulus). kn = math.inf means bonded joints (allowed but for "rigid").

    blocks = "continuum": the homogenised bar. A length h holds one block (compliance h / M per unit
    area) and one joint (1 / kn), so the bar's modulus is M_eff with 1 / M_eff = 1 / M + 1 / (kn h);
    a fixed-free bar's first mode is a quarter wave, f = sqrt(M_eff / rho) / (4 H).

    blocks = "rigid": n point masses m = rho h (per unit width and thickness), joined by springs
    k = kn (x 1 m of width), the lowest by a spring k to the base; M is not used. With u_0 = 0 (base)
    and the top's equation m u_n'' = k (u_{n-1} - u_n) written as the interior one with u_{n+1} = u_n,
    the trial u_j = sin(j theta) satisfies every interior equation
    -m w^2 u_j = k (u_{j+1} - 2 u_j + u_{j-1}) with w^2 = (2k / m)(1 - cos theta) = (4k/m) sin^2(theta / 2),
    and the top's when sin((n + 1) theta) = sin(n theta), i.e. theta = (2p + 1) pi / (2n + 1). The first:

        w = 2 sqrt(k / m) sin(pi / (2 (2n + 1))),   f = w / (2 pi).

    Against the homogenised bar with M = inf (M_eff = kn h) it is exact to FIRST order in 1/n only:
    f / f_bar = (4n / pi) sin(pi / (4n + 2)) = 1 - 1 / (2n) + ..., 0.637 at n = 1, 0.951 at n = 10
    (see below for why).

    blocks = "simply-deformable": two DOF per block, the centroid's translation v_j (mass rho h) and
    the uniform strain e_j (consistent mass rho integral (y - y_c)^2 dy = rho h^3 / 12, stiffness
    M h from the strain energy M e^2 h / 2); the faces move by v_j -/+ e_j h / 2 and each joint is a
    spring kn between the bottom face of a block and the top face of the one below (or the base).
    The 2n x 2n mass and stiffness matrices are assembled here and the generalised eigenproblem
    K phi = w^2 M phi solved by scipy.linalg.eigh: that is the exact answer of this discrete system
    (its "closed form"), not an approximation of it. With kn = inf the faces are tied and the system
    is the bar of n two-node elements with consistent mass, whose first frequency is
    w^2 = (6M / (rho h^2)) (1 - cos theta) / (2 + cos theta), theta = pi / (2n) (the mode sin(j theta)
    at the nodes, as for the rigid chain), i.e. f / f_bar = 1 + pi^2 / (96 n^2) + ...: second order.
    It tends to the rigid chain as M -> inf and to the bar of modulus M as kn -> inf.

    Why the jointed chains converge to first order only, as n grows at fixed kn h: a joint sits at
    the bottom of each cell of height h while the homogenised bar spreads its compliance over the
    cell, so the joints' share phi = M_eff / (kn h) of the compliance is displaced h/2 towards the
    base, the same as a massless extra length phi h / 2 below a fixed-free bar: f / f_bar
    = H / (H + phi h / 2) = 1 - phi / (2n) + O(1/n^2). The rigid chain has phi = 1; the
    simply-deformable chain at kn h = M has phi = 1/2 and error -1/(4n) (-0.0300 at n = 8, -0.0039
    at n = 64), bonded it has phi = 0.
    """
    H = _positive("height", height)
    n = _count("n_blocks", n_blocks)
    rho, M = _positive("rho", rho), _positive("modulus", modulus)
    kn = _positive_or_inf("kn", kn)
    if blocks not in _BLOCKS:
        raise ValueError(f"blocks = {blocks!r}: must be one of {', '.join(_BLOCKS)}")
    h = H / n
    if blocks == "continuum":
        m_eff = 1.0 / (1.0 / M + 1.0 / (kn * h))
        return math.sqrt(m_eff / rho) / (4.0 * H)
    if blocks == "rigid":
        if math.isinf(kn):
            raise ValueError("kn = inf: a chain of rigid blocks bonded together has no finite frequency")
        w = 2.0 * math.sqrt(kn / (rho * h)) * math.sin(math.pi / (2.0 * (2 * n + 1)))
        return w / (2.0 * math.pi)
    mass, stiffness = _simply_deformable_chain(n, h, rho, M, kn)
    w2 = scipy.linalg.eigh(stiffness, mass, eigvals_only=True, subset_by_index=[0, 0])[0]
    return math.sqrt(w2) / (2.0 * math.pi)


def jointed_column_first_period(*, height, n_blocks, rho, modulus, kn, blocks="simply-deformable"):
    """The period (s) of jointed_column_first_frequency's first mode, 1 / f."""
    return 1.0 / jointed_column_first_frequency(height=height, n_blocks=n_blocks, rho=rho, modulus=modulus, kn=kn,
                                                blocks=blocks)


# ---------------------------------------------------------------- a long block in bending


_SUPPORTS = ("cantilever", "simply-supported")
_SHEAR_COEFFICIENT = 5.0 / 6.0   # of a rectangular section


def long_block_bending_deflection(*, length, depth, E, nu, load, support="cantilever"):
    """Deflection under the load of a long elastic block (a beam of length L, depth d, unit
    thickness, plane strain) by Timoshenko beam theory: load P per unit thickness (N/m), deflection
    in its direction.

    Plane strain makes the bending modulus E' = E / (1 - nu^2) (the block cannot contract across its
    thickness); shear uses G = E / (2 (1 + nu)) on the area d with the rectangle's coefficient 5/6.
    Per unit thickness I = d^3 / 12. By the unit-load method the deflection under P is
    integral M^2 / (P E' I) dx + integral V^2 / (P kappa G d) dx:
      support = "cantilever", P at the free end (M = P (L - x), V = P):
          delta = P L^3 / (3 E' I) + P L / (kappa G d) = 4 P L^3 / (E' d^3) + 6 P L / (5 G d);
      support = "simply-supported", P at mid-span (each half a cantilever of length L/2 loaded by P/2):
          delta = P L^3 / (48 E' I) + P L / (4 kappa G d).

    A simply-deformable block cannot represent this: its strain is uniform, with no curvature mode
    (NUREG/CR-5429 Fig. 1.3-5), so one such block bends not at all; it gives only the rigid and
    uniform-shear part (simply_deformable_cantilever_tip_deflection), and a beam of them needs many
    blocks along and across it, with the joints' compliance, to approach these values.
    """
    L, d = _positive("length", length), _positive("depth", depth)
    E, nu = _young_poisson(E, nu)
    P = _scalar("load", load)
    if not math.isfinite(P):
        raise ValueError(f"load = {P}: must be finite")
    if support not in _SUPPORTS:
        raise ValueError(f"support = {support!r}: must be one of {', '.join(_SUPPORTS)}")
    bending_modulus, G, inertia = E / (1.0 - nu * nu), E / (2.0 * (1.0 + nu)), d ** 3 / 12.0
    if support == "cantilever":
        return P * L ** 3 / (3.0 * bending_modulus * inertia) + P * L / (_SHEAR_COEFFICIENT * G * d)
    return P * L ** 3 / (48.0 * bending_modulus * inertia) + P * L / (4.0 * _SHEAR_COEFFICIENT * G * d)


def simply_deformable_cantilever_tip_deflection(*, length, depth, E, nu, load):
    """Deflection of the loaded end of ONE simply-deformable block (length L, depth d, unit thickness,
    plane strain) held on its end face x = 0 and loaded on its other end face x = L by a uniform shear
    traction of resultant P per unit thickness: P L / (G d), G = E / (2 (1 + nu)).

    Holding the face x = 0 (two of its points suffice, its displacement being linear along it) makes
    du/dy = 0 there, and du/dy is uniform in the block: e_22 = 0 and the rotation equals e_12, so
    u_x = e_11 x, u_y = gamma x with gamma = 2 e_12. The load does work P gamma L, the strain energy is
    d L [(lambda + 2G) e_11^2 + G gamma^2] / 2 (plane strain), so e_11 = 0 and G d L gamma = P L:
    gamma = P / (G d), the mean shear stress P / d over G (the mean stress, module notes: the load and
    the reactions' resultants give sigma_12 = P L / (d L)). The loaded face moves by gamma L as a whole.

    This is the shear part of the Timoshenko cantilever (long_block_bending_deflection) with the shear
    coefficient 1 instead of 5/6 (uniform rather than parabolic shear), i.e. 5/6 of it, and nothing of
    the bending part 4 P L^3 / (E' d^3): the block is stiffer than the beam by a factor that grows as
    (L / d)^2 (NUREG/CR-5429 Fig. 1.3-5).
    """
    L, d = _positive("length", length), _positive("depth", depth)
    E, nu = _young_poisson(E, nu)
    P = _scalar("load", load)
    if not math.isfinite(P):
        raise ValueError(f"load = {P}: must be finite")
    return P * L / (E / (2.0 * (1.0 + nu)) * d)

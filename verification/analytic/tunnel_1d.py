"""A numerical reference for the circular tunnel in a Mohr-Coulomb medium that keeps the
out-of-plane stress: the axisymmetric, plane-strain, small-strain elastoplastic problem solved
in one dimension (radius), independently of vdec.

Salencon's closed form (plasticity.salencon_tunnel) takes szz as the intermediate principal
stress. From an in-situ szz = p0 it is not: near the wall szz reaches s_tt, the state sits on
the edge of the two faces, and the wall moves about 1 % further. This solves the whole problem:

- linear elements in r from a to `outer`, graded in proportion to r, one-point integration at
  the element's mid-radius: e_rr = (u2 - u1) / h, e_tt = (u1 + u2) / (2 r_m), e_zz = 0;
- plane-strain isotropic elasticity, Mohr-Coulomb on (s_rr, s_tt, szz) (tension positive,
  s1 <= s2 <= s3) with the flow rule of dilation psi: the return onto the main face
  f = s1 - N_phi s3 + 2 c sqrt(N_phi) along the potential g = s1 - N_psi s3, and onto the edge
  with the second face when the main-face return would reorder the stresses (two consistency
  conditions; de Souza Neto, Peric and Owen, Computational Methods for Plasticity, 2008, 8.2);
- the wall pressure lowered from p0 to pi in equal increments, the outer boundary held at the
  in-situ traction, each increment iterated with the elastic stiffness (initial-stiffness
  method) until the residual is below 1e-11 of the load.

With `outer` = 60 a the outer boundary moves the wall's displacement by about (R_p / outer)^2,
below 1e-3.
"""
import math

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl


def _return(s, D, n_phi, n_psi, k):
    """Mohr-Coulomb return of principal stresses s (rows, any order), vectorised."""
    order = np.argsort(s, axis=1)
    srt = np.take_along_axis(s, order, axis=1)
    f = srt[:, 0] - n_phi * srt[:, 2] + k
    out = srt.copy()
    y = f < 0.0
    if np.any(y):
        na, ma = np.array([1.0, 0.0, -n_phi]), np.array([1.0, 0.0, -n_psi])
        Dm = D @ ma
        face = srt[y] - np.outer(f[y] / (na @ Dm), Dm)
        low = face[:, 1] < face[:, 0]      # s2 became the most compressive: edge s1 = s2
        high = face[:, 1] > face[:, 2]     # s2 became the least compressive: edge s2 = s3
        for mask, nb, mb in ((low, np.array([0.0, 1.0, -n_phi]), np.array([0.0, 1.0, -n_psi])),
                             (high, np.array([1.0, -n_phi, 0.0]), np.array([1.0, -n_psi, 0.0]))):
            if not np.any(mask):
                continue
            A = np.array([[na @ D @ ma, na @ D @ mb], [nb @ D @ ma, nb @ D @ mb]])
            trial = srt[y][mask]
            rhs = np.stack([trial @ na + k, trial @ nb + k], axis=1)
            dl = np.linalg.solve(A, rhs.T).T
            face[mask] = trial - np.outer(dl[:, 0], D @ ma) - np.outer(dl[:, 1], D @ mb)
        out[y] = face
    result = np.empty_like(s)
    np.put_along_axis(result, order, out, axis=1)
    return result


def tunnel_1d(*, a, outer, p0, pi, szz0, bulk, shear, cohesion, friction_deg, dilation_deg,
              elements=400, increments=50):
    """The tunnel unloaded from the in-situ state (s_rr = s_tt = -p0, szz = szz0, tension
    positive) to the wall pressure pi; p0 and pi are pressures (compression positive). Returns a
    dict: 'r' (the nodes), 'ur' (radial displacement at the nodes, outward positive), 'r_mid'
    with 'srr', 'stt', 'szz' at the elements' mid-radii, and 'plastic_radius' (the largest
    mid-radius of an element on the yield surface, a if none)."""
    if not (0.0 < a < outer and elements >= 10 and increments >= 1):
        raise ValueError("need 0 < a < outer, at least 10 elements and one increment")
    phi, psi = math.radians(friction_deg), math.radians(dilation_deg)
    if not (0.0 < phi < math.pi / 2 and 0.0 <= psi <= phi):
        raise ValueError("friction in (0, 90) degrees and 0 <= dilation <= friction")
    a1, a2 = bulk + 4.0 * shear / 3.0, bulk - 2.0 * shear / 3.0
    D = np.array([[a1, a2, a2], [a2, a1, a2], [a2, a2, a1]])
    n_phi = (1 + math.sin(phi)) / (1 - math.sin(phi))
    n_psi = (1 + math.sin(psi)) / (1 - math.sin(psi))
    k = 2.0 * cohesion * math.sqrt(n_phi)
    r = a * (outer / a) ** (np.arange(elements + 1) / elements)
    h = np.diff(r)
    rm = 0.5 * (r[1:] + r[:-1])
    w = rm * h  # integration weight (per radian)
    # Strain-displacement rows: e_rr = (u2 - u1) / h, e_tt = (u1 + u2) / (2 rm).
    b1 = np.stack([-1.0 / h, 0.5 / rm, np.zeros_like(h)], axis=1)
    b2 = np.stack([1.0 / h, 0.5 / rm, np.zeros_like(h)], axis=1)
    Db1, Db2 = b1 @ D, b2 @ D
    k11 = np.einsum("ej,ej->e", Db1, b1) * w
    k12 = np.einsum("ej,ej->e", Db1, b2) * w
    k22 = np.einsum("ej,ej->e", Db2, b2) * w
    n = elements + 1
    rows = np.concatenate([np.arange(elements), np.arange(elements), np.arange(1, n), np.arange(1, n)])
    cols = np.concatenate([np.arange(elements), np.arange(1, n), np.arange(elements), np.arange(1, n)])
    K = sp.csc_matrix((np.concatenate([k11, k12, k12, k22]), (rows, cols)), shape=(n, n))
    solve = spl.factorized(K)
    sig = np.tile([-p0, -p0, szz0], (elements, 1)).astype(float)
    u = np.zeros(n)
    for step in range(1, increments + 1):
        wall = p0 + (pi - p0) * step / increments
        fext = np.zeros(n)
        fext[0] = a * wall
        fext[-1] = -outer * p0
        du = np.zeros(n)
        for _ in range(20000):
            de = b1 * du[:-1, None] + b2 * du[1:, None]
            trial = _return(sig + de @ D, D, n_phi, n_psi, k)
            fint = np.zeros(n)
            np.add.at(fint, np.arange(elements), np.einsum("ej,ej->e", b1, trial) * w)
            np.add.at(fint, np.arange(1, n), np.einsum("ej,ej->e", b2, trial) * w)
            residual = fext - fint
            if np.linalg.norm(residual) < 1e-11 * np.linalg.norm(fext):
                break
            du += solve(residual)
        else:
            raise RuntimeError(f"increment {step} did not converge")
        sig = trial
        u += du
    yielding = sig.min(axis=1) - n_phi * sig.max(axis=1) + k < 1e-6 * p0
    return {"r": r, "ur": u, "r_mid": rm, "srr": sig[:, 0], "stt": sig[:, 1], "szz": sig[:, 2],
            "plastic_radius": float(rm[yielding].max()) if np.any(yielding) else a}


_SOLUTIONS = {}


def _solution(*key):
    """tunnel_1d for the parameters in key (in its keyword order), computed once per process."""
    if key not in _SOLUTIONS:
        names = ("a", "outer", "p0", "pi", "szz0", "bulk", "shear", "cohesion", "friction_deg", "dilation_deg",
                 "elements", "increments")
        _SOLUTIONS[key] = tunnel_1d(**dict(zip(names, key)))
    return _SOLUTIONS[key]


def radial_displacement(*, r, a, outer, p0, pi, szz0, bulk, shear, cohesion, friction_deg, dilation_deg,
                        elements=400, increments=50):
    """u_r (outward positive) of tunnel_1d at the radii r, interpolated linearly between its nodes;
    a radius below a (a gridpoint of the wall moved inward) reads the wall's value. A field
    reference: the harness passes the samples' r. The solution is computed once per set of
    parameters (it takes about half a second)."""
    solution = _solution(float(a), float(outer), float(p0), float(pi), float(szz0), float(bulk), float(shear),
                         float(cohesion), float(friction_deg), float(dilation_deg), int(elements), int(increments))
    return np.interp(np.asarray(r, dtype=float), solution["r"], solution["ur"])

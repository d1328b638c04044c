r"""The kernels of the 3D panel method (:mod:`stripcoef.hull.panels`): the exact and the
quadrature influence of constant flat triangular panels, the influence matrices and the
one-level solve of the added mass.

With :math:`G = 1/(4\pi r)`, the source and dipole influence of panel :math:`T_l` at
:math:`x_k`, :math:`S_{kl} = \iint_{T_l} G\,dS` [m] and :math:`D_{kl} = \iint_{T_l}
\partial G/\partial n_\xi\,dS` [-], and the direct (Green's identity) equation
:math:`(\tfrac12 I - D)\Phi = -S N` (Hess & Smith 1967, Prog. Aero. Sci. 8; Newman 1977,
"Marine Hydrodynamics", eq. 4.97; Katz & Plotkin 2001, "Low-Speed Aerodynamics", 2nd ed.,
sec. 9.2-9.6 and 10.4); the method, its levels and their extrapolation:
:mod:`stripcoef.hull.panels`.  Apart so that :mod:`stripcoef.hull.mirror_panels` (the solve
with image panels) and :mod:`stripcoef.hull.panels` (which calls it) share them.
"""

from __future__ import annotations

import numpy as np

#: Pairs closer than this many source-panel diameters (longest edge) use the exact integrals [-].
NEAR_FACTOR = 2.0
#: Pairs closer than this many diameters (and not near) use a three-point rule; beyond, one
#: point: its relative error is below ~0.3 % per pair beyond 4 diameters (the leading error is
#: the panel's second moment over r^2, Katz & Plotkin 2001, sec. 10.4.1) [-].
MID_FACTOR = 4.0
_FOUR_PI = 4.0 * np.pi


def _frames(tri):
    """Centroids, unit normals, areas [m^2] and longest edges [m] of (n, 3, 3) triangles."""
    e1, e2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    cr = np.cross(e1, e2)
    area2 = np.linalg.norm(cr, axis=1)
    normal = cr / area2[:, None]
    edges = np.linalg.norm(tri[:, [1, 2, 0]] - tri, axis=2)
    return tri.mean(axis=1), normal, 0.5 * area2, edges.max(axis=1)


def triangle_integrals(points, tri, normal):
    r"""Exact influence of a unit constant source and a unit normal dipole on flat triangles.

    .. math::
        s = \frac{1}{4\pi}\iint_T \frac{dS}{|x - \xi|} \ [\mathrm{m}],\qquad
        d = \frac{1}{4\pi}\iint_T \frac{(x-\xi)\cdot n}{|x - \xi|^3}\,dS = -\frac{\Omega}{4\pi}
        \ [-]

    Pairwise: ``points`` (k, 3) [m], ``tri`` (k, 3, 3) [m] counter-clockwise about ``normal``
    (k, 3).  Source: Wilton et al. (1984), IEEE Trans. Antennas Propag. 32(3) 276-281,

    .. math:: \iint_T \frac{dS}{R} = \sum_{edges} t_0\,[\sinh^{-1}(s^+/R_0) -
              \sinh^{-1}(s^-/R_0)] - |h| \sum_{edges}\Big[\tan^{-1}\frac{t_0 s^+}{R_0^2 + |h|
              R^+} - \tan^{-1}\frac{t_0 s^-}{R_0^2 + |h| R^-}\Big]

    (h the height of x above the plane, t_0 its in-plane distance to the edge line, s^\pm the
    edge ends along it, :math:`R_0^2 = t_0^2 + h^2`).  Solid angle: van Oosterom & Strackee
    (1983), :math:`\tan(\Omega/2) = R_1\cdot(R_2\times R_3)/(r_1 r_2 r_3 + (R_1\cdot R_2) r_3
    + (R_1\cdot R_3) r_2 + (R_2\cdot R_3) r_1)`, :math:`R_k = v_k - x`; zero on the panel
    itself (principal value).
    """
    idx = np.arange(len(points))
    return pair_integrals(points, tri, normal, idx, idx)


def pair_integrals(points, tri, normal, k, l):
    r""":func:`triangle_integrals` of the pairs (point ``k``, panel ``l``) [m, -]: ``points``
    (m, 3), ``tri`` (n, 3, 3), ``normal`` (n, 3), index arrays ``k``, ``l``.  Each panel's
    edges (unit tangent, in-plane outward normal, length) are computed once and gathered per
    pair, and the sums run by coordinate components (the same formulas as
    :func:`triangle_integrals`; equal to round-off)."""
    edge = tri[:, [1, 2, 0]] - tri                             # (n, 3, 3) edge e: v_e -> v_e+1
    elen = np.linalg.norm(edge, axis=2)                        # (n, 3)
    lt = edge / elen[..., None]
    u = np.cross(lt, normal[:, None, :])                       # in-plane, out of the triangle
    tv = np.ascontiguousarray(tri.transpose(1, 2, 0))          # (3 vertices, 3 coords, n)
    ltc = np.ascontiguousarray(lt.transpose(1, 2, 0))
    uc = np.ascontiguousarray(u.transpose(1, 2, 0))
    lnc = np.ascontiguousarray(elen.T)
    nc = np.ascontiguousarray(normal.T)
    pc = np.ascontiguousarray(np.asarray(points, float).T)
    px, py, pz = pc[0][k], pc[1][k], pc[2][k]
    R = [(tv[v, 0][l] - px, tv[v, 1][l] - py, tv[v, 2][l] - pz) for v in range(3)]
    r = [np.sqrt(x * x + y * y + z * z) for x, y, z in R]

    def dot(a, b):
        # (+ 0.0: a sum of zeros is +0, as numpy's einsum and matmul give it; the sign of a
        # zero numerator is the side of the plane arctan2 takes for a point on a panel's
        # plane -- overlapping coplanar panels of a faceted input)
        return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + 0.0

    (x1, y1, z1), (x2, y2, z2) = R[1], R[2]
    num = dot(R[0], (y1 * z2 - z1 * y2, z1 * x2 - x1 * z2, x1 * y2 - y1 * x2))
    den = r[0] * r[1] * r[2] + dot(R[0], R[1]) * r[2] + dot(R[0], R[2]) * r[1] \
        + dot(R[1], R[2]) * r[0]
    omega = 2.0 * np.arctan2(num, den)
    h = -dot(R[0], (nc[0][l], nc[1][l], nc[2][l]))       # height of the point above the plane
    ah = np.abs(h)
    h2 = h * h
    total = np.zeros(len(k))
    for e in range(3):
        a = R[e]
        ln = lnc[e][l]
        t0 = dot(a, (uc[e, 0][l], uc[e, 1][l], uc[e, 2][l]))
        sm = dot(a, (ltc[e, 0][l], ltc[e, 1][l], ltc[e, 2][l]))
        sp = sm + ln
        r02 = t0 * t0 + h2
        ok = r02 > 1e-24 * ln * ln
        r0 = np.sqrt(np.where(ok, r02, 1.0))
        term = t0 * (np.arcsinh(sp / r0) - np.arcsinh(sm / r0)) - ah * (
            np.arctan(t0 * sp / (r02 + ah * r[(e + 1) % 3] + 1e-300))
            - np.arctan(t0 * sm / (r02 + ah * r[e] + 1e-300)))
        total += np.where(ok, term, 0.0)
    return total / _FOUR_PI, -omega / _FOUR_PI


def influence_matrices(tri, near_factor: float = NEAR_FACTOR, mid_factor: float = MID_FACTOR):
    r"""Source S [m] and dipole D [-] influence matrices of constant flat triangular panels.

    Row k: collocation point (centroid of panel k); column l: panel l.  Exact integrals
    (:func:`triangle_integrals`) within ``near_factor`` diameters (longest edge) of panel l;
    the three-point rule of degree 2 (Strang & Fix 1973, points at barycentric (2/3, 1/6, 1/6),
    weights A/3) within ``mid_factor`` diameters; the one-point rule
    :math:`S = A_l/(4\pi r)`, :math:`D = A_l\,(x_k - c_l)\cdot n_l/(4\pi r^3)` beyond
    (Katz & Plotkin 2001, sec. 10.4.1: the one-point error is the panel's second moment over
    r^2, below 0.3 % per pair beyond 4 diameters) -- or the three-point rule for all pairs
    when more than :data:`DENSE_MID_FRACTION` of them are in the mid zone.  The panels'
    own block of :func:`influence_at`.
    """
    return influence_at(_frames(tri)[0], tri, self_block=True, near_factor=near_factor,
                        mid_factor=mid_factor)


def _one_point(r2, x0, c0, n, w, self_block, rows: int = 256):
    r"""The one-point rule for every pair, :math:`S_{kl} = w_l/r`, :math:`D_{kl} = w_l\,
    (x_k - c_l)\cdot n_l/r^3`, :math:`w = A/(4\pi)` [m, -], from the squared distances ``r2``
    [m^2] (overwritten: it becomes S); coordinates ``x0``, ``c0`` shifted by one common
    point [m]; ``self_block``: the panel itself is left at r = 1 (overwritten afterwards).
    By blocks of ``rows`` points, so that the temporaries stay in cache (the same operations
    in the same order as on whole matrices)."""
    if self_block:
        np.fill_diagonal(r2, 1.0)
    cn = np.einsum("ij,ij->i", c0, n)[None, :]
    wr = w[None, :]
    dd = np.empty_like(r2)
    for a in range(0, len(r2), rows):
        b = slice(a, a + rows)
        inv_r = r2[b]
        np.maximum(inv_r, 1e-300, out=inv_r)
        np.sqrt(inv_r, out=inv_r)
        np.divide(1.0, inv_r, out=inv_r)
        # (x_k - c_l) . n_l A_l / (4 pi r^3)
        db = dd[b]
        np.matmul(x0[b], n.T, out=db)
        db -= cn
        db *= wr
        db *= inv_r
        db *= inv_r
        db *= inv_r
        inv_r *= wr
    return r2, dd


def squared_distances(points, c):
    """|x_k - c_l|^2 [m^2] of ``points`` (m, 3) to the centroids ``c`` (n, 3), by matrix
    products about the centroids' mean (round-off of the size of the body, not of its place)."""
    shift = c.mean(axis=0)
    x0, c0 = points - shift, c - shift
    r2 = x0 @ c0.T
    r2 *= -2.0
    r2 += np.einsum("ij,ij->i", x0, x0)[:, None]
    r2 += np.einsum("ij,ij->i", c0, c0)[None, :]
    return r2


def influence_at(points, tri, *, self_block: bool, dense: bool | None = None,
                 near_factor: float = NEAR_FACTOR, mid_factor: float = MID_FACTOR):
    r"""Source S [m] and dipole D [-] influence of the constant flat panels ``tri`` (n, 3, 3)
    [m] at ``points`` (m, 3) [m], by the rules of :func:`influence_matrices` (exact integrals
    within ``near_factor`` diameters, the three-point rule within ``mid_factor``, one point
    beyond); the three-point rule for every pair when ``dense`` (``None``: when more than
    :data:`DENSE_MID_FRACTION` of the pairs are in the mid zone).  ``self_block``: the points
    are the panels' own centroids (the panel itself: exact source, no dipole)."""
    c, n, area, diam = _frames(tri)
    shift = c.mean(axis=0)
    x0, c0 = points - shift, c - shift
    r2 = squared_distances(points, c)
    if self_block:
        np.fill_diagonal(r2, 0.0)
    # pairs within mid_factor diameters (near ones among them, the panel itself included),
    # found on r2 before it is reused
    mid = r2 < ((mid_factor * diam) ** 2)[None, :]
    kn, ln = _near_pairs(points, c, diam, r2, near_factor, mid_factor, self_block)
    mid[kn, ln] = False                    # (a near pair is within mid_factor diameters)
    if dense is None:
        dense = int(np.count_nonzero(mid)) > DENSE_MID_FRACTION * len(points) * len(c)
    w = area / _FOUR_PI
    if dense:
        # many pairs in the mid zone (long panels: frames of thin tubes): the three-point rule
        # for every pair in dense matrix products is cheaper than gathering them one by one
        # (it overwrites every pair: the one-point rule is not computed)
        s, dd = r2, np.empty_like(r2)
        _three_point_dense(x0, n, tri - shift, w, s, dd)
    else:
        s, dd = _one_point(r2, x0, c0, n, w, self_block)
    km, lm = np.nonzero(mid) if not dense else ((), ())
    if len(km):
        # the three-point rule pair by pair (each panel's points computed once, then gathered)
        sk = np.zeros(len(km))
        dk = np.zeros(len(km))
        pk, nl = points[km], n[lm]
        for q in range(3):
            xi = (2.0 / 3.0) * tri[:, q] + (1.0 / 6.0) * (tri[:, (q + 1) % 3]
                                                          + tri[:, (q + 2) % 3])
            dq = pk - xi[lm]
            iq = 1.0 / np.sqrt(np.einsum("ij,ij->i", dq, dq))
            sk += iq
            dk += np.einsum("ij,ij->i", dq, nl) * iq ** 3
        s[km, lm] = sk * w[lm] / 3.0
        dd[km, lm] = dk * w[lm] / 3.0
    for sl in np.array_split(np.arange(len(kn)), max(1, len(kn) // 200000)):
        sk, dk = pair_integrals(points, tri, n, kn[sl], ln[sl])
        s[kn[sl], ln[sl]] = sk
        dd[kn[sl], ln[sl]] = dk
    if self_block:
        np.fill_diagonal(dd, 0.0)       # principal value on the panel itself (flat: no dipole)
    return s, dd


def _near_pairs(points, c, diam, r2, near_factor, mid_factor, self_block):
    r"""Indices (k, l) of the pairs within ``near_factor`` diameters, :math:`|x_k - c_l|^2 <
    (f\,d_l)^2` with the distance taken directly (not from the matrix products of ``r2``,
    whose round-off is of the size of the body), row by row, among the pairs that ``r2``
    places within ``mid_factor`` diameters; and the panel itself when ``self_block``.  Only
    the pairs that ``r2`` places within the threshold plus a bound on
    its round-off (:math:`64\,\epsilon\,(\max|x_k - m| + \max|c_l - m|)^2`, m the centroids'
    mean as in :func:`squared_distances`) are measured again: the same pairs as measuring
    every pair."""
    shift = c.mean(axis=0)
    reach = (np.sqrt(np.einsum("ij,ij->i", points - shift, points - shift)).max()
             + np.sqrt(np.einsum("ij,ij->i", c - shift, c - shift)).max())
    slack = 64.0 * np.finfo(float).eps * reach * reach
    limit = (near_factor * diam) ** 2
    k, l = np.nonzero(r2 < np.minimum(limit + slack, (mid_factor * diam) ** 2)[None, :])
    dkl = points[k] - c[l]
    near = np.einsum("ij,ij->i", dkl, dkl) < limit[l]
    if self_block:
        near |= k == l
    return k[near], l[near]


#: Share of all pairs in the mid zone beyond which the three-point rule is applied to every
#: pair at once (:func:`_three_point_dense`) [-]; a choice of speed, not of accuracy (the
#: three-point rule is at least as accurate as the one-point rule it replaces far away).
DENSE_MID_FRACTION = 0.1


def _three_point_dense(c0, n, tri0, w, s, dd, rows: int = 256):
    r"""Overwrite S and D [m, -] by the three-point rule (Strang & Fix 1973, degree 2) for all
    pairs: :math:`S_{kl} = \frac{w_l}{3}\sum_q 1/|x_k - \xi_{lq}|`, :math:`D_{kl} =
    \frac{w_l}{3}\sum_q (x_k - \xi_{lq})\cdot n_l / |x_k - \xi_{lq}|^3`, w = A/(4 pi);
    coordinates ``c0``, ``tri0`` shifted by one common point [m] (the near pairs are
    overwritten afterwards by the exact integrals).  By blocks of ``rows`` points, so that the
    temporaries stay in cache (the same operations in the same order as on whole matrices)."""
    cc = np.einsum("ij,ij->i", c0, c0)
    xis = [(2.0 / 3.0) * tri0[:, q] + (1.0 / 6.0) * (tri0[:, (q + 1) % 3] + tri0[:, (q + 2) % 3])
           for q in range(3)]
    xx = [np.einsum("ij,ij->i", xi, xi)[None, :] for xi in xis]
    xn = [np.einsum("ij,ij->i", xi, n)[None, :] for xi in xis]
    w3 = (w / 3.0)[None, :]
    for a in range(0, len(c0), rows):
        b = slice(a, a + rows)
        cn = c0[b] @ n.T
        sb, db = s[b], dd[b]
        sb[:] = 0.0
        db[:] = 0.0
        for q in range(3):
            r2 = c0[b] @ xis[q].T
            r2 *= -2.0
            r2 += cc[b, None]
            r2 += xx[q]
            np.maximum(r2, 1e-300, out=r2)
            ir = np.sqrt(r2, out=r2)
            np.divide(1.0, ir, out=ir)
            sb += ir
            t = cn - xn[q]
            t *= ir
            t *= ir
            t *= ir
            db += t
        sb *= w3
        db *= w3


def generalised_normals(centers, normals, about=(0.0, 0.0, 0.0)):
    r"""(n, 6) generalised normals :math:`(n, (x - x_{ref})\times n)` [-, m] (Newman 1977,
    eq. 4.104)."""
    return np.hstack([normals, np.cross(centers - np.asarray(about, float), normals)])


def solve_added_mass(tri, *, rho: float, about=(0.0, 0.0, 0.0),
                     near_factor: float = NEAR_FACTOR) -> np.ndarray:
    r"""6x6 added mass [kg, kg m, kg m^2] of one panelling (no extrapolation, not symmetrised).

    Solves :math:`(\tfrac12 I - D)\Phi = -S N` (module docstring) by one LU and returns
    :math:`A_{ij} = -\rho \sum_k a_k n_i(x_k)\,\Phi_{kj}` (Newman 1977, eq. 4.148).
    ``tri`` (n, 3, 3) [m], counter-clockwise seen from the fluid (normals out of the body).
    """
    import scipy.linalg

    tri = np.asarray(tri, dtype=float)
    c, n, area, _ = _frames(tri)
    s, d = influence_matrices(tri, near_factor)
    nrm = generalised_normals(c, n, about)
    lhs = -d
    lhs[np.diag_indices_from(lhs)] += 0.5
    phi = scipy.linalg.solve(lhs, -(s @ nrm), overwrite_a=True, check_finite=False)
    return -rho * (nrm * area[:, None]).T @ phi

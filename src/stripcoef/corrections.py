r"""3D corrections of strip theory from an axisymmetric boundary-element solution.

Strip theory integrates 2D section added mass along the body, which ignores the
flow around the ends: it overestimates the transverse terms (sway/heave) by
5-10 % and the rotational ones (pitch/yaw) by 20-30 % on typical hulls, and
gives no axial (surge) added mass at all.

This module solves the 3D potential flow exactly (to discretisation error)
about the *equivalent body of revolution* of the strips -- the body with the
same section area at every x, :math:`r_{eq}(x) = \sqrt{A(x)/\pi}` -- with an
axisymmetric boundary-element method, and returns

- its axial added mass :math:`m_{11}` (used directly for surge), and
- the 3D/strip ratios of its transverse and rotational added mass,

  .. math:: f_t = \frac{m_{22}^{3D}}{\int \rho\pi r_{eq}^2 dx},\qquad
            f_r = \frac{m_{66}^{3D}}{\int \rho\pi r_{eq}^2 (x - x_c)^2 dx}

  which scale the strip-theory matrix of the real sections (end correction).

For a spheroid both are Lamb's exact values; for blunt bodies (capsules,
Myring hulls with flat tails, boxes) they replace the equal-volume spheroid of
:func:`stripcoef.hull.end_correction_factors`, whose axial term is 30 % low on
a capsule.

Method (direct boundary-integral formulation in Fourier modes)
---------------------------------------------------------------
With :math:`G = -1/(4\pi R)` and n out of the body, Green's identity at a
surface point p reads

.. math:: \tfrac12\phi(p) + \iint_S \phi\,\frac{\partial G}{\partial n_q}\,dS_q
          = \iint_S G\,\frac{\partial\phi}{\partial n_q}\,dS_q .

On a body of revolution (x axis, :math:`y = r\cos\theta`, :math:`z = r\sin\theta`)
each rigid mode has :math:`\phi = \phi_m(s)\cos m\theta` with m = 0 for surge
(:math:`\partial\phi/\partial n = n_x`) and m = 1 for sway
(:math:`n_r`) and yaw (:math:`x n_r - r n_x`).  The :math:`\theta` integrals of
the kernels are complete elliptic integrals: with
:math:`P = (x-x')^2 + r^2 + r'^2`, :math:`Q = 2rr'`,
:math:`A^2 = P + Q`, :math:`B^2 = P - Q`, :math:`k^2 = 2Q/A^2`,

.. math:: \int_0^{2\pi}\!\frac{d\theta}{R} = \frac{4K(k)}{A},\quad
          \int_0^{2\pi}\!R\,d\theta = 4AE(k),\quad
          \int_0^{2\pi}\!\frac{d\theta}{R^3} = \frac{4E(k)}{AB^2},

and :math:`\cos\theta = (P - R^2)/Q` gives the :math:`\cos\theta`,
:math:`\cos^2\theta` moments (Gradshteyn & Ryzhik 2007, 2.571, 8.111-8.112;
the ring-source kernels of Hess & Smith 1967, *Prog. Aerosp. Sci.* 8, sec. 5).
The meridian is cut into straight (conical) panels of constant potential;
panel integrals use Gauss-Legendre points, clustered towards the collocation
point on the panel itself and on its neighbours (log-singular kernels).
Added mass (Newman 1977, eq. 4.148):

.. math:: m_{11} = -2\pi\rho\int \phi_0 n_x r\,ds,\quad
          m_{22} = -\pi\rho\int \phi_{1,v} n_r r\,ds,\quad
          m_{66} = -\pi\rho\int \phi_{1,r} (x n_r - r n_x) r\,ds .

References
----------
Newman, J. N. (1977) *Marine Hydrodynamics*, sec. 4.13-4.15 and 7.4 (slender
bodies and their end effects).  Lamb, H. (1932) *Hydrodynamics*, sec. 373
(spheroid coefficients, the exact check).  Hess, J. L. & Smith, A. M. O. (1967)
"Calculation of potential flow about arbitrary bodies", *Prog. Aerosp. Sci.* 8.
"""

from __future__ import annotations

import functools
import math

import numpy as np
from scipy.special import ellipe, ellipk

from stripcoef.errors import InputError

#: Lateral-equivalent bodies closed to r = 0 at the ends (False: blunt ends keep their flat faces,
#: which rock in pitch and yaw; measured: no difference on the open-frame ROV benchmark).
CLOSED_ENDS = False
#: Meridian panels used by default.
DEFAULT_PANELS = 160
#: 2D roll added mass below this fraction of rho A^2 is round-off, not roll (a circle's panel
#: solution gives ~1e-29 of it): :func:`roll_relief` has nothing to relieve [-]
ROLL_ROUNDOFF = 1e-9
#: sway and heave sections equal to this relative tolerance share one equivalent body [-]
SAME_BODY_RTOL = 1e-10
_GAUSS_FAR = np.polynomial.legendre.leggauss(4)
_GAUSS_NEAR = np.polynomial.legendre.leggauss(12)
# the near rule: 12-point Gauss-Legendre on u in (0, 1) mapped by t = u^3 (cubic clustering
# towards t = 0, the end nearest to the collocation point): points t and weights 3u^2 w/2
_CLUSTER_T = (0.5 * (_GAUSS_NEAR[0] + 1.0)) ** 3
_CLUSTER_W = 3.0 * (0.5 * (_GAUSS_NEAR[0] + 1.0)) ** 2 * 0.5 * _GAUSS_NEAR[1]
# the own-panel rule: the near rule on each half of the panel from its mid-point outwards, as
# columns (rows: the 12 points forwards, then the 12 backwards): direction, t, weight
_HALVES_SIGN = np.repeat([1.0, -1.0], _CLUSTER_T.size)[:, None]
_HALVES_T = np.tile(_CLUSTER_T, 2)[:, None]
_HALVES_W = np.tile(_CLUSTER_W, 2)[:, None]
#: far-panel kernels are evaluated in equal blocks of collocation rows with at most about this
#: many (Gauss point, collocation point, panel) triples each (one block up to n = 78 panels).
#: Measured after a mesh pipeline (benchmarks/mesh_speed.py): the whole (4, n, n) at once is
#: 2x slower at n = 166 (its multi-MB temporaries go back to the system and are faulted in
#: again on every call); 8192-triple blocks cost 0.1 ms per extra block at n = 78.
_BLOCK_PAIRS = 24576
_TRAP_THETA = 16
# The integrands are even in theta (they depend on it through cos theta only), so the 16 nodes
# theta_k = 2 pi k / 16 of the periodic trapezoid rule take only the 9 values cos(theta_k),
# k = 0..8 (nodes k and 16 - k coincide): the rule is evaluated on those 9, nodes 1..7 counted
# twice.  Same rule, same result to round-off, 9/16 of the square roots.
_TRAP_COS = np.cos(2.0 * np.pi * np.arange(_TRAP_THETA // 2 + 1) / _TRAP_THETA)
_TRAP_COUNT = np.r_[1.0, np.full(_TRAP_THETA // 2 - 1, 2.0), 1.0]
#: trapezoid weights times cos^k theta, k = 0, 1, 2 (rows), on the 9 distinct nodes (columns)
_TRAP_W = (2.0 * np.pi / _TRAP_THETA * _TRAP_COUNT[None, :]
           * _TRAP_COS[None, :] ** np.arange(3)[:, None])


def _ring_integrals(p, q):
    r"""Elliptic-integral forms of the ring integrals with :math:`R^2 = P - Q\cos\theta`.

    .. math:: A^2 = P + Q,\ B^2 = P - Q,\ m = 2Q/A^2,\quad
              I_0 = \int_0^{2\pi}\frac{d\theta}{R} = \frac{4K(m)}{A},\quad
              I_1 = \int_0^{2\pi}\frac{\cos\theta\,d\theta}{R} = \frac{P I_0 - 4AE(m)}{Q}

    ``p`` [m^2], ``q`` [m^2]; returns A [m], B^2 [m^2], K, E [-], I_0, I_1 [1/m].
    Gradshteyn & Ryzhik (2007), 2.571 and 8.111-8.112.
    """
    a2 = p + q
    b2 = np.maximum(p - q, 1e-300)
    a = np.sqrt(a2)
    m = np.clip(2.0 * q / a2, 0.0, 1.0 - 1e-16)
    kk, ee = ellipk(m), ellipe(m)
    i0 = 4.0 * kk / a
    i1 = (p * i0 - 4.0 * a * ee) / q
    return a, b2, kk, ee, i0, i1


def _inverse_distances(cos_nodes, p, q):
    r"""1/R and 1/R^3 at the trapezoid nodes of every far ring pair: (nodes, N) arrays,

    .. math:: R_{kn} = \sqrt{P_n - Q_n\cos\theta_k}

    (``cos_nodes`` :math:`\cos\theta_k` [-], ``p``, ``q`` (N,) [m^2]; R [m]).  1/R is built in
    one buffer (R^2, then R, then 1/R in place: fewer large temporaries).
    """
    inv = np.multiply.outer(cos_nodes, q)
    np.subtract(p, inv, out=inv)
    np.sqrt(inv, out=inv)
    np.divide(1.0, inv, out=inv)
    inv3 = inv * inv
    inv3 *= inv
    return inv, inv3


def _theta_moments(x, r, xq, rq, m):
    r"""theta-integrals over [0, 2 pi] that the mode-m kernels need (m = 0 or 1):

    .. math:: I_m = \int\frac{\cos^m\theta}{R}d\theta,\quad
              J_m = \int\frac{\cos^m\theta}{R^3}d\theta,\quad
              J_{m+1} = \int\frac{\cos^{m+1}\theta}{R^3}d\theta

    Elliptic-integral closed forms where the ring is near (Q/P >= 0.25); a
    periodic trapezoid rule (spectrally accurate) where it is far.

    :math:`R^2 = P - Q\cos\theta`; :math:`I_0 = 4K/A`, :math:`J_0 = 4E/(AB^2)`, and by
    recursion :math:`I_1 = (P I_0 - 4AE)/Q`, :math:`J_1 = (P J_0 - I_0)/Q`,
    :math:`J_2 = (P J_1 - I_1)/Q`. ``x, r, xq, rq`` [m] (arrays that broadcast together);
    returns (I_m [1/m], J_m, J_{m+1} [1/m^3]). Gradshteyn & Ryzhik (2007), 2.571,
    8.111-8.112 (module docstring).
    """
    dx2 = (x - xq) ** 2
    p = dx2 + r * r + rq * rq
    q = np.broadcast_to(2.0 * r * rq, p.shape)
    far = q < 0.25 * p
    i_m, j_m, j_m1 = np.empty_like(p), np.empty_like(p), np.empty_like(p)
    if np.any(far):
        pf, qf = p[far], q[far]                        # all far pairs, flattened: (N,)
        inv, inv3 = _inverse_distances(_TRAP_COS, pf, qf)                # (9, N) each
        i_m[far] = _TRAP_W[m] @ inv                     # sum of w c^m / R
        m3 = _TRAP_W[m:m + 2] @ inv3                    # sums of w c^m / R^3, w c^(m+1) / R^3
        j_m[far], j_m1[far] = m3[0], m3[1]
    near = ~far
    if np.any(near):
        pn, qn = p[near], q[near]
        a, b2, kk, ee, i0, i1 = _ring_integrals(pn, qn)
        j0 = 4.0 * ee / (a * b2)
        j1 = (pn * j0 - i0) / qn
        if m == 0:
            i_m[near], j_m[near], j_m1[near] = i0, j0, j1
        else:
            i_m[near], j_m[near], j_m1[near] = i1, j1, (pn * j1 - i1) / qn   # J_2
    return i_m, j_m, j_m1


def _kernels(xc, rc, xq, rq, nxq, nrq, mode):
    r"""S and D kernels per unit meridian length at collocation (xc, rc) from ring (xq, rq).

    .. math:: S_m = -\frac{r_q}{4\pi}\int\frac{\cos m\theta}{R}d\theta,\quad
              D_m = \frac{r_q}{4\pi}\int\frac{(q-p)\cdot n_q\,\cos m\theta}{R^3}d\theta,
              \quad (q-p)\cdot n_q = (x_q - x_c)n_x + n_r r_q - n_r r_c\cos\theta

    (G = -1/(4 pi R), module docstring; Hess & Smith 1967, sec. 5). Positions [m], normals
    [-]; S [-] and D [1/m] per unit meridian length.  For m = 0, 1:
    :math:`S_m = -r_q I_m/4\pi`, :math:`D_m = r_q(b J_m - n_r r_c J_{m+1})/4\pi` with
    :math:`b = (x_q - x_c)n_x + n_r r_q` (:func:`_theta_moments`).
    """
    if mode >= 2:
        return _mode_kernels(xc, rc, xq, rq, nxq, nrq, mode)
    i_m, j_m, j_m1 = _theta_moments(xc, rc, xq, rq, mode)
    base = (xq - xc) * nxq + nrq * rq
    s = -rq * i_m / (4.0 * np.pi)
    d = rq * (base * j_m - nrq * rc * j_m1) / (4.0 * np.pi)
    return s, d


_TRAP_THETA_MODE = 48


@functools.lru_cache(maxsize=None)
def _mode_trapezoid(mode):
    r"""The 48-point periodic trapezoid rule of :func:`_mode_kernels` for Fourier mode
    ``mode``, on its 25 distinct values of :math:`\cos\theta` (the integrands are even in
    theta, as for :data:`_TRAP_COS`; nodes 1..23 counted twice).

    Returns the nodes :math:`c_k = \cos\theta_k` (25,) and read-only weights W (3, 25) with
    :math:`\sum_k W_{0k}/R_k \approx \int_0^{2\pi}\cos m\theta/R\,d\theta`,
    :math:`\sum_k W_{1k}/R_k^3 \approx \int\cos m\theta/R^3\,d\theta` and
    :math:`\sum_k W_{2k}/R_k^3 \approx \int\cos\theta\cos m\theta/R^3\,d\theta`
    [rad]. Built once per mode (cached).
    """
    half = _TRAP_THETA_MODE // 2
    th = 2.0 * np.pi * np.arange(half + 1) / _TRAP_THETA_MODE
    count = np.r_[1.0, np.full(half - 1, 2.0), 1.0]        # nodes k and 48 - k coincide
    c = np.cos(th)
    wcm = 2.0 * np.pi / _TRAP_THETA_MODE * count * np.cos(mode * th)
    weights = np.array([wcm, wcm, c * wcm])
    weights.setflags(write=False)
    c.setflags(write=False)
    return c, weights


def _toroidal(chi, kmax):
    r"""Toroidal Legendre functions :math:`Q_{k-1/2}(\chi)`, k = 0..kmax, and their derivatives.

    .. math:: Q_{-1/2} = \kappa K(\kappa^2),\quad
              Q_{1/2} = \chi\kappa K(\kappa^2) - \sqrt{2(\chi+1)}E(\kappa^2),\quad
              \kappa^2 = \frac{2}{\chi+1},

    :math:`(n+1)Q_{n+1} = (2n+1)\chi Q_n - nQ_{n-1}`, and
    :math:`(\chi^2-1)Q'_n = n(\chi Q_n - Q_{n-1})` with :math:`Q_{-3/2} = Q_{1/2}`
    (Abramowitz & Stegun 1964, 8.5.3, 8.5.4, 8.13.3; Gradshteyn & Ryzhik 2007, 8.834).
    ``chi`` >= 1 [-]; upward recurrence, used for chi <= 4 (near rings) where it is stable
    to ~1e-7 for k <= 6. Returns arrays (kmax + 2, ...) of Q and of
    :math:`n(\chi Q_n - Q_{n-1})` (the derivative without its :math:`1/(\chi^2-1)`).
    """
    k2 = np.clip(2.0 / (chi + 1.0), 0.0, 1.0 - 1e-16)
    kk, ee = ellipk(k2), ellipe(k2)
    q = [np.sqrt(k2) * kk, chi * np.sqrt(k2) * kk - np.sqrt(2.0 * (chi + 1.0)) * ee]
    for k in range(1, kmax + 1):
        n = k - 0.5
        q.append(((2 * n + 1) * chi * q[k] - n * q[k - 1]) / (n + 1))
    q = np.array(q)
    dn = np.empty_like(q)
    dn[0] = -0.5 * (chi * q[0] - q[1])
    for k in range(1, q.shape[0]):
        dn[k] = (k - 0.5) * (chi * q[k] - q[k - 1])
    return q, dn


def _mode_kernels(xc, rc, xq, rq, nxq, nrq, mode, own_panel=False):
    r"""S and D kernels of Fourier mode m >= 2 (as :func:`_kernels` for m = 0, 1).

    .. math:: \int_0^{2\pi}\frac{\cos m\theta}{R}d\theta = \frac{2\sqrt2}{\sqrt Q}Q_{m-1/2}(\chi),
              \quad \int_0^{2\pi}\frac{\cos m\theta}{R^3}d\theta
              = -\frac{4\sqrt2}{Q^{3/2}}Q'_{m-1/2}(\chi),\quad \chi = P/Q

    (:func:`_toroidal`; R^2 = P - Q cos theta), :math:`\cos\theta\cos m\theta =
    \frac12(\cos(m+1)\theta + \cos(m-1)\theta)`, and on the collocation point's own panel
    :math:`\int(1-\cos\theta)\cos m\theta/R^3 = (I_m - B^2J_m)/Q`, :math:`B^2 = P - Q`,
    without cancellation.  Far rings (Q < P/4): periodic trapezoid rule.  Units as
    :func:`_kernels`.
    """
    xc, rc, xq, rq, nxq, nrq = np.broadcast_arrays(xc, rc, xq, rq, nxq, nrq)
    p = (xc - xq) ** 2 + rc * rc + rq * rq
    q = 2.0 * rc * rq
    far = q < 0.25 * p
    im = np.empty(p.shape)
    jc = np.empty(p.shape)          # int cos(theta) cos(m theta) / R^3
    jm = np.empty(p.shape)
    b2jm = np.empty(p.shape)
    if np.any(far):
        c, wts = _mode_trapezoid(mode)
        pf, qf = p[far], q[far]
        inv, inv3 = _inverse_distances(c, pf, qf)                        # (25, N) each
        im[far] = wts[0] @ inv
        jm[far], jc[far] = wts[1:] @ inv3
        b2jm[far] = (pf - qf) * jm[far]
    near = ~far
    if np.any(near):
        pn, qn = p[near], q[near]
        chi = pn / qn
        tq, dn = _toroidal(chi, mode + 1)
        sq = np.sqrt(qn)
        im[near] = 2.0 * np.sqrt(2.0) * tq[mode] / sq
        # J_k = -4 sqrt2 dn_k / ((chi^2 - 1) Q^1.5);  B^2 J_k = -4 sqrt2 dn_k / ((chi + 1) sqrt Q)
        b2j = -4.0 * np.sqrt(2.0) * dn / ((chi + 1.0) * sq)
        b2 = np.maximum(pn - qn, 1e-300)
        jk = b2j / b2
        jm[near] = jk[mode]
        jc[near] = 0.5 * (jk[mode + 1] + jk[mode - 1])
        b2jm[near] = b2j[mode]
    s = -rq * im / (4.0 * np.pi)
    if own_panel:
        d = rq * nrq * rc * (im - b2jm) / q / (4.0 * np.pi)
    else:
        base = (xq - xc) * nxq + nrq * rq
        d = rq * (base * jm - nrq * rc * jc) / (4.0 * np.pi)
    return s, d


def mode_inertia(x, r, *, mode: int, rho: float, panels: int = DEFAULT_PANELS) -> float:
    r"""3D inertia of the Fourier mode ``mode`` = m >= 2 of a body of revolution.

    The body's surface moves with normal velocity :math:`v_n = r\,n_r\cos m\theta` (a radial
    field :math:`u_r = r\cos m\theta`; on a cylinder of radius r the 2D value is
    :math:`\rho\pi r^4/m` per unit length, from :math:`\phi = -(r^2/m)(r/\varrho)^m\cos m\theta`),
    and

    .. math:: I_m = -\rho\iint_S\phi\,v_n\,dS = -\pi\rho\int\phi_m(s)\,r^2 n_r\,ds

    with :math:`\phi_m` from the direct boundary-integral equation of the module docstring in
    mode m.  ``x, r`` [m] as :func:`body_of_revolution_added_mass`, ``rho`` [kg/m^3]; returns
    I_m [kg m^2].  References: Newman (1977) sec. 4.13 (2D multipoles); Hess & Smith (1967)
    sec. 5 (ring kernels); Abramowitz & Stegun (1964) ch. 8 (toroidal functions).
    """
    xn, rn = _meridian(x, r, int(panels))
    S, D, (length, nx, nr, xc, rc) = _influence(xn, rn, int(mode))
    A = D + 0.5 * np.eye(D.shape[0])
    bc = rc * nr
    phi = np.linalg.solve(A, S @ bc)
    return float(-np.pi * rho * np.sum(phi * rc * bc * length))


def _panel_geometry(xn, rn):
    dx, dr = np.diff(xn), np.diff(rn)
    length = np.hypot(dx, dr)
    tx, tr = dx / length, dr / length
    # meridian runs from the nose (x min) to the tail; the outward normal is (-tr, tx)
    return length, tx, tr, -tr, tx


def _influence(xn, rn, mode):
    r"""Influence matrices S, D of Fourier mode ``mode`` on the open meridian (xn, rn).

    .. math:: S_{ij} = \int_{panel\ j} S_m(c_i, q)\,ds_q,\qquad
              D_{ij} = \int_{panel\ j} D_m(c_i, q)\,ds_q

    with the ring kernels :func:`_kernels` (own panel: :func:`_self_kernels`) and the
    collocation points :math:`c_i` at the panel mid-points.  Far panels: 4-point
    Gauss-Legendre; the collocation point's own panel and its two neighbours: 12-point
    Gauss-Legendre clustered cubically towards the collocation point (log-singular kernels;
    own panel: two halves from the mid-point outwards).  Nodes ``xn, rn`` [m]; returns
    S [m], D [-] and (panel length [m], n_x, n_r [-], x_c, r_c [m]).  Hess & Smith (1967),
    sec. 5 (module docstring).

    Each rule is evaluated on whole arrays instead of a loop over its points: the far rule
    on (Gauss point, collocation point, panel) arrays of shape (4, rows, n) (blocks of
    collocation rows, :data:`_BLOCK_PAIRS`), the neighbour and own-panel rules in one kernel
    call each on (point, pair) arrays; the point axis (axis 0) is then summed in order, as
    the loop over the points did.
    """
    n = xn.size - 1
    length, tx, tr, nx, nr = _panel_geometry(xn, rn)
    xc, rc = 0.5 * (xn[1:] + xn[:-1]), 0.5 * (rn[1:] + rn[:-1])
    # far panels: 4 Gauss points on every panel j, (4, n) arrays (row k: point k of each panel)
    g, w = _GAUSS_FAR
    xq = xc + 0.5 * g[:, None] * length * tx
    rq = rc + 0.5 * g[:, None] * length * tr
    wl = (0.5 * w[:, None] * length)[:, None, :]      # Gauss weight times panel length (4, 1, n)
    S = np.empty((n, n))
    D = np.empty((n, n))
    # kernels for every (point k, collocation point i, panel j): shape (4, rows, n), in blocks
    # of collocation rows (see _BLOCK_PAIRS)
    blocks = math.ceil(xq.size * n / _BLOCK_PAIRS)
    rows = math.ceil(n / blocks)                       # equal blocks, the last one shorter
    for i0 in range(0, n, rows):
        b = slice(i0, i0 + rows)
        s, d = _kernels(xc[None, b, None], rc[None, b, None], xq[:, None, :], rq[:, None, :],
                        nx[None, None, :], nr[None, None, :], mode)
        S[b] = np.sum(s * wl, axis=0)
        D[b] = np.sum(d * wl, axis=0)
    # neighbouring panels j = i - 1 and j = i + 1 (pairs flattened: (2n - 2,)), integrated
    # from the end nearest to the collocation point into the panel; points along axis 0
    tcl, wcl = _CLUSTER_T[:, None], _CLUSTER_W[:, None]
    i = np.concatenate([np.arange(1, n), np.arange(0, n - 1)])
    j = np.concatenate([np.arange(0, n - 1), np.arange(1, n)])
    after = j > i                       # panel after i: start at its first node, go forwards
    start_x = np.where(after, xn[j], xn[j + 1])
    start_r = np.where(after, rn[j], rn[j + 1])
    dirn = np.where(after, 1.0, -1.0)
    sq = tcl * length[j]                # arc length from the start node (12, 2n - 2)
    s, d = _kernels(xc[i], rc[i], start_x + dirn * sq * tx[j], start_r + dirn * sq * tr[j],
                    nx[j], nr[j], mode)
    S[i, j] = np.sum(s * wcl * length[j], axis=0)
    D[i, j] = np.sum(d * wcl * length[j], axis=0)
    # own panel: its two halves from the mid-point outwards, (24, n) arrays
    sq = _HALVES_T * 0.5 * length
    s, d = _self_kernels(xc, rc, xc + _HALVES_SIGN * sq * tx, rc + _HALVES_SIGN * sq * tr,
                         nx, nr, mode)
    own = np.arange(n)
    S[own, own] = np.sum(s * _HALVES_W * 0.5 * length, axis=0)
    D[own, own] = np.sum(d * _HALVES_W * 0.5 * length, axis=0)
    return S, D, (length, nx, nr, xc, rc)


def _self_kernels(xc, rc, xq, rq, nxq, nrq, mode):
    """Kernels on the collocation point's own (straight) panel, cancellation-free:
    there (q - p) . n = n_r r (1 - cos theta) exactly.

    Same S_m, D_m as :func:`_kernels` with (q - p) . n_q = n_r r_c (1 - cos theta), so
    D_m = r_q n_r r_c/(4 pi) int (1 - cos theta) cos(m theta)/R^3 dtheta (module docstring).
    Units as :func:`_kernels`.
    """
    if mode >= 2:
        return _mode_kernels(xc, rc, xq, rq, nxq, nrq, mode, own_panel=True)
    dx2 = (xc - xq) ** 2
    p = dx2 + rc * rc + rq * rq
    q = 2.0 * rc * rq
    a, b2, kk, ee, i0, i1 = _ring_integrals(p, q)
    if mode == 0:
        s = -rq * i0 / (4.0 * np.pi)
        jdiff = 4.0 * (kk - ee) / (a * q)                 # int (1 - cos)/R^3
    else:
        s = -rq * i1 / (4.0 * np.pi)
        j0 = 4.0 * ee / (a * b2)
        j1 = (p * j0 - i0) / q
        jdiff = (i1 - b2 * j1) / q                        # int (1 - cos) cos / R^3
    d = rq * nrq * rc * jdiff / (4.0 * np.pi)
    return s, d


def _meridian(x, r, panels, area_linear=False):
    r"""Closed meridian from the nose tip (r = 0) to the tail tip, resampled by arc length
    with cosine clustering towards both ends; between the given points r is linear in x, or
    with ``area_linear`` the area :math:`\pi r^2` is (r = sqrt of the linear interpolant of
    r^2: round noses and tails sampled at a few stations are followed, not cut by chords)."""
    x = np.asarray(x, dtype=float)
    r = np.asarray(r, dtype=float)
    if x.ndim != 1 or x.shape != r.shape or x.size < 2 or np.any(np.diff(x) < 0) \
            or np.any(r < 0) or not np.all(np.isfinite(x)) or not np.all(np.isfinite(r)):
        raise InputError("profile must be non-decreasing x with finite radii >= 0",
                         key="profile", value=f"{x.size} points", expected="x increasing, r >= 0")
    if r[0] > 0:
        x, r = np.concatenate([x[:1], x]), np.concatenate([[0.0], r])
    if r[-1] > 0:
        x, r = np.concatenate([x, x[-1:]]), np.concatenate([r, [0.0]])
    seg = np.hypot(np.diff(x), np.diff(r))
    keep = seg > 1e-12 * max(x[-1] - x[0], 1e-300)      # x is non-decreasing
    if not keep.all():                                  # drop repeated points
        keep = np.concatenate([[True], keep])
        x, r = x[keep], r[keep]
        seg = np.hypot(np.diff(x), np.diff(r))
    s = np.concatenate([[0.0], np.cumsum(seg)])
    # the profile's corners (flat caps, steps) and the two tips split it into smooth runs;
    # each run gets panels in proportion to its length, cosine-clustered towards its ends
    knots = np.unique(np.concatenate([[0.0], s[_corners(x, r)], s[-1:]]))
    runs = np.diff(knots)
    n_run = np.maximum(4, np.round(panels * runs / runs.sum())).astype(int)
    t = [knots[:1]]
    for a, length, n in zip(knots[:-1], runs, n_run):
        t.append(a + length * 0.5 * (1.0 - np.cos(np.pi * np.arange(1, n + 1) / n)))
    t = np.concatenate(t)
    xn = np.interp(t, s, x)
    rn = np.sqrt(np.interp(t, s, r * r)) if area_linear else np.interp(t, s, r)
    rn[0] = rn[-1] = 0.0
    return xn, rn


def _corners(x, r):
    d = np.column_stack([np.diff(x), np.diff(r)])
    d /= np.linalg.norm(d, axis=1)[:, None]
    cosang = np.einsum("ij,ij->i", d[1:], d[:-1])
    return np.concatenate([[False], cosang < np.cos(np.radians(20.0)), [False]])


def body_of_revolution_added_mass(x, r, *, rho: float, x_ref: float = 0.0,
                                  panels: int = DEFAULT_PANELS, modes=(0, 1),
                                  area_linear: bool = False) -> np.ndarray:
    r"""6x6 added mass of a body of revolution about the x axis (3D potential flow).

    .. math:: m_{11} = -2\pi\rho\int\phi_0 n_x r\,ds,\ \
              m_{22} = m_{33} = -\pi\rho\int\phi_{1,v} n_r r\,ds,\ \
              m_{55} = m_{66} = -\pi\rho\int\phi_{1,r}(X n_r - r n_x) r\,ds

    with :math:`X = x - x_{ref}`, and the coupling
    :math:`m_{26} = -m_{35} = -\pi\rho\int\phi_{1,r} n_r r\,ds`.

    Parameters
    ----------
    x, r : arrays
        Meridian stations [m] (non-decreasing) and radii [m]; ends with r > 0 get
        flat caps.
    rho : float
        Fluid density [kg/m^3]
    x_ref : float
        Reference point on the axis for the rotational terms [m]
    panels : int
        Meridian panels (plus cap corners).
    modes : tuple of int
        Fourier modes to solve: 0 for surge, 1 for sway, heave, pitch and yaw (default both;
        the terms of a mode left out are 0).
    area_linear : bool
        Between the profile's points interpolate the area :math:`\pi r^2` linearly in x
        instead of r (for profiles sampled from strips, :func:`hull_corrections`).

    Returns
    -------
    (6, 6) array
        M_A [kg, kg m, kg m^2], FRD DOF order; roll is 0.

    References
    ----------
    Newman (1977) sec. 4.13-4.15; Hess & Smith (1967) sec. 5; Lamb (1932) sec. 373.
    """
    xn, rn = _meridian(x, r, int(panels), area_linear)
    return _meridian_added_mass(xn - x_ref, rn, rho, _influence, modes)


def _meridian_added_mass(xn, rn, rho, influence, modes=(0, 1)) -> np.ndarray:
    """6x6 added mass from the mode-0 (surge) and mode-1 (sway and yaw together) solutions on
    the meridian panel nodes (xn, rn) [m] (x about the reference point), with ``influence``
    the S, D matrices of an open (:func:`_influence`) or closed (:func:`_influence_closed`)
    meridian; the equations of :func:`body_of_revolution_added_mass`. ``rho`` [kg/m^3]."""
    out = np.zeros((6, 6))
    if 0 in modes:
        S, D, (length, nx, nr, xc, rc) = influence(xn, rn, 0)
        phi = np.linalg.solve(D + 0.5 * np.eye(D.shape[0]), S @ nx)
        out[0, 0] = -2.0 * np.pi * rho * np.sum(phi * nx * rc * length)
    if 1 in modes:
        S, D, (length, nx, nr, xc, rc) = influence(xn, rn, 1)
        bc = np.column_stack([nr, xc * nr - rc * nx])
        phi = np.linalg.solve(D + 0.5 * np.eye(D.shape[0]), S @ bc)
        m = -np.pi * rho * (bc * (rc * length)[:, None]).T @ phi   # [[m22, m26], [m62, m66]]
        m = 0.5 * (m + m.T)
        out[1, 1] = out[2, 2] = m[0, 0]
        out[5, 5] = out[4, 4] = m[1, 1]
        out[1, 5] = out[5, 1] = m[0, 1]
        out[2, 4] = out[4, 2] = -m[0, 1]
    return out


def strip_section_added_mass(strips, rho: float) -> np.ndarray:
    r"""Per-strip 2D added mass (n, 3, 3), the sum of the parts' sections [kg/m, kg, kg m].

    .. math:: m^{2D}(x_i) = \sum_p c_{p,i}\, m_p(x_i)

    with coverage fractions :math:`c_{p,i}` [-] and ``rho`` [kg/m^3]. Translation terms only
    are used by :func:`hull_corrections` (they do not depend on the roll reference point).
    [assumption] sections add without interaction (strip theory, Newman 1977, sec. 7.4).
    """
    from stripcoef.sections import section_added_mass
    out = np.zeros((strips.n, 3, 3))
    for p in strips.parts:
        np.add.at(out, p.index, section_added_mass(p, rho) * _coverage(p)[:, None, None])
    return out


def _coverage(part) -> np.ndarray:
    """Fraction of each covered strip's width that the part spans (1 if not recorded)."""
    cov = getattr(part, "coverage", None)
    return np.ones(part.index.size) if cov is None else np.asarray(cov, dtype=float)


def _equivalent_radius(strips, per_strip, *, closed_ends: bool = False):
    """Profile (x, r) with pi r^2 = per_strip (an area [m^2]), ends extrapolated linearly
    (or closed to r = 0 at the body's ends).

    r = sqrt(A / pi) [m] at the strip centres x [m], plus end stations at x_min, x_max with
    A_end = max(A_0 + (A_1 - A_0)/(x_1 - x_0) (x_end - x_0), 0). [assumption] linear
    end extrapolation; equal-area body of the module docstring.
    """
    x = strips.x
    if strips.n < 2:
        raise InputError("too few strips for the 3D correction", key="strips", value=strips.n,
                         expected=">= 2")

    def end(i0, i1, xe):
        slope = (per_strip[i1] - per_strip[i0]) / (x[i1] - x[i0])
        return max(per_strip[i0] + slope * (xe - x[i0]), 0.0)

    a_lo = 0.0 if closed_ends else end(0, 1, strips.x_min)
    a_hi = 0.0 if closed_ends else end(-1, -2, strips.x_max)
    xs = np.r_[strips.x_min, x, strips.x_max]
    rs = np.sqrt(np.maximum(np.r_[a_lo, per_strip, a_hi], 0.0) / np.pi)
    return xs, rs


def _strip_area(strips) -> np.ndarray:
    """Section area of every strip, all parts that displace water summed [m^2]."""
    area = np.zeros(strips.n)
    for p in strips.parts:
        np.add.at(area, p.index, p.area * _coverage(p))
    return area


def equivalent_profile(strips):
    r"""Equal-area body of revolution of a set of strips: :math:`r_{eq} = \sqrt{A(x)/\pi}`.

    Section areas of all parts that displace water are summed per strip; the ends
    are extrapolated linearly in area to the body's first and last x (a pointed
    end gets r = 0, a blunt one keeps its area and gets a flat cap).

    Returns
    -------
    (x, r) arrays [m]

    References
    ----------
    See module docstring (equivalent body of revolution; Newman 1977, sec. 7.4).
    """
    return _equivalent_radius(strips, _strip_area(strips))


def _axial_added_mass(strips, rho, panels):
    """Surge added mass: the equal-area body of the hull parts, plus each other part as its
    own equal-area body (appendages are not smeared into rings round the hull).

    m_11 = m_11^BEM[r_hull] + sum_parts m_11^BEM[r_part] [kg] (module docstring, Newman
    1977, eq. 4.148); a part of < 3 strips gets the sphere's m_11 = rho V / 2 (Lamb 1932,
    sec. 373, k_1 = 1/2). ``rho`` [kg/m^3]. [assumption] no interaction between parts.
    """
    area = np.zeros(strips.n)
    others = []
    for p in strips.parts:
        if p.role == "hull":
            np.add.at(area, p.index, p.area * _coverage(p))
        else:
            others.append(p)
    m11 = 0.0
    if np.any(area > 0):
        xs, rs = _equivalent_radius(strips, area)
        m11 += body_of_revolution_added_mass(xs, rs, rho=rho, panels=panels, modes=(0,),
                                             area_linear=True)[0, 0]
    for p in others:
        cov = _coverage(p)
        vol = float(np.sum(p.area * cov * strips.dx[p.index]))
        if p.index.size < 3 or vol <= 0:
            m11 += 0.5 * rho * vol                  # too short to resolve: a sphere's k1 = 1/2
            continue
        order = np.argsort(p.index)
        idx, a, cov = p.index[order], p.area[order], cov[order]
        x = strips.x[idx]
        half = 0.5 * strips.dx[idx]
        # a part ending inside a strip covers the fraction cov of it from the inner side:
        # its end is there (not smeared over the strip), extrapolated in area
        x_lo = x[0] + half[0] - cov[0] * 2 * half[0]
        x_hi = x[-1] - half[-1] + cov[-1] * 2 * half[-1]
        a_lo = max(a[1] + (a[1] - a[2]) / (x[2] - x[1]) * (x[1] - x_lo), 0.0)
        a_hi = max(a[-2] + (a[-2] - a[-3]) / (x[-2] - x[-3]) * (x_hi - x[-2]), 0.0)
        px = np.r_[x_lo, x[1:-1], x_hi]
        pr = np.sqrt(np.r_[a_lo, a[1:-1], a_hi] / np.pi)
        m11 += body_of_revolution_added_mass(px, pr, rho=rho, panels=max(40, panels // 2),
                                             modes=(0,), area_linear=True)[0, 0]
    return m11


def _lateral(strips, per_strip, rho, xc, panels, closed_ends=CLOSED_ENDS):
    r"""3D/strip factors and coupling increment of the body of revolution pi r^2 = per_strip.

    .. math:: f_t = \frac{m_{22}^{3D}}{\rho\sum A\,dx},\quad
              f_r = \frac{m_{66}^{3D}}{\rho\sum A X^2 dx},\quad
              \Delta_{26} = m_{26}^{3D} - \sqrt{f_t f_r}\,\rho\sum A X\,dx,\quad X = x - x_c

    ``per_strip`` A [m^2], ``rho`` [kg/m^3], ``xc`` [m]; returns f_t, f_r [-],
    Delta_26 [kg m] and the 6x6 BEM matrix. See module docstring and :func:`hull_corrections`.
    """
    if not np.any(np.asarray(per_strip) > 0):      # nothing to correct in this direction
        return 1.0, 1.0, 0.0, np.zeros((6, 6))
    xs, rs = _equivalent_radius(strips, per_strip, closed_ends=closed_ends)
    m3 = body_of_revolution_added_mass(xs, rs, rho=rho, x_ref=xc, panels=panels, modes=(1,),
                                       area_linear=True)
    a = np.pi * rs[1:-1] ** 2
    s22 = rho * np.sum(a * strips.dx)
    s26 = rho * np.sum(a * (strips.x - xc) * strips.dx)
    s66 = rho * np.sum(a * (strips.x - xc) ** 2 * strips.dx)
    ft, fr = float(m3[1, 1] / s22), float(m3[5, 5] / s66)
    return ft, fr, float(m3[1, 5] - np.sqrt(ft * fr) * s26), m3


def roll_symmetry_order(contours, max_order: int = 6) -> int:
    r"""Rotational symmetry order k of a section about its area centroid, at least 2.

    The largest k <= ``max_order`` for which the section rotated by :math:`2\pi/k` covers
    itself (symmetric difference < 1 % of its area); 2 when there is none (the roll flow of
    a rigid rotation has no source and its dipole is the sway/heave coupling, so its own far
    field is at least a quadrupole, Newman 1977, sec. 4.13).  ``contours`` (y, z) rings [m].
    """
    from shapely import affinity

    from stripcoef.geometry.mesh import section_geometry
    geom = section_geometry(contours)
    if geom.is_empty:
        return 2
    c = geom.centroid
    for k in range(max_order, 2, -1):
        rot = affinity.rotate(geom, 360.0 / k, origin=c)
        if geom.symmetric_difference(rot).area < 0.01 * geom.area:
            return k
    return 2


def roll_relief(strips, m44, *, rho: float, mode: int = 2, panels: int = DEFAULT_PANELS):
    r"""3D/strip ratio of the roll added mass from the roll-equivalent body of revolution.

    Each run of strips with roll added mass gets the body of revolution whose mode-m
    inertia per unit length (:func:`mode_inertia`, :math:`\rho\pi r^4/m` on a cylinder)
    equals the section's 2D roll added mass about its centroid,

    .. math:: r_p(x) = \left(\frac{m\,m_{44}^{2D}(x)}{\rho\pi}\right)^{1/4},\qquad
              f_p = \frac{\sum_{runs} I_m^{3D}[r_p]}{\int m_{44}^{2D}\,dx}

    with m the sections' rotational symmetry order (:func:`roll_symmetry_order`; 2 for a
    plate, 4 for a cruciform): the order of the 2D roll far field, whose decay along x sets
    the 3D relief.  Exact in the 2D limit (long cylinders) and for a sphere's mode 2
    (:math:`I_2 = 16\pi\rho R^5/45`, spherical harmonic of degree 2); [assumption] for other
    sections, checked against Lamb's exact elliptic plates (Lamb 1932, sec. 373, rotation
    about a diameter of the ellipsoid with c -> 0): the factor is 9 % low at aspect ratio 1,
    19 % low at 3.6 (docs/theory.md sec. 6).  ``m44`` [kg m] per strip, ``rho`` [kg/m^3].

    Returns the factor f_p [-] (1 if no strip has roll added mass, or only round-off: below
    :data:`ROLL_ROUNDOFF` times :math:`\int\rho A^2 dx`, e.g. a circle's panel solution).
    """
    m44 = np.clip(np.asarray(m44, dtype=float), 0.0, None)
    total = float(np.sum(m44 * strips.dx))
    if _roll_is_roundoff(strips, m44, rho):
        return 1.0
    on = m44 > 1e-3 * m44.max()
    i3d = 0.0
    j = 0
    n = strips.n
    while j < n:
        if not on[j]:
            j += 1
            continue
        k = j
        while k + 1 < n and on[k + 1]:
            k += 1
        x = strips.x[j:k + 1]
        r = (mode * m44[j:k + 1] / (rho * np.pi)) ** 0.25
        lo, hi = x[0] - 0.5 * strips.dx[j], x[-1] + 0.5 * strips.dx[k]
        i3d += mode_inertia(np.r_[lo, x, hi], np.r_[r[0], r, r[-1]], mode=mode, rho=rho,
                            panels=max(40, panels // 2))
        j = k + 1
    return i3d / total


def _roll_is_roundoff(strips, m44, rho) -> bool:
    r"""No roll added mass but round-off: :math:`\int m_{44}^{2D} dx \le`
    :data:`ROLL_ROUNDOFF` :math:`\int\rho A^2 dx` (``m44`` [kg m] per strip, ``rho``
    [kg/m^3])."""
    total = float(np.sum(np.clip(m44, 0.0, None) * strips.dx))
    return not total > ROLL_ROUNDOFF * rho * float(np.sum(_strip_area(strips) ** 2 * strips.dx))


def _polygon_roll_mode(strips, m44) -> int | None:
    """Symmetry order of the section with the largest roll added mass, for bodies made of
    polygon parts only (meshes); None otherwise (vehicle files: roll left uncorrected)."""
    if not strips.parts or any(p.shape != "polygon" or p.contours is None for p in strips.parts):
        return None
    if len(strips.parts) != 1:
        return 2
    p = strips.parts[0]
    k = int(np.argmax(np.asarray(m44)[p.index]))
    return roll_symmetry_order(p.contours[k])


def hull_corrections(strips, *, rho: float, center, section_added_mass=None,
                     panels: int = DEFAULT_PANELS) -> dict:
    r"""3D corrections for :func:`stripcoef.assemble.added_mass`, per direction.

    Each lateral direction gets its own *added-mass-equivalent* body of revolution,
    whose radius reproduces the strips' 2D added mass in that direction,

    .. math:: \pi\rho\, r_v(x)^2 = m^{2D}_{22}(x),\qquad \pi\rho\, r_w(x)^2 = m^{2D}_{33}(x),

    (for a circular hull both are the hull itself; fins, plates and pods widen them
    where they are).  Its 3D added mass (axisymmetric BEM) against its own strip
    theory gives the factors and the sway-yaw / heave-pitch coupling increments,

    .. math:: f_v = \frac{m_{22}^{3D}[r_v]}{\int\rho\pi r_v^2 dx},\quad
              f_r = \frac{m_{66}^{3D}[r_v]}{\int\rho\pi r_v^2 (x-x_c)^2 dx},\quad
              \Delta_{26} = m_{26}^{3D}[r_v] - \sqrt{f_v f_r}\int\rho\pi r_v^2 (x-x_c) dx

    and likewise :math:`f_w, f_q, \Delta_{35}` from :math:`r_w`.  The axial added mass
    is that of the equal-area body :math:`\pi r_A^2 = A(x)` of the hull parts plus that of
    each other part's own equal-area body (appendages are not smeared into rings).
    Applied to the strip matrix S about ``center``:
    :math:`S \to D S D`, :math:`D = diag(1, \sqrt{f_v}, \sqrt{f_w}, 1, \sqrt{f_q}, \sqrt{f_r})`,
    then :math:`S_{11} += m_{11}`, :math:`S_{26} = S_{62} += \Delta_{26}`,
    :math:`S_{35} = S_{53} += \Delta_{35}`.  For a body of revolution this is its exact
    3D matrix (to the panel discretisation).  A body whose every section has a hole (a duct,
    a ring: :func:`bore_area`) gets one *hollow* equivalent body instead, the tube of its
    outer-contour and bore areas, for surge and both lateral directions
    (:func:`_hollow_corrections`; exact for a circular tube).  Roll: for mesh bodies (polygon
    parts) the section roll terms are scaled by :func:`roll_relief` (``scale[3]``); otherwise 1.

    Parameters
    ----------
    strips : Strips
    rho : float
        Fluid density [kg/m^3]
    center : (3,)
        Point about which the strip matrix is assembled (its x is used) [m]
    section_added_mass : (n, 3, 3) array, optional
        Per-strip 2D added mass (:func:`strip_section_added_mass`); default: the
        equal-area circle, :math:`\rho A(x)` in both directions.

    Returns
    -------
    dict
        ``scale`` (6,) diagonal of D**2, ``axial_added_mass`` [kg], ``coupling_26``,
        ``coupling_35`` [kg m], and the legacy ``translation``/``rotation``/``coupling``
        (sway-yaw values), ``method``.

    References
    ----------
    See the module docstring; Newman (1977) sec. 7.4 for strip theory's end error;
    DNV-RP-C205 table A-2 for the finite-length reduction of plates that this
    reproduces for plate-like sections.
    """
    xc = float(np.asarray(center, dtype=float)[0])
    bore = bore_area(strips)            # a bore along the whole body: hollow equivalent body
    if bore is not None:
        m11, fv, fr, d26 = _hollow_corrections(strips, bore, rho, xc, panels)
    else:
        m11 = _axial_added_mass(strips, rho, panels)
    if section_added_mass is None:
        mv = mw = _strip_area(strips)
    else:
        m2d = np.asarray(section_added_mass, dtype=float)
        mv, mw = m2d[:, 0, 0] / rho, m2d[:, 1, 1] / rho
    if bore is None:
        fv, fr, d26, _ = _lateral(strips, mv, rho, xc, panels)
    if bore is not None or section_added_mass is None \
            or np.allclose(mv, mw, rtol=SAME_BODY_RTOL, atol=0.0):
        fw, fq, d35 = fv, fr, -d26      # one equivalent body for both directions
    else:
        fw, fq, d62, _ = _lateral(strips, mw, rho, xc, panels)
        d35 = -d62                      # heave-pitch: M[2,4] = -m26 of the heave body
    fp = 1.0
    if section_added_mass is not None:
        m44 = np.asarray(section_added_mass, dtype=float)[:, 2, 2]
        mode = None if _roll_is_roundoff(strips, m44, rho) else _polygon_roll_mode(strips, m44)
        if mode is not None:
            fp = roll_relief(strips, m44, rho=rho, mode=mode, panels=panels)
    return {"scale": np.array([1.0, fv, fw, fp, fq, fr]),
            "axial_added_mass": float(m11),
            "coupling_26": d26, "coupling_35": d35,
            "translation": fv, "rotation": fr, "coupling": d26,
            "method": "axisymmetric BEM of the added-mass-equivalent bodies of revolution"}


def apply_corrections(strip_matrix, corr: dict) -> np.ndarray:
    r"""Corrected 6x6 added mass from the pure strip matrix about ``center`` (see
    :func:`hull_corrections`): :math:`D S D` plus the axial term and coupling increments.

    .. math:: M = D S D + m_{11} e_1 e_1^T + \Delta_{26}(e_2 e_6^T + e_6 e_2^T)
              + \Delta_{35}(e_3 e_5^T + e_5 e_3^T),\quad D = \operatorname{diag}(\sqrt{scale})

    ``strip_matrix`` S and the result [kg, kg m, kg m^2]; ``scale`` [-], ``axial_added_mass``
    [kg], couplings [kg m]. References: see module docstring (Newman 1977, sec. 7.4).
    """
    s = np.sqrt(np.asarray(corr["scale"], dtype=float))
    m = s[:, None] * np.asarray(strip_matrix, dtype=float) * s[None, :]
    m[0, 0] += corr["axial_added_mass"]
    m[1, 5] += corr["coupling_26"]
    m[5, 1] += corr["coupling_26"]
    m[2, 4] += corr["coupling_35"]
    m[4, 2] += corr["coupling_35"]
    return m


# --- bodies of revolution whose meridian does not touch the axis (tubes, rings) -------------

def _closed_meridian(xm, rm, panels):
    r"""Panel nodes of a closed meridian polygon off the axis (a tube's wall section).

    ``xm, rm`` [m]: the polygon's vertices, r > 0, any orientation; returned clockwise in the
    (x, r) plane (so that :func:`_panel_geometry`'s normal :math:`(-t_r, t_x)` points out of
    the wall).  Its corners (turns > 20 degrees) split it into smooth runs, each resampled by
    arc length with panels in proportion to its length (at least 4), cosine-clustered towards
    its ends (as :func:`_meridian`); the last node equals the first.
    """
    xm = np.asarray(xm, dtype=float)
    rm = np.asarray(rm, dtype=float)
    if xm.ndim != 1 or xm.shape != rm.shape or xm.size < 3 or np.any(rm <= 0) \
            or not np.all(np.isfinite(xm)) or not np.all(np.isfinite(rm)):
        raise InputError("a closed meridian needs >= 3 finite corners with r > 0",
                         key="meridian", value=f"{xm.size} points", expected="r > 0 (off the axis)")
    signed = 0.5 * np.sum(xm * np.roll(rm, -1) - np.roll(xm, -1) * rm)
    if signed > 0:                      # counter-clockwise in (x, r): reverse
        xm, rm = xm[::-1], rm[::-1]
    seg = np.hypot(np.roll(xm, -1) - xm, np.roll(rm, -1) - rm)
    keep = seg > 1e-12 * max(np.ptp(xm), np.ptp(rm))
    xm, rm = xm[keep], rm[keep]
    d = np.column_stack([np.roll(xm, -1) - xm, np.roll(rm, -1) - rm])
    d /= np.linalg.norm(d, axis=1)[:, None]
    corner = np.einsum("ij,ij->i", d, np.roll(d, 1, axis=0)) < np.cos(np.radians(20.0))
    if not np.any(corner):
        corner[0] = True
    first = int(np.argmax(corner))               # start the loop at a corner
    xm, rm, corner = (np.roll(v, -first) for v in (xm, rm, corner))
    xs, rs = np.r_[xm, xm[0]], np.r_[rm, rm[0]]
    s = np.r_[0.0, np.cumsum(np.hypot(np.diff(xs), np.diff(rs)))]
    knots = np.r_[s[:-1][corner], s[-1]]
    runs = np.diff(knots)
    n_run = np.maximum(4, np.round(panels * runs / runs.sum())).astype(int)
    t = [a + length * 0.5 * (1.0 - np.cos(np.pi * np.arange(n) / n))
         for a, length, n in zip(knots[:-1], runs, n_run)]
    t = np.r_[np.concatenate(t), s[-1]]
    xn, rn = np.interp(t, s, xs), np.interp(t, s, rs)
    xn[-1], rn[-1] = xn[0], rn[0]
    return xn, rn


def _influence_closed(xn, rn, mode):
    """:func:`_influence` for a closed meridian (last node = first): the first and last
    panels are neighbours too, integrated with the same clustered rule from their shared
    node (their kernels are log-singular there)."""
    S, D, geo = _influence(xn, rn, mode)
    length, nx, nr, xc, rc = geo
    _, tx, tr, _, _ = _panel_geometry(xn, rn)
    n = xc.size
    # (i, j, start node of the integration, direction along panel j); the 12 points at once
    for i, j, x0, r0, dirn in ((n - 1, 0, xn[0], rn[0], 1.0), (0, n - 1, xn[n], rn[n], -1.0)):
        sq = _CLUSTER_T * length[j]
        s, d = _kernels(xc[i], rc[i], x0 + dirn * sq * tx[j], r0 + dirn * sq * tr[j],
                        nx[j], nr[j], mode)
        S[i, j] = np.sum(s * _CLUSTER_W * length[j])
        D[i, j] = np.sum(d * _CLUSTER_W * length[j])
    return S, D, geo


def ring_body_added_mass(xm, rm, *, rho: float, x_ref: float = 0.0,
                         panels: int = DEFAULT_PANELS) -> np.ndarray:
    r"""6x6 added mass of a body of revolution about the x axis whose meridian is a closed
    polygon off the axis (a tube, a duct ring: the water inside the bore is outside the body).

    Same direct boundary-integral equation and ring kernels as
    :func:`body_of_revolution_added_mass` (module docstring: :math:`G = -1/4\pi R`,
    :math:`\phi = \phi_m(s)\cos m\theta`, Hess & Smith 1967 sec. 5), on a closed meridian
    (outer wall, ends and bore all wetted),

    .. math:: m_{11} = -2\pi\rho\oint\phi_0 n_x r\,ds,\quad
              m_{22} = m_{33} = -\pi\rho\oint\phi_{1,v} n_r r\,ds,\quad
              m_{55} = m_{66} = -\pi\rho\oint\phi_{1,r}(X n_r - r n_x) r\,ds

    (Newman 1977, eq. 4.148), :math:`X = x - x_{ref}`, :math:`m_{26} = -m_{35}`.  A long tube
    tends to the 2D annulus, whose bore water moves with it:
    :math:`m_{22}/L \to \rho\pi(r_o^2 + r_i^2)` (exterior circle :math:`\rho\pi r_o^2`,
    Newman 1977 sec. 4.13; the bore's rigid water :math:`\rho\pi r_i^2`).

    Parameters
    ----------
    xm, rm : arrays
        Corners of the meridian polygon [m], all r > 0 (e.g. a tube of length l:
        x = (0, l, l, 0), r = (r_i, r_i, r_o, r_o))
    rho : float
        Fluid density [kg/m^3]
    x_ref : float
        Reference point on the axis for the rotational terms [m]
    panels : int
        Meridian panels in all.

    Returns
    -------
    (6, 6) array
        M_A [kg, kg m, kg m^2], FRD DOF order; roll 0.
    """
    xn, rn = _closed_meridian(xm, rm, int(panels))
    return _meridian_added_mass(xn - x_ref, rn, rho, _influence_closed)


def bore_area(strips):
    r"""Per-strip area of the bore of a body whose every section has a hole [m^2], else None.

    .. math:: A_{bore}(x_i) = \sum_{parts} c_{p,i} \sum_{holes} |A_{hole}|

    (holes: the clockwise rings of the polygon parts' contours, ``Strips`` of a mesh;
    coverage :math:`c_{p,i}`).  None when a strip has no hole, or a part is not a polygon:
    a bore along the whole body (a duct, a ring) gets the hollow equivalent bodies of
    :func:`hull_corrections`, anything else the solid ones.
    """
    from stripcoef.geometry.mesh import ring_integrals
    if not strips.parts or any(p.shape != "polygon" or p.contours is None for p in strips.parts):
        return None
    several = np.zeros(strips.n)        # a hole needs a second ring round it in the section
    for p in strips.parts:
        np.add.at(several, p.index, [len(rings) > 1 for rings in p.contours])
    if not np.all(several > 0):
        return None
    out = np.zeros(strips.n)
    for p in strips.parts:
        holes = np.array([sum(-a for a in (ring_integrals(r)[0] for r in rings) if a < 0)
                          if len(rings) > 1 else 0.0 for rings in p.contours])
        np.add.at(out, p.index, holes * _coverage(p))
    return out if np.all(out > 0) else None


def _hollow_profile(strips, bore):
    """Closed meridian (x, r) of the tube of a bored body: pi r_o^2 = A(x) + A_bore(x) (the
    outer contour's area), pi r_i^2 = A_bore(x) at the strip centres, flat ends at the body's
    first and last x [m]."""
    area = _strip_area(strips)
    ri2 = np.asarray(bore, dtype=float) / np.pi
    ro2 = ri2 + np.maximum(area, 1e-9 * ri2) / np.pi
    x = np.r_[strips.x_min, strips.x, strips.x_max]
    ro = np.sqrt(np.r_[ro2[0], ro2, ro2[-1]])
    ri = np.sqrt(np.r_[ri2[0], ri2, ri2[-1]])
    return np.r_[x, x[::-1]], np.r_[ro, ri[::-1]]


def _hollow_corrections(strips, bore, rho, xc, panels):
    r"""Axial added mass, 3D/strip factors and coupling increment of a bored body.

    A body whose every section has a hole (a duct, a ring) gets, instead of the solid
    equivalent bodies of :func:`hull_corrections`, its *hollow* equivalent body: the tube with
    the same outer-contour and bore areas,

    .. math:: \pi r_o^2 = A(x) + A_{bore}(x),\qquad \pi r_i^2 = A_{bore}(x),

    solved with :func:`ring_body_added_mass` (for a circular tube: the tube itself, so its 3D
    matrix is exact).  In 2D the bore's water moves with the section (its 2D added mass
    counts :math:`\rho A_{bore}`, docs/theory.md sec. 6); in 3D it leaves axially, which the
    tube's 3D flow holds.  The factors are those of the tube against its own strip theory
    (the 2D annulus :math:`\rho\pi(r_o^2 + r_i^2)`), applied to the real sections' strip
    matrix in both lateral directions,

    .. math:: f_t = \frac{m_{22}^{3D}}{\rho\int\pi(r_o^2+r_i^2)dx},\quad
              f_r = \frac{m_{66}^{3D}}{\rho\int\pi(r_o^2+r_i^2)(x-x_c)^2dx},\quad
              \Delta_{26} = m_{26}^{3D} - \sqrt{f_t f_r}\,\rho\int\pi(r_o^2+r_i^2)(x-x_c)dx

    and :math:`m_{11} = m_{11}^{3D}`.  ``bore`` [m^2], ``rho`` [kg/m^3], ``xc`` [m]; returns
    (m11 [kg], f_t, f_r [-], Delta_26 [kg m]).  [assumption] beyond circular tubes: a short
    square ring (outer 0.6 m, wall 0.06 m, length 0.03-0.6 m) against Capytaine is within
    -0.9..+4.0 % on sway and heave, +4.6..+11.0 % on pitch, +3.0..+5.3 % on surge, where the
    solid equivalent bodies gave -8..-15 %, +124..+1600 % and +110..+170 %
    (benchmarks/junction_relief.py rings; Newman 1977 sec. 4.13 for the 2D annulus).
    """
    xm, rm = _hollow_profile(strips, bore)
    m3 = ring_body_added_mass(xm, rm, rho=rho, x_ref=xc, panels=panels)
    n = strips.n
    a = np.pi * (rm[1:n + 1] ** 2 + rm[::-1][1:n + 1] ** 2)
    s22 = rho * np.sum(a * strips.dx)
    s26 = rho * np.sum(a * (strips.x - xc) * strips.dx)
    s66 = rho * np.sum(a * (strips.x - xc) ** 2 * strips.dx)
    ft, fr = float(m3[1, 1] / s22), float(m3[5, 5] / s66)
    return float(m3[0, 0]), ft, fr, float(m3[1, 5] - np.sqrt(ft * fr) * s26)

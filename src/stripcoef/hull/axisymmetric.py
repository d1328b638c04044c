r"""Axisymmetric boundary-element solver: the exact 3D added mass of a body of revolution.

Solid bodies (:func:`body_of_revolution_added_mass`), ring bodies with a bore
(:func:`ring_body_added_mass`) and single Fourier modes (:func:`mode_inertia`), used by
:mod:`stripcoef.hull.corrections`.

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
from stripcoef.hull.memo import array_memo


#: Meridian panels used by default.
DEFAULT_PANELS = 160


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

    A ring on the axis (:math:`Q = 0`: a zero radius at either end, e.g. a panel of an
    equal-area profile that runs along the axis where no body is) has R independent of
    theta, and the limits :math:`I_0 = 2\pi/\sqrt{P}`, :math:`I_1 = 0` are used there (the
    recursion's 0/0 would be a NaN).

    ``p`` [m^2], ``q`` [m^2]; returns A [m], B^2 [m^2], K, E [-], I_0, I_1 [1/m].
    Gradshteyn & Ryzhik (2007), 2.571 and 8.111-8.112.
    """
    a2 = p + q
    b2 = np.maximum(p - q, 1e-300)
    a = np.sqrt(a2)
    m = np.clip(2.0 * q / a2, 0.0, 1.0 - 1e-16)
    kk, ee = ellipk(m), ellipe(m)
    i0 = 4.0 * kk / a
    on_axis = q <= 0.0
    i1 = np.where(on_axis, 0.0, (p * i0 - 4.0 * a * ee) / np.where(on_axis, 1.0, q))
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
    # a panel on the axis (r_c = 0, Q = 0): R = A for every theta, so
    # int (1 - cos)/R^3 = 2 pi/A^3 and int (1 - cos) cos/R^3 = -pi/A^3 (limits of the
    # recursions below, whose 0/0 would be a NaN)
    on_axis = q <= 0.0
    qs = np.where(on_axis, 1.0, q)
    if mode == 0:
        s = -rq * i0 / (4.0 * np.pi)
        jdiff = np.where(on_axis, 2.0 * np.pi / a**3,
                         4.0 * (kk - ee) / (a * qs))      # int (1 - cos)/R^3
    else:
        s = -rq * i1 / (4.0 * np.pi)
        j0 = 4.0 * ee / (a * b2)
        j1 = (p * j0 - i0) / qs
        jdiff = np.where(on_axis, -np.pi / a**3,
                         (i1 - b2 * j1) / qs)             # int (1 - cos) cos / R^3
    d = rq * nrq * rc * jdiff / (4.0 * np.pi)
    return s, d


def _closed_profile(x, r):
    """The offsets (x, r) as float arrays, checked (x non-decreasing, r >= 0, finite; else an
    :class:`~stripcoef.errors.InputError` naming the profile), closed on the axis: a point at
    r = 0 added at an end whose radius is not zero (a flat nose or tail cap)."""
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
    return x, r


def _meridian(x, r, panels, area_linear=False):
    r"""Closed meridian from the nose tip (r = 0) to the tail tip, resampled by arc length
    with cosine clustering towards both ends; between the given points r is linear in x, or
    with ``area_linear`` the area :math:`\pi r^2` is (r = sqrt of the linear interpolant of
    r^2: round noses and tails sampled at a few stations are followed, not cut by chords)."""
    x, r = _closed_profile(x, r)
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
    return _body_of_revolution(np.ascontiguousarray(x, dtype=float),
                               np.ascontiguousarray(r, dtype=float), float(rho),
                               float(x_ref), int(panels), tuple(int(k) for k in modes),
                               bool(area_linear))


@array_memo(maxsize=256)
def _body_of_revolution(x, r, rho: float, x_ref: float, panels: int, modes: tuple,
                        area_linear: bool):
    """:func:`body_of_revolution_added_mass` of float64 profile arrays and plain numbers (the
    memo's key, :func:`stripcoef.hull.memo.array_memo`).  Solved once per process for the
    same profile and settings: the 3D corrections of every estimate of a vehicle solve the
    same equivalent bodies (a study of 512 samples of one vehicle, 514 solves of 2 distinct
    bodies: tests/test_study.py)."""
    xn, rn = _meridian(x, r, panels, area_linear)
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


#: Meridian panels of the axial-flow surface speed (:func:`axial_surface_speed`; assumption:
#: 400. Converged on the smooth meridian of :func:`smooth_meridian`: Stratford's station on the
#: SUBOFF hull is 0.8745, 0.8750, 0.8745, 0.8745 l on 200, 400, 800, 1600 panels, within the
#: 0.0005 l of its 2001 stations; on the tabulated polyline itself it moved 0.8755 -> 0.8645 l
#: as the panels resolved the speed peaks at its vertices; validation.lift.panel_stations) [-].
SURFACE_SPEED_PANELS = 400

#: Points at which a smooth run of the meridian is sampled between two offsets to place the
#: panel nodes by arc length (:func:`smooth_meridian`; the nodes themselves lie on the
#: interpolant, so this sets only their spacing, not the surface) [-].
_ARC_SAMPLES = 16


def _smooth_runs(x, r):
    r"""The offsets (x, r) of a body of revolution (x non-decreasing, r >= 0) cut into runs that
    are smooth: at a point given twice in a row (a corner, such as the junction of a cone and a
    cylinder: :meth:`stripcoef.geometry.profiles.Profile.offsets` repeats it) and at both ends
    of a stretch along a repeated x (a step, or a flat cap: ends with r > 0 get one). Returns a
    list of (x, r) arrays, one per run, each run's ends shared with its neighbours; a run of
    >= 4 points with x increasing is interpolated by :func:`_run_interpolant`, a shorter one or
    one along a repeated x is straight. Every other point is taken as an offset of a smooth
    curve (turns between chords are not read as corners: a round nose tabulated at a few
    points turns by more than 20 degrees between its chords)."""
    x, r = _closed_profile(x, r)
    tiny = 1e-12 * max(x[-1] - x[0], 1e-300)
    same = np.hypot(np.diff(x), np.diff(r)) <= tiny       # point i + 1 repeats point i
    keep = np.concatenate([[True], ~same])
    index = np.cumsum(keep) - 1                          # each point's index once repeats go
    x, r = x[keep], r[keep]
    cut = np.zeros(x.size, dtype=bool)
    cut[index[:-1][same]] = True                         # a repeated point: a corner
    flat = np.flatnonzero(np.diff(x) <= tiny)            # a stretch along a repeated x
    cut[flat] = cut[flat + 1] = True
    cut[0] = cut[-1] = True
    ends = np.flatnonzero(cut)
    return [(x[a:b + 1], r[a:b + 1]) for a, b in zip(ends[:-1], ends[1:])]


def _run_interpolant(x, r):
    r"""r(x) [m] on one smooth run of offsets (:func:`_smooth_runs`): the square root of the
    not-a-knot cubic spline through :math:`r^2` (C2; de Boor 1978, *A Practical Guide to
    Splines*, ch. IV; ``scipy.interpolate.make_interp_spline``, k = 3), linear along a run of
    fewer than 4 points or one that does not advance in x. The spline is of r^2, the section's
    area over pi, because at a round tip :math:`r \propto \sqrt{x}` has an infinite slope while
    :math:`r^2` is smooth there (a spheroid's :math:`r^2` is a quadratic: the interpolant is the
    spheroid exactly)."""
    from scipy.interpolate import make_interp_spline

    if x.size < 4 or np.any(np.diff(x) <= 0.0):
        return lambda t: np.interp(t, x, r) if x[-1] > x[0] else np.full_like(t, r[0])
    spline = make_interp_spline(x, r * r, k=3)
    return lambda t: np.sqrt(np.maximum(spline(t), 0.0))


def smooth_meridian(x, r, panels: int):
    r"""Panel nodes of a body of revolution on a C2 interpolant of its offsets, from the nose
    tip (r = 0) to the tail tip.

    A tabulated hull is a set of offsets of a smooth body; joined by chords (:func:`_meridian`)
    it is a polyline whose slope jumps at every offset, and the axial potential flow has a speed
    peak at each such vertex that finer panels resolve (on SUBOFF's 400 offsets Stratford's
    station moved 0.8755 -> 0.8645 l from 200 to 1600 panels while the peak speed rose). Here
    each smooth run of the offsets (:func:`_smooth_runs`: split at corners, steps and flat caps,
    which stay corners) is interpolated by :func:`_run_interpolant` (the cubic spline of
    :math:`r^2`), and its panels (in proportion to its arc length, at least 4,
    cosine-clustered towards its ends as in :func:`_meridian`) are placed by arc length on the
    interpolant, every node on it: the panel solution then converges to the flow about that
    smooth body.

    ``x`` [m] non-decreasing, ``r`` [m] >= 0 (ends with r > 0 get flat caps), ``panels``
    about how many; returns the nodes (xn, rn) [m].
    """
    runs = _smooth_runs(x, r)
    curves, arcs = [], []
    for xr, rr in runs:
        f = _run_interpolant(xr, rr)
        if xr[-1] > xr[0]:
            u = np.linspace(0.0, 1.0, _ARC_SAMPLES + 1)[1:]
            xd = np.concatenate([xr[:1], (xr[:-1, None] + np.diff(xr)[:, None] * u).ravel()])
            rd = f(xd)
            rd[0], rd[-1] = rr[0], rr[-1]
        else:                                           # a flat cap or a step: straight
            xd, rd = xr[[0, -1]], rr[[0, -1]]
        arc = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(xd), np.diff(rd)))])
        curves.append((f, xd, rd, arc, rr))
        arcs.append(arc[-1])
    runs_len = np.asarray(arcs)
    n_run = np.maximum(4, np.round(panels * runs_len / runs_len.sum())).astype(int)
    xs, rs = [np.zeros(1) + curves[0][1][0]], [np.zeros(1) + curves[0][2][0]]
    for (f, xd, rd, arc, rr), n in zip(curves, n_run):
        t = arc[-1] * 0.5 * (1.0 - np.cos(np.pi * np.arange(1, n + 1) / n))
        xn = np.interp(t, arc, xd)
        if xd[-1] > xd[0]:
            rn = f(xn)
            rn[-1] = rr[-1]
        else:
            rn = np.interp(t, arc, rd)
        xs.append(xn)
        rs.append(rn)
    xn, rn = np.concatenate(xs), np.concatenate(rs)
    rn[0] = rn[-1] = 0.0
    return xn, rn


def smooth_radius(x, r, at) -> np.ndarray:
    """r [m] at the stations ``at`` [m] of the C2 interpolant of the offsets ``x``, ``r`` [m]
    that :func:`smooth_meridian` places the panels on (:func:`_run_interpolant`, run by run;
    0 outside the offsets)."""
    at = np.asarray(at, dtype=float)
    out = np.zeros_like(at)
    for xr, rr in _smooth_runs(x, r):
        if xr[-1] > xr[0]:
            inside = (at >= xr[0]) & (at <= xr[-1])
            out[inside] = _run_interpolant(xr, rr)(at[inside])
    return out


def axial_surface_speed(s, r, *, panels: int = SURFACE_SPEED_PANELS, at=None) -> np.ndarray:
    r"""Surface speed of a body of revolution in axial potential flow, :math:`U_e/U`, from the
    exact (panel) solution: the surge mode m = 0 of this module's boundary-element method on
    the smooth body through the offsets ``s``, ``r`` (:func:`smooth_meridian`).

    .. math:: \tfrac12\phi_0 + \int \phi_0\,D_0\,ds = \int S_0\,n_x\,ds,\qquad
              \frac{U_e}{U} = \Big|\frac{d\phi_0}{ds_m} - t_x\Big|

    (:math:`\phi_0` the potential of the body moving at unit speed along +x, :math:`\partial
    \phi_0/\partial n = n_x`; in the body's frame the stream along -x adds :math:`-t_x`;
    :math:`s_m` the arc length along the
    meridian, :math:`t_x` its tangent's x component), at the panels' mid-points and
    interpolated linearly to the stations ``at``. The line-source approximation of slender-body
    theory (:func:`stripcoef.hull.lift.surface_speed_ratio`) is within 7 % of it on the SUBOFF
    afterbody but lower at the shoulder's suction peak (1.07 against 1.12), where a pressure-
    recovery criterion such as Stratford's starts.

    Parameters
    ----------
    s : (n,) array
        Offsets' stations from the nose, non-decreasing [m] (a table's own points, or dense
        samples of an analytic profile: not samples of a polyline, whose vertices the
        interpolant would follow)
    r : (n,) array
        Radii r(s) >= 0 [m] at ``s``
    panels : int
        Meridian panels (cosine-clustered towards the ends of each smooth run)
    at : (m,) array, optional
        Stations from the nose [m] at which the speed is returned (default ``s``)

    Returns
    -------
    (m,) array
        U_e/U [-] at ``at`` (0 at a stagnation point)

    References
    ----------
    Hess, J. L. & Smith, A. M. O. (1967), "Calculation of potential flow about arbitrary
    bodies", *Prog. Aerosp. Sci.* 8 (the axisymmetric source-panel method and its surface
    velocity); Lamb (1932), *Hydrodynamics*, sec. 373 (a prolate spheroid's exact surface speed
    :math:`U(1 + k_1)|t_x|`, the check in tests/test_lift_separation.py); de Boor (1978) ch. IV
    (the cubic spline of the offsets).
    """
    s = np.asarray(s, dtype=float)
    r = np.asarray(r, dtype=float)
    at = s if at is None else np.asarray(at, dtype=float)
    return _axial_surface_speed(s, r, at, int(panels))


@array_memo(maxsize=16)
def _axial_surface_speed(s, r, at, panels) -> np.ndarray:
    """:func:`axial_surface_speed` of float arrays and an int (the memo's key: one solve per
    process for each hull)."""
    xn, rn = smooth_meridian(s, r, panels)
    S, D, (seg, nx, _, xc, _) = _influence(xn, rn, 0)
    phi = np.linalg.solve(D + 0.5 * np.eye(D.shape[0]), S @ nx)
    arc = np.concatenate([[0.0], np.cumsum(seg)])
    speed = np.abs(np.gradient(phi, 0.5 * (arc[1:] + arc[:-1])) - np.diff(xn) / seg)
    return np.interp(at, xc, speed)

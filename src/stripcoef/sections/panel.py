r"""2D potential-flow panel method: added mass of arbitrary (multi-part) sections.

A strip's section is one or several closed contours in the (y, z) plane
(several parts, e.g. a hull with side pods; holes, e.g. the water inside a duct
ring).  The fluid is everything outside the solid material.  For each rigid
mode k (sway, heave, roll about a point (y0, z0)) the velocity potential
:math:`\phi_k` satisfies Laplace's equation, decays at infinity and has the
body-boundary condition

.. math:: \partial\phi_k/\partial n = n_k, \qquad
          (n_1, n_2, n_3) = (n_y,\; n_z,\; (y-y_0) n_z - (z-z_0) n_y)

with :math:`n` the unit normal pointing out of the material into the fluid
(the roll term is :math:`(\omega \times r)\cdot n` for a rotation about +x in
FRD axes).  Green's second identity with :math:`G = \ln r / (2\pi)` gives, at a
point of a smooth boundary (the direct formulation),

.. math:: \tfrac12 \phi(x) + \oint \phi(\xi)\,\partial G/\partial n_\xi\, ds
          = \oint G\, \partial\phi/\partial n_\xi\, ds

which is discretised with straight panels of constant potential, collocation at
panel mid-points and the exact (analytic) line integrals of :math:`G` and
:math:`\partial G/\partial n` over each panel.  The added-mass matrix per unit
length is

.. math:: m_{ik} = -\rho \oint \phi_k\, n_i\, ds \quad [kg/m,\ kg,\ kg\,m]

(symmetrised; the discrete matrix is symmetric to the discretisation error).

All contours of a section are solved together, so the interaction between parts
is exact in 2D.  A hole (a ring inside another ring, oriented clockwise) is
fluid enclosed by the material: its interior Neumann problem fixes the
potential only up to a constant, which is removed by a rank-one augmentation
(zero mean potential on each hole ring).  The hole's water then moves with the
section (translation added mass includes :math:`\rho A_{hole}`; rotation of a
circular hole entrains nothing).

References
----------
Newman, J. N. (1977) *Marine Hydrodynamics*, MIT Press, sec. 4.13-4.15 (added
mass, the 2D added-mass table, :math:`m_{ij} = -\rho\oint\phi_j n_i ds`).
Katz, J. & Plotkin, A. (2001) *Low-Speed Aerodynamics*, 2nd ed., Cambridge,
ch. 10 (constant-strength source and doublet line elements, influence
coefficients) and ch. 11 (2D panel methods).
"""

from __future__ import annotations

import numpy as np

from stripcoef.errors import InputError
from stripcoef.geometry.polygons import CORNER_ANGLE, orient_contours, points_in_ring

#: Default number of panels per section (all contours together).
DEFAULT_PANELS = 96
#: Minimum panels on any one contour.
MIN_PANELS_PER_CONTOUR = 24
#: Minimum panels between two sharp corners.
MIN_PANELS_PER_EDGE = 6
#: Weight of the turning angle against arc length when placing panels on smooth rings.
CURVATURE_WEIGHT = 1.0
#: Sections are solved in batches of at most this many ...
_BATCH = 48
#: ... and of at most this many influence coefficients B N^2 (512 kB per (B, N, N) array).
#: Measured on this machine (benchmarks/mesh_speed.py part 1, 200 sections of ~96 panels):
#: 36 ms in batches of 7, 46 ms one by one, slower again in batches of 48, whose temporaries
#: outgrow the caches (and, in a fresh process, come as new pages on every call).
_BATCH_ELEMENTS = 65536


# --------------------------------------------------------------------------- geometry


def _resample_cornered(r: np.ndarray, n: int, corners: np.ndarray, shape) -> np.ndarray:
    r"""``n`` nodes on the polyline ``r`` with sharp corners (``corners``: flags per vertex,
    at least one; ``shape``: its :func:`ring_shape`), cosine-clustered towards the corners:
    the nodes of each edge between consecutive corners at
    :math:`s = s_0 + \ell\,(1 - \cos(\pi j / m))/2`, j = 0..m-1, with m its share of ``n``
    (at least :data:`MIN_PANELS_PER_EDGE`, the rest by length). Rings without corners are
    resampled by :func:`_resample_smooth`. Reference: the cosine spacing of panel methods
    (Katz & Plotkin 2001, ch. 11); accuracy against exact sections in
    tests/test_panel_exact.py."""
    seg, _ = shape
    closed = np.concatenate((r, r[:1]))
    s = np.concatenate(([0.0], np.cumsum(seg)))
    perim = s[-1]
    idx = np.nonzero(corners)[0]
    # start at the first corner; edges between consecutive corners
    s0 = s[idx]
    lengths = np.diff(np.concatenate([s0, [s0[0] + perim]]))
    k = len(idx)
    base = np.full(k, min(MIN_PANELS_PER_EDGE, max(1, n // k)))
    extra = n - base.sum()
    if extra > 0:
        share = lengths / lengths.sum() * extra
        add = np.floor(share).astype(int)
        rem = extra - add.sum()
        add[np.argsort(share - add)[::-1][:rem]] += 1
        base = base + add
    parts = []
    for a, length, m in zip(s0, lengths, base):
        j = np.arange(m)
        parts.append(a + length * 0.5 * (1.0 - np.cos(np.pi * j / m)))
    t = np.mod(np.concatenate(parts), perim)
    y = np.interp(t, s, closed[:, 0], period=None)
    z = np.interp(t, s, closed[:, 1], period=None)
    return np.column_stack([y, z])


def _panel_budget(corner_flags, panels, perims) -> list[int]:
    """Panels of each ring of one section: ``panels`` shared in proportion to the rings'
    perimeters ``perims`` [m], each ring keeping at least :data:`MIN_PANELS_PER_CONTOUR` and
    :data:`MIN_PANELS_PER_EDGE` per sharp corner (``corner_flags``: per ring, per vertex)."""
    mins = np.array([max(MIN_PANELS_PER_CONTOUR, MIN_PANELS_PER_EDGE * int(c.sum()))
                     for c in corner_flags])
    total = max(int(panels), int(mins.sum()))
    share = perims / perims.sum() * total
    n = np.maximum(mins, np.floor(share).astype(int))
    # trim or pad to the exact total, keeping the minima
    diff = total - int(n.sum())
    order = np.argsort(share - n)[::-1]
    i = 0
    while diff != 0 and i < 10 * len(n) + abs(diff) * len(n):
        j = order[i % len(n)]
        if diff > 0:
            n[j] += 1
            diff -= 1
        elif n[j] > mins[j]:
            n[j] -= 1
            diff += 1
        i += 1
    return [int(v) for v in n]


def discretise(contours, *, panels: int | None = None, where: str = "contours"):
    """Panel nodes of a section: list of (n_c, 2) rings, oriented, resampled.

    The one-section case of the ring set's :func:`_discretise_rings` (the code every
    section of a strip model goes through).

    Parameters
    ----------
    contours : list of (n, 2) arrays
        Rings of (y, z) points [m]; orientation is normalised here.
    panels : int, optional
        Total number of panels.  Default: :data:`DEFAULT_PANELS` times
        ``min(3, sqrt(P^2 / (4 pi A)))`` of the most slender ring (more panels for
        slender sections), and at least enough for the per-contour and per-edge minima.  ``0`` keeps the input
        vertices as panel nodes.
    where : str
        Name of ``contours`` in error messages.
    """
    if contours is None or not len(contours):
        orient_contours([], where)                      # its error: no contour
    nodes, budget = _discretise_rings(_ring_set([contours], where, single=True), panels)
    return np.split(nodes, np.cumsum(budget)[:-1])


# --------------------------------------------------------------------------- solver

def _u_log_r2(u, r2):
    """u ln(r2), and 0 where r2 = 0 (a field point on a panel end: u = 0 there); may
    overwrite r2."""
    if (r2 > 0).all():
        out = np.log(r2, out=r2)
        out *= u
        return out
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(r2 > 0, u * np.log(np.where(r2 > 0, r2, 1.0)), 0.0)


def _solve_batch(p1, p2, holes_list, about, rho):
    """Added-mass matrices (B, 3, 3) of B sections with panels p1 -> p2 (B, N, 2)."""
    d = p2 - p1
    length = np.linalg.norm(d, axis=2)                                    # (B, N)
    t = d / length[..., None]
    nrm = np.stack([t[..., 1], -t[..., 0]], axis=2)                       # out of the body
    mid = 0.5 * (p1 + p2)
    # field point i, panel j: (B, N, N) arrays broadcast from contiguous (B, N) components
    my, mz = np.ascontiguousarray(mid[..., 0]), np.ascontiguousarray(mid[..., 1])
    ay, az = np.ascontiguousarray(p1[..., 0]), np.ascontiguousarray(p1[..., 1])
    ty, tz = np.ascontiguousarray(t[..., 0]), np.ascontiguousarray(t[..., 1])
    dy = my[:, :, None] - ay[:, None, :]
    dz = mz[:, :, None] - az[:, None, :]
    ty, tz = ty[:, None, :], tz[:, None, :]
    L = length[:, None, :]
    # local coordinates of the field point: xl along panel j, yl along its normal
    # (in place: the (B, N, N) temporaries are the costly part)
    xl = dy * ty
    xl += dz * tz                                                         # dy ty + dz tz
    dy *= tz
    dz *= ty
    yl = np.subtract(dy, dz, out=dy)                                      # dy tz - dz ty
    y2 = yl * yl
    u2 = xl - L
    r1 = xl * xl
    r1 += y2                                                              # xl^2 + yl^2
    den = r1 - xl * L                                                     # y2 + xl^2 - xl L
    r2 = u2 * u2
    r2 += y2
    f1, f2 = _u_log_r2(xl, r1), _u_log_r2(u2, r2)
    ang = np.arctan2(L * yl, den)                                         # subtended angle
    # S_ij = int_j G ds;  G = ln(r) / (2 pi):  S = (0.5 (f1 - f2) - L + yl ang) / (2 pi)
    S = f1
    S -= f2
    S *= 0.5
    S -= L
    yl *= ang
    S += yl
    S /= 2.0 * np.pi
    D = np.negative(ang, out=ang)                                         # int_j dG/dn ds
    D /= 2.0 * np.pi                                                      # = -ang / (2 pi)
    n = p1.shape[1]
    diag = np.arange(n)
    D[:, diag, diag] = 0.0
    A = D
    A[:, diag, diag] += 0.5
    yc = mid[..., 0] - about[:, :1]
    zc = mid[..., 1] - about[:, 1:]
    q = np.stack([nrm[..., 0], nrm[..., 1], yc * nrm[..., 1] - zc * nrm[..., 0]], axis=2)
    rhs = S @ q                                                           # (B, N, 3)
    for b, holes in enumerate(holes_list):
        for sl in holes:                                                  # remove the null space
            w = np.zeros(n)
            w[sl] = length[b, sl] / length[b, sl].sum()
            u = np.zeros(n)
            u[sl] = 1.0
            A[b] += np.outer(u, w)
    phi = np.linalg.solve(A, rhs)                                         # (B, N, 3)
    m = -rho * np.einsum("bji,bjk->bik", q * length[..., None], phi)
    return 0.5 * (m + np.swapaxes(m, 1, 2))


def added_mass_contours(contours, *, rho: float, about=(0.0, 0.0),
                        panels: int | None = None) -> np.ndarray:
    r"""Added-mass matrix per unit length of a 2D section made of closed contours.

    .. math:: m_{ik} = -\rho \oint \phi_k\, n_i\, ds, \qquad i, k \in
              \{\text{sway}, \text{heave}, \text{roll}\}

    with :math:`\phi_k` the unit-velocity potential of mode k solved by the
    direct boundary-element method (module docstring).  Rows/columns are
    (sway, heave, roll about ``about``); units [kg/m], [kg], [kg m] for the
    translation, coupling and rotation entries.

    Parameters
    ----------
    contours : list of (n, 2) arrays
        Closed rings of (y, z) points [m] (FRD body axes: y starboard, z down).
        Outer rings and holes in any orientation (holes are found by nesting).
    rho : float
        Fluid density [kg/m^3]
    about : (y0, z0)
        Point about which the roll terms are taken [m]
    panels : int, optional
        Total panel count (default 96, more for slender sections and many sharp corners); ``0`` uses
        the input vertices as they are.

    Returns
    -------
    (3, 3) array
        Symmetric added-mass matrix per unit length.

    References
    ----------
    Newman (1977) *Marine Hydrodynamics*, sec. 4.13-4.15; Katz & Plotkin (2001)
    *Low-Speed Aerodynamics*, ch. 10-11.
    """
    return added_mass_sections([contours], rho=rho, about=[about], panels=panels)[0]


def added_mass_sections(sections, *, rho: float, about=(0.0, 0.0),
                        panels: int | None = None) -> np.ndarray:
    r"""Batched :func:`added_mass_contours` for many sections (one per strip).

    .. math:: m^{(s)}_{ik} = -\rho \oint_{C_s} \phi^{(s)}_k n_i\, ds

    Sections with the same panel count are solved together as one stacked
    dense system (numpy batched LU); the rings of all sections are cleaned,
    oriented and resampled together (:class:`_RingSet`).

    Parameters
    ----------
    sections : list of lists of (n, 2) arrays, or a ring set
        For each strip, its contours of (y, z) points [m].  An empty list gives
        a zero matrix (a strip with no material).  A ring set (:func:`part_rings`)
        holds them already cleaned and oriented.
    rho : float
        Fluid density [kg/m^3]
    about : (y0, z0), (n, 2) array or None
        Roll reference point, shared or per section [m]; ``None``: each section's
        area centroid (:func:`section_centroid`).
    panels : int, optional
        Panels per section (see :func:`added_mass_contours`).

    Returns
    -------
    (n, 3, 3) array
        Added-mass matrices per unit length (sway, heave, roll) [kg/m, kg, kg m].

    References
    ----------
    Newman (1977) sec. 4.13-4.15; Katz & Plotkin (2001) ch. 10-11.
    """
    if not np.isfinite(rho) or rho <= 0:
        raise InputError("fluid density must be positive", key="rho", value=rho,
                         expected="> 0 kg/m^3")
    rs = sections if isinstance(sections, _RingSet) else _ring_set(sections, "sections")
    nsec = rs.nsec
    if about is None:
        about = rs.centroids()
    about = np.asarray(about, dtype=float)
    if about.ndim == 1:
        about = np.broadcast_to(about, (nsec, 2))
    if about.shape != (nsec, 2):
        raise InputError("about must be (y0, z0) or one point per section", key="about",
                         value=f"shape {about.shape}", expected=f"(2,) or ({nsec}, 2)")
    out = np.zeros((nsec, 3, 3))
    if len(rs.count) == 0:
        return out
    nodes, budget = _discretise_rings(rs, panels)
    # bookkeeping on the flat node array: each ring's first node and each node's successor
    # in its ring (the end of panel i is node nxt[i], as np.roll(ring, -1) per ring)
    end = np.cumsum(budget)
    first = end - budget
    nxt = np.arange(1, len(nodes) + 1)
    nxt[end - 1] = first
    size = np.bincount(rs.section, budget, nsec).astype(int)            # panels per section
    start = first[np.minimum(rs.rings_of[:-1], len(first) - 1)]         # first node per section
    # holes: rings of negative area, as slices of their section's panels
    y, z = nodes[:, 0], nodes[:, 1]
    ring_area = np.add.reduceat(y * z[nxt] - y[nxt] * z, first)
    holes = [[] for _ in range(nsec)]
    for r in np.nonzero(ring_area < 0)[0]:
        a = first[r] - start[rs.section[r]]
        holes[rs.section[r]].append(slice(a, a + budget[r]))
    # sections with the same panel count are solved together, in chunks (_BATCH_ELEMENTS)
    for n in np.unique(size[size > 0]):
        members = np.nonzero(size == n)[0]
        chunk = max(1, min(_BATCH, _BATCH_ELEMENTS // (n * n)))
        for k in range(0, len(members), chunk):
            idx = members[k:k + chunk]
            p1 = start[idx][:, None] + np.arange(n)                      # (B, n) node indices
            out[idx] = _solve_batch(_take_points(nodes, p1), _take_points(nodes, nxt[p1]),
                                    [holes[s] for s in idx], about[idx], rho)
    return out


# --------------------------------------------------------------------------- all sections at once
#
# A strip model has one section per strip (75 to 200 of them, each with one or a few rings),
# and for rings of a few hundred points the per-call overhead of numpy costs more than the
# arithmetic.  _RingSet holds every ring of every section in one padded 2D array and runs
# the steps (clean, orient, edge lengths and turning angles, resample) once for all rings;
# a single section (added_mass_contours, discretise) is the case of one.  Cleaning and
# orienting repeat :func:`~stripcoef.geometry.polygons.orient_contours` (which the mesh
# slicer and the polygon drag use on one section) operation for operation, so the rings are
# the same to the last bit; only the signed ring areas (used for their sign and, by the
# default panel count, their size) are summed in another order (tests/test_panel_batched.py).
#
# Padded layout: ring r with n_r vertices is row r of ``pts`` (R, m + 1, 2), m = max n_r;
# columns n_r..m repeat the ring's first vertex.  Edge i (vertex i -> i + 1) is then the
# closing edge for i = n_r - 1 and has zero length for i >= n_r, so row sums and cumulative
# sums over a row are those of the closed ring, and min / max over a row are the ring's.

class _RingSet:
    """Every ring of a list of sections: cleaned, oriented (outer rings CCW, holes CW),
    with its edge lengths and turning angles, in padded arrays (layout above).

    Attributes: ``nsec`` sections; per ring ``section`` (owner), ``count`` (vertices),
    ``area`` (signed [m^2]), ``pts`` (R, m + 1, 2) [m], ``seg`` (R, m) edge lengths [m],
    ``turn`` (R, m) |turning angle| [rad], ``corner`` (R, m) bool; ``rings_of`` (nsec + 1,)
    ring index of each section's first ring (rings are stored in section order).
    """

    def __init__(self, nsec, section, count, pts, area):
        self.nsec = nsec
        self.section, self.count, self.pts, self.area = section, count, pts, area
        self.rings_of = np.searchsorted(section, np.arange(nsec + 1))
        e_out = pts[:, 1:] - pts[:, :-1]                                 # (R, m, 2)
        # incoming edge of vertex i: edge i - 1; of vertex 0: the closing edge n_r - 1
        rows = np.arange(len(count))
        e_in = np.concatenate((e_out[rows, count - 1][:, None], e_out[:, :-1]), axis=1)
        # as ring_shape, elementwise on all rings (zero past each ring's end)
        self.seg = np.sqrt(e_out[..., 0] ** 2 + e_out[..., 1] ** 2)
        cross = e_in[..., 0] * e_out[..., 1] - e_in[..., 1] * e_out[..., 0]
        dot = e_in[..., 0] * e_out[..., 0] + e_in[..., 1] * e_out[..., 1]
        # zero past each ring's end: there e_out = 0 and arctan2(0, -0.0) would be pi
        real = np.arange(e_out.shape[1]) < count[:, None]
        self.turn = np.where(real, np.abs(np.arctan2(cross, dot)), 0.0)
        self.corner = self.turn > CORNER_ANGLE

    def ring(self, r) -> np.ndarray:
        """Ring ``r``'s (n_r, 2) vertices (a view)."""
        return self.pts[r, :self.count[r]]

    def shape(self, r):
        """Ring ``r``'s :func:`ring_shape` (views)."""
        n = self.count[r]
        return self.seg[r, :n], self.turn[r, :n]

    def centroids(self) -> np.ndarray:
        r"""(nsec, 2) area centroid (y_c, z_c) of each section [m], (0, 0) if empty.

        .. math:: y_c = \frac{1}{6A}\sum (y_i + y_{i+1})(y_i z_{i+1} - y_{i+1} z_i)

        over all rings of the section (holes, clockwise, subtract), as :func:`ring_centroid`.
        Reference: shoelace formula for the first moments of a polygon (Green's theorem).
        """
        y, z = self.pts[..., 0], self.pts[..., 1]
        c = y[:, :-1] * z[:, 1:] - y[:, 1:] * z[:, :-1]                   # zero in the padding
        # per ring sums, then summed over each section's rings in order (as ring_centroid)
        s = self.section
        a = np.bincount(s, 0.5 * self.row_sums(c), self.nsec)
        sy = np.bincount(s, self.row_sums((y[:, :-1] + y[:, 1:]) * c) / 6.0, self.nsec)
        sz = np.bincount(s, self.row_sums((z[:, :-1] + z[:, 1:]) * c) / 6.0, self.nsec)
        out = np.zeros((self.nsec, 2))
        ok = a != 0
        out[ok, 0], out[ok, 1] = sy[ok] / a[ok], sz[ok] / a[ok]
        return out

    def perimeters(self) -> np.ndarray:
        r"""(R,) perimeter :math:`P = \sum_i |p_{i+1} - p_i|` of each ring [m] (elementary
        geometry; the sum of :func:`ring_shape`'s edge lengths)."""
        return self.row_sums(self.seg)

    def row_sums(self, a) -> np.ndarray:
        """``a[r, :count[r]].sum()`` for each ring r of an (R, >= max count) array.

        Each row is summed as the 1-D slice of its own length, so the last bits are those of
        the one-ring code (numpy sums pairwise, and trailing zeros would change the pairs):
        rings of equal length are summed together.
        """
        m = self.pts.shape[1] - 1
        if (self.count == m).all():
            return a[:, :m].sum(axis=1)
        out = np.empty(len(self.count))
        for n in np.unique(self.count):
            rows = np.nonzero(self.count == n)[0]
            out[rows] = a[rows, :n].sum(axis=1)
        return out


def _refuse(sections, where, s, single=False):
    """Raise the error of the first section that :func:`orient_contours` refuses (the
    message names the ring); if it accepts them all (a ring whose area rounds to zero in one
    sum and not in the other), the zero-area error of section ``s``. ``single``: one
    section, named ``where`` itself."""
    def name(i):
        return where if single else f"{where}[{i}]"

    for i, c in enumerate(sections):
        if c is not None and len(c):
            orient_contours(c, name(i))
    raise InputError("contour has zero area", key=name(s))


def _ring_set(sections, where: str = "sections", single: bool = False) -> "_RingSet":
    """:class:`_RingSet` of ``sections`` (each a list of (n, 2) rings [m]; ``None`` or ``[]``:
    an empty section).  Invalid rings raise the :class:`InputError` of :func:`orient_contours`
    (``single``: ``sections`` is one section, named ``where``)."""
    rings, owner = [], []
    for s, contours in enumerate(sections):
        for c in contours if contours is not None else ():
            r = np.asarray(c, dtype=float)
            if r.ndim != 2 or r.shape[1] != 2 or len(r) < 3:
                _refuse(sections, where, s, single)
            rings.append(r)
            owner.append(s)
    nsec = len(sections)
    if not rings:
        return _RingSet(nsec, np.zeros(0, int), np.zeros(0, int), np.zeros((0, 1, 2)),
                        np.zeros(0))
    flat = np.concatenate(rings)
    if not np.isfinite(flat).all():
        _refuse(sections, where, 0, single)
    section = np.array(owner)
    count = np.array([len(r) for r in rings])
    pts = _padded(flat, count)
    rows = np.arange(len(count))
    # clean_ring on all rings: 1) a closing point equal to the first (np.allclose's test)
    # is dropped (its column becomes padding) ...
    first, last = pts[:, 0], pts[rows, count - 1]
    closing = (np.abs(first - last) <= 1e-8 + 1e-5 * np.abs(last)).all(axis=1)
    if closing.any():
        count = count - closing
        pts[rows[closing], count[closing]] = first[closing]
    # ... 2) so are points repeating their successor (within 1e-12 of the ring's size)
    y, z = pts[..., 0], pts[..., 1]
    scale = np.maximum(np.maximum(y.max(axis=1) - y.min(axis=1), z.max(axis=1) - z.min(axis=1)),
                       1e-300)
    d = pts[:, 1:] - pts[:, :-1]                                         # edge i: i -> i + 1
    real = np.arange(pts.shape[1] - 1) < count[:, None]
    short = (d[..., 0] ** 2 + d[..., 1] ** 2 <= ((1e-12 * scale) ** 2)[:, None]) & real
    if short.any():
        keep = real & ~short
        count = keep.sum(axis=1)
        pts = _padded(pts[:, :-1][keep], count)
    if (count < 3).any():
        _refuse(sections, where, 0, single)
    # signed area of each ring (shoelace, as signed_area; the padding adds zeros)
    y, z = pts[..., 0], pts[..., 1]
    area = 0.5 * (y[:, :-1] * z[:, 1:] - y[:, 1:] * z[:, :-1]).sum(axis=1)
    if (area == 0.0).any():
        _refuse(sections, where, int(section[np.argmax(area == 0.0)]), single)
    # orient_contours: a ring inside an odd number of the section's other rings is a hole
    # (clockwise), the others are outer rings (counter-clockwise).  Nesting is tested only
    # in sections with several rings (few), one ring at a time.
    want_ccw = np.ones(len(count), bool)
    bounds = np.searchsorted(section, np.arange(nsec + 1))
    for s in np.nonzero(np.diff(bounds) > 1)[0]:
        probes = pts[bounds[s]:bounds[s + 1], 0]                        # each ring's first point
        depth = np.zeros(len(probes), int)
        for j in range(bounds[s], bounds[s + 1]):                        # inside ring j?
            inside = points_in_ring(probes, pts[j, :count[j]])
            inside[j - bounds[s]] = False
            depth += inside
        want_ccw[bounds[s]:bounds[s + 1]] = depth % 2 == 0
    flip = (area > 0) != want_ccw
    if flip.any():                                                       # as r[::-1]
        area = np.where(flip, -area, area)
        n = count[flip][:, None]
        col = np.arange(pts.shape[1])
        back = np.where(col < n, n - 1 - col, n - 1)                    # padding: new first
        pts[flip] = np.take_along_axis(pts[flip], back[:, :, None], axis=1)
    return _RingSet(nsec, section, count, pts, area)


def _padded(flat, count) -> np.ndarray:
    """Rings stored one after the other in ``flat`` (count[r] points each) as the padded
    (R, max(count) + 1, 2) array of :class:`_RingSet` (padding: the ring's first point)."""
    start = np.cumsum(count) - count
    col = np.arange(int(count.max()) + 1)
    return _take_points(flat, start[:, None] + np.where(col < count[:, None], col, 0))


def _take_points(points, index) -> np.ndarray:
    """``points[index]`` for (P, 2) ``points``: the rows read as complex numbers, which is
    several times faster than numpy's fancy indexing of rows (same values)."""
    flat = np.ascontiguousarray(points, dtype=float).view(np.complex128).reshape(-1)
    return flat.take(index).view(np.float64).reshape(np.shape(index) + (2,))


def part_rings(part) -> _RingSet:
    """:class:`_RingSet` of a ``polygon`` part's sections, built once per part and kept on it
    (the added mass and the cross-flow drag of a strip model both need it)."""
    cache = getattr(part, "_ring_set_cache", None)
    if cache is not None and cache[0] is part.contours:
        return cache[1]
    rs = _ring_set(part.contours, "sections")
    part._ring_set_cache = (part.contours, rs)
    return rs


def _interp_rows(x, xp, fps, last):
    """``np.interp`` row by row: row r is ``np.interp(x[r], xp[r, :last[r] + 1],
    fp[r, :last[r] + 1])`` for each ``fp`` in the list ``fps`` (one knot search for all),
    with numpy's arithmetic (on the knot interval xp[j] <= x < xp[j+1]:
    (fp[j+1] - fp[j]) / (xp[j+1] - xp[j]) * (x - xp[j]) + fp[j]; fp[last] at and after the
    last knot).  Needs x >= xp[:, 0] and rows of xp increasing."""
    nr, nk = xp.shape
    base = np.arange(nr)[:, None] * nk                 # xp.ravel()[base + j] is xp[r, j]
    xpf = xp.reshape(-1)
    lastc = last[:, None]
    # the knot interval of every x by one searchsorted over all rows, row r shifted by
    # r * span (span: a power of two above every value, so the rows stay apart) ...
    span = 2.0 ** (np.ceil(np.log2(max(float(xp.max()), float(x.max()), 1.0))) + 1.0)
    shift = np.arange(nr)[:, None] * span
    j = np.searchsorted((xp + shift).reshape(-1), (x + shift).reshape(-1), side="right")
    j = np.clip(j.reshape(x.shape) - 1 - base, 0, lastc)
    # ... the shift rounds, and values closer than its last bit may tie: correct j exactly
    while True:
        up = (j < lastc) & (xpf.take(base + np.minimum(j + 1, nk - 1)) <= x)
        down = (j > 0) & (xpf.take(base + j) > x)
        if not (up.any() or down.any()):
            break
        j = j + up - down
    k = base + np.minimum(j, lastc - 1)                # interval's left knot
    x0 = xpf.take(k)
    dx, at_knot, past = xpf.take(k + 1) - x0, x == x0, j >= lastc
    out = []
    for fp in fps:
        fpf = fp.reshape(-1)
        f0 = fpf.take(k)
        val = (fpf.take(k + 1) - f0) / dx * (x - x0) + f0
        out.append(np.where(past, fpf.take(base + lastc), np.where(at_knot, f0, val)))
    return out


def _resample_smooth(rs: _RingSet, rings, n) -> np.ndarray:
    r"""``n`` nodes on each of the rings ``rings`` (no sharp corner) of ``rs``, all at once:
    (len(rings), max(n), 2), row i's first n[i] nodes.

    Equidistributed in arc length plus turning,
    :math:`\mu(s) = s + w\,P/(2\pi)\,\Theta(s)` (w = :data:`CURVATURE_WEIGHT`, P the
    perimeter, :math:`\Theta` the turning angle so far, each vertex's turn spread over its
    two edges): n equal steps of mu mapped back to s, then to (y, z) by linear interpolation
    along the ring. [assumption] the weighting is this module's choice (no published rule);
    accuracy against exact sections in tests/test_panel_exact.py."""
    cnt = rs.count[rings]
    seg, turn = rs.seg[rings], rs.turn[rings]
    k = len(rings)
    rows = np.arange(k)
    zero = np.zeros((k, 1))
    s = np.concatenate((zero, np.cumsum(seg, axis=1)), axis=1)          # arc length at vertices
    perim = s[rows, cnt]
    # mu(s) = s + P/(2 pi) Theta(s), the turning at each vertex spread over its two edges
    turn_next = np.concatenate((turn[:, 1:], zero), axis=1)
    turn_next[rows, cnt - 1] = turn[:, 0]                                # the ring closes
    theta = np.concatenate((zero, np.cumsum(0.5 * (turn + turn_next), axis=1)), axis=1)
    mu = s + (CURVATURE_WEIGHT * perim / (2.0 * np.pi))[:, None] * theta
    # n equidistributed values of mu per ring (as np.linspace(0, mu_end, n, endpoint=False))
    col = np.arange(int(n.max()))
    q = col * (mu[rows, cnt] / n)[:, None] + 0.0
    q = np.where(col < n[:, None], q, 0.0)                               # padding: any valid x
    (t,) = _interp_rows(q, mu, [s], cnt)
    pts = rs.pts[rings]
    return np.stack(_interp_rows(t, s, [pts[..., 0], pts[..., 1]], cnt), axis=2)


def _discretise_rings(rs: _RingSet, panels):
    """Panel nodes of every section of ``rs`` (see :func:`discretise` for the panel count):
    the nodes of all rings in ring order (Q, 2) and the node count of each ring (R,).
    Smooth rings: :func:`_resample_smooth`; rings with sharp corners:
    :func:`_resample_cornered`."""
    if panels == 0:
        return rs.pts[:, :-1][np.arange(rs.pts.shape[1] - 1) < rs.count[:, None]], rs.count
    ncorner = rs.corner.sum(axis=1)
    nrings = np.diff(rs.rings_of)
    several = np.nonzero(nrings > 1)[0]
    perims = rs.perimeters() if panels is None or several.size else None
    if panels is None:
        # DEFAULT_PANELS times sqrt(P^2 / (4 pi A)) of the section's most slender ring
        # (1 for a circle, 4.2 for a 10:1 ellipse), capped at 3x, rounded to 16 for batching
        q = perims ** 2 / (4.0 * np.pi * np.abs(rs.area))
        full = nrings > 0
        qs = np.maximum.reduceat(q, rs.rings_of[:-1][full])
        per_sec = np.zeros(rs.nsec, int)
        per_sec[full] = 16 * np.round(DEFAULT_PANELS * np.minimum(3.0, np.sqrt(qs)) / 16)
    else:
        per_sec = np.full(rs.nsec, int(panels))
    # one ring: its whole budget, at least the per-contour and per-edge minima
    # (_panel_budget with one ring); several rings: _panel_budget, section by section
    budget = np.maximum(per_sec[rs.section],
                        np.maximum(MIN_PANELS_PER_CONTOUR, MIN_PANELS_PER_EDGE * ncorner))
    for s in several:
        mine = slice(rs.rings_of[s], rs.rings_of[s + 1])
        budget[mine] = _panel_budget(rs.corner[mine], per_sec[s], perims[mine])
    nodes = np.empty((int(budget.sum()), 2))
    first = np.cumsum(budget) - budget                                   # first node of each ring
    smooth = np.nonzero(ncorner == 0)[0]
    if smooth.size:
        res = _resample_smooth(rs, smooth, budget[smooth])
        valid = np.arange(res.shape[1]) < budget[smooth][:, None]
        if smooth.size == len(budget) and valid.all():   # all rings, same count: in order
            nodes = res.reshape(-1, 2)
        else:
            nodes[(first[smooth][:, None] + np.arange(res.shape[1]))[valid]] = res[valid]
    for r in np.nonzero(ncorner > 0)[0]:                                 # cosine clustering
        nodes[first[r]:first[r] + budget[r]] = _resample_cornered(rs.ring(r), budget[r],
                                                                  rs.corner[r, :rs.count[r]],
                                                                  rs.shape(r))
    return nodes, budget


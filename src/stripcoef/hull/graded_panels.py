r"""Panels graded towards the edges of a thin box member (a plate) or of a right prism (a
coarse cylinder, an extruded polygon: the section after :func:`box_level`), for the panel
method.

A plate of thickness t thinner than the uniform panels' edge h (issue 32: the CAD benchmark's
plates, t 2-5 % of the span) is a knife edge at the panels' scale: the isotropic remesh keeps
its rim as a crease but puts one panel across it, and the in-plane terms (the translations in
its plane and the rotation about its normal, where the flow turns round the rim) converge
slowly from above.  Measured on seed 1375923287 of ``benchmarks.cad_shapes``: the uniform
Capytaine levels of plate 3 (0.27 x 0.35 x 0.0086 m) are still 7.6 % above the limit in yaw
at 14,000 faces, and the panel method's extrapolation (order 1 from 1,700 and 4,700 panels)
+7.6 % in yaw and +5.2 % in sway against the edge-graded references
(``reference_tables/bem/cad_plates_graded.csv``, bands 0.3-1.3 %).

Here such a member, a convex polyhedron of six parallelogram faces (:func:`box_faces`), is
panelled as the references are: each face a tensor grid of quadrilaterals (two triangles
each) whose nodes are spaced towards both ends of every edge,

.. math:: x_k = \frac L2\left(1 - \cos\frac{\pi k}{n}\right),\qquad k = 0 \dots n

(the cosine spacing: the panel at an edge is of the order of the square of the uniform one,
a mesh graded towards the edges with exponent 2, which restores the convergence the edge
singularity takes from uniform panels: von Petersdorff & Stephan 1990, Math. Methods Appl.
Sci. 12, 229-249, "boundary element methods on graded meshes"), n even on every edge
(:data:`LEAST_NODES` at least, so that the thickness is crossed by several rows and the
mid-planes are node lines: a mirror plane through the centre cuts no panel).  An edge's count
depends only on its length, so the faces meeting at it share its nodes (a conforming mesh).
The member's sharpest edge is then resolved (rows across the thickness far thinner than t),
and the value's order is that of its right-angled edges (:func:`stripcoef.hull.panels.
edge_order`, 4/3), not the knife edge's 1.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Fewest panels along any edge [-] (even: the mid-plane a node line), so that the
#: thickness is crossed by several rows (the references' eighth box: at least 3 per half).
LEAST_NODES = 4
#: Relative tolerance of the geometric tests (planes, parallelograms) [-].
TOL = 1e-7


def _planes(v, f, most: int = 6):
    """[(unit outward normal, offset)] of the distinct face planes of a closed surface
    (vertices [m], faces); ``None`` as soon as there are more than ``most`` (a curved or
    finely faceted body is given up after a few faces, whatever its size)."""
    scale = float(np.ptp(v, axis=0).max())
    c0 = v.mean(axis=0)
    tri = v[f]
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    a = np.linalg.norm(n, axis=1)
    keep = a > 1e-14 * scale ** 2
    n = n[keep] / a[keep, None]
    p0 = tri[keep, 0]
    out: list = []
    for ni, pi in zip(n, p0):
        if np.dot(ni, pi - c0) < 0:
            ni = -ni
        d = float(np.dot(ni, pi))
        if not any(np.dot(ni, m) > 1 - TOL and abs(d - dd) <= TOL * scale for m, dd in out):
            out.append((ni, d))
            if len(out) > most:
                return None
    return out


def box_faces(vertices, faces):
    """The six faces of a closed surface that is a parallelepiped (a box, a plate: a convex
    polyhedron of six parallelogram faces, however its CAD export triangulated them), each
    as its four corners (4, 3) [m] counter-clockwise seen from outside; ``None`` for any
    other body."""
    from scipy.spatial import ConvexHull, QhullError

    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int64)
    if len(v) < 8 or len(f) < 12:
        return None
    scale = float(np.ptp(v, axis=0).max())
    planes = _planes(v, f)
    if planes is None or len(planes) != 6:
        return None
    # convex: every vertex on the inner side of every face plane
    for n, d in planes:
        if np.any(v @ n - d > 1e-6 * scale):
            return None
    out = []
    for n, d in planes:
        on = v[np.abs(v @ n - d) <= 1e-6 * scale]
        key = np.round(on / (1e-9 * scale)).astype(np.int64)
        on = on[np.unique(key, axis=0, return_index=True)[1]]
        c = on.mean(axis=0)
        e1 = on[np.argmax(np.linalg.norm(on - c, axis=1))] - c
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(n, e1)
        # the corners: the convex hull of the plane's points (points inside the face or on
        # its sides dropped), counter-clockwise about n
        try:
            hull = ConvexHull(np.column_stack([(on - c) @ e1, (on - c) @ e2]))
        except QhullError:         # degenerate (collinear) points: not a face of a box
            return None
        ring = on[hull.vertices]
        if len(ring) != 4:
            return None
        if np.linalg.norm(ring[0] + ring[2] - ring[1] - ring[3]) > 1e-6 * scale:
            return None                                   # not a parallelogram
        out.append(ring)
    return out


def thickness(corners) -> float:
    """The smallest distance between two opposite faces of the parallelepiped [m]; of a
    :class:`Prism`, the smaller of its height and its polygon's least width (the least
    distance between a side's line and the farthest corner)."""
    if isinstance(corners, Prism):
        b = corners.base
        k = len(b)
        width = min(max(float(np.linalg.norm(np.cross(b[(i + 1) % k] - b[i], p - b[i])))
                        / float(np.linalg.norm(b[(i + 1) % k] - b[i])) for p in b)
                    for i in range(k))
        return min(corners.height, width)
    c0 = np.mean([q.mean(axis=0) for q in corners], axis=0)
    heights = []
    for q in corners:
        n = np.cross(q[1] - q[0], q[3] - q[0])
        n /= np.linalg.norm(n)
        heights.append(2.0 * abs(np.dot(n, q[0] - c0)))
    return float(min(heights))


def _nodes(length: float, h: float, least: int = LEAST_NODES) -> np.ndarray:
    """Even n (at least ``least``, :data:`LEAST_NODES`) of about length / h panels, spaced as
    cosines on [0, 1] [-]."""
    n = max(least, 2 * int(round(0.5 * length / h)))
    return 0.5 * (1.0 - np.cos(np.pi * np.arange(n + 1) / n))


def box_panels(corners, h: float) -> np.ndarray:
    """The graded panelling (triangles (n, 3, 3) [m], counter-clockwise seen from the fluid)
    of the parallelepiped whose faces are ``corners`` (:func:`box_faces`), about ``h`` [m]
    mean panel size along every edge (module docstring)."""
    tris = []
    for q in corners:
        u = _nodes(float(np.linalg.norm(q[1] - q[0])), h)
        w = _nodes(float(np.linalg.norm(q[3] - q[0])), h)
        uu, ww = np.meshgrid(u, w, indexing="ij")
        p = (q[0] + uu[..., None] * (q[1] - q[0]) + ww[..., None] * (q[3] - q[0]))
        a, b = p[:-1, :-1], p[1:, :-1]
        c, d = p[1:, 1:], p[:-1, 1:]
        tris.append(np.stack([a, b, c], axis=-2).reshape(-1, 3, 3))
        tris.append(np.stack([a, c, d], axis=-2).reshape(-1, 3, 3))
    return np.concatenate(tris)


def panels_at(corners, h: float) -> int:
    """Triangles of :func:`box_panels` at ``h`` (no mesh built) [-]."""
    total = 0
    for q in corners:
        nu = len(_nodes(float(np.linalg.norm(q[1] - q[0])), h)) - 1
        nw = len(_nodes(float(np.linalg.norm(q[3] - q[0])), h)) - 1
        total += 2 * nu * nw
    return total


def size_for_panels(corners, panels: int) -> float:
    """The panel size h [m] whose :func:`box_panels` has about ``panels`` triangles, and at
    least as many (bisection on h; the counts are steps); ``corners`` may be a
    :class:`Prism`."""
    area = _area(corners)
    hi = 4.0 * np.sqrt(area / max(panels, 1))
    lo = hi / 64.0
    for _ in range(60):
        mid = np.sqrt(lo * hi)
        if _panels_at(corners, mid) >= panels:
            lo = mid
        else:
            hi = mid
    if isinstance(corners, Prism):
        # at least LEAST_NODES panels on the polygon's longest side, graded: a coarser
        # level does not resolve the flow round its facet edges (prism section's docstring)
        b = corners.base
        lo = min(lo, float(np.linalg.norm(np.roll(b, -1, axis=0) - b, axis=1).max())
                 / LEAST_NODES)
    return float(lo)


def positive_part(tri, planes, about, scale: float):
    """The triangles on the positive side of each of ``planes`` ("x", "y", "z") through
    ``about`` [m], or ``None`` when some triangle straddles a plane (the panelling is then
    solved whole)."""
    keep = np.ones(len(tri), bool)
    p0 = np.asarray(about, float)
    for p in planes:
        a = "xyz".index(p)
        x = tri[:, :, a] - p0[a]
        tol = 1e-9 * scale
        pos = (x >= -tol).all(axis=1)
        neg = (x <= tol).all(axis=1)
        if not np.all(pos | neg):
            return None
        keep &= pos
    return tri[keep]


def box_level(corners, panels: int, planes=(), about=(0.0, 0.0, 0.0)):
    """One level of the graded panelling of a parallelepiped at about ``panels`` triangles
    (at least as many): (vertices [m], faces, the planes it is to be solved with, its
    largest row across the thickness [m]).  With mirror planes through ``about`` that cut
    no panel, the part on their positive side (:func:`positive_part`, solved with image
    panels by :mod:`stripcoef.hull.mirror_panels`); else the whole panelling and no
    planes.  ``corners`` may be a :class:`Prism` (:func:`prism_panels`)."""
    h = size_for_panels(corners, panels)
    tri = prism_panels(corners, h) if isinstance(corners, Prism) else box_panels(corners, h)
    scale = float(np.ptp(tri.reshape(-1, 3), axis=0).max())
    part = positive_part(tri, tuple(planes), about, scale) if planes else None
    use = tuple(planes) if part is not None else ()
    tri = part if part is not None else tri
    t = thickness(corners)
    row = float(np.diff(_nodes(t, h)).max() * t)
    return (tri.reshape(-1, 3), np.arange(3 * len(tri)).reshape(-1, 3), use, row)


# --- right prisms: a convex polygon extruded (issue 32's coarse cylinders and extrusions) ---
#
# A coarse cylinder's rotation about its axis (and an extruded polygon's) exists only through
# its facet edges: the normal velocity (x x n) . e_axis vanishes on a circle and the flow of
# the polygon turns round each facet edge, a wedge of fluid of angle pi + theta (theta = 2 pi
# / k for a regular k-gon), where the velocity goes as r^(pi / (pi + theta) - 1) (Newman
# 1977, sec. 4.x; the edge singularities of von Petersdorff & Stephan 1990).  The isotropic
# remesh puts triangles of one size across these edges wherever its own edge flips leave
# them, so its levels of that small term wander (seed 1795948662's 12-facet cylinder 4: roll
# 1.19e-3, 0.99e-3, 1.02e-3, 0.97e-3 kg m^2 at 416 to 3,040 panels, the edge-graded
# reference 0.99e-3; benchmarks/data/roll32g_trace.md).  Such a prism is panelled as its
# references are (``benchmarks.graded_references.half_prism``): each cap as sectors from the
# polygon's centroid, graded towards the rim (sin spacing), each side a tensor grid graded
# towards both of its facet edges and towards both caps (cosine spacing, the box's
# :func:`_nodes`), a side's count depending only on its length, so that caps and sides share
# their nodes.


@dataclass(frozen=True)
class Prism:
    """A right prism: the convex polygon ``base`` (k, 3) [m], counter-clockwise seen from
    outside through that cap, extruded by ``height`` [m] along ``axis`` (unit, into the
    body from the base cap)."""

    base: np.ndarray
    axis: np.ndarray
    height: float

    @property
    def top(self) -> np.ndarray:
        """The other cap's corners, each above its base corner [m]."""
        return self.base + self.height * self.axis


#: Most sides of a prism panelled as one (its planes are read up to this many plus the two
#: caps); a finer faceted cylinder (a smooth one at the feature angle, 12 sides or more, and
#: its remesh) goes to the isotropic remesh, as before.  Not a tuned factor: a bound on the
#: cost of reading the planes, and every prism of the benchmark families (5-12 sides) is in.
MOST_PRISM_SIDES = 24
#: Fewest panels along a side of a prism's polygon [-] (even: a mirror plane through a
#: side's middle is a node line; its longest side takes at least :data:`LEAST_NODES`,
#: :func:`size_for_panels`); the height, like a box's thickness, at least LEAST_NODES.  No
#: floor of LEAST_NODES on every side, so that the sides' counts grow with 1/h from the
#: coarsest level and the levels stay one family (with 4 on every side the short sides of a
#: 12-gon stalled while the rest refined and its roll wandered by 3 %).
PRISM_LEAST_NODES = 2
#: Whether a right prism (other than a box) takes the graded panels (:func:`prism_faces`).
PRISMS = True


def prism_faces(vertices, faces, most_panels: int | None = None):
    """The :class:`Prism` a closed surface is (a convex polygon of 5 to
    :data:`MOST_PRISM_SIDES` sides extruded normal to its plane, however its caps and sides
    were triangulated; a box is :func:`box_faces`'), ``None`` for any other body, when
    :data:`PRISMS` is off, or when its coarsest graded level (:data:`LEAST_NODES` panels on
    its longest side) has more than ``most_panels`` (the caller's cap on a level: a long
    many-sided prism, whose facets are short, stays with the isotropic remesh)."""
    from scipy.spatial import ConvexHull, QhullError

    if not PRISMS:
        return None
    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int64)
    if len(v) < 10 or len(f) < 16:
        return None
    scale = float(np.ptp(v, axis=0).max())
    planes = _planes(v, f, most=MOST_PRISM_SIDES + 2)
    if planes is None or len(planes) < 7:
        return None
    for n, d in planes:                                  # convex
        if np.any(v @ n - d > 1e-6 * scale):
            return None
    normals = np.array([n for n, _ in planes])
    for i, (n, d) in enumerate(planes):
        opp = [j for j in range(len(planes)) if normals[j] @ n < -1 + TOL]
        if len(opp) != 1:
            continue
        others = [j for j in range(len(planes)) if j != i and j != opp[0]]
        if np.all(np.abs(normals[others] @ n) < 1e-6):
            break
    else:
        return None
    height = d + planes[opp[0]][1]
    on = v[np.abs(v @ n - d) <= 1e-6 * scale]
    c = on.mean(axis=0)
    e1 = on[np.argmax(np.linalg.norm(on - c, axis=1))] - c
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(n, e1)
    try:
        hull = ConvexHull(np.column_stack([(on - c) @ e1, (on - c) @ e2]))
    except QhullError:
        return None
    base = on[hull.vertices]                              # counter-clockwise about n
    if len(base) != len(others):
        return None
    top = base - height * n
    other_cap = v[np.abs(v @ n - (d - height)) <= 1e-6 * scale]
    if not all(np.min(np.linalg.norm(other_cap - p, axis=1)) <= 1e-6 * scale for p in top):
        return None
    # every vertex on one of the caps (no point of a side off them: a side is a rectangle)
    if len(on) + len(other_cap) != len(np.unique(np.round(v / (1e-9 * scale)), axis=0)):
        return None
    prism = Prism(base, -n, float(height))
    if most_panels is not None and _panels_at(prism, size_for_panels(prism, 1)) > most_panels:
        return None
    return prism


def _prism_counts(prism: Prism, h: float):
    """(node arrays on [0, 1]: per side along the rim, along the height, radial on the
    caps) of the graded panelling at about ``h`` [m] (module docstring)."""
    sides = np.linalg.norm(np.roll(prism.base, -1, axis=0) - prism.base, axis=1)
    # equal sides (a regular polygon's, to round-off) take equal counts: h is bisected onto
    # a count's step, where the round-off of an STL (float32, 6e-8) would round two equal
    # sides apart
    sides = sides.max() * np.round(sides / sides.max(), 6)
    c = prism.base.mean(axis=0)
    r_max = float(np.max(np.linalg.norm(prism.base - c, axis=1)))
    nr = max(1, int(round(r_max / h)))
    radial = np.sin(0.5 * np.pi * np.arange(nr + 1) / nr)      # uniform at the centre
    return ([_nodes(s, h, PRISM_LEAST_NODES) for s in sides], _nodes(prism.height, h),
            radial)


def _tri(p):
    """The two triangles (a, b, c), (a, c, d) of each cell of the grid p (nu, nv, 3)."""
    a, b = p[:-1, :-1], p[1:, :-1]
    c, d = p[1:, 1:], p[:-1, 1:]
    return np.concatenate([np.stack([a, b, c], axis=-2).reshape(-1, 3, 3),
                           np.stack([a, c, d], axis=-2).reshape(-1, 3, 3)])


def prism_panels(prism: Prism, h: float) -> np.ndarray:
    """The graded panelling (triangles (n, 3, 3) [m], counter-clockwise seen from the fluid)
    of ``prism`` at about ``h`` [m] along every edge (the section's docstring); the cap
    sectors' first row, a cell with two corners at the centroid, gives one triangle."""
    along, up, radial = _prism_counts(prism, h)
    k = len(prism.base)
    tris = []
    for cap in (prism.base, prism.top):
        c = cap.mean(axis=0)
        for i in range(k):
            rim = cap[i] + along[i][:, None] * (cap[(i + 1) % k] - cap[i])
            tris.append(_tri(c + radial[:, None, None] * (rim[None, :, :] - c)))
    for i in range(k):
        rim = prism.base[i] + along[i][:, None] * (prism.base[(i + 1) % k] - prism.base[i])
        tris.append(_tri(rim[:, None, :] + up[None, :, None] * prism.height * prism.axis))
    tri = np.concatenate(tris)
    cr = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    dbl = np.linalg.norm(cr, axis=1)
    scale = float(np.ptp(np.vstack([prism.base, prism.top]), axis=0).max())
    tri = tri[dbl > 1e-12 * scale ** 2]
    cr = cr[dbl > 1e-12 * scale ** 2]
    centre = 0.5 * (prism.base.mean(axis=0) + prism.top.mean(axis=0))
    inward = np.einsum("ij,ij->i", cr, tri.mean(axis=1) - centre) < 0   # convex: outward
    tri[inward] = tri[inward][:, ::-1]
    return tri


def _panels_at(shape, h: float) -> int:
    """Triangles of the graded panelling of a box (:func:`panels_at`) or a prism at ``h``."""
    if not isinstance(shape, Prism):
        return panels_at(shape, h)
    along, up, radial = _prism_counts(shape, h)
    rim = sum(len(a) - 1 for a in along)
    return 2 * rim * (2 * len(radial) - 3) + 2 * rim * (len(up) - 1)


def _area(shape) -> float:
    if not isinstance(shape, Prism):
        return sum(float(np.linalg.norm(np.cross(q[1] - q[0], q[3] - q[0]))) for q in shape)
    b = shape.base
    k = len(b)
    cap = 0.5 * np.linalg.norm(sum(np.cross(b[i], b[(i + 1) % k]) for i in range(k)))
    return float(2 * cap + shape.height * sum(np.linalg.norm(b[(i + 1) % k] - b[i])
                                              for i in range(k)))

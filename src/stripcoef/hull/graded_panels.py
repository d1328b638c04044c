r"""Panels graded towards the edges of a thin box member (a plate), for the panel method.

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
    """The smallest distance between two opposite faces of the parallelepiped [m]."""
    c0 = np.mean([q.mean(axis=0) for q in corners], axis=0)
    heights = []
    for q in corners:
        n = np.cross(q[1] - q[0], q[3] - q[0])
        n /= np.linalg.norm(n)
        heights.append(2.0 * abs(np.dot(n, q[0] - c0)))
    return float(min(heights))


def _nodes(length: float, h: float) -> np.ndarray:
    """Even n (at least :data:`LEAST_NODES`) of about length / h panels, spaced as cosines on
    [0, 1] [-]."""
    n = max(LEAST_NODES, 2 * int(round(0.5 * length / h)))
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
    least as many (bisection on h; the counts are steps)."""
    area = sum(float(np.linalg.norm(np.cross(q[1] - q[0], q[3] - q[0]))) for q in corners)
    hi = 4.0 * np.sqrt(area / max(panels, 1))
    lo = hi / 64.0
    for _ in range(60):
        mid = np.sqrt(lo * hi)
        if panels_at(corners, mid) >= panels:
            lo = mid
        else:
            hi = mid
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
    planes."""
    h = size_for_panels(corners, panels)
    tri = box_panels(corners, h)
    scale = float(np.ptp(tri.reshape(-1, 3), axis=0).max())
    part = positive_part(tri, tuple(planes), about, scale) if planes else None
    use = tuple(planes) if part is not None else ()
    tri = part if part is not None else tri
    t = thickness(corners)
    row = float(np.diff(_nodes(t, h)).max() * t)
    return (tri.reshape(-1, 3), np.arange(3 * len(tri)).reshape(-1, 3), use, row)

"""Edge-graded panels of the bluff set's unions of prisms along x (issue 32): the box with
skids, the L-shaped block, the box with a pod, the cylinder with a float and the twin hull of
:mod:`benchmarks.bluff_shapes` (``PRISM_PARTS``), for ``benchmarks.graded_references unions``.

Every part of these shapes is a convex prism along x (a box, or trimesh's 24-sided cylinder
along x: the faceted body that the stored references ``bem_bluff.csv`` and the panel method
both see), so their union is a stepped prism: between two consecutive part ends the cross
section (y, z) is the union of the parts present; at each end the body's face is the
difference of the sections on either side.  Each planar piece is panelled on its own (the
constant-panel direct method needs no conforming mesh: the panels only have to cover the
surface once):

- the side between two part ends: each edge of the section's boundary times the nodes in x
  (a piece of length l in ceil(m sqrt(l / S)) panels, S the body's largest extent, m the
  level: :func:`_count`), graded towards both part ends (x_k = L (1 - cos(pi k / n)) / 2: the panel at an edge the
  square of the uniform one, as :mod:`benchmarks.plate_graded` grades a box); along the
  boundary towards each *sharp* vertex only (turning angle above :data:`SHARP`): a box's
  corners and the lines where two parts meet, not the 15 deg facet joints of a 24-sided
  cylinder, which tessellate a round surface and are panelled uniformly (the flow there is
  nearly regular: the wedge exponent pi / (pi + 15 deg) = 0.92, Newman 1977 sec. 4.4);
- the end faces: cut into vertical trapezoids at the y of every vertex (no vertex inside a
  trapezoid, so its lower and upper sides are straight), each a structured grid graded
  towards its four sides.

Only the y >= 0 half is built (every shape here is mirror-symmetric in y) and, where the shape
is also mirror-symmetric in x (``box_skid``, ``twin_hull``), its x >= 0 quarter; the solve uses
Capytaine's mirror planes.  The shape is taken about its volume centroid (the point of
``bem_bluff.csv``).
"""

from __future__ import annotations

import numpy as np

from benchmarks.plate_graded import cosine_nodes, graded_nodes

#: a vertex of a section's boundary whose turning angle exceeds this is a sharp edge [rad]
#: (boxes 90 deg, part junctions 35-90 deg; the 24-sided cylinders' facet joints 15 deg)
SHARP = np.radians(30.0)
#: coordinates closer than this are one [m]
TOL = 1e-10


def _prism(part):
    """(x0, x1, section polygon (y, z)) of a convex trimesh prism along x [m]."""
    from shapely.geometry import MultiPoint

    v = np.asarray(part.vertices, float)
    xs = np.unique(np.round(v[:, 0], 9))
    if len(xs) != 2:
        raise ValueError(f"not a prism along x: {len(xs)} distinct x")
    return float(v[:, 0].min()), float(v[:, 0].max()), MultiPoint(v[:, 1:]).convex_hull


def shape_prisms(name: str):
    """The prisms of the bluff set's shape ``name`` about its volume centroid (the
    union's, as ``bem_bluff.csv``), and whether the shape is mirror-symmetric in x:
    ([(x0, x1, polygon)], symmetric_in_x)."""
    from shapely import affinity

    from benchmarks.bluff_shapes import PRISM_PARTS, SHAPES

    c = np.asarray(SHAPES[name][0](None).center_mass, float)
    if abs(c[1]) > 1e-9:
        raise ValueError(f"{name}: volume centroid off the mirror plane y = 0 ({c[1]:.3g} m)")
    c[1] = 0.0                                           # the union's round-off (1e-13 m)
    if abs(c[0]) < 1e-9:
        c[0] = 0.0
    out = []
    for p in PRISM_PARTS[name]():
        x0, x1, poly = _prism(p)
        out.append((x0 - c[0], x1 - c[0], affinity.translate(poly, -c[1], -c[2])))
    xs = sorted({v for a, b, _ in out for v in (a, b)})
    for xa, xb in zip(xs[:-1], xs[1:]):
        sec = _section(out, 0.5 * (xa + xb))
        mirrored = affinity.scale(sec, -1.0, 1.0, origin=(0.0, 0.0))
        if mirrored.symmetric_difference(sec).area > 1e-9 * max(sec.area, 1e-30):
            raise ValueError(f"{name}: not mirror-symmetric in y about its centroid")
    ends = sorted((round(a, 9), round(b, 9)) for a, b, _ in out)
    flipped = sorted((round(-b, 9), round(-a, 9)) for a, b, _ in out)
    return out, ends == flipped and abs(c[0]) < 1e-9


def _section(prisms, x):
    """The union of the sections of the prisms present at x (shapely, maybe empty)."""
    from shapely.geometry import Polygon
    from shapely.ops import unary_union

    live = [p for a, b, p in prisms if a < x < b]
    return unary_union(live) if live else Polygon()


def _rings(section):
    """The boundary rings of a section, each (k, 2) counter-clockwise about the solid
    (exterior CCW, holes CW), collinear vertices removed."""
    from shapely.geometry import MultiPolygon
    from shapely.geometry.polygon import orient

    polys = section.geoms if isinstance(section, MultiPolygon) else [section]
    out = []
    for p in polys:
        if p.is_empty:
            continue
        p = orient(p, 1.0)
        for ring in [p.exterior, *p.interiors]:
            r = np.asarray(ring.coords, float)[:-1]
            keep = []
            for i in range(len(r)):
                a, b = r[i] - r[i - 1], r[(i + 1) % len(r)] - r[i]
                if abs(a[0] * b[1] - a[1] * b[0]) > 1e-12 * np.linalg.norm(a) * np.linalg.norm(b):
                    keep.append(i)
            out.append(r[keep])
    return out


def _turning(ring):
    """Turning angle at each vertex of a closed ring [rad]."""
    a = ring - np.roll(ring, 1, axis=0)
    b = np.roll(ring, -1, axis=0) - ring
    return np.abs(np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], np.einsum("ij,ij->i", a, b)))


def _spacing(n: int, start_sharp: bool, end_sharp: bool) -> np.ndarray:
    """n + 1 nodes on [0, 1]: graded towards the sharp end(s), else uniform."""
    if start_sharp and end_sharp:
        return cosine_nodes(1.0, n)
    if end_sharp:
        return graded_nodes(1.0, n)
    if start_sharp:
        return 1.0 - graded_nodes(1.0, n)[::-1]
    return np.linspace(0.0, 1.0, n + 1)


def _count(m: int, length: float, scale: float, least: int) -> int:
    """Panels on a graded piece of ``length`` [m] of a body of extent ``scale`` [m] at level
    ``m``: ceil(m sqrt(length / scale)), at least ``least``.  Every piece's panels shrink
    as 1/m from the coarsest level used (a count proportional to the length would hold the
    short pieces, a skid's 0.03 m, at their floor of two panels over several levels: the
    levels would not be similar, and Eça & Hoekstra's fit takes one h for all panels);
    short pieces are panelled relatively finer, where a body's edges crowd."""
    return max(least, int(np.ceil(m * np.sqrt(length / scale) - 1e-9)))


def _count_smooth(m: int, length: float, scale: float) -> int:
    """Panels on a facet between two smooth (not sharp) joints, uniform: half of
    :func:`_count`, at least one."""
    return max(1, int(np.ceil(0.5 * m * np.sqrt(length / scale) - 1e-9)))


def _side(ring, x_nodes, m, scale):
    """Quadrilaterals (q, 4, 3) of the side of a section ring between the x nodes, the
    y >= 0 half, outward normals; graded along the ring towards its sharp vertices."""
    sharp = _turning(ring) > SHARP
    quads = []
    k = len(ring)
    for i in range(k):
        a, b = ring[i], ring[(i + 1) % k]
        sa, sb = bool(sharp[i]), bool(sharp[(i + 1) % k])
        if a[0] < -TOL and b[0] < -TOL or (abs(a[0]) <= TOL and abs(b[0]) <= TOL):
            continue                                    # the other half, or on the mirror
        if a[0] < -TOL or b[0] < -TOL:                   # crosses y = 0: keep y >= 0
            t = a[0] / (a[0] - b[0])
            cut = a + t * (b - a)
            cut[0] = 0.0
            a, sa = (cut, False) if a[0] < 0 else (a, sa)
            b, sb = (cut, False) if b[0] < 0 else (b, sb)
        length = float(np.linalg.norm(b - a))
        n = _count(m, length, scale, 2) if (sa or sb) else _count_smooth(m, length, scale)
        t = _spacing(n, sa, sb)
        pts = a + t[:, None] * (b - a)                   # (nt, 2) y, z
        for j in range(len(pts) - 1):
            for x0, x1 in zip(x_nodes[:-1], x_nodes[1:]):
                p, q = pts[j], pts[j + 1]
                # ring CCW in (y, z): the solid on the left, outward normal (dz, -dy)
                quads.append([[x0, *p], [x0, *q], [x1, *q], [x1, *p]])
    return quads


def _trapezoids(region):
    """The region (shapely) cut at the y of each of its vertices into pieces with straight
    lower and upper sides: [(ya, yb, (zlo_a, zhi_a), (zlo_b, zhi_b))]."""
    from shapely.geometry import MultiPolygon, box

    polys = region.geoms if isinstance(region, MultiPolygon) else [region]
    ys = np.unique(np.round(np.concatenate(
        [np.asarray(r.coords)[:, 0] for p in polys if not p.is_empty
         for r in [p.exterior, *p.interiors]]), 10))
    out = []
    for ya, yb in zip(ys[:-1], ys[1:]):
        if yb - ya < TOL:
            continue
        piece = region.intersection(box(ya, -1e3, yb, 1e3))
        pieces = piece.geoms if hasattr(piece, "geoms") else [piece]
        for p in pieces:
            if p.geom_type != "Polygon" or p.area < 1e-14:
                continue
            c = np.asarray(p.exterior.coords)[:-1]
            at_a, at_b = c[np.abs(c[:, 0] - ya) < 1e-9, 1], c[np.abs(c[:, 0] - yb) < 1e-9, 1]
            if len(at_a) == 0 or len(at_b) == 0 or len(at_a) + len(at_b) != len(c):
                raise ValueError(f"slab {ya:.6g}-{yb:.6g}: not a trapezoid")
            out.append((ya, yb, (at_a.min(), at_a.max()), (at_b.min(), at_b.max())))
    return out


def _end(region, x, sign, m, scale):
    """Quadrilaterals of the planar end face ``region`` (y, z) at x, normal sign * x."""
    quads = []
    for ya, yb, (la, ha), (lb, hb) in _trapezoids(region):
        ty = cosine_nodes(1.0, _count(m, yb - ya, scale, 2))
        tz = cosine_nodes(1.0, _count(m, max(ha - la, hb - lb), scale, 2))
        y = ya + ty * (yb - ya)
        lo, hi = la + ty * (lb - la), ha + ty * (hb - ha)
        z = lo[:, None] + tz[None, :] * (hi - lo)[:, None]          # (ny, nz)
        for i in range(len(y) - 1):
            for j in range(len(tz) - 1):
                q = [[x, y[i], z[i, j]], [x, y[i + 1], z[i + 1, j]],
                     [x, y[i + 1], z[i + 1, j + 1]], [x, y[i], z[i, j + 1]]]
                quads.append(q if sign > 0 else q[::-1])             # (y, z) CCW: +x
    return quads


def graded_part(prisms, m: int, quarter: bool):
    """The y >= 0 half (and x >= 0 quarter if ``quarter``) of the union of ``prisms``
    [(x0, x1, polygon)], panelled with ``m`` panels on the longest extent (graded as the
    module says): (vertices [m], faces (n, 4)) for Capytaine, outward normals; a panel with
    a zero-length side written as a triangle (its last vertex repeating the third), panels
    of zero area dropped."""
    from shapely.geometry import Polygon, box

    xs = sorted({round(v, 12) for a, b, _ in prisms for v in (a, b)})
    lo = np.array([min(p.bounds[0] for *_, p in prisms), min(p.bounds[1] for *_, p in prisms)])
    hi = np.array([max(p.bounds[2] for *_, p in prisms), max(p.bounds[3] for *_, p in prisms)])
    scale = max(xs[-1] - xs[0], *(hi - lo))
    if quarter:
        xs = [0.0] + [x for x in xs if x > TOL]
    half = box(0.0, -1e3, 1e3, 1e3)
    quads = []
    for i, (xa, xb) in enumerate(zip(xs[:-1], xs[1:])):
        sec = _section(prisms, 0.5 * (xa + xb))
        if sec.is_empty:
            continue
        n = _count(m, xb - xa, scale, 2)
        t = graded_nodes(1.0, n) if (quarter and i == 0) else cosine_nodes(1.0, n)
        xn = xa + t * (xb - xa)
        for ring in _rings(sec):
            quads += _side(ring, xn, m, scale)
    for k, x in enumerate(xs):
        if quarter and k == 0:
            continue                                     # the mirror plane x = 0
        left = _section(prisms, 0.5 * (xs[k - 1] + x)) if k > 0 else Polygon()
        right = _section(prisms, 0.5 * (x + xs[k + 1])) if k + 1 < len(xs) else Polygon()
        for region, sign in ((left.difference(right), 1.0), (right.difference(left), -1.0)):
            region = region.intersection(half)
            if region.area > 1e-14:
                quads += _end(region, x, sign, m, scale)
    return _faces(np.asarray(quads, float))


def _faces(quads):
    """(vertices, faces (n, 4)) of quadrilaterals (q, 4, 3): coincident vertices merged
    (1e-12 m), a panel with a repeated corner written as a triangle (last vertex repeating
    the third), panels of zero area dropped."""
    key = np.round(quads.reshape(-1, 3) / 1e-12).astype(np.int64)
    _, first, inv = np.unique(key, axis=0, return_index=True, return_inverse=True)
    v = quads.reshape(-1, 3)[first]
    idx = inv.reshape(-1, 4)
    out = []
    for q in idx:
        u = list(dict.fromkeys(q.tolist()))
        if len(u) < 3:
            continue
        p = v[u]
        n = np.cross(p[2] - p[0], p[-1] - p[1]) if len(u) == 4 else \
            np.cross(p[1] - p[0], p[2] - p[0])
        if np.linalg.norm(n) < 1e-16:
            continue
        if len(u) == 3:
            u.append(u[2])
        out.append(u)
    return v, np.array(out)


def whole(v, f, quarter: bool):
    """The whole closed body of a half (quarter) built by :func:`graded_part`, mirrored
    (faces reversed to keep the normals outward): (vertices, faces) for checks."""
    for axis, on in ((1, True), (0, quarter)):
        if on:
            w = v * np.where(np.arange(3) == axis, -1.0, 1.0)
            f = np.vstack([f, f[:, ::-1] + len(v)])
            v = np.vstack([v, w])
    return v, f


def area_volume(v, f):
    """Area [m^2] and enclosed volume [m^3] of quadrilateral panels (n, 4) (triangles
    with a repeated last vertex): each split into two triangles, the volume by the
    divergence theorem, V = sum (c . n) A / 3."""
    a, vol = 0.0, 0.0
    for tri in (f[:, [0, 1, 2]], f[:, [0, 2, 3]]):
        p = v[tri]
        n = 0.5 * np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
        a += np.linalg.norm(n, axis=1).sum()
        vol += np.einsum("ij,ij->", p.mean(axis=1), n) / 3.0
    return a, vol

"""Longest-edge bisection of a closed triangle mesh (the input's own surface at more panels),
and the surface area and enclosed volume both the panel levels and the remesh are checked by.

The panel method's input family (:func:`stripcoef.hull.panels.panel_levels`) and the remesher's
last resort (:func:`stripcoef.hull.remesh.remesh_family`, where no remesh keeps the area) both
refine the faces as they are: every new vertex lies on a face, so the geometry is unchanged
(Rivara 1984).  A module of its own so that both read it without importing each other.
"""

from __future__ import annotations

import numpy as np

from stripcoef.hull.memo import array_memo


def bisect_longest(vertices, faces, max_edge):
    r"""Split faces until no edge is longer than ``max_edge`` [m], always at the midpoint of a
    face's longest edge (Rivara 1984, "Algorithms for refining triangular grids suitable for
    adaptive and multigrid techniques", Int. J. Numer. Meth. Eng. 20: the longest-edge
    bisection with its conforming closure): slivers become well-shaped triangles, the mesh
    stays closed and its winding kept, and the new vertices lie on the flat faces (the
    geometry is unchanged).  Returns (vertices, faces)."""
    return _bisect(vertices, faces, lambda centroids: np.full(len(centroids), float(max_edge)))


def bisect_graded(vertices, faces, size, max_faces: int | None = None):
    r"""Split faces until every face's longest edge is at most ``size(centroids)`` [m] at its
    centroid (``size``: (n, 3) points [m] -> (n,) edge lengths [m], a sizing field such as
    :func:`stripcoef.hull.remesh.edge_graded_size`), always at the midpoint of the longest
    edge with Rivara's conforming closure (:func:`bisect_longest`, whose rule this is with a
    bound that varies over the surface): the surface unchanged, the mesh closed and its
    winding kept.  Returns (vertices, faces), or ``None`` once the mesh would exceed
    ``max_faces`` (a field finer than the caller can solve)."""
    return _bisect(vertices, faces, size, max_faces)


def _bisect(vertices, faces, bound, max_faces=None):
    """Longest-edge bisection until each face's longest edge is at most ``bound(centroids)``
    (``None`` beyond ``max_faces``)."""
    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int64)
    for _ in range(60):
        t = v[f]
        elen = np.linalg.norm(t[:, [1, 2, 0]] - t, axis=2)      # edge k: vertex k -> k+1
        longest = np.argmax(elen, axis=1)
        limit = np.asarray(bound(t.mean(axis=1)), float)
        if (elen.max(axis=1) <= limit).all():
            break
        if max_faces is not None and len(f) > max_faces:
            return None
        a = f.reshape(-1)
        b = np.roll(f, -1, axis=1).reshape(-1)
        key = np.minimum(a, b) * len(v) + np.maximum(a, b)
        uniq, inv = np.unique(key, return_inverse=True)
        inv = inv.reshape(-1, 3)
        rows = np.arange(len(f))
        marked = np.zeros(len(uniq), bool)
        marked[inv[rows, longest][elen[rows, longest] > limit]] = True
        while True:          # closure: a face with a marked edge has its longest edge marked
            need = marked[inv].any(axis=1) & ~marked[inv[rows, longest]]
            if not need.any():
                break
            marked[inv[rows[need], longest[need]]] = True
        ids = np.full(len(uniq), -1, np.int64)
        ids[marked] = len(v) + np.arange(marked.sum())
        ends = np.column_stack([uniq // len(v), uniq % len(v)])[marked]
        v = np.vstack([v, 0.5 * (v[ends[:, 0]] + v[ends[:, 1]])])
        # rotate each face so that its longest edge is 0 -> 1
        r = (longest[:, None] + np.arange(3)) % 3
        fa, fb, fc = np.take_along_axis(f, r, axis=1).T
        mab, mbc, mca = np.take_along_axis(ids[inv], r, axis=1).T
        split = mab >= 0
        out = [np.column_stack([fa, fb, fc])[~split]]
        fa, fb, fc, mab, mbc, mca = (x[split] for x in (fa, fb, fc, mab, mbc, mca))
        nb, nc = mbc < 0, mca < 0
        out += [np.column_stack([mab, fb, fc])[nb],                   # (m, b, c) whole
                np.column_stack([mab, fb, mbc])[~nb], np.column_stack([mab, mbc, fc])[~nb],
                np.column_stack([fa, mab, fc])[nc],                   # (a, m, c) whole
                np.column_stack([fa, mab, mca])[~nc], np.column_stack([mab, fc, mca])[~nc]]
        f = np.vstack(out)
    return v, f


def refine(vertices, faces, panels: int):
    """About ``panels`` triangles (the most at or below it) by longest-edge bisection
    (:func:`bisect_longest`), the edge bound found by bisection on the count.  A mesh of
    ``panels`` faces or more is returned as it is.  Returns (vertices, faces).  Computed once
    per process for the same mesh and count (:func:`_refined`: the panel method refines a
    vehicle's surface the same way at every estimate of it)."""
    if len(faces) >= panels:
        return vertices, faces
    return _refined(np.ascontiguousarray(vertices, dtype=float),
                    np.ascontiguousarray(faces, dtype=np.int64), int(panels))


@array_memo(maxsize=32)
def _refined(vertices, faces, panels: int):
    """:func:`refine` of float64 vertices and int64 faces (the memo's key,
    :func:`stripcoef.hull.memo.array_memo`)."""
    t = vertices[faces]
    hi = float(np.linalg.norm(t[:, [1, 2, 0]] - t, axis=2).max())
    lo = 1e-3 * hi
    best = (vertices, faces)
    for _ in range(14):
        mid = np.sqrt(lo * hi)
        v, f = bisect_longest(vertices, faces, mid)
        if len(f) > panels:
            lo = mid
        else:
            hi = mid
            if len(f) > len(best[1]):
                best = (v, f)
        if 0.97 * panels <= len(best[1]):
            break
    return best


def split_in_four(vertices, faces):
    """Every face split into four at its edge midpoints (trimesh.remesh.subdivide): the same
    polyhedron with the panel size halved, so that the two levels of the extrapolation are one
    family of meshes.  Returns (vertices, faces)."""
    import trimesh.remesh

    return trimesh.remesh.subdivide(vertices, faces)


def surface_area(vertices, faces) -> float:
    """Surface area [m^2] of a triangle mesh (vertices [m], faces): the sum of the triangles'
    areas, |(b - a) x (c - a)| / 2."""
    t = np.asarray(vertices, float)[np.asarray(faces)]
    return float(0.5 * np.linalg.norm(np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]),
                                      axis=1).sum())


def enclosed_volume(vertices, faces) -> float:
    """Enclosed volume [m^3] of a closed, outward-wound triangle mesh: the sum of the signed
    tetrahedra a . (b x c) / 6 (divergence theorem)."""
    t = np.asarray(vertices, float)[np.asarray(faces)]
    return float(np.einsum("ij,ij->i", t[:, 0], np.cross(t[:, 1], t[:, 2])).sum() / 6.0)

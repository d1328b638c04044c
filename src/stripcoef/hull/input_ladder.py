r"""The input family's levels: two nested pairs of the input's own faces, and its coarsening.

Without the remesher a small input (at most N/4 faces for N panels asked; boxes and plates
excepted, :mod:`stripcoef.hull.graded_panels`) was solved on two levels, the input bisected to
:math:`N_1 = \max(N/4, 2F)` panels and that split in four (:func:`stripcoef.hull.panels.
panel_levels`).  Two levels have no change to measure: their estimate is Roache's two-grid
index (:math:`F_s = 3`) plus the step, which warned on 28 of the 30 CAD shapes of seed
1375923287 that are neither boxes nor plates (8 of them off by more than 5 %), and cannot
see a term whose two values agree by chance.

:func:`ladder_levels` adds a second pair of the same kind: the input bisected to
:math:`2N_1` (Rivara 1984's longest-edge bisection, :func:`stripcoef.hull.bisection.refine`)
and that split in four, :math:`N_1 < 2N_1 < 4N_1 < 8N_1` (the remesher's N/4 ... 2N).  Each
pair is one polyhedron with h halved (its two meshes similar, so one error constant), the two
pairs one refinement apart; the value is the finer pair's Richardson extrapolation and its
estimate, which the warning reads, the step to the finest level plus the change since the
coarser pair's (:func:`stripcoef.hull.panel_error.ladder_extrapolation`).  Measured on those
30 shapes against the most resolved references (``python -m benchmarks.base_levels --whole``,
docs/performance.md): 179 of 180 diagonal terms within 5 % (168 with two levels), 9 of 30
shapes warned (28), 207 of 235 terms covered (226) by that estimate.  The band shown is Eça &
Hoekstra's least-squares uncertainty of the four levels moved to the value
(:func:`stripcoef.hull.panel_error.least_squares_error`): 233 of those 235 terms, and 95.1 %
and 97.3 % of the ladder's terms on two more seeds, the warnings unchanged
(``python -m benchmarks.ladder_estimate_rules``, benchmarks/data/ladder_estimate_rules.md).

The input family's coarsening lives here too: a mesh finer than the levels is coarsened by
quadric vertex clustering (:func:`coarsen`, :func:`vertex_quadrics`), on cells of
:data:`CLUSTER_CELL` times the level's edge; :func:`stripcoef.hull.panels.fine_smooth_input`
reads the same cell for its rule (remesh32h).
"""

from __future__ import annotations

import numpy as np

from stripcoef.hull.bisection import refine, split_in_four, surface_area
from stripcoef.hull.remesh import LEAST_FACE_RATIO

#: Cell of the input family's vertex clustering over the edge h of the level's equilateral
#: panels (:func:`stripcoef.hull.panels.coarsen`) [-]: a cell of 0.75 h gives about the
#: level's count after the clustering drops the faces that lose a vertex.
CLUSTER_CELL = 0.75


def vertex_quadrics(vertices, faces):
    r"""Per vertex, the summed plane quadrics of its faces: :math:`Q = \sum a\, n n^T` (V, 9)
    and :math:`b = \sum a\, n (n\cdot p)` (V, 3), a the doubled face area [m^2] (Lindstrom
    2000); computed once for all the clusterings of a mesh."""
    tri = vertices[faces]
    cr = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    a2 = np.linalg.norm(cr, axis=1)
    nrm = cr / np.where(a2 > 0, a2, 1.0)[:, None]
    q = (a2[:, None, None] * nrm[:, :, None] * nrm[:, None, :]).reshape(-1, 9)
    b = a2[:, None] * nrm * np.einsum("ij,ij->i", nrm, tri[:, 0])[:, None]
    idx = faces.reshape(-1)
    nv = len(vertices)
    qv = np.column_stack([np.bincount(idx, weights=np.repeat(q[:, c], 3), minlength=nv)
                          for c in range(9)])
    bv = np.column_stack([np.bincount(idx, weights=np.repeat(b[:, c], 3), minlength=nv)
                          for c in range(3)])
    return qv, bv


def _cluster(vertices, faces, h, quadrics=None):
    r"""Vertex clustering on a grid of cell ``h`` [m] (Rossignac & Borrel 1993, "Multi-resolution
    3D approximations for rendering complex scenes"), each cell's vertex placed where it
    minimises the summed squared distances to the planes of the faces around it (the quadric
    error metric, Lindstrom 2000, "Out-of-core simplification of large polygonal models",
    SIGGRAPH: :math:`x = \bar x + Q^+ (b - Q\bar x)`, :math:`Q = \sum a\, n n^T`,
    :math:`b = \sum a\, n (n\cdot p)`, singular values below 1e-3 of the largest dropped), so
    that edges and corners stay sharp.  Faces that lose a vertex, and pairs of coincident
    faces of opposite winding (a collapsed thin wall), are dropped.  ``quadrics``: those of
    :func:`vertex_quadrics` (computed if omitted)."""
    qv, bv = vertex_quadrics(vertices, faces) if quadrics is None else quadrics
    key3 = np.floor((vertices - vertices.min(axis=0)) / h).astype(np.int64)
    dims = key3.max(axis=0) + 1
    key = (key3[:, 0] * dims[1] + key3[:, 1]) * dims[2] + key3[:, 2]
    _, inv, counts = np.unique(key, return_inverse=True, return_counts=True)
    k = len(counts)
    mean = np.column_stack([np.bincount(inv, weights=vertices[:, c], minlength=k)
                            for c in range(3)]) / counts[:, None]
    qc = np.column_stack([np.bincount(inv, weights=qv[:, c], minlength=k)
                          for c in range(9)]).reshape(-1, 3, 3)
    bc = np.column_stack([np.bincount(inv, weights=bv[:, c], minlength=k) for c in range(3)])
    u, sv, vt = np.linalg.svd(qc)
    sinv = np.where(sv > 1e-3 * sv[:, :1], 1.0 / np.where(sv > 0, sv, 1.0), 0.0)
    resid = bc - np.einsum("kij,kj->ki", qc, mean)
    # x = mean + V S^+ U^T (b - Q mean)  (Q = U S V^T)
    nv = mean + np.einsum("kji,kj->ki", vt, sinv * np.einsum("kji,kj->ki", u, resid))
    # a vertex may not leave its cell's neighbourhood (ill-conditioned quadrics)
    far = np.linalg.norm(nv - mean, axis=1) > h
    nv[far] = mean[far]
    f = inv[faces]
    f = f[(f[:, 0] != f[:, 1]) & (f[:, 1] != f[:, 2]) & (f[:, 0] != f[:, 2])]
    # coincident faces: same vertex set; equal winding -> keep one, opposite -> drop both
    srt = np.sort(f, axis=1)
    _, first, ids = np.unique(srt, axis=0, return_index=True, return_inverse=True)
    ids = ids.reshape(-1)
    rot = np.argmin(f, axis=1)                       # winding: rotate the smallest index first
    canon = np.take_along_axis(f, (rot[:, None] + np.arange(3)) % 3, axis=1)
    sign = np.where(canon[:, 1] == srt[:, 1], 1, -1)
    net = np.bincount(ids, weights=sign)
    keep = np.zeros(len(f), bool)
    keep[first] = net[ids[first]] != 0
    f = f[keep]
    flip = net[ids[keep]] * sign[keep] < 0
    f[flip] = f[flip][:, ::-1]
    used = np.unique(f)
    remap = np.full(len(nv), -1, np.int64)
    remap[used] = np.arange(len(used))
    return nv[used], remap[f]


def coarsen(vertices, faces, panels: int, quadrics=None):
    r"""At most about ``panels`` triangles of a finer closed mesh by quadric vertex clustering
    (:func:`_cluster`) on cells of :math:`0.75 h`, :math:`h = \sqrt{4A/(\sqrt3 N)}` the side of
    N equilateral triangles covering the area A [m^2]; the cell is corrected twice on the
    count reached (faces ~ cell^-2).  ``quadrics``: :func:`vertex_quadrics` of the mesh
    (computed if omitted).  Returns (vertices, faces)."""
    if quadrics is None:
        quadrics = vertex_quadrics(vertices, faces)
    h = CLUSTER_CELL * np.sqrt(4.0 * surface_area(vertices, faces) / (np.sqrt(3.0) * panels))
    best = None
    for _ in range(4):
        cv, cf = _cluster(vertices, faces, h, quadrics)
        if len(cf) <= 1.1 * panels and (best is None or len(cf) > len(best[1])):
            best = (cv, cf)
        ratio = len(cf) / panels
        if 0.8 < ratio <= 1.1:
            break
        h *= np.sqrt(ratio) * (1.02 if ratio > 1 else 0.98)
    return best if best is not None else (cv, cf)


def ladder_levels(vertices, faces, panels: int, limit: int):
    """The four levels (coarse to fine, (vertices, faces) each) of a closed mesh of at most
    ``panels`` / 4 faces: the input bisected to N_1 = max(N/4, 2F) and 2 N_1 panels, each
    split in four at the edge midpoints (:func:`stripcoef.hull.bisection.split_in_four`), or
    ``None`` when the input is larger or the finest level would exceed ``limit`` panels or the
    bisection cannot reach a second pair (the caller's two levels then)."""
    v, f = np.asarray(vertices, float), np.asarray(faces, np.int64)
    if 4 * len(f) > panels:
        return None
    n1 = max(panels // 4, 2 * len(f))
    b1, b2 = refine(v, f, n1), refine(v, f, 2 * n1)
    # (the bisection to a count moves in steps: a uniform input may not reach 2 N_1 and
    # then returns N_1 again; the second pair is kept where it has at least
    # LEAST_FACE_RATIO times the first's panels, the remeshed families' least step)
    if 4 * len(b2[1]) > limit or len(b2[1]) < LEAST_FACE_RATIO * len(b1[1]):
        return None
    return [b1, b2, split_in_four(*b1), split_in_four(*b2)]

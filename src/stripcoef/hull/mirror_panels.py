r"""The panel method on half, a quarter or an eighth of a body with mirror planes: images.

A body that a reflection :math:`g` (through the plane of one coordinate about the reference
point, :mod:`stripcoef.assembly.symmetry`) maps onto itself has, for each mode j of the
radiation problem of :mod:`stripcoef.hull.panels`, a potential of definite parity: the
generalised normal :math:`n_j` keeps or changes its sign under g (:math:`P_j(g) = \pm1`,
:data:`PARITY`), and so does :math:`\phi_j`,
:math:`\phi_j(g x) = P_j(g)\,\phi_j(x)`.  With the group G of the k planes' reflections
(:math:`|G| = 2^k`) the panels are those of one :math:`1/|G|` of the surface and their images
(the panel method remeshes the closed part, :func:`capped_part`, and drops its caps,
:func:`drop_caps`; :func:`mirror_half` cuts a given panelling instead), and the integral
equation collocated on that part alone reads, for each class :math:`\sigma` of modes (one parity per plane; Newman 1977, "Marine Hydrodynamics",
sec. 4.15; the planes of symmetry of Hess & Smith 1967, "Calculation of potential flow about
arbitrary bodies", Prog. Aero. Sci. 8, whose method takes the images of the panels in them so
that only the part of the body on one side is panelled),

.. math::
    \Big(\tfrac12 I - \sum_{g\in G}\chi_\sigma(g)\,D_g\Big)\Phi_\sigma
        = -\Big(\sum_{g\in G}\chi_\sigma(g)\,S_g\Big) N_\sigma,\qquad
    S_g[k, l] = S(g x_k, T_l),\ D_g[k, l] = D(g x_k, T_l)

(:math:`\chi_\sigma(g)` the product of the parities of the planes in g; the influence of the
image panel :math:`gT_l`, its normal reflected, at :math:`x_k` equals that of :math:`T_l` at
:math:`g x_k` since g is an orthogonal involution), and

.. math:: A_{ij} = -\rho\,|G|\sum_{k} a_k\, n_i(x_k)\,\Phi_{kj}

for i, j of one class, exactly zero otherwise (the couplings the planes forbid).  For one
plane, two solves of N/2 unknowns instead of one of N (a quarter of the LU work, half the
influence matrix); for two, four of N/4.  Each pair (collocation point, panel) gets the same
quadrature rule as in the full panelling (the same distances), so that the result equals the
full solve on the mirrored panelling (:func:`mirror_full`) to round-off
(tests/test_mirror_panels.py).
"""

from __future__ import annotations

import itertools

import numpy as np

from stripcoef.hull.panel_kernels import (DENSE_MID_FRACTION, MID_FACTOR, NEAR_FACTOR,
                                          _frames, generalised_normals, influence_at,
                                          squared_distances)

#: Parity of (u, v, w, p, q, r), and of the generalised normals and potentials of the six
#: modes, under the reflection that reverses each coordinate through the reference point:
#: velocities are vectors, angular velocities pseudovectors (the table and its derivation:
#: :mod:`stripcoef.assembly.symmetry`; Newman 1977, sec. 4.15) [-].
PARITY = {"y": np.array([1, -1, 1, -1, 1, -1]),
          "z": np.array([1, 1, -1, -1, -1, 1]),
          "x": np.array([-1, 1, 1, 1, -1, -1])}

#: The coordinate each reflection reverses.
AXIS = {"x": 0, "y": 1, "z": 2}
#: Vertices closer to a plane than this fraction of the panelling's median edge are moved onto
#: it before the surface is cut there [-]: the cut then splits no triangle into a sliver
#: narrower than about a quarter of an edge (a choice of panel shape, not of accuracy: on a
#: symmetric surface the normal at the plane lies in the plane, so the move is along the
#: surface to first order).
SNAP_FRACTION = 0.25


def _parity(planes):
    return np.array([PARITY[p] for p in planes]).reshape(len(planes), 6)


def _signs(planes, element):
    """(3,) coordinate signs of the reflection through the planes of ``element`` (a tuple of
    bools, one per plane)."""
    s = np.ones(3)
    for p, on in zip(planes, element):
        if on:
            s[AXIS[p]] = -1.0
    return s


def _compact(v, f):
    """(vertices, faces) with only the vertices the faces use, renumbered."""
    used = np.unique(f)
    remap = np.full(len(v), -1, np.int64)
    remap[used] = np.arange(len(used))
    return v[used], remap[f]


def mirror_half(vertices, faces, planes, about=(0.0, 0.0, 0.0)):
    r"""The part of a closed panelling on the positive side of each of ``planes`` (``x``,
    ``y``, ``z``: the coordinate planes through ``about`` [m]), cut there (triangles across a
    plane split, trimesh.intersections.slice_faces_plane; vertices within
    :data:`SNAP_FRACTION` of the median edge moved onto the plane first, those on it exactly
    on it).  Returns (vertices [m], faces) of the open part, winding kept, or ``None`` when
    nothing is left."""
    from trimesh.intersections import slice_faces_plane

    v = np.array(vertices, float)
    f = np.asarray(faces, np.int64)
    p0 = np.asarray(about, float)
    t = v[f]
    edge = float(np.median(np.linalg.norm(t[:, [1, 2, 0]] - t, axis=2)))
    scale = float(np.ptp(v, axis=0).max())
    for p in planes:
        a = AXIS[p]
        d = v[:, a] - p0[a]
        v[np.abs(d) < SNAP_FRACTION * edge, a] = p0[a]
        normal = np.zeros(3)
        normal[a] = 1.0
        v, f = slice_faces_plane(v, f, plane_normal=normal, plane_origin=p0)[:2]
        if len(f) == 0:
            return None
        v = np.array(v, float)
        v[np.abs(v[:, a] - p0[a]) < 1e-9 * scale, a] = p0[a]
        on = v[f, a] == p0[a]
        f = f[~on.all(axis=1)]              # faces lying in the plane: inside the whole body
    tri = v[f]
    dbl = np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
    f = f[dbl > 1e-12 * scale ** 2]
    if len(f) == 0:
        return None
    return _compact(v, f)


def mirror_full(vertices, faces, planes, about=(0.0, 0.0, 0.0)):
    """The whole panelling of a part (:func:`mirror_half`) and its images through ``planes``
    (each image's winding reversed, so that its normals stay outward).  Returns (vertices
    [m], faces); the vertices on a plane are repeated (the panels are what counts)."""
    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int64)
    p0 = np.asarray(about, float)
    vs, fs = [], []
    for element in itertools.product((False, True), repeat=len(planes)):
        s = _signs(planes, element)
        fs.append((f if sum(element) % 2 == 0 else f[:, ::-1]) + len(vs) * len(v))
        vs.append(p0 + s * (v - p0))
    return np.vstack(vs), np.vstack(fs)


def solve_mirrored(tri, planes, *, rho: float, about=(0.0, 0.0, 0.0),
                   near_factor: float = NEAR_FACTOR) -> np.ndarray:
    r"""6x6 added mass [kg, kg m, kg m^2] of the body that ``tri`` (n, 3, 3) [m], a part cut by
    :func:`mirror_half`, and its images through ``planes`` about ``about`` [m] make (module
    docstring: one LU per class of modes; no extrapolation, not symmetrised; the couplings
    the planes forbid exactly zero).  ``rho`` [kg/m^3]."""
    import scipy.linalg

    planes = tuple(planes)
    tri = np.asarray(tri, float)
    c, n, area, diam = _frames(tri)
    p0 = np.asarray(about, float)
    elements = list(itertools.product((False, True), repeat=len(planes)))
    points = [p0 + _signs(planes, e) * (c - p0) for e in elements]
    # the dense three-point switch of the full panelling: its mid-zone (not near) pairs are
    # |G| times those of the blocks here, over (|G| n)^2 pairs
    mid = 0
    for e, x in zip(elements, points):
        r2 = squared_distances(x, c)
        if not any(e):
            np.fill_diagonal(r2, 0.0)
        k, l = np.nonzero(r2 < ((MID_FACTOR * diam) ** 2)[None, :])
        d2 = np.einsum("ij,ij->i", x[k] - c[l], x[k] - c[l])
        near = d2 < (near_factor * diam[l]) ** 2
        if not any(e):
            near |= k == l
        mid += int(np.count_nonzero(~near))
    dense = len(elements) * mid > DENSE_MID_FRACTION * (len(elements) * len(c)) ** 2
    blocks = [influence_at(x, tri, self_block=not any(e), dense=dense, near_factor=near_factor)
              for e, x in zip(elements, points)]
    nrm = generalised_normals(c, n, about)
    parity = _parity(planes)                       # (planes, 6)
    out = np.zeros((6, 6))
    for sigma in itertools.product((1, -1), repeat=len(planes)):
        modes = np.nonzero(np.all(parity == np.array(sigma)[:, None], axis=0))[0]
        if not len(modes):
            continue
        chi = [float(np.prod([sg for sg, on in zip(sigma, e) if on])) for e in elements]
        s = sum(ch * b[0] for ch, b in zip(chi, blocks))
        lhs = -sum(ch * b[1] for ch, b in zip(chi, blocks))
        lhs[np.diag_indices_from(lhs)] += 0.5
        phi = scipy.linalg.solve(lhs, -(s @ nrm[:, modes]), overwrite_a=True,
                                 check_finite=False)
        out[np.ix_(modes, modes)] = -rho * len(elements) * (nrm[:, modes]
                                                            * area[:, None]).T @ phi
    return out


def capped_part(vertices, faces, planes, about=(0.0, 0.0, 0.0)):
    """The closed body on the positive side of each of ``planes`` through ``about`` [m]: the
    surface cut there and each cut closed by a flat cap in the plane (manifold3d's
    ``Manifold.trim_by_plane``, exact and manifold, the library of the package's unions:
    :func:`stripcoef.geometry.mesh_close.manifold_boolean`), to be remeshed as a whole (the
    cap's rim a crease, so that the remesher keeps vertices on the plane) and its caps dropped
    by :func:`drop_caps`.  Returns (vertices [m], faces) or ``None`` when the cut fails."""
    import manifold3d

    p0 = np.asarray(about, float)
    try:
        body = manifold3d.Manifold(manifold3d.Mesh64(
            vert_properties=np.ascontiguousarray(vertices, dtype=np.float64),
            tri_verts=np.ascontiguousarray(faces, dtype=np.uint64)))
        for p in planes:
            normal = np.zeros(3)
            normal[AXIS[p]] = 1.0
            body = body.trim_by_plane(normal, float(p0[AXIS[p]]))
        out = body.to_mesh64()
    except Exception:          # manifold3d refuses the input: no part, the full solve
        return None
    v = np.asarray(out.vert_properties, float)[:, :3]
    f = np.asarray(out.tri_verts, np.int64)
    if len(f) < 4:
        return None
    from stripcoef.geometry.mesh import EdgeTopology

    return (v, f) if EdgeTopology(f).consistent else None


def drop_caps(vertices, faces, planes, about=(0.0, 0.0, 0.0)):
    """The remeshed :func:`capped_part` without its caps: the faces whose three vertices lie in
    one of ``planes`` (within 1e-9 of the body's size; those vertices put exactly on it).
    Returns (vertices [m], faces) of the open part, or ``None`` when nothing is left."""
    v = np.array(vertices, float)
    f = np.asarray(faces, np.int64)
    p0 = np.asarray(about, float)
    scale = float(np.ptp(v, axis=0).max())
    cap = np.zeros(len(f), bool)
    for p in planes:
        a = AXIS[p]
        on = np.abs(v[:, a] - p0[a]) <= 1e-9 * scale
        v[on, a] = p0[a]
        cap |= on[f].all(axis=1)
    f = f[~cap]
    if len(f) == 0:
        return None
    return _compact(v, f)

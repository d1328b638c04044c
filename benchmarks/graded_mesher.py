"""A graded reference mesher for an arbitrary closed triangle mesh (issue 32): gmsh remeshes
the body's surface with triangles graded towards its sharp edges, for Capytaine references of
shapes that are no union of prisms (frames of tubes along three axes, the VideoRay-like body,
public vehicle meshes).

Independent of the library's own panel code (:mod:`stripcoef.hull`): the input's sharp edges
(dihedral beyond ``angle``, 30 deg as :mod:`benchmarks.graded_unions`) are found here from
the triangles, gmsh (Geuzaine & Remacle 2009) classifies the triangulation into patches
bounded by those edges (``gmsh.model.mesh.classifySurfaces``, its discrete surfaces
reparametrised: gmsh tutorial t13) and meshes each patch again (Frontal-Delaunay) at the size

    h(d) = clip(H sqrt(2 d / L), h_0, H),   h_0 = H^2 / (2 L)               [m]

at a distance d [m] from the nearest sharp edge: the growth of the cosine spacing
x_k = L (1 - cos(pi k / 2m)) used by the structured references (:mod:`benchmarks.plate_graded`;
there h = (pi / 2m) sqrt(2 L d) near the edge, so the panel at the edge is the square of the
uniform one, H^2 / 2L), made isotropic.  ``L`` [m] is the grading length, fixed over a body's
levels, ``H`` the level's largest panel.  At a convex edge the flow is singular (Newman 1977
sec. 4.4) and uniform panels converge at a lower order (4/3 in h at a right angle: von
Petersdorff & Stephan 1990); grading the panels this way restores a faster convergence, which
the references measure rather than assume (Eça & Hoekstra 2014 over four or five levels:
:func:`validation.graded_bodies.references`).

The new nodes lie on the input's triangles (gmsh's discrete surfaces), the sharp edges are kept
as patch boundaries; a smooth crease below ``angle`` (a faceted cylinder's facet joints) is cut
by panels larger than a facet, a geometric error that vanishes as h^2 with the levels.

With ``mirror=True`` only the y >= 0 half is meshed (the input cut on y = 0 without a cap, its
cut a patch boundary not graded towards) and Capytaine solves it on its xOz mirror plane
(Ancellin & Dias 2019).
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import tempfile  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

#: dihedral [deg] beyond which an edge is sharp (graded towards): as benchmarks.graded_unions
ANGLE = 30.0


#: the panel at a sharp edge is H / RATIO
RATIO = 4.0
#: growth of the panel size with the distance from the nearest sharp edge, dh/dd [-]
GROWTH = 0.25
#: dihedral [deg] beyond which two input faces lie in different patches: every facet plane of
#: a faceted body its own patch, so that the remeshed body is the input's exactly
PATCH_ANGLE = 30.0


def sharp_edges(mesh, angle: float = ANGLE, convex_only: bool = True) -> np.ndarray:
    """(k, 2, 3) [m] end points of the edges of a closed triangle mesh whose dihedral (the angle
    between the two faces' normals) exceeds ``angle`` [deg]; ``convex_only``: the convex ones
    alone (the body's edges where the flow is singular, Newman 1977 sec. 4.4; at a concave
    edge, where two parts meet, the velocity vanishes)."""
    ang = np.asarray(mesh.face_adjacency_angles, float)
    keep = ang > np.radians(angle)
    if convex_only:
        keep &= np.asarray(mesh.face_adjacency_convex, bool)
    e = np.asarray(mesh.face_adjacency_edges)[keep]
    return np.asarray(mesh.vertices, float)[e]


def edge_points(edges: np.ndarray, spacing: float) -> np.ndarray:
    """Points [m] along the segments ``edges`` (k, 2, 3) at most ``spacing`` [m] apart."""
    pts = [np.zeros((0, 3))]
    for a, b in edges:
        n = max(1, int(np.ceil(np.linalg.norm(b - a) / spacing)))
        t = np.linspace(0.0, 1.0, n + 1)[:, None]
        pts.append(a + t * (b - a))
    return np.unique(np.round(np.vstack(pts), 12), axis=0)


def size_function(H: float, ratio: float = None, growth: float = None):
    """h(d) [m] of the module's grading, h = min(H, H / ratio + growth d), and its least value
    H / ratio [m]."""
    ratio = RATIO if ratio is None else ratio
    growth = GROWTH if growth is None else growth
    h0 = H / ratio

    def h(d):
        return np.minimum(H, h0 + growth * np.maximum(d, 0.0))
    return h, h0


def half_mesh(mesh, axes=(1,)):
    """The part of a closed trimesh on the positive side of the coordinate planes ``axes``
    (0: x = 0, 1: y = 0, 2: z = 0; default the y >= 0 half), open along the cuts (no cap)."""
    import trimesh

    for axis in axes:
        mesh = trimesh.intersections.slice_mesh_plane(mesh, plane_normal=np.eye(3)[axis],
                                                      plane_origin=[0.0, 0.0, 0.0], cap=False)
    return mesh


def graded_mesh(mesh, H: float, angle: float = ANGLE, mirror: bool = False,
                convex_only: bool = True, patch_angle: float = PATCH_ANGLE,
                verbose: bool = False, curvature: float = None, planes=None,
                curve_angle: float = 180.0):
    """(vertices (n, 3) [m], triangles (k, 3)) of ``mesh`` (a closed trimesh) remeshed by gmsh
    with panels graded towards its sharp edges (module docstring; ``H`` the largest panel
    [m], ``L`` the grading length [m]); with ``mirror`` its y >= 0 half only (the body must
    be mirror-symmetric in y = 0), the cut's nodes on y = 0 exactly.  Normals as the input's
    (outward).  ``curvature`` (a length R_c [m], off by default): where the surface is curved
    with a radius R [m] the panel is also at most H R / R_c (gmsh's size from curvature,
    ``Mesh.MeshSizeFromCurvature``, 2 pi R_c / H panels per 2 pi radians), so that a tube
    thinner than R_c gets panels in proportion to its radius at every level (the levels stay
    one family scaled by H).  ``planes``: the coordinate axes (0, 1, 2) of the mirror planes
    whose positive side alone is meshed (``mirror`` is ``planes=(1,)``; (0, 1, 2) the eighth
    x, y, z >= 0 of a body symmetric in all three), each cut's nodes on its plane exactly.
    ``curve_angle`` [deg]: the patch boundaries are split into curves where they turn by more
    (gmsh's ``classifySurfaces`` curveAngle; 180 keeps them whole, whose remesh may cut a
    corner of the polyline; a polyhedron's corners are kept with a small angle)."""
    import gmsh
    from scipy.spatial import cKDTree

    h, h0 = size_function(H)
    edges = sharp_edges(mesh, angle, convex_only)
    tree = cKDTree(edge_points(edges, 0.25 * h0)) if len(edges) else None
    planes = tuple(planes) if planes is not None else ((1,) if mirror else ())
    surf = half_mesh(mesh, planes) if planes else mesh
    with tempfile.TemporaryDirectory() as tmp:
        stl = str(Path(tmp) / "body.stl")
        surf.export(stl)
        gmsh.initialize(["-noenv"], readConfigFiles=False)
        try:
            gmsh.option.setNumber("General.Terminal", 1 if verbose else 0)
            gmsh.option.setNumber("General.NumThreads", 1)
            gmsh.merge(stl)
            gmsh.model.mesh.classifySurfaces(np.radians(patch_angle), True, True,
                                              np.radians(curve_angle))
            gmsh.model.mesh.createGeometry()
            gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
            gmsh.option.setNumber("Mesh.MeshSizeFromCurvature",
                                  0 if curvature is None else
                                  max(1, int(round(2.0 * np.pi * curvature / H))))
            gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
            gmsh.option.setNumber("Mesh.MeshSizeMin", h0)
            gmsh.option.setNumber("Mesh.MeshSizeMax", H)
            gmsh.option.setNumber("Mesh.Algorithm", 6)

            def size(dim, tag, x, y, z, lc):
                cap = H if curvature is None else min(H, lc)
                if tree is None:
                    return cap
                return float(min(cap, h(tree.query((x, y, z))[0])))

            gmsh.model.mesh.setSizeCallback(size)
            gmsh.model.mesh.generate(2)
            tags, coords, _ = gmsh.model.mesh.getNodes()
            v = np.asarray(coords, float).reshape(-1, 3)
            index = np.zeros(int(np.max(tags)) + 1, int)
            index[np.asarray(tags, int)] = np.arange(len(tags))
            tri = []
            for _, stag in gmsh.model.getEntities(2):
                types, _, nodes = gmsh.model.mesh.getElements(2, stag)
                for t, n in zip(types, nodes):
                    if t != 2:
                        raise RuntimeError(f"gmsh element type {t} on surface {stag}: "
                                           "expected 3-node triangles")
                    tri.append(index[np.asarray(n, int)].reshape(-1, 3))
            v = v.copy()
        finally:
            gmsh.finalize()
    tri = [_orient_like(v, t, surf) for t in tri]
    f = np.vstack(tri)
    # nodes that gmsh duplicated (a patch corner shared by curves) merged, the triangles that
    # then repeat a node (zero area) dropped
    tol = 1e-9 * float(np.ptp(v))
    _, first, inv = np.unique(np.round(v / tol), axis=0, return_index=True,
                              return_inverse=True)
    f = first[inv.reshape(-1)][f]
    f = f[(f[:, 0] != f[:, 1]) & (f[:, 1] != f[:, 2]) & (f[:, 0] != f[:, 2])]
    used = np.unique(f)
    remap = np.full(len(v), -1)
    remap[used] = np.arange(len(used))
    v, f = v[used], remap[f]
    f = _consistent(v, f, surf)
    for axis in planes:
        on = np.abs(v[:, axis]) < 1e-9 * max(1.0, float(np.ptp(v)))
        v[on, axis] = 0.0
    return v, f



def _consistent(v, f, mesh):
    """The triangles' winding made consistent across the conforming remesh (trimesh's
    ``fix_winding``: a patch whose vote in :func:`_orient_like` went wrong, RexROV's, turned
    like its neighbours), then all turned if most of the area disagrees with the input's
    normals (outward)."""
    import trimesh

    m = trimesh.Trimesh(v, f, process=False)
    trimesh.repair.fix_winding(m)
    return _orient_like(v, np.asarray(m.faces), mesh)


def _orient_like(v, f, mesh):
    """The triangles of one gmsh patch ``f``, all turned if most of them disagree (area
    weighted) with the normal of the input face whose centroid is nearest (outward)."""
    from scipy.spatial import cKDTree

    c = v[f].mean(axis=1)
    n = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    _, k = cKDTree(np.asarray(mesh.triangles_center)).query(c)
    vote = np.einsum("ij,ij->i", n, np.asarray(mesh.face_normals)[k])
    return f[:, ::-1].copy() if vote.sum() < 0 else f


#: the largest relative volume change a level may make (the facet joints cut: videoray_like
#: -1.4 % at its coarsest level); beyond it the remesh is refused
MAX_VOLUME_CHANGE = 0.05


def accepted(c: dict, what: str) -> dict:
    """``c`` of :func:`check`, or a one-line error when the remesh is not the body (its volume
    off by more than :data:`MAX_VOLUME_CHANGE`: RexROV's surface comes back from gmsh as its
    own triangles with patches turned inwards, volume -140 %)."""
    if not c["consistent"]:
        raise RuntimeError(f"{what}: the remesh's triangles are not consistently wound: "
                           "not used")
    if not abs(c["volume"]) <= MAX_VOLUME_CHANGE:
        raise RuntimeError(f"{what}: the remesh's volume differs by {100 * c['volume']:+.1f} % "
                           f"from the body's (at most {100 * MAX_VOLUME_CHANGE:g} %): not used")
    return c


def whole(v, f, mirror: bool):
    """The closed body's (vertices, triangles) of a half (mirrored in y, faces reversed)."""
    if not mirror:
        return v, f
    w = v * np.array([1.0, -1.0, 1.0])
    return np.vstack([v, w]), np.vstack([f, f[:, ::-1] + len(v)])


def check(v, f, mesh, mirror: bool) -> dict:
    """Area [m^2] and volume [m^3] of the remeshed body (mirrored where ``mirror``) against the
    input's, relative differences; the least triangle quality 4 sqrt(3) A / (a^2 + b^2 + c^2)."""
    wv, wf = whole(v, f, mirror)
    p = wv[wf]
    cr = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    area = 0.5 * np.linalg.norm(cr, axis=1)
    vol = np.einsum("ij,ij->i", p[:, 0], np.cross(p[:, 1], p[:, 2])).sum() / 6.0
    sq = sum(np.sum((p[:, (k + 1) % 3] - p[:, k]) ** 2, axis=1) for k in range(3))
    q = 4.0 * np.sqrt(3.0) * area / sq
    import trimesh

    closed = trimesh.Trimesh(wv, wf, process=True)
    return {"faces": len(wf), "area": float(area.sum() / mesh.area - 1.0),
            "volume": float(vol / mesh.volume - 1.0), "quality": float(q.min()),
            "consistent": bool(closed.is_winding_consistent)}


def predicted_gb(faces: int) -> float:
    """Memory [GB] of Capytaine's half solve (one mirror plane) of ``faces`` faces (whole
    body): S and K N x N/2 complex128 and K's two diagonal blocks N/2 x N/2, 24 N^2 bytes
    (22.8 measured at 18,210 faces: :mod:`benchmarks.frame_references`), and 0.5 GB for the
    interpreter and the mesher."""
    return 24.0 * faces ** 2 / 1e9 + 0.5


def peak_gb() -> float:
    """Peak resident memory of this process so far [GB] (Linux: ru_maxrss in kB)."""
    import resource

    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e6


RHO = 1000.0
#: the bluff set's shapes that are no union of prisms along x, mirror-symmetric in y = 0
#: (benchmarks.bluff_shapes.SHAPES): the frames and the VideoRay-like body
SHAPES = ("videoray_like", "open_frame", "bluerov2_heavy")
#: largest panel H [m] of each level, coarse to fine (whole body at most about 13,000 faces)
LEVELS = {"videoray_like": (0.045, 0.032, 0.0226, 0.016, 0.0135),
          "open_frame": (0.064, 0.045, 0.032, 0.024),
          "bluerov2_heavy": (0.064, 0.045, 0.032, 0.024)}
HEADER = ["shape", "what", "level", "m", "faces", "i", "j", "added_mass", "seconds"]
DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")


def capytaine_mirror(v, f):
    """6x6 added mass [kg, kg m, kg m^2] about the origin, rho = :data:`RHO`, of the closed
    body whose y >= 0 half is the triangles (v, f) (outward normals): Capytaine (direct
    method, no free surface) on ``cpt.ReflectionSymmetricMesh`` (plane xOz); (matrix, faces
    of the whole body, wall time [s])."""
    import logging
    import time

    import capytaine as cpt

    from benchmarks.plate_graded import solve_added_mass

    logging.getLogger("capytaine").setLevel(logging.ERROR)
    t0 = time.perf_counter()
    quads = np.column_stack([f, f[:, 2]])
    mesh = cpt.ReflectionSymmetricMesh(half=cpt.Mesh(vertices=v, faces=quads), plane="xOz")
    return solve_added_mass(mesh), 2 * len(f), time.perf_counter() - t0


def shape_body(name):
    """The bluff set's shape ``name`` about its volume centroid (the stored references'
    point), as :func:`benchmarks.bluff_shapes.shape_mesh` takes it without refining."""
    from benchmarks.bluff_shapes import SHAPES as BLUFF

    m = BLUFF[name][0](None)
    m.apply_translation(-np.asarray(m.center_mass, float))
    if abs(m.center_mass[1]) > 1e-9 * float(np.max(m.extents)):
        raise ValueError(f"{name}: volume centroid y = {m.center_mass[1]:.3g} m: expected a "
                         "body mirror-symmetric in y = 0")
    return m


def run(path, names, levels=None, curvature=None, max_gb=None, first_level=0):
    """Every level of each shape of ``names``: Capytaine on the graded half, rows of
    :data:`HEADER` appended to ``path`` as they come (``m`` holds H [m]).  ``curvature``:
    :func:`graded_mesh`'s (the ``what`` column says it); ``max_gb``: a level whose half solve
    is predicted over it (:func:`predicted_gb`) is said and not
    solved; ``first_level``: the first level's index (a finer level appended to a shape's
    rows)."""
    import csv
    import sys
    import time

    import capytaine

    new = not Path(path).exists()
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    with open(path, "a", newline="") as fh:
        if new:
            fh.write(f"# python -m benchmarks.graded_mesher {' '.join(sys.argv[1:])}: "
                     f"Capytaine {capytaine.__version__} (direct method, no free surface, "
                     f"rho = 1000 kg/m^3), gmsh triangles graded towards the convex edges "
                     f"sharper than {ANGLE:g} deg (h = min(H, H / {RATIO:g} + {GROWTH:g} d); "
                     "benchmarks.graded_mesher), the y >= 0 half solved on the xOz mirror "
                     "plane; m = H [m]; upper-triangle 6x6 added mass [kg, kg m, kg m^2] about "
                     "the volume centroid\n")
            csv.writer(fh).writerow(HEADER)
        w = csv.writer(fh)
        for name in names:
            body = shape_body(name)
            for lev, H in enumerate(levels or LEVELS[name], start=first_level):
                v, f = graded_mesh(body, H, mirror=True, curvature=curvature)
                c = accepted(check(v, f, body, True), f"{name} at H = {H:g} m")
                if max_gb is not None:
                    if predicted_gb(2 * len(f)) > max_gb:
                        print(f"{name}: H {H:g} m, {2 * len(f)} faces: predicted "
                              f"{predicted_gb(2 * len(f)):.1f} GB > {max_gb:g} GB, not solved",
                              flush=True)
                        continue
                cpu = time.process_time()
                a, n, sec = capytaine_mirror(v, f)
                cpu = time.process_time() - cpu
                if max_gb is not None:
                    print(f"{name}: H {H:g} m: solve {cpu:.1f} s CPU, peak {peak_gb():.2f} GB",
                          flush=True)
                print(f"{name}: H {H:g} m, {n} faces (area {c['area']:+.1e}, volume "
                      f"{c['volume']:+.1e}, least quality {c['quality']:.3f}), {sec:.1f} s: "
                      + " ".join(f"{x:.6g}" for x in np.diag(a)), flush=True)
                what = f"{name} remeshed by gmsh, mirror xOz" + (
                    "" if curvature is None else f", curvature length {curvature:g} m")
                w.writerows([name, what, lev, f"{H:g}", n,
                             i, j, f"{a[i, j]:.9g}", f"{sec:.2f}"]
                            for i in range(6) for j in range(i, 6))
                fh.flush()



#: public meshes (benchmarks.public_meshes.MESHES) with graded references: the ROVs, whose
#: creases the uniform references' order-2 extrapolation treats as smooth
PUBLIC = ("smilodon", "erov", "rexrov", "caldus", "caracara", "desistek_saga")
#: face counts aimed at by a public mesh's levels (whole body, no mirror plane)
PUBLIC_FACES = (1500, 2500, 4000, 6500)
#: N ~ H^-PUBLIC_EXPONENT between levels (measured on videoray_like: 1.33, edge-dominated)
PUBLIC_EXPONENT = 1.4


def public_surface(mirror, name):
    """The closed surface the panel method solves of a public mesh (loaded, repaired and
    united as :func:`benchmarks.public_meshes.bem_reference` takes it), in its body axes about
    the body origin, as a trimesh."""
    import trimesh

    from benchmarks.public_meshes import MESHES, read_from_mirror
    from stripcoef.geometry.vehicle import load_vehicle

    mesh = next(m for m in MESHES if m.name == name)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / f"{name}{Path(mesh.path).suffix}"
        path.write_bytes(read_from_mirror(Path(mirror), mesh))
        body = load_vehicle(path).bodies[0]
        surface = body.united() if hasattr(body, "united") else body.mesh
    return trimesh.Trimesh(np.asarray(surface.vertices, float), np.asarray(surface.faces),
                           process=True)


def public_levels(body, faces=PUBLIC_FACES):
    """[(H [m], (v, f))] of the levels of a public mesh's surface aimed at ``faces``: one trial
    at the uniform size of the middle count, then H = H_0 (N_0 / N)^(1 / PUBLIC_EXPONENT)."""
    mid = faces[len(faces) // 2]
    h_try = float(np.sqrt(body.area / (0.433 * mid)))
    n_try = len(graded_mesh(body, h_try)[1])
    out = []
    for n in faces:
        H = h_try * (n_try / n) ** (1.0 / PUBLIC_EXPONENT)
        out.append((H, graded_mesh(body, H)))
    return out



def centred_box(body):
    """(x, y, z) extents [m] of a body that is an axis-aligned box centred on the origin (eight
    vertices, its volume that of its bounds), else None."""
    v = np.asarray(body.vertices, float)
    ext = np.ptp(v, axis=0)
    if (len(np.unique(np.round(v, 9), axis=0)) != 8
            or abs(body.volume / np.prod(ext) - 1.0) > 1e-6
            or np.max(np.abs(v.max(axis=0) + v.min(axis=0))) > 1e-6 * ext.max()):
        return None
    return tuple(float(x) for x in ext)


def _public_box(w, fh, name, extents):
    """A box's levels as the bluff set's boxes are solved (:mod:`benchmarks.graded_references`
    boxes: structured quadrilaterals cosine-graded towards every edge,
    :func:`benchmarks.plate_graded.eighth_box`, the quarter solved on two mirror planes): the
    five finest of its BOX_LEVELS within MAX_FACES, rows as :func:`run_public` (m: the
    panels on the longest horizontal half-edge)."""
    from benchmarks.graded_references import BOX_LEVELS, MAX_FACES, MAX_LEVELS
    from benchmarks.plate_graded import capytaine_eighth, eighth_box

    x, y, z = extents
    fit = [m for m in BOX_LEVELS if 8 * len(eighth_box(x, y, z, m)[1]) <= MAX_FACES]
    what = (f"box {x:.5g} x {y:.5g} x {z:.5g} m, structured quadrilaterals graded towards "
            "every edge (benchmarks.plate_graded.eighth_box)")
    for lev, m in enumerate(fit[-MAX_LEVELS:]):
        a, n, sec = capytaine_eighth(*eighth_box(x, y, z, m))
        print(f"{name}: {what}, m {m}, {n} faces, {sec:.1f} s: "
              + " ".join(f"{q:.6g}" for q in np.diag(a)), flush=True)
        w.writerows([name, what, lev, m, n, i, j, f"{a[i, j]:.9g}", f"{sec:.2f}"]
                    for i in range(6) for j in range(i, 6))
        fh.flush()


def run_public(path, mirror, names, faces=PUBLIC_FACES, boxes=True):
    """Every level of each public mesh of ``names``: Capytaine (the whole body, about the body
    origin), rows of :data:`HEADER` appended to ``path`` (``m`` holds H [m])."""
    import csv
    import logging
    import sys
    import time

    import capytaine
    import capytaine as cpt

    from benchmarks.plate_graded import solve_added_mass

    logging.getLogger("capytaine").setLevel(logging.ERROR)
    new = not Path(path).exists()
    with open(path, "a", newline="") as fh:
        if new:
            fh.write(f"# python -m benchmarks.graded_mesher {' '.join(sys.argv[1:])}: "
                     f"Capytaine {capytaine.__version__} (direct method, no free surface, "
                     f"rho = 1000 kg/m^3), gmsh triangles graded towards the convex edges "
                     f"sharper than {ANGLE:g} deg (h = min(H, H / {RATIO:g} + {GROWTH:g} d); "
                     "benchmarks.graded_mesher), the whole body solved; m = H [m]; "
                     "upper-triangle 6x6 added mass [kg, kg m, kg m^2] about the body origin "
                     "of the loaded mesh\n")
            csv.writer(fh).writerow(HEADER)
        w = csv.writer(fh)
        for name in names:
            body = public_surface(mirror, name)
            box = centred_box(body) if boxes else None
            if box is not None:
                _public_box(w, fh, name, box)
                continue
            for lev, (H, (v, f)) in enumerate(public_levels(body, faces)):
                c = accepted(check(v, f, body, False), f"{name} at H = {H:.4g} m")
                t0 = time.perf_counter()
                mesh = cpt.Mesh(vertices=v, faces=np.column_stack([f, f[:, 2]]))
                a = solve_added_mass(mesh)
                sec = time.perf_counter() - t0
                print(f"{name}: H {H:.4g} m, {len(f)} faces (area {c['area']:+.1e}, volume "
                      f"{c['volume']:+.1e}, least quality {c['quality']:.3f}), {sec:.1f} s: "
                      + " ".join(f"{x:.6g}" for x in np.diag(a)), flush=True)
                w.writerows([name, f"{name} remeshed by gmsh", lev, f"{H:.5g}", len(f),
                             i, j, f"{a[i, j]:.9g}", f"{sec:.2f}"]
                            for i in range(6) for j in range(i, 6))
                fh.flush()



def compare_public(levels_csv, stored_csv):
    """Per mesh of ``levels_csv`` (:func:`run_public`) and term: its graded reference (Eça &
    Hoekstra over the levels, :func:`validation.graded_bodies.references`) moved to each
    stored run's reference point (``stored_csv``: reference_tables/public_meshes/
    public_meshes.csv, its ``ref_x, ref_y, ref_z``), against the stored run's model and
    uniform reference; a diagonal term relative to itself, a coupling to sqrt(A_ii A_jj) (the
    public benchmark's scale, :func:`benchmarks.public_meshes.compare_at`).  Returns rows
    (dicts) and prints them."""
    import csv

    from stripcoef.conventions import transform_matrix
    from validation.graded_bodies import references
    from validation.public_meshes import moved_uncertainty

    with open(stored_csv, newline="") as fh:
        stored = [r for r in csv.DictReader(ln for ln in fh if not ln.startswith("#"))]
    out = []
    for name, (ref, band, order, faces) in references(levels_csv).items():
        runs = {}
        for r in stored:
            if r["mesh"] == name and r["run"] in ("auto", "repaired"):
                runs.setdefault(r["run"], []).append(r)
        for run, rows in runs.items():
            point = np.array([float(rows[0][k]) for k in ("ref_x", "ref_y", "ref_z")])
            ref_p = transform_matrix(ref, from_point=(0, 0, 0), to_point=point)
            band_p = moved_uncertainty(band, point)
            d = np.sqrt(np.abs(np.diag(ref_p)))
            for r in rows:
                i, j = int(r["i"]), int(r["j"])
                if i != j and r["significant"] not in ("1", "True"):
                    continue
                s = d[i] * d[j]
                row = dict(mesh=name, run=run, i=i, j=j, faces="/".join(map(str, faces)),
                           graded=ref_p[i, j], band=band_p[i, j] / s, order=order[i, j],
                           model=(float(r["model"]) - ref_p[i, j]) / s,
                           uniform=(float(r["bem"]) - ref_p[i, j]) / s,
                           model_vs_uniform=float(r["error_rel"]))
                out.append(row)
                print(f"{name} ({run}) [{DOFS[i]}, {DOFS[j]}]: graded {ref_p[i, j]:.6g} (band "
                      f"{100 * row['band']:.2f} %, order {row['order']:.2f}); model "
                      f"{100 * row['model']:+.2f} %, uniform reference "
                      f"{100 * row['uniform']:+.2f} % (model against it "
                      f"{100 * row['model_vs_uniform']:+.2f} %)")
    return out


def main(argv=None) -> int:
    import argparse

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--csv", required=True, help="append the levels here (--compare: read)")
    ap.add_argument("--compare", default=None, metavar="STORED_CSV",
                    help="compare the public meshes' levels of --csv with this stored run "
                    "(reference_tables/public_meshes/public_meshes.csv) and stop")
    ap.add_argument("--public", nargs="+", default=None, choices=PUBLIC,
                    help="these public meshes (benchmarks.public_meshes) instead of the "
                    "bluff shapes; needs --mirror")
    ap.add_argument("--mirror", default=None, help="the public meshes' clones (as "
                    "benchmarks.public_meshes --mirror)")
    ap.add_argument("--faces", type=int, nargs="+", default=list(PUBLIC_FACES),
                    help="face counts a public mesh's levels aim at (default "
                    + " ".join(map(str, PUBLIC_FACES)) + ")")
    ap.add_argument("--gmsh-boxes", action="store_true",
                    help="a public mesh that is a box remeshed by gmsh too (the mesher's check "
                    "against the structured box panels)")
    ap.add_argument("--only", nargs="+", default=list(SHAPES), choices=SHAPES)
    ap.add_argument("--levels", type=float, nargs="+", default=None,
                    help="largest panel H [m] of each level (default: the shape's LEVELS)")
    ap.add_argument("--curvature", type=float, default=None, metavar="R_C",
                    help="panels also at most H R / R_C where the surface has a radius R "
                    "(graded_mesh's curvature; off by default)")
    ap.add_argument("--max-gb", type=float, default=None,
                    help="skip a level whose half solve is predicted over this many GB")
    ap.add_argument("--first-level", type=int, default=0,
                    help="index of the first level written (to append finer levels)")
    args = ap.parse_args(argv)
    if args.compare:
        compare_public(args.csv, args.compare)
        return 0
    if args.public:
        if not args.mirror:
            ap.error("--public needs --mirror")
        run_public(args.csv, args.mirror, args.public, tuple(args.faces),
                   boxes=not args.gmsh_boxes)
        return 0
    run(args.csv, args.only, args.levels, args.curvature, args.max_gb, args.first_level)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

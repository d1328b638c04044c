"""Edge-graded Capytaine references of the CAD benchmark's frames (issue 32, ``frame32i``).

A frame of :mod:`benchmarks.cad_shapes` is two side plates (boxes l x t x h at y = +-w/2, t =
10-30 mm) and two to four cross tubes (16-sided prisms along y, ends flush with the plates'
outer faces, some overlapping).  Its union is exactly: the two plates, and the union P of the
tubes' 16-gons in the xOz plane extruded between the plates' inner faces.  The flow is
singular at the plates' convex edges (interior angle pi/2: velocity ~ r^(-1/3), Newman 1977
sec. 4.4), so uniform panels converge at an order below one there (von Petersdorff & Stephan
1990) and the uniform Capytaine levels of the draws (1,500-12,000 faces) had not entered the
asymptotic range (benchmarks/data/cad32h_trace.md sec. 5).

Here every face is panelled on its own, graded towards the plate edges by the cosine law of
the structured plate references (:mod:`benchmarks.plate_graded`): on an edge of length l with
a largest (mid) panel H, n = ceil(pi l / 2H) panels at x_k = l (1 - cos(pi k / n)) / 2, so
that the panel next to an edge is H^2 / l, the square of the uniform one, and the spacing at
a distance d from the edge h(d) = H sqrt(4 d / l):

- the plate's outer face and its four rims are rectangles: structured quadrilaterals on those
  nodes (across the thickness t the rim's n_t nodes follow the same cosine law, n_t so that
  its panel at each edge is the faces' H^2 / l, and at least six);
- the inner face is the rectangle less P (the tubes' holes): gmsh (Geuzaine & Remacle 2009;
  Frontal-Delaunay on the planar domain, a maintained mesher for a domain with holes that no
  structured grid fits) at the size h(x, z) = min(h_x, h_z), each the cosine law of the
  structured faces' nodes in that direction (clipped to [H^2 / l, H]), so that its size
  across an edge is the rims' and outer face's spacing there;
- the tubes' walls (P's boundary between the inner faces, its edges concave: no singularity)
  are quadrilaterals, each facet cut into panels no wider than H / 2 and H / 2 along y.

Why not one library mesh of the whole surface: an isotropic remesh graded the same way
(:func:`benchmarks.graded_mesher.graded_mesh`, gmsh on the discrete surface; pymeshlab's
isotropic remesher is isotropic too) must make a rim's panels edge-sized along the rim as well
as across it, since the whole rim lies within t/2 of two edges: their number grows as H^-4
(frame 6 of seed 1795971315: 6,004 / 11,060 / 19,292 faces at H = 0.06 / 0.045 / 0.035 m,
about half of them on the rims and edge strips), so that the levels within 8 GB span too little
for Eça & Hoekstra.  Structured cosine panels are fine across an edge and coarse along it
(the plate references' anisotropy); gmsh meshes the one face no grid fits.

The faces meet non-conformingly at the edges, which the collocation method of constant panels
allows (each panel's source strength is unknown on its own; no continuity is assumed:
Hess & Smith 1967).  The nodes lie on the body's faces, so every level is the faceted body
exactly (area and volume against the parts' manifold union, checked at each level).  The body
is mirror-symmetric in y = 0 (the plates and the tubes' full span), so the y >= 0 half is
built and Capytaine (direct method, no free surface, rho 1000 kg/m^3) solves it on its xOz
plane (``cpt.ReflectionSymmetricMesh``, as :mod:`benchmarks.frame_references`).  Each term's
reference is Eça & Hoekstra's least squares over the levels, the draws' estimator
(:func:`validation.cad_shapes.fine_reference`, h ~ N^(-1/2)).

Checks with known answers first (``--check``):

- ``plate``: a thin plate of a stored edge-graded plate reference (cad_plates_graded_SEED.csv,
  structured on three mirror planes by :mod:`benchmarks.plate_graded`), turned so that its
  thickness lies along y, panelled by this module (the face gmsh-graded, the rims structured,
  the y >= 0 half on xOz), against that reference;
- ``ellipsoid``: a triaxial ellipsoid (gmsh's OpenCASCADE sphere scaled; no edge), its y >= 0
  half on xOz, against Lamb's exact added mass (:func:`stripcoef.hull.lamb.
  ellipsoid_added_mass`).

Usage (gmsh from the ``graded`` extra; Capytaine from ``bem``):

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.graded_cad_frames --check plate \\
        --shape 1795971315:1 --levels 0.06 0.045 0.034 0.026
    OPENBLAS_NUM_THREADS=1 python -m benchmarks.graded_cad_frames --check ellipsoid
    OPENBLAS_NUM_THREADS=1 python -m benchmarks.graded_cad_frames --faces --seed S --only K
    OPENBLAS_NUM_THREADS=1 python -m benchmarks.graded_cad_frames --seed S --only K ... \\
        --levels 0.05 0.04 0.032 0.025 --csv reference_tables/bem/graded_cad_frames_S.csv

The rows have the columns of ``graded_cad_1375923287.csv`` (shape, what, level, m = H [m],
faces of the whole body, i, j, added mass [kg, kg m, kg m^2] about the origin, seconds of CPU
of the solve), read by :func:`validation.graded_bodies.read` and by ``validation.cad_draws``
as the frames' most resolved references.
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import csv  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

from benchmarks.plate_graded import RHO, _grid, cosine_nodes  # noqa: E402

DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")
#: largest (mid) panel H [m] per level, coarse to fine
LEVELS = (0.05, 0.04, 0.032, 0.025)
#: the most memory a level's half solve may take [GB]: 24 N^2 bytes + 0.5 GB
#: (:func:`benchmarks.graded_mesher.predicted_gb`)
MAX_GB = 8.5
#: the fewest panels across a tube's facet
TUBE_MIN = 3
#: the fewest panels across a plate's thickness
RIM_MIN = 6
HEADER = ["shape", "what", "level", "m", "faces", "i", "j", "added_mass", "seconds"]
#: the ellipsoid check's semi-axes [m] and levels (largest panel [m])
ELLIPSOID = (0.3, 0.15, 0.1)
ELLIPSOID_LEVELS = (0.05, 0.036, 0.026, 0.019)


def cosine_size(H: float, length: float):
    """h(d) [m] of the cosine law on an edge of ``length`` [m] at largest panel ``H`` [m]: the
    spacing of :func:`benchmarks.plate_graded.cosine_nodes` at a distance d from its nearer
    end, h = H sqrt(4 d / l), clipped to [H^2 / l, H]."""
    def h(d):
        return np.clip(H * np.sqrt(4.0 * np.maximum(d, 0.0) / length), H * H / length, H)
    return h


def _panels(length: float, H: float) -> int:
    """Panels n of the cosine nodes on an edge of ``length`` whose middle one is ``H``:
    n = ceil(pi l / 2H), at least 2."""
    return max(2, int(np.ceil(np.pi * length / (2.0 * H))))


def _rim_panels(t: float, h0: float) -> int:
    """Panels n_t of the cosine nodes across a rim of thickness ``t`` [m] whose panel at each
    edge, t pi^2 / (4 n_t^2), is the faces' edge panel ``h0`` [m]: n_t = ceil(pi/2 sqrt(t /
    h0)), at least :data:`RIM_MIN` (as :func:`benchmarks.plate_graded.eighth_box`'s three on
    a half thickness)."""
    return max(RIM_MIN, int(np.ceil(0.5 * np.pi * np.sqrt(t / h0))))


def frame_geometry(parts) -> dict:
    """The frame of :func:`benchmarks.cad_shapes.make_shape` from its parts: plate length l
    along x and height h along z [m], the plates' inner and outer faces y_in, y_out [m] (the
    plates at +-(y_in + y_out)/2), and the tubes' union in xOz as shapely polygons (each a
    16-gon's convex hull of the tube's vertices; a tube's ends on the outer faces)."""
    import shapely
    from shapely.geometry import MultiPoint

    plates = [np.asarray(p.bounds, float) for p in parts[:2]]
    lo, hi = sorted(plates, key=lambda b: b[0, 1])
    if not (np.allclose(lo[:, [0, 2]], hi[:, [0, 2]]) and np.isclose(lo[0, 1], -hi[1, 1])
            and np.isclose(lo[1, 1], -hi[0, 1])
            and np.allclose(hi[0, [0, 2]], -hi[1, [0, 2]])):
        raise ValueError("not a frame of benchmarks.cad_shapes: two plates mirror-symmetric "
                         "in y = 0 about the x and z axes expected")
    y_in, y_out = float(hi[0, 1]), float(hi[1, 1])
    polys = []
    for p in parts[2:]:
        v = np.asarray(p.vertices, float)
        if not (np.isclose(v[:, 1].min(), -y_out) and np.isclose(v[:, 1].max(), y_out)):
            raise ValueError("a tube does not end on the plates' outer faces")
        polys.append(MultiPoint(v[:, [0, 2]]).convex_hull)
    union = shapely.unary_union(polys)
    geoms = list(getattr(union, "geoms", [union]))
    for g in geoms:
        if len(g.interiors):
            raise ValueError("the tubes enclose a hole: not built")
    return dict(l=float(hi[1, 0] - hi[0, 0]), h=float(hi[1, 2] - hi[0, 2]), y_in=y_in,
                y_out=y_out, tubes=[shapely.geometry.polygon.orient(g, 1.0) for g in geoms])


def holed_face(l: float, h: float, holes, H: float, verbose: bool = False):
    """Triangles of the rectangle [-l/2, l/2] x [-h/2, h/2] (coordinates (x, z)) less the
    polygons ``holes`` (shapely, inside it), meshed by gmsh (Frontal-Delaunay) at the size
    min(h_x, h_z) of :func:`cosine_size` towards the rectangle's edges: (points (n, 2),
    triangles (k, 3) counter-clockwise in (x, z))."""
    import gmsh

    hx, hz = cosine_size(H, l), cosine_size(H, h)
    h0 = H * H / max(l, h)
    gmsh.initialize(["-noenv"], readConfigFiles=False)
    try:
        gmsh.option.setNumber("General.Terminal", 1 if verbose else 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.model.add("face")
        geo = gmsh.model.geo

        def loop(pts):
            tags = [geo.addPoint(float(x), float(z), 0.0) for x, z in pts]
            lines = [geo.addLine(tags[i], tags[(i + 1) % len(tags)]) for i in range(len(tags))]
            return geo.addCurveLoop(lines)

        rect = [(-l / 2, -h / 2), (l / 2, -h / 2), (l / 2, h / 2), (-l / 2, h / 2)]
        loops = [loop(rect)] + [loop(np.asarray(g.exterior.coords)[:-1]) for g in holes]
        geo.addPlaneSurface(loops)
        geo.synchronize()
        for key, val in (("Mesh.MeshSizeFromPoints", 0), ("Mesh.MeshSizeFromCurvature", 0),
                         ("Mesh.MeshSizeExtendFromBoundary", 0), ("Mesh.MeshSizeMin", h0),
                         ("Mesh.MeshSizeMax", H), ("Mesh.Algorithm", 6)):
            gmsh.option.setNumber(key, val)

        def size(dim, tag, x, y, z, lc):
            return float(min(hx(l / 2 - abs(x)), hz(h / 2 - abs(y))))

        gmsh.model.mesh.setSizeCallback(size)
        gmsh.model.mesh.generate(2)
        tags, coords, _ = gmsh.model.mesh.getNodes()
        pts = np.asarray(coords, float).reshape(-1, 3)[:, :2].copy()
        index = np.zeros(int(np.max(tags)) + 1, int)
        index[np.asarray(tags, int)] = np.arange(len(tags))
        types, _, nodes = gmsh.model.mesh.getElements(2)
        tri = np.vstack([index[np.asarray(n, int)].reshape(-1, 3)
                         for t, n in zip(types, nodes) if t == 2])
    finally:
        gmsh.finalize()
    a = pts[tri]
    cross = ((a[:, 1, 0] - a[:, 0, 0]) * (a[:, 2, 1] - a[:, 0, 1])
             - (a[:, 1, 1] - a[:, 0, 1]) * (a[:, 2, 0] - a[:, 0, 0]))
    tri[cross < 0] = tri[cross < 0][:, ::-1]
    return pts, tri


def _joined(pieces) -> tuple:
    """One panel set (vertices [m], faces) of several (vertices, faces) pieces, each piece's
    face indices shifted past the vertices before it."""
    offsets = np.cumsum([0] + [len(v) for v, _ in pieces[:-1]])
    return (np.vstack([v for v, _ in pieces]),
            np.vstack([f + off for (_, f), off in zip(pieces, offsets)]))


def _quads(tri):
    """Triangles as Capytaine's quadrilaterals (the third vertex repeated)."""
    return np.column_stack([tri, tri[:, 2]])


def half_frame(geo: dict, H: float, tube_min: int = None):
    """The y >= 0 half of a frame (:func:`frame_geometry`) panelled at largest panel ``H``
    [m] (module docstring): (vertices (n, 3) [m], faces (k, 4), quadrilaterals and triangles
    with a repeated vertex), outward normals, open on y = 0."""
    l, h, y_in, y_out = geo["l"], geo["h"], geo["y_in"], geo["y_out"]
    tube_min = TUBE_MIN if tube_min is None else tube_min
    t = y_out - y_in
    X = cosine_nodes(l, _panels(l, H))
    Z = cosine_nodes(h, _panels(h, H))
    Y = cosine_nodes(t, _rim_panels(t, H * H / max(l, h)))
    e = np.eye(3)
    c = np.array([-l / 2, 0.0, -h / 2])
    pieces = [
        _grid(c + [0, y_out, 0], e[2], e[0], Z, X),                # outer face, +y
        _grid(c + [l, y_in, 0], e[1], e[2], Y, Z),                 # rim x = l/2, +x
        _grid(c + [0, y_in, 0], e[2], e[1], Z, Y),                 # rim x = -l/2, -x
        _grid(c + [0, y_in, h], e[0], e[1], X, Y),                 # rim z = h/2, +z
        _grid(c + [0, y_in, 0], e[1], e[0], Y, X)]                 # rim z = -h/2, -z
    pts, tri = holed_face(l, h, geo["tubes"], H)                   # inner face, -y
    pieces.append((np.column_stack([pts[:, 0], np.full(len(pts), y_in), pts[:, 1]]),
                   _quads(tri)))
    ys = np.linspace(0.0, y_in, max(1, int(np.ceil(2.0 * y_in / H))) + 1)
    for g in geo["tubes"]:                                         # tube walls, outward
        ring = np.asarray(g.exterior.coords)
        for a, b in zip(ring[:-1], ring[1:]):
            seg = float(np.hypot(*(b - a)))
            s = np.linspace(0.0, seg, max(tube_min, int(np.ceil(2.0 * seg / H))) + 1)
            u = np.array([b[0] - a[0], 0.0, b[1] - a[1]]) / seg
            pieces.append(_grid(np.array([a[0], 0.0, a[1]]), e[1], u, ys, s))
    return _joined(pieces)


def whole(v, f):
    """The closed body of a y >= 0 half: mirrored in y, faces reversed (normals outward)."""
    w = v * np.array([1.0, -1.0, 1.0])
    return np.vstack([v, w]), np.vstack([f, f[:, ::-1] + len(v)])


def check(v, f, body) -> dict:
    """Faces, area and volume of a half's whole body relative to the closed trimesh ``body``
    (each quadrilateral as two triangles; a repeated vertex gives a zero-area one)."""
    wv, wf = whole(v, f)
    tri = np.vstack([wf[:, [0, 1, 2]], wf[:, [0, 2, 3]]])
    p = wv[tri]
    area = 0.5 * np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1).sum()
    vol = np.einsum("ij,ij->i", p[:, 0], np.cross(p[:, 1], p[:, 2])).sum() / 6.0
    return {"faces": len(wf), "area": float(area / body.area - 1.0),
            "volume": float(vol / body.volume - 1.0)}


def capytaine_half(v, f):
    """6x6 added mass [kg, kg m, kg m^2] about the origin, rho = :data:`RHO`, of the closed
    body whose y >= 0 half is (v, f) (quadrilaterals, outward normals): Capytaine, direct
    method, no free surface, on its xOz plane; (matrix, faces of the whole body)."""
    import logging

    import capytaine as cpt

    from benchmarks.plate_graded import solve_added_mass

    logging.getLogger("capytaine").setLevel(logging.ERROR)
    mesh = cpt.ReflectionSymmetricMesh(half=cpt.Mesh(vertices=v, faces=f), plane="xOz")
    return solve_added_mass(mesh), 2 * len(f)


def predicted_gb(faces: int) -> float:
    """Memory [GB] of the half solve of ``faces`` faces (whole body):
    :func:`benchmarks.graded_mesher.predicted_gb`'s rule (24 N^2 bytes + 0.5 GB)."""
    return 24.0 * faces ** 2 / 1e9 + 0.5


def frames(seed: int, count: int, only=None) -> dict:
    """{k: (description, parts, clean surface)} of the frames among the first ``count``
    shapes of ``seed`` (:func:`benchmarks.cad_shapes.drawn_shapes`)."""
    from benchmarks.cad_shapes import clean_surface, drawn_shapes

    return {k: (what, parts, clean_surface(parts)) for k, family, parts, what
            in drawn_shapes(seed, count) if family == "frame" and (only is None or k in only)}


def _level(geo, body, H, name):
    v, f = half_frame(geo, H)
    c = check(v, f, body)
    if abs(c["area"]) > 1e-6 or abs(c["volume"]) > 1e-6:
        raise RuntimeError(f"{name} at H = {H:g} m: the panels are not the body (area "
                           f"{c['area']:+.1e}, volume {c['volume']:+.1e})")
    return v, f, c


def run(path, seed: int, count: int, only=None, levels=LEVELS, max_gb: float = MAX_GB,
        first_level: int = 0):
    """Every level of each frame: panel, check, solve; rows of :data:`HEADER` appended to
    ``path`` as they come."""
    import capytaine

    new = not Path(path).exists()
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    with open(path, "a", newline="") as fh:
        if new:
            fh.write(f"# python -m benchmarks.graded_cad_frames {' '.join(sys.argv[1:])}: "
                     f"Capytaine {capytaine.__version__} (direct method, no free surface, "
                     "rho = 1000 kg/m^3), the frames of seed "
                     f"{seed} panelled graded towards the plates' edges by the cosine law "
                     "(structured rims and outer faces, gmsh inner faces; benchmarks."
                     "graded_cad_frames), the y >= 0 half solved on the xOz plane; m = H [m]; "
                     "seconds: CPU of the solve; upper-triangle 6x6 added mass [kg, kg m, kg "
                     "m^2] about the origin\n")
            csv.writer(fh).writerow(HEADER)
        w = csv.writer(fh)
        for k, (what, parts, body) in frames(seed, count, only).items():
            geo = frame_geometry(parts)
            for lev, H in enumerate(levels, start=first_level):
                v, f, c = _level(geo, body, H, f"frame {k}")
                if predicted_gb(c["faces"]) > max_gb:
                    print(f"{k}: H {H:g} m, {c['faces']} faces: predicted "
                          f"{predicted_gb(c['faces']):.1f} GB > {max_gb:g} GB, not solved",
                          flush=True)
                    continue
                cpu = time.process_time()
                a, n = capytaine_half(v, f)
                cpu = time.process_time() - cpu
                print(f"{k}: H {H:g} m, {n} faces (area {c['area']:+.1e}, volume "
                      f"{c['volume']:+.1e}), {cpu:.1f} s CPU: "
                      + " ".join(f"{x:.6g}" for x in np.diag(a)), flush=True)
                w.writerows([k, f"{what}, cosine-graded, mirror xOz", lev, f"{H:g}", n, i, j,
                             f"{a[i, j]:.9g}", f"{cpu:.2f}"]
                            for i in range(6) for j in range(i, 6))
                fh.flush()


def plate_geometry(chord: float, span: float, thickness: float) -> dict:
    """A lone plate as :func:`half_frame` takes it: chord along x, span along z, thickness
    along y centred on y = 0 (its inner face on the mirror plane: y_in = 0, no tubes)."""
    return dict(l=chord, h=span, y_in=0.0, y_out=thickness / 2, tubes=[])


def half_plate(geo: dict, H: float):
    """The y >= 0 half of a lone plate (:func:`plate_geometry`): its face y = t/2 meshed by
    gmsh at the cosine-law size (:func:`holed_face`, no hole), its rims structured across the
    half thickness graded towards the edge (:func:`benchmarks.plate_graded.graded_nodes`:
    the face's rims as :func:`half_frame` panels them, the other half on the mirror plane)."""
    from benchmarks.plate_graded import graded_nodes

    l, h, t2 = geo["l"], geo["h"], geo["y_out"]
    X = cosine_nodes(l, _panels(l, H))
    Z = cosine_nodes(h, _panels(h, H))
    Y = graded_nodes(t2, (_rim_panels(2 * t2, H * H / max(l, h)) + 1) // 2)
    e = np.eye(3)
    c = np.array([-l / 2, 0.0, -h / 2])
    pts, tri = holed_face(l, h, [], H)
    tri = tri[:, ::-1]                                             # the face y = +t/2: +y
    pieces = [(np.column_stack([pts[:, 0], np.full(len(pts), t2), pts[:, 1]]), _quads(tri)),
              _grid(c + [l, 0, 0], e[1], e[2], Y, Z), _grid(c, e[2], e[1], Z, Y),
              _grid(c + [0, 0, h], e[0], e[1], X, Y), _grid(c, e[1], e[0], Y, X)]
    return _joined(pieces)


#: the lone plate's DOFs (x chord, y thickness, z span) in plate_graded's axes (x chord,
#: y span, z thickness): surge, heave, sway, roll, yaw, pitch
PLATE_DOFS = (0, 2, 1, 3, 5, 4)


def check_plate(seed: int, k: int, levels) -> list[str]:
    """A stored edge-graded plate (reference_tables/bem/cad_plates_graded_SEED.csv) panelled
    by this module, against its structured reference: lines of a table, printed."""
    import trimesh

    from validation import ROOT
    from validation.cad_shapes import fine_reference, read_graded

    chord, span, t, n_ref, terms = read_graded(
        ROOT / "reference_tables" / "bem" / f"cad_plates_graded_{seed}.csv")[k]
    geo = plate_geometry(chord, span, t)
    body = trimesh.creation.box([chord, t, span])
    counts, mats = [], []
    for H in levels:
        v, f = half_plate(geo, H)
        c = check(v, f, body)
        cpu = time.process_time()
        a, n = capytaine_half(v, f)
        print(f"plate {seed}:{k} H {H:g}: {n} faces (area {c['area']:+.1e}, volume "
              f"{c['volume']:+.1e}), {time.process_time() - cpu:.1f} s CPU: "
              + " ".join(f"{x:.6g}" for x in np.diag(a)), flush=True)
        counts.append(n)
        mats.append(np.diag(np.diag(a)))
    ref, band, order = fine_reference(counts, mats)
    lines = [f"Plate {k} of seed {seed} ({chord:.3f} x {span:.3f} x {t:.4f} m): this module's "
             f"levels {'/'.join(map(str, counts))} faces against the structured reference "
             f"({'/'.join(map(str, n_ref))} faces on three mirror planes), each Eça & Hoekstra",
             "", "| term | structured ref. (band) | this module (band, order) | difference | "
             "finest level vs structured |", "|---|---|---|---|---|"]
    for i in range(6):
        s = PLATE_DOFS[i]
        r, u, _ = fine_reference(n_ref, [np.array([[x]]) for x in terms[s]])
        lines.append(f"| {DOFS[i]} | {r[0, 0]:.5g} ({100 * u[0, 0] / abs(r[0, 0]):.1f} %) | "
                     f"{ref[i, i]:.5g} ({100 * band[i, i] / abs(ref[i, i]):.1f} %, "
                     f"{order[i, i]:.2f}) | {100 * (ref[i, i] / r[0, 0] - 1):+.2f} % | "
                     f"{100 * (mats[-1][i, i] / r[0, 0] - 1):+.2f} % |")
    print("\n".join(lines))
    return lines


def ellipsoid_half(abc, H: float):
    """The y >= 0 half of the ellipsoid of semi-axes ``abc`` [m] meshed by gmsh (its
    OpenCASCADE unit sphere scaled; triangles at most ``H`` [m]): (vertices, faces (k, 4)),
    outward normals, the cut's nodes on y = 0."""
    import gmsh

    a, b, c = abc
    gmsh.initialize(["-noenv"], readConfigFiles=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        occ = gmsh.model.occ
        s = occ.addSphere(0, 0, 0, 1.0)
        occ.dilate([(3, s)], 0, 0, 0, a, b, c)
        box = occ.addBox(-2 * a, 0, -2 * c, 4 * a, 2 * b, 4 * c)
        occ.intersect([(3, s)], [(3, box)])
        occ.synchronize()
        gmsh.option.setNumber("Mesh.MeshSizeMax", H)
        gmsh.option.setNumber("Mesh.MeshSizeMin", 0.0)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        gmsh.option.setNumber("Mesh.Algorithm", 6)
        gmsh.model.mesh.generate(2)
        tags, coords, _ = gmsh.model.mesh.getNodes()
        v = np.asarray(coords, float).reshape(-1, 3).copy()
        index = np.zeros(int(np.max(tags)) + 1, int)
        index[np.asarray(tags, int)] = np.arange(len(tags))
        tri = []
        for _, stag in gmsh.model.getEntities(2):
            types, _, nodes = gmsh.model.mesh.getElements(2, stag)
            tri += [index[np.asarray(n, int)].reshape(-1, 3) for t, n in zip(types, nodes)
                    if t == 2]
    finally:
        gmsh.finalize()
    tri = np.vstack(tri)
    p = v[tri]
    cen = p.mean(axis=1)
    keep = cen[:, 1] > 1e-9 * b                                  # the cut's cap dropped
    tri, p, cen = tri[keep], p[keep], cen[keep]
    nrm = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    out = np.einsum("ij,ij->i", nrm, cen / np.array([a, b, c]) ** 2) < 0
    tri[out] = tri[out][:, ::-1]
    v[np.abs(v[:, 1]) < 1e-9 * b, 1] = 0.0
    return v, _quads(tri)


def check_ellipsoid(abc=ELLIPSOID, levels=ELLIPSOID_LEVELS) -> list[str]:
    """The ellipsoid's half solved on xOz at each level, Eça & Hoekstra over the levels,
    against Lamb's exact diagonal: lines of a table, printed."""
    from stripcoef.hull.lamb import ellipsoid_added_mass
    from validation.cad_shapes import fine_reference

    exact = np.asarray(ellipsoid_added_mass(*abc, rho=RHO), float)
    counts, mats = [], []
    for H in levels:
        v, f = ellipsoid_half(abc, H)
        cpu = time.process_time()
        a, n = capytaine_half(v, f)
        print(f"ellipsoid H {H:g}: {n} faces, {time.process_time() - cpu:.1f} s CPU: "
              + " ".join(f"{x:.6g}" for x in np.diag(a)), flush=True)
        counts.append(n)
        mats.append(np.diag(np.diag(a)))
    ref, band, order = fine_reference(counts, mats)
    lines = [f"Ellipsoid semi-axes {abc} m, levels {'/'.join(map(str, counts))} faces, "
             "Eça & Hoekstra, against Lamb's exact added mass", "",
             "| term | exact | reference (band, order) | reference vs exact | finest level "
             "vs exact |", "|---|---|---|---|---|"]
    for i in range(6):
        lines.append(f"| {DOFS[i]} | {exact[i]:.5g} | {ref[i, i]:.5g} "
                     f"({100 * band[i, i] / abs(ref[i, i]):.2f} %, {order[i, i]:.2f}) | "
                     f"{100 * (ref[i, i] / exact[i] - 1):+.2f} % | "
                     f"{100 * (mats[-1][i, i] / exact[i] - 1):+.2f} % |")
    print("\n".join(lines))
    return lines


def compare(seed: int, path=None) -> list[str]:
    """Per frame of ``seed``'s graded file (default reference_tables/bem/
    graded_cad_frames_SEED.csv) and per diagonal term and counted coupling (at least 1 % of
    sqrt(A_ii A_jj), as ``validation.cad_draws``): the graded reference (Eça & Hoekstra over
    the levels: its band, order), the draw's model against it and its estimated band, and
    the reference the draw's count used before (``validation.cad_draws.DRAWS`` without this
    file) against the graded one; errors of the scale sqrt(A_ii A_jj).  Lines of a table,
    printed."""
    from validation.cad_draws import BEM, DRAWS, TOL, best, counted_terms, model_rows
    from validation.cad_shapes import fine_reference
    from validation.graded_bodies import read

    path = Path(path) if path else BEM / f"graded_cad_frames_{seed}.csv"
    rows = model_rows(BEM / f"cad_shapes_{seed}.csv")
    draw = next(d for d in DRAWS if d[0] == seed)
    plates, coarse, levels = draw[1], [c for c in draw[2] if c != path.name], draw[3]
    before, source = best(rows, plates and BEM / plates, [BEM / c for c in coarse],
                          [BEM / x for x in levels], seed)
    lines = [f"Seed {seed}: the model (cad_shapes_{seed}.csv) against the graded frames "
             f"({path.name}); errors of sqrt(A_ii A_jj)", "",
             "| frame | term | graded levels (faces) | graded ref. (band, order) | model vs "
             "graded (model's band) | covered | reference before vs graded (its source) |",
             "|---|---|---|---|---|---|---|"]
    for k, (what, n, mats) in sorted(read(path).items()):
        if k not in rows:
            continue
        ref, band, order = fine_reference(n, mats)
        x = rows[k]
        for i, j, s in counted_terms(ref):
            err = (x["model"][i, j] - ref[i, j]) / s
            cov = abs(x["model"][i, j] - ref[i, j]) <= x["est"][i, j]
            mark = "**" if abs(err) > TOL else ""
            lines.append(
                f"| {k} | {DOFS[i]}" + ("" if i == j else f"-{DOFS[j]}")
                + f" | {n[0]}-{n[-1]} ({len(n)}) | {ref[i, j]:.5g} "
                f"({100 * band[i, j] / s:.1f} %, {order[i, j]:.2f}) | {mark}"
                f"{100 * err:+.1f} %{mark} ({100 * x['est'][i, j] / s:.1f} %) | "
                + ("yes" if cov else "no") + f" | {100 * (before[k][i, j] - ref[i, j]) / s:+.1f} % "
                f"({source.get((k, i, j), 'uniform 3,000-face')}) |")
    print("\n".join(lines))
    return lines


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m benchmarks.graded_cad_frames",
                                 description=__doc__.split("\n\n")[0])
    ap.add_argument("--seed", type=int, default=None)
    ap.add_argument("--count", type=int, default=40)
    ap.add_argument("--only", type=int, nargs="+", default=None)
    ap.add_argument("--levels", type=float, nargs="+", default=None,
                    help="largest panel H [m] per level, coarse to fine")
    ap.add_argument("--max-gb", type=float, default=MAX_GB)
    ap.add_argument("--first-level", type=int, default=0)
    ap.add_argument("--csv", default=None, help="append the levels here")
    ap.add_argument("--faces", action="store_true", help="panel and check the levels, no solve")
    ap.add_argument("--check", choices=("plate", "ellipsoid"), default=None)
    ap.add_argument("--shape", default=None, metavar="SEED:K", help="--check plate: the plate")
    ap.add_argument("--compare", action="store_true",
                    help="the draw's model against the seed's stored graded frames")
    args = ap.parse_args(argv)
    if args.compare:
        if args.seed is None:
            ap.error("--compare needs --seed")
        compare(args.seed, args.csv)
        return 0
    if args.check == "ellipsoid":
        check_ellipsoid(levels=tuple(args.levels or ELLIPSOID_LEVELS))
        return 0
    if args.check == "plate":
        if not args.shape or ":" not in args.shape:
            ap.error("--check plate needs --shape SEED:K")
        seed, k = (int(x) for x in args.shape.split(":"))
        check_plate(seed, k, tuple(args.levels or LEVELS))
        return 0
    if args.seed is None:
        ap.error("--seed is required")
    levels = tuple(args.levels or LEVELS)
    if args.faces:
        for k, (what, parts, body) in frames(args.seed, args.count, args.only).items():
            geo = frame_geometry(parts)
            for H in levels:
                t0 = time.process_time()
                _, _, c = _level(geo, body, H, f"frame {k}")
                print(f"{k} ({what}): H {H:g} m: {c['faces']} faces, area {c['area']:+.1e}, "
                      f"volume {c['volume']:+.1e}, predicted {predicted_gb(c['faces']):.1f} "
                      f"GB, {time.process_time() - t0:.1f} s", flush=True)
        return 0
    if args.csv is None:
        ap.error("--csv is required (or --faces, --check)")
    run(args.csv, args.seed, args.count, args.only, levels, args.max_gb, args.first_level)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

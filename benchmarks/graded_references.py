"""Capytaine references of bodies with edges on panels graded towards the edges (issue 32): the
boxes, the chamfered box and the unions of prisms of the bluff set, and the extruded polygons
of the CAD benchmark.

The stored uniform-mesh references of these bodies (``reference_tables/bem/bem_bluff.csv``:
two subdivided levels, Richardson at order 2, i.e. error ~ 1/N) assume the smooth body's order
of convergence.  At a convex edge the flow is singular (the wedge potential r^(pi/omega),
Newman 1977 sec. 4.4) and uniform panels converge at a lower order (4/3 in h at a right
angle: von Petersdorff & Stephan 1990; :func:`stripcoef.hull.panels.edge_order`), so an
order-2 extrapolation of two uniform levels leaves part of the error in the reference.  Here
the same solver (Capytaine, direct method, no free surface; Ancellin & Dias 2019) solves
structured quadrilaterals whose nodes are spaced as x_k = L sin(pi k / 2m) towards every edge
(the cosine spacing of :mod:`benchmarks.plate_graded`: the panel at an edge is the square of
the uniform one), at five levels, and each term is extrapolated by Eça & Hoekstra's least
squares over them with the order observed (:func:`validation.cad_shapes.fine_reference`,
h ~ N^(-1/2)): references that assume no order.

- ``boxes``: the eight boxes of :mod:`benchmarks.bluff_shapes` (``box_*``, ``cube``), about
  their centre (= their volume centroid, the stored references' point), built as
  :func:`benchmarks.plate_graded.eighth_box` and solved on their quarter
  (:func:`benchmarks.plate_graded.capytaine_eighth`);
- ``bluff``: the bluff set's prism (``chamfer_box``: a box with one edge chamfered, a pentagon
  extruded), about its volume centroid, meshed and solved as the extrusions below;
- ``unions``: the bluff set's unions of prisms along x (``box_skid``, ``l_block``,
  ``twin_hull``, ``cyl_float``, ``box_pod_top_aft``: boxes and trimesh's 24-sided cylinders,
  :data:`benchmarks.bluff_shapes.PRISM_PARTS`), about their volume centroid, panelled by
  :mod:`benchmarks.graded_unions` (graded towards the sharp edges only, not the cylinders'
  15 deg facet joints), their y >= 0 half solved on Capytaine's xOz plane, and the x >= 0
  quarter on xOz and yOz for the two that are mirror-symmetric in x too;
- ``extrusions``: the extruded convex polygons of the CAD benchmark's seed (family
  ``extrusion`` of :mod:`benchmarks.cad_shapes`, drawn again exactly as it draws them), about
  the origin as that benchmark takes them: each cap a fan of quadrilateral sectors from the
  polygon's centroid, graded towards the rim and, along each side, towards both corners; the
  sides graded towards both caps; the half on one side of the mid-plane solved on
  Capytaine's mirror plane (the prism turned by a cyclic permutation of the axes, a proper
  rotation, so that its mid-plane is xOz) and the 6x6 matrix turned back;
- ``checks``: the procedure's own checks: a square prism built by the extrusion mesher
  against the same box built by :func:`~benchmarks.plate_graded.eighth_box` (two
  independent panellings, one limit), the sphere and a triaxial ellipsoid on uniform UV
  meshes against Lamb's exact values and a level of ``bem_bluff.csv`` re-solved (the
  installed Capytaine's results checked).

Usage (one BLAS thread; the finest level at most 13,000 faces (a box's quarter solved) or
8,000 (an extrusion's half)):

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.graded_references boxes \\
        --csv reference_tables/bem/graded_boxes.csv
    OPENBLAS_NUM_THREADS=1 python -m benchmarks.graded_references bluff \\
        --levels 13 16 19 23 27 32 38 --csv reference_tables/bem/graded_bluff.csv
    OPENBLAS_NUM_THREADS=1 python -m benchmarks.graded_references unions \\
        --csv reference_tables/bem/graded_unions.csv
    OPENBLAS_NUM_THREADS=1 python -m benchmarks.graded_references extrusions \\
        --seed 1375923287 --count 40 --csv reference_tables/bem/graded_extrusions.csv
    OPENBLAS_NUM_THREADS=1 python -m benchmarks.graded_references checks

``benchmarks.graded_value_order`` compares the panel method's value at order 2 and at the
edge's formal order with these references.
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

from benchmarks.plate_graded import (_merge, capytaine_eighth, cosine_nodes,  # noqa: E402,F401
                                     eighth_box, graded_nodes, solve_added_mass)
from validation.graded_bodies import read, references  # noqa: E402,F401  (re-exported)

RHO = 1000.0
#: panels on the longest half-edge of a box, one level each: the five finest of these whose
#: whole body has at most :data:`MAX_FACES` faces
BOX_LEVELS = (8, 11, 16, 23, 32, 45)
#: faces of the finest level at most (its quarter solve peaks near 4 GB at 12,700 faces)
MAX_FACES = 13000
#: levels per body at most
MAX_LEVELS = 5
#: panels on the longest side of an extruded polygon, one level each (the five finest within
#: :data:`PRISM_MAX_FACES`)
PRISM_LEVELS = (6, 8, 11, 13, 16, 19, 23, 27, 32)
#: faces of an extrusion's finest level at most (its half solve: two blocks of N/2 faces)
PRISM_MAX_FACES = 8000
#: the bluff set's boxes (benchmarks.bluff_shapes.SHAPES)
BOXES = ("box_bluerov", "box_4_1_1", "box_1_4_1", "box_1_1_4", "box_2_2_1", "box_1_2_2",
         "box_2_1_1", "cube")
DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")
HEADER = ["shape", "what", "level", "m", "faces", "i", "j", "added_mass", "seconds"]


def box_extents(name: str) -> tuple:
    """(x, y, z) extents [m] of a box of the bluff set (its builder's trimesh)."""
    from benchmarks.bluff_shapes import SHAPES

    return tuple(float(x) for x in SHAPES[name][0](None).extents)


def half_prism(poly, height: float, m: int):
    """The z >= 0 half of the convex polygon ``poly`` (k, 2) [m] extruded over
    [-height/2, height/2] (z), graded quadrilaterals: (vertices [m], faces (n, 4)), outward
    normals; a sector's panels at the centroid are triangles written as quadrilaterals whose
    last vertex repeats the third.  ``m`` panels on the longest side; each side n_i =
    max(3, m L_i / L_max) panels graded towards both corners; the cap's sectors
    max(3, m r_max / L_max) rows graded towards the rim (sin spacing); the half height
    max(3, m (h/2) / L_max) rows graded towards the cap."""
    poly = np.asarray(poly, float)
    k = len(poly)
    c = poly.mean(axis=0)
    sides = [np.linalg.norm(poly[(i + 1) % k] - poly[i]) for i in range(k)]
    big = max(sides)
    r_max = float(np.max(np.linalg.norm(poly - c, axis=1)))
    s = graded_nodes(1.0, max(3, round(m * r_max / big)))
    z = graded_nodes(0.5 * height, max(3, round(m * 0.5 * height / big)))
    parts = []
    for i in range(k):
        a, b = poly[i], poly[(i + 1) % k]
        t = cosine_nodes(1.0, max(3, round(m * sides[i] / big)))
        rim = a + t[:, None] * (b - a)                                     # (nt, 2)
        # cap sector: c + s (rim - c), z = h/2
        ss, tt = np.meshgrid(s, np.arange(len(t)), indexing="ij")
        pts = c + ss[..., None] * (rim[tt] - c)
        cap = np.concatenate([pts, np.full(pts.shape[:2] + (1,), 0.5 * height)], axis=-1)
        parts.append(_quads(cap))
        # side i: rim (t) x z
        zz, tt = np.meshgrid(z, np.arange(len(t)), indexing="ij")
        side = np.concatenate([rim[tt], zz[..., None]], axis=-1)
        parts.append(_quads(side))
    v, f = _merge(parts)
    return v, _orient(v, f, np.r_[c, 0.0])


def _quads(grid):
    """Quadrilaterals of a structured grid of points (nu, nv, 3): (vertices, faces)."""
    nu, nv = grid.shape[:2]
    idx = np.arange(nu * nv).reshape(nu, nv)
    faces = np.stack([idx[:-1, :-1], idx[1:, :-1], idx[1:, 1:], idx[:-1, 1:]], -1)
    return grid.reshape(-1, 3), faces.reshape(-1, 4)


def _orient(v, f, inside):
    """Faces of a convex body's surface turned to outward normals (seen from ``inside``), the
    degenerate corner of a sector's first row written as a triangle (repeated third vertex);
    panels of zero area dropped."""
    out = []
    for q in f:
        u = list(dict.fromkeys(q.tolist()))
        if len(u) < 3:
            continue
        p = v[u]
        n = np.cross(p[2] - p[0], p[-1] - p[1]) if len(u) == 4 else np.cross(p[1] - p[0],
                                                                              p[2] - p[0])
        if np.linalg.norm(n) < 1e-14:
            continue
        if np.dot(n, p.mean(axis=0) - inside) < 0:
            u = u[::-1]
        if len(u) == 3:
            u.append(u[2])
        out.append(u)
    return np.array(out)


#: the solve's axes from the prism's own (polygon x, polygon y, extrusion z): solve = (y, z, x),
#: a cyclic permutation (a proper rotation), so that the mid-plane z = 0 is the solve's xOz
_TO_SOLVE = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]])


def capytaine_half(v, f, rotation):
    """6x6 added mass [kg, kg m, kg m^2] about the origin, rho = :data:`RHO`, of the closed
    body whose half on one side of its mirror plane is (v, f) in its own axes; ``rotation``
    (3x3, proper) takes its axes to the solve's, where the plane is xOz: Capytaine (direct
    method, no free surface) on ``cpt.ReflectionSymmetricMesh``; the matrix turned back to the
    body's axes.  (matrix, faces of the whole body, wall time [s])."""
    import logging

    import capytaine as cpt

    logging.getLogger("capytaine").setLevel(logging.ERROR)
    rot = np.asarray(rotation, float)
    t0 = time.perf_counter()
    half = cpt.Mesh(vertices=v @ rot.T, faces=f)
    mesh = cpt.ReflectionSymmetricMesh(half=half, plane="xOz")
    a = solve_added_mass(mesh)
    t = np.zeros((6, 6))
    t[:3, :3] = t[3:, 3:] = rot.T                     # solve axes -> body axes (det +1)
    return t @ a @ t.T, 2 * len(f), time.perf_counter() - t0


def prism_added_mass(poly, height, axis_perm, m):
    """6x6 added mass about the origin of a CAD benchmark extrusion (its polygon, height and
    the axis permutation of :func:`benchmarks.cad_shapes._fan_prism`: global[:, k] =
    local[:, perm[k]]) on the graded mesh of :func:`half_prism` with ``m`` panels on the
    longest side; (matrix in the global axes, faces, seconds)."""
    v, f = half_prism(poly, height, m)
    a, n, sec = capytaine_half(v, f, _TO_SOLVE)         # in the prism's own axes
    p = np.zeros((3, 3))
    for k, q in enumerate(axis_perm):
        p[k, q] = 1.0                                   # global = p @ local
    assert np.isclose(np.linalg.det(p), 1.0)
    t = np.zeros((6, 6))
    t[:3, :3] = t[3:, 3:] = p
    return t @ a @ t.T, n, sec


#: the bluff set's prisms (benchmarks.bluff_shapes.SHAPES): a convex polygon extruded
BLUFF_PRISMS = ("chamfer_box",)


def bluff_prism(name: str):
    """(polygon (k, 2) [m], height [m], perm) of a prism of the bluff set about its volume
    centroid (:func:`benchmarks.bluff_shapes.shape_mesh`'s point), read from its builder's
    convex hull: the extrusion axis is the one whose coordinate takes two values; the
    polygon, in the axes of :func:`benchmarks.cad_shapes._fan_prism` (global[:, k] =
    local[:, perm[k]]), ordered about its centroid."""
    from benchmarks.bluff_shapes import SHAPES

    mesh = SHAPES[name][0](None)
    v = np.asarray(mesh.vertices, float) - np.asarray(mesh.center_mass, float)
    axis = next(k for k in range(3) if len(np.unique(np.round(v[:, k], 12))) == 2)
    perm = {2: [0, 1, 2], 0: [2, 0, 1], 1: [1, 2, 0]}[axis]
    local = np.empty_like(v)
    local[:, perm] = v
    top = local[local[:, 2] > 0][:, :2]
    c = top.mean(axis=0)
    poly = top[np.argsort(np.arctan2(top[:, 1] - c[1], top[:, 0] - c[0]))]
    return poly, float(np.ptp(local[:, 2])), perm


def run_bluff(path, levels):
    """The bluff set's prisms at every level, about their volume centroid."""
    fh, w = _writer(path, "python -m benchmarks.graded_references bluff --levels "
                    + " ".join(map(str, levels)))
    with fh:
        for name in BLUFF_PRISMS:
            poly, h, perm = bluff_prism(name)
            fit = [m for m in levels if 2 * len(half_prism(poly, h, m)[1]) <= PRISM_MAX_FACES]
            for lev, m in enumerate(fit[-MAX_LEVELS:]):
                a, n, sec = prism_added_mass(poly, h, perm, m)
                print(f"{name}: m {m}, {n} faces, {sec:.1f} s: "
                      + " ".join(f"{x:.6g}" for x in np.diag(a)), flush=True)
                _rows(w, name, f"{len(poly)}-gon prism {h:g} m long", lev, m, n, a, sec)
                fh.flush()


def extrusions_of_seed(seed: int, count: int) -> dict:
    """{shape: (polygon (k, 2) [m], height [m], perm)} of the extrusions among the first
    ``count`` shapes of ``seed`` of :mod:`benchmarks.cad_shapes`, drawn exactly as it draws
    them; polygon and height read back from the prism's vertices (its first k vertices are
    the bottom cap, local = global[:, inverse perm])."""
    from benchmarks.cad_shapes import drawn_shapes

    perms = {2: [0, 1, 2], 0: [2, 0, 1], 1: [1, 2, 0]}
    out = {}
    for k, family, parts, what in drawn_shapes(seed, count):
        if family != "extrusion":
            continue
        g = np.asarray(parts[0].vertices, float)
        axis = "xyz".index(what.split("along ")[-1])
        perm = perms[axis]
        local = np.empty_like(g)
        local[:, perm] = g
        n = len(g) // 2
        out[k] = (local[:n, :2].copy(), float(local[n:, 2].max() - local[:n, 2].min()), perm)
    return out


def _writer(path, command, graded="every edge"):
    import capytaine

    Path(path).parent.mkdir(parents=True, exist_ok=True)
    fh = open(path, "w", newline="")
    fh.write(f"# {command}: Capytaine {capytaine.__version__} (direct method, no free "
             f"surface, rho = 1000 kg/m^3), structured quadrilaterals graded towards {graded}"
             ", mirror planes used; upper-triangle 6x6 added mass [kg, kg m, kg m^2]\n")
    w = csv.writer(fh)
    w.writerow(HEADER)
    return fh, w


def _rows(w, shape, what, lev, m, n, a, sec):
    w.writerows([shape, what, lev, m, n, i, j, f"{a[i, j]:.9g}", f"{sec:.2f}"]
                for i in range(6) for j in range(i, 6))


def run_boxes(path, levels, only=None):
    """The bluff set's boxes at every level, about their centre."""
    fh, w = _writer(path, "python -m benchmarks.graded_references boxes --levels "
                    + " ".join(map(str, levels)) + (f" --only {' '.join(only)}" if only else ""))
    with fh:
        for name in (only or BOXES):
            x, y, z = box_extents(name)
            # eighth_box's m counts the longest horizontal half-edge: a tall box's levels
            # scaled so that m counts its longest edge
            scale = max(x, y) / max(x, y, z)
            ms = list(dict.fromkeys(max(1, round(m * scale)) for m in levels))
            fit = [m for m in ms if 8 * len(eighth_box(x, y, z, m)[1]) <= MAX_FACES]
            for lev, m in enumerate(fit[-MAX_LEVELS:]):
                a, n, sec = capytaine_eighth(*eighth_box(x, y, z, m))
                print(f"{name:12s} {x:.3f} x {y:.3f} x {z:.3f}: m {m}, {n} faces, {sec:.1f} s: "
                      + " ".join(f"{v:.6g}" for v in np.diag(a)), flush=True)
                _rows(w, name, f"box {x:g} x {y:g} x {z:g} m", lev, m, n, a, sec)
                fh.flush()


def run_extrusions(path, seed, count, levels, only=None):
    """The seed's extrusions at every level, about the origin."""
    shapes = {k: x for k, x in extrusions_of_seed(seed, count).items()
              if not only or k in only}
    fh, w = _writer(path, f"python -m benchmarks.graded_references extrusions --seed {seed} "
                    f"--count {count} --levels " + " ".join(map(str, levels))
                    + (f" --only {' '.join(map(str, only))}" if only else ""))
    with fh:
        for k, (poly, h, perm) in shapes.items():
            what = f"{len(poly)}-gon extruded {h:.3f} m along {'xyz'[perm.index(2)]}"
            fit = [m for m in levels if 2 * len(half_prism(poly, h, m)[1]) <= PRISM_MAX_FACES]
            for lev, m in enumerate(fit[-MAX_LEVELS:]):
                a, n, sec = prism_added_mass(poly, h, perm, m)
                print(f"{k:3d} {what}: m {m}, {n} faces, {sec:.1f} s: "
                      + " ".join(f"{v:.6g}" for v in np.diag(a)), flush=True)
                _rows(w, k, what, lev, m, n, a, sec)
                fh.flush()


#: the bluff set's unions of prisms along x (benchmarks.bluff_shapes.PRISM_PARTS), cheapest
#: first (the mirror-symmetric in x are solved on a quarter)
UNIONS = ("box_skid", "l_block", "twin_hull", "cyl_float", "box_pod_top_aft")
#: panels on the longest extent of a union, one level each (the five finest within
#: :data:`MAX_FACES` for a quarter, :data:`PRISM_MAX_FACES` for a half)
UNION_LEVELS = (8, 10, 13, 16, 19, 23, 27, 32)
#: the unions' grading, as their file's header says it
UNION_GRADING = ("every sharp edge (not the 15 deg facet joints of the 24-sided cylinders; "
                 "benchmarks.graded_unions)")


def union_added_mass(prisms, quarter, m):
    """6x6 added mass about the origin (the shape's volume centroid) of a union of prisms
    along x (:mod:`benchmarks.graded_unions`) on its graded panels with ``m`` on the longest
    extent: Capytaine on its y >= 0 half (``quarter``: its x >= 0 quarter) and the mirror
    planes; (matrix, faces of the whole body, wall time [s])."""
    import logging

    import capytaine as cpt

    from benchmarks.graded_unions import graded_part

    logging.getLogger("capytaine").setLevel(logging.ERROR)
    t0 = time.perf_counter()
    v, f = graded_part(prisms, m, quarter)
    mesh = cpt.ReflectionSymmetricMesh(half=cpt.Mesh(vertices=v, faces=f), plane="xOz")
    if quarter:
        mesh = cpt.ReflectionSymmetricMesh(half=mesh, plane="yOz")
    return solve_added_mass(mesh), (4 if quarter else 2) * len(f), time.perf_counter() - t0


def union_levels(prisms, quarter, levels):
    """The five finest of ``levels`` whose whole body is within the face cap."""
    from benchmarks.graded_unions import graded_part

    cap, k = (MAX_FACES, 4) if quarter else (PRISM_MAX_FACES, 2)
    return [m for m in levels if k * len(graded_part(prisms, m, quarter)[1]) <= cap][-MAX_LEVELS:]


def run_unions(path, levels, only=None):
    """The bluff set's unions of prisms at every level, about their volume centroid."""
    from benchmarks.graded_unions import shape_prisms

    fh, w = _writer(path, "python -m benchmarks.graded_references unions --levels "
                    + " ".join(map(str, levels)) + (f" --only {' '.join(only)}" if only else ""),
                    UNION_GRADING)
    with fh:
        for name in (only or UNIONS):
            prisms, quarter = shape_prisms(name)
            what = f"{len(prisms)} prisms along x, {'quarter' if quarter else 'half'} solved"
            for lev, m in enumerate(union_levels(prisms, quarter, levels)):
                a, n, sec = union_added_mass(prisms, quarter, m)
                print(f"{name}: m {m}, {n} faces, {sec:.1f} s: "
                      + " ".join(f"{x:.6g}" for x in np.diag(a)), flush=True)
                _rows(w, name, what, lev, m, n, a, sec)
                fh.flush()


def union_check(name="box_bluerov", levels=(13, 16, 19, 23, 27)):
    """The unions' mesher (:mod:`benchmarks.graded_unions`, quarter solve) on one box of the
    bluff set against its stored graded reference (``graded_boxes.csv``: the eighth-box
    mesher): two independent panellings, one limit; printed."""
    from shapely.geometry import box as rect

    from validation.cad_shapes import fine_reference
    from validation.graded_bodies import BOXES

    x, y, z = box_extents(name)
    prisms = [(-x / 2, x / 2, rect(-y / 2, -z / 2, y / 2, z / 2))]
    counts, mats = [], []
    for m in levels:
        a, n, sec = union_added_mass(prisms, True, m)
        counts.append(n)
        mats.append(a)
        print(f"{name} by the unions' mesher: m {m}, {n} faces, {sec:.1f} s: "
              + " ".join(f"{v:.6g}" for v in np.diag(a)), flush=True)
    ref, band, _ = fine_reference(counts, mats)
    stored, sband, _, _ = references(BOXES)[name]
    for i in range(6):
        print(f"{DOFS[i]}: unions' mesher {ref[i, i]:.6g} (band {100 * band[i, i] / ref[i, i]:.2f}"
              f" %), graded_boxes.csv {stored[i, i]:.6g} (band "
              f"{100 * sband[i, i] / stored[i, i]:.2f} %), difference "
              f"{100 * (ref[i, i] / stored[i, i] - 1):+.2f} %")


def checks(levels):
    """Capytaine on the sphere and a triaxial ellipsoid against Lamb's exact values, a level of
    ``bem_bluff.csv`` re-solved, and the extrusion mesher against the box mesher on one
    square prism (Eça & Hoekstra over ``levels``); printed."""
    import trimesh

    from stripcoef.bem import bem_added_mass
    from stripcoef.hull.lamb import ellipsoid_added_mass
    from validation.cad_shapes import fine_reference

    for name, (a, b, c) in (("sphere 0.15", (0.15, 0.15, 0.15)),
                            ("ellipsoid 0.30 x 0.15 x 0.08", (0.3, 0.15, 0.08))):
        exact = np.asarray(ellipsoid_added_mass(a, b, c, rho=RHO), float)
        for n in (16, 24):
            s = trimesh.creation.uv_sphere(radius=1.0, count=[n, 2 * n])
            s.apply_scale([a, b, c])
            d = np.diag(bem_added_mass(s, rho=RHO))
            rel = [f"{100 * (x / e - 1):+.2f} %" if e > 1e-9 * exact.max() else "-"
                   for x, e in zip(d, exact)]
            print(f"{name}, {len(s.faces)} faces, Capytaine / Lamb - 1: " + ", ".join(rel),
                  flush=True)
    from benchmarks.bluff_shapes import read_references, shape_mesh

    stored = read_references("a_1")
    for name in ("cube", "box_bluerov"):
        mesh = shape_mesh(name, 2300)                  # bem_bluff.csv's first level
        a = bem_added_mass(mesh, rho=RHO)
        print(f"{name}: bem_bluff.csv's level of {len(mesh.faces)} faces re-solved, largest "
              f"difference {np.abs(a - stored[name]).max() / np.abs(stored[name]).max():.1e} "
              "of the largest term", flush=True)
    side, h = 0.3, 0.2
    poly = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]], float) * 0.5 * side
    prism, box = [], []
    for m in levels:
        a, n1, _ = prism_added_mass(poly, h, [0, 1, 2], m)
        b, n2, _ = capytaine_eighth(*eighth_box(side, side, h, m // 2))
        prism.append((n1, a))
        box.append((n2, b))
        print(f"square prism m {m}: {n1} faces {np.round(np.diag(a), 5)}; box m {m // 2}: "
              f"{n2} faces {np.round(np.diag(b), 5)}", flush=True)
    rp, bp, _ = fine_reference([n for n, _ in prism], [a for _, a in prism])
    rb, bb, _ = fine_reference([n for n, _ in box], [a for _, a in box])
    for i in range(6):
        print(f"{DOFS[i]}: prism mesher {rp[i, i]:.6g} (band {100 * bp[i, i] / rp[i, i]:.2f} "
              f"%), box mesher {rb[i, i]:.6g} (band {100 * bb[i, i] / rb[i, i]:.2f} %), "
              f"difference {100 * (rp[i, i] / rb[i, i] - 1):+.2f} %")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("what", choices=("boxes", "bluff", "unions", "extrusions", "checks",
                                     "union-check"))
    ap.add_argument("--seed", type=int, default=1375923287, help="the CAD benchmark's seed")
    ap.add_argument("--count", type=int, default=40, help="its shape count (default 40)")
    ap.add_argument("--levels", type=int, nargs="+", default=None,
                    help="panels on the longest (half-)edge, one level each")
    ap.add_argument("--csv", default=None, help="write the levels here")
    ap.add_argument("--only", nargs="+", default=None, help="these shapes only")
    args = ap.parse_args(argv)
    if args.what == "checks":
        checks(args.levels or (8, 11, 16, 23))
        return 0
    if args.what == "union-check":
        union_check(levels=tuple(args.levels or (13, 16, 19, 23, 27)))
        return 0
    if not args.csv:
        ap.error(f"{args.what} needs --csv")
    if args.what == "boxes":
        run_boxes(args.csv, args.levels or BOX_LEVELS, args.only)
    elif args.what == "bluff":
        run_bluff(args.csv, args.levels or PRISM_LEVELS)
    elif args.what == "unions":
        run_unions(args.csv, args.levels or UNION_LEVELS, args.only)
    else:
        run_extrusions(args.csv, args.seed, args.count, args.levels or PRISM_LEVELS,
                       [int(x) for x in args.only] if args.only else None)
    return 0


if __name__ == "__main__":
    sys.exit(main())

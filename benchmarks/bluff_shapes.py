"""Bluff-shape benchmark: strip theory + 3D corrections against converged BEM references.

Shapes (body axes FRD, metres, centred on their volume centroid): boxes from 1:4:1 to 4:1:1 in
all orientations and a cube, short cylinders along x, y and z, a sphere, an oblate and two
triaxial ellipsoids, an open frame of tubes with thruster pods, a VideoRay-like body, the
BlueROV2-Heavy-like frame of the former geometry/bluerov2_heavy.stl (:func:`former_bluerov2_parts`,
18 shapes), and six asymmetric bluff
bodies for the off-diagonal terms (issue 14): a box with two skids below, a box with a pod on
top aft, an L-shaped block (raised housing at the front), a cylinder with a float on top
forward, a box with its front-top edge chamfered, and two cylinders joined by a top plate
(24 shapes in all).

References (stored, never recomputed by the tests):

    python -m benchmarks.bluff_shapes --reference      # about 2 min quiet, 1.3 GB peak

runs Capytaine (direct method, no free surface, rho = 1000) on each shape at two resolutions
(about 2300 and 4600 faces: at most 5000 faces per solve, one solve at a time) and writes
reference_tables/bem/bem_bluff.csv: both resolutions, their face counts and the Richardson
extrapolation A = (N2 A2 - N1 A1) / (N2 - N1) (the direct method converges at second order in
the panel size h ~ N^-1/2, i.e. as 1/N). Smooth shapes (sphere, ellipsoids, cylinders) are
re-tessellated at each resolution; faceted shapes (boxes, frames) keep their geometry and are
subdivided.

Accuracy and timing:

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.bluff_shapes [--no-corrections | --per-dof-axes]

prints every shape x every diagonal term and the significant off-diagonals (|BEM| >= 1 % of
the geometric mean of the two diagonals) against the Richardson value, and the ellipsoids
against Lamb's exact values (:func:`stripcoef.hull.lamb.ellipsoid_added_mass`).
"""

from __future__ import annotations

import argparse
import csv
import datetime
import os
import sys
import time
from pathlib import Path

import numpy as np
import trimesh

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "reference_tables" / "bem" / "bem_bluff.csv"
RHO = 1000.0
#: target faces of the two BEM resolutions (each solve <= 5000 faces, ~1.4 GB)
LEVELS = (2300, 4600)
#: faces of the strip-theory input of smooth shapes
STRIP_FACES = 20000
#: an off-diagonal term is significant when |BEM| >= this fraction of sqrt(A_ii A_jj)
SIGNIFICANT = 0.01
DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")
TERM_NAMES = ("X_udot", "Y_vdot", "Z_wdot", "K_pdot", "M_qdot", "N_rdot")


def _T(xyz):
    return trimesh.transformations.translation_matrix(xyz)


def _box(size, center=(0, 0, 0)):
    return trimesh.creation.box(size, transform=_T(center))


def _cyl(d, length, center, axis, sections):
    c = trimesh.creation.cylinder(radius=0.5 * d, height=length, sections=sections)
    c.apply_transform(trimesh.geometry.align_vectors([0, 0, 1], np.asarray(axis, float)))
    c.apply_translation(center)
    return c


def _round_cylinder(d, length, axis, faces):
    """Solid circular cylinder (diameter d, length [m]) along ``axis`` ("x", "y" or "z"), about
    ``faces`` triangles of even size: revolved (stripcoef.geometry.mesh.revolved_mesh) with
    rings on the flat ends, not trimesh's fans of sliver triangles (aspect ratio > 20 at the
    centre, which biased the BEM of the end caps: +12 % on the pitch of the short cylinder)."""
    r = 0.5 * d
    for k in range(16, 400, 2):
        h = 2 * np.pi * r / k
        nr, nl = max(2, int(np.ceil(r / h))), max(2, int(np.ceil(length / h)))
        if 2 * k * (2 * nr + nl) > faces:
            break
        best = (k, nr, nl)
    k, nr, nl = best
    rr = np.linspace(0.0, r, nr + 1)
    zs = np.r_[np.full(nr, -0.5 * length), np.linspace(-0.5 * length, 0.5 * length, nl + 1),
               np.full(nr, 0.5 * length)]
    rs = np.r_[rr[:-1], np.full(nl + 1, r), rr[::-1][1:]]
    m = trimesh.creation.revolve(np.column_stack([rs, zs]), sections=k)    # about z
    m = trimesh.Trimesh(m.vertices, m.faces, process=True)
    if m.volume < 0:
        m.invert()
    m.apply_transform(trimesh.geometry.align_vectors([0, 0, 1], np.eye(3)["xyz".index(axis)]))
    return m


def _ellipsoid(a, b, c, faces):
    """UV-sphere scaled to semi-axes (a, b, c) along (x, y, z), about ``faces`` triangles."""
    n = max(8, int(round(np.sqrt(faces / 8.0))))
    s = trimesh.creation.uv_sphere(radius=1.0, count=[n, 2 * n])
    s.apply_scale([a, b, c])
    return s


def _union(parts):
    return trimesh.boolean.union(parts, engine="manifold")


def open_frame():
    """Open frame 0.50 x 0.40 x 0.30 m: four longitudinal tubes (D 0.04 m) at the corners,
    four cross tubes, four vertical posts, two thruster pods (D 0.08, L 0.10 m, along x) aft
    and one vertical pod in the middle of the top."""
    s = 16
    parts = []
    for y in (-0.18, 0.18):
        for z in (-0.13, 0.13):
            parts.append(_cyl(0.04, 0.50, [0, y, z], [1, 0, 0], s))
    for x in (-0.23, 0.23):
        for z in (-0.13, 0.13):
            parts.append(_cyl(0.04, 0.40, [x, 0, z], [0, 1, 0], s))
        for y in (-0.18, 0.18):
            parts.append(_cyl(0.04, 0.30, [x, y, 0], [0, 0, 1], s))
    for y in (-0.18, 0.18):
        parts.append(_cyl(0.08, 0.10, [-0.18, y, 0.05], [1, 0, 0], s))
        parts.append(_box([0.04, 0.02, 0.10], [-0.18, y, 0.09]))
    parts.append(_cyl(0.08, 0.10, [0.0, 0.0, -0.13], [0, 0, 1], s))
    parts.append(_box([0.02, 0.36, 0.02], [0.0, 0.0, -0.13]))
    return _union(parts)


def videoray_like():
    """VideoRay-like micro ROV, 0.30 x 0.22 x 0.21 m overall, asymmetric fore-aft and
    top-bottom: a rounded main hull (capsule D 0.14 m along x), two side thruster pods aft,
    a float block on top shifted forward and a lower skid (bar) aft."""
    s = 20
    hull = trimesh.creation.capsule(height=0.16, radius=0.07, count=[s, s])
    hull.apply_transform(trimesh.geometry.align_vectors([0, 0, 1], [1, 0, 0]))
    parts = [hull]
    for y in (-0.08, 0.08):
        parts.append(_cyl(0.06, 0.09, [-0.09, y, 0.0], [1, 0, 0], s))
    parts.append(_box([0.16, 0.14, 0.05], [0.03, 0.0, -0.08]))        # float, forward, on top
    parts.append(_box([0.12, 0.03, 0.03], [-0.06, 0.0, 0.09]))        # skid below, aft
    return _union(parts)


#: sections of the round parts of the asymmetric shapes (24: the two BEM resolutions of
#: cyl_float, twin_hull and box_pod_top_aft come out near 2300 and 4600 faces; 32 gave
#: cyl_float 2270 and 2942 only, a poorly conditioned Richardson step)
_ASYM_SECTIONS = 24


def box_skid_parts():
    """The parts of :func:`box_skid` (trimesh solids, before their union)."""
    parts = [_box([0.40, 0.30, 0.20])]
    for y in (-0.10, 0.10):
        parts.append(_box([0.36, 0.03, 0.04], [0.0, y, 0.12]))
    return parts


def box_skid():
    """Box 0.40 x 0.30 x 0.20 m with two skid bars 0.36 x 0.03 x 0.04 m below it at
    y = +-0.10 m (z 0.10-0.14 m: on the box's bottom face): asymmetric top-bottom."""
    return _union(box_skid_parts())


def box_pod_top_aft_parts():
    """The parts of :func:`box_pod_top_aft` (trimesh solids, before their union)."""
    return [_box([0.45, 0.35, 0.22]),
            _cyl(0.10, 0.20, [-0.12, 0.0, -0.14], [1, 0, 0], _ASYM_SECTIONS)]


def box_pod_top_aft():
    """Box 0.45 x 0.35 x 0.22 m with a cylindrical pod (D 0.10, L 0.20 m, along x) on top, aft,
    centred at (-0.12, 0, -0.14) m: asymmetric fore-aft and top-bottom."""
    return _union(box_pod_top_aft_parts())


def l_block_parts():
    """The parts of :func:`l_block` (trimesh solids, before their union)."""
    return [_box([0.40, 0.30, 0.12]), _box([0.15, 0.30, 0.15], [0.125, 0.0, -0.13])]


def l_block():
    """Box 0.40 x 0.30 x 0.12 m with a raised housing 0.15 x 0.30 x 0.15 m on top at the front
    (centred at (0.125, 0, -0.13) m, 0.005 m into the box): an L-shaped side profile."""
    return _union(l_block_parts())


def cyl_float_parts():
    """The parts of :func:`cyl_float` (trimesh solids, before their union)."""
    return [_cyl(0.15, 0.40, [0.0, 0.0, 0.0], [1, 0, 0], _ASYM_SECTIONS),
            _box([0.30, 0.20, 0.06], [0.04, 0.0, -0.095])]


def cyl_float():
    """Cylinder along x (D 0.15, L 0.40 m) with a float block 0.30 x 0.20 x 0.06 m on top,
    shifted forward (centred at (0.04, 0, -0.095) m)."""
    return _union(cyl_float_parts())


def chamfer_box():
    """Box 0.40 x 0.30 x 0.20 m with its front-top edge chamfered (0.10 m along x, 0.10 m down
    the front face): the convex hull of the corners with the two front-top ones replaced by
    (0.20, +-0.15, 0.0) and (0.10, +-0.15, -0.10)."""
    pts = [(x, y, z) for x in (-0.20, 0.20) for y in (-0.15, 0.15) for z in (-0.10, 0.10)
           if not (x > 0 and z < 0)]
    pts += [(0.20, y, 0.0) for y in (-0.15, 0.15)] + [(0.10, y, -0.10) for y in (-0.15, 0.15)]
    return trimesh.convex.convex_hull(np.array(pts, float))


def twin_hull_parts():
    """The parts of :func:`twin_hull` (trimesh solids, before their union)."""
    parts = [_cyl(0.12, 0.50, [0.0, y, 0.0], [1, 0, 0], _ASYM_SECTIONS) for y in (-0.15, 0.15)]
    parts.append(_box([0.30, 0.42, 0.04], [0.0, 0.0, -0.07]))
    return parts


def twin_hull():
    """Two cylinders along x (D 0.12, L 0.50 m) at y = +-0.15 m joined by a top plate
    0.30 x 0.42 x 0.04 m centred at (0, 0, -0.07) m: a catamaran-like body."""
    return _union(twin_hull_parts())


def former_bluerov2_parts():
    """The parts (overlapping trimesh solids) of the BlueROV2-Heavy-like frame that
    geometry/bluerov2_heavy.stl held until issue 32 (scripts/make_bluerov2_heavy.py then; the
    shipped files now hold the published parts): overall 0.457 x 0.575 x 0.254 m, two solid
    side panels 12.7 mm thick, a buoyancy block, the 4" and 3" tubes, a lower tray, eight
    T200 pods as solid 20-sided cylinders (D 0.10, L 0.11 m; the horizontal ones at 45 deg) and
    the wings of the vertical ones.  Kept as it was: the stored BEM reference
    (reference_tables/bem/bem_bluff.csv, bluerov2_heavy) is of their union."""
    def box(size, center):
        return trimesh.creation.box(size, transform=trimesh.transformations.translation_matrix(
            center))

    def cyl(diameter, length, center, direction):
        c = trimesh.creation.cylinder(radius=0.5 * diameter, height=length, sections=20)
        c.apply_transform(trimesh.geometry.align_vectors([0, 0, 1], np.asarray(direction, float)))
        c.apply_translation(center)
        return c

    lx, ly, lz = 0.457, 0.575, 0.254
    pod_d, pod_l, y_panel = 0.10, 0.11, 0.17
    parts = [box([lx, 0.0127, lz], [0.0, s * y_panel, 0.0]) for s in (-1, 1)]
    parts.append(box([0.40, 2 * y_panel, 0.06], [0.0, 0.0, -0.5 * lz + 0.03]))
    parts.append(cyl(0.114, 0.32, [0.02, 0.0, -0.01], [1, 0, 0]))
    parts.append(cyl(0.089, 0.26, [0.0, 0.0, 0.075], [1, 0, 0]))
    parts.append(box([0.30, 2 * y_panel, 0.0127], [0.0, 0.0, 0.5 * lz - 0.02]))
    y_v = 0.5 * ly - 0.5 * pod_d
    for sx in (-1, 1):
        for sy in (-1, 1):
            parts.append(cyl(pod_d, pod_l, [sx * 0.14, sy * 0.10, 0.06],
                             [np.sqrt(0.5), -sx * sy * np.sqrt(0.5), 0.0]))
            parts.append(cyl(pod_d, pod_l, [sx * 0.12, sy * y_v, -0.055], [0, 0, 1]))
            parts.append(box([0.10, y_v - y_panel + 0.01, 0.0127],
                             [sx * 0.12, sy * 0.5 * (y_v + y_panel), -0.055]))
    return parts


def _bluerov2():
    """The union of :func:`former_bluerov2_parts` (manifold3d; byte for byte the former
    geometry/bluerov2_heavy.stl)."""
    return trimesh.boolean.union(former_bluerov2_parts(), engine="manifold")


#: the bluff set's unions of prisms along x (boxes, 24-sided cylinders): their parts
#: (benchmarks.graded_references unions)
PRISM_PARTS = {"box_skid": box_skid_parts, "l_block": l_block_parts,
               "box_pod_top_aft": box_pod_top_aft_parts, "cyl_float": cyl_float_parts,
               "twin_hull": twin_hull_parts}

#: name -> (builder(faces) -> trimesh, smooth, what it is)
SHAPES = {
    "box_bluerov": (lambda n: _box([0.46, 0.58, 0.25]), False, "box 0.46 x 0.58 x 0.25 m"),
    "box_4_1_1": (lambda n: _box([0.6, 0.15, 0.15]), False, "box 4:1:1 (long in x)"),
    "box_1_4_1": (lambda n: _box([0.15, 0.6, 0.15]), False, "box 1:4:1 (wide)"),
    "box_1_1_4": (lambda n: _box([0.15, 0.15, 0.6]), False, "box 1:1:4 (tall)"),
    "box_2_2_1": (lambda n: _box([0.4, 0.4, 0.2]), False, "box 2:2:1 (flat)"),
    "box_1_2_2": (lambda n: _box([0.2, 0.4, 0.4]), False, "box 1:2:2 (short)"),
    "box_2_1_1": (lambda n: _box([0.4, 0.2, 0.2]), False, "box 2:1:1"),
    "cube": (lambda n: _box([0.3, 0.3, 0.3]), False, "cube 0.3 m"),
    "cyl_x_short": (lambda n: _round_cylinder(0.3, 0.25, "x", n), True,
                    "cylinder along x, L 0.25 D 0.30 m"),
    "cyl_y": (lambda n: _round_cylinder(0.2, 0.5, "y", n), True,
              "cylinder along y, L 0.50 D 0.20 m"),
    "cyl_z_puck": (lambda n: _round_cylinder(0.4, 0.12, "z", n), True,
                   "cylinder along z (puck), D 0.40 H 0.12 m"),
    "sphere": (lambda n: _ellipsoid(0.15, 0.15, 0.15, n), True, "sphere R 0.15 m"),
    "oblate": (lambda n: _ellipsoid(0.2, 0.2, 0.08, n), True, "oblate spheroid 0.2, 0.2, 0.08 m"),
    "triaxial_wide": (lambda n: _ellipsoid(0.15, 0.3, 0.08, n), True,
                      "triaxial ellipsoid 0.15, 0.30, 0.08 m (wide)"),
    "triaxial_long": (lambda n: _ellipsoid(0.3, 0.15, 0.08, n), True,
                      "triaxial ellipsoid 0.30, 0.15, 0.08 m (long)"),
    "open_frame": (lambda n: open_frame(), False, "open frame: 12 tubes, 3 thruster pods"),
    "videoray_like": (lambda n: videoray_like(), False, "VideoRay-like body (asymmetric)"),
    "bluerov2_heavy": (lambda n: _bluerov2(), False,
                       "BlueROV2-Heavy-like frame (the former geometry/bluerov2_heavy.stl)"),
    "box_skid": (lambda n: box_skid(), False, "box 0.40 x 0.30 x 0.20 m, two skids below"),
    "box_pod_top_aft": (lambda n: box_pod_top_aft(), False,
                        "box 0.45 x 0.35 x 0.22 m, cylindrical pod on top aft"),
    "l_block": (lambda n: l_block(), False, "box 0.40 x 0.30 x 0.12 m, raised housing at the front"),
    "cyl_float": (lambda n: cyl_float(), False, "cylinder along x D 0.15 L 0.40 m, float on top forward"),
    "chamfer_box": (lambda n: chamfer_box(), False, "box 0.40 x 0.30 x 0.20 m, front-top edge chamfered"),
    "twin_hull": (lambda n: twin_hull(), False, "two cylinders along x joined by a top plate"),
}

#: semi-axes of the shapes that Lamb solves exactly
ELLIPSOIDS = {"sphere": (0.15, 0.15, 0.15), "oblate": (0.2, 0.2, 0.08),
              "triaxial_wide": (0.15, 0.3, 0.08), "triaxial_long": (0.3, 0.15, 0.08)}


def refine(mesh, faces):
    """Subdivide edges longer than a bound chosen (bisection) for about ``faces`` triangles,
    not more."""
    base = trimesh.Trimesh(mesh.vertices, mesh.faces, process=True)
    if len(base.faces) >= faces:
        return base
    lo, hi = 1e-4, float(np.max(base.edges_unique_length))
    best = base
    for _ in range(18):
        mid = np.sqrt(lo * hi)
        v, f = trimesh.remesh.subdivide_to_size(base.vertices, base.faces, max_edge=mid)
        if len(f) > faces:
            lo = mid
        else:
            hi, best = mid, trimesh.Trimesh(v, f, process=True)
    return best


def shape_mesh(name, faces):
    """The shape at about ``faces`` triangles, centred on its volume centroid."""
    build, smooth, _ = SHAPES[name]
    m = build(faces) if smooth else build(None)
    m = refine(m, faces)
    m.apply_translation(-m.center_mass)
    return m


def strip_mesh(name):
    """The strip-theory input: the shape's own facets, or a fine tessellation of a smooth one."""
    build, smooth, _ = SHAPES[name]
    m = build(STRIP_FACES) if smooth else build(None)
    m = trimesh.Trimesh(m.vertices, m.faces, process=True)
    m.apply_translation(-m.center_mass)
    return m


def make_references(names):
    import capytaine
    from stripcoef.bem import bem_added_mass

    rows = []
    for name in names:
        mats, counts = [], []
        for level in LEVELS:
            m = shape_mesh(name, level)
            t0 = time.perf_counter()
            a = bem_added_mass(m, rho=RHO, reference_point=(0, 0, 0), max_faces=5000)
            dt = time.perf_counter() - t0
            mats.append(a)
            counts.append(len(m.faces))
            print(f"{name:16s} {len(m.faces):5d} faces {dt:6.1f} s  diag "
                  f"{np.array2string(np.diag(a), precision=4)}", flush=True)
        n1, n2 = counts
        rich = (n2 * mats[1] - n1 * mats[0]) / (n2 - n1)
        for i in range(6):
            for j in range(i, 6):
                rows.append([name, i, j, f"{mats[0][i, j]:.8g}", f"{mats[1][i, j]:.8g}",
                             n1, n2, f"{rich[i, j]:.8g}"])
    header = [
        "# BEM added mass of the bluff benchmark shapes (benchmarks/bluff_shapes.py), about the",
        "# volume centroid, body axes FRD, rho = 1000 kg/m^3, units kg, kg m, kg m^2.",
        f"# Source: Capytaine {capytaine.__version__}, method direct, free_surface = inf,",
        "# two resolutions (faces_1, faces_2), Richardson extrapolation assuming error ~ 1/N:",
        "# richardson = (faces_2 a_2 - faces_1 a_1) / (faces_2 - faces_1).",
        f"# Generated {datetime.date.today().isoformat()} by python -m benchmarks.bluff_shapes --reference",
    ]
    old = read_references() if DATA.exists() else {}
    keep = [r for r in _raw_rows() if r[0] not in names] if DATA.exists() else []
    DATA.parent.mkdir(parents=True, exist_ok=True)
    with open(DATA, "w", newline="") as fh:
        fh.write("\n".join(header) + "\n")
        w = csv.writer(fh)
        w.writerow(["shape", "i", "j", "a_1", "a_2", "faces_1", "faces_2", "richardson"])
        w.writerows(keep + rows)
    del old


def _raw_rows():
    with open(DATA) as fh:
        lines = [ln for ln in fh if not ln.startswith("#")]
    return list(csv.reader(lines))[1:]


def read_references(column="richardson"):
    """{shape: 6x6 array} of the stored BEM references (``column``: richardson, a_1 or a_2)."""
    out = {}
    with open(DATA) as fh:
        lines = [ln for ln in fh if not ln.startswith("#")]
    for r in csv.DictReader(lines):
        m = out.setdefault(r["shape"], np.zeros((6, 6)))
        i, j = int(r["i"]), int(r["j"])
        m[i, j] = m[j, i] = float(r[column])
    return out


def reference_source(name) -> str:
    """Where :func:`reference_matrix` takes the shape's reference from (a file and how; the
    graded file's band of the diagonal, its largest relative term)."""
    from validation.graded_bodies import bluff_sources

    graded = bluff_sources()
    if name in graded:
        ref, band, path = graded[name]
        d = np.diag(ref)
        on = d > 1e-9 * d.max()
        return (f"{path} (Eca & Hoekstra over edge-graded levels; diagonal band up to "
                f"{100 * np.max(np.diag(band)[on] / d[on]):.2g} %)")
    source = "reference_tables/bem/bem_bluff.csv (richardson)"
    if name in ELLIPSOIDS:
        source += "; diagonal: Lamb (stripcoef.hull.lamb.ellipsoid_added_mass)"
    return source


def reference_matrix(name, refs=None):
    """The reference M_A of a shape: the stored Richardson BEM (``refs``, default
    :func:`read_references`), with Lamb's exact diagonal for the ellipsoids
    (:func:`stripcoef.hull.lamb.ellipsoid_added_mass`), and the edge-graded Capytaine matrix
    for the boxes, the chamfered box and the unions of prisms (box_skid, l_block,
    box_pod_top_aft, cyl_float, twin_hull) (:func:`validation.graded_bodies.bluff_references`:
    Eça & Hoekstra over four or five graded levels, bands 0.1-0.8 % but for the roll of the
    long boxes about their long axis (2-5.5 %), where the stored two-level Richardson at
    order 2 is up to 5.0 % off: benchmarks/data/graded_value_order.md,
    benchmarks/data/graded_bias.md) [kg, kg m, kg m^2]."""
    from stripcoef.hull.lamb import ellipsoid_added_mass
    from validation.graded_bodies import bluff_references

    ref = (read_references() if refs is None else refs)[name].copy()
    if name in ELLIPSOIDS:
        ref[np.diag_indices(6)] = ellipsoid_added_mass(*ELLIPSOIDS[name], rho=RHO)
    graded = bluff_references()
    if name in graded:
        ref = graded[name][0].copy()
    return ref


def _reference_note(names) -> str:
    """Which reference each shape of ``names`` is compared with, and the graded ones' bands
    (the accuracy tables' note)."""
    from validation.graded_bodies import bluff_sources

    graded = {k: v for k, v in bluff_sources().items() if k in names}
    note = "Richardson BEM (bem_bluff.csv); ellipsoid diagonals: Lamb exact"
    if graded:
        bands = [band[i, i] / ref[i, i] for ref, band, _ in graded.values() for i in range(6)]
        files = sorted({p.split("/")[-1] for _, _, p in graded.values()})
        note = (f"edge-graded Capytaine for {len(graded)} shapes ({', '.join(files)}; "
                f"Eça & Hoekstra, diagonal bands {100 * min(bands):.2f}-{100 * max(bands):.1f} %"
                f", median {100 * float(np.median(bands)):.2f} %), otherwise " + note)
    return note


def strip_matrix(name, corrections=True):
    """Strip-theory M_A of the shape about its centroid, and the wall time of estimate() [s]."""
    from stripcoef.assembly.estimate import estimate
    from stripcoef.fluid import Fluid
    from stripcoef.geometry.vehicle import Vehicle

    m = strip_mesh(name)
    veh = Vehicle.from_mesh(m, name=name, fluid=Fluid(density=RHO, kinematic_viscosity=1e-6,
                                                       source="benchmark"))
    t0 = time.perf_counter()
    model = estimate(veh, corrections=corrections, added_mass_method="strips")
    return np.asarray(model.added_mass), time.perf_counter() - t0


#: cyclic axis maps of load_mesh: body = P mesh
_PERM = {"x": np.eye(3), "y": np.array([[0., 1, 0], [0, 0, 1], [1, 0, 0]]),
         "z": np.array([[0., 0, 1], [1, 0, 0], [0, 1, 0]])}


def axis_matrix(name, axis):
    """M_A of the shape sliced along the mesh ``axis``, rotated back to the mesh axes
    (M_mesh = T^T M_body T, T = diag(P, P)), about the centroid [kg, kg m, kg m^2]."""
    from stripcoef.assembly.estimate import estimate
    from stripcoef.fluid import Fluid
    from stripcoef.geometry.vehicle import Vehicle

    veh = Vehicle.from_mesh(strip_mesh(name), name=name, axis=axis,
                            fluid=Fluid(density=RHO, kinematic_viscosity=1e-6, source="benchmark"))
    t = np.kron(np.eye(2), _PERM[axis])
    return t.T @ np.asarray(estimate(veh, added_mass_method="strips").added_mass) @ t


def round_axis(mesh):
    """The axis (0, 1, 2) about which the mesh's mid-section is a circle -- equal extents across
    it and the section's area pi/4 of its bounding square within 1 % -- else None."""
    e = np.ptp(mesh.vertices, axis=0)
    c = 0.5 * (mesh.vertices.min(axis=0) + mesh.vertices.max(axis=0))
    for a in range(3):
        k, m = [b for b in range(3) if b != a]
        if abs(e[k] - e[m]) > 0.01 * max(e[k], e[m]):
            continue
        sec = mesh.section(plane_origin=c, plane_normal=np.eye(3)[a])
        if sec is None:
            continue
        area = sum(p.area for p in sec.to_2D()[0].polygons_full)
        if abs(area / (0.25 * np.pi * e[k] * e[m]) - 1.0) < 0.01:
            return a
    return None


def per_dof_axes(extent, round_about=None):
    r"""Candidate (measured, not adopted): the slicing axis of each DOF by slenderness.

    A body of revolution (``round_about``, :func:`round_axis`) is sliced along its axis for
    every DOF (its equivalent bodies of revolution are itself: exact there). Otherwise:
    translation along j, the largest of L_j / max(L_k, L_m) (axial: the equal-area body along
    j), L_k / L_m and L_m / L_k (sections moving across j, their 2D width the third extent);
    rotation about j, the largest of L_j / max(L_k, L_m) (sections rolling), L_k / L_j and
    L_m / L_j (sections translating across j, their 2D width L_j). Strip theory along an axis
    is the slender-body limit about it (Newman 1977, sec. 7.4): the larger the ratio, the
    closer to 2D the flow of the sections. ``extent`` (L_x, L_y, L_z) [m]."""
    e = np.asarray(extent, float)
    if round_about is not None:     # a body of revolution: its equivalent bodies are its own
        return ["xyz"[round_about]] * 6
    out = []
    for j in range(3):
        k, m = [a for a in range(3) if a != j]
        cand = {j: e[j] / max(e[k], e[m]), k: e[k] / e[m], m: e[m] / e[k]}
        out.append(max(cand, key=cand.get))
    for j in range(3):
        k, m = [a for a in range(3) if a != j]
        cand = {j: e[j] / max(e[k], e[m]), k: e[k] / e[j], m: e[m] / e[j]}
        out.append(max(cand, key=cand.get))
    return ["xyz"[a] for a in out]


def per_dof_matrix(name):
    """Candidate per-DOF combination of the three slicings (:func:`per_dof_axes`): row/column i
    of DOF i from its axis' matrix, couplings from the axis of the larger diagonal pair."""
    mesh = strip_mesh(name)
    axes = per_dof_axes(np.ptp(mesh.vertices, axis=0), round_axis(mesh))
    t0 = time.perf_counter()
    mats = {a: axis_matrix(name, a) for a in set(axes)}
    out = np.zeros((6, 6))
    for i in range(6):
        for j in range(6):
            out[i, j] = mats[axes[i] if i == j or axes[i] == axes[j] else axes[min(i, j)]][i, j]
    return 0.5 * (out + out.T), time.perf_counter() - t0


def panel_matrix(name, panels=None):
    """M_A of the shape by the 3D panel method (stripcoef.hull.panels, Richardson from two
    resolutions) from the strip-theory input mesh (loaded and repaired as the CLI does), and
    its wall time [s] (panelling and solves; the repair excluded)."""
    from stripcoef.geometry.mesh import mesh_body
    from stripcoef.hull.panels import DEFAULT_PANELS, panel_added_mass

    body = mesh_body(strip_mesh(name), name=name)
    t0 = time.perf_counter()
    a, info = panel_added_mass(body, rho=RHO, panels=panels or DEFAULT_PANELS)
    return a, time.perf_counter() - t0, info


def bem_equal_accuracy(name, error, ref):
    """Capytaine (direct) at the resolution whose error equals ``error`` (worst relative
    diagonal error, [-]), from its stored first-level error e_1 at N_1 faces and the 1/N law:
    N = N_1 e_1 / error. Returns (N asked, faces solved, wall time [s], its worst diagonal
    error [-]); None when N exceeds the 5000 faces of one solve (no extrapolated time)."""
    from stripcoef.bem import bem_added_mass

    a1 = read_references("a_1")[name]
    n1 = int(_faces(name)[0])
    e1 = np.max(np.abs(np.diag(a1) - np.diag(ref))[np.diag(ref) > 1e-6 * np.diag(ref).max()]
                / np.diag(ref)[np.diag(ref) > 1e-6 * np.diag(ref).max()])
    n = int(np.ceil(n1 * e1 / max(error, 1e-9)))
    if n > 5000:
        return n, None, None, None
    m = shape_mesh(name, n)
    t0 = time.perf_counter()
    a = bem_added_mass(m, rho=RHO, reference_point=(0, 0, 0), max_faces=5000)
    dt = time.perf_counter() - t0
    d = np.diag(ref)
    ok = d > 1e-6 * d.max()
    return n, len(m.faces), dt, float(np.max(np.abs(np.diag(a)[ok] / d[ok] - 1.0)))


def _faces(name):
    for r in _raw_rows():
        if r[0] == name:
            return int(r[5]), int(r[6])
    raise KeyError(name)


def significant_terms(ref):
    """Diagonal terms and the off-diagonals with |A_ij| >= SIGNIFICANT sqrt(A_ii A_jj)."""
    d = np.abs(np.diag(ref))
    out = [(i, i) for i in range(6) if d[i] > 1e-6 * d.max()]
    for i in range(6):
        for j in range(i + 1, 6):
            if abs(ref[i, j]) >= SIGNIFICANT * np.sqrt(d[i] * d[j]) and d[i] * d[j] > 0:
                out.append((i, j))
    return out


def errors(strip, ref):
    """{(i, j): error} -- diagonal: relative [-]; off-diagonal: (strip - ref) / sqrt(A_ii A_jj)."""
    out = {}
    d = np.abs(np.diag(ref))
    for i, j in significant_terms(ref):
        if i == j:
            out[(i, j)] = (strip[i, i] - ref[i, i]) / ref[i, i]
        else:
            out[(i, j)] = (strip[i, j] - ref[i, j]) / np.sqrt(d[i] * d[j])
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--reference", action="store_true", help="recompute the BEM references")
    ap.add_argument("--only", nargs="*", help="shapes (default all)")
    ap.add_argument("--no-corrections", action="store_true")
    ap.add_argument("--write", action="store_true",
                    help="also write benchmarks/data/bluff_accuracy_<mode>.md")
    ap.add_argument("--per-dof-axes", action="store_true",
                    help="candidate: each DOF from the slicing axis of per_dof_axes()")
    ap.add_argument("--method", choices=("strips", "panels"), default="strips",
                    help="panels: the 3D panel method (stripcoef.hull.panels)")
    ap.add_argument("--panels", type=int, default=None, help="panels of the finer resolution")
    ap.add_argument("--bem-timing", action="store_true",
                    help="with --method panels: time Capytaine at the panel method's accuracy")
    args = ap.parse_args(argv)
    names = args.only or list(SHAPES)
    if args.reference:
        make_references(names)
        return 0
    refs = read_references()
    worst_d, worst_o, times, ratios = 0.0, 0.0, [], []
    head = "| shape | " + " | ".join(TERM_NAMES) + " | off-diagonals (of diag. scale) | time [s] |"
    ncol = 9
    if args.method == "panels":
        head += " panels N1/N2 |"
        ncol += 1
        if args.bem_timing:
            head += " Capytaine at equal accuracy (faces, worst diag. error, time) | speed ratio |"
            ncol += 2
    lines = [head, "|---" * ncol + "|"]
    for name in names:
        ref = reference_matrix(name, refs)
        info = None
        if args.method == "panels":
            a, dt, info = panel_matrix(name, args.panels)
        elif args.per_dof_axes:
            a, dt = per_dof_matrix(name)
        else:
            a, dt = strip_matrix(name, corrections=not args.no_corrections)
        times.append(dt)
        err = errors(a, ref)
        cells = []
        for i in range(6):
            e = err.get((i, i))
            cells.append("0 (0)" if e is None else f"{100 * e:+.1f} %")
            if e is not None:
                worst_d = max(worst_d, abs(e))
        offs = []
        for (i, j), e in err.items():
            if i != j:
                offs.append(f"{TERM_NAMES[i][0]}{TERM_NAMES[j][2:]}: {100 * e:+.1f} %")
                worst_o = max(worst_o, abs(e))
        extra = ""
        if info is not None:
            extra = f" | {info['panels'][0]}/{info['panels'][1]}"
            if args.bem_timing:
                worst = max(abs(e) for (i, j), e in err.items() if i == j)
                n, nf, bt, be = bem_equal_accuracy(name, worst, ref)
                extra += (f" | N {n} > 5000: not run | -" if nf is None else
                          f" | {nf} faces, {100 * be:.1f} %, {bt:.2f} s | {bt / dt:.2f}")
                if nf is not None:
                    ratios.append(bt / dt)
        lines.append(f"| {name} | " + " | ".join(cells) + f" | {'; '.join(offs) or '-'} | {dt:.3f}"
                     + extra + " |")
    summary = (f"worst diagonal {100 * worst_d:.1f} %, worst off-diagonal {100 * worst_o:.1f} % "
               f"of the diagonal scale, median wall time {np.median(times):.3f} s "
               f"(reference: {_reference_note(names)})")
    if ratios:
        summary += (f"; Capytaine at equal accuracy / panel method: median {np.median(ratios):.2f}x, "
                    f"range {min(ratios):.2f}-{max(ratios):.2f}x over {len(ratios)} shapes")
    print("\n".join(lines) + "\n\n" + summary)
    if args.write:
        mode = "per_dof_axes" if args.per_dof_axes else \
            ("no_corrections" if args.no_corrections else "default")
        if args.method == "panels":
            mode = "panels"
        flag = {"default": "", "per_dof_axes": " --per-dof-axes",
                "no_corrections": " --no-corrections",
                "panels": " --method panels" + (" --bem-timing" if args.bem_timing else "")
                + (f" --panels {args.panels}" if args.panels else "")}[mode]
        out = ROOT / "benchmarks" / "data" / f"bluff_accuracy_{mode}.md"
        out.write_text(f"### {TITLES[mode]}\n\n`OPENBLAS_NUM_THREADS=1 python "
                       f"-m benchmarks.bluff_shapes{flag} --write` "
                       f"({datetime.date.today().isoformat()}). Diagonal: relative error; "
                       f"off-diagonal: error / sqrt(A_ii A_jj) of the reference.\n\n"
                       + "\n".join(lines) + "\n\n" + summary + "\n")
    return 0


TITLES = {"default": "strip theory (slicing along x, 3D corrections; `--added-mass-method strips`)",
          "no_corrections": "pure strip theory (slicing along x)",
          "per_dof_axes": "candidate, not adopted: each DOF from the slicing axis chosen by "
                          "slenderness (per_dof_axes)",
          "panels": "3D panel method (stripcoef.hull.panels: direct method, constant "
                    "triangles, Richardson from two resolutions)"}


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

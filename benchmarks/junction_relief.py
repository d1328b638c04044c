"""3D survival of the 2D added mass of short rings: axisymmetric tubes and a short frame junction.

Run:  .venv/bin/python -m benchmarks.junction_relief tubes     (about 1 minute, < 1 GB)
      .venv/bin/python -m benchmarks.junction_relief frames    (a few minutes, ~3 GB)

tubes:  transverse and axial added mass of short circular tubes (length l, bore r_i, outer r_o)
        from stripcoef.hull.corrections.ring_body_added_mass against Capytaine on a
        RotationSymmetricMesh of the same tube (direct method, no free surface), and the ratio
        to the 2D annulus rho pi (r_o^2 + r_i^2) l.
frames: frames with short posts (a closed "ladder" and an open "arch", not the ROV), BEM with
        and without the posts against strip theory (stripcoef.assembly.estimate.estimate): what the
        posts add.
smallbody: each post as a small body in the members' 3D flow (main_smallbody).
rings:  a short square ring alone (main_rings): BEM against its equivalent bodies.
      .venv/bin/python -m benchmarks.junction_relief smallbody (about 1 minute, ~2 GB)
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import logging
import sys
import time

import numpy as np

from stripcoef.hull.corrections import ring_body_added_mass

RHO = 1000.0


def _profile(l, ri, ro, n_len, n_wall):
    """Closed (r, z) profile of a tube wall, counter-clockwise (Capytaine's outward normals)."""
    def seg(a, b, n):
        t = 0.5 * (1.0 - np.cos(np.pi * np.arange(n) / n))
        return a[None, :] + t[:, None] * (b - a)[None, :]
    c = [np.array(p, float) for p in ((ro, -l / 2), (ro, l / 2), (ri, l / 2), (ri, -l / 2))]
    pts = np.vstack([seg(c[0], c[1], n_len), seg(c[1], c[2], n_wall),
                     seg(c[2], c[3], n_len), seg(c[3], c[0], n_wall), c[0][None, :]])
    return pts


def capytaine_tube(l, ri, ro, n_len=40, n_wall=16, n_circ=64):
    """Capytaine on a tube about its axis (Capytaine's z = our x): our [m11, m22, m66 about the
    centre]."""
    import capytaine as cpt
    logging.getLogger("capytaine").setLevel(logging.ERROR)
    prof = _profile(l, ri, ro, n_len, n_wall)
    pts = np.column_stack([prof[:, 0], np.zeros(len(prof)), prof[:, 1]])
    c, s = np.cos(2 * np.pi / n_circ), np.sin(2 * np.pi / n_circ)
    rot = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    n = len(pts)
    verts = np.concatenate([pts, pts @ rot.T])
    faces = np.array([(i, i + n, i + n + 1, i + 1) for i in range(n - 1)])
    mesh = cpt.RotationSymmetricMesh(wedge=cpt.Mesh(vertices=verts, faces=faces), n=n_circ)
    body = cpt.FloatingBody(mesh=mesh, dofs=cpt.rigid_body_dofs(rotation_center=(0, 0, 0)))
    dofs = ("Heave", "Surge", "Pitch")
    pbs = [cpt.RadiationProblem(body=body, radiating_dof=d, free_surface=np.inf, omega=np.inf,
                                rho=RHO) for d in dofs]
    res = cpt.BEMSolver(method="direct").solve_all(pbs, progress_bar=False)
    return np.array([res[k].added_mass[d] for k, d in enumerate(dofs)]), (n - 1) * n_circ


def main_tubes():
    ro = 0.3
    print("| r_i/r_o | l/(2 r_i) | ours m22 / 2D | Capytaine m22 / 2D | diff | ours m11 | Capytaine m11 "
          "| ours m66 | Capytaine m66 | faces | s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for ri in (0.15, 0.24, 0.27):
        for lr in (0.1, 0.25, 0.5, 1.0, 2.0):
            l = lr * 2 * ri
            ours = ring_body_added_mass([-l / 2, l / 2, l / 2, -l / 2], [ri, ri, ro, ro], rho=RHO)
            t0 = time.perf_counter()
            ref, faces = capytaine_tube(l, ri, ro)
            sec = time.perf_counter() - t0
            m2d = RHO * np.pi * (ro ** 2 + ri ** 2) * l
            print(f"| {ri / ro:.2f} | {lr:.2f} | {ours[1, 1] / m2d:.4f} | {ref[1] / m2d:.4f} | "
                  f"{100 * (ours[1, 1] - ref[1]) / ref[1]:+.2f} % | {ours[0, 0]:.4g} | {ref[0]:.4g} | "
                  f"{ours[5, 5]:.4g} | {ref[2]:.4g} | {faces} | {sec:.1f} |", flush=True)


# --- frames: boxes with two reflection symmetries (y = 0 and x = 0), given by their quarter --

def _box(lo, hi):
    import trimesh
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    return trimesh.creation.box(hi - lo, transform=trimesh.transformations.translation_matrix(
        0.5 * (lo + hi)))


def full_mesh(quarter_boxes):
    """The whole body: each quarter box (x >= 0, y >= 0) mirrored in x = 0 and y = 0, unioned."""
    import trimesh
    boxes = []
    for lo, hi in quarter_boxes:
        xs = [(-hi[0], hi[0])] if lo[0] == 0 else [(lo[0], hi[0]), (-hi[0], -lo[0])]
        ys = [(-hi[1], hi[1])] if lo[1] == 0 else [(lo[1], hi[1]), (-hi[1], -lo[1])]
        for x0, x1 in xs:
            for y0, y1 in ys:
                boxes.append(_box([x0, y0, lo[2]], [x1, y1, hi[2]]))
    return trimesh.boolean.union(boxes, engine="manifold")


def quarter_mesh(quarter_boxes, max_edge):
    """The x >= 0, y >= 0 quarter, open on x = 0 and y = 0, edges <= ``max_edge`` [m]."""
    import trimesh
    q = trimesh.boolean.union([_box(lo, hi) for lo, hi in quarter_boxes], engine="manifold")
    c, n = q.triangles_center, q.face_normals
    cut = ((np.abs(c[:, 0]) < 1e-9) & (n[:, 0] < -0.99)) | \
        ((np.abs(c[:, 1]) < 1e-9) & (n[:, 1] < -0.99))
    q.update_faces(~cut)
    q.remove_unreferenced_vertices()
    v, f = trimesh.remesh.subdivide_to_size(q.vertices, q.faces, max_edge=max_edge)
    return trimesh.Trimesh(v, f, process=True)


def bem_quarter(quarter_boxes, max_edge):
    """Capytaine (two reflection symmetries, direct, no free surface) about the origin."""
    from benchmarks.mesh_reference_convergence import capytaine_quarter
    q = quarter_mesh(quarter_boxes, max_edge)
    a, sec = capytaine_quarter(q, (0.0, 0.0, 0.0))
    return a, 4 * len(q.faces), sec


def strip_model(quarter_boxes, strips=200):
    """stripcoef.assembly.estimate.estimate (as shipped) on the whole body, about the origin."""
    import warnings

    from stripcoef.conventions import transform_matrix
    from stripcoef.fluid import Fluid
    from stripcoef.geometry.mesh import mesh_body
    from stripcoef.geometry.vehicle import MassSpec, Vehicle
    from stripcoef.assembly.estimate import estimate
    body = mesh_body(full_mesh(quarter_boxes), origin="file", name="frame")
    v = Vehicle(name="frame", source="benchmark", hull=None, bodies=[body], holes=[],
                fluid=Fluid(density=RHO, kinematic_viscosity=1e-6, source="benchmark"),
                mass=MassSpec(), thrusters=[], reference="center_of_buoyancy")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m = estimate(v, strips=strips)
    return transform_matrix(m.added_mass, from_point=m.reference_point, to_point=(0, 0, 0))


def section_2d(quarter_boxes, x):
    """2D added mass (sway, heave, roll about the origin) of the whole body's section at x."""
    import shapely
    from shapely.geometry import box
    from shapely.geometry.polygon import orient

    from stripcoef.sections.panel import added_mass_sections
    polys = []
    for lo, hi in quarter_boxes:
        if lo[0] - 1e-12 <= abs(x) <= hi[0] + 1e-12 or (lo[0] == 0 and abs(x) <= hi[0]):
            for s in (1, -1):
                y0, y1 = sorted((s * lo[1], s * hi[1]))
                polys.append(box(y0, lo[2], y1, hi[2]))
    geom = shapely.union_all(polys)
    rings = []
    for g in getattr(geom, "geoms", [geom]):
        g = orient(g, 1.0)
        rings.append(np.asarray(g.exterior.coords)[:-1])
        rings.extend(np.asarray(h.coords)[:-1] for h in g.interiors)
    return added_mass_sections([rings], rho=RHO, about=np.zeros((1, 2)))[0], geom


# Test frames (not the ROV), quarter boxes (lo, hi) [m]: members along x and short crossing
# posts (length 0.06 along x) at x = +-0.3
LADDER_BARS = [((0, 0, -0.30), (0.5, 0.30, -0.18)), ((0, 0, 0.18), (0.5, 0.30, 0.30))]
LADDER_POSTS = [((0.27, 0.24, -0.18), (0.33, 0.30, 0.18))]
ARCH_MEMBERS = [((0, 0, -0.25), (0.40, 0.25, -0.13)), ((0, 0.17, 0.13), (0.45, 0.27, 0.25))]
ARCH_POSTS = [((0.27, 0.19, -0.13), (0.33, 0.25, 0.13))]


def main_frames(max_edge=0.04):
    dof = ("surge", "sway", "heave", "roll", "pitch", "yaw")
    for name, members, posts in (("ladder (closed ring at the posts)", LADDER_BARS, LADDER_POSTS),
                                 ("arch (open ring at the posts)", ARCH_MEMBERS, ARCH_POSTS)):
        m2d_j, geom = section_2d(members + posts, 0.3)
        m2d_m, _ = section_2d(members, 0.3)
        holes = sum(len(g.interiors) for g in getattr(geom, "geoms", [geom]))
        print(f"\n{name}: 2D at the posts (x = 0.3), holes {holes}: joint sway {m2d_j[0, 0]:.1f}, "
              f"heave {m2d_j[1, 1]:.1f} kg/m; members sway {m2d_m[0, 0]:.1f}, heave "
              f"{m2d_m[1, 1]:.1f} kg/m; excess x 0.06 m x 2 junctions: sway "
              f"{2 * 0.06 * (m2d_j[0, 0] - m2d_m[0, 0]):.2f} kg, heave "
              f"{2 * 0.06 * (m2d_j[1, 1] - m2d_m[1, 1]):.2f} kg", flush=True)
        full, nf, s1 = bem_quarter(members + posts, max_edge)
        base, nb, s2 = bem_quarter(members, max_edge)
        sf, sb = strip_model(members + posts), strip_model(members)
        print(f"BEM {nf} / {nb} faces ({s1:.0f} s / {s2:.0f} s), about the origin")
        print("| term | BEM with posts | BEM without | posts add (BEM) | strip with | strip without "
              "| posts add (strip) | with: strip vs BEM |")
        print("|---|---|---|---|---|---|---|---|")
        for i in range(6):
            print(f"| {dof[i]} | {full[i, i]:.4g} | {base[i, i]:.4g} | {full[i, i] - base[i, i]:.4g} | "
                  f"{sf[i, i]:.4g} | {sb[i, i]:.4g} | {sf[i, i] - sb[i, i]:.4g} | "
                  f"{100 * (sf[i, i] - full[i, i]) / full[i, i]:+.2f} % |", flush=True)


def main_rings(max_edge=0.04):
    """A short square ring (outer 0.6 m, wall 0.06 m, length l along x) moving in its own
    plane: the BEM against 2D x l and the equivalent bodies of revolution of the section."""
    from stripcoef.hull.corrections import body_of_revolution_added_mass
    print("| l [m] | faces | BEM m22 / (2D l) | disc | hollow, r_o from 2D | hollow, r_o from outer area "
          "| estimate: sway, heave, pitch, surge vs BEM |")
    print("|---|---|---|---|---|---|---|")
    for l in (0.03, 0.06, 0.12, 0.3, 0.6):
        boxes = [((0, 0, -0.3), (l / 2, 0.3, -0.24)), ((0, 0, 0.24), (l / 2, 0.3, 0.3)),
                 ((0, 0.24, -0.24), (l / 2, 0.3, 0.24))]
        m2d, geom = section_2d(boxes, 0.0)
        hole = sum(sum(abs(g.area) for g in [type(p)(h) for h in p.interiors])
                   for p in getattr(geom, "geoms", [geom]))
        a, faces, _ = bem_quarter(boxes, max_edge)
        strip = m2d[0, 0] * l
        r = np.sqrt(m2d[0, 0] / (RHO * np.pi))
        disc = body_of_revolution_added_mass([-l / 2, l / 2], [r, r], rho=RHO)[1, 1]
        ri = np.sqrt(hole / np.pi)
        ro = np.sqrt(m2d[0, 0] / (RHO * np.pi) - ri * ri)
        t1 = ring_body_added_mass([-l / 2, l / 2, l / 2, -l / 2], [ri, ri, ro, ro], rho=RHO)[1, 1]
        ro2 = np.sqrt(0.36 / np.pi)
        t2 = ring_body_added_mass([-l / 2, l / 2, l / 2, -l / 2], [ri, ri, ro2, ro2], rho=RHO)[1, 1]
        f2 = t2 / (RHO * np.pi * (ro2 ** 2 + ri ** 2) * l)
        est = strip_model(boxes)
        errs = ", ".join(f"{100 * (est[i, i] - a[i, i]) / a[i, i]:+.1f} %" for i in (1, 2, 4, 0))
        print(f"| {l} | {faces} | {a[1, 1] / strip:.4f} | {disc / strip:.4f} | {t1 / strip:.4f} | "
              f"{f2:.4f} | {errs} |", flush=True)


# the ROV's float, pontoons and posts (benchmarks/mesh_shapes.open_frame_rov), by quarter
ROV_MEMBERS = [((0, 0, -0.275), (0.45, 0.3, -0.125)), ((0, 0.23, 0.125), (0.5, 0.35, 0.275))]
ROV_POSTS = [((0.35, 0.24, -0.125), (0.41, 0.30, 0.125))]


def main_smallbody(max_edge=0.04):
    r"""Each post as a small body in the members' 3D flow (a check of the junction model).

    With u the fluid velocity (per unit body velocity in DOF d) of the frame *without* posts
    at the post's place, a post of cross-section A' and 2D cross-flow added mass m' per unit
    length (axis z: none along it) adds, over its height h,

    .. math:: \Delta M_{dd} = h\,\overline{m'[(\delta_{dx} - u_x)^2 + (\delta_{dy} - u_y)^2]
              - \rho A'|u|^2}

    (kinetic energy of a small body in a locally uniform flow: its own added mass on the
    relative velocity, less the moving water it displaces; Taylor 1928, Proc. R. Soc. A 120,
    "The forces on a body placed in a curved or converging stream of fluid"; exact limits: u = 0
    gives m', a body in rigidly moving bore water u = e_d gives -rho A').  m' = 4.754 rho a^2
    for a square of half-side a (DNV-RP-H103 (2011) table A-1).  u from Capytaine's indirect
    method (source distribution) at 3 x 3 x 8 points per post, averaged.
    """
    import capytaine as cpt
    logging.getLogger("capytaine").setLevel(logging.ERROR)
    print("| frame | DOF | mean u at the post (x, y, z) | post's own m' h (4 posts) | small-body estimate (4 posts) |")
    print("|---|---|---|---|---|")
    for name, members, posts in (("arch", ARCH_MEMBERS, ARCH_POSTS), ("ladder", LADDER_BARS, LADDER_POSTS),
                                 ("ROV", ROV_MEMBERS, ROV_POSTS)):
        q = quarter_mesh(members, max_edge)
        m = cpt.Mesh(vertices=np.asarray(q.vertices, float), faces=np.asarray(q.faces, int))
        mesh = cpt.ReflectionSymmetricMesh(half=cpt.ReflectionSymmetricMesh(half=m, plane="xOz"),
                                           plane="yOz")
        body = cpt.FloatingBody(mesh=mesh, dofs=cpt.rigid_body_dofs(rotation_center=(0, 0, 0)))
        solver = cpt.BEMSolver(method="indirect")
        dofs = ("Surge", "Sway", "Heave")
        # omega plays no role without a free surface (a finite one keeps the results numeric)
        res = solver.solve_all([cpt.RadiationProblem(body=body, radiating_dof=d, free_surface=np.inf,
                                                     omega=1.0, rho=RHO) for d in dofs],
                               progress_bar=False)
        (lo, hi), = posts
        lo, hi = np.array(lo, float), np.array(hi, float)
        g = [lo[i] + (np.arange(n) + 0.5) / n * (hi[i] - lo[i]) for i, n in enumerate((3, 3, 8))]
        pts = np.array([(x, y, z) for x in g[0] for y in g[1] for z in g[2]])
        a, h = 0.5 * (hi[0] - lo[0]), hi[2] - lo[2]
        area = (hi[0] - lo[0]) * (hi[1] - lo[1])
        mprime = 4.754 * RHO * a * a
        normals = np.asarray(body.mesh.merged().faces_normals)
        for k, d in enumerate(dofs):
            bc = np.asarray(res[k].problem.boundary_condition)
            f = int(np.argmax(np.abs(normals[:, k])))
            u = np.real(np.asarray(solver.compute_velocity(pts, res[k])) / (bc[f] / normals[f, k]))
            e = np.zeros(3)
            e[k] = 1.0
            rel = e[None, :] - u
            per_len = mprime * (rel[:, 0] ** 2 + rel[:, 1] ** 2) - RHO * area * np.sum(u ** 2, axis=1)
            own = 4 * h * mprime * (1.0 if k < 2 else 0.0)
            print(f"| {name} | {d} | {np.array2string(u.mean(0), precision=3)} | {own:.2f} | "
                  f"{4 * h * per_len.mean():.2f} |", flush=True)


if __name__ == "__main__":
    what = sys.argv[1] if len(sys.argv) > 1 else "tubes"
    {"tubes": main_tubes, "frames": main_frames, "smallbody": main_smallbody,
     "rings": main_rings}[what]()

"""Thin plates' added mass with panels graded towards the edges: independent references for the
CAD benchmark's plates (issue 32).

The CAD benchmark's plate references (benchmarks/cad_shapes.py, Capytaine on isotropic
remeshes up to 3,000 faces; benchmarks/bem_fine_references.py up to 14,000 faces) converge
slowly on a thin plate's in-plane terms: the flow round a sharp edge of interior angle
pi/2 (a box) has a velocity singular as r^(-1/3) (the wedge potential r^(pi/alpha)
cos(pi theta/alpha), alpha = 3 pi/2; Newman 1977 sec. 4.4), and panels of uniform size h
resolve it at an error of order h^(2/3) to h (von Petersdorff & Stephan 1990).  Here the
same solver (Capytaine 3.0, direct method, no free surface; Ancellin & Dias 2019) solves
structured quadrilateral meshes whose nodes are spaced as x_k = L sin(pi k / (2 m)) on each
half-edge L (k = 0..m): the panel next to an edge has the width L pi^2 / (8 m^2), the
square of the uniform one (the cosine spacing of the lifting-surface literature, e.g.
Katz & Plotkin 2001 sec. 12.1), so that an edge's singular flow is resolved at a rate near
the smooth body's.  The three mirror planes of a box or a disc are used
(an eighth built, mirrored in z, and its quarter solved with
``cpt.ReflectionSymmetricMesh`` on the two vertical planes Capytaine 3.0 takes).  Each term is
extrapolated from five or more levels by Eça & Hoekstra's least squares
(:func:`validation.cad_shapes.fine_reference`, h ~ N^(-1/2)).

Checks of the procedure against exact results (``--checks``):

- the thin circular disc of radius a: A_33 = 8/3 rho a^3 and, about a diameter,
  A_44 = A_55 = 16/45 rho a^5 (Lamb 1932, Hydrodynamics, art. 108; Kochin, Kibel & Roze
  1964; Newman 1977 table 4.3), the in-plane terms A_11 = A_22 = A_66 -> 0; the disc is
  a cylinder of thickness t, extrapolated to t -> 0 as in benchmarks/plate_added_mass.py
  (linear in t from t/a = 0.04 and 0.02, :data:`THICKNESS`);
- rectangular plates a x b moving normal to themselves: DNV-RP-H103 table A-2
  (reference_tables/dnv_rp_c205/table_a2_plates_3d.csv), lambda = A_33 / (rho pi/4 a^2 b),
  at the CAD plates' own aspect ratios, extrapolated in thickness the same way.

Usage (from the repository root; each run well under 15 min on one core):

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.plate_graded --checks --levels 8 11 16 23 \\
        --checks-csv reference_tables/bem/plates_graded_checks.csv
    OPENBLAS_NUM_THREADS=1 python -m benchmarks.plate_graded --seed 1375923287 --count 40 \\
        --csv reference_tables/bem/cad_plates_graded.csv

The second writes one row per (plate, level, diagonal term) of the seed's plates (the CAD
benchmark's draws repeated: :func:`plates_of_seed`); ``validation.cad_shapes`` reads it.
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

RHO = 1000.0
#: panels on the longest half-edge of the plate's face, one level each (faces of the whole
#: plate about 8 (m m_short + m_t (m + m_short)))
LEVELS = (8, 11, 16, 23, 32)
DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")
#: the checks' thicknesses t/a, thick to thin: the value at t -> 0 is 2 f(t/2) - f(t), the
#: error linear in t removed (benchmarks/plate_added_mass.py)
THICKNESS = (0.04, 0.02)


def graded_nodes(half: float, m: int) -> np.ndarray:
    """m + 1 nodes on [0, half], x_k = half sin(pi k / (2 m)): uniform near the mirror plane
    (0), the square of the uniform spacing next to the edge (half) [m]."""
    return half * np.sin(0.5 * np.pi * np.arange(m + 1) / m)


def cosine_nodes(length: float, n: int) -> np.ndarray:
    """n + 1 nodes on [0, length] graded towards both ends, x_k = length (1 - cos(pi k/n))/2:
    :func:`graded_nodes` on each half [m]."""
    return 0.5 * length * (1.0 - np.cos(np.pi * np.arange(n + 1) / n))


def _grid(p0, du, dv, u, v):
    """Quadrilaterals of the grid p0 + u_i du + v_j dv (u, v node arrays; du, dv unit
    vectors), vertices and faces, ordered so that du x dv is the outward normal."""
    uu, vv = np.meshgrid(u, v, indexing="ij")
    pts = p0 + uu[..., None] * du + vv[..., None] * dv
    nu, nv = len(u), len(v)
    idx = np.arange(nu * nv).reshape(nu, nv)
    faces = np.stack([idx[:-1, :-1], idx[1:, :-1], idx[1:, 1:], idx[:-1, 1:]], -1)
    return pts.reshape(-1, 3), faces.reshape(-1, 4)


def _merge(parts):
    """One mesh of several (vertices, faces), coincident vertices merged (1e-12 m)."""
    verts, faces, off = [], [], 0
    for v, f in parts:
        verts.append(v)
        faces.append(f + off)
        off += len(v)
    v = np.vstack(verts)
    key = np.round(v / 1e-12).astype(np.int64)
    _, first, inv = np.unique(key, axis=0, return_index=True, return_inverse=True)
    return v[first], inv.reshape(-1)[np.vstack(faces)]


def eighth_box(c: float, s: float, t: float, m: int):
    """The x, y, z >= 0 eighth of the box c (x) x s (y) x t (z) centred at the origin, graded
    quadrilaterals (m panels on the longest half-edge, at least 3 on the thickness's):
    (vertices [m], faces (n, 4)), outward normals."""
    big = max(c, s)
    mx, my = max(3, round(m * c / big)), max(3, round(m * s / big))
    mz = max(3, round(m / 4), round(m * t / big))
    x, y, z = graded_nodes(c / 2, mx), graded_nodes(s / 2, my), graded_nodes(t / 2, mz)
    e = np.eye(3)
    return _merge([_grid(np.array([0, 0, t / 2]), e[0], e[1], x, y),     # top: +z
                   _grid(np.array([c / 2, 0, 0]), e[1], e[2], y, z),     # side: +x
                   _grid(np.array([0, s / 2, 0]), e[2], e[0], z, x)])    # side: +y


def eighth_disc(a: float, t: float, m: int):
    """The x, y, z >= 0 eighth of the cylinder of radius a and thickness t (axis z) centred
    at the origin: the quarter face in polar panels (m rings graded towards the rim, m
    sectors; the centre's panels triangles as quadrilaterals with a repeated vertex) and the
    quarter rim (m/4 rows, at least 3, graded towards the face); outward normals."""
    r = graded_nodes(a, m)
    n_th = m
    th = np.linspace(0.0, 0.5 * np.pi, n_th + 1)
    rr, tt = np.meshgrid(r, th, indexing="ij")
    pts = np.stack([rr * np.cos(tt), rr * np.sin(tt), np.full_like(rr, t / 2)], -1)
    idx = np.arange(pts.shape[0] * pts.shape[1]).reshape(pts.shape[:2])
    faces = np.stack([idx[:-1, :-1], idx[1:, :-1], idx[1:, 1:], idx[:-1, 1:]], -1)
    faces = faces.reshape(-1, 4)
    top = (pts.reshape(-1, 3), faces)
    z = graded_nodes(t / 2, max(3, round(m / 4)))
    zz, tt = np.meshgrid(z, th, indexing="ij")
    rim_pts = np.stack([a * np.cos(tt), a * np.sin(tt), zz], -1)
    idx = np.arange(rim_pts.shape[0] * rim_pts.shape[1]).reshape(rim_pts.shape[:2])
    rim_f = np.stack([idx[:-1, :-1], idx[:-1, 1:], idx[1:, 1:], idx[1:, :-1]], -1)
    v, f = _merge([top, (rim_pts.reshape(-1, 3), rim_f.reshape(-1, 4))])
    # the centre's panels: two corners merged; Capytaine takes a triangle as a quadrilateral
    # whose last vertex repeats the third
    out = []
    for q in f:
        u = list(dict.fromkeys(q.tolist()))
        if len(u) == 3:
            u.append(u[2])
        if len(u) == 4:
            out.append(u)
    return v, np.array(out)


def capytaine_eighth(v, f):
    """6x6 added mass [kg, kg m, kg m^2] of the closed body whose x, y, z >= 0 eighth is
    (v, f), about the origin, rho = :data:`RHO`: Capytaine, direct method, no free surface,
    the two vertical mirror planes used; (matrix, faces of the whole body, wall time [s])."""
    import logging

    import capytaine as cpt

    logging.getLogger("capytaine").setLevel(logging.ERROR)
    t0 = time.perf_counter()
    # Capytaine 3.0 takes the vertical mirror planes only (xOz, yOz): the z < 0 half is
    # mirrored here (faces reversed to keep the normals outward) and a quarter solved
    below = v * np.array([1.0, 1.0, -1.0])
    quarter = cpt.Mesh(vertices=np.vstack([v, below]),
                       faces=np.vstack([f, f[:, ::-1] + len(v)]))
    mesh = cpt.ReflectionSymmetricMesh(
        half=cpt.ReflectionSymmetricMesh(half=quarter, plane="xOz"), plane="yOz")
    return solve_added_mass(mesh), 8 * len(f), time.perf_counter() - t0


def solve_added_mass(mesh) -> np.ndarray:
    """6x6 infinite-frequency added mass [kg, kg m, kg m^2] about the origin, rho =
    :data:`RHO`, of a Capytaine mesh (symmetric ones included): the six radiation problems
    without a free surface, direct method, the matrix symmetrised (its asymmetry is the
    solver's discretisation error, about 1e-4 of the diagonal)."""
    import capytaine as cpt

    body = cpt.FloatingBody(mesh=mesh, dofs=cpt.rigid_body_dofs(rotation_center=(0, 0, 0)))
    names = list(body.dofs)
    problems = [cpt.RadiationProblem(body=body, radiating_dof=d, free_surface=np.inf,
                                     omega=np.inf, rho=RHO) for d in names]
    res = cpt.BEMSolver(method="direct").solve_all(problems, progress_bar=False)
    a = np.zeros((6, 6))
    for j, r in enumerate(res):
        for i, d in enumerate(names):
            a[i, j] = float(np.real(r.added_mass[d]))
    return 0.5 * (a + a.T)


def plates_of_seed(seed: int, count: int) -> dict:
    """{shape index: (chord [m] along x, span [m] along y, thickness [m] along z)} of the
    plates among the first ``count`` shapes of ``seed``, drawn exactly as
    benchmarks.cad_shapes draws them (each plate a box about the origin)."""
    from benchmarks.cad_shapes import drawn_shapes

    return {k: tuple(float(x) for x in parts[0].extents)
            for k, family, parts, _ in drawn_shapes(seed, count) if family == "plate"}


def extrapolated(rows):
    """{(shape, i): (reference, band, order, faces)} of :data:`HEADER` rows: each diagonal
    term over its levels by Eça & Hoekstra (:func:`validation.cad_shapes.fine_reference`)."""
    from validation.cad_shapes import fine_reference

    by: dict = {}
    for r in rows:
        by.setdefault((int(r["shape"]), int(r["i"])), []).append(
            (int(r["faces"]), float(r["added_mass"])))
    out = {}
    for key, lv in by.items():
        lv.sort()
        n = [x for x, _ in lv]
        ref, band, order = fine_reference(n, [np.array([[y]]) for _, y in lv])
        out[key] = (float(ref[0, 0]), float(band[0, 0]), float(order[0, 0]), n)
    return out


HEADER = ["shape", "chord_m", "span_m", "thickness_m", "level", "m", "faces", "i",
          "added_mass", "seconds"]


def run_plates(seed, count, levels, path, only=None):
    """Solve every plate of the seed (``only``: those shape indices) at every level, one row
    per diagonal term, each level written as soon as it is known."""
    plates = {k: x for k, x in plates_of_seed(seed, count).items() if not only or k in only}
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="") as fh:
        fh.write(f"# python -m benchmarks.plate_graded --seed {seed} --count {count} --levels "
                 f"{' '.join(map(str, levels))}"
                 + (f" --only {' '.join(map(str, only))}" if only else "")
                 + f": Capytaine {_version()} (direct method, no free surface, an eighth "
                 "mirrored in z and its quarter solved on two mirror planes, rho = 1000 "
                 "kg/m^3), edge-"
                 "graded structured quadrilaterals; diagonal added mass about the plate's "
                 "centre [kg, kg m^2]\n")
        w = csv.writer(fh)
        w.writerow(HEADER)
        for k, (c, s, t) in plates.items():
            for lev, m in enumerate(levels):
                a, n, sec = capytaine_eighth(*eighth_box(c, s, t, m))
                print(f"{k:3d} plate {c:.3f} x {s:.3f} x {t:.4f}: m {m}, {n} faces, "
                      f"{sec:.1f} s: " + " ".join(f"{x:.5g}" for x in np.diag(a)), flush=True)
                for i in range(6):
                    w.writerow([k, f"{c:.9g}", f"{s:.9g}", f"{t:.9g}", lev, m, n, i,
                                f"{a[i, i]:.9g}", f"{sec:.2f}"])
                fh.flush()


def _version():
    import capytaine

    return capytaine.__version__


def _dnv_lambda(b_over_a):
    """DNV-RP-H103 table A-2, lambda at b/a (linear interpolation; out of the table: error)."""
    from stripcoef.data import load_table

    return load_table("plate_added_mass_dnv").interp(1.0 / b_over_a, "lambda")


CHECK_HEADER = ["body", "b_over_a", "t_over_a", "level", "m", "faces", "i", "added_mass"]


def checks(levels, path):
    """The procedure against exact results, solved and written to ``path``
    (:data:`CHECK_HEADER`, one row per level and diagonal term): the disc of radius a = 1 m
    and the rectangular plates a x b (a = 1 m, b/a = 1, 1.5, 2) at each t/a of
    :data:`THICKNESS`; then printed as ``validation.cad_shapes.graded_checks`` reads them
    (Eça & Hoekstra over the levels, linear extrapolation to t -> 0, against Lamb's disc and
    DNV-RP-H103 table A-2)."""
    from validation.cad_shapes import graded_checks

    bodies = [("disc", 1.0, lambda m, t: eighth_disc(1.0, t, m))]
    bodies += [("plate", r, lambda m, t, r=r: eighth_box(r, 1.0, t, m)) for r in (1.0, 1.5, 2.0)]
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="") as fh:
        fh.write(f"# python -m benchmarks.plate_graded --checks --checks-csv FILE --levels "
                 f"{' '.join(map(str, levels))}: Capytaine {_version()} (direct method, no "
                 "free surface, rho = 1000 kg/m^3), edge-graded quadrilaterals; a = 1 m; "
                 "diagonal added mass about the centre [kg, kg m^2]\n")
        w = csv.writer(fh)
        w.writerow(CHECK_HEADER)
        for body, ratio, make in bodies:
            for t in THICKNESS:
                for lev, m in enumerate(levels):
                    a, n, sec = capytaine_eighth(*make(m, t))
                    print(f"{body} b/a {ratio} t/a {t}: m {m}, {n} faces, {sec:.1f} s",
                          flush=True)
                    w.writerows([body, ratio, t, lev, m, n, i, f"{a[i, i]:.9g}"]
                                for i in range(6))
                    fh.flush()
    for line in graded_checks(path)["lines"]:
        print(line)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--checks", action="store_true",
                    help="the exact disc and DNV table A-2 checks of the procedure")
    ap.add_argument("--seed", type=int, default=None, help="the CAD benchmark's seed")
    ap.add_argument("--count", type=int, default=40, help="its shape count (default 40)")
    ap.add_argument("--levels", type=int, nargs="+", default=LEVELS,
                    help="panels on the longest half-edge, one level each")
    ap.add_argument("--csv", default=None, help="write the seed's plates' levels here")
    ap.add_argument("--checks-csv", default=None, help="write the checks' levels here")
    ap.add_argument("--only", type=int, nargs="+", default=None,
                    help="solve only these shapes of the seed (its plates)")
    args = ap.parse_args(argv)
    if args.checks:
        if not args.checks_csv:
            ap.error("--checks needs --checks-csv")
        checks(args.levels, args.checks_csv)
    if args.seed is not None:
        if not args.csv:
            ap.error("--seed needs --csv")
        run_plates(args.seed, args.count, args.levels, args.csv, args.only)
    return 0


if __name__ == "__main__":
    sys.exit(main())

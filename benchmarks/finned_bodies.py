"""Finned Myring hulls: the vehicle-file strip model against a converged Capytaine BEM.

Run (from the repository root):
  python -m benchmarks.finned_bodies            # compare against the stored BEM references
  python -m benchmarks.finned_bodies --bem      # recompute the BEM references (~25 min; ~10 GB
                                                # a case: --only CASE runs one per process)
  python -m benchmarks.finned_bodies --convergence   # Y_rdot vs strip count 250..8000

Bodies (all along x, metres, origin at mid-length): the REMUS-like Myring hull of
benchmarks/mesh_shapes.py (Prestero 2001, table 2.1: a = 0.191, b = 0.654, c = 0.541,
d = 0.191 m, n = 2, tail half-angle 25 deg; untruncated, L = 1.386 m) with a cruciform of four
flat rectangular fins (thickness 0.012 m) on it, in six sizes and places (``CASES``); the
bodies, the stored references' readers and the Richardson arithmetic are validation/finned.py.
The BEM mesh is the hull of revolution unioned with four boxes running from the axis to the
fin tip radius (benchmarks/mesh_shapes.py style); the vehicle file describes the same body
with a ``profile`` of Myring segments and four ``fin`` appendages from the hull surface to the
tip.

BEM: ``stripcoef.bem.bem_added_mass`` (Capytaine, direct method, no free surface) about the
origin, at three refinements of the mesh; the body's two reflection symmetries (y = 0, z = 0) let
Capytaine solve a quarter mesh (<= 2,500 faces: the memory of a 5,000-face general mesh) for
the full body's matrices (:func:`bem_quarter`, as in mesh_reference_convergence.py); the direct method converges at second
order in the panel size h ~ N^(-1/2), so the error ~ 1/N and the Richardson value of the two
finest meshes is A_inf = A_3 + (A_3 - A_2) N_2 / (N_3 - N_2); the coarsest mesh checks that
order (:func:`observed_order`).  The references are stored in
reference_tables/bem/bem_finned_bodies.csv (one row per case and mesh, plus the extrapolated row).
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse
import csv
import time
import warnings

import numpy as np

from validation.finned import (CASES, COMPARED, DATA, LENGTH, MESH_LEVELS, RHO, TERMS, THICKNESS,
                               X0, hull_profile, hull_radius, load_references, meshes,
                               observed_order, richardson, richardson_spread, strip_model,
                               vehicle_dict)


def hull_mesh(level: int):
    """The bare hull's surface mesh at mesh level ``level`` of :data:`MESH_LEVELS`
    (``n_profile`` meridian panels, ``sections`` round the axis)."""
    from stripcoef.geometry.mesh import revolved_mesh
    n_profile, sections, _ = MESH_LEVELS[level]
    return revolved_mesh(*hull_profile(n_profile + 1), sections=sections)


def bem_mesh(case: str, level: int):
    import trimesh

    xc, chord, tip = CASES[case]
    max_edge = chord / MESH_LEVELS[level][2]
    # each level is built from scratch (the hull's facets converge to the body, not only the
    # panels); the fins' boxes are split to edges <= max_edge before the union
    hull = hull_mesh(level)
    fins = []
    for ang in (0.0, 0.5 * np.pi, np.pi, 1.5 * np.pi):
        box = trimesh.creation.box([chord, THICKNESS, tip])
        box.apply_translation([xc, 0.0, 0.5 * tip])
        box.apply_transform(trimesh.transformations.rotation_matrix(ang, [1, 0, 0]))
        v, f = trimesh.remesh.subdivide_to_size(box.vertices, box.faces, max_edge=max_edge)
        fins.append(trimesh.Trimesh(v, f, process=True))
    return trimesh.boolean.union([hull] + fins, engine="manifold")


#: Capytaine's frame is (x_c, y_c, z_c) = (y, z, x) of ours (a cyclic permutation, handedness
#: kept), so our symmetry planes y = 0 and z = 0 are its yOz and xOz; its DOFs (surge_c, sway_c,
#: heave_c, roll_c, pitch_c, yaw_c) are our (sway, heave, surge, pitch, yaw, roll)
OURS_FROM_CAPYTAINE = (2, 0, 1, 5, 3, 4)


def quarter(mesh):
    """The y >= 0, z >= 0 quarter of a body symmetric about y = 0 and z = 0, open on those planes."""
    import trimesh
    q = trimesh.intersections.slice_mesh_plane(mesh, [0, 1, 0], [0, 0, 0], cap=False)
    return trimesh.intersections.slice_mesh_plane(q, [0, 0, 1], [0, 0, 0], cap=False)


def bem_quarter(mesh_q, rho=RHO, linear_solver="lu_decomposition"):
    """6x6 added mass about the origin of the body whose quarter is ``mesh_q``: Capytaine's
    direct method on a ReflectionSymmetricMesh of ReflectionSymmetricMesh (the full body's
    matrices with a quarter of the memory, benchmarks/mesh_reference_convergence.py).
    ``linear_solver`` "gmres" needs no LU factors: 7.4 GB peak at 19,112 full-body faces
    against about 10 GB with the default (docs/performance.md)."""
    import logging

    import capytaine as cpt
    logging.getLogger("capytaine").setLevel(logging.ERROR)
    v = np.asarray(mesh_q.vertices, float)[:, [1, 2, 0]]
    q = cpt.Mesh(vertices=v, faces=np.asarray(mesh_q.faces, int))
    mesh = cpt.ReflectionSymmetricMesh(half=cpt.ReflectionSymmetricMesh(half=q, plane="xOz"),
                                       plane="yOz")
    body = cpt.FloatingBody(mesh=mesh, dofs=cpt.rigid_body_dofs(rotation_center=(0.0, 0.0, 0.0)))
    dofs = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")
    pbs = [cpt.RadiationProblem(body=body, radiating_dof=d, free_surface=np.inf, omega=np.inf,
                                rho=rho) for d in dofs]
    engine = cpt.DefaultMatrixEngine(linear_solver=linear_solver)
    res = cpt.BEMSolver(method="direct", engine=engine).solve_all(pbs, progress_bar=False)
    a_c = np.array([[float(np.real(r.added_mass[d])) for d in dofs] for r in res]).T
    p = OURS_FROM_CAPYTAINE
    a = a_c[np.ix_(p, p)]
    return 0.5 * (a + a.T)


def run_bem(cases=None):
    """BEM references of ``cases`` (default all) at every mesh level; the stored rows of the other
    cases are kept."""
    cases = list(cases or CASES)
    levels = {}
    if DATA.exists():
        for case, stored in load_references().items():
            if case in CASES and case not in cases:
                levels[case] = [(n, stored[str(n)]) for n in meshes(stored)]
    for case in cases:
        levels[case] = []
        for level in range(len(MESH_LEVELS)):
            mesh_q = quarter(bem_mesh(case, level))
            t0 = time.perf_counter()
            a = bem_quarter(mesh_q)
            n = 4 * len(mesh_q.faces)
            print(f"{case}: {n} faces, {time.perf_counter() - t0:.1f} s", flush=True)
            levels[case].append((n, a))
    write_references(levels)


def write_references(levels: dict) -> None:
    """Store case -> [(faces, 6x6 BEM matrix), ...] with each case's Richardson row from its two
    finest meshes."""
    rows = []
    for case in CASES:
        if case not in levels:
            continue
        res = sorted(levels[case], key=lambda item: item[0])
        rows += [(case, str(n), a) for n, a in res]
        rows.append((case, "richardson", richardson(*res[-2:])))
    DATA.parent.mkdir(exist_ok=True)
    with open(DATA, "w", newline="") as fh:
        fh.write("# Added mass of finned Myring hulls (benchmarks/finned_bodies.py CASES), Capytaine BEM,\n"
                 "# direct method, two reflection symmetries, no free surface, rho = 1025 kg/m^3, about the origin (mid-length),\n"
                 "# FRD body axes; M_A entries (Fossen signs, positive diagonal) [kg, kg m, kg m^2].\n"
                 "# Source: computed by python -m benchmarks.finned_bodies --bem (stripcoef.bem.bem_added_mass);\n"
                 "# faces = full-body mesh size (4 x the solved quarter), 'richardson' = A_3 + (A_3 - A_2) N_2/(N_3 - N_2) from the two finest\n"
                 "# meshes (second order in h; the coarsest checks the order, benchmarks/finned_bodies.py observed_order).\n")
        w = csv.writer(fh)
        w.writerow(["case", "faces"] + [f"m{i}{j}" for i, j in TERMS])
        for case, n, a in rows:
            w.writerow([case, n] + [f"{a[i, j]:.8g}" for i, j in TERMS])


def compare():
    refs = load_references()
    worst = 0.0
    print("| case | term | BEM finest | BEM Richardson | BEM spread % | strip (1000) | error % |")
    print("|---|---|---|---|---|---|---|")
    for case in CASES:
        r = refs[case]
        fine = r[str(meshes(r)[-1])]
        conv = r["richardson"]
        m = strip_model(case)
        for i, j in COMPARED:
            err = 100.0 * (m[i, j] - conv[i, j]) / conv[i, j]
            worst = max(worst, abs(err))
            print(f"| {case} | M_A[{i},{j}] | {fine[i, j]:.5g} | {conv[i, j]:.5g} "
                  f"| {richardson_spread(r, i, j):.1f} | {m[i, j]:.5g} | {err:+.2f} |")
    print(f"largest error: {worst:.2f} %")


def orders():
    """Observed convergence order q (error ~ N^-q) of every compared term on the three stored
    meshes (:func:`observed_order`; 1 = second order in h, as the Richardson rows assume)."""
    refs = load_references()
    print("| case | " + " | ".join(f"M_A[{i},{j}]" for i, j in COMPARED) + " |")
    print("|---|" + "---|" * len(COMPARED))
    for case in CASES:
        r = refs[case]
        ns = meshes(r)[-3:]
        if len(ns) < 3:
            continue
        qs = [observed_order(ns, [r[str(n)][i, j] for n in ns]) for i, j in COMPARED]
        print(f"| {case} | " + " | ".join(f"{q:.2f}" for q in qs) + " |")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bem", action="store_true", help="recompute the BEM references")
    ap.add_argument("--only", nargs="*", help="with --bem: only these cases (the others kept)")
    ap.add_argument("--order", action="store_true",
                    help="the BEM's observed convergence order per term on the stored meshes")
    ap.add_argument("--convergence", action="store_true",
                    help="the coupling vs the strip count instead of the BEM comparison")
    ap.add_argument("--sheet-mesh", action="store_true",
                    help="the fins' 3D shares vs the thin-sheet panel mesh (~8 min)")
    args = ap.parse_args()
    if args.convergence:
        convergence()
        return
    if args.sheet_mesh:
        sheet_mesh_refinement()
        return
    if args.order:
        orders()
        return
    if args.bem:
        run_bem(args.only)
    compare()



#: the thin-sheet mesh doubled in every direction (stripcoef.hull.finsheet defaults: chord 8,
#: span 6, quarter 8, aft 12, fore 24 panels)
SHEET_FINE = {"chord": 16, "span": 12, "quarter": 16, "aft": 24, "fore": 48}


def sheet_mesh_refinement():
    """The fins' 3D share (stripcoef.hull.finsheet.fins_added_mass) of sway, yaw, their coupling
    and roll for every case with the default sheet mesh and with :data:`SHEET_FINE`, each against
    the BEM's share (validation.fins.fin_shares: finned Richardson minus the exact bare hull)
    [%], and the time of one solve (docs/performance.md)."""
    from stripcoef.hull.finsheet import FinPlanform, fins_added_mass
    from validation.fins import fin_shares
    shares = fin_shares()

    def radius(x):
        return hull_radius(np.clip(x, X0, X0 + LENGTH))

    terms = ((1, 1), (5, 5), (1, 5), (3, 3))
    print("| case | mesh | time [s] | " + " | ".join(f"M_A[{i},{j}] share error %"
                                                          for i, j in terms) + " |")
    print("|---|---|---|" + "---|" * len(terms))
    for case, (xc, chord, tip) in CASES.items():
        fins = [FinPlanform(k * 0.5 * np.pi, xc - 0.5 * chord, xc + 0.5 * chord, tip)
                for k in range(4)]
        bem = shares[case][2]
        for name, mesh in (("default", {}), ("doubled", SHEET_FINE)):
            t0 = time.perf_counter()
            d = fins_added_mass(radius, X0, X0 + LENGTH, fins, [THICKNESS] * 4, [4] * 4,
                                rho=RHO, **mesh)
            dt = time.perf_counter() - t0
            print(f"| {case} | {name} | {dt:.1f} | " + " | ".join(
                f"{100 * (d[i, j] / bem[i, j] - 1):+.2f}" for i, j in terms) + " |", flush=True)


def convergence(counts=(250, 500, 1000, 2000, 4000, 8000)):
    """Y_rdot = -M_A[1,5] (about the origin) of the REMUS-like finned hull and of its bare hull vs
    the strip count, each relative to its value at the largest count, with and without the 3D
    corrections (docs/performance.md)."""
    rows = []
    for name, fins, corr in (("finned, pure strip", True, False), ("finned, corrected", True, True),
                             ("bare hull, pure strip", False, False),
                             ("bare hull, corrected", False, True)):
        vals = []
        for n in counts:
            d = vehicle_dict("remus_tail", n)
            d["corrections"] = corr
            if not fins:
                d["appendages"] = []
            from stripcoef.assembly.estimate import estimate
            from stripcoef.geometry.vehicle import parse_vehicle
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                m = estimate(parse_vehicle(d, file="<conv>")).added_mass
            vals.append(m[1, 5])
        rows.append((name, vals))
    print("| body | " + " | ".join(str(n) for n in counts) + " |")
    print("|---|" + "---|" * len(counts))
    for name, vals in rows:
        ref = vals[-1]
        print(f"| {name} | " + " | ".join(f"{100 * (v - ref) / abs(ref):+.3f} %" for v in vals[:-1])
              + f" | {ref:.5g} kg m |")


if __name__ == "__main__":
    main()

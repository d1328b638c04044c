"""Finned hulls' added mass: the BEM reference refined on the fins, the hull's discretisation removed.

Stored for large_tail (the case that needs it, below), remus_tail and small_tail (checks on
other bodies).

Run (from the repository root):
  python -m benchmarks.fin_bem_refinement          # the stored study against the strip model
  python -m benchmarks.fin_bem_refinement --bem    # solve the meshes not yet stored (~17 min
                                                   # a case on 2 cores; the finest mesh needs
                                                   # most of 23 GB); --case CASE for another
                                                   # hull of validation.finned.CASES

Why: about mid-length, large_tail's sway-yaw and heave-pitch couplings (0.4 kg m) are the 23 %
difference of the hull's share (+1.86 kg m) and the fins' (-1.45 kg m), so 1 % of the fins'
share is 3.5 % of the coupling.  The three stored levels of benchmarks/finned_bodies.py refine
hull and fins together and split the fin boxes by repeated halving: the coupling there goes
0.3936, 0.3941, 0.4121 (not monotone: the fins' 12 mm thickness gets its second panel only at
the finest level), and the Richardson value's spread is 7.4 %.

Method:

- **The hull's error cancels.**  The hull is meshed once (``HULL_LEVEL`` of
  validation.finned.MESH_LEVELS) and solved bare on that same mesh; each finned result is
  A = A_BEM(finned) - A_BEM(bare, same hull mesh) + A_exact(bare), with A_exact the
  axisymmetric solution (validation.finned.bare_hull_exact, exact to 0.02 %).  What is left is the
  error of the fins and their junction.
- **The fins are refined alone**, as structured boxes (:func:`fin_box`) with cosine spacing
  along the chord, across the thickness and along the span (panels clustered at the edges,
  where the flow round a thin body is singular): ``REFINEMENT`` lists (chord, thickness, span)
  panel counts.
- **Symmetry check:** on this cruciform body M[1,5] = -M[2,4] exactly; their difference on one
  mesh shows the BEM's own scatter (the y and z fins meet the faceted hull differently).

The meshes: (16, 4, 16), (24, 4, 24), (32, 4, 32) refine the fin's plane at a fixed thickness
(:func:`in_plane_order`), (32, 6, 40) then refines thickness and span.  Memory bounds the
study: with gmres (no LU) a 19,112-face mesh peaked at 7.4 GB and a 27,080-face one was killed
at 24 GB, past the 23 GB machine that made it (docs/performance.md); the finest mesh has
23,216 faces.  Stored in reference_tables/bem/bem_fin_refinement.csv (raw BEM matrices; the
correction is applied on loading, validation.finned.load_refinement).
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "2")

import argparse
import csv
import time

import numpy as np

from benchmarks import finned_bodies as fb
from validation import finned
from validation.finned import (CASE, COUPLINGS, DIAGONAL, HULL_LEVEL, REFINEMENT, in_plane_order,
                               load_raw, load_refinement, mean_coupling, stored_cases)

DATA = finned.REFINEMENT_DATA


def cosine_nodes(a: float, b: float, n: int) -> np.ndarray:
    """n + 1 nodes from a to b clustered at both ends: a + (b - a)(1 - cos(pi k/n))/2."""
    return a + (b - a) * 0.5 * (1.0 - np.cos(np.pi * np.arange(n + 1) / n))


def _grid(origin, a, b, sa, sb):
    """Triangles on the parallelogram origin + s a + t b at the nodes s in sa, t in sb (each
    from 0 to 1); outward normal along a x b."""
    s, t = np.meshgrid(sa, sb, indexing="ij")
    v = origin + s[..., None] * a + t[..., None] * b
    idx = np.arange(len(sa) * len(sb)).reshape(len(sa), len(sb))
    p, q = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel()
    r, u = idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()
    return v.reshape(-1, 3), np.concatenate([np.stack([p, q, r], 1), np.stack([p, r, u], 1)])


def fin_box(xs, ys, zs):
    """Closed box mesh with its nodes at xs, ys, zs (increasing) along its three edge
    directions: structured, so each direction is refined on its own."""
    import trimesh
    ex, ey, ez = np.eye(3)
    unit = [(c - c[0]) / (c[-1] - c[0]) for c in (xs, ys, zs)]
    lx, ly, lz = (c[-1] - c[0] for c in (xs, ys, zs))
    o = np.array([xs[0], ys[0], zs[0]])
    faces = [(o, ly * ey, lx * ex, 1, 0), (o + lz * ez, lx * ex, ly * ey, 0, 1),
             (o, lx * ex, lz * ez, 0, 2), (o + ly * ey, lz * ez, lx * ex, 2, 0),
             (o, lz * ez, ly * ey, 2, 1), (o + lx * ex, ly * ey, lz * ez, 1, 2)]
    vs, fs, n = [], [], 0
    for origin, a, b, ia, ib in faces:
        v, f = _grid(origin, a, b, unit[ia], unit[ib])
        vs.append(v)
        fs.append(f + n)
        n += len(v)
    box = trimesh.Trimesh(np.vstack(vs), np.vstack(fs), process=True)
    box.merge_vertices(digits_vertex=12)
    if not box.is_watertight:
        raise RuntimeError("fin_box: the structured box is not closed")
    return box


def finned_mesh(case: str, chord_panels: int, thickness_panels: int, span_panels: int):
    """The finned body: the hull at ``HULL_LEVEL`` unioned with four structured fin boxes
    running from the axis to the tip (three panels below 0.8 of the hull radius at the fin's
    aft edge, inside the hull; ``span_panels`` cosine-spaced from there to the tip)."""
    import trimesh
    xc, chord, tip = finned.CASES[case]
    inner = 0.8 * float(finned.hull_radius(xc - 0.5 * chord))
    xs = cosine_nodes(xc - 0.5 * chord, xc + 0.5 * chord, chord_panels)
    ys = cosine_nodes(-0.5 * finned.THICKNESS, 0.5 * finned.THICKNESS, thickness_panels)
    zs = np.concatenate([np.linspace(0.0, inner, 4)[:-1], cosine_nodes(inner, tip, span_panels)])
    fins = []
    for ang in (0.0, 0.5 * np.pi, np.pi, 1.5 * np.pi):
        box = fin_box(xs, ys, zs)
        box.apply_transform(trimesh.transformations.rotation_matrix(ang, [1, 0, 0]))
        fins.append(box)
    return trimesh.boolean.union([fb.hull_mesh(HULL_LEVEL)] + fins, engine="manifold")


def run_bem(case: str = CASE, *, force: bool = False) -> None:
    """Solve the bare hull and every mesh of ``REFINEMENT`` and store them; meshes already
    stored are kept unless ``force``."""
    stored = {} if force or not DATA.exists() else load_raw(case)
    rows = [] if not DATA.exists() else [
        (other, name, n, a) for other in stored_cases() if other != case
        for name, (n, a) in load_raw(other).items()]
    for name, mesh in [("bare", lambda: fb.hull_mesh(HULL_LEVEL))] + [
            (",".join(map(str, spec)), lambda spec=spec: finned_mesh(case, *spec))
            for spec in REFINEMENT]:
        if name in stored:
            rows.append((case, name, *stored[name]))
            continue
        q = fb.quarter(mesh())
        t0 = time.perf_counter()
        a = fb.bem_quarter(q, linear_solver="gmres")
        n = 4 * len(q.faces)
        print(f"{case} {name}: {n} faces, {time.perf_counter() - t0:.0f} s", flush=True)
        rows.append((case, name, n, a))
    with open(DATA, "w", newline="") as fh:
        fh.write("# Added mass of benchmarks/finned_bodies.py's finned hulls with the fins refined alone "
                 "(benchmarks/fin_bem_refinement.py):\n"
                 f"# Capytaine BEM, direct method, gmres, two reflection symmetries, no free surface, "
                 f"rho = {finned.RHO:g} kg/m^3, about the origin (mid-length), FRD axes [kg, kg m, kg m^2];\n"
                 f"# hull mesh level {HULL_LEVEL} of finned_bodies.MESH_LEVELS in every row; 'bare' = "
                 "that hull alone; 'mesh' = fin box (chord, thickness, span) panels, cosine-spaced.\n"
                 "# Raw BEM values: the hull correction (minus 'bare', plus the exact bare hull) is "
                 "applied by validation.finned.load_refinement().\n")
        w = csv.writer(fh)
        w.writerow(["case", "mesh", "faces"] + [f"m{i}{j}" for i, j in finned.TERMS])
        for case_, name, n, a in rows:
            w.writerow([case_, name, n] + [f"{a[i, j]:.8g}" for i, j in finned.TERMS])


def report(case: str = CASE) -> None:
    study = load_refinement(case)
    m = finned.strip_model(case)
    terms = COUPLINGS + DIAGONAL
    print("| fin mesh | faces | " + " | ".join(f"M_A[{i},{j}]" for i, j in terms)
          + " | M[1,5] + M[2,4] % |")
    print("|---|---|" + "---|" * (len(terms) + 1))
    for name, n, a in study:
        asym = 100 * (a[1, 5] + a[2, 4]) / a[1, 5]
        print(f"| {name} | {n} | " + " | ".join(f"{a[i, j]:.5g}" for i, j in terms)
              + f" | {asym:+.2f} |")
    print("| strip model (1000) | | " + " | ".join(f"{m[i, j]:.5g}" for i, j in terms) + " | |")
    fine = study[-1][2]
    print("model against the finest: " + ", ".join(
        f"M_A[{i},{j}] {100 * (m[i, j] / fine[i, j] - 1):+.2f} %" for i, j in terms))
    print("mean coupling: " + ", ".join(f"{mean_coupling(a):.5g}" for _, _, a in study)
          + f"; model {100 * (mean_coupling(m) / mean_coupling(fine) - 1):+.2f} % off the finest")
    print("observed in-plane order q: " + ", ".join(
        f"M_A[{i},{j}] {in_plane_order(study, i, j):.2f}" for i, j in terms))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bem", action="store_true",
                    help="solve the meshes of REFINEMENT not yet stored")
    ap.add_argument("--force", action="store_true", help="with --bem: solve every mesh again")
    ap.add_argument("--case", default=CASE, choices=sorted(finned.CASES),
                    help=f"the finned hull (default {CASE})")
    args = ap.parse_args()
    if args.bem:
        run_bem(args.case, force=args.force)
    report(args.case)


if __name__ == "__main__":
    main()

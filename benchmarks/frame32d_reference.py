"""Finer Capytaine levels of single CAD shapes, on the 2-core machine (issue 32, ``frame32d``).

``benchmarks.bem_fine_references`` remeshes every shape of a seed and solves them on a 16-core
machine; this takes one shape (SEED:K of ``benchmarks.cad_shapes``), its clean surface (the
parts' manifold union, :func:`benchmarks.cad_shapes.clean_surface`) remeshed in one family
(:func:`stripcoef.hull.remesh.remesh_family`, the default modes, as the fine references of
seed 1375923287 were made) at ``--levels`` faces, and solves each level with Capytaine
(direct method, no free surface, :func:`benchmarks.bem_fine_references.added_mass`), about
the origin, rho = 1000 kg/m^3, one CSV row per upper-triangle term in the columns of
reference_tables/bem/cad_shapes_fine_levels.csv (``shape, level, faces, seconds, i, j,
added_mass``) plus the seed.  The levels are estimated by Eça & Hoekstra's least squares
(:func:`validation.cad_shapes.fine_reference`) where there are four or more.  Usage:

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.frame32d_reference --shape 1795919297:22 \\
        --levels 1500 3000 6000 9000 --csv OUT.csv
"""

from __future__ import annotations

import argparse
import csv
import sys
import time

import numpy as np


def main(argv=None) -> int:
    from benchmarks.bem_fine_references import _solver, added_mass
    from benchmarks.cad_shapes import clean_surface, drawn_shapes
    from stripcoef.hull.remesh import edge_for_panels, remesh_family

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--shape", required=True, metavar="SEED:K")
    ap.add_argument("--levels", type=int, nargs="+", default=[1500, 3000, 6000, 9000])
    ap.add_argument("--csv", required=True)
    args = ap.parse_args(argv)
    seed, k = (int(x) for x in args.shape.split(":"))
    parts = next(p for kk, _, p, _ in drawn_shapes(seed, k + 1) if kk == k)
    surface = clean_surface(parts)
    v, f = np.asarray(surface.vertices, float), np.asarray(surface.faces)
    t0 = time.process_time()
    fam = remesh_family(v, f, [edge_for_panels(float(surface.area), n) for n in args.levels],
                        max_faces=int(1.6 * args.levels[-1]))
    if fam is None:
        print(f"{args.shape}: no remesh family", flush=True)
        return 1
    print(f"{args.shape}: mode {fam[1]}, faces {[len(x[1]) for x in fam[0]]}, "
          f"remesh CPU {time.process_time() - t0:.1f} s", flush=True)
    solver, how = _solver()
    with open(args.csv, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["seed", "shape", "level", "faces", "seconds", "i", "j", "added_mass"])
        for level, (lv, lf) in enumerate(fam[0]):
            t0 = time.process_time()
            a = added_mass(solver, np.asarray(lv, float), np.asarray(lf, np.int64))
            dt = time.process_time() - t0
            for i in range(6):
                for j in range(i, 6):
                    w.writerow([seed, k, level, len(lf), f"{dt:.2f}", i, j, repr(float(a[i, j]))])
            fh.flush()
            print(f"level {level}: {len(lf)} faces, {dt:.1f} s CPU ({how}), diagonal "
                  + " ".join(f"{a[i, i]:.6g}" for i in range(6)), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Finer Capytaine levels of single CAD shapes, on the 2-core machine (issue 32, ``frame32d``).

``benchmarks.bem_fine_references`` remeshes every shape of a seed and solves them on a 16-core
machine; this takes one shape (SEED:K of ``benchmarks.cad_shapes``), its clean surface (the
parts' manifold union, :func:`benchmarks.cad_shapes.clean_surface`) remeshed in one family
(:func:`stripcoef.hull.remesh.remesh_family`, the default modes, as the fine references of
seed 1375923287 were made) at ``--levels`` faces, and solves each level with Capytaine
(direct method, no free surface, :func:`benchmarks.bem_fine_references.added_mass`), about
the origin, rho = 1000 kg/m^3, one CSV row per upper-triangle term in the columns of
reference_tables/bem/cad_shapes_fine_levels.csv (``shape, level, faces, seconds, i, j,
added_mass``) plus the seed.  ``--cad-shapes-cap``: the remesher's default face cap, as
``benchmarks.cad_shapes`` calls it (its references' family; else 1.6 times the finest target).

``--compare``: the shape's levels read back from ``--csv``, estimated by Eça & Hoekstra's least
squares over them (four or more: :func:`validation.cad_shapes.fine_reference`) and as
``benchmarks.cad_shapes`` does (the two finest Richardson-extrapolated as 1/N, their grid
convergence index), and the model (``benchmarks.cad_shapes.patched_estimates``) with the
option ``value_pair="nested"`` (:func:`stripcoef.hull.panel_error.finest_pair_under_refined`)
and without, each
diagonal term and the worst significant coupling against each reference, and how many terms
the model's band covers.  Usage:

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.frame32d_reference --shape 1795919297:22 \\
        --levels 1500 3000 6000 12000 --csv OUT.csv [--compare]
"""

from __future__ import annotations

import argparse
import csv
import functools
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
    ap.add_argument("--cad-shapes-cap", action="store_true")
    ap.add_argument("--compare", action="store_true")
    args = ap.parse_args(argv)
    seed, k = (int(x) for x in args.shape.split(":"))
    if args.compare:
        return compare(args.csv, seed, k)
    parts = next(p for kk, _, p, _ in drawn_shapes(seed, k + 1) if kk == k)
    surface = clean_surface(parts)
    v, f = np.asarray(surface.vertices, float), np.asarray(surface.faces)
    t0 = time.process_time()
    fam = remesh_family(v, f, [edge_for_panels(float(surface.area), n) for n in args.levels],
                        max_faces=None if args.cad_shapes_cap else int(1.6 * args.levels[-1]))
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


def compare(path, seed: int, k: int) -> int:
    from benchmarks.cad_shapes import DOFS, SIGNIFICANT, patched_estimates
    from stripcoef.hull import panels as P
    from stripcoef.hull.convergence import grid_convergence_index, richardson
    from validation.cad_shapes import fine_reference

    levels: dict = {}
    with open(path, newline="") as fh:
        for r in csv.DictReader(line for line in fh if not line.startswith("#")):
            if (int(r["seed"]), int(r["shape"])) != (seed, k):
                continue
            n, m = levels.setdefault(int(r["level"]), [int(r["faces"]), np.zeros((6, 6))])
            i, j = int(r["i"]), int(r["j"])
            m[i, j] = m[j, i] = float(r["added_mass"])
    counts = [levels[x][0] for x in sorted(levels)]
    mats = [levels[x][1] for x in sorted(levels)]
    refs = []
    if len(mats) >= 4:
        ref, band, _ = fine_reference(counts, mats)
        refs.append((f"Eça & Hoekstra over {'/'.join(map(str, counts))}", ref, band))
    if len(mats) >= 3:
        for lo in range(len(mats) - 2):
            sub_n, sub_m = counts[lo:lo + 3], mats[lo:lo + 3]
            ref = richardson(sub_m[-2], sub_m[-1], sub_n[-2], sub_n[-1])
            gci, _, _ = grid_convergence_index(sub_m, sub_n)
            refs.append((f"as benchmarks.cad_shapes, {'/'.join(map(str, sub_n))}", ref,
                         gci + np.abs(ref - sub_m[-1])))
    print(f"{seed}:{k} Capytaine levels " + "; ".join(
        f"{n}: " + " ".join(f"{m[i, i]:.5g}" for i in range(6)) for n, m in zip(counts, mats)))
    for name, ref, band in refs:
        print(f"reference {name}: " + " ".join(
            f"{ref[i, i]:.5g} ({100 * band[i, i] / abs(ref[i, i]):.1f} %)" for i in range(6)))
    lines = ["| reference | rule | levels | " + " | ".join(DOFS)
             + " | worst coupling | covered |", "|---" * 11 + "|"]
    nested = functools.partial(P.panel_added_mass, value_pair="nested")
    for rule, patches in (("nested", {(P, "panel_added_mass"): nested}), ("default", {})):
        for _, _, model, _ in patched_estimates(seed, k + 1, patches, only={k}):
            s = RHO / model.density
            ours = np.asarray(model.added_mass) * s
            est = np.asarray(model.added_mass_error) * s
            for name, ref, _ in refs:
                d = np.sqrt(np.abs(np.diag(ref)))
                scale = np.outer(d, d)
                sig = [(i, j) for i in range(6) for j in range(i, 6)
                       if i == j or abs(ref[i, j]) >= SIGNIFICANT * scale[i, j]]
                err = (ours - ref) / scale
                cov = sum(abs(ours[i, j] - ref[i, j]) <= est[i, j] for i, j in sig)
                coup = max((abs(err[i, j]) for i, j in sig if i != j), default=0.0)
                lines.append(f"| {name} | {rule} | "
                             + "/".join(map(str, model.conditions["added_mass_panel_levels"]))
                             + " | " + " | ".join(f"{100 * err[i, i]:+.1f} %" for i in range(6))
                             + f" | {100 * coup:.1f} % | {cov}/{len(sig)} |")
    print("\n".join(lines))
    return 0


RHO = 1000.0


if __name__ == "__main__":
    sys.exit(main())

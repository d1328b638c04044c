"""A fresh CAD seed's model rows against the most resolved reference of each term (issue 32).

``benchmarks.cad_shapes`` compares the model with Capytaine on isotropic remeshes of up to
3,000 faces, which converge slowly on a thin plate's in-plane terms and a coarse cylinder's
rotation about its axis (edge singularities; docs/performance.md).  For a seed other than
1375923287 (whose fine and graded references ``validation.cad_shapes.best_references``
reads) this replaces, per term, the stored 3,000-face reference by the edge-graded one where
the seed has it: the plates' diagonal terms (``benchmarks.plate_graded``, read by
:func:`validation.cad_shapes.read_graded`) and every term of the coarse cylinders
(``benchmarks.graded_polyhedra cylinders``), each Eça & Hoekstra's least squares over its
levels (:func:`validation.cad_shapes.fine_reference`).  Counts as ``benchmarks.cad_shapes``
does: every diagonal term and each coupling at least 1 % of sqrt(A_ii A_jj); a shape's
warning is its ``warned`` column.  Usage:

    python -m benchmarks.cad_seed_best --model CSV [--plates CSV] [--coarse CSV]
"""

from __future__ import annotations

import argparse
import csv
import sys

import numpy as np

from benchmarks.cad_shapes import DOFS, SIGNIFICANT

TOL = 0.05


def model_rows(path) -> dict:
    """{shape: dict(family, warned, cpu, model, bem, est (6x6 each, est in [kg...]))}."""
    out: dict = {}
    with open(path, newline="") as fh:
        fh.readline()
        for r in csv.DictReader(fh):
            if r["what"].startswith("FAILED"):
                continue
            x = out.setdefault(int(r["shape"]), dict(
                family=r["family"], warned=r["warned"] == "1", cpu=float(r["cpu_model_s"]),
                model=np.zeros((6, 6)), bem=np.zeros((6, 6)), est_rel=np.zeros((6, 6))))
            i, j = int(r["i"]), int(r["j"])
            for key, col in (("model", "model"), ("bem", "bem"),
                             ("est_rel", "estimated_error_rel")):
                x[key][i, j] = x[key][j, i] = float(r[col])
    for x in out.values():        # the band back to [kg, ...] from the stored run's scale
        d = np.sqrt(np.abs(np.diag(x["bem"])))
        x["est"] = x["est_rel"] * np.outer(d, d)
    return out


def best(rows: dict, plates=None, coarse=None) -> tuple[dict, dict]:
    """({shape: 6x6 reference}, {(shape, i, j): source}) the edge-graded where held."""
    from validation.cad_shapes import fine_reference, read_graded
    from validation.graded_bodies import read

    refs = {k: x["bem"].copy() for k, x in rows.items()}
    source = {}
    if plates:
        for k, (_, _, _, faces, terms) in read_graded(plates).items():
            if k not in refs:             # a shape the draw lost (its BEM failed): no row
                continue
            for i in range(6):
                r, _, _ = fine_reference(faces, [np.array([[v]]) for v in terms[i]])
                refs[k][i, i] = r[0, 0]
                source[(k, i, i)] = "graded plate"
    if coarse:
        for k, (_, n, mats) in read(coarse).items():
            if k not in refs:
                continue
            r, _, _ = fine_reference(n, mats)
            refs[k] = 0.5 * (r + r.T)
            for i in range(6):
                for j in range(i, 6):
                    source[(k, i, j)] = "graded cylinder"
    return refs, source


def tally(rows: dict, refs: dict, source: dict) -> str:
    diag = coup = diag_in = coup_in = terms = covered = 0
    off_shapes = off_warned = 0
    misses = []
    for k in sorted(rows):
        x, ref = rows[k], refs[k]
        d = np.sqrt(np.abs(np.diag(ref)))
        scale = np.outer(d, d)
        off = False
        for i in range(6):
            for j in range(i, 6):
                if i != j and abs(ref[i, j]) < SIGNIFICANT * scale[i, j]:
                    continue
                err = x["model"][i, j] - ref[i, j]
                rel = err / scale[i, j]
                inside = abs(rel) <= TOL
                cov = abs(err) <= x["est"][i, j]
                terms += 1
                covered += cov
                if i == j:
                    diag += 1
                    diag_in += inside
                else:
                    coup += 1
                    coup_in += inside
                if not inside:
                    off = True
                    misses.append(f"{k} {x['family']} {DOFS[i]}"
                                  + ("" if i == j else f"-{DOFS[j]}")
                                  + f" {100 * rel:+.1f} % (band {100 * x['est'][i, j] / scale[i, j]:.1f} %, "
                                  + ("covered" if cov else "NOT covered") + ", "
                                  + ("warned" if x["warned"] else "NOT warned") + "; "
                                  + source.get((k, i, j), "uniform 3,000-face reference")
                                  + ")")
        off_shapes += off
        off_warned += off and x["warned"]
    cpu = np.array([x["cpu"] for x in rows.values()])
    return (f"diagonal terms within 5 %: {diag_in}/{diag}; couplings within 5 % of the "
            f"scale: {coup_in}/{coup}; the band covers the error: {covered}/{terms} "
            f"({100 * covered / terms:.1f} %); shapes off by > 5 % warned: {off_warned}/"
            f"{off_shapes}; shapes warned: {sum(x['warned'] for x in rows.values())}/"
            f"{len(rows)}; estimate CPU median {np.median(cpu):.2f} s (max {cpu.max():.2f} s)\n"
            + "".join(f"- {m}\n" for m in misses))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--model", required=True, help="a benchmarks.cad_shapes CSV")
    ap.add_argument("--plates", default=None, help="the seed's benchmarks.plate_graded CSV")
    ap.add_argument("--coarse", default=None,
                    help="the seed's benchmarks.graded_polyhedra cylinders CSV")
    args = ap.parse_args(argv)
    rows = model_rows(args.model)
    print("Against the stored 3,000-face references:\n" + tally(rows, *best(rows)))
    if args.plates or args.coarse:
        print("Against the most resolved reference of each term:\n"
              + tally(rows, *best(rows, args.plates, args.coarse)))
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""The stored CAD draws with the right prisms panelled graded towards their edges, or not
(issue 32, branch roll32g: :func:`stripcoef.hull.graded_panels.prism_faces`).

Only a shape whose closed surface is a right prism other than a box (the ``coarse``
cylinders, the ``extrusion`` polygons) takes another path when
:data:`stripcoef.hull.graded_panels.PRISMS` changes; every other shape's estimate is the same
code either way.  So for a stored draw (``benchmarks.cad_shapes --csv``) this re-runs the model
on those shapes only, against the stored references (``run_one`` with the stored run's
references, drawn exactly as the run drew them), once with ``PRISMS`` off (the isotropic
remesh, as before) and once on, and writes two full CSVs: the stored rows with the prisms'
rows replaced by each re-run (``OUT_off.csv``, ``OUT_on.csv``), which
``python -m benchmarks.cad_seed_best --model OUT_on.csv --plates ... --coarse ...`` counts.
Usage (one BLAS thread):

    python -m benchmarks.roll32g_draws --seed 1795948662 \\
        --references reference_tables/bem/cad_shapes_1795948662.csv --out /tmp/d62
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import csv  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402

import numpy as np  # noqa: E402

from benchmarks.cad_shapes import (FAMILIES, HEADER, clean_surface, csv_rows, drawn_shapes,  # noqa: E402
                                   make_shape, run_one, stored_references)
from stripcoef.hull import graded_panels as G  # noqa: E402


def prism_shapes(seed: int, count: int) -> list:
    """The shapes k of the draw whose clean surface :func:`~stripcoef.hull.graded_panels.
    prism_faces` reads as a right prism."""
    out = []
    for k, family, parts, _ in drawn_shapes(seed, count):
        s = clean_surface(parts)
        if G.box_faces(s.vertices, s.faces) is None and G.prism_faces(s.vertices, s.faces):
            out.append(k)
    return out


def rerun(seed: int, count: int, stored: dict, only, prisms: bool) -> dict:
    """{k: run_one's result} of the shapes ``only`` with :data:`PRISMS` = ``prisms``."""
    saved = G.PRISMS
    G.PRISMS = prisms
    rng = np.random.default_rng(seed)
    out = {}
    try:
        with tempfile.TemporaryDirectory() as tmp:
            for k in range(count):
                family = FAMILIES[int(rng.integers(0, len(FAMILIES)))]
                if k not in only or k not in stored:
                    make_shape(family, rng)
                    rng.uniform(), rng.uniform()
                    continue
                r = run_one(family, rng, tmp, None, stored[k])
                r["k"] = k
                out[k] = r
                print(f"{k} {family} {r['what']} prisms {'on' if prisms else 'off'}: panels "
                      f"{r['panels']}, CPU {r['c_model']:.2f} s, diagonal "
                      + " ".join(f"{100 * x['rel']:+.1f}" for x in r["rows"] if x["i"] == x["j"])
                      + " % (vs the stored 3,000-face reference)", flush=True)
    finally:
        G.PRISMS = saved
    return out


def write(path, references, results: dict, note: str) -> None:
    """The stored run's CSV with the shapes of ``results`` replaced."""
    with open(references, newline="") as fh:
        first = fh.readline().strip()
        rows = [r for r in csv.reader(fh)][1:]
    with open(path, "w", newline="") as fh:
        fh.write(f"{first}; {note}\n")
        w = csv.writer(fh)
        w.writerow(HEADER)
        done = set()
        for r in rows:
            k = int(r[0])
            if k in results:
                if k not in done:
                    w.writerows(csv_rows(results[k]))
                    done.add(k)
                continue
            w.writerow(r)


def compare(out: str, plates=None, coarse=None) -> str:
    """A markdown table per diagonal term of the re-run prisms (``OUT_off.csv`` against
    ``OUT_on.csv``): the error against the most resolved reference (``validation.cad_draws.
    best``) and whether the band covers it, each way; then the couplings and off-diagonal
    coverage that changed."""
    from validation.cad_draws import DOFS, SIGNIFICANT, best, model_rows

    off, on = model_rows(f"{out}_off.csv"), model_rows(f"{out}_on.csv")
    refs, source = best(off, plates, coarse)
    with open(f"{out}_on.csv") as fh:
        note = fh.readline()
    changed = sorted(k for k in on if not np.array_equal(on[k]["model"], off[k]["model"]))
    lines = ["| # | family | term | reference | off: error (band) | on: error (band) |",
             "|---" * 6 + "|"]
    for k in changed:
        ref = refs[k]
        d = np.sqrt(np.abs(np.diag(ref)))
        for i in range(6):
            for j in range(i, 6):
                if i != j and abs(ref[i, j]) < SIGNIFICANT * d[i] * d[j]:
                    continue
                cells = []
                for x in (off[k], on[k]):
                    err = (x["model"][i, j] - ref[i, j]) / (d[i] * d[j])
                    band = x["est"][i, j] / (d[i] * d[j])
                    cells.append(f"{100 * err:+.1f} % ({100 * band:.1f} %"
                                 + ("" if abs(err) <= band else ", NOT covered") + ")")
                term = DOFS[i] + ("" if i == j else f"-{DOFS[j]}")
                lines.append(f"| {k} | {off[k]['family']} | {term} | "
                             + source.get((k, i, j), "uniform 3,000-face") + " | "
                             + " | ".join(cells) + " |")
    cpu = [f"{k}: {off[k]['cpu']:.2f} -> {on[k]['cpu']:.2f} s" for k in changed]
    return note.strip("# \n") + "\n\n" + "\n".join(lines) + "\n\nCPU " + ", ".join(cpu) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, required=True)
    ap.add_argument("--count", type=int, default=40)
    ap.add_argument("--references", required=True, help="the draw's stored cad_shapes CSV")
    ap.add_argument("--out", required=True, help="prefix of OUT_off.csv and OUT_on.csv")
    ap.add_argument("--modes", nargs="+", default=["off", "on"], choices=("off", "on"))
    ap.add_argument("--compare", action="store_true",
                    help="only compare OUT_off.csv with OUT_on.csv (per term)")
    ap.add_argument("--plates", default=None, help="the seed's plate_graded CSV (--compare)")
    ap.add_argument("--coarse", default=None, help="the seed's graded cylinders (--compare)")
    args = ap.parse_args(argv)
    if args.compare:
        print(compare(args.out, args.plates, args.coarse))
        return 0
    stored = stored_references(args.references)
    only = prism_shapes(args.seed, args.count)
    print(f"seed {args.seed}: right prisms {only}", flush=True)
    for mode in args.modes:
        res = rerun(args.seed, args.count, stored, only, mode == "on")
        write(f"{args.out}_{mode}.csv", args.references, res,
              f"prisms' rows re-run by python -m benchmarks.roll32g_draws --seed {args.seed} "
              f"(graded prisms {mode})")
    return 0


if __name__ == "__main__":
    sys.exit(main())

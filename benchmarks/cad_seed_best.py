"""A fresh CAD seed's model rows against the most resolved reference of each term (issue 32).

``benchmarks.cad_shapes`` compares the model with Capytaine on isotropic remeshes of up to
3,000 faces, which converge slowly on a thin plate's in-plane terms and a coarse cylinder's
rotation about its axis (edge singularities; docs/performance.md).  For a seed other than
1375923287 (whose fine and graded references ``validation.cad_shapes.best_references``
reads) this replaces, per term, the stored 3,000-face reference by the edge-graded one where
the seed has it: the plates' diagonal terms (``benchmarks.plate_graded``, read by
:func:`validation.cad_shapes.read_graded`) and every term of the coarse cylinders
(``benchmarks.graded_polyhedra cylinders``; a low-polygon polyhedron's,
``benchmarks.graded_polyhedra coarse``, the same ``--coarse``), else, where none is held, four
or more finer Capytaine levels of a traced shape (``benchmarks.frame32d_reference``,
``--levels``: the rows of the draw's seed, read from the model CSV's first line), each Eça &
Hoekstra's least squares over its levels (:func:`validation.cad_shapes.fine_reference`;
:func:`validation.cad_draws.best`).  Counts as ``benchmarks.cad_shapes``
does: every diagonal term and each coupling at least 1 % of sqrt(A_ii A_jj); a shape's
warning is its ``warned`` column.  Usage:

    python -m benchmarks.cad_seed_best --model CSV [--plates CSV] [--coarse CSV ...] \\
        [--levels CSV ...]
"""

from __future__ import annotations

import argparse
import sys

from validation.cad_draws import best, model_rows, tally

__all__ = ["best", "model_rows", "tally", "main"]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--model", required=True, help="a benchmarks.cad_shapes CSV")
    ap.add_argument("--plates", default=None, help="the seed's benchmarks.plate_graded CSV")
    ap.add_argument("--coarse", nargs="*", default=(),
                    help="the seed's benchmarks.graded_polyhedra cylinders (or coarse) CSVs")
    ap.add_argument("--levels", nargs="*", default=(),
                    help="benchmarks.frame32d_reference CSVs holding the seed's rows")
    args = ap.parse_args(argv)
    rows = model_rows(args.model)
    seed = draw_seed(args.model) if args.levels else None
    print("Against the stored 3,000-face references:\n" + tally(rows, *best(rows)))
    if args.plates or args.coarse or args.levels:
        print("Against the most resolved reference of each term:\n"
              + tally(rows, *best(rows, args.plates, args.coarse, args.levels, seed)))
    return 0


def draw_seed(path) -> int:
    """The seed of a ``benchmarks.cad_shapes`` CSV, from its first line's ``--seed N``."""
    with open(path) as fh:
        words = fh.readline().split()
    if "--seed" not in words or words.index("--seed") + 1 >= len(words):
        print(f"{path}: its first line names no --seed; expected a benchmarks.cad_shapes CSV",
              file=sys.stderr)
        raise SystemExit(2)
    return int(words[words.index("--seed") + 1].rstrip(";"))


if __name__ == "__main__":
    sys.exit(main())

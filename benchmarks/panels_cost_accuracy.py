"""Cost against accuracy: stripcoef's 3D panel method and Capytaine on the same bluff shapes.

Issue 14 asks for "1000x faster than the BEM at equal accuracy". This benchmark measures what
that takes. For each shape it runs, in one process and one after the other:

- stripcoef.hull.panels.panel_added_mass at a ladder of panel counts (the two extrapolated
  levels follow from it), best of 3;
- Capytaine (stripcoef.bem.bem_added_mass, direct method) at a ladder of face counts, one solve
  each, after one warm-up solve that is not counted;

and compares each with the stored converged reference (reference_tables/bem/bem_bluff.csv, the
Richardson column; Lamb's exact diagonal for the ellipsoids): the worst relative error of the
significant diagonal terms. For each accuracy level it then reports the cheapest run of each
that reaches it, and the ratio of the two times -- the speed-up "at equal accuracy".

It also times the dense LU factorisation (scipy.linalg.lu_factor, one BLAS thread) of the
finest panel count that reaches each level: the one step that any direct boundary-element
solve of that many unknowns cannot skip, i.e. a floor under the panel method's time at that
accuracy.

Run:  OPENBLAS_NUM_THREADS=1 python -m benchmarks.panels_cost_accuracy [--write] [--only ...]

``--write`` writes benchmarks/data/panels_cost_accuracy.md. Times are wall-clock on a shared
machine: read the ratios, which are measured in one run, more than the absolute times.
"""

from __future__ import annotations

import argparse
import datetime
import os
import sys
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from benchmarks.mesh_speed import best  # noqa: E402  (best of n wall times, one helper)

ROOT = Path(__file__).resolve().parents[1]

OUT = ROOT / "benchmarks" / "data" / "panels_cost_accuracy.md"

#: shapes: the issue's box, a 2:1:1 box, a short cylinder across x, the VideoRay-like body
SHAPES = ("box_bluerov", "box_2_1_1", "cyl_y", "videoray_like")
#: panel counts asked of the panel method (its ``panels`` argument)
PANELS = (100, 200, 400, 800, 1500, 3000)
#: Capytaine face counts (each solve at most 4000 faces: memory and time on 2 shared cores)
FACES = (400, 700, 1000, 1500, 2300, 3200, 4000)
#: fewest faces of a smooth shape's tessellation (bluff_shapes._round_cylinder needs ~610)
SMOOTH_MIN_FACES = 700
#: accuracy levels: worst diagonal error [-]
LEVELS = (0.10, 0.05, 0.025)


def _worst(a, ref):
    d, r = np.diag(a), np.diag(ref)
    ok = np.abs(r) > 1e-6 * np.abs(r).max()
    return float(np.max(np.abs(d[ok] / r[ok] - 1.0)))


def panel_runs(name, ref, B):
    """[(panels asked, (N1, N2), worst error against ``ref``, best-of-3 time [s])]"""
    from stripcoef.geometry.mesh import mesh_body
    from stripcoef.hull.panels import panel_added_mass

    body = mesh_body(B.strip_mesh(name), name=name)
    out = []
    for n in PANELS:
        (a, info), t = best(lambda: panel_added_mass(body, rho=B.RHO, panels=n))
        out.append((n, tuple(info["panels"]), _worst(a, ref), t))
        print(f"  panels {n:5d} -> {info['panels']}: worst {100 * out[-1][2]:6.2f} %, "
              f"{out[-1][3]:.3f} s", flush=True)
    return out


def bem_runs(name, ref, B):
    """[(faces, worst error against ``ref``, time [s])], one solve each after an uncounted
    warm-up"""
    from stripcoef.bem import bem_added_mass

    ladder = [f for f in FACES if not B.SHAPES[name][1] or f >= SMOOTH_MIN_FACES]
    bem_added_mass(B.shape_mesh(name, ladder[0]), rho=B.RHO, reference_point=(0, 0, 0))
    out, seen = [], set()
    for faces in ladder:
        m = B.shape_mesh(name, faces)
        if len(m.faces) in seen:
            continue
        seen.add(len(m.faces))
        a, t = best(lambda: bem_added_mass(m, rho=B.RHO, reference_point=(0, 0, 0),
                                           max_faces=5000), n=1)
        out.append((len(m.faces), _worst(a, ref), t))
        print(f"  Capytaine {len(m.faces):5d} faces: worst {100 * out[-1][1]:6.2f} %, "
              f"{out[-1][2]:.3f} s", flush=True)
    return out


def lu_time(n):
    """Best of 3 of scipy.linalg.lu_factor of a dense n x n matrix [s]."""
    import scipy.linalg

    rng = np.random.default_rng(0)
    a = rng.random((n, n)) + n * np.eye(n)
    return best(lambda: scipy.linalg.lu_factor(a, check_finite=False))[1]


def cheapest(runs, level, err_at, time_at):
    ok = [r for r in runs if err_at(r) <= level]
    return min(ok, key=time_at) if ok else None


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", nargs="*", default=list(SHAPES))
    ap.add_argument("--write", action="store_true", help=f"write {OUT.relative_to(ROOT)}")
    args = ap.parse_args(argv)
    from benchmarks import bluff_shapes as B

    rows = []
    for name in args.only:
        print(name, flush=True)
        ref = B.reference_matrix(name)
        pr, br = panel_runs(name, ref, B), bem_runs(name, ref, B)
        for level in LEVELS:
            p = cheapest(pr, level, lambda r: r[2], lambda r: r[3])
            b = cheapest(br, level, lambda r: r[1], lambda r: r[2])
            lu = lu_time(p[1][1]) if p else None
            rows.append((name, level, p, b, lu))
    lines = [
        f"`OPENBLAS_NUM_THREADS=1 python -m benchmarks.panels_cost_accuracy` "
        f"({datetime.date.today().isoformat()}). Worst diagonal error against the converged "
        "reference; the cheapest run of each method that reaches the level; LU: the dense "
        "factorisation alone of the panel method's finer level at that accuracy.",
        "",
        "| shape | accuracy | panel method (panels N1/N2, error, time) | Capytaine (faces, "
        "error, time) | Capytaine / panel method | LU of N2 alone | Capytaine time / 1000 |",
        "|---|---|---|---|---|---|---|",
    ]
    for name, level, p, b, lu in rows:
        ps = f"{p[1][0]}/{p[1][1]}, {100 * p[2]:.1f} %, {1e3 * p[3]:.0f} ms" if p else "not reached"
        bs = f"{b[0]}, {100 * b[1]:.1f} %, {1e3 * b[2]:.0f} ms" if b else "not reached (<= 4000 faces)"
        ratio = f"{b[2] / p[3]:.1f}x" if p and b else "-"
        lus = f"{1e3 * lu:.1f} ms" if lu is not None else "-"
        budget = f"{b[2]:.2f} ms" if b else "-"
        lines.append(f"| {name} | {100 * level:g} % | {ps} | {bs} | {ratio} | {lus} | {budget} |")
    text = "\n".join(lines) + "\n"
    print(text)
    if args.write:
        OUT.write_text(text)
        print(f"wrote {OUT.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

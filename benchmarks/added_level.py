"""The refinement's added level at Celik et al.'s r >= 1.3, measured on a stored CAD draw (issue 32, ``frame32g``).

The panel method's refinement adds a fourth level at twice the finest target
(:func:`stripcoef.hull.remesh.added_level`).  It now takes that remesh only where it refines the
finest level by Celik et al.'s r >= 1.3 (2008, J. Fluids Eng. 130, 078001, step 2; 1.69 in
panels) and otherwise grows it there (within the 6,000-face limit); before, it took a remesh of
1.25 times the panels (r = 1.12), which on the frames' no-flip families gave finest pairs of
r = 1.14-1.20 (benchmarks/data/fresh32f_trace.md).  Each shape of the draw is estimated as
``benchmarks.cad_shapes`` does (:func:`benchmarks.cad_shapes.patched_estimates`) with the
default; where the added level was grown (the only case in which the two rules differ) it is
estimated again with the former rule (``ratio`` = ``LEAST_FACE_RATIO``).  Both are counted
against the most resolved reference of each term as ``benchmarks.cad_seed_best`` counts
(value, band shown and warning of this run; the stored rows' are not read).  Usage:

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.added_level --seed S --count N \\
        --model DRAW.csv [--plates CSV] [--coarse CSV] [--only K ...]
"""

from __future__ import annotations

import argparse
import sys

import numpy as np

RHO = 1000.0


def estimates(seed: int, count: int, only, ratio=None):
    """Yield (k, dict(model, est, warned, cpu, levels, grown)) of the draw's shapes under the
    added-level ``ratio`` (default: the module's)."""
    from benchmarks.cad_shapes import patched_estimates
    from stripcoef.hull import bisection, panels, remesh

    real_added, real_grown = remesh.added_level, remesh.grown_level
    state = {"inside": False, "grown": False}

    def added(*a, **kw):
        if ratio is not None:
            kw["ratio"] = ratio
        state["inside"] = True
        try:
            return real_added(*a, **kw)
        finally:
            state["inside"] = False

    def grown(*a, **kw):
        if state["inside"]:
            state["grown"] = True
        return real_grown(*a, **kw)

    def clear():
        # (the per-process memo of the panel solves and bisections emptied: the former rule's
        # re-run would otherwise find the levels it shares with the default solved)
        state["grown"] = False
        panels._solved_level.cache_clear()
        bisection._refined.cache_clear()

    patches = {(remesh, "added_level"): added, (remesh, "grown_level"): grown}
    for k, _, model, cpu in patched_estimates(seed, count, patches, only=only, before=clear):
        s = RHO / model.density
        c = model.conditions
        yield k, dict(model=np.asarray(model.added_mass) * s,
                      est=np.asarray(model.added_mass_error) * s,
                      warned=not c.get("added_mass_converged", True), cpu=cpu,
                      levels=tuple(c.get("added_mass_panel_levels") or ()),
                      grown=state["grown"])


def main(argv=None) -> int:
    from benchmarks.cad_seed_best import best, model_rows, tally
    from benchmarks.cad_shapes import DOFS
    from stripcoef.hull import remesh

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, required=True)
    ap.add_argument("--count", type=int, default=40)
    ap.add_argument("--model", required=True, help="the draw's benchmarks.cad_shapes CSV")
    ap.add_argument("--plates", default=None)
    ap.add_argument("--coarse", default=None)
    ap.add_argument("--only", type=int, nargs="*", default=None)
    args = ap.parse_args(argv)
    rows = model_rows(args.model)
    keep = {k for k in rows if args.only is None or k in args.only}
    refs, source = best(rows, args.plates, args.coarse)
    new, old = {}, {}
    for k, x in estimates(args.seed, args.count, keep):
        if k not in keep:
            continue
        new[k] = dict(rows[k], **{f: x[f] for f in ("model", "est", "warned", "cpu")})
        y = x
        if x["grown"]:
            y = next(iter(dict(estimates(args.seed, args.count, {k},
                                         ratio=remesh.LEAST_FACE_RATIO)).values()))
        old[k] = dict(rows[k], **{f: y[f] for f in ("model", "est", "warned", "cpu")})
        ref = refs[k]
        d = np.sqrt(np.abs(np.diag(ref)))

        def err(m):
            return 100 * (np.diag(m) - np.diag(ref)) / d ** 2

        line = (f"{k} {rows[k]['family']} levels {'/'.join(map(str, y['levels']))}"
                f" -> {'/'.join(map(str, x['levels']))} ({y['cpu']:.1f} -> {x['cpu']:.1f} s CPU)")
        if x["grown"]:
            line += ": " + ", ".join(f"{DOFS[i]} {a:+.1f} -> {b:+.1f} %"
                                     for i, (a, b) in enumerate(zip(err(y["model"]),
                                                                    err(x["model"]))))
            line += f"; warned {y['warned']} -> {x['warned']}"
        else:
            line += ": the same levels"
        print(line, flush=True)
    print(f"\nFormer rule (added level at {remesh.LEAST_FACE_RATIO} x the panels):\n"
          + tally(old, refs, source))
    print(f"Default (added level at Celik et al.'s r >= 1.3, {remesh.MIN_FACE_RATIO:.2f} x):\n"
          + tally(new, refs, source))
    return 0


if __name__ == "__main__":
    sys.exit(main())

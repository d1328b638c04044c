"""A divergent finest pair not extrapolated, measured on a CAD draw (issue 32, ``fresh32f``; a probe, not adopted).

Stern et al. (2001, "Comprehensive approach to verification and validation of CFD simulations --
Part 1: methodology and procedures", J. Fluids Eng. 123, 793-802, sec. 4) form a Richardson
value only where the three finest solutions converge monotonically, 0 < R_G = e21/e32 < 1;
where R_G > 1 (divergence) none is formed.  With unequal refinement ratios the ratio is taken
on the changes per unit of h^p (p the panel model's formal order, h ~ N^-1/2):

    q = [(phi_3 - phi_2)/(h_3^p - h_2^p)] / [(phi_2 - phi_1)/(h_2^p - h_1^p)]

(1, 2, 3 coarse to fine; q = 1 on an exact power law).  The probe: each shape of the draw
estimated as ``benchmarks.cad_shapes`` does, its panel levels recorded
(:func:`benchmarks.fresh32f_trace.model_ladder`), and each term whose q > 1 takes the finest
level's value instead of the model's (the band shown left as the model's); both (the
default re-run here, not the stored rows) counted
against the most resolved reference of each term as ``benchmarks.cad_seed_best`` counts.
Usage:

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.divergent_pair --seed S --count N \\
        --model DRAW.csv [--plates CSV] [--coarse CSV] [--only K ...]
"""

from __future__ import annotations

import argparse
import sys

import numpy as np

RHO = 1000.0


def divergence_ratio(counts, values, order: float) -> float:
    """q of the three finest of ``values`` (``counts`` panels, coarse to fine) [-]; NaN where
    the middle change is zero."""
    n = np.asarray(counts[-3:], float)
    v = np.asarray(values[-3:], float)
    hp = n ** (-0.5 * order)
    d1, d2 = (v[1] - v[0]) / (hp[1] - hp[0]), (v[2] - v[1]) / (hp[2] - hp[1])
    return float(d2 / d1) if d1 != 0.0 else float("nan")


def divergent_value(info, value, order=None):
    """The model's 6x6 ``value`` with every term whose three finest levels diverge (q > 1)
    replaced by the finest level's (symmetric part), and the mask of those terms."""
    mats = [0.5 * (np.asarray(m) + np.asarray(m).T) for m in info["levels"]]
    counts = info["panels"]
    p = info["formal_order"] if order is None else order
    out, mask = np.array(value, float), np.zeros((6, 6), bool)
    if len(mats) < 3:
        return out, mask
    for i in range(6):
        for j in range(i, 6):
            q = divergence_ratio(counts, [m[i, j] for m in mats], p)
            if q > 1.0:
                out[i, j] = out[j, i] = mats[-1][i, j]
                mask[i, j] = mask[j, i] = True
    return out, mask


def main(argv=None) -> int:
    from benchmarks.cad_seed_best import best, model_rows, tally
    from benchmarks.cad_shapes import DOFS
    from benchmarks.fresh32f_trace import model_ladder

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, required=True)
    ap.add_argument("--count", type=int, default=40)
    ap.add_argument("--model", required=True, help="the draw's benchmarks.cad_shapes CSV")
    ap.add_argument("--plates", default=None)
    ap.add_argument("--coarse", default=None)
    ap.add_argument("--only", type=int, nargs="*", default=None)
    args = ap.parse_args(argv)
    rows = model_rows(args.model)
    keep = sorted(k for k in rows if args.only is None or k in args.only)
    refs, source = best(rows, args.plates, args.coarse)
    alt, base = {}, {}
    for k in keep:
        model, info, cpu = model_ladder(args.seed, k)
        if model is None or info is None:
            print(f"{k}: no panel ladder", flush=True)
            continue
        s = RHO / model.density
        value = np.asarray(model.added_mass) * s
        levels = dict(info, levels=[np.asarray(m) * s for m in info["levels"]])
        new, mask = divergent_value(levels, value)
        x = dict(rows[k])
        x["model"] = new
        alt[k] = x
        base[k] = dict(rows[k], model=value)        # this run's default, not the stored rows
        ref = refs[k]
        changed = [(i, j) for i in range(6) for j in range(i, 6) if mask[i, j]]
        print(f"{k} {x['family']} levels {'/'.join(map(str, info['panels']))} ({cpu:.1f} s): "
              + (", ".join(f"{DOFS[i]}" + ("" if i == j else f"-{DOFS[j]}")
                           + f" {100 * (value[i, j] - ref[i, j]) / np.sqrt(abs(ref[i, i] * ref[j, j])):+.1f}"
                           f" -> {100 * (new[i, j] - ref[i, j]) / np.sqrt(abs(ref[i, i] * ref[j, j])):+.1f} %"
                           for i, j in changed) or "no divergent term"), flush=True)
    print("\nDefault (this run's values):\n" + tally(base, refs, source))
    print("Divergent terms at their finest level:\n" + tally(alt, refs, source))
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""The panel value of an under-refined finest pair, on the stored CAD seeds (issue 32, ``frame32d``).

The option ``value_pair="nested"`` of :func:`stripcoef.hull.panels.panel_added_mass`
(:func:`stripcoef.hull.panel_error.finest_pair_under_refined`): where the finest two of four
levels refine by less than Celik et al.'s r = 1.3 (a level added at the fallback ratio of
1.25 in panels) the value is the nested pairs' extrapolation (levels n-2 and n, n-3 and n-1)
instead of the two finest.  Each shape of each seed is estimated as
``benchmarks.cad_shapes`` does (:func:`benchmarks.cad_shapes.patched_estimates`); where its
levels trigger the rule it is estimated again with the option (the levels' solves reused from
the memo); both against the most resolved reference the
repository holds for the term (:func:`validation.cad_shapes.best_references`: the fine and
edge-graded ones for seed 1375923287, the stored 3,000-face ones for the others).  Counted as
``benchmarks.cad_seed_best`` counts: every diagonal term, each coupling at least 1 % of
sqrt(A_ii A_jj); a term is covered where |model - reference| <= the model's band.  Usage:

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.frame32d_trace [--seed S:N ...] [--only K ...]
"""

from __future__ import annotations

import argparse
import functools
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
RHO = 1000.0
TOL = 0.05
#: the stored seeds and their shape counts (reference_tables/bem/cad_shapes_SEED.csv)
SEEDS = ("1375923287:40", "1380175913:14", "1795919297:40", "3068041537:14")


def _terms(model_ma, band, ref: dict, k: int):
    """[(i, j, relative error over the scale, covered)] of the counted terms."""
    from benchmarks.cad_shapes import SIGNIFICANT

    r = np.zeros((6, 6))
    for i in range(6):
        for j in range(i, 6):
            r[i, j] = r[j, i] = ref[(k, i, j)][0]
    d = np.sqrt(np.abs(np.diag(r)))
    out = []
    for i in range(6):
        for j in range(i, 6):
            scale = d[i] * d[j]
            if i != j and abs(r[i, j]) < SIGNIFICANT * scale:
                continue
            err = model_ma[i, j] - r[i, j]
            out.append((i, j, err / scale, abs(err) <= band[i, j]))
    return out


def tally(rows) -> str:
    diag = [t for t in rows if t[0] == t[1]]
    coup = [t for t in rows if t[0] != t[1]]
    return (f"diagonal within 5 %: {sum(abs(t[2]) <= TOL for t in diag)}/{len(diag)}; "
            f"couplings within 5 % of the scale: {sum(abs(t[2]) <= TOL for t in coup)}/"
            f"{len(coup)}; covered: {sum(t[3] for t in rows)}/{len(rows)} "
            f"({100 * sum(t[3] for t in rows) / max(1, len(rows)):.1f} %)")


def main(argv=None) -> int:
    from benchmarks.cad_shapes import DOFS, patched_estimates
    from stripcoef.hull import panels as P
    from validation.cad_shapes import best_references

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", nargs="+", default=list(SEEDS), metavar="SEED:N")
    ap.add_argument("--only", type=int, nargs="+", default=None, help="shape indices")
    args = ap.parse_args(argv)
    nested = {(P, "panel_added_mass"): functools.partial(P.panel_added_mass,
                                                        value_pair="nested")}
    lines = ["| shape | family | levels | rule | " + " | ".join(DOFS)
             + " | worst coupling | terms covered | CPU [s] |", "|---" * 12 + "|"]
    rows = {"nested": [], "default": []}
    c0 = time.process_time()
    for spec in args.seed:
        seed, count = (int(x) for x in spec.split(":"))
        ref = best_references(ROOT / "reference_tables" / "bem" / f"cad_shapes_{seed}.csv")
        only = set(args.only) if args.only else None
        for k, family, model, cpu in patched_estimates(seed, count, {}, only=only):
            if (k, 0, 0) not in ref:
                continue
            counts = model.conditions["added_mass_panel_levels"]
            variants = [("default", model, cpu)]
            if P.finest_pair_under_refined(counts):
                variants += [("nested", m, c) for _, _, m, c in
                             patched_estimates(seed, k + 1, nested, only={k})]
            else:
                rows["nested"] += _terms(*_scaled(model), ref, k)
            for name, m, c in variants:
                t = _terms(*_scaled(m), ref, k)
                rows[name] += t
                if len(variants) == 1:
                    continue
                diag = {i: e for i, j, e, _ in t if i == j}
                coup = [e for i, j, e, _ in t if i != j]
                lines.append(f"| {seed}:{k} | {family} | " + "/".join(map(str, counts))
                             + f" | {name} | " + " | ".join(f"{100 * diag[i]:+.1f} %"
                                                            for i in range(6))
                             + f" | {100 * max(map(abs, coup), default=0.0):.1f} % | "
                             + f"{sum(x[3] for x in t)}/{len(t)} | {c:.1f} |")
                print(lines[-1], flush=True)
    print("\n".join(lines))
    print(f"\ndefault (the two finest): {tally(rows['default'])}")
    print(f"value_pair='nested':      {tally(rows['nested'])}")
    print(f"CPU {time.process_time() - c0:.0f} s")
    return 0


def _scaled(model):
    """(M_A, its band) at rho = 1000 kg/m^3, the references' density."""
    s = RHO / model.density
    return np.asarray(model.added_mass) * s, np.asarray(model.added_mass_error) * s


if __name__ == "__main__":
    sys.exit(main())

"""The panel method's estimated error and its not-converged rule, measured on a CAD seed.

Replays the shapes of a seed of ``benchmarks.cad_shapes`` as a user has them, runs the whole
estimate (``estimate(load_vehicle(FILE), added_mass_method="panels")``) with the refinement
forced on to ``--max-panels`` (every level the rule could ask for: N/4, N/2, N, 2N, 4N), and
evaluates on those levels, against stored references, each definition of the extrapolated
value's estimated error:

- ``gci+step`` (the rule before issue 32's estimate work): the grid convergence index of the
  finest level (three levels: Oberkampf & Roy's F_s and order; four or more: Eça & Hoekstra's
  least squares) plus the step to the extrapolation (:func:`stripcoef.hull.panels.
  estimated_error`); its ``asymptotic_possible`` taken as False for the plates and frames
  (members thinner than the panels), which reproduces the stored run's 273 of 281 and 37 of
  38 on seed 1375923287;
- ``step``: |A - A_1|; ``change``: |A - A'| (the extrapolation of the pair before);
  ``max(step,change)``; ``step+change`` (:func:`stripcoef.hull.panels.extrapolation_error`,
  the rule adopted);

each at a fixed number of levels and with the refinement rule (start at three levels, add
one while a term's estimated error exceeds 5 % of its scale, up to four or five).  Per rule:
the terms whose estimate covers the actual error (diagonal terms and couplings whose
reference is at least 1 % of the scale), the same with the reference's band added
root-sum-square (ASME V&V 20-2009), the terms within 5 %, the shapes flagged, the shapes
with some term off by more than 5 % that are flagged, and the mean number of levels.

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.panel_estimate_rule --seed 1375923287
        --count 40 --references reference_tables/bem/cad_shapes.csv [--best] [--md OUT]

``--references``: a CSV of ``benchmarks.cad_shapes`` for the same seed (its ``bem`` column
and ``bem_gci_rel`` band); ``--best``: instead, the most resolved reference this repository
holds per term of seed 1375923287 (``validation.cad_shapes.best_references``: edge-graded,
else 12,000-17,000 faces, else the stored 3,000).  Needs the ``remesh`` extra: a shape
solved on the base install's input ladder (two nested pairs, one stage, no refinement family
of three to five levels) is skipped and said so; ``benchmarks.ladder_estimate_rules`` measures
the ladder.  The formal order of k levels is the one the estimate used at the stage that
solved them (:func:`stage_orders`).
"""

from __future__ import annotations

import argparse
import collections
import os
import sys
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from benchmarks.cad_shapes import (DOFS, SIGNIFICANT, patched_estimates,  # noqa: E402
                                   stored_references)

RHO = 1000.0
TOL = 0.05
RULES = ("gci+step", "step", "change", "max(step,change)", "step+change",
         "step+change/(r^p-1)", "stern-oscillatory", "eca-hoekstra-oscillatory")
#: the rules whose value is not the Richardson extrapolation on every term
OSCILLATORY = ("stern-oscillatory", "eca-hoekstra-oscillatory")
MODES = ("3 levels", "4 levels", "5 levels", "refine to 4", "refine to 5")


def capture(seed: int, count: int, max_panels: int, only=None) -> dict:
    """{shape: dict(family, counts, levels (rho 1000), formal orders per stage, mirrors,
    length [m], cpu [s])} of the seed's shapes, the refinement forced to ``max_panels``."""
    import stripcoef.hull.panels as panels

    real_pam, real_order = panels.panel_added_mass, panels.edge_order
    rec: dict = {}

    def order(*a, **k):
        out = real_order(*a, **k)
        rec.setdefault("formal", []).append(out)
        return out

    def forced(*a, **k):
        m, info = real_pam(*a, **dict(k, tolerance=0.0, max_panels=max_panels))
        rec.update(info=info, rho=k["rho"])
        return m, info

    out = {}
    patches = {(panels, "panel_added_mass"): forced, (panels, "edge_order"): order}
    for k, family, model, cpu in patched_estimates(seed, count, patches, only, rec.clear):
        info = rec["info"]
        if "nested pairs" in info["family"]:
            # the base install's input ladder (two nested pairs, one stage: no refinement
            # family whose three, four, five levels could be compared)
            print(f"{k:3d} {family:12s} skipped: its levels are the input ladder (two nested "
                  f"pairs); python -m benchmarks.ladder_estimate_rules measures it", flush=True)
            continue
        out[k] = dict(family=family, counts=tuple(info["panels"]),
                      levels=[np.asarray(m) * RHO / rec["rho"] for m in info["levels"]],
                      formal=stage_orders(rec["formal"], len(info["panels"])),
                      mirrors=tuple(model.conditions["mirror_planes"] or ()),
                      length=info["length"], cpu=cpu)
        print(f"{k:3d} {family:12s} panels {'/'.join(map(str, info['panels']))}, "
              f"CPU {out[k]['cpu']:.2f} s", flush=True)
    return out


def stage_orders(calls, n_levels: int) -> dict:
    """{number of levels: the formal order the estimate used with them} from the estimate's
    ``edge_order`` calls, one per refinement stage: the first stage solves the initial
    levels (three remeshed, four on the input ladder), each later stage adds one, so the
    first call belongs to ``n_levels - len(calls) + 1`` levels.  Fewer levels than the
    first stage's take its order (the estimate never judged them)."""
    first = n_levels - len(calls) + 1
    orders = {first + i: p for i, p in enumerate(calls)}
    for k in range(1, first):
        orders[k] = calls[0]
    return orders


def rules_at(shape: dict, k_levels: int) -> tuple:
    """(extrapolated M_A, {rule: estimated error}) of the first ``k_levels`` levels."""
    from stripcoef.hull.convergence import (grid_convergence_index, least_squares_band,
                                            richardson)
    from stripcoef.hull.panels import estimated_error, extrapolation_error

    mats, n = shape["levels"][:k_levels], shape["counts"][:k_levels]
    p = shape["formal"][k_levels]
    a = richardson(mats[-2], mats[-1], n[-2], n[-1], order=p)
    sym = 0.5 * (a + a.T)
    fine = mats[-1]
    asym = np.abs(fine - fine.T)
    gci, _, _ = grid_convergence_index(mats[-3:], n[-3:], formal_order=p,
                                       asymptotic_possible=shape["family"] not in ("plate",
                                                                                   "frame"))
    if k_levels >= 4:
        gci, _, _ = least_squares_band(n, mats)
    before = richardson(mats[-3], mats[-2], n[-3], n[-2], order=p)
    step = np.abs(sym - 0.5 * (fine + fine.T))
    change = np.abs(sym - 0.5 * (before + before.T))
    out = {"gci+step": estimated_error(fine, a, gci),
           "step": np.maximum(step, asym), "change": np.maximum(change, asym),
           "max(step,change)": np.maximum(np.maximum(step, change), asym),
           "step+change": extrapolation_error(mats, n, p)}
    # the change read as Richardson's error estimate of the finer of the two extrapolations,
    # a refinement r = sqrt(N_1 / N_2) apart at the formal order (Roache 1998 eq. 5.4.1)
    r = np.sqrt(n[-1] / n[-2])
    e = step + change / (r ** p - 1.0)
    out["step+change/(r^p-1)"] = np.maximum(np.maximum(e, e.T), asym)
    values = {r: sym for r in out}
    for rule in OSCILLATORY:
        values[rule], out[rule] = oscillatory(mats, n, sym, out["step+change"], rule)
    return values, out


def oscillatory(mats, counts, value, error, rule: str) -> tuple:
    r"""(value, estimated error) per term where the three finest levels oscillate, the
    extrapolation ``value`` and its ``error`` elsewhere.

    The convergence ratio of the three finest levels, :math:`R = \varepsilon_{21} /
    \varepsilon_{32}` (:math:`\varepsilon_{21} = S_1 - S_2`, 1 the finest; Stern, Wilson,
    Coleman & Paterson 2001, "Comprehensive approach to verification and validation of CFD
    simulations -- Part 1", J. Fluids Eng. 123, 793-802, sec. "Verification", eq. 18):
    :math:`R < 0` is oscillatory convergence, where no Richardson extrapolation applies.
    There (each term alone, on the symmetrised levels):

    - ``stern-oscillatory``: the finest level, its uncertainty half the range of the
      oscillation, :math:`U = \tfrac12 (S_U - S_L)` over the three levels (Stern et al. 2001,
      eq. 24);
    - ``eca-hoekstra-oscillatory``: the finest level, its uncertainty Eça & Hoekstra's
      least squares over every level (2014, J. Comput. Phys. 262, 104-130: sec. 3, eqs. 18-21,
      the observed order fitted and, where the fit's standard deviation exceeds the data
      range, :math:`U = 3\sigma/\Delta_\phi\,(\varepsilon + \sigma + |\phi_1 -
      \phi_{fit}|)`; :func:`stripcoef.hull.convergence.least_squares_band`), at least
      Stern's half range; needs four levels (three: Stern's).
    """
    from stripcoef.hull.convergence import least_squares_band

    sym = [0.5 * (np.asarray(m) + np.asarray(m).T) for m in mats]
    s3, s2, s1 = sym[-3], sym[-2], sym[-1]
    osc = (s1 - s2) * (s2 - s3) < 0
    half = 0.5 * (np.maximum(np.maximum(s1, s2), s3) - np.minimum(np.minimum(s1, s2), s3))
    band = half
    if rule == "eca-hoekstra-oscillatory" and len(mats) >= 4:
        band = np.maximum(least_squares_band(counts, sym)[0], half)
    fine = np.asarray(mats[-1])
    asym = np.abs(fine - fine.T)
    return (np.where(osc, s1, value), np.where(osc, np.maximum(band, asym), error))


def _planes(matrix, mirrors):
    """The couplings the mirror planes forbid set to zero, as the estimate writes them."""
    from stripcoef.assembly.symmetry import enforce_symmetry

    return enforce_symmetry(matrix, mirrors) if mirrors else np.asarray(matrix)


def evaluate(shapes: dict, refs: dict, bands: dict) -> dict:
    """Per (rule, mode): the counts of the module docstring."""
    from stripcoef.hull.panels import relative_error

    stats: dict = collections.defaultdict(collections.Counter)
    for k, s in sorted(shapes.items()):
        if k not in refs:
            continue
        ref, band = refs[k], np.nan_to_num(bands[k], nan=0.0)
        d = np.sqrt(np.abs(np.diag(ref)))
        scale = np.outer(d, d)
        sig = (np.eye(6, dtype=bool) | (np.abs(ref) >= SIGNIFICANT * scale)) \
            & np.triu(np.ones((6, 6), bool))
        levels = {}
        for kl in range(3, len(s["counts"]) + 1):
            a, est = rules_at(s, kl)
            levels[kl] = ({r: _planes(v, s["mirrors"]) for r, v in a.items()},
                          {r: _planes(e, s["mirrors"]) for r, e in est.items()})
        for rule in RULES:
            for mode in MODES:
                last = int(mode[0]) if mode[0].isdigit() else int(mode[-1])
                kl = last
                if mode.startswith("refine"):
                    kl = 3
                    while kl < last and kl + 1 in levels and relative_error(
                            levels[kl][0][rule], levels[kl][1][rule], s["length"]).max() > TOL:
                        kl += 1
                if kl not in levels:
                    continue
                a, est = levels[kl][0][rule], levels[kl][1][rule]
                err = np.abs(a - ref)
                x = stats[(rule, mode)]
                x["terms"] += int(sig.sum())
                x["covered"] += int((err[sig] <= est[sig]).sum())
                x["covered_rss"] += int((err[sig] <= np.hypot(est, band)[sig]).sum())
                x["within"] += int((err[sig] <= TOL * scale[sig]).sum())
                flagged = bool(relative_error(a, est, s["length"]).max() > TOL)
                off = bool((err[sig] > TOL * scale[sig]).any())
                x["shapes"] += 1
                x["flagged"] += flagged
                x["off"] += off
                x["off_flagged"] += off and flagged
                x["levels"] += kl
                for i in range(6):
                    if err[i, i] > TOL * scale[i, i]:
                        stats[("misses", rule, mode)][
                            f"{k} {s['family']} {DOFS[i]} {100 * (a[i, i] - ref[i, i]) / ref[i, i]:+.1f} %"
                            f" (est. {100 * est[i, i] / abs(ref[i, i]):.1f} %"
                            + (", warned)" if flagged else ")")] += 1
    return stats


def table(stats: dict) -> str:
    lines = ["| levels | rule | covers actual | with the reference's band | within 5 % | "
             "shapes flagged | off by > 5 % and flagged | mean levels |",
             "|---|---|---|---|---|---|---|---|"]
    for mode in MODES:
        for rule in RULES:
            x = stats.get((rule, mode))
            if not x:
                continue
            lines.append(f"| {mode} | {rule} | {x['covered']}/{x['terms']} "
                         f"({100 * x['covered'] / x['terms']:.1f} %) | "
                         f"{100 * x['covered_rss'] / x['terms']:.1f} % | "
                         f"{x['within']}/{x['terms']} | {x['flagged']}/{x['shapes']} | "
                         f"{x['off_flagged']}/{x['off']} | {x['levels'] / x['shapes']:.2f} |")
    for mode in MODES:
        for rule in RULES:
            miss = stats.get(("misses", rule, mode))
            if miss and mode == "4 levels":
                lines.append(f"\n{mode}, {rule}: diagonal terms off by more than 5 %: "
                             + "; ".join(miss))
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, required=True)
    ap.add_argument("--count", type=int, default=40)
    ap.add_argument("--references", required=True, metavar="CSV",
                    help="a benchmarks.cad_shapes CSV of the same seed")
    ap.add_argument("--best", action="store_true",
                    help="the most resolved references of seed 1375923287 instead")
    ap.add_argument("--max-panels", type=int, default=6400)
    ap.add_argument("--md", default=None, help="write the table to this Markdown file")
    args = ap.parse_args(argv)
    stored = stored_references(args.references)
    sets = {"the references of " + args.references: (
        {k: x["ref"] for k, x in stored.items()}, {k: x["gci"] for k, x in stored.items()})}
    if args.best:
        from validation.cad_shapes import best_matrices

        sets["the most resolved reference of each term (validation.cad_shapes."
             "best_references)"] = best_matrices(args.references)
    shapes = capture(args.seed, args.count, args.max_panels, only=set(stored))
    cpu = np.array([s["cpu"] for s in shapes.values()])
    text = (f"`python -m benchmarks.panel_estimate_rule --seed {args.seed} --count "
            f"{args.count} --references {args.references}" + (" --best" if args.best else "")
            + f"` ({len(shapes)} shapes; the whole estimate with every level to "
            f"{args.max_panels} panels: CPU median {np.median(cpu):.2f} s, max "
            f"{cpu.max():.2f} s)\n")
    for name, (refs, bands) in sets.items():
        text += f"\nAgainst {name}:\n\n" + table(evaluate(shapes, refs, bands)) + "\n"
    print("\n" + text)
    if args.md:
        Path(args.md).write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())

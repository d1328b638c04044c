"""The order of the panel method's extrapolated value on the CAD shapes (issue 32).

``stripcoef.hull.panels.panel_added_mass`` extrapolated each term from its two finest levels
at order 2 in the panel size h (the error of constant panels on a smooth body ~ 1/N; Hess &
Smith 1967; since ``benchmarks.graded_value_order`` it takes the formal order), while its
grid convergence index already took the body's formal order
``edge_order`` (4/3 at a right-angled edge, 1 at a knife edge or a member thinner than the
finest panel: the edge singularity r^(pi/omega), von Petersdorff & Stephan 1990).  Where the
levels converge at that lower order, Richardson's value at order 2 removes only
(r - 1)/(r^2 - 1) of the remaining error.  This benchmark re-runs the stored CAD run's model
(``benchmarks.cad_shapes --references``) with the levels recorded (a wrapper around
``stripcoef.hull.panels._solve_level`` and ``panel_added_mass`` for the run's duration;
nothing in the library changes), re-extrapolates the two finest levels at order 2 (the
library's value, checked), at the formal order and at order 1 (Roache 1998 eq. 5.4.1), and
compares each with the most resolved reference this repository holds for the term
(``validation.cad_shapes.best_references``: the edge-graded levels, else the fine uniform,
else the stored 3,000-face ones); the library's estimate (its index plus the step from the
finest level to the value) is re-formed around each value.  Two more values the verification
literature names are measured beside them (issue 32, `order32`): the two finest levels
extrapolated at each term's observed order (Celik et al. 2008) within Eça & Hoekstra's (2014)
[0.5, 2], and the finest level itself (Roache 1998 ch. 5: the index is a band about the
fine-grid solution).  The base install's input family (two nested pairs, each split in four) is
extrapolated as the library does, the finer pair.  Usage:

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.cad_value_order [--md FILE] [--save PICKLE]
    python -m benchmarks.cad_value_order --load PICKLE [--md FILE]

(a few minutes: the model of the 38 shapes of seed 1375923287; measured 2026-11-29: 36 s user
+ 12 s sys with the remesh extra, 43 + 16 s in the base install; ``--load`` compares levels
kept by ``--save`` with the references as they are now).
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
REFS = ROOT / "reference_tables" / "bem" / "cad_shapes_1375923287.csv"
DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")


def recorded_run(seed=1375923287, count=40, only=None):
    """{shape: (counts, [6x6 per level], formal order, model's value, its estimated error)}
    of the stored run's
    model, the panel levels recorded while ``benchmarks.cad_shapes`` re-runs it (about the
    run's own reference point, rho = 1000 kg/m^3 times the model's density ratio undone);
    ``only``: these shapes of the run alone (the others' rows left out of the references
    it re-runs on, so that it skips them)."""
    import benchmarks.cad_shapes as CS
    import stripcoef.hull.panels as P

    solve, pam, run_one = P._solve_level, P.panel_added_mass, CS.run_one
    levels: list = []
    calls: list = []
    out: dict = {}

    def solve_rec(*a, **kw):
        n, m = solve(*a, **kw)
        levels.append((n, np.array(m, float)))
        return n, m

    def pam_rec(*a, **kw):
        levels.clear()
        value, info = pam(*a, **kw)
        calls.append((list(levels), info, np.array(value, float), kw.get("rho")))
        return value, info

    def run_rec(family, rng, tmp, bem_faces, stored=None):
        calls.clear()
        r = run_one(family, rng, tmp, bem_faces, stored)
        lv, info, value, rho = calls[-1]
        n = [c for c, _ in lv]
        k = len(out)
        out[k] = (n, [m * 1000.0 / rho for _, m in lv], float(info["formal_order"]),
                  value * 1000.0 / rho, np.asarray(info["error"], float) * 1000.0 / rho)
        return r

    P._solve_level, P.panel_added_mass, CS.run_one = solve_rec, pam_rec, run_rec
    try:
        with tempfile.TemporaryDirectory() as tmp:
            refs = REFS
            if only is not None:
                refs = Path(tmp) / "references.csv"
                lines = REFS.read_text().splitlines(keepends=True)
                refs.write_text("".join(lines[:2]) + "".join(
                    ln for ln in lines[2:] if int(ln.split(",", 1)[0]) in set(only)))
            CS.main(["--seed", str(seed), "--count", str(count), "--references", str(refs),
                     "--csv", str(Path(tmp) / "run.csv")])
            shapes = sorted(CS.stored_references(refs))
    finally:
        P._solve_level, P.panel_added_mass, CS.run_one = solve, pam, run_one
    return {shapes[k]: v for k, v in out.items()}


def ladder(n, mats=None, formal=None, value=None) -> bool:
    """Whether the levels ``n`` are the input family's two nested pairs (its input split in
    four twice over: :mod:`stripcoef.hull.input_ladder`, N_3 = 4 N_1 and N_4 = 4 N_2), whose
    value is the finer pair's extrapolation; with the levels ``mats``, the ``formal`` order
    and the library's ``value`` given, also that the finer pair's extrapolation is the one
    that returns the value (a graded plate's counts 416/800/1664/3200 are four times over too,
    its value the two finest levels')."""
    from stripcoef.hull.convergence import richardson

    if not (len(n) == 4 and n[2] == 4 * n[0] and n[3] == 4 * n[1]):
        return False
    if value is None:
        return True
    pair = richardson(mats[1], mats[3], n[1], n[3], order=formal)
    last = richardson(mats[2], mats[3], n[2], n[3], order=formal)
    return float(np.abs(pair - value).max()) < float(np.abs(last - value).max())


def observed_value(n, mats, pairs: bool = False):
    """The two finest levels Richardson-extrapolated at each term's observed order (Celik et
    al. 2008 eqs. 3-5 over the three finest levels, :func:`stripcoef.hull.convergence.
    observed_order`) bounded to Eça & Hoekstra's (2014, sec. 3) range of the free order,
    [0.5, 2]; a term whose levels oscillate (no observed order) at order 2 (their fixed
    alternative of the smooth body).  ``pairs``: the levels are two nested pairs
    (:func:`ladder`), the order that of the two pairs' changes."""
    from stripcoef.hull.convergence import (EH_ORDER_FIXED, EH_ORDER_LOW, observed_order,
                                            richardson)

    if len(mats) < 3:
        return richardson(mats[-2], mats[-1], n[-2], n[-1], order=2.0)
    if pairs:
        # two nested pairs, each split in four (r = 2): the observed order of the two pairs'
        # changes, d_fine / d_coarse = (h_2 / h_1)^p (the same error constant C h^p on both)
        d0, d1 = mats[2] - mats[0], mats[3] - mats[1]
        with np.errstate(divide="ignore", invalid="ignore"):
            p = np.log(d1 / d0) / np.log(np.sqrt(n[0] / n[1]))
        p = np.where(np.isfinite(p) & (d1 / d0 > 0), np.clip(p, EH_ORDER_LOW, EH_ORDER_FIXED),
                     2.0)
        return mats[3] + (mats[3] - mats[1]) / (2.0 ** p - 1.0)
    h = np.asarray(n[-3:], float) ** -0.5
    p = observed_order(mats[-1], mats[-2], mats[-3], h[1] / h[2], h[0] / h[1])
    p = np.where(np.isfinite(p), np.clip(p, EH_ORDER_LOW, EH_ORDER_FIXED), 2.0)
    r = (float(n[-1]) / float(n[-2])) ** 0.5
    return mats[-1] + (mats[-1] - mats[-2]) / (r ** p - 1.0)


def compare(recorded):
    """Rows per term of the recorded run against the best references: the errors of the
    value at order 2 (the library's), at the formal order and at order 1, relative to the
    reference's diagonal scale; and of two values the verification literature names: the
    two finest levels extrapolated at the observed order (:func:`observed_value`) and the
    finest level itself (the fine-grid solution that Roache's index and ASME V&V 20's
    numerical uncertainty are a band about; Roache 1998 ch. 5), each with the library's
    index re-formed around it (the index plus the step from the finest level)."""
    from stripcoef.hull.convergence import richardson
    from validation.cad_shapes import best_comparison

    rows = []
    for r in best_comparison():
        k, i, j = r["shape"], r["i"], r["j"]
        if k not in recorded:
            continue
        n, mats, formal, value, error = recorded[k]
        # the base install's ladder: the finer pair (levels 2 and 4) extrapolated, as the
        # library does (panel_error.ladder_extrapolation)
        pairs = ladder(n, mats, formal, value)
        c, f = (1, 3) if pairs else (-2, -1)
        full = {p: richardson(mats[c], mats[f], n[c], n[f], order=p)
                for p in (2.0, formal, 1.0)}
        a = {p: x[i, j] for p, x in full.items()}
        obs, fin = observed_value(n, mats, pairs)[i, j], mats[-1][i, j]
        # the order of the library's own value (2 until issue 32's graded references, the
        # formal order since): the extrapolation that returns the recorded value
        p_lib = min((2.0, formal), key=lambda p: float(np.abs(full[p] - value).max()))
        ref, norm = r["ref"], r["norm"]
        # the library's estimate, GCI + |A - A_1| (stripcoef.hull.panels.estimated_error):
        # its index recovered from the library's value, the step taken from each value
        fine = mats[-1][i, j]
        gci = max(error[i, j] - abs(a[p_lib] - fine), 0.0)
        est = {p: gci + abs(a[p] - fine) for p in a}
        est_obs, est_fin = gci + abs(obs - fine), gci
        rows.append(dict(shape=k, family=r["family"], i=i, j=j, formal=formal,
                         significant=r["significant"], source=r["source"], band=r["band"],
                         p_lib=p_lib, stored=r["err"], checked=(a[p_lib] - ref) / norm,
                         lib=(a[2.0] - ref) / norm,
                         formal_err=(a[formal] - ref) / norm, one=(a[1.0] - ref) / norm,
                         observed=(obs - ref) / norm, finest=(fin - ref) / norm,
                         cov={"lib": abs(a[2.0] - ref) <= est[2.0],
                              "formal_err": abs(a[formal] - ref) <= est[formal],
                              "one": abs(a[1.0] - ref) <= est[1.0],
                              "observed": abs(obs - ref) <= est_obs,
                              "finest": abs(fin - ref) <= est_fin},
                         est={"lib": est[2.0] / norm, "formal_err": est[formal] / norm,
                              "one": est[1.0] / norm, "observed": est_obs / norm,
                              "finest": est_fin / norm}))
    return rows


def summary(rows) -> str:
    diag = [r for r in rows if r["i"] == r["j"]]
    sig = [r for r in rows if r["significant"] and r["i"] != r["j"]]
    lines = ["| value extrapolated at | diagonal terms within 5 % | median abs. error | max | "
             "couplings within 5 % of scale | the estimate covers (significant terms) | "
             "median diagonal estimate |", "|---|---|---|---|---|---|---|"]
    allsig = diag + sig
    for label, key in (("order 2", "lib"), ("the formal edge order", "formal_err"),
                       ("order 1", "one"),
                       ("the observed order, in [0.5, 2]", "observed"),
                       ("the finest level (not extrapolated)", "finest")):
        e = np.abs([r[key] for r in diag])
        c = np.abs([r[key] for r in sig])
        lines.append(f"| {label} | {int((e <= 0.05).sum())} of {len(e)} | "
                     f"{100 * np.median(e):.2f} % | {100 * e.max():.1f} % | "
                     f"{int((c <= 0.05).sum())} of {len(c)} | "
                     f"{sum(r['cov'][key] for r in allsig)} of {len(allsig)} | "
                     f"{100 * np.median([r['est'][key] for r in diag]):.1f} % |")
    fam = sorted({r["family"] for r in diag})
    keys = ("lib", "formal_err", "one", "observed", "finest")
    lines += ["", "| family | terms | within 5 %: order 2 / formal / 1 / observed / finest | "
              "median abs. error: order 2 / formal / 1 / observed / finest |", "|---|---|---|---|"]
    for f in fam:
        d = [r for r in diag if r["family"] == f]
        w = [sum(abs(r[k]) <= 0.05 for r in d) for k in keys]
        m = [100 * np.median(np.abs([r[k] for r in d])) for k in keys]
        lines.append(f"| {f} | {len(d)} | " + " / ".join(map(str, w)) + " | "
                     + " / ".join(f"{x:.2f}" for x in m) + " % |")
    worst = sorted(diag, key=lambda r: -max(abs(r[k]) for k in ("formal_err", "observed",
                                                                 "finest")))[:12]
    lines += ["", "| # | family | term | formal order | order 2 | formal | order 1 | observed | "
              "finest | reference (band) |", "|---|---|---|---|---|---|---|---|---|---|"]
    lines += [f"| {r['shape']} | {r['family']} | {DOFS[r['i']]} | {r['formal']:.2f} | "
              f"{100 * r['lib']:+.1f} % | {100 * r['formal_err']:+.1f} % | "
              f"{100 * r['one']:+.1f} % | {100 * r['observed']:+.1f} % | "
              f"{100 * r['finest']:+.1f} % | {r['source']} ({100 * r['band']:.1f} %) |"
              for r in worst]
    check = max(abs(r["checked"] - r["stored"]) for r in rows)
    lib = sorted({"2" if r["p_lib"] == 2.0 else "the formal order" for r in rows})
    lines += ["", f"(The library's value is the one at {' and at '.join(lib)}; re-computed "
              f"from the recorded levels it differs from the stored run's model "
              f"(`reference_tables/bem/cad_shapes.csv`) by at most {100 * check:.3f} % of the "
              "scale.)"]
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--md", default=None, help="write the summary here")
    ap.add_argument("--save", default=None, metavar="PICKLE",
                    help="keep the recorded levels here (a file outside the repository)")
    ap.add_argument("--load", default=None, metavar="PICKLE",
                    help="compare the levels --save kept instead of re-running the model")
    args = ap.parse_args(argv)
    import pickle

    if args.load:
        with open(args.load, "rb") as fh:
            recorded = pickle.load(fh)
    else:
        recorded = recorded_run()
    if args.save:
        with open(args.save, "wb") as fh:
            pickle.dump(recorded, fh)
    text = summary(compare(recorded))
    print(text)
    if args.md:
        Path(args.md).write_text(
            "# The order of the panel method's extrapolated value (benchmarks.cad_value_order)\n\n"
            "`OPENBLAS_NUM_THREADS=1 python -m benchmarks.cad_value_order --md "
            f"{args.md}`\n\n" + text)
    return 0


if __name__ == "__main__":
    sys.exit(main())

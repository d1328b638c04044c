"""Do held-out references fall inside the stated 95 % bands as often as the bands claim?

Never against the references that set a band. Two checks:

1. **Leave one shape out, within the BEM / exact sets.** The method bands are set from
   reference_tables/method_errors/method_errors.csv (scripts/make_method_uncertainty.py: stripcoef against
   Lamb's exact solutions and converged Capytaine runs). For each shape, its band is re-made
   from the OTHER shapes of its class and family (sd = q95 / 1.96 of their |ln(strip/ref)|,
   stripcoef.study.calibration) and its own terms are checked against it. For a diagonal
   term the band of the sampling, a e^(+-1.96 sigma), is exact (one lognormal factor per DOF
   group), so no Monte Carlo is needed here; for a coupling it is a +- 1.96 sigma_c
   sqrt(A_ii A_jj) about the model's value, zero or not, for every coupling the shape's mirror
   symmetries allow (stripcoef.study.sources.couple; the ``allowed`` column of the errors
   file, stripcoef.assembly.symmetry) or the model has (>= 1 %); any other stays at the model's
   value and is inside only if that is the reference's; the congruence's own spread left out (it only widens
   the band). The translational quadratic drag is checked the same way where the errors file
   has it (matrix quadratic_damping: measured whole-body drag of simple bodies,
   reference_tables/body_drag_3d, benchmarks/drag_bodies.py).
2. **Held-out papers.** The VideoRay Pro III's measured coefficients (Wang & Clark 2006,
   Table I, Experimental column; reference_tables/videoray_pro3) against the bands of the
   shipped table from a Monte Carlo study (stripcoef.study.uncertainty, method error only).
   No VideoRay number sets any band. Each term is counted under the basis of the row of the
   shipped table it was sampled with (measured or assumed: src/stripcoef/data/method_uncertainty.csv).
   Linear damping is not predicted by the method (its drag
   is quadratic): those rows are printed as excluded, with that reason, and not counted.
   The other papers cannot be checked here: ROV II (Eng et al. 2009) and ROMEO (Indiveri 1998)
   have no geometry in the repository, and MARES (Ferreira et al. 2009) has no surviving
   numbers (reference_tables/*/README.md).

Coverage is given with its exact 95 % binomial (Clopper-Pearson) interval: a claimed 95 %
outside it is a real miss; inside it, the n items cannot tell. The verdict is against 95 %,
the rate the printed [P2.5, P97.5] bands are read at; a band made from fewer than 19 terms
claims only k/(n+1) (split-conformal, stripcoef.study.calibration), given in its own column.
Terms of one shape are correlated (one factor per DOF group; Y and Z alike on a body of
revolution): the effective number of items is smaller than the count, so the intervals are
if anything too narrow.

Run: python -m benchmarks.band_coverage [--samples 256] [--write]   (about 10-20 s)
"""

from __future__ import annotations

import argparse
import datetime
import os
import sys
from pathlib import Path

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

ROOT = Path(__file__).resolve().parent.parent

import numpy as np  # noqa: E402

from stripcoef.study.calibration import (binomial_interval, claimed_coverage,  # noqa: E402
                                         leave_one_group_out)
from stripcoef.study.shapes import CLASSES  # noqa: E402
from stripcoef.study.sources import PANELS  # noqa: E402

OUT = ROOT / "benchmarks" / "data" / "band_coverage.md"
CLAIM = 0.95


def _rate(k, n):
    lo, hi = binomial_interval(k, n)
    verdict = ("no band (one shape)" if n == 0 else
               "consistent with 95 %" if lo <= CLAIM <= hi else
               ("too narrow" if hi < CLAIM else "too wide"))
    return (f"{k}/{n}" if n else "-", f"{100 * k / n:.0f} %" if n else "-",
            f"[{100 * lo:.0f}, {100 * hi:.0f}] %" if n else "-", verdict)


def _moved(row) -> bool:
    """Whether the sampling moves this coupling (stripcoef.study.sources.couple): the shape's
    mirror symmetries allow it (``allowed`` of reference_tables/method_errors/method_errors.csv,
    stripcoef.assembly.symmetry), or the model has it, >= 1 % of sqrt(A_ii A_jj) (the scale
    recovered from the stored error, (strip - ref) / scale)."""
    a, ref, e = float(row["strip"]), float(row["reference"]), float(row["error"])
    has = e != 0 and abs(a) >= 0.01 * abs((a - ref) / e)
    return row["allowed"] == "yes" or has


def cross_validation(rows):
    """(table lines, per-class (k, n)) of the leave-one-shape-out check."""
    lines = ["| class | family | shapes | inside / terms | rate | 95 % interval | verdict | "
             "claim k/(n+1) | outside (shape term error) |", "|---|---|---|---|---|---|---|---|---|"]
    per_class, diagonal = {}, [0, 0]
    for cls, matrix, fam in [(c, m, f) for c in (*CLASSES, PANELS)
                             for m in ("added_mass", "quadratic_damping")
                             for f in ("translation", "rotation", "coupling")]:
        sel = [r for r in rows if r["class"] == cls and r["family"] == fam
               and r.get("matrix", "added_mass") == matrix]
        if not sel:
            continue
        err = np.array([float(r["error"]) for r in sel])
        groups = np.array([r["shape"] for r in sel])
        shapes = np.unique(groups)
        ok = leave_one_group_out(err, groups)
        if fam == "coupling":
            # the sampling moves every coupling the symmetries allow (stripcoef.study
            # .sources.couple), zero in the model or not; a forbidden one stays where the
            # model has it: inside only if the error is zero
            moved = np.array([_moved(r) for r in sel])
            ok = np.where(moved, ok, err == 0.0)
        n = len(sel) if shapes.size > 1 else 0
        k = int(ok.sum()) if n else 0
        kk, nn = per_class.get(cls, (0, 0))
        per_class[cls] = (kk + k, nn + n)
        if fam != "coupling" and cls != PANELS:   # the same shapes again: not pooled
            diagonal[0] += k
            diagonal[1] += n
        miss = "; ".join(f"{r['shape']} {r['term']} {float(r['error']):+.3g}"
                         + (" (forbidden by its symmetry, zero in the model: not moved)"
                            if fam == "coupling" and not _moved(r) else "")
                         for r, o in zip(sel, ok) if not o) if n else \
            "one shape only: nothing to leave out"
        cnt, rate, ci, verdict = _rate(k, n)
        # what each fold's band claims: k/(n+1) of the other shapes' term count
        claim = np.mean([claimed_coverage(int((groups != g).sum())) for g in groups]) \
            if n else float("nan")
        lines.append(f"| {cls} | {matrix.replace('_', ' ')} {fam}{'s' if fam == 'coupling' else ''} | {shapes.size} | {cnt} | {rate} | {ci} | "
                     f"{verdict} | {f'{100 * claim:.0f} %' if n else '-'} | {miss or '-'} |")
    return lines, per_class, tuple(diagonal)


def held_out(samples):
    """(table lines, {band basis: (k, n)}, excluded lines, class) of the VideoRay check against
    the shipped bands."""
    from stripcoef.study.uncertainty import uncertainty
    from validation.reference import load_table

    from stripcoef.study.sources import _method_table

    path = ROOT / "geometry" / "videoray_pro3.yaml"
    res = uncertainty(path, samples=samples, seed=0, limits=False, workers=1, progress=False)
    bases = {(r["class"], r["matrix"], r["dofs"]): r["basis"] for r in _method_table()}
    panels = _panels(path)
    summ = res.summary()
    scope = {src.name: src.in_scope for src in res.sources if src.kind == "method"}
    lines = ["| reference | class | term | measured | nominal | P2.5 | P97.5 | band basis | inside |",
             "|---|---|---|---|---|---|---|---|---|"]
    excluded, counts = [], {}
    for table in ("table1_added_mass", "table1_quadratic_drag", "table1_linear_drag"):
        for row in load_table("videoray_pro3", table):
            if not row["name"].endswith(".experimental"):
                continue
            name = row["name"].split(".")[0]
            ref = -row["value"]
            s = summ[name]
            if table == "table1_linear_drag":
                excluded.append(f"- {name} = {ref:.4g} (measured): not predicted -- the method's "
                                f"drag is quadratic, its linear part only the Reynolds-number "
                                f"share (nominal {s['nominal']:.3g}); outside the model, not "
                                f"counted")
                continue
            lo, hi = sorted((s["p2.5"], s["p97.5"]))
            ok = lo <= ref <= hi
            matrix = "added_mass" if name.endswith("dot") else "quadratic_damping"
            group = "translation" if name[0] in "XYZ" else "rotation"
            basis = bases[(PANELS if matrix == "added_mass" and panels else res.shape_class,
                           matrix, group)]
            basis = {"measured": "measured (BEM/exact sets)" if matrix == "added_mass" else
                     "measured (published 3D drag)" if group == "translation" else
                     "measured (stored OpenFOAM rotations)"}.get(basis, basis)
            if not scope.get(f"{matrix}.{group}", True):
                basis += ", extrapolated (vehicle's L/D outside its reference bodies')"
            kk, nn = counts.get(basis, (0, 0))
            counts[basis] = (kk + ok, nn + 1)
            lines.append(f"| VideoRay Pro III, Wang & Clark 2006 Table I (measured) | "
                         f"{res.shape_class} | {name} | {ref:.4g} | {s['nominal']:.4g} | "
                         f"{lo:.4g} | {hi:.4g} | {matrix.replace('_', ' ')} {group}: {basis} | "
                         f"{'yes' if ok else '**no**'} |")
    return lines, counts, excluded, res.shape_class


def _panels(path) -> bool:
    """Whether the VideoRay model's added mass is the panel method's (then its added-mass
    rows are the ``panels`` rows; its damping keeps its class's)."""
    from stripcoef.geometry.vehicle import load_vehicle
    from stripcoef.study.sources import uses_panels

    return uses_panels(load_vehicle(path))


def main(argv=None):
    from validation.method_errors import read_errors

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--samples", type=int, default=256)
    ap.add_argument("--write", action="store_true", help=f"also write {OUT.relative_to(ROOT)}")
    args = ap.parse_args(argv)
    rows = read_errors()
    cv_lines, per_class, diagonal = cross_validation(rows)
    n_panel_shapes = len({r["shape"] for r in rows if r["class"] == PANELS})
    ho_lines, counts, excluded, vr_class = held_out(args.samples)
    summary = ["| class | check | inside / items | rate | 95 % interval | verdict |",
               "|---|---|---|---|---|---|"]
    for cls in (*CLASSES, PANELS):
        kk, nn = per_class.get(cls, (0, 0))
        what = (f"3D panel method, {n_panel_shapes} bluff shapes" if cls == PANELS else
                "BEM / exact; published 3D drag")
        summary.append(f"| {cls} | leave one shape out ({what}) | "
                       + " | ".join(_rate(kk, nn)) + " |")
    # strip theory's classes only: the panel rows are the same shapes by another method
    pooled = [sum(per_class.get(c, (0, 0))[i] for c in CLASSES) for i in (0, 1)]
    summary.append("| all classes | leave one shape out (BEM / exact; published 3D drag) | "
                   + " | ".join(_rate(*pooled)) + " |")
    summary.append("| all classes, diagonal terms only | leave one shape out (BEM / exact; published 3D drag) | "
                   + " | ".join(_rate(*diagonal)) + " |")
    k = sum(c[0] for c in counts.values())
    n = sum(c[1] for c in counts.values())
    summary.append(f"| {vr_class} (VideoRay) | held-out paper (measured), all | "
                   + " | ".join(_rate(k, n)) + " |")
    for basis, (kk, nn) in counts.items():
        summary.append(f"| {vr_class} (VideoRay) | held-out paper, bands {basis} | "
                       + " | ".join(_rate(kk, nn)) + " |")
    text = "\n".join([
        f"`python -m benchmarks.band_coverage --samples {args.samples}` "
        f"({datetime.date.today().isoformat()}). Bands: src/stripcoef/data/method_uncertainty.csv "
        "(scripts/make_method_uncertainty.py). Interval: exact binomial 95 % (Clopper-Pearson).",
        "", "Coverage per class:", "", *summary, "",
        "Leave one shape out, per class and term family (a shape's terms against the band made "
        "from the other shapes of its class):", "", *cv_lines, "",
        f"Held-out paper ({args.samples} samples; no number of it sets a band):", "", *ho_lines,
        "", "Excluded from the count:", "", *excluded, ""])
    print(text)
    if args.write:
        OUT.write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())

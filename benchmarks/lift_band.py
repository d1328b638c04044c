"""The lift and control uncertainty band measured on the DARPA SUBOFF captive-model data.

stripcoef's lift (static and rotary) and control derivatives of Roddy's configurations 1-6
(validation.lift.suboff_comparisons: every configuration as built, ring wing No. 1 included in 1, 2
and 6 as the lift element of stripcoef.assembly.lift.ring_wing_lift; docs/validation.md, 'The ring
wing')
against Roddy 1990's Table 4. For each term the error is ln(model/measured); a term whose model
has the wrong sign, or whose measured value is zero within its uncertainty, has no such error
and is counted as outside every factor band. The band is sd(ln) = q95(|ln|) / 1.96
(stripcoef.study.calibration), and its coverage is checked leaving one configuration out: each
configuration's terms against the band set by the others (never against the terms that set it).

With the default body lift (``--method datcom``: the rule of ``body_lift: auto`` since issue 34's
second pass; ``slender`` was it before) writes reference_tables/method_errors/lift_errors.csv (scripts/make_method_uncertainty.py reads it);
prints the bands, then the issue's checks with the same rule: the Table 4 checks met
(validation.lift.issue_checks), the Appendix B drift-curve points within 20 %
(validation.lift.drift_curve_checks) and the fully appended body's stability indices G_H, G_V
(validation.lift.stability_indices). ``--method datcom``: the slender rule's potential lift times
Munk's k2 - k1 (USAF DATCOM sec. 4.2.1.1, ``body_lift: datcom``).
``--terms`` also prints every Table 4 term, measured and modelled, with their ratio.
``--surface-speed panel`` (with ``--method stratford``): a what-if, Stratford's criterion on the
bare hull's axisymmetric panel solution's surface speed (validation.lift.suboff_surface_speeds,
the suction peak the line sources reach only in part: 0.876 l instead of 0.902 l) in place of
the line sources ``body_lift: stratford`` uses; the fins' stern flow is unchanged.
``--sidewash`` (with ``--method datcom`` or ``stratford``): the same checks without the
sidewash, with the appendages' trailing vortices and with the body's separated pair too
(stripcoef.assembly.sidewash, Pitts, Nielsen & Kaattari 1957; validation.lift.sidewash_checks),
an option outside the default model; writes nothing.
``--method stratford_panel``: ``body_lift: stratford_panel``, Stratford's criterion and the
fins' stern flow on the axisymmetric panel solution's axial flow (an option of the library);
``--crossflow-center hoerner`` (with ``datcom`` or ``stratford_panel``): the drift-curve check
with the hull's viscous cross-flow force at Hoerner's centre of body lift (0.65 l) instead of the
strips' planform centroid (validation.crossflow_center, a what-if; the linear terms unchanged);
``--panels N`` solves that flow on N meridian panels (the library's 400 otherwise; placed on
the C2 interpolant of the hull's offsets, converged: 20 Table 4 checks on 200-1600).
Usage: python -m benchmarks.lift_band [--method datcom|slender|on|stratford|stratford_panel] [--terms]
[--surface-speed line|panel] [--sidewash] [--panels N] [--crossflow-center centroid|hoerner]  (about 60 s; --sidewash about 2 min)
"""

from __future__ import annotations

import argparse
import csv
import math
import sys
from pathlib import Path

import numpy as np

from stripcoef.study.calibration import Z95, binomial_interval, leave_one_group_out, quantile95
from validation.lift import (METHOD_KEY, drift_curve_checks, issue_checks, stability_indices,
                             suboff_comparisons)

ROOT = Path(__file__).resolve().parents[1]

OUT = ROOT / "reference_tables" / "method_errors" / "lift_errors.csv"
#: configurations whose model is their own geometry (all six since the ring wing is built)
CONFIGS = (1, 2, 3, 4, 5, 6)


def rows(method: str = "datcom") -> list[dict]:
    out = []
    for c in suboff_comparisons():
        if c["config"] not in CONFIGS:
            continue
        model = c[METHOD_KEY[method]]
        ratio = model / c["measured"]
        zero = abs(c["measured"]) < 0.05 * 0.01      # |value| below 5e-4 of a typical 0.01
        matrix = "control" if c["kind"] == "control" else "lift"
        out.append({"config": c["config"], "term": c["name"], "matrix": matrix,
                    "measured": c["measured"], "model": model,
                    "error": math.log(ratio) if ratio > 0 and not zero else float("nan")})
    return out


def band(errors) -> dict:
    """sd(ln) = q95 / 1.96 of the terms with the right sign; ``n`` all terms, ``signed`` those;
    ``claim`` k/(n+1), a wrong-signed term counted outside."""
    e = np.asarray(errors, float)
    finite = e[np.isfinite(e)]
    q = quantile95(np.abs(finite)) if finite.size else float("nan")
    k = int(np.sum(np.abs(finite) <= q))
    return {"n": int(e.size), "signed": int(finite.size), "q95": q, "sd": q / Z95,
            "claim": k / (e.size + 1)}


def leave_one_out(rs, matrix) -> tuple[int, int]:
    """(inside, total): each configuration's terms against the band of the others' right-signed
    terms; a wrong-signed term is outside (stripcoef.study.calibration.leave_one_group_out)."""
    sel = [r for r in rs if r["matrix"] == matrix]
    ok = leave_one_group_out([r["error"] for r in sel], [r["config"] for r in sel])
    return int(ok.sum()), len(sel)


def _stratford_on_panel_speed():
    """Make this process's ``body_lift: stratford`` read the SUBOFF panel solution's surface
    speed (validation.lift.suboff_surface_speeds, interpolated at the criterion's stations) in
    Stratford's criterion: the --surface-speed panel what-if. SUBOFF hulls only (the models
    this benchmark builds)."""
    import stripcoef.assembly.lift as assembly
    from validation.lift import FT, suboff_surface_speeds

    _, _, xc, panel = suboff_surface_speeds()
    criterion = assembly.stratford_separation

    def on_panel_speed(s, speed_ratio, **kw):
        return criterion(s, np.interp(s, FT * np.asarray(xc), panel), **kw)
    assembly.stratford_separation = on_panel_speed


def _panels(count: int) -> None:
    """Make this process's ``body_lift: stratford_panel`` solve the axial flow on ``count``
    meridian panels (stripcoef.hull.axisymmetric.axial_surface_speed; the library's default
    SURFACE_SPEED_PANELS): the --panels sensitivity."""
    import functools

    import stripcoef.assembly.lift as assembly
    from stripcoef.hull.axisymmetric import axial_surface_speed

    assembly.axial_surface_speed = functools.partial(axial_surface_speed, panels=count)


def _sidewash(method: str, terms: bool) -> int:
    """Print the issue's checks without and with the sidewash (validation.lift.sidewash_checks)
    and, with ``terms``, every Table 4 term's ratio without and with it."""
    from validation.lift import sidewash_checks, sidewash_comparisons

    if terms:
        for r in sidewash_comparisons():
            if r["method"] == method:
                print(f"{method:9s} config {r['config']} {r['name']:4s} measured "
                      f"{r['measured']:+.6f} without {r['without'] / r['measured']:+.2f} "
                      f"appendages' vortices {r['with'] / r['measured']:+.2f} "
                      f"+ body pair {r['with_body'] / r['measured']:+.2f}")
    c = sidewash_checks(method)
    for name, i in (("appendages' vortices", 1), ("+ body pair", 2)):
        print(f"{method:9s} sidewash, {name}: issue checks (Table 4) {c['table4'][0]}/"
              f"{c['table4'][3]} -> {c['table4'][i]}/{c['table4'][3]}; drift curves within "
              f"20 %: {c['drift'][0]}/{c['drift'][3]} -> {c['drift'][i]}/{c['drift'][3]}")
    return 0


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--method", choices=("datcom", "slender", "on", "stratford", "stratford_panel"),
                    default="datcom",
                    help="body lift: 'datcom' (the default model's rule: slender times Munk's "
                         "k2 - k1), 'slender', 'on' (Hoerner), 'stratford' (the DATCOM "
                         "rule cut at Stratford's separation station) or 'stratford_panel' "
                         "(the same on the axisymmetric panel solution's axial flow)")
    ap.add_argument("--terms", action="store_true",
                    help="print every Table 4 term: measured, model, ratio")
    ap.add_argument("--surface-speed", choices=("line", "panel"), default="line",
                    help="with --method stratford: the surface speed Stratford's criterion reads "
                         "('line': the model's line sources; 'panel': the axisymmetric panel "
                         "solution, a what-if)")
    ap.add_argument("--sidewash", action="store_true",
                    help="with --method datcom or stratford: the Table 4 and drift-curve checks "
                         "without and with the appendages' trailing-vortex sidewash")
    ap.add_argument("--crossflow-center", choices=("centroid", "hoerner"), default="centroid",
                    help="with --method datcom or stratford_panel: where the hull's viscous "
                         "cross-flow force acts in the drift-curve check ('centroid': the "
                         "strips, the model; 'hoerner': Hoerner's centre of body lift, 0.65 l, "
                         "a what-if of validation.crossflow_center)")
    ap.add_argument("--panels", type=int, default=None,
                    help="with --method stratford_panel: meridian panels of the axial flow "
                         "(a sensitivity; the library's default otherwise)")
    args = ap.parse_args(argv)
    if args.crossflow_center != "centroid" and args.method not in ("datcom", "stratford_panel"):
        ap.error("--crossflow-center needs --method datcom or stratford_panel")
    if args.panels is not None:
        if args.method != "stratford_panel" or args.panels < 20:
            ap.error("--panels needs --method stratford_panel and at least 20 panels")
        _panels(args.panels)
    if args.sidewash:
        if args.method not in ("datcom", "stratford"):
            ap.error("--sidewash needs --method datcom or stratford")
        return _sidewash(args.method, args.terms)
    if args.surface_speed == "panel":
        if args.method != "stratford":
            ap.error("--surface-speed panel needs --method stratford")
        _stratford_on_panel_speed()
    rs = rows(args.method)
    if args.terms:
        for r in rs:
            print(f"{args.method:8s} config {r['config']} {r['term']:4s} measured {r['measured']:+.6f} "
                  f"model {r['model']:+.6f} ratio {r['model'] / r['measured']:+.2f}")
    if args.method == "datcom":
        with open(OUT, "w", newline="") as fh:
            fh.write("# Generated by python -m benchmarks.lift_band: ln(model/measured) of the SUBOFF "
                     "lift and control derivatives (Roddy 1990 Table 4), default body lift "
                     "(the DATCOM rule: slender-body lift times Munk's k2 - k1); "
                     "empty error: wrong sign or measured zero\n")
            w = csv.DictWriter(fh, ["config", "term", "matrix", "measured", "model", "error"],
                               lineterminator="\n")
            w.writeheader()
            for r in rs:
                w.writerow({**r, "model": f"{r['model']:.6g}",
                            "error": "" if not np.isfinite(r["error"]) else f"{r['error']:.4f}"})
    for matrix in ("lift", "control"):
        b = band([r["error"] for r in rs if r["matrix"] == matrix])
        k, n = leave_one_out(rs, matrix)
        lo, hi = binomial_interval(k, n)
        print(f"{args.method:8s} {matrix:8s} terms {b['n']:2d} (right sign {b['signed']:2d}) "
              f"q95|ln| {b['q95']:.3f} sd(ln) {b['sd']:.3f} (claim {b['claim']:.3f}); "
              f"leave one configuration out: {k}/{n} inside = {k / n:.2f} [{lo:.2f}, {hi:.2f}]")
    key = METHOD_KEY[args.method]
    checks = sum(1 for c in suboff_comparisons() if c["ok"] is not None)
    k, n = drift_curve_checks(args.method)
    if args.crossflow_center != "centroid":
        from validation.crossflow_center import placement_checks
        k0 = k
        k, n = placement_checks()[(args.method, args.crossflow_center)]
        print(f"{args.method:8s} hull's viscous cross-flow at Hoerner's centre (0.65 l): "
              f"drift curves within 20 % {k0}/{n} -> {k}/{n} (Table 4 and the bands: linear "
              "terms, unchanged)")
    stab = stability_indices()
    print(f"{args.method:8s} issue checks (Table 4) {issue_checks(key)}/{checks}; drift curves "
          f"within 20 %: {k}/{n}; G_H {stab['horizontal'][key]:+.2f} (measured "
          f"{stab['horizontal']['measured']:+.2f}), G_V {stab['vertical'][key]:+.2f} (measured "
          f"{stab['vertical']['measured']:+.2f})")
    return 0


if __name__ == "__main__":
    sys.exit(main())

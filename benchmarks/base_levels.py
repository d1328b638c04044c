"""The base install's panel levels (no remesher) and a third and fourth level, on a CAD seed.

Without the remesher a small input (at most N/4 faces, N the panels asked for) is refined by
longest-edge bisection to N_1 = max(N/4, 2F) panels and that split in four
(:func:`stripcoef.hull.panels.panel_levels`): two levels, whose estimate is Roache's two-grid
index (F_s = 3) plus the step (:func:`stripcoef.hull.panels.richardson_error`).  Two levels
cannot show a term whose two values agree by chance, and the index warns on nearly every
shape.  This benchmark replays the shapes of a seed of ``benchmarks.cad_shapes`` as a user has
them, takes the surface the panel method solves on, and solves on it the families:

- ``two``: N_1 bisected, 4 N_1 its split in four (the base install now);
- ``ladder``: the same, and 2 N_1 bisected from the input with 8 N_1 its split in four: two
  nested pairs of one ratio (h halved), N_1 < 2 N_1 < 4 N_1 < 8 N_1 (the remesher's N/4 ... 2N);
  the value the finer pair's extrapolation A = R(2 N_1, 8 N_1), its error the step to the finest
  plus the change since the coarser pair's A' = R(N_1, 4 N_1),
  :math:`|A - A_{8N_1}| + |A - A'|` (the rule of :func:`stripcoef.hull.panels.
  extrapolation_error`, with the two pairs of one family);
- ``three``: N_1, 2 N_1 bisected, 4 N_1 (the value the two-level one, R(N_1, 4 N_1); its
  change since R(N_1, 2 N_1): a cheap third level, but 2 N_1 is not of the split family);

each level solved with the body's mirror planes where it has them (the input cut at the planes
through the reference point and capped, :func:`stripcoef.hull.mirror_panels.capped_part`,
bisected and split as the whole body would be, its caps dropped, image panels) or whole.
Per family, against the most resolved reference of each term
(``validation.cad_shapes.best_references``): the diagonal terms within 5 %, the couplings
within 5 % of the scale, the terms the estimate covers (and with the reference's band), the
shapes warned, the shapes with a term off by more than 5 % that are warned, and the CPU of the
levels' solves [s] (one thread).

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.base_levels --seed 1375923287 --count 40
        --references reference_tables/bem/cad_shapes.csv [--only K ...] [--md OUT]

Runs without the remesher (the point: the base install); the boxes and plates, panelled by
:mod:`stripcoef.hull.graded_panels` in every install, are left out.
"""

from __future__ import annotations

import argparse
import collections
import os
import sys
import time
import warnings
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from benchmarks.cad_shapes import (DOFS, SIGNIFICANT, patched_estimates,  # noqa: E402
                                   stored_references)

RHO = 1000.0
TOL = 0.05
KINDS = ("two", "three", "ladder", "ladder, change/(r^p-1)")


def capture(seed: int, count: int, panels: int, only=None) -> dict:
    """{shape: dict(family, v, f, about, mirrors, scale)}: the surface each shape's estimate
    solves on (``estimate(load_vehicle(FILE), added_mass_method="panels")``), the reference
    point and the mirror planes it used; boxes and plates (graded panels) left out."""
    import stripcoef.hull.panels as panels_mod
    from stripcoef.hull.graded_panels import box_faces

    real = panels_mod.panel_added_mass
    rec: dict = {}

    def spy(mesh, **k):
        body = mesh.united() if hasattr(mesh, "united") else getattr(mesh, "mesh", mesh)
        rec.update(v=np.asarray(body.vertices, float), f=np.asarray(body.faces, np.int64),
                   about=np.asarray(k.get("about", (0, 0, 0)), float),
                   mirrors=tuple(sorted(set(k.get("mirrors") or ()))))
        return real(mesh, **k)

    out = {}
    for k, family, _, _ in patched_estimates(seed, count, {(panels_mod, "panel_added_mass"): spy},
                                             only, rec.clear, added_mass_panels=panels):
        if box_faces(rec["v"], rec["f"]) is not None:
            continue
        out[k] = dict(family=family, **rec, scale=float(np.ptp(rec["v"], axis=0).max()))
    return out


def levels_of(shape, panels: int, mirrors: bool = True) -> tuple:
    """({name: (vertices, faces)} of the candidate levels, planes): the whole body bisected to
    N_1 = max(N/4, 2F) and 2 N_1 panels (:func:`stripcoef.hull.panels.panel_levels`), with
    mirror planes each cut there (:func:`stripcoef.hull.mirror_panels.mirror_half`: the part
    on the planes' positive side, solved with its images), then split in four."""
    from stripcoef.hull.mirror_panels import mirror_half
    from stripcoef.hull.panels import refine, split_in_four

    v, f = shape["v"], shape["f"]
    n1 = max(panels // 4, 2 * len(f))
    b1, b2 = refine(v, f, n1), refine(v, f, 2 * n1)
    planes = shape["mirrors"] if mirrors else ()
    if planes:
        h1, h2 = (mirror_half(*b, planes, shape["about"]) for b in (b1, b2))
        if h1 is None or h2 is None:
            planes = ()
        else:
            b1, b2 = h1, h2
    return {"N1": b1, "2N1": b2, "4N1": split_in_four(*b1), "8N1": split_in_four(*b2)}, planes


def solve(shape, panels: int, mirrors: bool = True) -> tuple:
    """({name: (panels, 6x6 M_A at rho 1000, not symmetrised)}, formal order per finest
    level name, CPU [s] per level)."""
    from stripcoef.hull.panels import (NEAR_FACTOR, _solve_level_now, edge_features,
                                       edge_order, member_thickness, surface_area)
    from stripcoef.hull.remesh import edge_for_panels

    lv, planes = levels_of(shape, panels, mirrors)
    out, cpu = {}, {}
    for name, (pv, pf) in lv.items():
        c0 = time.process_time()
        out[name] = _solve_level_now(pv, pf, shape["scale"], RHO, shape["about"],
                                     NEAR_FACTOR, planes)
        cpu[name] = time.process_time() - c0
    feats = edge_features(shape["v"], shape["f"])
    area = surface_area(shape["v"], shape["f"])
    from stripcoef.hull.mirror_panels import mirror_full
    from stripcoef.hull.panels import THIN_EDGE_RATIO

    formal = {}
    for fine in ("4N1", "8N1"):
        pv, pf = lv[fine]
        if planes:
            pv, pf = mirror_full(pv, pf, planes, shape["about"])
        thick = member_thickness(pv, pf)
        edge = edge_for_panels(area, out[fine][0])
        formal[fine] = edge_order(feats.turning, edge, thick,
                                  sheet=feats.sheet_wider_than(THIN_EDGE_RATIO * edge))
    return out, formal, cpu


def estimates(sol, formal) -> dict:
    """{kind: (extrapolated M_A symmetrised, its estimated error, levels' panels)}."""
    from stripcoef.hull.convergence import grid_convergence_index, richardson
    from stripcoef.hull.panel_error import estimated_error

    n = {k: v[0] for k, v in sol.items()}
    m = {k: np.asarray(v[1]) for k, v in sol.items()}

    def r(a, b, p):
        return richardson(m[a], m[b], n[a], n[b], order=p)

    def sym(x):
        return 0.5 * (x + x.T)

    out = {}
    p = formal["4N1"]
    a = r("N1", "4N1", p)
    gci, _, _ = grid_convergence_index([m["N1"], m["4N1"]], [n["N1"], n["4N1"]],
                                       formal_order=p)
    out["two"] = (sym(a), estimated_error(m["4N1"], a, gci), (n["N1"], n["4N1"]))
    fine = m["4N1"]
    asym = np.abs(fine - fine.T)
    step = np.abs(sym(a) - sym(fine))
    change = np.abs(sym(a) - sym(r("N1", "2N1", p)))
    e = step + change
    out["three"] = (sym(a), np.maximum(np.maximum(e, e.T), asym), (n["N1"], n["2N1"], n["4N1"]))
    q = formal["8N1"]
    a8 = r("2N1", "8N1", q)
    a4 = r("N1", "4N1", q)
    fine = m["8N1"]
    e = np.abs(sym(a8) - sym(fine)) + np.abs(sym(a8) - sym(a4))
    out["ladder"] = (sym(a8), np.maximum(np.maximum(e, e.T), np.abs(fine - fine.T)),
                     (n["N1"], n["2N1"], n["4N1"], n["8N1"]))
    # the change read as Richardson's error estimate of the finer of two extrapolations a
    # refinement r = sqrt(N_8N1 / N_4N1) apart at the formal order (Roache 1998 eq. 5.4.1)
    r = np.sqrt(n["8N1"] / n["4N1"])
    e = np.abs(sym(a8) - sym(fine)) + np.abs(sym(a8) - sym(a4)) / (r ** q - 1.0)
    out["ladder, change/(r^p-1)"] = (sym(a8), np.maximum(np.maximum(e, e.T),
                                                          np.abs(fine - fine.T)),
                                     (n["N1"], n["2N1"], n["4N1"], n["8N1"]))
    return out


def evaluate(shapes, results, refs, bands) -> dict:
    """Per kind: the counts of the module docstring."""
    from stripcoef.assembly.symmetry import enforce_symmetry
    from stripcoef.hull.panel_error import relative_error

    stats: dict = collections.defaultdict(collections.Counter)
    misses: dict = collections.defaultdict(list)
    for k, s in sorted(shapes.items()):
        if k not in refs or k not in results:
            continue
        ref, band = refs[k], np.nan_to_num(bands[k], nan=0.0)
        d = np.sqrt(np.abs(np.diag(ref)))
        scale = np.outer(d, d)
        sig = (np.eye(6, dtype=bool) | (np.abs(ref) >= SIGNIFICANT * scale)) \
            & np.triu(np.ones((6, 6), bool))
        est_all, cpu = results[k]
        for kind, (a, e, counts) in est_all.items():
            if s["mirrors"]:
                a, e = enforce_symmetry(a, s["mirrors"]), enforce_symmetry(e, s["mirrors"])
            err = np.abs(a - ref)
            x = stats[kind]
            diag = np.eye(6, dtype=bool)
            x["diag"] += 6
            x["diag_within"] += int((err[diag] <= TOL * scale[diag]).sum())
            coup = sig & ~diag
            x["coup"] += int(coup.sum())
            x["coup_within"] += int((err[coup] <= TOL * scale[coup]).sum())
            x["terms"] += int(sig.sum())
            x["covered"] += int((err[sig] <= e[sig]).sum())
            x["covered_rss"] += int((err[sig] <= np.hypot(e, band)[sig]).sum())
            flagged = bool(relative_error(a, e, s["scale"]).max() > TOL)
            off = bool((err[sig] > TOL * scale[sig]).any())
            x["shapes"] += 1
            x["flagged"] += flagged
            x["off"] += off
            x["off_flagged"] += off and flagged
            x["cpu"] += sum(cpu[n] for n in {"two": ("N1", "4N1"),
                                               "three": ("N1", "2N1", "4N1")}.get(
                                                   kind, ("N1", "2N1", "4N1", "8N1")))
            for i, j in zip(*np.nonzero(sig & (err > e))):
                misses[kind + " uncovered"].append(
                    f"{k} {DOFS[i]}-{DOFS[j]} {100 * err[i, j] / scale[i, j]:.1f}/"
                    f"{100 * e[i, j] / scale[i, j]:.1f} %")
            for i in range(6):
                if err[i, i] > TOL * scale[i, i]:
                    misses[kind].append(f"{k} {s['family']} {DOFS[i]} "
                                        f"{100 * (a[i, i] - ref[i, i]) / ref[i, i]:+.1f} % "
                                        f"(est. {100 * e[i, i] / abs(ref[i, i]):.1f} %"
                                        f"{', warned' if flagged else ''})")
    return stats, misses


def table(stats, misses) -> str:
    lines = ["| levels | diagonal within 5 % | couplings within 5 % | covers actual | "
             "with the reference's band | shapes warned | off by > 5 % and warned | "
             "levels' CPU per shape [s] |", "|---|---|---|---|---|---|---|---|"]
    for kind in KINDS:
        x = stats.get(kind)
        if not x:
            continue
        lines.append(f"| {kind} | {x['diag_within']}/{x['diag']} | {x['coup_within']}/"
                     f"{x['coup']} | {x['covered']}/{x['terms']} "
                     f"({100 * x['covered'] / x['terms']:.1f} %) | "
                     f"{100 * x['covered_rss'] / x['terms']:.1f} % | "
                     f"{x['flagged']}/{x['shapes']} | {x['off_flagged']}/{x['off']} | "
                     f"{x['cpu'] / x['shapes']:.2f} |")
    for kind in KINDS:
        if misses.get(kind):
            lines.append(f"\n{kind}: diagonal terms off by more than 5 %: "
                         + "; ".join(misses[kind]))
        if misses.get(kind + " uncovered"):
            lines.append(f"\n{kind}: terms whose estimate does not cover the error (error/"
                         "estimate over the scale): " + "; ".join(misses[kind + " uncovered"]))
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, required=True)
    ap.add_argument("--count", type=int, default=40)
    ap.add_argument("--references", required=True, metavar="CSV",
                    help="the benchmarks.cad_shapes CSV of the seed (its shapes; the most "
                         "resolved references of seed 1375923287 are taken per term)")
    ap.add_argument("--panels", type=int, default=1600)
    ap.add_argument("--only", type=int, nargs="+", default=None)
    ap.add_argument("--md", default=None)
    ap.add_argument("--whole", action="store_true",
                    help="solve the whole body (no mirror planes), as the base install does")
    args = ap.parse_args(argv)
    from validation.cad_shapes import best_matrices

    stored = stored_references(args.references)
    refs, bands = best_matrices(args.references)
    only = set(stored) if args.only is None else set(args.only) & set(stored)
    shapes = capture(args.seed, args.count, args.panels, only=only)
    results = {}
    for k, s in shapes.items():
        from scipy.linalg import LinAlgWarning

        try:
            with warnings.catch_warnings():
                warnings.simplefilter("error", LinAlgWarning)
                sol, formal, cpu = solve(s, args.panels, not args.whole)
        except (np.linalg.LinAlgError, LinAlgWarning) as exc:    # a cut the images cannot take
            print(f"{k:3d} mirrored levels refused ({exc}): the whole body", flush=True)
            s["mirrors_solved"] = False
            sol, formal, cpu = solve(s, args.panels, False)
        results[k] = (estimates(sol, formal), cpu)
        print(f"{k:3d} {s['family']:11s} mirrors {''.join(s['mirrors']) or '-':3s} panels "
              + "/".join(str(sol[n][0]) for n in ("N1", "2N1", "4N1", "8N1"))
              + f", order {formal['4N1']:.2f}/{formal['8N1']:.2f}, CPU "
              + "/".join(f"{cpu[n]:.2f}" for n in ("N1", "2N1", "4N1", "8N1")) + " s",
              flush=True)
    stats, misses = evaluate(shapes, results, refs, bands)
    text = (f"`python -m benchmarks.base_levels --seed {args.seed} --count {args.count} "
            f"--references {args.references}" + (" --whole" if args.whole else "")
            + f"` ({len(results)} shapes, no remesher, against the most resolved reference "
            "of each term)\n\n" + table(stats, misses) + "\n")
    print("\n" + text)
    if args.md:
        Path(args.md).write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())

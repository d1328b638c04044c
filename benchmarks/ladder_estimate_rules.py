"""Published estimate rules on the base install's four-level ladder, on a CAD seed.

Without the remesher an input of at most N/4 faces is solved on four levels, two nested pairs
of its faces bisected and split in four, N_1 < 2N_1 < 4N_1 < 8N_1 (:mod:`stripcoef.hull.
input_ladder`); the value is the finer pair's Richardson extrapolation A = R(L_2, L_4) at the
formal order p (Roache 1998 eq. 5.4.1).  This benchmark runs the estimate as a user does
(``estimate(load_vehicle(FILE), added_mass_method="panels")``, base install, whole body), keeps
the four levels it solved, and reads their error by each rule, the value A in all of them:

- ``step + change`` (:func:`stripcoef.hull.panel_error.ladder_extrapolation`):
  :math:`|A - L_4| + |A - A'|`, A' = R(L_1, L_3) the coarser pair's extrapolation (the band
  shown until this benchmark; the refinement and the warning still read it);
- ``step + change/(r^p-1)``: the change read as Richardson's error estimate of the finer of two
  extrapolations a refinement :math:`r = \\sqrt{N_4/N_3}` apart (Richardson 1911; Roache 1998
  eq. 5.4.1 applied to the extrapolated values);
- ``GCI F_s 1.25, finer pair``: Roache's grid convergence index of L_4 from the finer pair,
  :math:`1.25\\,|L_4 - L_2|/(r^p - 1)`, :math:`r = \\sqrt{N_4/N_2}` = 2 (Roache 1998 ch. 5,
  F_s = 1.25 where the order is known), moved to A by the step
  (:func:`stripcoef.hull.panel_error.estimated_error`);
- ``Eça & Hoekstra``: the least-squares uncertainty of L_4 over the four levels (Eça &
  Hoekstra 2014, J. Comput. Phys. 262, 104-130, eqs. 18-21;
  :func:`stripcoef.hull.convergence.least_squares_band`), moved to A by the step;
- ``GCI, Oberkampf & Roy order, three finest``: Roache's index of L_4 from L_2, L_3, L_4
  (r = sqrt 2) with Oberkampf & Roy's choice of order and factor (2010 sec. 8.6.3.2: F_s
  1.25 and the formal order within 10 % of it, else 3 and the observed order in [0.5, p_f];
  :func:`stripcoef.hull.convergence.grid_convergence_index`), moved to A by the step;
- ``GCI F_s 1.25, p = min(observed, formal)``: Roache's three-grid index with the observed
  order bounded by the formal one (Roache 1998 ch. 5), the same three levels (:func:`roache_bounded`);
- ``Xing & Stern FS, three finest``: Xing & Stern's factor-of-safety uncertainty (Xing &
  Stern 2010, "Factors of safety for Richardson extrapolation", J. Fluids Eng. 132, 061403:
  F_S0 = 2.45, F_S1 = 1.6, F_S2 = 14.8, P the observed over the formal order;
  :func:`xing_stern`), the same three levels, moved to A by the step;
- rules that show one band and warn on another estimate (Eça & Hoekstra's error estimate
  against their uncertainty; ASME V&V 20-2009 keeps the two apart too): ``E&H U shown, warn
  E&H error estimate`` (their epsilon_phi moved to A by the step), ``E&H U shown, warn step +
  change`` (the default since this benchmark: :func:`stripcoef.hull.panel_error.
  least_squares_error`), ``X&S U shown, warn step + change``;
- ``E&H a constant per pair U shown, warn step + change``: Eça & Hoekstra's least squares
  with one error constant per nested pair at the formal order (their sec. 2.1: the
  expansion's constant belongs to a family of geometrically similar grids; the ladder is two;
  :func:`benchmarks.ladder_families.ladder_least_squares_error`), moved to A by the step.

Each is symmetrised and no smaller than the finest solve's asymmetry.  A shape is warned where
the rule's warning estimate (the band itself but for the split rules), judged about the
volume centroid as the estimate judges it, exceeds the tolerance of the diagonal scale
(:func:`stripcoef.hull.panel_error.relative_error`); the shapes the ladder does not solve
(boxes and plates: graded panels; inputs over N/4) keep the estimate's own value and
warning under every rule, and its step plus change as their band but under the default,
which shows the least-squares band where they have four levels.  "median estimate / actual":
the band over the actual error, median over the terms compared (how wide the band is).  Against the most resolved
reference of each term (``validation.cad_shapes.best_references``) for the seed of
reference_tables/bem/cad_shapes.csv, else the stored run's own references:

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.ladder_estimate_rules --seed 1375923287
        --count 40 --references reference_tables/bem/cad_shapes.csv [--md OUT]
"""

from __future__ import annotations

import argparse
import collections
import os
import pickle
import sys
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from benchmarks.cad_shapes import (DOFS, SIGNIFICANT, patched_estimates,  # noqa: E402
                                   stored_references)

RHO = 1000.0
TOL = 0.05
#: Roache's safety factor where the order is known (Roache 1998 ch. 5) [-]
FS_KNOWN_ORDER = 1.25
#: Xing & Stern's (2010) factors of safety [-] (J. Fluids Eng. 132, 061403: F_S0 at P = 0,
#: F_S1 at P = 1, F_S2 the slope's factor above P = 1; as ITTC 7.5-03-01-01 rev. 04 quotes them)
XS_FS0, XS_FS1, XS_FS2 = 2.45, 1.6, 14.8
RULES = ("step + change (the warning; the former band)", "step + change/(r^p-1)", "GCI F_s 1.25, finer pair",
         "Eça & Hoekstra", "GCI, Oberkampf & Roy order, three finest",
         "Xing & Stern FS, three finest",
         "E&H U shown, warn E&H error estimate", "E&H U shown, warn step + change (default)",
         "X&S U shown, warn step + change", "GCI F_s 1.25, p = min(observed, formal)",
         "E&H a constant per pair U shown, warn step + change")
#: the rule of stripcoef.hull.panels (panel_error.least_squares_error)
DEFAULT = RULES[7]


def capture(seed: int, count: int, only=None) -> dict:
    """{shape: dict(family, value, error, warned, counts, levels (rho 1000), formal, centroid,
    length, mirrors, ladder, cpu)} of the seed's shapes, each run by the estimate as a user
    does (base install)."""
    import stripcoef.geometry.mesh as mesh_mod
    import stripcoef.hull.panels as panels
    from stripcoef.hull.panel_error import ladder_extrapolation
    from stripcoef.hull.remesh import available

    # (with the remesher no shape is on the ladder: the rules differ only in the default's
    # least-squares band of the shapes with four levels or more)
    remesher = available()
    real_pam, real_centroid = panels.panel_added_mass, mesh_mod.volume_centroid
    rec: dict = {}

    def centroid(*a, **k):
        out = real_centroid(*a, **k)
        if rec.get("inside") and "centroid" not in rec:     # the estimate's own (panels.py)
            rec["centroid"] = np.asarray(out, float)
        return out

    def spy(*a, **k):
        rec["inside"] = True
        try:
            m, info = real_pam(*a, **k)
        finally:
            rec["inside"] = False
        rec.update(info=info, rho=k["rho"], value=np.asarray(m, float))
        return m, info

    out = {}
    patches = {(panels, "panel_added_mass"): spy, (mesh_mod, "volume_centroid"): centroid}
    for k, family, model, cpu in patched_estimates(seed, count, patches, only, rec.clear):
        info, f = rec["info"], RHO / rec["rho"]
        levels = [np.asarray(m) * f for m in info["levels"]]
        counts = tuple(info["panels"])
        ladder = False
        # (the warning's estimate; the band shown before four levels had their own)
        warned_on = info.get("estimate", info["error"])
        if len(levels) == 4 and warned_on is not None:
            _, e = ladder_extrapolation(levels, counts, info["formal_order"])
            ladder = bool(np.allclose(e, np.asarray(warned_on) * f, rtol=1e-9,
                                      atol=1e-12))
        out[k] = dict(family=family, value=rec["value"] * f,
                      error=None if info["error"] is None else np.asarray(info["error"]) * f,
                      estimate=None if warned_on is None else np.asarray(warned_on) * f,
                      warned=not info["converged"], counts=counts, levels=levels,
                      formal=info["formal_order"], centroid=rec.get("centroid"),
                      length=info["length"], ladder=ladder,
                      mirrors=tuple(model.conditions["mirror_planes"] or ()),
                      remesher=remesher,
                      cpu=cpu)
        print(f"{k:3d} {family:12s} panels {'/'.join(map(str, counts))}"
              f"{' ladder' if ladder else ''}, CPU {out[k]['cpu']:.2f} s", flush=True)
    return out


def xing_stern(levels, counts, p) -> np.ndarray:
    r"""Xing & Stern's (2010) factor-of-safety uncertainty of the finest of the three finest
    ``levels`` [their unit] (module docstring): :math:`U = (F_{S1} P + F_{S0}(1 - P))
    |\delta_{RE}|` for :math:`0 < P \le 1`, :math:`(F_{S1} P + F_{S2}(P - 1))|\delta_{RE}|`
    above, :math:`P = p_{RE}/p_{th}`, :math:`\delta_{RE} = \varepsilon_{21}/(r_{21}^{p_{RE}}
    - 1)` where the levels converge monotonically (:math:`0 < R = \varepsilon_{21}/
    \varepsilon_{32} < 1`); oscillation (R < 0): half the range of the three (Stern et al.
    2001); divergence (R >= 1) or no change: Roache's two-grid index on the larger change
    (:func:`stripcoef.hull.convergence.grid_convergence_index`'s fallback)."""
    from stripcoef.hull.convergence import grid_convergence_index, observed_order

    f3, f2, f1 = (np.asarray(x, float) for x in levels[-3:])
    n3, n2, n1 = counts[-3:]
    r21, r32 = np.sqrt(n1 / n2), np.sqrt(n2 / n3)
    e21, e32 = f2 - f1, f3 - f2
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = e21 / e32
        q = observed_order(f1, f2, f3, r21, r32)
        delta = np.abs(e21) / (r21 ** q - 1.0)
    big = np.where(q / p <= 1.0, XS_FS1 * q / p + XS_FS0 * (1.0 - q / p),
                   XS_FS1 * q / p + XS_FS2 * (q / p - 1.0))
    u = big * delta
    monotone = (ratio > 0) & (ratio < 1) & np.isfinite(u)
    half = 0.5 * (np.maximum(np.maximum(f1, f2), f3) - np.minimum(np.minimum(f1, f2), f3))
    fallback = grid_convergence_index(levels[-3:], counts[-3:], formal_order=p)[0]
    return np.where(monotone, u, np.where(ratio < 0, half, fallback))


def roache_bounded(levels, counts, p) -> np.ndarray:
    r"""Roache's three-grid index of the finest of the three finest ``levels`` [their unit]:
    :math:`1.25\,|f_2 - f_1|/(r_{21}^{q} - 1)`, q the observed order bounded by the formal
    one, :math:`q = \min(\hat p, p_f)` (Roache 1998 ch. 5, F_s = 1.25 with three grids);
    an oscillating sequence or one with no observed order: the two-grid index on the larger
    change (:func:`stripcoef.hull.convergence.grid_convergence_index`'s fallback)."""
    from stripcoef.hull.convergence import (SAFETY_THREE_GRIDS, grid_convergence_index,
                                            observed_order)

    f3, f2, f1 = (np.asarray(x, float) for x in levels[-3:])
    n3, n2, n1 = counts[-3:]
    r21, r32 = np.sqrt(n1 / n2), np.sqrt(n2 / n3)
    q = observed_order(f1, f2, f3, r21, r32)
    with np.errstate(divide="ignore", invalid="ignore"):
        three = SAFETY_THREE_GRIDS * np.abs(f2 - f1) / (r21 ** np.minimum(q, p) - 1.0)
    fallback = grid_convergence_index(levels[-3:], counts[-3:], formal_order=p)[0]
    return np.where(np.isfinite(q) & np.isfinite(three), three, fallback)


def eca_hoekstra_parts(levels, counts) -> tuple:
    """Per term (upper triangle mirrored) of the four levels: Eça & Hoekstra's uncertainty U
    of the finest level (eqs. 20-21) and their error estimate epsilon_phi = |phi_fit(h_1) -
    phi_0| (the fit's error of the finest level, no safety factor) [their unit]
    (:func:`stripcoef.hull.convergence.eca_hoekstra`)."""
    from stripcoef.hull.convergence import eca_hoekstra

    mats = np.stack([np.asarray(m, float) for m in levels])
    u, eps = np.zeros((6, 6)), np.zeros((6, 6))
    for i in range(6):
        for j in range(i, 6):
            r = eca_hoekstra(counts, mats[:, i, j])
            u[i, j] = u[j, i] = r.uncertainty
            eps[i, j] = eps[j, i] = r.error
    return u, eps


def rules(levels, counts, p) -> dict:
    """{rule: (value A, estimated error shown, estimate the warning reads)} [kg, kg m,
    kg m^2] of the four levels (module docstring)."""
    from stripcoef.hull.convergence import grid_convergence_index, richardson
    from benchmarks.ladder_families import ladder_least_squares_error
    from stripcoef.hull.panel_error import estimated_error, ladder_extrapolation

    m = [np.asarray(x, float) for x in levels]
    a, default = ladder_extrapolation(m, counts, p)
    fine = m[3]
    asym = np.abs(fine - fine.T)
    before = richardson(m[0], m[2], counts[0], counts[2], order=p)
    step = np.abs(a - 0.5 * (fine + fine.T))
    change = np.abs(a - 0.5 * (before + before.T))
    r = np.sqrt(counts[3] / counts[2])
    e = step + change / (r ** p - 1.0)
    out = {RULES[0]: (a, default, default)}
    e = np.maximum(np.maximum(e, e.T), asym)
    out[RULES[1]] = (a, e, e)
    r = np.sqrt(counts[3] / counts[1])
    gci = FS_KNOWN_ORDER * np.abs(fine - m[1]) / (r ** p - 1.0)
    e = estimated_error(fine, a, gci)
    out[RULES[2]] = (a, e, e)
    sym = [0.5 * (x + x.T) for x in m]
    u, eps = eca_hoekstra_parts(counts=counts, levels=sym)
    eh = estimated_error(fine, a, u)
    out[RULES[3]] = (a, eh, eh)
    e = estimated_error(fine, a, grid_convergence_index(sym[1:], counts[1:],
                                                        formal_order=p)[0])
    out[RULES[4]] = (a, e, e)
    xs = estimated_error(fine, a, xing_stern(sym, counts, p))
    out[RULES[5]] = (a, xs, xs)
    e = estimated_error(fine, a, roache_bounded(sym[1:], counts[1:], p))
    out[RULES[9]] = (a, e, e)
    out[RULES[6]] = (a, eh, estimated_error(fine, a, eps))
    out[RULES[7]] = (a, eh, default)
    out[RULES[8]] = (a, xs, default)
    out[RULES[10]] = (a, ladder_least_squares_error(m, counts, a, p), default)
    return out


def evaluate(shapes: dict, refs: dict) -> tuple:
    """Per rule: the diagonal terms and couplings within 5 %, the terms covered, the shapes
    warned, the shapes with a term off by more than 5 % and those of them warned; the misses."""
    from stripcoef.assembly.symmetry import enforce_symmetry
    from stripcoef.conventions import transform_matrix
    from stripcoef.hull.panel_error import least_squares_error, relative_error

    stats: dict = collections.defaultdict(collections.Counter)
    misses: dict = collections.defaultdict(list)
    ratios: dict = collections.defaultdict(list)
    for k, s in sorted(shapes.items()):
        if k not in refs:
            continue
        ref = refs[k]
        d = np.sqrt(np.abs(np.diag(ref)))
        scale = np.outer(d, d)
        diag = np.eye(6, dtype=bool)
        sig = (diag | (np.abs(ref) >= SIGNIFICANT * scale)) & np.triu(np.ones((6, 6), bool))
        if s["ladder"]:
            per = rules(s["levels"], s["counts"], s["formal"])
            at_c = [transform_matrix(m, from_point=(0, 0, 0), to_point=s["centroid"])
                    for m in s["levels"]]
            per_c = rules(at_c, s["counts"], s["formal"])
            warned = {x: bool(relative_error(per_c[x][0], per_c[x][2], s["length"]).max()
                              > TOL) for x in RULES}
            if warned[DEFAULT] != s["warned"]:
                print(f"{k}: the default rule's warning differs from the estimate's", flush=True)
            # (Eça & Hoekstra's order search stops at a relative tolerance: the levels scaled
            # to rho 1000 move it by about 1e-8)
            if s.get("estimate") is not None and not np.allclose(
                    per[DEFAULT][1], s["error"], rtol=1e-6,
                    atol=1e-9 * np.abs(s["error"]).max()):
                print(f"{k}: the default rule's band differs from the estimate's", flush=True)
        else:
            # the estimate's own value and warning; its band the step plus the change under
            # every rule but the default, which shows the least-squares band from four levels
            est = s.get("estimate")
            est = s["error"] if est is None else est
            per = {x: (s["value"], est, est) for x in RULES}
            if est is not None and len(s["levels"]) >= 4:
                per[DEFAULT] = (s["value"], least_squares_error(s["levels"], s["counts"],
                                                                s["value"])[0], est)
            warned = {x: s["warned"] for x in RULES}
        for rule in RULES:
            a, e, _ = per[rule]
            if s["mirrors"]:
                a, e = enforce_symmetry(a, s["mirrors"]), enforce_symmetry(e, s["mirrors"])
            err = np.abs(a - ref)
            x = stats[rule]
            x["diag"] += 6
            x["diag_within"] += int((err[diag] <= TOL * scale[diag]).sum())
            coup = sig & ~diag
            x["coup"] += int(coup.sum())
            x["coup_within"] += int((err[coup] <= TOL * scale[coup]).sum())
            x["terms"] += int(sig.sum())
            x["covered"] += int((err[sig] <= e[sig]).sum())
            if s["ladder"]:
                x["ladder_terms"] += int(sig.sum())
                x["ladder_covered"] += int((err[sig] <= e[sig]).sum())
            ratios[rule].extend((e[sig] / np.maximum(err[sig], 1e-12 * scale[sig])).tolist())
            off = bool((err[sig] > TOL * scale[sig]).any())
            x["shapes"] += 1
            x["ladder"] += s["ladder"]
            x["warned"] += warned[rule]
            x["ladder_warned"] += warned[rule] and s["ladder"]
            x["off"] += off
            x["off_warned"] += off and warned[rule]
            for i in range(6):
                if err[i, i] > TOL * scale[i, i]:
                    misses[rule].append(f"{k} {s['family']} {DOFS[i]} "
                                        f"{100 * (a[i, i] - ref[i, i]) / ref[i, i]:+.1f} % "
                                        f"(est. {100 * e[i, i] / abs(ref[i, i]):.1f} %"
                                        f"{', warned' if warned[rule] else ', NOT warned'})")
            if off and not warned[rule] and not any(m.startswith(f"{k} ")
                                                    for m in misses[rule]):
                misses[rule].append(f"{k} {s['family']}: a coupling off by > 5 %, NOT warned")
    for rule, r in ratios.items():
        stats[rule]["ratio"] = float(np.median(r))
    return stats, misses


def table(stats, misses) -> str:
    lines = ["| rule | diagonal within 5 % | couplings within 5 % | estimate covers actual | "
             "of them on the ladder | median estimate / actual | shapes warned (of them "
             "ladder) | off by > 5 % and warned |",
             "|---|---|---|---|---|---|---|---|"]
    for rule in RULES:
        x = stats[rule]
        lines.append(f"| {rule} | {x['diag_within']}/{x['diag']} | {x['coup_within']}/"
                     f"{x['coup']} | {x['covered']}/{x['terms']} "
                     f"({100 * x['covered'] / max(x['terms'], 1):.1f} %) | "
                     f"{x['ladder_covered']}/{x['ladder_terms']} "
                     f"({100 * x['ladder_covered'] / max(x['ladder_terms'], 1):.1f} %) | "
                     f"{x['ratio']:.1f} | "
                     f"{x['warned']}/{x['shapes']} ({x['ladder_warned']}/{x['ladder']}) | "
                     f"{x['off_warned']}/{x['off']} |")
    for rule in RULES:
        if misses.get(rule):
            lines.append(f"\n{rule}: shapes off by more than 5 %: " + "; ".join(misses[rule]))
    return "\n".join(lines)


def references(path) -> tuple:
    """({shape: 6x6 reference}, which): the most resolved references of seed 1375923287's
    stored run, else the stored run's own (the fine and graded references of
    ``best_references`` are that seed's shapes)."""
    from validation.cad_shapes import DATA, best_matrices

    if Path(path).resolve() == Path(DATA).resolve():
        return best_matrices(path)[0], "the most resolved reference of each term"
    return ({k: x["ref"] for k, x in stored_references(path).items()},
            "the stored run's references")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, required=True)
    ap.add_argument("--count", type=int, default=40)
    ap.add_argument("--references", required=True, metavar="CSV",
                    help="the benchmarks.cad_shapes CSV of the seed")
    ap.add_argument("--only", type=int, nargs="+", default=None)
    ap.add_argument("--md", default=None)
    ap.add_argument("--levels", default=None, metavar="PICKLE",
                    help="the captured levels: read from this file where it exists, else "
                         "captured and written to it (to compare rules without solving again)")
    args = ap.parse_args(argv)
    refs, which = references(args.references)
    only = set(refs) if args.only is None else set(args.only) & set(refs)
    if args.levels and Path(args.levels).exists():
        with open(args.levels, "rb") as fh:
            shapes = {k: s for k, s in pickle.load(fh).items() if k in only}
    else:
        shapes = capture(args.seed, args.count, only=only)
        if args.levels:
            with open(args.levels, "wb") as fh:
                pickle.dump(shapes, fh)
    stats, misses = evaluate(shapes, refs)
    cpu = sorted(s["cpu"] for s in shapes.values())
    install = ("with the remesher" if any(s.get("remesher") for s in shapes.values())
               else "base install, no remesher")
    text = (f"`python -m benchmarks.ladder_estimate_rules --seed {args.seed} --count "
            f"{args.count} --references {args.references}` ({install}; "
            f"{len(shapes)} shapes, {sum(s['ladder'] for s in shapes.values())} on the "
            f"four-level ladder; against {which}; estimate CPU median "
            f"{cpu[len(cpu) // 2]:.2f} s)\n\n" + table(stats, misses) + "\n")
    print("\n" + text)
    if args.md:
        Path(args.md).write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())

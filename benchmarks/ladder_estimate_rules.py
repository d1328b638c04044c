"""Published estimate rules on the base install's four-level ladder, on a CAD seed.

Without the remesher an input of at most N/4 faces is solved on four levels, two nested pairs
of its faces bisected and split in four, N_1 < 2N_1 < 4N_1 < 8N_1 (:mod:`stripcoef.hull.
input_ladder`); the value is the finer pair's Richardson extrapolation A = R(L_2, L_4) at the
formal order p (Roache 1998 eq. 5.4.1).  This benchmark runs the estimate as a user does
(``estimate(load_vehicle(FILE), added_mass_method="panels")``, base install, whole body), keeps
the four levels it solved, and reads their error by each rule, the value A in all of them:

- ``step + change`` (the default, :func:`stripcoef.hull.panel_error.ladder_extrapolation`):
  :math:`|A - L_4| + |A - A'|`, A' = R(L_1, L_3) the coarser pair's extrapolation;
- ``step + change/(r^p-1)``: the change read as Richardson's error estimate of the finer of two
  extrapolations a refinement :math:`r = \\sqrt{N_4/N_3}` apart (Richardson 1911; Roache 1998
  eq. 5.4.1 applied to the extrapolated values);
- ``GCI F_s 1.25, finer pair``: Roache's grid convergence index of L_4 from the finer pair,
  :math:`1.25\\,|L_4 - L_2|/(r^p - 1)`, :math:`r = \\sqrt{N_4/N_2}` = 2 (Roache 1998 ch. 5,
  F_s = 1.25 where the order is known), moved to A by the step
  (:func:`stripcoef.hull.panel_error.estimated_error`);
- ``Eça & Hoekstra``: the least-squares uncertainty of L_4 over the four levels (Eça &
  Hoekstra 2014, J. Comput. Phys. 262, 104-130, eqs. 18-21;
  :func:`stripcoef.hull.convergence.least_squares_band`), moved to A by the step.

Each is symmetrised and no smaller than the finest solve's asymmetry.  A shape is warned where
the rule's estimate, judged about the volume centroid as the estimate judges it, exceeds the
tolerance of the diagonal scale (:func:`stripcoef.hull.panel_error.relative_error`); the
shapes the ladder does not solve (boxes and plates: graded panels; inputs over N/4) keep the
estimate's own value, error and warning under every rule.  Against the most resolved
reference of each term (``validation.cad_shapes.best_references``) for the seed of
reference_tables/bem/cad_shapes.csv, else the stored run's own references:

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.ladder_estimate_rules --seed 1375923287
        --count 40 --references reference_tables/bem/cad_shapes.csv [--md OUT]
"""

from __future__ import annotations

import argparse
import collections
import os
import sys
import tempfile
import time
import warnings
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from benchmarks.cad_shapes import (DOFS, SIGNIFICANT, stored_references,  # noqa: E402
                                   user_files)

RHO = 1000.0
TOL = 0.05
#: Roache's safety factor where the order is known (Roache 1998 ch. 5) [-]
FS_KNOWN_ORDER = 1.25
RULES = ("step + change (default)", "step + change/(r^p-1)", "GCI F_s 1.25, finer pair",
         "Eça & Hoekstra")


def capture(seed: int, count: int, only=None) -> dict:
    """{shape: dict(family, value, error, warned, counts, levels (rho 1000), formal, centroid,
    length, mirrors, ladder, cpu)} of the seed's shapes, each run by the estimate as a user
    does (base install)."""
    import stripcoef.geometry.mesh as mesh_mod
    import stripcoef.hull.panels as panels
    from stripcoef.assembly import estimate
    from stripcoef.geometry.vehicle import load_vehicle
    from stripcoef.hull.panel_error import ladder_extrapolation

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
    with tempfile.TemporaryDirectory() as tmp:
        for k, family, path, unit in user_files(seed, count, tmp, only):
            rec.clear()
            c0 = time.process_time()
            try:
                panels.panel_added_mass, mesh_mod.volume_centroid = spy, centroid
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    model = estimate(load_vehicle(path, length_unit=unit, origin=(0, 0, 0)),
                                     added_mass_method="panels")
            except Exception as exc:            # a refusal is a result: say it, go on
                print(f"{k:3d} {family}: FAILED {type(exc).__name__}: {exc}", flush=True)
                continue
            finally:
                panels.panel_added_mass, mesh_mod.volume_centroid = real_pam, real_centroid
            info, f = rec["info"], RHO / rec["rho"]
            levels = [np.asarray(m) * f for m in info["levels"]]
            counts = tuple(info["panels"])
            ladder = False
            if len(levels) == 4 and info["error"] is not None:
                _, e = ladder_extrapolation(levels, counts, info["formal_order"])
                ladder = bool(np.allclose(e, np.asarray(info["error"]) * f, rtol=1e-9,
                                          atol=1e-12))
            out[k] = dict(family=family, value=rec["value"] * f,
                          error=None if info["error"] is None else np.asarray(info["error"]) * f,
                          warned=not info["converged"], counts=counts, levels=levels,
                          formal=info["formal_order"], centroid=rec.get("centroid"),
                          length=info["length"], ladder=ladder,
                          mirrors=tuple(model.conditions["mirror_planes"] or ()),
                          cpu=time.process_time() - c0)
            print(f"{k:3d} {family:12s} panels {'/'.join(map(str, counts))}"
                  f"{' ladder' if ladder else ''}, CPU {out[k]['cpu']:.2f} s", flush=True)
    return out


def rules(levels, counts, p) -> dict:
    """{rule: (value A, estimated error)} [kg, kg m, kg m^2] of the four levels (module
    docstring)."""
    from stripcoef.hull.convergence import least_squares_band, richardson
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
    out = {RULES[0]: (a, default),
           RULES[1]: (a, np.maximum(np.maximum(e, e.T), asym))}
    r = np.sqrt(counts[3] / counts[1])
    gci = FS_KNOWN_ORDER * np.abs(fine - m[1]) / (r ** p - 1.0)
    out[RULES[2]] = (a, estimated_error(fine, a, gci))
    sym = [0.5 * (x + x.T) for x in m]
    u = least_squares_band(counts, sym)[0]
    out[RULES[3]] = (a, estimated_error(fine, a, u))
    return out


def evaluate(shapes: dict, refs: dict) -> tuple:
    """Per rule: the diagonal terms and couplings within 5 %, the terms covered, the shapes
    warned, the shapes with a term off by more than 5 % and those of them warned; the misses."""
    from stripcoef.assembly.symmetry import enforce_symmetry
    from stripcoef.conventions import transform_matrix
    from stripcoef.hull.panel_error import relative_error

    stats: dict = collections.defaultdict(collections.Counter)
    misses: dict = collections.defaultdict(list)
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
            warned = {x: bool(relative_error(*per_c[x], s["length"]).max() > TOL)
                      for x in RULES}
            if warned[RULES[0]] != s["warned"]:
                print(f"{k}: the default rule's warning differs from the estimate's", flush=True)
        else:
            per = {x: (s["value"], s["error"]) for x in RULES}
            warned = {x: s["warned"] for x in RULES}
        for rule in RULES:
            a, e = per[rule]
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
    return stats, misses


def table(stats, misses) -> str:
    lines = ["| rule | diagonal within 5 % | couplings within 5 % | estimate covers actual | "
             "shapes warned (of them ladder) | off by > 5 % and warned |",
             "|---|---|---|---|---|---|"]
    for rule in RULES:
        x = stats[rule]
        lines.append(f"| {rule} | {x['diag_within']}/{x['diag']} | {x['coup_within']}/"
                     f"{x['coup']} | {x['covered']}/{x['terms']} "
                     f"({100 * x['covered'] / max(x['terms'], 1):.1f} %) | "
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
    args = ap.parse_args(argv)
    refs, which = references(args.references)
    only = set(refs) if args.only is None else set(args.only) & set(refs)
    shapes = capture(args.seed, args.count, only=only)
    stats, misses = evaluate(shapes, refs)
    cpu = sorted(s["cpu"] for s in shapes.values())
    text = (f"`python -m benchmarks.ladder_estimate_rules --seed {args.seed} --count "
            f"{args.count} --references {args.references}` (base install, no remesher; "
            f"{len(shapes)} shapes, {sum(s['ladder'] for s in shapes.values())} on the "
            f"four-level ladder; against {which}; estimate CPU median "
            f"{cpu[len(cpu) // 2]:.2f} s)\n\n" + table(stats, misses) + "\n")
    print("\n" + text)
    if args.md:
        Path(args.md).write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())

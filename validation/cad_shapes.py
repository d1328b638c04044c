"""docs/validation.md: seeded CAD-style bluff shapes against Capytaine (issue 32).

Reads the stored run of ``benchmarks/cad_shapes.py`` (``reference_tables/bem/cad_shapes.csv``: the
seed and command on its first line, then one row per term of each shape), so the section
states what that run measured; a new run (a fresh seed) replaces the file.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from stripcoef.conventions import DOF as DOFS
from validation import ROOT, markdown_table, read_stored_run

DATA = ROOT / "reference_tables" / "bem" / "cad_shapes.csv"
#: Capytaine on the same shapes' surfaces at four or five levels up to 12,000-17,000 faces
#: (``python -m benchmarks.bem_fine_references``), and the seed's thin members (shapes 100+)
FINE = ROOT / "reference_tables" / "bem" / "cad_shapes_fine_levels.csv"
#: the same solver on the coarser level (about 750 faces) of the same remesh family, where
#: it is one (35 of the 40 shapes: the family of benchmarks.cad_shapes' stored references,
#: whose 1,500- and 3,000-face levels are FINE's two coarsest)
FINE_750 = ROOT / "reference_tables" / "bem" / "cad_shapes_fine_levels_750.csv"
#: finer levels of the same family where its fine levels stopped short (frame 34: three
#: levels to 5,954 faces, then 8,744, 11,844 and 15,988)
FINE_EXTRA = ROOT / "reference_tables" / "bem" / "cad_shapes_fine_levels_extra.csv"
#: the level files of the fine references: every level of a shape, in one family
FINE_ALL = (FINE, FINE_750, FINE_EXTRA)
#: the seed whose shapes the fine and graded reference files hold (shape k of that seed)
REFERENCE_SEED = 1375923287
#: the thin members' shape numbers in FINE start here
THIN_OFFSET = 100
#: the seed's plates solved with panels graded towards the edges (benchmarks.plate_graded)
GRADED = ROOT / "reference_tables" / "bem" / "cad_plates_graded.csv"
#: that procedure on the thin disc and on plates of DNV-RP-H103 table A-2
GRADED_CHECKS = ROOT / "reference_tables" / "bem" / "plates_graded_checks.csv"
#: the seed's coarse tessellations and a filleted box on panels graded towards every edge
#: (benchmarks.graded_polyhedra: the whole 6x6 per level)
GRADED_COARSE = ROOT / "reference_tables" / "bem" / "graded_coarse.csv"
#: the seed's low-polygon ellipsoid 14 and filleted box 18 on gmsh triangles graded towards
#: every facet edge (benchmarks.graded_cad)
GRADED_CAD = ROOT / "reference_tables" / "bem" / "graded_cad_1375923287.csv"


def number(cell) -> float:
    """A stored run's CSV cell as a number; an empty or missing cell is unknown (NaN), never
    0 (``benchmarks.cad_shapes`` writes what it cannot know so)."""
    return float(cell) if cell not in (None, "") else float("nan")


def read_levels(*paths) -> dict:
    """{shape: {level: (faces, 6x6 added mass [kg, kg m, kg m^2])}} of one or more levels
    CSVs (``benchmarks.bem_fine_references solve``: one row per upper-triangle term); the
    levels of several files merged per shape, numbered coarse to fine by their faces."""
    import csv

    merged: dict = {}
    for n, path in enumerate(paths):
        out: dict = {}
        with open(path, newline="") as fh:
            for r in csv.DictReader(fh):
                k, lev = int(r["shape"]), int(r["level"])
                _, a = out.setdefault(k, {}).setdefault(lev, (int(r["faces"]),
                                                              np.zeros((6, 6))))
                i, j = int(r["i"]), int(r["j"])
                a[i, j] = a[j, i] = float(r["added_mass"])
        for k, lv in out.items():
            faces = {f for f, _ in merged.get(k, {}).values()}
            merged.setdefault(k, {}).update({(n, lev): x for lev, x in lv.items()
                                             if x[0] not in faces})
    return {k: {i: x for i, x in enumerate(sorted(lv.values(), key=lambda x: x[0]))}
            for k, lv in merged.items()}


#: the reference's estimate from the BEM levels: "eca-hoekstra" (four levels or more; fewer:
#: "gci") or "gci" (the three finest, the panel method's own rule)
FINE_METHODS = ("eca-hoekstra", "gci")


def fine_reference(counts, mats, method: str = "eca-hoekstra", extra_orders=()):
    """(reference, band, order) per term of BEM levels ``mats`` (coarse to fine, ``counts``
    faces); h ~ N^(-1/2).

    ``method="eca-hoekstra"`` (four levels or more): the least-squares procedure of Eça &
    Hoekstra 2014 over all the levels (:func:`stripcoef.hull.convergence.eca_hoekstra`: the
    fit phi_0 + alpha h^p of least standard deviation, with or without weights, or where p is
    out of [0.5, 2] the best of the fixed orders 1, 2 and 1 & 2; sec. 3 and App. A): the
    reference is that fit's limit phi_0, the band the paper's uncertainty U of the finest
    level (eqs. 20-21; it contains phi_0), the order the chosen fit's (the observed p, or
    the fixed order of the alternative fit, 1 for the fit in h and h^2);
    ``extra_orders`` join the fixed-order fits (:func:`~stripcoef.hull.convergence.
    eca_hoekstra`).  ``method="gci"``, and any shape with three levels: the library's rule
    for the panel levels (:mod:`stripcoef.hull.convergence`): the grid convergence index of
    the finest level over the three finest with the order it uses (the formal order 2 in h
    in the asymptotic range, else the observed order within [0.5, 2] and a safety factor 3:
    Oberkampf & Roy 2010, sec. 8.6.3.2), and the two finest Richardson-extrapolated with
    that order (Roache 1998, eq. 5.4.1)."""
    from stripcoef.hull.convergence import (EH_MIN_LEVELS, eca_hoekstra,
                                            grid_convergence_index, richardson)

    if method not in FINE_METHODS:
        raise ValueError(f"method {method!r}: expected one of {', '.join(FINE_METHODS)}")
    if method == "eca-hoekstra" and len(counts) >= EH_MIN_LEVELS:
        mats = [np.asarray(m, float) for m in mats]
        shape = mats[0].shape
        ref, band, order = np.zeros(shape), np.zeros(shape), np.zeros(shape)
        symmetric = len(shape) == 2 and all(np.array_equal(m, m.T) for m in mats)
        for idx in np.ndindex(shape):
            if symmetric and idx[0] > idx[1]:
                continue                              # an added mass: the upper triangle
            r = eca_hoekstra(counts, [m[idx] for m in mats], extra_orders=extra_orders)
            ref[idx], band[idx], order[idx] = r.extrapolated, r.uncertainty, r.fit_order
        if symmetric:
            for x in (ref, band, order):
                low = np.tril_indices(shape[0], -1)
                x[low] = x.T[low]
        return ref, band, order
    gci, order, _ = grid_convergence_index(mats, counts)
    return richardson(mats[-2], mats[-1], counts[-2], counts[-1], order=order), gci, order


def fine_comparison(levels_path=FINE_ALL, model_path=DATA, method: str = "eca-hoekstra",
                    extra_orders=()) -> list[dict]:
    """Per term of every CAD shape in both files: the model (the stored run's rows), the
    stored 3000-face reference and the fine reference with its band (:func:`fine_reference`
    by ``method``), errors relative to the fine reference's diagonal term (a coupling: to
    sqrt(A_ii A_jj))."""
    levels = read_levels(*((levels_path,) if isinstance(levels_path, (str, Path))
                           else levels_path))
    _, stored = read_stored_run(model_path)
    rows = []
    by_shape: dict = {}
    for r in stored:
        if not r["what"].startswith("FAILED"):
            by_shape.setdefault(int(r["shape"]), []).append(r)
    for k, terms in sorted(by_shape.items()):
        lv = levels.get(k, {})
        if len(lv) < 3:
            continue
        n = [lv[x][0] for x in sorted(lv)]
        mats = [lv[x][1] for x in sorted(lv)]
        ref, band, order = fine_reference(n, mats, method, extra_orders)
        d = np.sqrt(np.abs(np.diag(ref)))
        for t in terms:
            i, j = int(t["i"]), int(t["j"])
            norm = abs(ref[i, i]) if i == j else d[i] * d[j]
            rows.append(dict(shape=k, family=t["family"], i=i, j=j, faces=n,
                             ref=ref[i, j], band=band[i, j] / norm, order=order[i, j],
                             step=abs(mats[-1][i, j] - mats[-2][i, j]) / norm,
                             err=(float(t["model"]) - ref[i, j]) / norm,
                             stored_err=(float(t["bem"]) - ref[i, j]) / norm,
                             est=float(t["estimated_error_rel"]),
                             significant=i == j or t["significant"] == "1"))
    return rows


def fine_holdout(levels_paths=FINE_ALL) -> dict:
    """The references' bands tested on a level they did not see, on every CAD shape with five
    levels or more: {"seen": {procedure: (terms whose finest-level move |f_N - f_(N-1)| lies
    within the band of f_(N-1) estimated without f_N, significant terms, the diagonal bands
    over their terms)}, "inside": {(b, a): (diagonal terms whose reference by procedure b lies
    within a's band, terms)}, "shapes": count}.  The first is a necessary condition (the
    limit of a monotone sequence lies beyond its finest level): the grid convergence index of
    the three levels before the finest, Eça & Hoekstra over the four before it."""
    levels = read_levels(*levels_paths)
    seen = {"GCI, 3 levels": [0, 0, []], "Eca-Hoekstra, 4 levels": [0, 0, []]}
    inside: dict = {}
    shapes = 0
    for k, lv in sorted(levels.items()):
        if k >= THIN_OFFSET or len(lv) < 5:
            continue
        shapes += 1
        n = [lv[x][0] for x in sorted(lv)]
        m = [lv[x][1] for x in sorted(lv)]
        diag = np.abs(np.diag(m[-1]))
        scale = np.sqrt(np.outer(diag, diag))
        terms = [(i, j) for i in range(6) for j in range(i, 6)
                 if abs(m[-1][i, j]) >= 0.01 * scale[i, j]]
        for label, (nn, mm, how) in {"GCI, 3 levels": (n[-4:-1], m[-4:-1], "gci"),
                                     "Eca-Hoekstra, 4 levels": (n[-5:-1], m[-5:-1],
                                                                "eca-hoekstra")}.items():
            _, band, _ = fine_reference(nn, mm, how)
            move = np.abs(m[-1] - mm[-1])
            c = seen[label]
            c[0] += sum(bool(move[ij] <= band[ij]) for ij in terms)
            c[1] += len(terms)
            c[2] += [float(band[i, i] / diag[i]) for i in range(6)]
        refs = {"GCI, 3 finest": fine_reference(n[-3:], m[-3:], "gci"),
                "E-H, 4 finest": fine_reference(n[-4:], m[-4:]),
                "E-H, all": fine_reference(n, m)}
        for a, (ra, ua, _) in refs.items():
            for b, (rb, _, _) in refs.items():
                if a != b:
                    x = inside.setdefault((b, a), [0, 0])
                    x[0] += int((np.abs(np.diag(rb) - np.diag(ra)) <= np.diag(ua)).sum())
                    x[1] += 6
    return dict(seen={k: tuple(v) for k, v in seen.items()},
                inside={k: tuple(v) for k, v in inside.items()}, shapes=shapes)


def fine_section() -> str:
    """The stored run's model and references against Capytaine refined to 12,000 faces."""
    if not (FINE.exists() and DATA.exists()):
        return ""
    rows = fine_comparison()
    if not rows:
        return ""
    before = fine_comparison(method="gci")
    b_diag = [r for r in before if r["i"] == r["j"]]
    b_miss = {(r["shape"], r["i"]) for r in b_diag if abs(r["err"]) > 0.05}
    b_firm = [r for r in b_diag if r["band"] <= 0.05]
    b_sig = [r for r in before if r["significant"]]
    held = fine_holdout() if FINE_750.exists() else None
    diag = [r for r in rows if r["i"] == r["j"]]
    sig = [r for r in rows if r["significant"]]
    coup = [r for r in sig if r["i"] != r["j"]]
    within = sum(abs(r["err"]) <= 0.05 for r in diag)
    bands = np.array([r["band"] for r in diag])

    def tight(limit):
        s = [r for r in diag if r["band"] <= limit]
        return f"{sum(abs(r['err']) <= 0.05 for r in s)} of {len(s)}"

    covered = sum(abs(r["err"]) <= r["est"] for r in sig)
    covered_vv = sum(abs(r["err"]) <= np.hypot(r["est"], r["band"]) for r in sig)
    miss = sorted((r for r in diag if abs(r["err"]) > 0.05), key=lambda r: -abs(r["err"]))
    finest = sorted({r["faces"][-1] for r in rows})
    fams = sorted({r["family"] for r in miss})
    loose = [r for r in miss if r["band"] > 0.05]
    firm = [r for r in miss if r["band"] <= 0.05]
    table = [[r["shape"], r["family"], DOFS[r["i"]], f"{100 * r['err']:+.1f} %",
              f"{100 * r['stored_err']:+.1f} %", f"{100 * r['band']:.1f} %",
              f"{r['order']:.2f}", f"{100 * r['est']:.1f} %"] for r in miss]
    levels = read_levels(FINE)
    thin = {k: lv for k, lv in levels.items() if k >= THIN_OFFSET and len(lv) >= 3}
    thin_rows, wing_band, wing_gci = [], 0.0, 0.0
    for k, lv in sorted(thin.items()):
        n = [lv[x][0] for x in sorted(lv)]
        ref, band, _ = fine_reference(n, [lv[x][1] for x in sorted(lv)])
        rel = np.diag(band) / np.maximum(np.abs(np.diag(ref)), 1e-300)
        thin_rows.append([k, "/".join(map(str, n))] + [f"{100 * x:.1f} %" for x in rel])
        if (k - THIN_OFFSET) % 2:                    # the odd members are the wings
            wing_band = max(wing_band, float(rel.max()))
            r3, b3, _ = fine_reference(n, [lv[x][1] for x in sorted(lv)], "gci")
            wing_gci = max(wing_gci, float((np.diag(b3) / np.abs(np.diag(r3))).max()))
    hard = [r for r in diag if (r["shape"], r["i"]) in b_miss]
    text = [
        "### The references refined to 12,000 faces\n",
        "The references above stop at 3,000 faces. The same surfaces (the same isotropic "
        "remesh family, from 1,500 faces to "
        f"{min(finest)}-{max(finest)} faces at the finest level solved, and on 35 shapes "
        "the family's 750-face level below) were solved again with "
        "Capytaine (direct method, no free surface) on a 16-core machine, the LU on its GPU, "
        "and each term estimated from all its levels by the least-squares procedure of Eça & "
        "Hoekstra (2014, J. Comput. Phys. 262, 104-130; "
        "`validation.cad_shapes.fine_reference`, `stripcoef.hull.convergence.eca_hoekstra`): "
        "the fit phi_0 + alpha h^p of least standard deviation, with or without weights "
        "favouring the fine levels, or where p is out of [0.5, 2] the best of the fixed orders "
        "1, 2 and 1 & 2; the reference is its phi_0, the band the paper's uncertainty of the "
        "finest level (safety factor 1.25 or 3, plus the fit's standard deviation and "
        "residual). Commands: "
        "`python -m benchmarks.bem_fine_references prepare --seed 1375923287 --count 40 --out "
        "DIR` (the remesh extra), `... solve --meshes DIR --csv levels.csv` (the 16-core "
        "machine; the 750-face level: `prepare ... --levels 750 1500 3000 --cad-shapes-cap`, "
        "`solve ... --max-level 0 --same-family reference_tables/bem/cad_shapes_fine_levels.csv`"
        ", one core), `... compare --levels reference_tables/bem/cad_shapes_fine_levels.csv "
        "reference_tables/bem/cad_shapes_fine_levels_750.csv --model "
        "reference_tables/bem/cad_shapes.csv --holdout`.\n",
        f"- The model's diagonal terms within 5 % of the fine references: **{within} of "
        f"{len(diag)}** (of the 3,000-face references: the table above). Where the fine "
        f"reference's own band is at most 5 %: **{tight(0.05)}**; at most 2 %: {tight(0.02)}.",
        f"- The 3,000-face references within 5 % of the fine ones: "
        f"{sum(abs(r['stored_err']) <= 0.05 for r in diag)} of {len(diag)} diagonal terms: "
        "part of the earlier agreement was two under-resolved solutions agreeing.",
        f"- Couplings within 5 % of the scale: {sum(abs(r['err']) <= 0.05 for r in coup)} of "
        f"{len(coup)}.",
        f"- The model's estimated error covers its error against the fine references in "
        f"{covered} of {len(sig)} terms ({100 * covered / len(sig):.0f} %); with the fine "
        f"references' band, root-sum-square (ASME V&V 20-2009): {covered_vv} of {len(sig)} "
        f"({100 * covered_vv / len(sig):.0f} %).",
        f"- The fine references' own band on the diagonal terms: median "
        f"{100 * np.median(bands):.1f} %, over 5 % on {int((bands > 0.05).sum())} of "
        f"{len(bands)} terms, at most {100 * bands.max():.0f} %.",
        f"- Before, by the grid convergence index of the three finest levels alone (the "
        f"panel method's own rule, Oberkampf & Roy's safety factor 3 off the asymptotic "
        f"range): {sum(abs(r['err']) <= 0.05 for r in b_diag)} of {len(b_diag)} diagonal "
        f"terms within 5 %, {sum(abs(r['err']) <= 0.05 for r in b_firm)} of {len(b_firm)} "
        f"where the band is at most 5 %, the estimate covering "
        f"{sum(abs(r['err']) <= r['est'] for r in b_sig)} of {len(b_sig)}; its "
        f"{len(b_miss)} misses ("
        f"{sum(r['band'] > 0.05 for r in b_diag if (r['shape'], r['i']) in b_miss)} with "
        f"bands over 5 %) have by Eça & Hoekstra a band of at "
        f"most 5 % on {sum(r['band'] <= 0.05 for r in hard)} and the model within 5 % on "
        f"{sum(abs(r['err']) <= 0.05 for r in hard)}."
        + (" Tested on a level they did not see (the " + str(held["shapes"]) + " shapes "
           "with five levels: the band of the last level but one, estimated without the "
           "finest, must contain the finest level's move): "
           + "; ".join(f"{label} {v[0]} of {v[1]} terms" for label, v in
                       held["seen"].items())
           + "; Eça & Hoekstra's band over all the levels contains the three-level "
           f"references in {held['inside'][('GCI, 3 finest', 'E-H, all')][0]} of "
           f"{held['inside'][('GCI, 3 finest', 'E-H, all')][1]} diagonal terms, the "
           f"three-level band contains Eça & Hoekstra's in "
           f"{held['inside'][('E-H, all', 'GCI, 3 finest')][0]}." if held else "")
        + "\n",
        f"Of the {len(miss)} terms off by more than 5 % (families: {', '.join(fams)}), "
        f"{len(loose)} have a fine reference that is itself uncertain by more than 5 %"
        + (f" (the order of its fit, column *order*: median "
           f"{np.median([r['order'] for r in loose]):.2f} in h, where a smooth body converges "
           f"at 2; the last doubling of the faces still moved them by "
           f"{100 * min(r['step'] for r in loose):.1f} to "
           f"{100 * max(r['step'] for r in loose):.1f} %)" if loose else "")
        + "; " + ("; ".join(f"the other{'s' if len(firm) > 1 else ''}: " + ", ".join(
            f"shape {r['shape']} {DOFS[r['i']]} {100 * r['err']:+.1f} % against a "
            f"{100 * r['band']:.1f} % band" for r in firm) for _ in [0]) if firm else
            "none is off where the reference has converged")
        + ". These are bodies with sharp convex edges: the potential of the flow in a wedge "
        "of fluid of angle alpha, r^(pi/alpha) cos(pi theta/alpha), makes the velocity "
        "singular as r^(-1/3) at a right-angled edge and r^(-1/2) at a plate's rim, which "
        "constant panels of uniform size resolve slowly. On those terms neither solver's value is "
        "known within 5 %, and the comparison cannot say which is closer; what would settle "
        "them is panels graded towards the edges (in both solvers) or levels beyond 24,000 "
        "faces.\n",
        markdown_table(["#", "family", "term", "model - fine reference", "3,000-face reference"
                        " - fine", "fine reference's band", "order", "model's estimate"],
                       table),
    ]
    if thin_rows:
        text += ["\nThe thin members of `benchmarks.thin_members` (seed 1473826805, shapes "
                 f"{THIN_OFFSET}+ in the same file: plates and NACA 00xx wings, their "
                 "references' panellings, four levels) refined the same way: the fine "
                 "references' own band "
                 "per diagonal term (over the term itself). The wings' references are "
                 f"uncertain by up to {100 * wing_band:.0f} % at 8,000 faces (by the "
                 f"three finest levels' grid convergence index: up to {100 * wing_gci:.0f} %)"
                 ": some of the wings' terms are not known within 5 % even there.\n",
                 markdown_table(["#", "faces"] + [f"band {d}" for d in DOFS], thin_rows)]
    return "\n".join(text) + "\n"


def section() -> str:
    if not DATA.exists():
        return ""
    command, rows = read_stored_run(DATA)
    shapes = {}
    failed = []
    for r in rows:
        if r["what"].startswith("FAILED"):
            failed.append((r["shape"], r["family"], r["what"]))
            continue
        shapes.setdefault(r["shape"], []).append(r)
    table = []
    diag_ok = diag_n = coup_ok = coup_n = cov = cov_n = 0
    all_ok = warned_miss = missed = 0
    t_model, t_bem = [], []
    for k, terms in shapes.items():
        head = terms[0]
        sig = [t for t in terms if t["significant"] == "1"]
        diag = [t for t in terms if t["i"] == t["j"]]
        coup = [t for t in sig if t["i"] != t["j"]]
        rel = {(int(t["i"]), int(t["j"])): float(t["error_rel"]) for t in terms}
        wd = max(diag, key=lambda t: abs(float(t["error_rel"])))
        wc = max(coup, key=lambda t: abs(float(t["error_rel"]))) if coup else None
        diag_ok += sum(abs(float(t["error_rel"])) <= 0.05 for t in diag)
        diag_n += len(diag)
        coup_ok += sum(abs(float(t["error_rel"])) <= 0.05 for t in coup)
        coup_n += len(coup)
        c = sum(t["covered"] == "1" for t in sig)
        cov += c
        cov_n += len(sig)
        ok = all(abs(float(t["error_rel"])) <= 0.05 for t in sig)
        all_ok += ok
        if not ok:
            missed += 1
            warned_miss += head["warned"] == "1"
        t_model.append(float(head["t_model_s"]))
        t_bem.append(number(head.get("t_bem_s")))
        table.append([k, head["family"], f"{head['what']} [{head['how']}]", head["panels"],
                      head["mirrors"],
                      f"{DOFS[int(wd['i'])]} {100 * rel[(int(wd['i']), int(wd['i']))]:+.1f} %",
                      (f"{DOFS[int(wc['i'])]}-{DOFS[int(wc['j'])]} "
                       f"{100 * float(wc['error_rel']):+.1f} %") if wc else "-",
                      f"{c}/{len(sig)}", "yes" if head["warned"] == "1" else "no"])
    n = len(shapes)
    miss = [t for terms in shapes.values() for t in terms
            if t["significant"] == "1" and abs(float(t["error_rel"])) > 0.05]
    miss_steps = [x for x in (number(t.get("bem_richardson_step_rel")) for t in miss)
                  if np.isfinite(x)]
    miss_families = {t["family"] for terms in shapes.values() for t in terms
                     if t["significant"] == "1" and abs(float(t["error_rel"])) > 0.05}
    all_steps = [x for x in (number(t.get("bem_richardson_step_rel"))
                             for terms in shapes.values() for t in terms if t["i"] == t["j"])
                 if np.isfinite(x)]
    note = ((f" Of the {len(miss)} terms off by more than 5 %, the reference's own "
             f"Richardson step (finest BEM level to the extrapolation) is "
             + (f"{100 * min(miss_steps):.1f} to {100 * max(miss_steps):.1f} % of the term "
                f"there" if miss_steps else "unknown (not in the stored run)")
             + (f", unknown on {len(miss) - len(miss_steps)}"
                if miss_steps and len(miss_steps) < len(miss) else "")
             + (f" (median over all diagonal terms {100 * np.median(all_steps):.1f} %"
                if all_steps else " (")
             + f"{'; ' if all_steps else ''}families: {', '.join(sorted(miss_families))}).")
            if miss else "")
    gci = ""
    if rows and "covered_with_bem_gci" in rows[0]:
        sig = [t for terms in shapes.values() for t in terms if t["significant"] == "1"]
        known = [t for t in sig if t["covered_with_bem_gci"] in ("0", "1")]
        vv = sum(t["covered_with_bem_gci"] == "1" for t in known)
        cpu = [float(terms[0]["cpu_model_s"]) for terms in shapes.values()]
        warned_all = sum(terms[0]["warned"] == "1" for terms in shapes.values())
        missed_cov = [t for t in known if t["covered_with_bem_gci"] != "1"]
        worst_miss = max(missed_cov, key=lambda t: abs(float(t["error_rel"])) - float(
            t["estimated_error_rel"])) if missed_cov else None
        gci = (" The estimate is the grid convergence index of the panel levels (Roache 1994, "
               "1998; safety factor and order as Oberkampf & Roy 2010, sec. 8.6.3.2: 1.25 and "
               "the formal order where the three finest levels' observed order is within 10 % "
               "of it, else 3 and the observed order, at least 0.5) "
               "plus the extrapolation's step; the references carry their own (three BEM "
               "levels). Counting both, root-sum-square as ASME V&V 20-2009 prescribes for a "
               "comparison error, the band covers "
               + (f"{vv} of {len(known)} terms ({100 * vv / len(known):.0f} %)" if known
                  else "an unknown number of terms (the references' own band is not in the "
                       "stored run)")
               + (f", the reference's band unknown on the other {len(sig) - len(known)}"
                  if known and len(known) < len(sig) else "")
               + (f"; the worst miss is {DOFS[int(worst_miss['i'])]}-"
                  f"{DOFS[int(worst_miss['j'])]} of shape {worst_miss['shape']} "
                  f"({worst_miss['family']}): error {100 * float(worst_miss['error_rel']):+.1f} %"
                  f" against the model's {100 * float(worst_miss['estimated_error_rel']):.1f} % "
                  f"and the reference's {100 * float(worst_miss['bem_gci_rel']):.1f} %"
                  if worst_miss else "")
               + f". The not-converged warning went off on {warned_all} of {n} shapes. "
               f"Whole-estimate CPU time (one thread): median {np.median(cpu):.2f} s, max "
               f"{max(cpu):.2f} s.")
    parts = ["## CAD-style bluff shapes, a fresh seed per run (issue 32)\n",
             "`benchmarks/cad_shapes.py` draws shapes from families of what CAD tools export "
             "(extruded convex polygons with fan-triangulated caps, chamfered and filleted "
             "boxes, frames of plates and tubes as overlapping parts, thin plates, coarse "
             "tessellations, box hulls with a pod pushed in), writes each as a user has it "
             "(millimetres or metres, STL or an OBJ with its vertices split at every face), "
             "and runs the whole estimate with `added_mass_method=\"panels\"` (default with the "
             "`remesh` extra, as in this run: isotropic remeshes at 400, 800 and 1600 panels, refined to 3200 while a term's estimated "
             "error exceeds 5 %) against Capytaine (direct method, no free surface) on "
             "isotropic remeshes of the shape's clean union at the resolutions of the command "
             "below, the two finest Richardson-extrapolated, about the same point. Nothing is "
             "fitted: every run draws a new seed. The stored run:\n",
             f"    {command}\n",
             f"{n} shapes solved" + (f", {len(failed)} failed (below)" if failed else "") + ": "
             f"diagonal terms within 5 %: {diag_ok} of {diag_n}; couplings (reference at least "
             f"1 % of sqrt(A_ii A_jj)) within 5 % of that scale: {coup_ok} of {coup_n}; shapes "
             f"with every such term within 5 %: {all_ok} of {n}. The estimated error "
             f"(`added_mass_error`) covers the actual error in {cov} of {cov_n} terms "
             f"({100 * cov / max(cov_n, 1):.0f} %; the issue asks for 90 %). "
             + (f"Of the {missed} shapes with a term off by more than 5 %, {warned_miss} got "
                f"the not-converged warning. " if missed else
                "No shape has a term off by more than 5 %. ")
             + f"Median whole-estimate time "
             f"{np.median(t_model):.2f} s (loaded shared machine, one BLAS thread), the BEM "
             f"reference solves (all levels, the references' own run) "
             + (f"{np.nanmedian(t_bem):.2f} s" if np.isfinite(t_bem).any() else "unknown")
             + (f" (unknown on {int(np.isnan(t_bem).sum())} shapes)"
                if 0 < np.isnan(t_bem).sum() < len(t_bem) else "")
             + "." + note + gci + "\n",
             markdown_table(["#", "family", "shape [file]", "panels", "mirrors",
                             "worst diagonal", "worst coupling (of scale)", "estimate covers",
                             "warned"], table)]
    if failed:
        parts.append("\nFailed: " + "; ".join(f"#{k} {fam}: {why}" for k, fam, why in failed))
    return "\n".join(parts) + "\n\n" + fine_section() + graded_section()


def read_graded(path=GRADED) -> dict:
    """{shape: (chord, span, thickness [m], faces per level, {i: values per level})} of the
    edge-graded plate levels (``benchmarks.plate_graded``: one row per level and diagonal
    term [kg, kg m^2]), levels coarse to fine."""
    import csv

    out: dict = {}
    with open(path, newline="") as fh:
        fh.readline()
        for r in csv.DictReader(fh):
            k = int(r["shape"])
            x = out.setdefault(k, (float(r["chord_m"]), float(r["span_m"]),
                                   float(r["thickness_m"]), {}, {}))
            x[3][int(r["level"])] = int(r["faces"])
            x[4].setdefault(int(r["i"]), {})[int(r["level"])] = float(r["added_mass"])
    return {k: (c, s, t, [f[x] for x in sorted(f)],
                {i: [v[x] for x in sorted(v)] for i, v in terms.items()})
            for k, (c, s, t, f, terms) in out.items()}


def graded_comparison(graded_path=GRADED, model_path=DATA) -> list[dict]:
    """Per diagonal term of every plate in ``graded_path``: the edge-graded reference and its
    band (Eça & Hoekstra over its levels, :func:`fine_reference`), the model (the stored run's
    row), the stored 3,000-face reference and the uniform fine reference with its band
    (:func:`fine_comparison`), all relative to the graded reference."""
    graded = read_graded(graded_path)
    _, stored = read_stored_run(model_path)
    fine = {(r["shape"], r["i"]): r for r in fine_comparison(model_path=model_path)
            if r["i"] == r["j"]}
    rows = []
    for k, (c, s, t, faces, terms) in sorted(graded.items()):
        for i, vals in sorted(terms.items()):
            if len(vals) < 3:
                continue
            ref, band, order = (float(x[0, 0]) for x in fine_reference(
                faces, [np.array([[v]]) for v in vals]))
            row = next((r for r in stored if r["shape"] == str(k) and r["i"] == str(i)
                        and r["j"] == str(i)), None)
            if row is None:
                continue
            f = fine.get((k, i))
            rows.append(dict(
                shape=k, i=i, dims=(c, s, t), faces=faces, ref=ref, band=band / abs(ref),
                order=order, step=abs(vals[-1] - vals[-2]) / abs(ref),
                err=(float(row["model"]) - ref) / abs(ref),
                est=float(row["estimated_error_rel"]),
                stored_err=(float(row["bem"]) - ref) / abs(ref),
                fine_err=None if f is None else (f["ref"] - ref) / abs(ref),
                fine_band=None if f is None else f["band"] * abs(f["ref"]) / abs(ref)))
    return rows


def graded_section() -> str:
    """The seed's plates against Capytaine on edge-graded panels."""
    if not (GRADED.exists() and DATA.exists()):
        return ""
    rows = graded_comparison()
    if not rows:
        return ""
    table = [[r["shape"], "%.3f x %.3f x %.4f" % r["dims"], DOFS[r["i"]],
              f"{r['faces'][0]}-{r['faces'][-1]}", f"{100 * r['band']:.1f} %",
              f"{r['order']:.2f}", f"{100 * r['err']:+.1f} %", f"{100 * r['est']:.1f} %",
              f"{100 * r['stored_err']:+.1f} %",
              "-" if r["fine_err"] is None else
              f"{100 * r['fine_err']:+.1f} % (band {100 * r['fine_band']:.1f} %)"]
             for r in rows]
    within = sum(abs(r["err"]) <= 0.05 for r in rows)
    covered = sum(abs(r["err"]) <= r["est"] for r in rows)
    inplane = [r for r in rows if r["i"] in (0, 1, 5)]
    normal = [r for r in rows if r["i"] in (2, 3, 4)]
    checks = graded_checks() if GRADED_CHECKS.exists() else None
    best = best_comparison()
    b_diag = [r for r in best if r["i"] == r["j"]]
    b_sig = [r for r in best if r["significant"]]
    b_coup = [r for r in b_sig if r["i"] != r["j"]]
    b_miss = sorted((r for r in b_diag if abs(r["err"]) > 0.05), key=lambda r: -abs(r["err"]))
    b_fams = sorted({r["family"] for r in b_miss})
    # the terms the stored run finds off by more than 5 %, against the most resolved reference
    was = sorted((r for r in b_diag if abs(r["stored_rel"]) > 0.05),
                 key=lambda r: -abs(r["stored_rel"]))
    stored_ok = sum(abs(r["stored_err"]) <= 0.05 for r in rows)
    fine_in = [r for r in rows if r["fine_err"] is not None]
    consistent = sum(abs(r["fine_err"]) <= np.hypot(r["fine_band"], r["band"])
                     for r in fine_in)
    return "\n".join([
        "\n### The plates with panels graded towards their edges\n",
        "The same solver (Capytaine, direct method, no free surface) on structured "
        "quadrilaterals spaced as x_k = L sin(pi k / 2m) on each half-edge L, so that the "
        "panel next to an edge is the square of the uniform one and the edge's singular flow "
        "is resolved; the box's mirror planes used; each term from its levels by Eça & "
        "Hoekstra as above. Commands: `python -m benchmarks.plate_graded --seed 1375923287 "
        "--count 40 --levels 8 11 16 23 32 --csv reference_tables/bem/cad_plates_graded.csv` "
        "(run as two `--only` processes, merged) and `python -m benchmarks.plate_graded "
        "--checks --levels 8 11 16 23 --checks-csv "
        "reference_tables/bem/plates_graded_checks.csv` (the procedure against the exact thin "
        "disc and DNV-RP-H103 table A-2).\n",
        f"- The model within 5 % of the graded references: **{within} of {len(rows)}** "
        f"diagonal terms of {len({r['shape'] for r in rows})} plates; its estimate covers "
        f"{covered} of them. The stored 3,000-face references within 5 % of them: {stored_ok} of "
        f"{len(rows)}. The uniform fine references agree with them within the two bands "
        f"(root-sum-square) on {consistent} of {len(fine_in)}.",
        f"- The graded references' own band: median "
        f"{100 * np.median([r['band'] for r in rows]):.1f} %, at most "
        f"{100 * max(r['band'] for r in rows):.1f} %.",
        f"- The model is high on the in-plane terms (surge, sway, yaw: a plate moving or "
        f"turning in its own plane): {100 * min(r['err'] for r in inplane):+.1f} to "
        f"{100 * max(r['err'] for r in inplane):+.1f} %, within 5 % on "
        f"{sum(abs(r['err']) <= 0.05 for r in inplane)} of {len(inplane)}; on the normal and "
        f"rotary terms (heave, roll, pitch) {100 * min(r['err'] for r in normal):+.1f} to "
        f"{100 * max(r['err'] for r in normal):+.1f} %. Its levels converge at order about "
        f"1 in h (the knife edge's), and its value is extrapolated at that formal order "
        f"(`stripcoef.hull.panels.edge_order`; order 2 before: `benchmarks/cad_value_order.py`"
        f", `benchmarks/data/cad_value_order.md`), as Capytaine on edge-graded panels of the "
        f"bluff set's boxes, these plates and the seed's extruded polygons decided "
        f"(`benchmarks/graded_value_order.py`, `benchmarks/data/graded_value_order.md`).",
        ("- The procedure checked (`reference_tables/bem/plates_graded_checks.csv`): "
         + "; ".join(checks["lines"]) + ".") if checks else "",
        f"- Against the most resolved reference this repository holds for each term (the "
        f"edge-graded, else the fine uniform, else the 3,000-face one: "
        f"`validation.cad_shapes.best_references`), the model's diagonal terms are within 5 % "
        f"on **{sum(abs(r['err']) <= 0.05 for r in b_diag)} of {len(b_diag)}**, couplings "
        f"within 5 % of the scale on {sum(abs(r['err']) <= 0.05 for r in b_coup)} of "
        f"{len(b_coup)}; the estimate covers {sum(abs(r['err']) <= r['est'] for r in b_sig)}"
        f" of {len(b_sig)} terms (with the reference's band, root-sum-square: "
        f"{sum(abs(r['err']) <= np.hypot(r['est'], r['band']) for r in b_sig)}). The "
        f"{len(b_miss)} diagonal {'term' if len(b_miss) == 1 else 'terms'} off by more "
        f"than 5 % ({'family' if len(b_fams) == 1 else 'families'} {', '.join(b_fams)}): "
        + "; ".join(f"{r['shape']} {DOFS[r['i']]} {100 * r['err']:+.1f} % ({r['source']}, "
                    f"band {100 * r['band']:.1f} %)" for r in b_miss) + ".",
        f"- The {len(was)} diagonal terms off by more than 5 % against the stored 3,000-face "
        "references, against the most resolved one (model error there; the 3,000-face "
        "reference's own error there): "
        + "; ".join(f"{r['shape']} {r['family']} {DOFS[r['i']]} "
                    f"{100 * r['stored_rel']:+.1f} % -> {100 * r['err']:+.1f} % "
                    f"({100 * r['stored_err']:+.1f} %)" for r in was)
        + ". Where the last number exceeds 5 % the 3,000-face reference was wrong; where the "
        "middle one does, the model is wrong too.\n",
        markdown_table(["#", "plate c x s x t [m]", "term", "faces", "graded band", "order",
                        "model - graded", "model's estimate", "3,000-face ref. - graded",
                        "fine ref. - graded"], table),
    ]) + "\n"


def graded_checks(path=GRADED_CHECKS) -> dict:
    """The edge-graded procedure (``benchmarks.plate_graded --checks``) against exact and
    published values: per body and t/a, each diagonal term by Eça & Hoekstra over its levels
    (:func:`fine_reference`), then t -> 0 by the linear extrapolation 2 f(t/2) - f(t) (the
    error linear in t removed, as benchmarks/plate_added_mass.py).  Compared with the thin
    circular disc of radius a, A_33 = 8/3 rho a^3 and A_44 = A_55 = 16/45 rho a^5 (Lamb
    1932, Hydrodynamics, art. 108; Newman 1977 table 4.3), and with DNV-RP-H103 table A-2
    for rectangular plates, lambda = A_33 / (rho pi/4 a^2 b) (a = 1 m the shorter side).
    Returns {"disc": {i: (t -> 0 value, exact, relative error)}, "plates": {b/a: (lambda at
    t -> 0, DNV's, relative error)}, "bands": largest relative band of a level series,
    "lines": the same as text}."""
    import csv

    from stripcoef.data import load_table

    series: dict = {}
    with open(path, newline="") as fh:
        fh.readline()
        for r in csv.DictReader(fh):
            key = (r["body"], float(r["b_over_a"]), float(r["t_over_a"]), int(r["i"]))
            series.setdefault(key, []).append((int(r["faces"]), float(r["added_mass"])))
    ext, bands = {}, []
    for key, lv in series.items():
        lv.sort()
        ref, band, _ = fine_reference([n for n, _ in lv], [np.array([[v]]) for _, v in lv])
        ext[key] = float(ref[0, 0])
        if key[3] in (2, 3, 4):                     # the normal and rotary terms
            bands.append(float(band[0, 0] / abs(ref[0, 0])))
    thick = sorted({k[2] for k in ext}, reverse=True)
    rho, a = 1000.0, 1.0

    def zero(body, ratio, i):
        return 2 * ext[(body, ratio, thick[1], i)] - ext[(body, ratio, thick[0], i)]

    exact = {2: 8 / 3 * rho * a ** 3, 3: 16 / 45 * rho * a ** 5, 4: 16 / 45 * rho * a ** 5}
    disc = {i: (zero("disc", 1.0, i), x, zero("disc", 1.0, i) / x - 1) for i, x in exact.items()}
    table = load_table("plate_added_mass_dnv")
    plates = {}
    for ratio in sorted({k[1] for k in ext if k[0] == "plate"}):
        lam = zero("plate", ratio, 2) / (rho * np.pi / 4 * a * a * ratio * a)
        dnv = table.interp(1.0 / ratio, "lambda")
        plates[ratio] = (lam, dnv, lam / dnv - 1)
    lines = [f"disc, t -> 0 (t/a {thick[0]} and {thick[1]}): "
             + "; ".join(f"{DOFS[i]} {v:.5g} against exact {x:.5g} ({100 * e:+.2f} %)"
                         for i, (v, x, e) in disc.items())]
    lines += [f"plate b/a = {r:g}: lambda at t -> 0 {v:.4f}, DNV-RP-H103 table A-2 {d:.3f} "
              f"({100 * e:+.2f} %)" for r, (v, d, e) in plates.items()]
    return dict(disc=disc, plates=plates, bands=max(bands), lines=lines)


def read_graded_levels(path) -> dict:
    """{shape: {level: (faces, 6x6 [kg, kg m, kg m^2])}} of a graded references CSV whose
    first line is its ``# `` command (``benchmarks.graded_polyhedra``: one row per level and
    upper-triangle term; the shape the CAD benchmark's index)."""
    import csv

    out: dict = {}
    with open(path, newline="") as fh:
        fh.readline()
        for r in csv.DictReader(fh):
            lv = out.setdefault(int(r["shape"]), {})
            _, a = lv.setdefault(int(r["level"]), (int(r["faces"]), np.zeros((6, 6))))
            i, j = int(r["i"]), int(r["j"])
            a[i, j] = a[j, i] = float(r["added_mass"])
    return out


def best_references(model_path=DATA) -> dict:
    """{(shape, i, j): (reference, band [kg, kg m, kg m^2], source)} of every term of the
    stored run: of the references this repository holds for the term -- the stored run's own
    (``bem``, 750-3,000 faces, its grid convergence index ``bem_gci_rel``), the fine levels'
    (up to 12,000-17,000 faces, Eça & Hoekstra, :func:`fine_reference`) and the edge-graded
    levels' (on the plates' diagonal terms :func:`read_graded`; every term of the coarse
    cylinders, :data:`GRADED_COARSE`, and of the low-polygon ellipsoid 14 and the filleted box
    18, :data:`GRADED_CAD`)
    -- the most resolved: the edge-graded, else the fine, else the stored one.  Not the smallest band: a three-level
    index of levels before the asymptotic range can be small and wrong (the plates' stored
    references, bands of 2-6 %, lie up to 18 % from the edge-graded ones, whose bands are
    0.3-2.5 %: docs/validation.md); an unknown band is never chosen."""
    command, stored = read_stored_run(model_path)
    out: dict = {}
    shapes: dict = {}
    for r in stored:
        if r["what"].startswith("FAILED"):
            continue
        shapes.setdefault(int(r["shape"]), []).append(r)
    # the fine and graded files number the shapes of REFERENCE_SEED: another seed's run (its
    # command names its seed) has only its own stored references
    seed = re.search(r"--seed (\d+)", command)
    ours = seed is None or int(seed.group(1)) == REFERENCE_SEED
    levels = read_levels(*FINE_ALL) if ours else {}
    graded = read_graded() if ours and GRADED.exists() else {}
    coarse = {}
    for path in (GRADED_COARSE, GRADED_CAD) if ours else ():
        if not path.exists():
            continue
        for k, lv in read_graded_levels(path).items():
            n = [lv[x][0] for x in sorted(lv)]
            coarse[k] = (*fine_reference(n, [lv[x][1] for x in sorted(lv)]), n)
    for k, terms in shapes.items():
        ref = np.zeros((6, 6))
        for t in terms:
            i, j = int(t["i"]), int(t["j"])
            ref[i, j] = ref[j, i] = float(t["bem"])
        d = np.sqrt(np.abs(np.diag(ref)))
        cands: dict = {}
        for t in terms:
            i, j = int(t["i"]), int(t["j"])
            band = number(t.get("bem_gci_rel")) * d[i] * d[j]
            if np.isfinite(band):
                cands.setdefault((i, j), []).append((band, float(t["bem"]), "3,000 faces"))
        lv = levels.get(k, {})
        if len(lv) >= 3:
            f_ref, f_band, _ = fine_reference([lv[x][0] for x in sorted(lv)],
                                              [lv[x][1] for x in sorted(lv)])
            for (i, j) in list(cands):
                cands[(i, j)].append((float(f_band[i, j]), float(f_ref[i, j]),
                                      f"fine, {lv[max(lv)][0]} faces"))
        if k in coarse:
            c_ref, c_band, _, c_faces = coarse[k]
            for (i, j) in list(cands):
                cands[(i, j)].append((float(c_band[i, j]), float(c_ref[i, j]),
                                      f"edge-graded, {c_faces[-1]} faces"))
        if k in graded:
            faces, g_terms = graded[k][3], graded[k][4]
            for i, vals in g_terms.items():
                g_ref, g_band, _ = fine_reference(faces, [np.array([[v]]) for v in vals])
                cands.setdefault((i, i), []).append((float(g_band[0, 0]), float(g_ref[0, 0]),
                                                     f"edge-graded, {faces[-1]} faces"))
        for key, c in cands.items():
            band, value, source = c[-1]             # appended least to most resolved
            out[(k, *key)] = (value, band, source)
    return out


def best_matrices(model_path=DATA) -> tuple[dict, dict]:
    """``({shape: 6x6 reference}, {shape: 6x6 band})`` [kg, kg m, kg m^2] of
    :func:`best_references`, each term and its transpose (a term without a reference: 0)."""
    refs: dict = {}
    bands: dict = {}
    for (k, i, j), (value, band, _) in best_references(model_path).items():
        ref, bnd = refs.setdefault(k, np.zeros((6, 6))), bands.setdefault(k, np.zeros((6, 6)))
        ref[i, j] = ref[j, i] = value
        bnd[i, j] = bnd[j, i] = band
    return refs, bands


def best_comparison(model_path=DATA) -> list[dict]:
    """Per term of the stored run: the model against :func:`best_references`, the error and
    the band relative to the best reference's diagonal scale (a coupling: sqrt(A_ii A_jj))."""
    best = best_references(model_path)
    _, stored = read_stored_run(model_path)
    rows = []
    for t in stored:
        if t["what"].startswith("FAILED"):
            continue
        k, i, j = int(t["shape"]), int(t["i"]), int(t["j"])
        if (k, i, j) not in best:
            continue
        ref, band, source = best[(k, i, j)]
        norm = np.sqrt(abs(best[(k, i, i)][0] * best[(k, j, j)][0]))
        rows.append(dict(shape=k, family=t["family"], i=i, j=j, ref=ref, band=band / norm,
                         norm=norm, source=source, err=(float(t["model"]) - ref) / norm,
                         est=float(t["estimated_error_rel"]),
                         stored_err=(float(t["bem"]) - ref) / norm,
                         stored_rel=float(t["error_rel"]),
                         significant=i == j or t["significant"] == "1"))
    return rows

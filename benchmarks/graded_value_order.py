"""The order of the panel method's extrapolated value against references that assume no order
(issue 32): edge-graded Capytaine on the bluff set's boxes and the CAD benchmark's plates and
extrusions.

``stripcoef.hull.panels.panel_added_mass`` extrapolates each term from its two finest levels
at order 2 in the panel size h; at a convex edge the levels converge at the edge's formal
order (``info["formal_order"]``, :func:`stripcoef.hull.panels.edge_order`: 4/3 at a right
angle, 1 at a knife edge).  ``benchmarks.cad_value_order`` found the formal order better on
the CAD shapes, while the bluff set's uniform references (``bem_bluff.csv``, two levels,
Richardson at order 2) found it worse on a box.  Here both are compared with references
that take no order: Capytaine on panels graded towards every edge, Eça & Hoekstra's least
squares over four or five levels (``benchmarks.graded_references``: the boxes;
``benchmarks.plate_graded``: the plates; ``benchmarks.graded_references extrusions``: the
extruded polygons).  The model's levels are recorded as it runs (the bluff set's boxes from
their 12-face input as ``benchmarks.bluff_shapes`` gives it; the CAD shapes as
``benchmarks.cad_value_order.recorded_run`` re-runs them), and its two finest levels
re-extrapolated (Roache 1998 eq. 5.4.1) at order 2 (the library's value, checked), at the
formal order and at order 1.  Usage:

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.graded_value_order [--md FILE]

(a few minutes on one core; needs the ``remesh`` extra, as the stored runs.)
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from validation.graded_bodies import BLUFF, BOXES, EXTRUSIONS, UNIONS

DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")
#: a coupling is compared when the reference is at least this fraction of sqrt(A_ii A_jj)
SIGNIFICANT = 0.01
ORDERS = ("2", "formal", "1")
#: a reference whose band (relative to the scale) is at most this is counted as settled
SETTLED = 0.02


def _values(counts, mats, formal):
    """{"2", "formal", "1": the two finest levels Richardson-extrapolated at that order}."""
    from stripcoef.hull.convergence import richardson

    return {k: richardson(mats[-2], mats[-1], counts[-2], counts[-1], order=p)
            for k, p in (("2", 2.0), ("formal", formal), ("1", 1.0))}


def _library(vals, value):
    """(the order whose value the library returned: "2" or "formal", their relative
    difference from it) -- the re-extrapolation checked against the library's own."""
    diff = {k: float(np.abs(vals[k] - value).max() / np.abs(value).max())
            for k in ("2", "formal")}
    k = min(diff, key=diff.get)
    return k, diff[k]


#: the set a graded file of the bluff set's shapes is counted in
KINDS = {BOXES.name: "bluff box", BLUFF.name: "bluff prism", UNIONS.name: "bluff union"}


def box_rows(paths=(BOXES, BLUFF, UNIONS)):
    """Per diagonal term and significant coupling (at least :data:`SIGNIFICANT` of the scale)
    of each shape of the bluff set in ``paths`` (the boxes, the chamfered box, the unions of
    prisms): the model's values against the graded reference, with the stored uniform
    reference (``bem_bluff.csv``: Richardson at order 2, and its finest level) against it
    too, relative to the reference's diagonal scale."""
    from benchmarks.bluff_shapes import panel_matrix, read_references
    from validation.graded_bodies import references

    refs = {}
    for path in paths:
        if Path(path).exists():
            refs.update({k: (*x, KINDS.get(Path(path).name, "bluff")) for k, x in references(path).items()})
    rich, fine = read_references("richardson"), read_references("a_2")
    rows = []
    for name, (ref, band, order, faces, kind) in refs.items():
        a, _, info = panel_matrix(name)
        counts, mats = list(info["panels"]), [np.asarray(m, float) for m in info["levels"]]
        vals = _values(counts, mats, float(info["formal_order"]))
        check = _library(vals, a)
        for row, i, j, norm in _matrix_rows(kind, name, ref, band, order, faces,
                                            float(info["formal_order"]), counts, check,
                                            np.asarray(info["error"]), vals):
            row.update(stored=(rich[name][i, j] - ref[i, j]) / norm,
                       stored_fine=(fine[name][i, j] - ref[i, j]) / norm)
            rows.append(row)
    return rows


def _matrix_rows(kind, name, ref, band, order, faces, formal, counts, check, error, vals):
    """``(row, i, j, norm)`` per diagonal term and significant coupling (at least
    :data:`SIGNIFICANT` of the scale) of one shape: the model's values ``vals`` against the
    graded reference ``ref``, relative to ``norm``, the reference's diagonal scale."""
    d = np.sqrt(np.abs(np.diag(ref)))
    for i in range(6):
        for j in range(i, 6):
            norm = d[i] * d[j]
            if i != j and abs(ref[i, j]) < SIGNIFICANT * norm:
                continue
            yield (dict(set=kind, shape=name, i=i, j=j, ref=ref[i, j], band=band[i, j] / norm,
                        order=order[i, j], faces=faces[-1], formal=formal, panels=counts,
                        check=check, est=float(error[i, j]) / norm,
                        err={o: (x[i, j] - ref[i, j]) / norm for o, x in vals.items()}),
                   i, j, norm)


def cad_rows(extrusions=EXTRUSIONS, recorded=None):
    """Per diagonal term of the CAD benchmark's plates (``cad_plates_graded.csv``) and per term
    of its extrusions (``extrusions``; couplings of at least :data:`SIGNIFICANT` of the
    scale): the model's values against the graded references, relative to the reference's
    diagonal scale."""
    from benchmarks.cad_value_order import recorded_run
    from validation.graded_bodies import references
    from validation.cad_shapes import fine_reference, read_graded

    plates = read_graded()
    ext = references(extrusions) if Path(extrusions).exists() else {}
    rec = recorded_run(only=sorted(set(plates) | set(ext))) if recorded is None else recorded
    rows = []
    for k, (c, s, t, faces, terms) in sorted(plates.items()):
        if k not in rec:
            continue
        counts, mats, formal, value, error = rec[k]
        vals = _values(counts, mats, formal)
        check = _library(vals, value)
        for i, v in sorted(terms.items()):
            ref, band, order = (float(x[0, 0]) for x in fine_reference(
                faces, [np.array([[y]]) for y in v]))
            rows.append(dict(set="CAD plate", shape=k, i=i, j=i, ref=ref, band=band / ref,
                             order=order, faces=faces[-1], formal=formal, panels=counts,
                             check=check, est=float(error[i, i]) / ref,
                             err={o: (x[i, i] - ref) / ref
                                               for o, x in vals.items()}))
    for k, (ref, band, order, faces) in sorted(ext.items()):
        if k not in rec:
            continue
        counts, mats, formal, value, error = rec[k]
        vals = _values(counts, mats, formal)
        check = _library(vals, value)
        rows += [row for row, *_ in _matrix_rows("CAD extrusion", k, ref, band, order, faces,
                                                  formal, counts, check, np.asarray(error),
                                                  vals)]
    return rows


def summary(rows) -> str:
    lines = ["| set | terms | within 5 %: order 2 / formal / 1 | within 2 %: order 2 / formal "
             "/ 1 | median abs. error: order 2 / formal / 1 | max abs. error: order 2 / formal "
             "/ 1 | closer to the reference at formal than at 2 | reference band: median, max "
             "| the library's estimate covers its error |", "|---|---|---|---|---|---|---|---|---|"]
    groups = [(s, [r for r in rows if r["set"] == s]) for s in dict.fromkeys(r["set"]
                                                                            for r in rows)]
    settled = [r for r in rows if abs(r["band"]) <= SETTLED]
    for label, g in groups + [("all", rows), (f"all, reference band <= {100 * SETTLED:g} %",
                                              settled)]:
        e = {o: np.abs([r["err"][o] for r in g]) for o in ORDERS}
        closer = sum(abs(r["err"]["formal"]) < abs(r["err"]["2"]) for r in g)
        # the library's estimated error about its own value (the order it extrapolates at)
        cov = sum(abs(r["err"][r["check"][0]]) <= r["est"] for r in g)
        b = np.abs([r["band"] for r in g])
        lines.append(f"| {label} | {len(g)} | "
                     + " / ".join(str(int((e[o] <= 0.05).sum())) for o in ORDERS) + " | "
                     + " / ".join(str(int((e[o] <= 0.02).sum())) for o in ORDERS) + " | "
                     + " / ".join(f"{100 * np.median(e[o]):.2f}" for o in ORDERS) + " % | "
                     + " / ".join(f"{100 * e[o].max():.1f}" for o in ORDERS) + " % | "
                     + f"{closer} of {len(g)} | {100 * np.median(b):.2f} %, "
                     f"{100 * b.max():.2f} % | {cov} of {len(g)} |")
    box = [r for r in rows if r["set"].startswith("bluff")]
    if box:
        s = np.abs([r["stored"] for r in box])
        lines += ["", f"The stored uniform references of the bluff set (`bem_bluff.csv`, two "
                  f"levels, Richardson at order 2) against the graded ones: median "
                  f"{100 * np.median(s):.2f} %, max {100 * s.max():.2f} %, within 1 % on "
                  f"{int((s <= 0.01).sum())} of {len(s)} terms.", "",
                  "| shape | term | graded reference (band, order, faces) | model panels | "
                  "formal order | order 2 | formal | order 1 | stored Richardson | stored "
                  "finest level |", "|---|---|---|---|---|---|---|---|---|---|"]
        lines += [f"| {r['shape']} | {DOFS[r['i']]}"
                  + ("" if r["i"] == r["j"] else f"-{DOFS[r['j']]}")
                  + f" | {r['ref']:.5g} ({100 * r['band']:.2f} %, "
                  f"{r['order']:.2f}, {r['faces']}) | {'/'.join(map(str, r['panels']))} | "
                  f"{r['formal']:.2f} | {100 * r['err']['2']:+.2f} % | "
                  f"{100 * r['err']['formal']:+.2f} % | {100 * r['err']['1']:+.2f} % | "
                  f"{100 * r['stored']:+.2f} % | {100 * r['stored_fine']:+.2f} % |" for r in box]
    cad = [r for r in rows if not r["set"].startswith("bluff")]
    if cad:
        lines += ["", "| # | set | term | graded reference (band, order, faces) | model panels | "
                  "formal order | order 2 | formal | order 1 |", "|---|---|---|---|---|---|---|"
                  "---|---|"]
        lines += [f"| {r['shape']} | {r['set']} | {DOFS[r['i']]}"
                  + ("" if r["i"] == r["j"] else f"-{DOFS[r['j']]}")
                  + f" | {r['ref']:.5g} ({100 * r['band']:.2f} %, {r['order']:.2f}, "
                  f"{r['faces']}) | {'/'.join(map(str, r['panels']))} | {r['formal']:.2f} | "
                  f"{100 * r['err']['2']:+.2f} % | {100 * r['err']['formal']:+.2f} % | "
                  f"{100 * r['err']['1']:+.2f} % |" for r in cad]
    lib = sorted({"order 2" if r["check"][0] == "2" else "the formal order" for r in rows})
    lines += ["", "(Errors relative to the reference's diagonal term, a coupling's to "
              "sqrt(A_ii A_jj). The library's value is the one at "
              + " and at ".join(lib) + "; re-computed from the recorded levels it "
              f"differs from it by at most {100 * max(r['check'][1] for r in rows):.2g} % of "
              "the largest term.)"]
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--md", default=None, help="write the summary here")
    ap.add_argument("--boxes", default=str(BOXES), help="the graded boxes' levels CSV")
    ap.add_argument("--bluff", default=str(BLUFF), help="the graded bluff prisms' levels CSV")
    ap.add_argument("--unions", default=str(UNIONS),
                    help="the graded bluff unions' levels CSV")
    ap.add_argument("--extrusions", default=str(EXTRUSIONS),
                    help="the graded extrusions' levels CSV")
    ap.add_argument("--no-cad", action="store_true", help="the bluff set's shapes only")
    args = ap.parse_args(argv)
    rows = box_rows((args.boxes, args.bluff, args.unions))
    if not args.no_cad:
        rows += cad_rows(args.extrusions)
    text = summary(rows)
    print(text)
    if args.md:
        Path(args.md).write_text(
            "# The panel method's value at order 2 and at the edge's order, against edge-graded "
            "references (benchmarks.graded_value_order)\n\n`OPENBLAS_NUM_THREADS=1 python -m "
            f"benchmarks.graded_value_order --md {args.md}`\n\n" + text)
    return 0


if __name__ == "__main__":
    sys.exit(main())

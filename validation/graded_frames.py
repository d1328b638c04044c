"""docs/validation.md: the shipped BlueROV2 Heavy's stored model rows against its graded,
mirror-symmetric Capytaine reference (issue 32), the section after
:mod:`validation.vehicle_surface`'s.

Reads ``reference_tables/bem/graded_frames.csv`` (``benchmarks.frame_references``: six levels
of the vehicle file's surface, geometry/bluerov2_heavy.stl, its y >= 0 half solved on the xOz
plane, about the body origin; each term's reference Eça & Hoekstra 2014's least squares over
the levels, :func:`validation.graded_bodies.references`), the stored model rows of
``reference_tables/bem/panels_vehicles.csv`` (both installs' diagonal terms) and the golden
model ``tests/golden/bluerov2_heavy.json`` (the base install's couplings, its reference point:
the centre of buoyancy).  The reference is moved to that point by the rigid transfer
:math:`A_P = H(-r)^T A_O H(-r)` (Fossen 2011, sec. 7.5.3;
:func:`stripcoef.conventions.transform_matrix`), its band by
:func:`validation.public_meshes.moved_uncertainty` (JCGM 100:2008 sec. 5.2.2).

A diagonal term's error is relative to the term, a coupling's to
:math:`\\sqrt{|A_{ii} A_{jj}|}` of the reference.
"""

from __future__ import annotations

import csv
import json

import numpy as np

from stripcoef.conventions import DOF as DOFS
from validation import ROOT, markdown_table

LEVELS = ROOT / "reference_tables" / "bem" / "graded_frames.csv"
PANELS_VEHICLES = ROOT / "reference_tables" / "bem" / "panels_vehicles.csv"
GOLDEN = ROOT / "tests" / "golden" / "bluerov2_heavy.json"
#: the surface's name in graded_frames.csv
NAME = "bluerov2_heavy_file"
#: the accuracy criterion of issue 32 [-]
WITHIN = 0.05


def frame_terms(levels_csv=LEVELS, stored_csv=PANELS_VEHICLES, golden=GOLDEN) -> dict:
    """The comparison: ``{"faces", "point", "levels": [(faces, diagonal (6,))], "rows"}``; each
    row a dict with install, i, j, model, graded (the reference about the model's point),
    band and error (relative), order, estimated (the stored estimate, relative), covered and
    uniform (the stored uniform Capytaine reference against the graded one; NaN for
    couplings).  Empty without the stored levels."""
    from stripcoef.conventions import transform_matrix
    from validation.graded_bodies import read, references
    from validation.public_meshes import moved_uncertainty

    refs = references(levels_csv) if levels_csv.exists() else {}
    if NAME not in refs:
        return {}
    ref, band, order, faces = refs[NAME]
    gold = json.loads(golden.read_text())
    point = np.asarray(gold["reference_point"], float)
    ref_p = transform_matrix(ref, from_point=(0, 0, 0), to_point=point)
    band_p = moved_uncertainty(band, point)
    d = np.sqrt(np.abs(np.diag(ref_p)))
    _, counts, mats = read(levels_csv)[NAME]
    levels = [(n, np.diag(transform_matrix(m, from_point=(0, 0, 0), to_point=point)))
              for n, m in zip(counts, mats)]
    with open(stored_csv, newline="") as fh:
        stored = [r for r in csv.DictReader(ln for ln in fh if not ln.startswith("#"))
                  if r["file"].endswith("bluerov2_heavy.yaml")]
    rows = []
    for r in stored:
        i = DOFS.index(r["dof"])
        g = ref_p[i, i]
        rows.append(dict(install=r["install"], i=i, j=i, model=float(r["estimate"]), graded=g,
                         band=band_p[i, i] / g, order=order[i, i],
                         error=float(r["estimate"]) / g - 1.0,
                         estimated=float(r["estimated_error_rel"]),
                         uniform=float(r["bem"]) / g - 1.0))
    a = np.asarray(gold["added_mass"], float)
    e = np.asarray(gold["added_mass_error"], float)
    for i in range(6):
        for j in range(i + 1, 6):
            s = d[i] * d[j]
            if a[i, j] == 0.0 and abs(ref_p[i, j]) < 1e-9 * s:
                continue                      # a coupling the mirror plane forbids in both
            rows.append(dict(install="base (golden)", i=i, j=j, model=a[i, j],
                             graded=ref_p[i, j], band=band_p[i, j] / s, order=order[i, j],
                             error=(a[i, j] - ref_p[i, j]) / s, estimated=e[i, j] / s,
                             uniform=float("nan")))
    for row in rows:
        row["covered"] = abs(row["error"]) <= row["estimated"]
    return dict(faces=list(faces), point=point, levels=levels, rows=rows)


def term_name(row) -> str:
    """'surge' for a diagonal row, 'surge-heave' for a coupling."""
    i, j = row["i"], row["j"]
    return DOFS[i] if i == j else f"{DOFS[i]}-{DOFS[j]}"


def section(levels_csv=LEVELS) -> str:
    """The section: the paragraph and table of :func:`frame_terms` ('' without the levels)."""
    t = frame_terms(levels_csv)
    if not t:
        return ""
    rows = t["rows"]
    table = [[r["install"], term_name(r), f"{r['model']:.6g}", f"{r['graded']:.6g}",
              f"{100 * r['band']:.2f} %", f"{r['order']:.2f}", f"{100 * r['error']:+.1f} %",
              f"{100 * r['estimated']:.1f} %", "yes" if r["covered"] else "no",
              "" if np.isnan(r["uniform"]) else f"{100 * r['uniform']:+.2f} %"] for r in rows]
    diag = [r for r in rows if r["i"] == r["j"]]
    worst = {}
    for r in diag:
        w = worst.get(r["install"])
        if w is None or abs(r["error"]) > abs(w["error"]):
            worst[r["install"]] = r
    text = [
        "## The BlueROV2 Heavy against its graded reference (issue 32)",
        "",
        "The vehicle file's surface (geometry/bluerov2_heavy.stl) meshed by the graded mesher on "
        f"{'/'.join(map(str, t['faces']))} faces (its y >= 0 half solved on the xOz mirror "
        "plane, `cpt.ReflectionSymmetricMesh`; the symmetric solve equals the full one on the "
        "same panels: tests/test_frame_references.py), Eça & Hoekstra's least squares over the "
        "levels, moved to the golden model's reference point "
        f"{np.round(t['point'], 5).tolist()} m. Levels: `python -m benchmarks.frame_references "
        "--csv reference_tables/bem/graded_frames.csv --levels ...` "
        "(reference_tables/bem/README.md); the stored model rows: "
        "reference_tables/bem/panels_vehicles.csv and tests/golden/bluerov2_heavy.json.",
        "",
        f"Diagonal terms within {100 * WITHIN:.0f} % of the graded reference: "
        + "; ".join(f"{inst} {sum(abs(r['error']) <= WITHIN for r in diag if r['install'] == inst)}"
                    f"/{sum(r['install'] == inst for r in diag)} (worst {term_name(w)} "
                    f"{100 * w['error']:+.1f} %)" for inst, w in worst.items())
        + f"; every term's estimate covers its error: {sum(r['covered'] for r in rows)}/"
        f"{len(rows)}. The stored uniform Capytaine reference lies within "
        f"{100 * max(abs(r['uniform']) for r in diag):.1f} % of the graded one: the errors are "
        "the panel method's on 12.7 mm plates and 40 mm tubes, not the reference's.",
        "",
        markdown_table(["install", "term", "model", "graded reference", "its band", "order",
                        "model error", "estimated error", "covered",
                        "stored uniform reference's error"], table),
    ]
    return "\n".join(text) + "\n"

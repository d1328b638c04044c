"""Validation section: bluff shapes (boxes, short cylinders, ellipsoids, open frames) against
converged Capytaine references and Lamb's exact ellipsoids (issue 14).

The references are data (reference_tables/bem/bem_bluff.csv, written by
``python -m benchmarks.bluff_shapes --reference``); the accuracy tables are the stored output
of the benchmark (benchmarks/data/bluff_accuracy_<mode>.md, written by
``python -m benchmarks.bluff_shapes [--per-dof-axes | --method panels --bem-timing] --write``),
so that this report does not rerun the 24 shapes.
"""

from __future__ import annotations

import csv

import numpy as np

from validation import ROOT, markdown_table

DATA = ROOT / "benchmarks" / "data"
#: the stored Capytaine references (reference_tables/bem/README.md)
BEM = ROOT / "reference_tables" / "bem"
DOF = ("X_udot", "Y_vdot", "Z_wdot", "K_pdot", "M_qdot", "N_rdot")


def _convergence_rows():
    """Per shape: faces of the two resolutions and the largest change of a diagonal term from
    the finer run to the Richardson value, relative to that term (an error estimate)."""
    lines = [ln for ln in open(BEM / "bem_bluff.csv") if not ln.startswith("#")]
    by = {}
    for r in csv.DictReader(lines):
        if r["i"] == r["j"]:
            by.setdefault(r["shape"], []).append(r)
    rows = []
    for shape, rs in by.items():
        a2 = np.array([float(r["a_2"]) for r in rs])
        ri = np.array([float(r["richardson"]) for r in rs])
        on = np.abs(ri) > 1e-4 * np.abs(ri).max()
        change = np.max(np.abs(a2[on] - ri[on]) / np.abs(ri[on]))
        rows.append([shape, f"{rs[0]['faces_1']} / {rs[0]['faces_2']}", f"{100 * change:.2f} %"])
    return rows


def _graded_boxes() -> str:
    """The references of the shapes with edge-graded Capytaine levels (the boxes, the
    chamfered box, the unions of prisms), and how far the stored two-level Richardson lies
    from them on the diagonal (a sentence; empty without the files)."""
    from validation.graded_bodies import bluff_sources

    graded = bluff_sources()
    if not graded:
        return ""
    lines = [ln for ln in open(BEM / "bem_bluff.csv") if not ln.startswith("#")]
    rich: dict = {}
    for r in csv.DictReader(lines):
        if r["i"] == r["j"] and r["shape"] in graded:
            rich.setdefault(r["shape"], {})[int(r["i"])] = float(r["richardson"])
    dev = [(abs(rich[k][i] / ref[i, i] - 1), k, i) for k, (ref, _, _) in graded.items()
           for i in range(6)]
    bands = [band[i, i] / ref[i, i] for ref, band, _ in graded.values() for i in range(6)]
    files = sorted({p.split("/")[-1] for _, _, p in graded.values()})
    worst = max(dev)
    return (f"The references of {', '.join(sorted(graded))} are Capytaine on panels graded "
            "towards every sharp edge (" + ", ".join(f"`reference_tables/bem/{f}`" for f in files)
            + "; `python -m benchmarks.graded_references boxes`, `bluff` and `unions`: four or "
            "five levels, Eça & Hoekstra's least squares, which assume no order; diagonal bands "
            f"{100 * min(bands):.2f} to {100 * max(bands):.2f} %): the two-level Richardson "
            f"above assumes order 2 at the edges and lies up to {100 * worst[0]:.1f} % from "
            f"them ({worst[1]} {DOF[worst[2]]}; within 1 % on "
            f"{sum(d <= 0.01 for d, _, _ in dev)} of {len(dev)} diagonal terms; per term: "
            "`benchmarks/data/graded_bias.md`). The accuracy tables below take the graded "
            "matrices (`benchmarks.bluff_shapes.reference_matrix`).\n")


def section() -> str:
    parts = ["## Bluff shapes: boxes, short cylinders, ellipsoids, open frames (issue 14)\n",
             "Eighteen shapes of `benchmarks/bluff_shapes.py` (body axes FRD, about the volume "
             "centroid, rho = 1000 kg/m^3). Reference: Capytaine 3.0.0, direct method, no free "
             "surface, two resolutions of at most 5000 faces and their Richardson extrapolation "
             "(`reference_tables/bem/bem_bluff.csv`); the ellipsoids' diagonals against Lamb's exact "
             "values (`stripcoef.hull.lamb.ellipsoid_added_mass`, which the stored BEM matches "
             "within 0.5 %, tests/test_bluff_shapes.py). Reference convergence (largest change of "
             "a diagonal term from the finer run to the extrapolation):\n",
             markdown_table(["shape", "faces", "finer run to Richardson"], _convergence_rows()),
             "\n" + _graded_boxes(),
             "The BEM meshes of `open_frame` (50 % of the area) and `bluerov2_heavy` (3 %) "
             "have panels of aspect ratio above 20 (thin tubes at <= 5000 faces; "
             "`stripcoef.bem.panel_quality`): their references are less certain than the "
             "convergence column says. The cylinders were first meshed with trimesh's end-cap "
             "fans (sliver panels, aspect up to 36): that reference put the short cylinder's "
             "pitch 12 % above the axisymmetric solution of the same body (0.04343 kg m^2, "
             "converged to 0.05 % at 640 meridian panels); with rings on the ends (aspect <= 12) "
             "the Richardson value is 0.04459, still converging slowly at the sharp edges "
             "(0.04630, 0.04539 at 2100, 4464 faces).\n"]
    parts.append("The 3D panel method (`stripcoef.hull.panels`, `estimate(added_mass_method="
                 "\"panels\")`, `--added-mass-method panels`; docs/theory.md \"3D panel "
                 "method\") solves the same potential-flow problem as the reference for any "
                 "closed mesh; the default, `auto`, takes the panels for "
                 "a mesh that is neither round at mid-length nor slender. The last columns "
                 "time Capytaine at the resolution whose error equals the panel method's worst "
                 "diagonal (from its stored first-level error and the 1/N law), in the same "
                 "run.\n")
    for mode in ("panels", "default", "per_dof_axes", "no_corrections"):
        acc = DATA / f"bluff_accuracy_{mode}.md"
        if acc.exists():
            parts.append(acc.read_text())
    return "\n".join(parts)

"""Edge-graded Capytaine references of bodies with edges (issue 32): the readers shared by the
benchmarks and tests.

``benchmarks.graded_references`` writes the levels (Capytaine on structured quadrilaterals
graded towards every edge, four or five levels per body): ``reference_tables/bem/
graded_boxes.csv`` (the boxes of ``benchmarks.bluff_shapes``), ``graded_bluff.csv`` (its
chamfered box), ``graded_unions.csv`` (its unions of prisms along x: the box with skids, the
L-shaped block, the box with a pod, the cylinder with a float, the twin hull; graded towards
their sharp edges only, not the facet joints of their 24-sided cylinders) and
``graded_extrusions.csv`` (the extruded polygons of ``benchmarks.cad_shapes``' seed
1375923287); ``benchmarks.graded_mesher`` writes ``graded_meshes.csv`` (the VideoRay-like body
of the bluff set, gmsh triangles graded towards its convex edges).  Each term's reference
is Eça & Hoekstra's least squares over the levels (:func:`validation.cad_shapes.fine_reference`,
h ~ N^(-1/2)): it assumes no order of convergence.
"""

from __future__ import annotations

import csv

import numpy as np

from validation import ROOT

BOXES = ROOT / "reference_tables" / "bem" / "graded_boxes.csv"
EXTRUSIONS = ROOT / "reference_tables" / "bem" / "graded_extrusions.csv"
#: the bluff set's prisms (``benchmarks.graded_references bluff``)
BLUFF = ROOT / "reference_tables" / "bem" / "graded_bluff.csv"
#: the bluff set's unions of prisms along x (``benchmarks.graded_references unions``)
UNIONS = ROOT / "reference_tables" / "bem" / "graded_unions.csv"
#: the bluff set's shapes remeshed by gmsh towards their convex edges (``benchmarks.
#: graded_mesher``: the VideoRay-like body)
MESHES = ROOT / "reference_tables" / "bem" / "graded_meshes.csv"
#: every graded file of the bluff set's shapes, about their volume centroid
BLUFF_FILES = (BOXES, BLUFF, UNIONS, MESHES)


def read(path) -> dict:
    """{shape: (what, faces per level, [6x6 per level] [kg, kg m, kg m^2])} of a graded
    references CSV (``benchmarks.graded_references``: one row per level and upper-triangle
    term), levels coarse to fine; shape: a name, or the CAD benchmark's index as an int."""
    out: dict = {}
    with open(path, newline="") as fh:
        fh.readline()
        for r in csv.DictReader(fh):
            key = int(r["shape"]) if r["shape"].isdigit() else r["shape"]
            what, lv = out.setdefault(key, (r["what"], {}))
            n, a = lv.setdefault(int(r["level"]), (int(r["faces"]), np.zeros((6, 6))))
            i, j = int(r["i"]), int(r["j"])
            a[i, j] = a[j, i] = float(r["added_mass"])
    return {k: (what, [lv[x][0] for x in sorted(lv)], [lv[x][1] for x in sorted(lv)])
            for k, (what, lv) in out.items()}


def references(path) -> dict:
    """{shape: (reference 6x6, band 6x6, order 6x6, faces)}: Eça & Hoekstra over each shape's
    levels (:func:`validation.cad_shapes.fine_reference`), shapes with fewer than its four
    levels left out."""
    from stripcoef.hull.convergence import EH_MIN_LEVELS
    from validation.cad_shapes import fine_reference

    return {k: (*fine_reference(n, mats), n) for k, (_, n, mats) in read(path).items()
            if len(n) >= EH_MIN_LEVELS}


def box_references(path=BOXES) -> dict:
    """{box name: (diagonal reference (6,), its band (6,))} of the bluff set's graded boxes
    [kg, kg m^2] (empty without the file)."""
    if not path.exists():
        return {}
    return {k: (np.diag(ref).copy(), np.diag(band).copy())
            for k, (ref, band, _, _) in references(path).items()}


def bluff_references(paths=BLUFF_FILES) -> dict:
    """{shape: (reference 6x6, band 6x6) [kg, kg m, kg m^2]} of every shape of the bluff set
    with graded levels (the boxes, the prism, the unions), about its volume centroid; files
    that do not exist are skipped."""
    return {k: (ref, band) for k, (ref, band, _) in bluff_sources(paths).items()}


def bluff_sources(paths=BLUFF_FILES) -> dict:
    """{shape: (reference 6x6, band 6x6, the file's path relative to the repository)} of
    :func:`bluff_references`."""
    out: dict = {}
    for path in paths:
        if path.exists():
            rel = path.relative_to(ROOT).as_posix()
            out.update({k: (ref, band, rel) for k, (ref, band, _, _) in references(path).items()})
    return out

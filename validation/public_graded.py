"""docs/validation.md: the public meshes' stored model rows against the edge-graded
Capytaine references of the six ROVs with sharp edges (issue 32), the section after
:mod:`validation.public_meshes`'s.

Reads ``reference_tables/public_meshes/graded_levels.csv`` (``benchmarks.graded_mesher
--public``: four or five levels per mesh, about the body origin of the loaded mesh, its
header says so; each term's reference the least squares of Eça & Hoekstra 2014 over the
levels, :func:`validation.graded_bodies.references`) and the stored model rows of
``reference_tables/public_meshes/public_meshes.csv`` (run ``auto``, about each run's own
reference point, its ``ref_x, ref_y, ref_z``).
"""

from __future__ import annotations

import numpy as np

from stripcoef.conventions import DOF as DOFS
from validation import ROOT, markdown_table, read_stored_run

GRADED = ROOT / "reference_tables" / "public_meshes" / "graded_levels.csv"
#: the stored run compared: the command as a user runs it
RUN = "auto"
#: the accuracy criterion of issue 32 [-]
WITHIN = 0.05


def moved_reference(ref, band, point):
    r"""A reference ``ref`` (6x6 added mass about the body origin O [kg, kg m, kg m^2]) and its
    band ``band`` (same units) about ``point`` P [m, body axes]: the rigid transfer
    :math:`A_P = H(-r)^T A_O H(-r)`, r = P - O (Fossen 2011, sec. 7.5.3; the library's
    :func:`stripcoef.conventions.transform_matrix`), the band bounded term by term for fully
    correlated errors (:func:`validation.public_meshes.moved_uncertainty`, JCGM 100:2008 sec.
    5.2.2)."""
    from stripcoef.conventions import transform_matrix
    from validation.public_meshes import moved_uncertainty

    return (transform_matrix(ref, from_point=(0.0, 0.0, 0.0), to_point=point),
            moved_uncertainty(band, point))


def term_scale(ref) -> np.ndarray:
    r"""The 6x6 scale :math:`\sqrt{|A_{ii}| |A_{jj}|}` of a reference's terms (a diagonal term
    relative to itself, a coupling to the geometric mean of its diagonal terms), each block's
    diagonal floored at NEGLIGIBLE of its largest as the stored rows are
    (:func:`benchmarks.public_meshes.compare_at`) [kg, kg m, kg m^2]."""
    from stripcoef.hull.panels import NEGLIGIBLE

    dg = np.abs(np.diag(np.asarray(ref, float))).copy()
    for block in (slice(0, 3), slice(3, 6)):
        dg[block] = np.maximum(dg[block], NEGLIGIBLE * dg[block].max())
    return np.sqrt(np.outer(dg, dg))


def _fitted_point(ref_o, uniform_p):
    """The point [m] about which the graded reference ``ref_o`` (about O) best matches the
    stored uniform reference (least squares over the 36 terms relative to their scale): a
    check that both references are about the same point, to the references' difference."""
    from scipy.optimize import least_squares

    from stripcoef.conventions import transform_matrix

    s = term_scale(uniform_p)
    return least_squares(lambda p: ((transform_matrix(ref_o, to_point=p) - uniform_p)
                                    / s).ravel(), np.zeros(3)).x


def graded_terms(levels_path=GRADED, data_path=None, run=RUN) -> list[dict]:
    """Per mesh of ``levels_path`` with a stored run ``run`` (``data_path``: public_meshes.csv)
    and per diagonal term and coupling that the stored rows mark significant: the model, the
    uniform reference and the graded one at the run's point, the errors [-] of the model
    against each (against the graded one: relative to :func:`term_scale` of the graded
    reference at the point), the graded band there, the model's estimated error (the stored
    ``estimated_error_rel`` times the stored rows' scale, made relative to the graded scale)
    and whether it covers the error against the graded reference, alone and root-sum-squared
    with the graded band (ASME V&V 20-2009).  Each row also carries the point, the largest
    change of a term the move to the point makes (``moved``, of the scale) and the distance
    [m] from the point to :func:`_fitted_point`."""
    from validation.graded_bodies import references
    from validation.public_meshes import DATA, POINT_COLUMNS

    data_path = DATA if data_path is None else data_path
    if not levels_path.exists() or not data_path.exists():
        return []
    _, rows = read_stored_run(data_path)
    out = []
    for mesh, (ref, band, order, faces) in references(levels_path).items():
        terms = [r for r in rows if r["mesh"] == mesh and r["run"] == run]
        if not terms:
            continue
        point = np.array([float(terms[0][c]) for c in POINT_COLUMNS])
        model, uniform, est_rel = np.zeros((6, 6)), np.zeros((6, 6)), np.zeros((6, 6))
        for r in terms:
            i, j = int(r["i"]), int(r["j"])
            for m, k in ((model, "model"), (uniform, "bem"), (est_rel, "estimated_error_rel")):
                m[i, j] = m[j, i] = float(r[k])
        ref_p, band_p = moved_reference(ref, band, point)
        s = term_scale(ref_p)
        est = est_rel * term_scale(uniform)            # [kg, kg m, kg m^2]
        moved = float(np.max(np.abs(ref_p - ref) / s))
        fit = float(np.linalg.norm(_fitted_point(ref, uniform) - point))
        for r in terms:
            i, j = int(r["i"]), int(r["j"])
            if i != j and r["significant"] != "1":
                continue
            e = model[i, j] - ref_p[i, j]
            out.append(dict(mesh=mesh, i=i, j=j, faces=faces, point=point, moved=moved, fit=fit,
                            model=model[i, j], uniform=uniform[i, j], graded=ref_p[i, j],
                            order=float(order[i, j]), band=band_p[i, j] / s[i, j],
                            error_uniform=float(r["error_rel"]), error_graded=e / s[i, j],
                            est=est[i, j] / s[i, j], covered=bool(abs(e) <= est[i, j]),
                            covered_vv=bool(abs(e) <= np.hypot(est[i, j], band_p[i, j]))))
    return out


def _worst(ts, key) -> str:
    """The term of ``ts`` of the largest |``key``|, named, in per cent ("-" without terms)."""
    if not ts:
        return "-"
    w = max(ts, key=lambda t: abs(t[key]))
    return f"{_name(w)} {100 * w[key]:+.1f} %"


def _name(t) -> str:
    """A term's name: 'sway' (diagonal), 'sway-yaw' (coupling)."""
    return DOFS[t["i"]] if t["i"] == t["j"] else f"{DOFS[t['i']]}-{DOFS[t['j']]}"


def section(levels_path=GRADED, data_path=None) -> str:
    """The section: the paragraph and table of :func:`graded_terms` ('' without the stored
    levels)."""
    terms = graded_terms(levels_path, data_path)
    if not terms:
        return ""
    by_mesh = {}
    for t in terms:
        by_mesh.setdefault(t["mesh"], []).append(t)
    table = []
    for mesh, ts in by_mesh.items():
        diag = [t for t in ts if t["i"] == t["j"]]
        coup = [t for t in ts if t["i"] != t["j"]]
        table.append([mesh, "/".join(map(str, ts[0]["faces"])),
                      f"{1000 * float(np.linalg.norm(ts[0]['point'])):.1f}",
                      f"{100 * ts[0]['moved']:.2f} %", f"{1000 * ts[0]['fit']:.1f}",
                      _worst(diag, "error_uniform"), _worst(diag, "error_graded"),
                      _worst(coup, "error_uniform"), _worst(coup, "error_graded"),
                      f"{sum(abs(t['error_uniform']) <= WITHIN for t in ts)}/{len(ts)}",
                      f"{sum(abs(t['error_graded']) <= WITHIN for t in ts)}/{len(ts)}",
                      f"{100 * min(t['band'] for t in ts):.1f}-"
                      f"{100 * max(t['band'] for t in ts):.1f} %",
                      f"{sum(t['covered'] for t in ts)}/{len(ts)} "
                      f"({sum(t['covered_vv'] for t in ts)})"])
    diag = [t for t in terms if t["i"] == t["j"]]
    coup = [t for t in terms if t["i"] != t["j"]]

    def within(ts, key):
        return sum(abs(t[key]) <= WITHIN for t in ts)

    tight = [t for t in terms if t["band"] <= WITHIN]
    return "\n".join([
        "## Public vehicle meshes against edge-graded references (issue 32)\n",
        f"The stored model rows of the section above (run `{RUN}`) against the edge-graded Capytaine references "
        "of the six ROVs with sharp edges (reference_tables/public_meshes/graded_levels.csv, "
        "`benchmarks.graded_mesher --public`: gmsh triangles graded towards the convex edges, "
        "smilodon's structured box panels, four or five levels each, independent of the "
        "library's remesh that the uniform references share with the model; each term the "
        "least squares of Eça & Hoekstra 2014 over the levels, "
        "`validation.graded_bodies.references`, its band the uncertainty U of the finest "
        "level). The levels are about the body origin of the loaded mesh (the file's header); "
        "each run's rows are about its reference point P (`ref_x, ref_y, ref_z`), so the "
        "graded reference is moved to P by the library's rigid transfer "
        "`stripcoef.conventions.transform_matrix` (Fossen 2011, sec. 7.5.3) and its band with "
        "`validation.public_meshes.moved_uncertainty` (`P from O`: P's distance from the origin; "
        "`moved`: the largest change of a term that move makes, of the term's scale; "
        "`fitted P`: the distance from P to the point about which the graded reference best "
        "matches the uniform one, least squares over the 36 terms, a check that both are "
        "about the same point to within the references' own difference). Against the graded "
        "reference a diagonal term relative to itself, a coupling (those the stored rows mark "
        "significant) to sqrt(A_ii A_jj) of the graded reference at P; against the uniform "
        "one the stored `error_rel`, of the uniform reference's scale. "
        f"Against the graded references: diagonal terms within 5 %: "
        f"{within(diag, 'error_graded')} of {len(diag)} (against the uniform ones "
        f"{within(diag, 'error_uniform')}); couplings within 5 % of their scale: "
        f"{within(coup, 'error_graded')} of {len(coup)} ({within(coup, 'error_uniform')}); "
        f"the graded band is {100 * min(t['band'] for t in terms):.1f}-"
        f"{100 * max(t['band'] for t in terms):.1f} % of the scale, within 5 % on "
        f"{len(tight)} of the {len(terms)} terms ({within(tight, 'error_graded')} of them "
        f"within 5 %). The model's estimated error (the stored `estimated_error_rel`) covers "
        f"its error against the graded reference in {sum(t['covered'] for t in terms)} of "
        f"{len(terms)} terms"
        + (" (not: " + "; ".join(
            f"{t['mesh']} {_name(t)} {100 * t['error_graded']:+.2f} % against an estimate of "
            f"{100 * t['est']:.2f} %, band {100 * t['band']:.2f} %"
            for t in terms if not t["covered"]) + ")" if not all(t["covered"] for t in terms)
           else "")
        + "; root-sum-squared with the graded band (ASME V&V 20-2009) in "
        f"{sum(t['covered_vv'] for t in terms)}.\n",
        markdown_table(["mesh", "graded faces", "P from O [mm]", "moved", "fitted P [mm]",
                        "worst diagonal vs uniform", "worst diagonal vs graded",
                        "worst coupling vs uniform", "worst coupling vs graded",
                        "within 5 % of uniform", "within 5 % of graded", "graded band",
                        "estimate covers (with band)"], table)])

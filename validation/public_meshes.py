"""docs/validation.md: public vehicle meshes, as a user runs them, against Capytaine (issue 32).

Reads the stored run of ``benchmarks/public_meshes.py``
(``reference_tables/public_meshes/public_meshes.csv``: its command on the first line, then one
row per term of each mesh and run, with the mesh's repository, commit, path and license).
"""

from __future__ import annotations

from stripcoef.conventions import DOF as DOFS
from validation import ROOT, markdown_table, read_stored_run

DATA = ROOT / "reference_tables" / "public_meshes" / "public_meshes.csv"
#: The Capytaine levels of the references (``--levels-csv``), four per mesh where stored.
LEVELS = ROOT / "reference_tables" / "public_meshes" / "bem_levels.csv"
#: The note of a COLLADA mesh's rows (benchmarks/public_meshes.py).
DAE = "read .dae directly"


def section() -> str:
    if not DATA.exists():
        return ""
    command, rows = read_stored_run(DATA)
    runs, refused, repaired = {}, {}, {}
    for r in rows:
        if r["run"] == "refused":
            refused[r["mesh"]] = (r["vehicle"], r["note"])
            continue
        runs.setdefault((r["mesh"], r["run"]), []).append(r)
    table = []
    n_diag = ok_diag = n_coup = ok_coup = n_sig = cov = cov_vv = 0
    n_all = settled = settled_ok = loose_ok = 0   # terms, those of a reference band <= 5 %
    for (mesh, run), terms in runs.items():
        head = terms[0]
        diag = [t for t in terms if t["i"] == t["j"]]
        coup = [t for t in terms if t["i"] != t["j"] and t["significant"] == "1"]
        sig = diag + coup
        wd = max(diag, key=lambda t: abs(float(t["error_rel"])))
        wc = max(coup, key=lambda t: abs(float(t["error_rel"]))) if coup else None
        est_max = max(float(t["estimated_error_rel"]) for t in sig)
        bem_max = max(float(t["bem_error_rel"]) for t in sig)
        n_diag += len(diag)
        ok_diag += sum(abs(float(t["error_rel"])) <= 0.05 for t in diag)
        n_coup += len(coup)
        ok_coup += sum(abs(float(t["error_rel"])) <= 0.05 for t in coup)
        n_all += len(sig)
        tight = [t for t in sig if float(t["bem_error_rel"]) <= 0.05]
        settled += len(tight)
        settled_ok += sum(abs(float(t["error_rel"])) <= 0.05 for t in tight)
        loose_ok += sum(abs(float(t["error_rel"])) <= 0.05 for t in sig
                        if float(t["bem_error_rel"]) > 0.05)
        c = sum(t["covered"] == "1" for t in sig)
        cv = sum(t["covered_with_bem_error"] == "1" for t in sig)
        if head["method"] == "panels":        # a strip-theory run has no estimated error
            n_sig += len(sig)
            cov += c
            cov_vv += cv
        if head["note"].startswith("stripcoef mesh"):
            repaired[mesh] = (head["vehicle"], head["note"])
        table.append([head["vehicle"], head["kind"], run + (" (.dae read directly)"
                                                          if head["note"] == DAE else ""),
                      head["method"], head["panel_levels"] or "-",
                      f"{DOFS[int(wd['i'])]} {100 * float(wd['error_rel']):+.1f} %",
                      (f"{DOFS[int(wc['i'])]}-{DOFS[int(wc['j'])]} "
                       f"{100 * float(wc['error_rel']):+.1f} %") if wc else "-",
                      f"{100 * est_max:.1f} %", f"{100 * bem_max:.1f} %",
                      "yes" if head["warned"] == "1" else "no",
                      f"{c}/{len(sig)} ({cv})", head["bem_faces"],
                      f"{float(head['seconds']):.1f}"])
    sources = {}
    for r in rows:
        sources[r["mesh"]] = (r["vehicle"], r["repo"], r["commit"][:10], r["path"], r["license"],
                              r["role"])
    parts = ["## Public vehicle meshes, as found (issue 32)\n",
             "`benchmarks/public_meshes.py` runs the ROV, AUV and glider meshes that open-source "
             "simulators and ROS description packages publish (repository, commit, path and "
             "license below and in reference_tables/public_meshes/README.md) as a user would: "
             "`stripcoef coefficients MESH --rho 1000 --json` (`auto`; a COLLADA file read "
             "directly, its declared unit and up axis honoured; a mesh refused as found "
             "repaired by the command its one-line error names, `stripcoef mesh MESH --repair "
             "-o OUT`, and OUT run: `repaired`; where a warning names another axis, `use --axis y` "
             "(the body longer across body x than along it), run again so: `auto, --axis y`, "
             "against the same reference turned into those axes), and with "
             "`--added-mass-method panels` where `auto` chose the strips, against Capytaine (direct method, no free "
             "surface) on isotropic remeshes of the closed surface the panel method solves, "
             "three resolutions, the two finest Richardson-extrapolated, moved to the run's "
             "reference point. The stored run:\n",
             f"    {command}\n",
             f"{len(runs)} runs of {len(sources) - len(refused)} meshes"
             + (f" ({len(refused)} more refused as found, below)" if refused else "")
             + f": diagonal terms within 5 %: {ok_diag} "
             f"of {n_diag}; couplings (reference at least 1 % of sqrt(A_ii A_jj)) within 5 % of "
             f"that scale: {ok_coup} of {n_coup}. In the panel-method runs the model's estimated "
             f"error covers the actual error in {cov} of {n_sig} terms; the root-sum-square of the model's and the "
             f"reference's estimated errors (ASME V&V 20-2009) in {cov_vv}; `BEM est. max`: the "
             f"reference's own largest estimated error (its grid convergence index and "
             f"Richardson step, of the same scale). The reference settles the 5 % criterion "
             f"only where its own band is within 5 %: {settled} of the {n_all} terms (diagonal "
             f"and significant couplings), {settled_ok} of them within 5 %; on the other "
             f"{n_all - settled} ({loose_ok} within 5 % of the reference's value) the "
             f"reference is not converged to 5 % (reference_tables/public_meshes/README.md "
             f"says why). A strip-theory run "
             "has no estimated error (zero in the table): its method band is the measured one "
             "of docs/validation.md, method-uncertainty table.\n",
             markdown_table(["vehicle", "kind", "run", "method", "panel levels",
                             "worst diagonal", "worst coupling (of scale)", "est. max",
                             "BEM est. max", "warned", "estimate covers (with BEM's)", "BEM faces",
                             "whole command [s]"], table),
             "",
             markdown_table(["mesh", "vehicle", "repository", "commit", "path", "license",
                             "role"], [[k, *v] for k, v in sources.items()])]
    if repaired:
        parts.append("\nRefused as found and repaired by the command the error names (one "
                     "line, exit 2: 'mesh is not watertight: N open or non-manifold edges (k of "
                     "n parts open) after hole filling; expected a closed surface: stripcoef "
                     "mesh MESH --repair -o OUT ...'): "
                     + "; ".join(f"{v} ({k}): `{why}`" for k, (v, why) in repaired.items()))
    if refused:
        parts.append("\nRefused as found (one-line error, exit 2; no reference computed): "
                     + "; ".join(f"{v} ({k}): {why.split(': error: ')[-1]}"
                                 for k, (v, why) in refused.items()))
    parts.append(_converged_part())
    return "\n".join(p for p in parts if p) + "\n"


def _order_range(orders) -> str:
    """'min-max' of the observed orders that exist (a term with no observed order: nan)."""
    seen = sorted(o for o in orders if o == o)
    return f"{seen[0]:.2f}-{seen[-1]:.2f}" if seen else "-"


def _converged_part() -> str:
    """The paragraph and table of :func:`converged_terms` ('' without stored levels)."""
    terms = converged_terms()
    if not terms:
        return ""
    by_run = {}
    for t in terms:
        by_run.setdefault((t["mesh"], t["run"]), []).append(t)
    table = []
    for (mesh, run), ts in by_run.items():
        w_bem = max(ts, key=lambda t: abs(t["error_bem"]))
        w_eh = max(ts, key=lambda t: abs(t["error_eh"]))
        table.append([mesh, run, "/".join(map(str, ts[0]["faces"])),
                      f"{w_bem['dof']} {100 * w_bem['error_bem']:+.1f} %",
                      f"{100 * max(t['band'] for t in ts):.1f} %",
                      f"{w_eh['dof']} {100 * w_eh['error_eh']:+.1f} %",
                      f"{100 * max(t['u'] for t in ts):.1f} %",
                      _order_range([t["order"] for t in ts]),
                      f"{sum(abs(t['error_eh']) <= 0.05 for t in ts)}/{len(ts)}",
                      f"{sum(abs(t['error_eh']) <= 0.05 and t['u'] <= 0.05 for t in ts)}"])
    n = len(terms)
    tight = [t for t in terms if t["u"] <= 0.05]
    return "\n".join([
        "\nThe references extrapolated again (reference_tables/public_meshes/bem_levels.csv: "
        "the Capytaine levels of the meshes where four are stored, the two finest those of "
        "the table above's 1/N reference): the least-squares procedure of Eça & Hoekstra (2014) on the four "
        "levels, order fitted (stripcoef.hull.convergence.eca_hoekstra_terms), instead of the "
        "1/N Richardson of the two finest; U its uncertainty of the finest level; runs in "
        "other axes left out, and meshes whose stored levels have another finest pair than "
        f"the reference. Of {n} diagonal terms, "
        f"{sum(abs(t['error_eh']) <= 0.05 for t in terms)} are within 5 % of that "
        f"extrapolation; {len(tight)} have U within 5 %, "
        f"{sum(abs(t['error_eh']) <= 0.05 for t in tight)} of them within 5 %.\n",
        markdown_table(["mesh", "run", "Capytaine faces", "worst diagonal vs 1/N",
                        "1/N band max", "worst diagonal vs E&H", "U max", "observed order",
                        "within 5 % of E&H", "and U <= 5 %"], table)])


def _levels(path=LEVELS) -> dict:
    """``{mesh: (face counts, [6x6 M_A about the body origin per level])}``, coarse to fine."""
    import numpy as np

    if not path.exists():
        return {}
    _, rows = read_stored_run(path)
    out = {}
    for r in rows:
        lv = out.setdefault(r["mesh"], {}).setdefault(int(r["level"]),
                                                      [int(r["faces"]), np.zeros((6, 6))])
        i, j = int(r["i"]), int(r["j"])
        lv[1][i, j] = lv[1][j, i] = float(r["added_mass"])
    return {m: ([d[k][0] for k in sorted(d)], [d[k][1] for k in sorted(d)])
            for m, d in out.items()}


def moved_uncertainty(u, to_point, from_point=(0.0, 0.0, 0.0)):
    r"""The uncertainties ``u`` (6x6, symmetric, [kg, kg m, kg m^2]) of the terms of an added-mass
    matrix about ``from_point``, carried with the matrix to ``to_point`` [m, body axes].

    The rigid transfer :math:`A_P = H^T A_O H`, :math:`H = H(-(P - O))` (Fossen 2011, sec.
    7.5.3; :func:`stripcoef.conventions.transform_matrix`) makes each term about P a linear
    combination of the 21 distinct terms about O, :math:`A_{P,ij} = \sum_{k \le l}
    c^{ij}_{kl} A_{O,kl}`, :math:`c^{ij}_{kl} = H_{ki} H_{lj} + H_{li} H_{kj}` (k < l) and
    :math:`H_{ki} H_{kj}` (k = l).  The terms' errors come from the same panellings and are
    correlated by an unknown amount, so the uncertainty taken is the law of propagation for
    fully correlated inputs (JCGM 100:2008, "Guide to the expression of uncertainty in
    measurement", sec. 5.2.2, r = 1), the bound for any correlation:

    .. math:: U_{P,ij} = \sum_{k \le l} |c^{ij}_{kl}|\, U_{O,kl}
              \quad [\mathrm{kg},\ \mathrm{kg\,m},\ \mathrm{kg\,m^2}]

    (transforming the matrix of U itself, :math:`|H^T U H|`, lets the terms' bands cancel
    one another: no bound)."""
    import numpy as np

    from stripcoef.conventions import transform_matrix

    u = np.asarray(u, float)
    out = np.zeros((6, 6))
    for k in range(6):
        for m in range(k, 6):
            unit = np.zeros((6, 6))
            unit[k, m] = unit[m, k] = 1.0
            out += np.abs(transform_matrix(unit, from_point=from_point,
                                           to_point=to_point)) * abs(u[k, m])
    return out


#: The columns of the stored runs' reference point (benchmarks/public_meshes.py) [m].
POINT_COLUMNS = ("ref_x", "ref_y", "ref_z")


def converged_terms(levels_path=LEVELS, data_path=DATA) -> list[dict]:
    r"""The stored runs' diagonal terms against the Eça & Hoekstra (2014) extrapolation of the
    four Capytaine levels (:func:`stripcoef.hull.convergence.eca_hoekstra_terms`, free order
    fitted) instead of the 1/N Richardson of the two finest.

    The levels are about the body origin; each run's matrices are about its reference point P
    (the run's JSON ``reference_point``: the loaded mesh's centre of buoyancy), stored in the
    CSV's :data:`POINT_COLUMNS`; both the E&H value and its uncertainty U are moved there
    (:func:`stripcoef.conventions.transform_matrix`, :func:`moved_uncertainty`).  ``fit``:
    the largest difference between the levels' 1/N Richardson moved to P and the run's
    stored reference, over the largest term (a check of P, ~1e-6 from the CSV's six digits);
    a CSV without the point columns (a run before they were written): P recovered as the
    point that minimises that difference (least squares over the 36 terms, ``point``
    "fitted").  Runs in other axes (``--axis``) are left out, and meshes whose stored levels
    have another finest pair than the reference's (``bem_faces``).  Per diagonal term: the model, the
    1/N reference and its band (``bem_error_rel``), the E&H value and its uncertainty U (of the
    finest level, Eça & Hoekstra eqs. 18-21, at P), the observed order, the model's error
    against each [-]; errors and U of the term, a term below NEGLIGIBLE of its block's largest
    of that floor (the stored rows' scale, benchmarks/public_meshes.py)."""
    import numpy as np

    from stripcoef.conventions import transform_matrix
    from stripcoef.hull.convergence import eca_hoekstra_terms, richardson
    from stripcoef.hull.panels import NEGLIGIBLE

    levels = _levels(levels_path)
    if not levels or not data_path.exists():
        return []
    _, rows = read_stored_run(data_path)
    runs = {}
    for r in rows:
        if r["run"] == "refused" or "--axis" in r["run"] or r["mesh"] not in levels:
            continue
        faces = [int(n) for n in r.get("bem_faces", "").split("/") if n]
        if faces and faces[-2:] != levels[r["mesh"]][0][-2:]:
            continue                      # another finest pair: not the stored reference
        d = runs.setdefault((r["mesh"], r["run"]), {k: np.zeros((6, 6)) for k in
                                                    ("bem", "model", "bem_error_rel")})
        if all(r.get(c) for c in POINT_COLUMNS):
            d["point"] = np.array([float(r[c]) for c in POINT_COLUMNS])
        i, j = int(r["i"]), int(r["j"])
        for k in ("bem", "model", "bem_error_rel"):
            d[k][i, j] = d[k][j, i] = float(r[k])
    out = []
    for (mesh, run), d in runs.items():
        counts, mats = levels[mesh]
        if len(mats) < 4:
            continue
        ref0 = richardson(mats[-2], mats[-1], counts[-2], counts[-1])
        point, how = d.get("point"), "stored"
        if point is None:
            from scipy.optimize import least_squares

            point, how = least_squares(lambda p: (transform_matrix(ref0, to_point=p)
                                                  - d["bem"]).ravel(), np.zeros(3)).x, "fitted"
        residual = float(np.max(np.abs(transform_matrix(ref0, to_point=point) - d["bem"]))
                         / np.max(np.abs(d["bem"])))
        ext, unc, order, _ = eca_hoekstra_terms(counts, mats)
        ext_p = transform_matrix(ext, to_point=point)
        unc_p = moved_uncertainty(unc, point)
        scale = np.abs(np.diag(d["bem"])).copy()      # the stored rows' scale (NEGLIGIBLE
        for block in (slice(0, 3), slice(3, 6)):     # floor: a body of revolution's roll)
            scale[block] = np.maximum(scale[block], NEGLIGIBLE * scale[block].max())
        for k in range(6):
            out.append(dict(mesh=mesh, run=run, dof=DOFS[k], faces=counts, fit=residual,
                            point=tuple(float(x) for x in point), point_from=how,
                            model=d["model"][k, k], bem=d["bem"][k, k],
                            band=d["bem_error_rel"][k, k], eh=ext_p[k, k],
                            u=unc_p[k, k] / scale[k], u_origin=abs(unc[k, k]) / scale[k],
                            order=float(order[k, k]),
                            error_bem=(d["model"][k, k] - d["bem"][k, k]) / scale[k],
                            error_eh=(d["model"][k, k] - ext_p[k, k]) / scale[k]))
    return out

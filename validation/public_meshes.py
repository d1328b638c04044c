"""docs/validation.md: public vehicle meshes, as a user runs them, against Capytaine (issue 32).

Reads the stored run of ``benchmarks/public_meshes.py``
(``reference_tables/public_meshes/public_meshes.csv``: its command on the first line, then one
row per term of each mesh and run, with the mesh's repository, commit, path and license).
"""

from __future__ import annotations

from stripcoef.conventions import DOF as DOFS
from validation import ROOT, markdown_table, read_stored_run

DATA = ROOT / "reference_tables" / "public_meshes" / "public_meshes.csv"
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
    return "\n".join(parts) + "\n"

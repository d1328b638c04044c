"""Validation section: the model's drag and rotational damping against steady RANS (issue 35).

The references are the stored ``stripcoef cfd --json`` results in reference_tables/cfd (its
README: solver, meshes, commands, cost); the model is the default estimate of the same
surface (:func:`stripcoef.cfd.compare.model_for`: the CFD's water and speed, moments about
the same origin), put beside each DOF by :func:`stripcoef.cfd.compare.with_comparison`, the
code behind ``stripcoef cfd MESH --result FILE --compare``. Nothing runs OpenFOAM here.
"""

from __future__ import annotations

import functools
import json
import warnings

import numpy as np

from validation import ROOT, markdown_table

FOLDER = ROOT / "reference_tables" / "cfd"
#: A mesh spread (two-grid GCI) above this marks a row mesh-limited: its CFD value is not
#: known to better than the model's own band and is left out of the summary.
GCI_LIMIT = 0.25
#: The error band of coarse steady RANS (k-omega SST, wall functions, 10-70k cells) on
#: sharp-edged bluff bodies, from the measured bodies of issue 35's probe and the cube here:
#: an rms |ln(RANS / measured)| of 0.16 on the finer meshes.
RANS_BAND = 0.16
#: Rows damped by skin friction alone, which wall functions at these y+ do not resolve: shown,
#: not a reference, left out of the summary.
FRICTION_ONLY = {("cylinder_ld1.stl", "roll"): "body of revolution about its axis"}


def _vehicle(source: str):
    from stripcoef.geometry.vehicle import MESH_SUFFIXES, load_vehicle

    path = ROOT / source
    if path.suffix.lower() in MESH_SUFFIXES:
        return load_vehicle(path, origin="centroid")
    return load_vehicle(path)


@functools.lru_cache(maxsize=1)
def stored():
    """Every stored result with the model beside it: (file name, CfdResult, HydroModel),
    computed once per process (the section and tests/test_damping_rotation.py read the same
    models; about 5 s of CPU)."""
    from stripcoef.cfd.compare import comparison_speed, model_for, with_comparison
    from stripcoef.cfd.result import CfdResult
    from stripcoef.fluid import Fluid

    out, models = [], {}
    for path in sorted(FOLDER.glob("*.json")):
        res = CfdResult.from_dict(json.loads(path.read_text()))
        water = Fluid(density=res.density, kinematic_viscosity=res.viscosity,
                      source="the CFD's water")
        key = (res.source, comparison_speed(res), res.density, res.viscosity)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            if key not in models:       # one model per body, speed and water
                models[key] = model_for(_vehicle(res.source), speed=key[1], fluid=water)
            out.append((path.name, with_comparison(res, None, fluid=water,
                                                   model=models[key]), models[key]))
    return tuple(out)


def strips_rotation(model, dof: str) -> float:
    """The strips' own quadratic damping of a rotation [kg m^2] (SNAME magnitude): what
    the model had before a bluff body's rotation took the surface integral
    (``conditions.rotational_drag["strips"]``), else the model's own term (a slender body
    keeps the strips)."""
    k = ("roll", "pitch", "yaw").index(dof)
    info = model.conditions.rotational_drag
    if info is not None:
        return float(info["strips"][k])
    return float(model.quadratic_damping[3 + k, 3 + k])


def rows():
    """One row per stored DOF: body, DOF, the CFD's and the model's damping at the CFD's speed."""
    from stripcoef.cfd.result import NAMES

    out = []
    for name, res, model in stored():
        for d, c in zip(res.dofs, res.comparison):
            fine = d.runs[0]
            rotation = d.dof in ("roll", "pitch", "yaw")
            # the strips' moment at the CFD's rate, for the rotation rows (before the rule)
            strips = (c.model_d_linear * c.speed + strips_rotation(model, d.dof) * c.speed ** 2
                      if rotation else c.model_force)
            out.append({"file": name, "body": res.source.split("/")[-1], "dof": d.dof,
                        "term": NAMES[d.dof][1], "rotation": rotation,
                        "strips_ratio": strips / c.cfd_force if c.cfd_force > 0 else float("nan"),
                        "surface": bool(rotation and model.conditions.rotational_drag),
                        "speed": c.speed, "levels": "/".join(str(r.level) for r in
                                                            reversed(d.runs)),
                        "cells": fine.cells, "cfd": c.cfd_force, "model": c.model_force,
                        "cfd_dq": d.d_quadratic, "ratio": c.ratio, "gci": d.gci,
                        "converged": d.converged, "fine_level": fine.level,
                        "y_plus": fine.y_plus,
                        "cpu_min": sum(r.cpu_seconds for r in d.runs) / 60.0})
    # a body's DOF run again on finer levels: the finer pair is the reference
    for r in out:
        finer = [o for o in out if o["body"] == r["body"] and o["dof"] == r["dof"]
                 and o["fine_level"] > r["fine_level"]]
        r["superseded"] = bool(finer)
        r["friction_only"] = (r["body"], r["dof"]) in FRICTION_ONLY
    return out


def summary_rows(rs):
    """The rows a summary counts: converged, within the mesh limit, the finest levels of
    their DOF, not friction-only, with a positive ratio."""
    return [r for r in rs if r["converged"] and r["gci"] is not None and r["gci"] <= GCI_LIMIT
            and not r["superseded"] and not r["friction_only"]
            and np.isfinite(r["ratio"]) and r["ratio"] > 0]


def _summary(rs, label, key="ratio"):
    use = summary_rows(rs)
    if not use:
        return f"- {label}: no row converged within the mesh limit."
    ln = np.log([r[key] for r in use])
    return (f"- {label}: {len(use)} rows (of {len(rs)}), model/CFD from "
            f"{np.exp(ln.min()):.3g} to {np.exp(ln.max()):.3g}, geometric mean "
            f"{np.exp(ln.mean()):.3g}, rms |ln(model/CFD)| {np.sqrt(np.mean(ln ** 2)):.2f} "
            f"(the coarse RANS band itself is about {RANS_BAND})")


def section() -> str:
    rs = rows()
    table = []
    for r in rs:
        unit = "rad/s" if r["rotation"] else "m/s"
        fu = "N m" if r["rotation"] else "N"
        gci = "-" if r["gci"] is None else f"{100 * r['gci']:.1f} %"
        flag = "" if r["converged"] else " NOT CONVERGED"
        if r["gci"] is not None and r["gci"] > GCI_LIMIT:
            flag += " mesh-limited"
        if r["superseded"]:
            flag += " (finer levels below)"
        if r["friction_only"]:
            flag += " friction only: not a reference"
        table.append([r["body"], r["dof"], r["term"], f"{r['speed']:.3g} {unit}", r["levels"],
                      f"{r['cells']:,}", f"{r['cfd']:.4g} {fu}", f"{-r['cfd_dq']:.4g}",
                      gci + flag, f"{r['model']:.4g} {fu}", f"{r['ratio']:.3f}",
                      f"{np.log(r['ratio']):+.2f}" if r["ratio"] > 0 else "-",
                      (f"{r['strips_ratio']:.3f}" + ("" if r["surface"] else " (same rule)"))
                      if r["rotation"] else "-",
                      f"{r['cpu_min']:.1f}"])
    rot = [r for r in rs if r["rotation"]]
    tra = [r for r in rs if not r["rotation"]]
    bodies = sorted({r["body"] for r in rot})
    yp = [r["y_plus"][2] for r in rs if r["y_plus"] is not None]
    return "\n".join([
        "## Drag and rotational damping against CFD (OpenFOAM, steady RANS)",
        "",
        "The default model's damping beside steady RANS of the same surface (issue 35): "
        "`stripcoef cfd MESH --result reference_tables/cfd/FILE.json --compare` prints each "
        "row. The CFD is OpenFOAM v1912's simpleFoam with k-omega SST and wall functions on a "
        "snappyHexMesh mesh (no prism layers), translations by an inflow, rotations by an MRF "
        "zone in a still tank (reference_tables/cfd/README.md: the commands, y+ and cost). "
        "Both sides give the damping force at the CFD's speed, `F = d_L u + d_Q u|u|`, "
        "opposing the motion; the quadratic term is the CFD's whole force over `u^2` "
        "(one speed). GCI: Roache's two-grid index of the finer mesh (refinement ratio 2, "
        "order 2, safety factor 3: the relative change between the two levels); a row above "
        f"{100 * GCI_LIMIT:.0f} % is mesh-limited and left out of the summary.",
        "",
        "Coarse steady RANS is a reference only to about a factor exp(0.16) = 1.17 on "
        "sharp-edged bluff bodies (the measured bodies of issue 35's probe; the cube here is "
        "2.5 % above Hoerner's measured C_D 1.05). The mean y+ of the finer meshes runs "
        f"from {min(yp):.0f} to {max(yp):.0f} (wall functions: about 30 to 300): the skin "
        "friction, which alone damps a body of revolution turning about its axis (the "
        "cylinder's roll), is not resolved, and such a row is not a reference. The damping "
        "of a bluff body turning is pressure drag of its faces and edges, what RANS holds "
        "best.",
        "",
        markdown_table(["body", "DOF", "term", "at", "levels", "cells (fine)",
                        "CFD F (fine)", "CFD d_Q (SNAME)", "GCI", "model F",
                        "model/CFD", "ln", "strips/CFD (rotation, before)", "CPU-min"],
                       table),
        "",
        f"Rotations of {len(bodies)} bodies ({', '.join(bodies)}):",
        "",
        _summary(rot, "rotations"),
        _summary(rot, "rotations, the strips' cross-flow at a lever arm (before)",
                 key="strips_ratio"),
        _summary(tra, "translations"),
        "",
        ROTATION_TEXT,
    ]) + "\n"


ROTATION_TEXT = (
    "Rotation of a bluff body (not slender: L below 5 times its largest breadth or height; "
    "every body here) is the pressure drag of its closed surface's elements moving into the "
    "water (`stripcoef.assembly.damping.rotational_pressure_drag`): an element at r with "
    "outward normal n has the normal velocity `v_n = (omega x r) . n`, takes "
    "`dF = -1/2 rho C(n) v_n^2 n dA` where `v_n > 0` (Morison's drag on the velocity of a "
    "structure moving in still water, DNV-RP-C205 sec. 6.2; the element-wise form of the "
    "simulators Stonefish and MuJoCo), and its moment about the axis integrates exactly on "
    "each triangle; the element coefficients `C(n) = sum_m n_m^2 C_m` are those whose sum in "
    "pure translation gives back the model's own X_uu, Y_vv, Z_ww (measured whole-body drag, "
    "issue 35), so no constant is set from these runs. Before, the strips turned each "
    "section's cross-flow drag at its lever arm into the pitch and yaw damping: the faces "
    "away from the axis, which a turning body pushes along its length, had no pressure drag "
    "(a box about its long axis: none at all). A slender body keeps the strips. What the "
    "surface integral still misses: a cube and a flat box in yaw at 0.28-0.33 of the CFD "
    "(each face's moment taken from its own normal velocity alone, 0 at its centre line, "
    "where the separated flow round a turning box's corners loads the whole face), a short "
    "round cylinder in yaw at 0.15 (the curved wall's normal velocity is small; its "
    "separated cross-flow is not). `python -m benchmarks.cfd_rotation --rotational` prints "
    "the per-shape table.")

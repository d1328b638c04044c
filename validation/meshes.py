"""Validation section: 2D panel method, axisymmetric 3D corrections, mesh consistency.

Generated from the same computations the tests assert (tests/test_panel_*.py,
tests/test_mesh_corrections.py, tests/test_mesh_consistency.py).
"""

from __future__ import annotations

import functools
import warnings

import numpy as np

from validation import ROOT, markdown_table
from stripcoef.hull.lamb import spheroid_added_mass

RHO = 1000.0


def _lamb(a, b):
    """Lamb's exact (m11, m22, m55) of a spheroid (stripcoef.hull.lamb, tested against Lamb's table)."""
    m = spheroid_added_mass(a, b, rho=RHO)
    return m[0], m[1], m[4]

def _panel_rows():
    from stripcoef.sections.panel import added_mass_contours
    th = np.linspace(0, 2 * np.pi, 800, endpoint=False)
    rows = []
    c = np.column_stack([0.5 * np.cos(th), 0.5 * np.sin(th)])
    m = added_mass_contours([c], rho=RHO)
    ref = RHO * np.pi * 0.25
    rows.append(["circle r = 0.5, m22", ref, m[0, 0], 100 * (m[0, 0] / ref - 1)])
    e = np.column_stack([np.cos(th), 0.4 * np.sin(th)])
    m = added_mass_contours([e], rho=RHO)
    for name, ref, val in (("ellipse 1 x 0.4, m22 = rho pi b^2", RHO * np.pi * 0.16, m[0, 0]),
                           ("ellipse, m33 = rho pi a^2", RHO * np.pi, m[1, 1]),
                           ("ellipse, m44 = rho pi (a^2-b^2)^2/8", RHO * np.pi * 0.84 ** 2 / 8, m[2, 2])):
        rows.append([name, ref, val, 100 * (val / ref - 1)])
    return rows


def _rect_rows():
    from validation.reference import load_table
    from stripcoef.sections.panel import added_mass_contours
    prefix = "rectangle.a_over_b_"
    rows = []
    for row in load_table("dnv_rp_c205", "table_a1_added_mass_2d"):
        name = row["name"]
        if not name.startswith(prefix) or "inf" in name:
            continue
        ab = float(name[len(prefix):].rsplit(".", 1)[0])
        b = 1.0 / ab
        m = added_mass_contours([np.array([[-1.0, -b], [1.0, -b], [1.0, b], [-1.0, b]])],
                                rho=RHO, panels=512)
        if name.endswith(".C_A"):
            val, printed = m[1, 1] / (RHO * np.pi), 0.005
        else:
            val, printed = m[2, 2] / (RHO * np.pi * max(1.0, b) ** 4), 0.0005 if \
                len(row["value_text"].split(".")[-1]) == 3 else 0.005
        tol = row["atol"] + row["rtol"] * abs(row["value"])
        diff = val - row["value"]
        status = ("within printed precision" if abs(diff) <= printed else
                  "within the row's tolerance" if abs(diff) <= tol else "outside (strict xfail)")
        rows.append([name[len(prefix):], row["value_text"], f"{val:.4f}", f"{diff:+.4f}", status])
    return rows


def _axisym_rows():
    from stripcoef.hull.corrections import body_of_revolution_added_mass
    rows = []
    for ld in (2, 4, 7.5, 12):
        a, b = 0.75, 0.75 / ld
        t = np.linspace(0, np.pi, 400)[::-1]
        m = body_of_revolution_added_mass(a * np.cos(t), b * np.sin(t), rho=RHO)
        ref = _lamb(a, b)
        rows.append([f"spheroid L/D = {ld:g} (Lamb)"] +
                    [f"{100 * (v / r - 1):+.3f}" for v, r in zip((m[0, 0], m[1, 1], m[5, 5]), ref)])
    th = np.linspace(0, np.pi / 2, 60)
    x = np.r_[-0.65 - 0.1 * np.cos(th), 0.65 + 0.1 * np.sin(th)]
    r = np.r_[0.1 * np.sin(th), 0.1 * np.cos(th)]
    m = body_of_revolution_added_mass(x, r, rho=RHO)
    rows.append(["capsule 1.5 x 0.2 (Capytaine, 12800 panels)"] +
                [f"{100 * (v / ref - 1):+.3f}" for v, ref in zip((m[0, 0], m[1, 1], m[5, 5]),
                                                                   (2.697, 41.05, 5.858))])
    return rows


@functools.lru_cache(maxsize=None)
def consistency_pair(name: str):
    """(profile model, mesh model) of the shipped vehicle ``name``'s hull, by its profile and
    by a mesh revolved from it (256 sections), 200 strips each: computed once per process
    (this section and tests/test_mesh_consistency.py read the same models)."""
    from stripcoef.assembly.estimate import estimate
    from stripcoef.geometry.mesh import mesh_body, revolved_mesh
    from stripcoef.geometry.vehicle import MassSpec, Vehicle, load_vehicle

    v = load_vehicle(ROOT / "geometry" / f"{name}.yaml")
    hull = v.bodies[0]
    lo, hi = hull.x_extent()
    xs = lo + (hi - lo) * 0.5 * (1 - np.cos(np.linspace(0, np.pi, 401)))
    body = mesh_body(revolved_mesh(xs, hull.half_breadth(xs), sections=256), origin="file")
    kw = dict(source="report", fluid=v.fluid, holes=[], mass=MassSpec(), thrusters=[],
              reference="center_of_buoyancy")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        a = estimate(Vehicle(name="p", hull=hull, bodies=[hull], **kw), strips=200)
        b = estimate(Vehicle(name="m", hull=None, bodies=[body], **kw), strips=200)
    return a, b


def _consistency_rows():
    rows = []
    for name in ("spheroid", "capsule", "mares"):
        a, b = consistency_pair(name)
        d = np.diag(a.added_mass)
        e = np.diag(b.added_mass)
        err = np.max(np.abs(e - d)[d > 0] / d[d > 0]) * 100
        dl_a, dl_b = np.diag(a.linear_damping), np.diag(b.linear_damping)
        dq_a, dq_b = np.diag(a.quadratic_damping), np.diag(b.quadratic_damping)
        cross = [1, 2, 4, 5]            # sway, heave, pitch, yaw: cross-flow drag
        axial = [0, 3]                  # surge, roll: friction on the wetted perimeter
        rows.append([f"{name} hull", f"{err:.3f}",
                     f"{100 * np.max(np.abs(dl_b - dl_a)[cross] / dl_a[cross]):.3f}",
                     f"{100 * np.max(np.abs(dq_b - dq_a)[axial] / dq_a[axial]):.3f}"])
    return rows


def section() -> str:
    parts = ["## Meshes, 2D panel method and 3D corrections\n",
             "### 2D panel method: exact solutions (default panel count)\n",
             markdown_table(["case", "exact [kg/m, kg m]", "panel method", "error %"], _panel_rows()),
             "\n### 2D panel method: DNV-RP-C205 Table A-1 rectangles (512 panels; C_A on rho pi a^2, "
             "beta on rho pi a_max^4; rows and tolerances from reference_tables/dnv_rp_c205)\n",
             markdown_table(["a/b . column", "table", "panel method", "difference", "status"],
                            _rect_rows()),
             "\n### Axisymmetric BEM of `stripcoef.hull.corrections` (160 meridian panels): error %\n",
             markdown_table(["body (reference)", "m11", "m22", "m66"], _axisym_rows()),
             "\n### Mesh made by revolving a shipped profile vs the profile (200 strips)\n",
             markdown_table(["vehicle", "max added-mass diagonal difference %",
                             "max cross-flow linear damping difference %",
                             "surge and roll quadratic damping (friction) difference %"],
                            _consistency_rows()),
             "\nThe friction terms come from the wetted perimeter: the profile's ellipse "
             "(Ramanujan) against the sum of the mesh sections' edge lengths "
             "(`stripcoef.assembly.damping.wetted_perimeter`).\n"]
    return "\n".join(parts)

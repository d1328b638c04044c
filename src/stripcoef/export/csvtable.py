r"""CSV export: one row per number, ``quantity,row,col,value,unit``.

Rows, in the export's axes and about its reference point:

* ``name``, ``axes``, ``point`` (text in ``value``); ``reference_point`` rows x, y, z
  (FRD coordinates of the point in the source model);
* ``mass``, ``volume``, ``density``, ``gravity``, ``kinematic_viscosity``;
* ``r_g`` and ``r_b`` rows x, y, z: CG and CB relative to the reference point;
* ``rigid_body_mass``, ``added_mass``, ``linear_damping``, ``quadratic_damping``:
  36 rows each, ``row`` and ``col`` the DOF names (surge ... yaw), Fossen's positive
  convention (``added_mass,surge,surge`` = -X_udot);
* per thruster ``thruster_allocation`` (row = DOF, col = thruster name) and its
  thrust map (``ct_forward`` ... ``deadband``, col = thruster name).

:func:`read` parses it back.  The calibrated ``effects`` a model may carry do not fit
this table (the registry warns, as for every format without ``holds_effects``).
"""

from __future__ import annotations

import csv
import io

import numpy as np

from stripcoef.conventions import DOF
from stripcoef.errors import InputError
from stripcoef.export._common import ExportFormat, ExportView, fmt
from stripcoef.views import entry_unit

NAME = "csv"

MATRICES = ("rigid_body_mass", "added_mass", "linear_damping", "quadratic_damping", "lift")
SCALARS = {"mass": "kg", "volume": "m^3", "density": "kg/m^3", "gravity": "m/s^2",
           "kinematic_viscosity": "m^2/s"}
THRUSTER_FIELDS = {"ct_forward": "N/cmd^2", "ct_backward": "N/cmd^2", "max_forward": "N",
                   "max_backward": "N", "eta_forward": "-", "eta_backward": "-",
                   "deadband": "cmd"}
XYZ = ("x", "y", "z")


#: SI unit of entry (i, j) of a mass or damping matrix (one home: stripcoef.views).
matrix_unit = entry_unit


def render(view: ExportView) -> str:
    model = view.model
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["quantity", "row", "col", "value", "unit"])
    w.writerow(["name", "", "", model.name, ""])
    w.writerow(["axes", "", "", view.axes, ""])
    w.writerow(["point", "", "", view.point_label, ""])
    for k, v in zip(XYZ, view.point):
        w.writerow(["reference_point", k, "", fmt(v), "m"])
    for key, unit in SCALARS.items():
        w.writerow([key, "", "", fmt(getattr(model, key)), unit])
    for key, vec in (("r_g", view.r_g), ("r_b", view.r_b)):
        for k, v in zip(XYZ, vec):
            w.writerow([key, k, "", fmt(v), "m"])
    for kind in MATRICES:
        m = view.matrix(kind)
        for i in range(6):
            for j in range(6):
                w.writerow([kind, DOF[i], DOF[j], fmt(m[i, j]), matrix_unit(kind, i, j)])
    b = view.allocation()
    for n, t in enumerate(model.thrusters):
        for i in range(6):
            w.writerow(["thruster_allocation", DOF[i], t.name, fmt(b[i, n]),
                        "-" if i < 3 else "m"])
        for key, unit in THRUSTER_FIELDS.items():
            w.writerow([key, "", t.name, fmt(getattr(t, key)), unit])
    for c in model.control_surfaces:
        b = view.vector6(c.derivative)
        for i in range(6):
            w.writerow(["control_derivative", DOF[i], c.name, fmt(b[i]),
                        "kg/(m rad)" if i < 3 else "kg/rad"])
        w.writerow(["max_deflection", "", c.name, fmt(c.max_deflection), "rad"])
    return buf.getvalue()


def read(text: str, *, file: str | None = None) -> dict:
    """Parse a table written by :func:`render` into arrays.

    Returns a dict with ``name``, ``axes``, ``point``, ``reference_point``, the scalars,
    ``r_g``, ``r_b``, the four 6x6 matrices, ``thrusters`` (names),
    ``thruster_allocation`` (6 x n) and ``thruster_params`` (name -> field -> value).
    """
    rows = list(csv.reader(io.StringIO(text)))
    if not rows or rows[0] != ["quantity", "row", "col", "value", "unit"]:
        raise InputError("not a stripcoef CSV export", file=file, key="header",
                         value=rows[0] if rows else "",
                         expected="quantity,row,col,value,unit")
    out: dict = {k: np.zeros((6, 6)) for k in MATRICES}
    out.update(reference_point=np.zeros(3), r_g=np.zeros(3), r_b=np.zeros(3))
    thr: dict[str, dict] = {}
    alloc: dict[str, np.ndarray] = {}
    ctrl: dict[str, np.ndarray] = {}
    dmax: dict[str, float] = {}
    for line, row in enumerate(rows[1:], start=2):
        if len(row) != 5:
            raise InputError("wrong number of columns", file=file, key=f"line {line}",
                             value=row, expected="5 columns")
        q, r, c, v, _ = row
        try:
            if q in ("name", "axes", "point"):
                out[q] = v
            elif q in ("reference_point", "r_g", "r_b"):
                out[q][XYZ.index(r)] = float(v)
            elif q in SCALARS:
                out[q] = float(v)
            elif q in MATRICES:
                out[q][DOF.index(r), DOF.index(c)] = float(v)
            elif q == "thruster_allocation":
                alloc.setdefault(c, np.zeros(6))[DOF.index(r)] = float(v)
            elif q in THRUSTER_FIELDS:
                thr.setdefault(c, {})[q] = float(v)
            elif q == "control_derivative":
                ctrl.setdefault(c, np.zeros(6))[DOF.index(r)] = float(v)
            elif q == "max_deflection":
                dmax[c] = float(v)
            else:
                raise ValueError(q)
        except ValueError:
            raise InputError("unreadable row", file=file, key=f"line {line}", value=row,
                             expected="a row written by stripcoef export --to csv") from None
    names = list(alloc)
    out["thrusters"] = names
    out["thruster_allocation"] = (np.column_stack([alloc[n] for n in names]) if names
                                  else np.zeros((6, 0)))
    out["thruster_params"] = thr
    out["control_surfaces"] = list(ctrl)
    out["control_derivatives"] = (np.column_stack([ctrl[n] for n in ctrl]) if ctrl
                                  else np.zeros((6, 0)))
    out["max_deflection"] = dmax
    return out


#: This format's entry of the registry :data:`stripcoef.export.FORMATS`.
FORMAT = ExportFormat(
    name=NAME,
    description="plain CSV table quantity,row,col,value,unit (matrices, mass properties, thrusters)",
    suffix=".csv",
    render=render)

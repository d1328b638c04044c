r"""NPZ export: numpy arrays in a compressed ``.npz`` archive (binary; needs ``-o``).

Arrays, in the export's axes and about its reference point: ``M_RB``, ``M_A``, ``D_L``,
``D_Q`` (6x6, Fossen's positive convention), ``mass``, ``volume``, ``density``,
``gravity``, ``kinematic_viscosity``, ``r_g``, ``r_b`` (CG and CB relative to the point),
``reference_point`` (FRD coordinates in the source model), ``axes``, ``point``, ``name``,
``dof``, ``thrusters`` (names) and ``B_thrusters`` (6 x n), plus ``model_json``: the
whole :meth:`HydroModel.to_dict` about the point (FRD), so that
``HydroModel.from_dict(json.loads(str(npz["model_json"])))`` restores the model.
Load with ``numpy.load(path)`` (no pickles are stored).
"""

from __future__ import annotations

import io

import numpy as np

from stripcoef.conventions import DOF
from stripcoef.export._common import ExportFormat, ExportView
from stripcoef.files import json_text

NAME = "npz"


def arrays(view: ExportView) -> dict:
    """The arrays stored in the archive."""
    model = view.model
    return {
        "name": np.array(model.name),
        "axes": np.array(view.axes),
        "point": np.array(view.point_label),
        "dof": np.array(DOF),
        "reference_point": np.asarray(view.point, dtype=float),
        "M_RB": view.matrix("rigid_body_mass"),
        "M_A": view.matrix("added_mass"),
        "D_L": view.matrix("linear_damping"),
        "D_Q": view.matrix("quadratic_damping"),
        "mass": np.array(float(model.mass)),
        "volume": np.array(float(model.volume)),
        "density": np.array(float(model.density)),
        "gravity": np.array(float(model.gravity)),
        "kinematic_viscosity": np.array(float(model.kinematic_viscosity)),
        "r_g": view.r_g,
        "r_b": view.r_b,
        "thrusters": np.array([t.name for t in model.thrusters], dtype=str),
        "B_thrusters": view.allocation() if model.thrusters else np.zeros((6, 0)),
        "L": view.matrix("lift"),
        "control_surfaces": np.array([c.name for c in model.control_surfaces], dtype=str),
        "B_delta": (np.column_stack([view.vector6(c.derivative) for c in model.control_surfaces])
                    if model.control_surfaces else np.zeros((6, 0))),
        "max_deflection": np.array([c.max_deflection for c in model.control_surfaces], float),
        "model_json": np.array(json_text(model.to_dict(), indent=None).strip()),
    }


def render(view: ExportView) -> bytes:
    buf = io.BytesIO()
    np.savez_compressed(buf, **arrays(view))
    return buf.getvalue()


#: This format's entry of the registry :data:`stripcoef.export.FORMATS`.
FORMAT = ExportFormat(
    name=NAME,
    description="numpy .npz archive of the matrices (binary, needs -o)",
    suffix=".npz",
    render=render,
    binary=True,
    holds_effects=True)

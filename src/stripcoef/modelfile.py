"""Read the VEHICLE argument of the model-consuming commands: a vehicle file or a model file.

A model file is :meth:`HydroModel.to_dict` as JSON, or as YAML (a mapping with
``added_mass`` and ``rigid_body_mass``); any other YAML is a vehicle file, estimated by strip
theory (:func:`stripcoef.load_vehicle` + :func:`stripcoef.estimate`).  Meshes need the mesh
options of ``stripcoef coefficients``: make a model file with it first.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from stripcoef.errors import InputError
from stripcoef.files import load_json, load_yaml, read_text
from stripcoef.model import HydroModel, check_physical

_MATRICES = ("added_mass", "linear_damping", "quadratic_damping", "rigid_body_mass")
_REQUIRED = _MATRICES + ("reference_point", "mass", "volume", "center_of_gravity",
                         "center_of_buoyancy", "density")


def load_model(path) -> HydroModel:
    """A HydroModel from a model file (JSON/YAML) or a vehicle file (YAML)."""
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in (".json", ".yaml", ".yml"):
        raise InputError("not a vehicle or model file", file=str(path), value=path.suffix,
                         expected="a vehicle file (.yaml) or a model file (.json/.yaml); for a "
                                  "mesh run 'stripcoef coefficients MESH --json -o model.json' "
                                  "first")
    text = read_text(path, kind="vehicle or model file")
    if suffix == ".json":
        return model_from_dict(load_json(text, file=str(path)), file=str(path))
    data = load_yaml(text, file=str(path))
    if isinstance(data, dict) and "added_mass" in data and "rigid_body_mass" in data:
        return model_from_dict(data, file=str(path))
    from stripcoef.assembly import estimate
    from stripcoef.geometry.vehicle import load_vehicle
    return estimate(load_vehicle(path))


def model_from_dict(data, *, file: str | None = None) -> HydroModel:
    """:meth:`HydroModel.from_dict` with every missing or malformed key reported by name."""
    if not isinstance(data, dict):
        raise InputError("not a model", file=file, value=type(data).__name__,
                         expected="a mapping from HydroModel.to_dict()")
    for key in _REQUIRED:
        if key not in data:
            raise InputError("missing key", file=file, key=key,
                             expected="a model file from HydroModel.to_dict()")
    for key in _MATRICES:
        _check_array(data[key], (6, 6), file, key)
    for key in ("reference_point", "center_of_gravity", "center_of_buoyancy"):
        _check_array(data[key], (3,), file, key)
    for key in ("mass", "volume", "density"):
        v = data[key]
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0:
            raise InputError("not a positive number", file=file, key=key, value=v,
                             expected="a finite number > 0")
    try:
        model = HydroModel.from_dict(data)
    except (KeyError, TypeError, ValueError) as exc:
        raise InputError(f"malformed model ({exc})", file=file,
                         expected="a model file from HydroModel.to_dict()") from None
    check_physical(model, file=file)
    _check_about_reference_point(model, file)
    return model


def _check_about_reference_point(model, file) -> None:
    r"""M_RB of a model file must be about its reference point: its blocks are
    :math:`m I` and :math:`-m S(r_g)`, :math:`r_g` = CG - reference point (Fossen 2011,
    eq. 3.44), within 1e-6 of their scale [kg, kg m]. A reference point or CG edited alone (or
    one far from the vehicle) would make every consumer wrong."""
    m = float(model.mass)
    m_rb = np.asarray(model.rigid_body_mass, dtype=float)
    r_g = np.asarray(model.center_of_gravity, float) - np.asarray(model.reference_point, float)
    # -m S(r_g) = m [[0, z, -y], [-z, 0, x], [y, -x, 0]]: M_RB[0,4] = m z, M_RB[1,5] = m x,
    # M_RB[2,3] = m y
    implied = np.array([m_rb[1, 5], m_rb[2, 3], m_rb[0, 4]]) / m
    scale = 1e-6 * (1.0 + float(np.max(np.abs(r_g))))
    if np.max(np.abs(np.diag(m_rb)[:3] - m)) > 1e-6 * m:
        raise InputError("rigid_body_mass does not hold the mass", file=file,
                         key="rigid_body_mass", value=np.diag(m_rb)[:3].tolist(),
                         expected=f"the mass {m:.6g} kg on the first three diagonal entries")
    if not np.all(np.abs(implied - r_g) <= scale):
        raise InputError("rigid_body_mass is not about the reference point", file=file,
                         key="reference_point", value=np.asarray(model.reference_point).tolist(),
                         expected=f"CG - reference point = {implied.tolist()} m as M_RB says "
                                  "(Fossen 2011, eq. 3.44)")


def _check_array(value, shape, file, key):
    """A nested list of finite numbers of ``shape``; the error names the first bad entry."""
    def walk(v, dims, where):
        if not dims:
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise InputError("not a finite number", file=file, key=where, value=v,
                                 expected=f"finite numbers of shape {shape}")
            return
        if not isinstance(v, (list, tuple)) or len(v) != dims[0]:
            raise InputError("wrong shape", file=file, key=where, value=v,
                             expected=f"{dims[0]} entries (an array of shape {shape})")
        for i, x in enumerate(v):
            walk(x, dims[1:], f"{where}[{i}]")
    walk(value, shape, key)

"""Read the VEHICLE argument of the model-consuming commands: a vehicle file or a model file.

A model file is :meth:`HydroModel.to_dict` as JSON, or as YAML (a mapping with
``added_mass`` and ``rigid_body_mass``); any other YAML is a vehicle file, estimated by strip
theory (:func:`stripcoef.load_vehicle` + :func:`stripcoef.estimate`).  Meshes need the mesh
options of ``stripcoef coefficients``: make a model file with it first.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import fields
from pathlib import Path

import numpy as np

from stripcoef.conventions import DOF, parse_dof
from stripcoef.errors import InputError, ModelWarning
from stripcoef.fluid import Fluid
from stripcoef.geometry.vehicle import Reader
from stripcoef.thrusters import Thruster
from stripcoef.files import load_json, load_yaml, read_text
from stripcoef.model import HydroModel
from stripcoef.physical import check_physical

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
    data = check_model_parts(data, file=file)
    try:
        model = HydroModel.from_dict(data)
    except (KeyError, TypeError, ValueError) as exc:
        raise InputError(f"malformed model ({exc})", file=file,
                         expected="a model file from HydroModel.to_dict()") from None
    check_physical(model, file=file)
    _check_about_reference_point(model, file)
    _note_folded_fin_munk(data, file)
    return model


def _note_folded_fin_munk(data: dict, file) -> None:
    """A model file written before the lifting fins' Munk compensation had a key of its own
    (``fin_munk_lift``, :mod:`stripcoef.assembly.fin_munk`) holds it inside ``lift``: read as
    it is (the same forces with the Munk moment), but without the Munk moment (``--no-munk``,
    ``--no-coriolis``) it cannot be dropped, so the fins' Munk moment is taken off twice. Its
    conditions (``lift.fin_munk``) tell such a file; a :class:`ModelWarning` says so."""
    lift = (data.get("conditions") or {}).get("lift")
    if "fin_munk_lift" not in data and isinstance(lift, dict) and lift.get("fin_munk"):
        warnings.warn(f"{file or 'model'}: written before 'fin_munk_lift': its 'lift' holds the "
                      "lifting fins' Munk compensation, read as it is (the same with the Munk "
                      "moment); without the Munk moment (--no-munk, --no-coriolis) the fins' "
                      "Munk moment is taken off twice: write the model file again "
                      "(stripcoef coefficients VEHICLE --json)", ModelWarning, stacklevel=3)


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


# ---------------------------------------------------------------------------
# The optional parts of a model file: scalars, thrusters, effects, control surfaces
# ---------------------------------------------------------------------------

def _thruster_keys() -> tuple:
    """Keys of a thruster entry: the fields of :class:`~stripcoef.thrusters.Thruster`."""
    return tuple(f.name for f in fields(Thruster))

_SURFACE_KEYS = ("name", "type", "derivative", "max_deflection", "stall_angle")


def check_model_parts(data: dict, *, file: str | None = None) -> dict:
    """Check what :meth:`HydroModel.from_dict` reads beside the matrices, like a vehicle file.

    Types, shapes, finiteness and physical ranges, each error naming the file, the key path
    (``thrusters[0].direction``), the value and what was expected:

    - ``name`` a string; ``gravity`` g > 0 [m/s^2]; ``kinematic_viscosity`` nu > 0 [m^2/s]
      (:class:`stripcoef.fluid.Fluid` checks the water as for a vehicle file);
    - ``thrusters``: a list of mappings with a unique non-empty ``name``, ``position`` and
      ``direction`` of 3 finite numbers, the direction not zero (it is normalised, as in a
      vehicle file: the thrust is along its unit vector), thrust coefficients and
      efficiencies > 0, limits >= 0 (``null`` = none), dead band >= 0;
    - ``effects``: a list of ``{name, dof, parameters}`` mappings, ``dof`` one of the six
      degrees of freedom (or ``all``), parameters finite numbers; the effect names, the
      DOFs they act in, their parameters and ranges checked against the effects library
      (:func:`stripcoef.effects.laws.check_effect_entries`);
    - ``lift`` and ``fin_munk_lift`` 6 x 6 finite; ``control_surfaces`` with a 6-vector
      ``derivative`` and
      angles > 0 [rad]; ``conditions`` and ``provenance`` mappings.

    Returns ``data`` with the thruster directions normalised (a new mapping).
    """
    r = Reader(file)
    data = dict(data)
    if "name" in data:
        name = r.string(data, "name", "")
        if not name.strip():
            raise r.err("name", "empty name", name, "a non-empty string")
    if data.get("gravity") is not None:
        r.number(data, "gravity", "", positive=True)
    if data.get("kinematic_viscosity") is not None:
        nu = r.number(data, "kinematic_viscosity", "", positive=True)
        try:
            Fluid(density=float(data["density"]), kinematic_viscosity=nu, source="model file")
        except InputError as exc:
            raise InputError(exc.what, file=file, key=exc.key, value=exc.value,
                             expected=exc.expected) from None
    for key in ("conditions", "provenance"):
        if data.get(key) is not None and not isinstance(data[key], dict):
            raise r.err(key, "not a mapping", data[key], "a mapping of keys to values")
    for key in ("lift", "fin_munk_lift"):
        if data.get(key) is not None:
            _check_array(data[key], (6, 6), file, key)
    data["thrusters"] = _check_thrusters(r, data)
    effects = data.get("effects")
    if effects is not None:
        if not isinstance(effects, list):
            raise r.err("effects", "wrong type", effects,
                        "a list of {name, dof, parameters} mappings")
        for k, entry in enumerate(effects):
            path = f"effects[{k}]"
            if not isinstance(entry, dict):       # other keys (std, units) are notes
                raise r.err(path, "not a mapping", entry, "{name, dof, parameters}")
            name = r.string(entry, "name", path, required=True)
            if not name.strip():
                raise r.err(f"{path}.name", "empty name", name, "an effect's name")
            if "dof" in entry:
                _check_dof(r, entry["dof"], f"{path}.dof", DOF)
            params = entry.get("parameters", {})
            if not isinstance(params, dict):
                raise r.err(f"{path}.parameters", "not a mapping", params,
                            "a mapping of parameter names to numbers")
            for p in params:
                r.number(params, p, f"{path}.parameters", required=True)
        if effects:
            # the effects library loads scipy (its window regressors): only for a file with effects
            from stripcoef.effects.laws import check_effect_entries
            check_effect_entries(effects, file=file)
    surfaces = r.listing(data, "control_surfaces", "")
    for k, entry in enumerate(surfaces):
        path = f"control_surfaces[{k}]"
        r.mapping(entry, path, _SURFACE_KEYS)
        r.string(entry, "name", path, required=True)
        r.string(entry, "type", path)
        r.vector(entry, "derivative", path, n=6, required=True)
        r.number(entry, "max_deflection", path, positive=True, required=True)
        r.number(entry, "stall_angle", path, positive=True)
    return data


def _check_dof(r, value, key, dof_names) -> None:
    """An effect's degree of freedom: a DOF name (surge..yaw, u..r, X..N), an index 0-5 or
    ``all``."""

    expected = "one of " + ", ".join(dof_names) + ", an index 0-5 or all"
    if isinstance(value, bool):
        raise r.err(key, "not a degree of freedom", value, expected)
    if isinstance(value, int):
        if not 0 <= value < 6:
            raise r.err(key, "not a degree of freedom", value, expected)
        return
    if not isinstance(value, str):
        raise r.err(key, "not a degree of freedom", value, expected)
    if value.strip().lower() == "all":
        return
    try:
        parse_dof(value)
    except InputError:
        raise r.err(key, "not a degree of freedom", value, expected) from None


def _check_thrusters(r, data) -> list:
    """The thruster entries of a model file, checked; directions normalised."""
    out = []
    names: set = set()
    keys = _thruster_keys()
    for k, t in enumerate(r.listing(data, "thrusters", "")):
        path = f"thrusters[{k}]"
        r.mapping(t, path, keys)
        name = r.string(t, "name", path, required=True)
        if not name.strip():
            raise r.err(f"{path}.name", "empty name", name,
                        "a non-empty name (logs carry its command in the column n_<name>)")
        if name in names:
            raise r.err(f"{path}.name", "duplicated thruster name", name, "unique names")
        names.add(name)
        r.vector(t, "position", path, required=True)
        d = r.vector(t, "direction", path, required=True)
        norm = float(np.linalg.norm(d))
        if not norm > 1e-12:
            raise r.err(f"{path}.direction", "zero vector", t["direction"],
                        "a non-zero direction (of the unit vector of positive thrust)")
        for key in ("ct_forward", "ct_backward", "eta_forward", "eta_backward"):
            r.number(t, key, path, positive=True)
        for key in ("max_forward", "max_backward"):
            if t.get(key) is not None and not (isinstance(t[key], float)
                                               and t[key] == float("inf")):
                r.number(t, key, path, nonneg=True)
        r.number(t, "deadband", path, nonneg=True)
        r.number(t, "torque_ratio", path)
        if "source" in t and not isinstance(t["source"], dict):
            raise r.err(f"{path}.source", "not a mapping", t["source"], "a mapping")
        out.append({**t, "direction": (d / norm).tolist()})
    return out

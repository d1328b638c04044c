"""Labelled views of the model's matrices: DOF names and units on every row and column.

- :func:`entry_unit` is the SI unit of one entry of a mass or damping matrix (force i per
  velocity j, Fossen's positive convention; the one home of these units, also used by the CSV
  export);
- :func:`matrix_frame` is a pandas DataFrame of a 6x6 matrix (pandas is optional:
  ``pip install 'stripcoef[pandas]'``), rows the forces ``X (surge)`` .. ``N (yaw)``, columns
  the velocities ``u (surge)`` .. ``r (yaw)``, with the units in ``frame.attrs["units"]`` (a
  6x6 DataFrame of unit strings);
- :func:`model_html` is the HTML a notebook shows for a ``HydroModel`` (no pandas needed).
"""

from __future__ import annotations

from html import escape

import numpy as np

from stripcoef.conventions import DOF, FORCES, VELOCITIES
from stripcoef.errors import InputError

#: The model's 6x6 matrices: attribute -> (title, symbol).
MATRICES = {
    "rigid_body_mass": ("rigid-body mass", "M_RB"),
    "added_mass": ("added mass", "M_A"),
    "linear_damping": ("linear damping", "D_L"),
    "quadratic_damping": ("quadratic damping", "D_Q"),
}


def entry_unit(kind: str, i: int, j: int) -> str:
    """SI unit of entry (i, j) of a mass or damping matrix (force_i per velocity_j).

    Mass [kg, kg m, kg m^2]; linear damping [kg/s, kg m/s, kg m^2/s]; quadratic damping
    (force_i / (|nu_j| nu_j)) [kg/m, kg, kg m, kg m^2] (Fossen 2011, eq. 7.190); lift
    (force_i / (u nu_j), docs/conventions.md) has the quadratic damping's units.
    """
    ti, tj = i < 3, j < 3
    if kind in ("rigid_body_mass", "added_mass"):
        return "kg" if ti and tj else ("kg m^2" if not ti and not tj else "kg m")
    if kind == "linear_damping":
        return "kg/s" if ti and tj else ("kg m^2/s" if not ti and not tj else "kg m/s")
    if kind in ("quadratic_damping", "lift"):
        return {(True, True): "kg/m", (True, False): "kg m", (False, True): "kg",
                (False, False): "kg m^2"}[(ti, tj)]
    raise InputError("unknown matrix", key="kind", value=kind,
                     expected="one of " + ", ".join(MATRICES))


#: Units of the study outputs that are not coefficients (stripcoef.study.evaluate).
_OUTPUT_UNITS = {"mass": "kg", "surge_speed_max": "m/s", "heave_speed_max": "m/s",
                 "sway_speed_max": "m/s", "yaw_rate_max": "rad/s", "min_turning_radius": "m"}

#: Units of vehicle-file numbers by their last key (docs/vehicle-file.md); "" where a key's
#: unit depends on its context.
_KEY_UNITS = {"radius": "m", "length": "m", "x": "m", "span": "m", "chord": "m",
              "thickness": "m", "diameter": "m", "inner_diameter": "m", "root": "m",
              "center": "m", "size": "m", "position": "m", "center_of_gravity": "m",
              "reference_point": "m", "mass": "kg", "density": "kg/m^3",
              "default_density": "kg/m^3", "kinematic_viscosity": "m^2/s",
              "temperature": "degC", "salinity": "PSU", "max_forward": "N",
              "max_backward": "N", "inertia": "kg m^2", "area": "m^2"}


def coefficient_unit(name: str) -> str:
    """SI unit of an SNAME coefficient or study output by its name ("" when unknown).

    ``X_udot`` (added mass), ``X_u`` (linear damping), ``X_uu`` (quadratic damping, and the
    lift terms ``Y_uv``: force per u nu_j) take :func:`entry_unit` of their matrix entry; a
    control derivative ``Y_uudr`` is force per (u^2 rad): the quadratic unit of a surge
    column per rad; ``mass`` [kg], speeds [m/s], ``yaw_rate_max`` [rad/s], radii [m].
    """
    from stripcoef.conventions import FORCES, VELOCITIES

    if name in _OUTPUT_UNITS:
        return _OUTPUT_UNITS[name]
    if name.startswith("u_max@"):
        return "m/s"
    force, _, rest = name.partition("_")
    if force not in FORCES or not rest or rest[0] not in VELOCITIES:
        return ""
    i = FORCES.index(force)
    if rest.endswith("dot") and len(rest) == 4:
        return entry_unit("added_mass", i, VELOCITIES.index(rest[0]))
    if len(rest) == 1:
        return entry_unit("linear_damping", i, VELOCITIES.index(rest[0]))
    if len(rest) == 2 and rest[1] in VELOCITIES:
        return entry_unit("quadratic_damping", i, VELOCITIES.index(rest[1]))
    if rest.startswith("uud"):
        return entry_unit("quadratic_damping", i, 0) + "/rad"
    return ""


def key_unit(path: str) -> str:
    """SI unit of a vehicle-file number by its key path (``hull.profile[1].radius`` -> m)."""
    leaf = str(path).split(".")[-1].split("[")[0]
    return _KEY_UNITS.get(leaf, "")


def with_unit(label: str, unit: str) -> str:
    """An axis label with its unit in brackets when one is known (``radius [m]``)."""
    return f"{label} [{unit}]" if unit else label


def labels():
    """Row labels (forces) and column labels (velocities): ``X (surge)``, ``u (surge)``."""
    return ([f"{f} ({d})" for f, d in zip(FORCES, DOF)],
            [f"{v} ({d})" for v, d in zip(VELOCITIES, DOF)])


def matrix_frame(matrix, kind: str):
    """A 6x6 matrix as a pandas DataFrame with DOF labels; units in ``attrs["units"]``."""
    try:
        import pandas as pd
    except ImportError:
        raise InputError("labelled views need pandas", key="kind", value=kind,
                         expected="pip install 'stripcoef[pandas]'") from None
    rows, cols = labels()
    frame = pd.DataFrame(np.asarray(matrix, dtype=float), index=rows, columns=cols)
    frame.attrs["units"] = pd.DataFrame([[entry_unit(kind, i, j) for j in range(6)]
                                         for i in range(6)], index=rows, columns=cols)
    title, symbol = MATRICES[kind]
    frame.attrs["name"] = f"{symbol} ({title})"
    return frame


def _table(matrix, kind: str) -> str:
    rows, cols = labels()
    title, symbol = MATRICES[kind]
    head = "".join(f"<th>{escape(c)}</th>" for c in cols)
    body = []
    for i, r in enumerate(rows):
        cells = "".join(f'<td title="{entry_unit(kind, i, j)}">{matrix[i, j]:.4g}</td>'
                        for j in range(6))
        body.append(f"<tr><th>{escape(r)}</th>{cells}</tr>")
    units = ", ".join(dict.fromkeys(entry_unit(kind, i, j) for i in range(6) for j in range(6)))
    return (f"<details><summary><b>{symbol}</b> {title} [{escape(units)}; hover an entry for "
            f"its unit]</summary><table><tr><th></th>{head}</tr>{''.join(body)}</table>"
            "</details>")


def model_html(model) -> str:
    """The notebook view of a HydroModel: mass properties and the four labelled matrices."""
    p = np.round(np.asarray(model.reference_point, float), 4) + 0.0
    g = np.round(np.asarray(model.center_of_gravity, float), 4) + 0.0
    b = np.round(np.asarray(model.center_of_buoyancy, float), 4) + 0.0
    parts = [f"<div><b>HydroModel {escape(str(model.name))}</b>: mass {model.mass:.4g} kg, "
             f"volume {model.volume:.4g} m^3, density {model.density:.5g} kg/m^3; matrices "
             f"about {p.tolist()} m (FRD body axes); CG {g.tolist()} m, CB {b.tolist()} m; "
             f"{len(model.thrusters)} thrusters"]
    for kind in MATRICES:
        parts.append(_table(np.asarray(getattr(model, kind), float), kind))
    return "".join(parts) + "</div>"

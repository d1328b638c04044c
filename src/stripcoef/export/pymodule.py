r"""Python export: an importable module holding the model as numpy arrays.

The module defines, in the export's axes and about its reference point:
``M_RB``, ``M_A``, ``D_L``, ``D_Q`` (6x6, Fossen's positive convention: the hydrodynamic
force is ``-M_A @ nu_dot - C_A(nu) @ nu - (D_L + D_Q * abs(nu)) @ nu``), ``M = M_RB + M_A``,
``MASS``, ``VOLUME``, ``DENSITY``, ``GRAVITY``, ``R_G`` and ``R_B`` (CG and CB relative to
the reference point), ``REFERENCE_POINT`` (FRD coordinates of the point in the source
model), ``AXES``, ``DOF``, ``THRUSTERS`` (names) and ``B_THRUSTERS`` (6 x n allocation,
``tau = B_THRUSTERS @ thrusts``), and ``COEFFICIENTS`` (SNAME derivatives by name, with
their signs, in the export's axes).

References
----------
Fossen (2011), Handbook of Marine Craft Hydrodynamics and Motion Control, eq. 7.190.
"""

from __future__ import annotations

import numpy as np

from stripcoef.conventions import DOF, FORCES, VELOCITIES, sname_coefficients
from stripcoef.export._common import ExportFormat, ExportView, fmt, header_lines

NAME = "python"


def _array(m) -> str:
    m = np.asarray(m, dtype=float)
    if m.ndim == 1:
        return "np.array([" + ", ".join(_num(v) for v in m) + "])"
    if m.size == 0:
        return f"np.zeros(({m.shape[0]}, {m.shape[1]}))"
    rows = ["    [" + ", ".join(_num(v) for v in row) + "]," for row in m]
    return "np.array([\n" + "\n".join(rows) + "\n])"


def _num(v) -> str:
    text = fmt(v)
    if text in ("Inf", "-Inf"):
        return "float('inf')" if text == "Inf" else "-float('inf')"
    return text


def render(view: ExportView) -> str:
    model = view.model
    ma = view.matrix("added_mass")
    dl = view.matrix("linear_damping")
    dq = view.matrix("quadratic_damping")
    coeffs = sname_coefficients(ma, dl, dq, tol=1e-12)
    lift = view.matrix("lift")
    coeffs.update({f"{FORCES[i]}_u{VELOCITIES[j]}": -float(lift[i, j]) for i in range(6)
                   for j in range(6) if abs(lift[i, j]) > 1e-12 * max(np.abs(lift).max(), 1e-300)})
    bdel = (np.column_stack([view.vector6(c.derivative) for c in model.control_surfaces])
            if model.control_surfaces else np.zeros((6, 0)))
    head = header_lines(view, NAME)
    lines = ['"""' + head[0] + ".", ""]
    lines += head[1:]
    lines += [
        "",
        "Fossen's convention: M_A, D_L, D_Q positive; hydrodynamic force",
        "-M_A nu_dot - C_A(nu) nu - (D_L + D_Q diag|nu|) nu. Units SI, radians.",
        '"""',
        "",
        "import numpy as np",
        "",
        f"NAME = {model.name!r}",
        f"AXES = {view.axes!r}",
        f"POINT = {view.point_label!r}",
        f"DOF = {tuple(DOF)!r}",
        f"REFERENCE_POINT = {_array(view.point)}  # [m], FRD coordinates of the source model",
        f"MASS = {_num(model.mass)}  # [kg]",
        f"VOLUME = {_num(model.volume)}  # [m^3]",
        f"DENSITY = {_num(model.density)}  # [kg/m^3]",
        f"GRAVITY = {_num(model.gravity)}  # [m/s^2]",
        f"KINEMATIC_VISCOSITY = {_num(model.kinematic_viscosity)}  # [m^2/s]",
        f"R_G = {_array(view.r_g)}  # CG relative to the reference point [m]",
        f"R_B = {_array(view.r_b)}  # CB relative to the reference point [m]",
        "",
        "# Rigid-body mass [kg, kg m, kg m^2]",
        f"M_RB = {_array(view.matrix('rigid_body_mass'))}",
        "",
        "# Added mass, positive (M_A[0, 0] = -X_udot) [kg, kg m, kg m^2]",
        f"M_A = {_array(ma)}",
        "",
        "# Linear damping, positive (D_L[0, 0] = -X_u) [kg/s, kg m/s, kg m^2/s]",
        f"D_L = {_array(dl)}",
        "",
        "# Quadratic damping, positive: force_i = -sum_j D_Q[i, j] |nu_j| nu_j",
        f"D_Q = {_array(dq)}",
        "",
        "# Lift (forward-speed) terms, positive: force = -u L nu (L[1, 1] = -Y_uv)",
        "# [kg/m, kg, kg m] (body and fin lift, Prestero 2001 sec. 3.6)",
        f"L = {_array(lift)}",
        "",
        "M = M_RB + M_A",
        "",
        f"CONTROL_SURFACES = {tuple(c.name for c in model.control_surfaces)!r}",
        "# Control surfaces: force = u |u| B_DELTA @ deflections [rad] (Prestero 2001 sec. 3.7)",
        f"B_DELTA = {_array(bdel)}",
        f"MAX_DEFLECTION = {_array(np.array([c.max_deflection for c in model.control_surfaces]))}"
        "  # [rad]",
        "",
        f"THRUSTERS = {tuple(t.name for t in model.thrusters)!r}",
        "# Thruster allocation: tau = B_THRUSTERS @ thrusts [N]",
        f"B_THRUSTERS = {_array(view.allocation()) if model.thrusters else 'np.zeros((6, 0))'}",
        "",
        "# SNAME derivatives (signed) in AXES",
        "COEFFICIENTS = {",
    ]
    lines += [f"    {k!r}: {_num(v)}," for k, v in coeffs.items()]
    lines += ["}", ""]
    return "\n".join(lines)


#: This format's entry of the registry :data:`stripcoef.export.FORMATS`.
FORMAT = ExportFormat(
    name=NAME,
    description="importable Python module with the matrices as numpy arrays",
    suffix=".py",
    render=render)

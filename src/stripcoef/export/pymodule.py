r"""Python export: an importable module holding the model as numpy arrays.

The module defines, in the export's axes and about its reference point:
``M_RB``, ``M_A``, ``D_L``, ``D_Q`` (6x6, Fossen's positive convention: the hydrodynamic
force is ``-M_A @ nu_dot - C_A(nu) @ nu - (D_L + D_Q * abs(nu)) @ nu``), ``M = M_RB + M_A``,
``MASS``, ``VOLUME``, ``DENSITY``, ``GRAVITY``, ``R_G`` and ``R_B`` (CG and CB relative to
the reference point), ``REFERENCE_POINT`` (FRD coordinates of the point in the source
model), ``AXES``, ``DOF``, ``THRUSTERS`` (names) and ``B_THRUSTERS`` (6 x n allocation,
``tau = B_THRUSTERS @ thrusts``), and ``COEFFICIENTS`` (SNAME derivatives by name, with
their signs, in the export's axes).

In FRD axes (the default) the module also runs: ``THRUSTER_MAPS`` and ``thrust(commands)``
(the bilinear map of Wang & Clark 2006, eq. 6, with its efficiencies, dead band and limits),
``state_derivative(eta, nu, tau, current)`` (Fossen 2011, eqs. 7.190 and 10.1: the same
equations as ``stripcoef simulate`` and the MSS export) and a class ``Vehicle`` in the style of
the vehicles of Fossen's PythonVehicleSimulator: ``Vehicle().dynamics(eta, nu, u_actual,
u_control, sampleTime)`` returns the next ``nu`` (one forward-Euler step) and ``u_actual``
(the thruster commands after a first-order lag of time constant ``T_n``, then the rudder and
elevator deflections [rad] after a lag ``T_delta``, clipped to ``MAX_DEFLECTION``). The
module needs numpy only. In FLU axes it holds the data only (the NED kinematics are FRD).

References
----------
Fossen (2011), Handbook of Marine Craft Hydrodynamics and Motion Control, eqs. 2.18, 2.29,
3.46, 4.6, 6.43, 7.190, 10.1; Wang & Clark (2006), eq. 6; Fossen's PythonVehicleSimulator
(github.com/cybergalactic/PythonVehicleSimulator) for the ``dynamics`` interface.
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
    if view.axes == "FRD":
        lines += _dynamics_lines(view)
    return "\n".join(lines)


def _dynamics_lines(view: ExportView) -> list[str]:
    """The runnable part of the module: thrust map, state derivative, a Vehicle class."""
    maps = ["THRUSTER_MAPS = ("]
    for t in view.model.thrusters:
        maps.append(f"    # {t.name}: thrust = eta C_t n|n| [N], clipped to [-max_backward, "
                    "max_forward]")
        maps.append(f"    {{'name': {t.name!r}, 'ct_forward': {_num(t.ct_forward)}, "
                    f"'ct_backward': {_num(t.ct_backward)}, 'eta_forward': "
                    f"{_num(t.eta_forward)}, 'eta_backward': {_num(t.eta_backward)}, "
                    f"'max_forward': {_num(t.max_forward)}, 'max_backward': "
                    f"{_num(t.max_backward)}, 'deadband': {_num(t.deadband)}}},")
    maps.append(")")
    return maps + [""] + _DYNAMICS.splitlines() + [""]


# The runnable part, written as it is into FRD modules (numpy only). Equations: Fossen (2011)
# eqs. 2.18/2.29 (J), 3.46/6.43 (C from M), 4.6 (g), 7.190 and 10.1 (relative velocity);
# thrust: Wang & Clark (2006), eq. 6 (stripcoef.thrusters.Thruster.thrust).
_DYNAMICS = '''
def skew(a):
    """S(a), S(a) b = a x b (Fossen 2011, eq. 2.10)."""
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


def coriolis(mass, nu):
    """C(nu) of a 6x6 inertia matrix [kg/s, kg m/s, kg m^2/s] (Fossen 2011, eqs. 3.46, 6.43)."""
    a = mass[:3, :3] @ nu[:3] + mass[:3, 3:] @ nu[3:]
    b = mass[3:, :3] @ nu[:3] + mass[3:, 3:] @ nu[3:]
    c = np.zeros((6, 6))
    c[:3, 3:] = -skew(a)
    c[3:, :3] = -skew(a)
    c[3:, 3:] = -skew(b)
    return c


def rotation(phi, theta, psi):
    """R(Theta), body to NED, zyx Euler angles [rad] (Fossen 2011, eq. 2.18)."""
    cf, sf, ct, st, cp, sp = (np.cos(phi), np.sin(phi), np.cos(theta), np.sin(theta),
                              np.cos(psi), np.sin(psi))
    return np.array([[cp * ct, -sp * cf + cp * st * sf, sp * sf + cp * cf * st],
                     [sp * ct, cp * cf + sf * st * sp, -cp * sf + st * sp * cf],
                     [-st, ct * sf, ct * cf]])


def kinematics(eta):
    """J(eta): eta_dot = J(eta) nu (Fossen 2011, eqs. 2.18 and 2.29)."""
    phi, theta = eta[3], eta[4]
    cf, sf, ct, tt = np.cos(phi), np.sin(phi), np.cos(theta), np.tan(theta)
    t = np.array([[1.0, sf * tt, cf * tt], [0.0, cf, -sf], [0.0, sf / ct, cf / ct]])
    j = np.zeros((6, 6))
    j[:3, :3] = rotation(*eta[3:6])
    j[3:, 3:] = t
    return j


def restoring(eta):
    """g(eta) [N, N m], the force is -g (Fossen 2011, eq. 4.6)."""
    w, b = MASS * GRAVITY, DENSITY * GRAVITY * VOLUME
    phi, theta = eta[3], eta[4]
    sf, cf, st, ct = np.sin(phi), np.cos(phi), np.sin(theta), np.cos(theta)
    (xg, yg, zg), (xb, yb, zb) = R_G, R_B
    return np.array([(w - b) * st, -(w - b) * ct * sf, -(w - b) * ct * cf,
                     -(yg * w - yb * b) * ct * cf + (zg * w - zb * b) * ct * sf,
                     (zg * w - zb * b) * st + (xg * w - xb * b) * ct * cf,
                     -(xg * w - xb * b) * ct * sf - (yg * w - yb * b) * st])


def thrust(commands):
    """Thrusts [N] of the thrusters for their commands (sequence in THRUSTERS order):
    T = eta C_t n|n| (forward/backward values), 0 inside the dead band, clipped to the limits
    (Wang & Clark 2006, eq. 6)."""
    out = np.zeros(len(THRUSTER_MAPS))
    for k, (t, n) in enumerate(zip(THRUSTER_MAPS, np.asarray(commands, dtype=float))):
        fwd = n >= 0.0
        ct = t["ct_forward"] * t["eta_forward"] if fwd else t["ct_backward"] * t["eta_backward"]
        value = 0.0 if abs(n) <= t["deadband"] else ct * n * abs(n)
        out[k] = min(max(value, -t["max_backward"]), t["max_forward"])
    return out


def state_derivative(eta, nu, tau, current=(0.0, 0.0, 0.0)):
    """(eta_dot, nu_dot) of the 6-DOF model [m/s, rad/s; m/s^2, rad/s^2].

    M nu_dot = tau - C_RB(nu) nu - C_A(nu_r) nu_r - D(nu_r) nu_r - g(eta) + M_A nu_c_dot,
    D(nu_r) = D_L + u_r L + D_Q diag|nu_r| (L: body and fin lift, 0 without fins),
    eta_dot = J(eta) nu, nu_r = nu - nu_c, nu_c = [R^T V_c; 0], nu_c_dot = [-S(w) R^T V_c; 0]
    (Fossen 2011, eqs. 7.190 and 10.1). eta [m, rad] NED pose, nu [m/s, rad/s] body
    velocity over ground (about the reference point, FRD), tau [N, N m] applied force,
    current V_c [m/s] constant in NED. Control-surface forces are part of tau:
    u_r |u_r| B_DELTA @ deflections [N, N m] for deflections [rad].
    """
    eta = np.asarray(eta, dtype=float)
    nu = np.asarray(nu, dtype=float)
    vc = rotation(*eta[3:6]).T @ np.asarray(current, dtype=float)
    nu_c = np.concatenate([vc, np.zeros(3)])
    nu_c_dot = np.concatenate([-skew(nu[3:]) @ vc, np.zeros(3)])
    nu_r = nu - nu_c
    force = (np.asarray(tau, dtype=float) - coriolis(M_RB, nu) @ nu
             - coriolis(M_A, nu_r) @ nu_r - (D_L + nu_r[0] * L + D_Q * np.abs(nu_r)) @ nu_r
             - restoring(eta) + M_A @ nu_c_dot)
    return kinematics(eta) @ nu, np.linalg.solve(M, force)


class Vehicle:
    """The model as a vehicle of Fossen's PythonVehicleSimulator (same interface).

    ``u_control`` and ``u_actual`` are the thruster commands (THRUSTERS order) followed by the
    control-surface deflections [rad] (CONTROL_SURFACES order: rudders, elevators), as the
    simulator's ``remus100`` takes its rudder and stern-plane angles beside the propeller.
    ``T_n`` [s] is a first-order lag of the actual thruster commands and ``T_delta`` [s] of
    the actual deflections (0: none, as in stripcoef simulate); the deflections are clipped
    to +-MAX_DEFLECTION; ``current`` [m/s] a constant NED current.
    """

    def __init__(self, controlSystem="stepInput", T_n=0.0, current=(0.0, 0.0, 0.0),
                 T_delta=0.0):
        self.name = NAME + " (stripcoef export)"
        self.L = None
        self.controls = ([f"{n} command" for n in THRUSTERS]
                         + [f"{n} deflection (rad)" for n in CONTROL_SURFACES])
        self.dimU = len(THRUSTERS) + len(CONTROL_SURFACES)
        self.controlMode = controlSystem
        self.controlDescription = "Step inputs of the thruster commands and deflections"
        self.nu = np.zeros(6)
        self.u_actual = np.zeros(self.dimU)
        self.T_n = float(T_n)
        self.T_delta = float(T_delta)
        self.current = np.asarray(current, dtype=float)
        self.u_step = np.zeros(self.dimU)

    def forces(self, eta, nu, u_actual):
        """tau [N, N m] of the actual inputs: B_THRUSTERS thrust(commands) plus the
        control surfaces' u_r |u_r| B_DELTA delta (u_r: surge speed through the water)."""
        u_actual = np.asarray(u_actual, dtype=float)
        n = len(THRUSTERS)
        tau = B_THRUSTERS @ thrust(u_actual[:n]) if n else np.zeros(6)
        if CONTROL_SURFACES:
            vc = rotation(*np.asarray(eta, dtype=float)[3:6]).T @ self.current
            u_r = float(nu[0]) - vc[0]
            tau = tau + u_r * abs(u_r) * (B_DELTA @ u_actual[n:])
        return tau

    def dynamics(self, eta, nu, u_actual, u_control, sampleTime):
        """One forward-Euler step of sampleTime [s]: returns (nu, u_actual) at the next sample."""
        u_actual = np.asarray(u_actual, dtype=float)
        _, nu_dot = state_derivative(eta, nu, self.forces(eta, nu, u_actual), self.current)
        target = np.asarray(u_control, dtype=float).copy()
        n = len(THRUSTERS)
        target[n:] = np.clip(target[n:], -MAX_DEFLECTION, MAX_DEFLECTION)
        lag = np.array([self.T_n] * n + [self.T_delta] * len(CONTROL_SURFACES))
        step = np.where(lag > 0.0, sampleTime / np.where(lag > 0.0, lag, 1.0), 1.0)
        u_actual = u_actual + np.minimum(step, 1.0) * (target - u_actual)
        return np.asarray(nu, dtype=float) + sampleTime * nu_dot, u_actual

    def stepInput(self, t):
        """The inputs of a step input at time t [s] (constant ``u_step``)."""
        return self.u_step.copy()
'''.strip("\n")


#: This format's entry of the registry :data:`stripcoef.export.FORMATS`.
FORMAT = ExportFormat(
    name=NAME,
    description="importable Python module with the matrices as numpy arrays",
    suffix=".py",
    render=render)

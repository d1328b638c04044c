r"""MSS (Marine Systems Simulator) export: a MATLAB / GNU Octave function file.

The file follows the style of Fossen's MSS vehicle models (cybergalactic/MSS
``CRAFT/AUV/models/remus100.m``): a self-contained function that returns the state
derivative of ``x = [u v w p q r x y z phi theta psi]'`` (FRD body velocities, NED
position, Euler angles), the speed and the model matrices:

.. code-block:: matlab

    [xdot, U, M, MRB, MA, D, g, DL, DQ, Bthr] = name(x, tau, Vc)
    [~, ~, M, MRB, MA] = name()          % empty call: the constant matrices

with, about the export's reference point (the CO of the file) in FRD body axes,

.. math::
    M\dot\nu = \tau - C_{RB}(\nu)\nu - C_A(\nu_r)\nu_r - D(\nu_r)\nu_r - g(\eta)
               + M_A \dot\nu_c, \qquad \dot\eta = J(\eta)\nu

:math:`\nu_r = \nu - \nu_c`, :math:`\nu_c = [R^T V_c; 0]` for a constant NED current
``Vc`` (irrotational, so :math:`\dot\nu_c = [-\omega\times R^T V_c; 0]`),
:math:`D(\nu_r) = D_L + D_Q\,\mathrm{diag}(|\nu_r|)`, C from the full M (Fossen 2011,
Theorem 3.2 / eq. 6.43), g from eq. 4.6 and J from eqs. 2.18 and 2.29.  MSS's own
sign convention is used: M_A and D positive, ``D*nu`` opposes the motion.

References
----------
Fossen (2011), Handbook of Marine Craft Hydrodynamics and Motion Control, eqs. 2.18, 2.29,
3.46, 4.6, 6.43, 7.190 and sec. 10.3 (ocean currents); Fossen's MSS ``remus100.m``.
"""

from __future__ import annotations

import re

import numpy as np

from stripcoef.errors import InputError
from stripcoef.export._common import ExportFormat, ExportView, clean, fmt, header_lines

NAME = "mss"

_IDENT = re.compile(r"^[A-Za-z][A-Za-z0-9_]{0,62}$")


def function_name_for(text: str) -> str:
    """A valid MATLAB identifier derived from a model or file name."""
    name = re.sub(r"[^A-Za-z0-9_]", "_", str(text))
    if not name or not name[0].isalpha():
        name = "model_" + name
    return name[:63]


def check_function_name(name: str) -> str:
    if not _IDENT.match(str(name)):
        raise InputError("not a MATLAB/Octave function name", key="output", value=name,
                         expected="a file name that is a valid identifier (a letter, then "
                                  "letters, digits or _; at most 63 characters) ending in .m")
    return str(name)


def _matrix(name: str, m) -> list[str]:
    m = np.atleast_2d(np.asarray(m, dtype=float))
    if m.size == 0:
        return [f"{name} = zeros({m.shape[0]}, 0);"]
    rows = ["  " + ", ".join(fmt(v) for v in row) for row in m]
    return [f"{name} = [", *[r + ";" for r in rows[:-1]], rows[-1] + "];"]


def render(view: ExportView, *, function_name: str | None = None) -> str:
    """The function file text (``view``: the model about the CO of the file, FRD axes)."""
    model = view.model
    fname = check_function_name(function_name or function_name_for(model.name))
    mrb = clean(view.matrix("rigid_body_mass"))
    ma = clean(view.matrix("added_mass"))
    dl = clean(view.matrix("linear_damping"))
    dq = clean(view.matrix("quadratic_damping"))
    bthr = view.allocation()
    thr_names = [t.name for t in model.thrusters]
    lift = clean(view.matrix("lift"))
    bdel = (np.column_stack([view.vector6(s.derivative) for s in model.control_surfaces])
            if model.control_surfaces else np.zeros((6, 0)))
    cs_names = [s.name for s in model.control_surfaces]

    head = header_lines(view, NAME)
    lines = [
        f"function [xdot, U, M, MRB, MA, D, g, DL, DQ, Bthr, L, Bdelta] = {fname}(x, tau, Vc, delta)",
        f"% {fname.upper()}  {head[0].split(': ', 1)[-1]}",
        "% Compatible with MATLAB and the free software GNU Octave (www.octave.org).",
        "% Style of Fossen's MSS vehicle models (cybergalactic/MSS CRAFT/AUV/models/remus100.m).",
    ]
    lines += ["% " + h for h in head[1:]]
    lines += [
        "%",
        "%   x   = [ u v w p q r x y z phi theta psi ]'  (m/s, rad/s, m, rad), FRD body",
        "%         velocities about the CO above, NED position, Euler angles (zyx)",
        "%   tau = [ X Y Z K M N ]' generalized force about the CO (N, Nm), default zeros",
        "%   Vc  = [ Vn Ve Vd ]' constant ocean current in NED (m/s), default zeros",
        "%   delta = control surface deflections (rad), one per column of Bdelta, default zeros",
        "%",
        "% Returns xdot (12x1), the speed U (m/s), M = MRB + MA, MRB, MA, the damping",
        "% D = DL + u_r*L + DQ*diag(|nu_r|) at the relative velocity nu_r (L: body and fin",
        "% lift, Prestero 2001 sec. 3.6), the restoring forces g(eta) (Fossen 2011, eq. 4.6),",
        "% DL, DQ, the thruster allocation Bthr (6 x n, tau = Bthr*T), L and the control",
        "% surfaces' Bdelta (force u_r*|u_r|*Bdelta*delta, Prestero 2001 sec. 3.7).",
        "% MA, DL, DQ are positive: -MA*nu_dot - D*nu is the hydrodynamic force.",
        "%",
        "%   M*nu_dot = tau + u_r|u_r| Bdelta delta - CRB(nu)*nu - CA(nu_r)*nu_r - D*nu_r - g",
        "%              + MA*nu_c_dot",
        "%",
        "% Example usage:",
        f"%   [~,~,M,MRB,MA] = {fname}()             : the constant matrices",
        f"%   [xdot,U] = {fname}(x, tau)             : no ocean current",
        f"%   [xdot,U] = {fname}(x, tau, [0.2 0 0]') : 0.2 m/s current towards north",
        "%",
        "% Thrusters (columns of Bthr): " + (", ".join(thr_names) if thr_names else "none"),
        "% Control surfaces (columns of Bdelta): " + (", ".join(cs_names) if cs_names else "none"),
        "",
        "if nargin < 1 || isempty(x), x = zeros(12,1); end",
        f"if nargin < 4 || isempty(delta), delta = zeros({len(cs_names)},1); end",
        "delta = delta(:);",
        "if nargin < 2 || isempty(tau), tau = zeros(6,1); end",
        "if nargin < 3 || isempty(Vc), Vc = zeros(3,1); end",
        "x = x(:); tau = tau(:); Vc = Vc(:);",
        "if length(x) ~= 12, error('x-vector must have dimension 12'); end",
        "if length(tau) ~= 6, error('tau-vector must have dimension 6'); end",
        "if length(Vc) ~= 3, error('Vc-vector must have dimension 3'); end",
        "",
        "% Model parameters (stripcoef)",
        f"rho = {fmt(model.density)};            % water density (kg/m3)",
        f"g_n = {fmt(model.gravity)};            % acceleration of gravity (m/s2)",
        f"m = {fmt(model.mass)};                 % mass (kg)",
        f"vol = {fmt(model.volume)};             % displaced volume (m3)",
        f"r_bg = [{'; '.join(fmt(v) for v in view.r_g)}];  % CG w.r.t. the CO (m)",
        f"r_bb = [{'; '.join(fmt(v) for v in view.r_b)}];  % CB w.r.t. the CO (m)",
        "W = m * g_n; B = rho * g_n * vol;      % weight and buoyancy (N)",
        "",
    ]
    lines += ["% Rigid-body mass matrix about the CO (Fossen 2011, eq. 3.44)"]
    lines += _matrix("MRB", mrb)
    lines += ["% Added mass, positive (MA(1,1) = -X_udot)"]
    lines += _matrix("MA", ma)
    lines += ["% Linear damping, positive (DL(1,1) = -X_u)"]
    lines += _matrix("DL", dl)
    lines += ["% Quadratic damping, positive: force_i = -sum_j DQ(i,j)*|nu_j|*nu_j (DQ(1,1) = -X_u|u|)"]
    lines += _matrix("DQ", dq)
    lines += ["% Thruster allocation about the CO: tau = Bthr * thrusts (N)"]
    lines += _matrix("Bthr", bthr)
    lines += ["% Lift (forward-speed) terms, positive: force = -u*L*nu (L(2,2) = -Y_uv)"]
    lines += _matrix("L", lift)
    lines += ["% Control surfaces: force = u*|u|*Bdelta*delta (Bdelta(2,1) = Y_uudr)"]
    lines += _matrix("Bdelta", bdel) if bdel.size else ["Bdelta = zeros(6,0);"]
    lines += [
        "",
        "% States, current and relative velocity",
        "nu = x(1:6); eta = x(7:12);",
        "[J, R] = eulerang_local(eta(4), eta(5), eta(6));",
        "nu_c = [R' * Vc; 0; 0; 0];",
        "nu_c_dot = [-cross(nu(4:6), nu_c(1:3)); 0; 0; 0];",
        "nu_r = nu - nu_c;",
        "U = sqrt(nu(1)^2 + nu(2)^2 + nu(3)^2);",
        "",
        "M = MRB + MA;",
        "D = DL + nu_r(1) * L + DQ * diag(abs(nu_r));",
        "g = gvect_local(W, B, eta(5), eta(4), r_bg, r_bb);",
        "CRB = m2c_local(MRB, nu);",
        "CA = m2c_local(MA, nu_r);",
        "",
        "tau_delta = nu_r(1) * abs(nu_r(1)) * (Bdelta * delta);",
        "nu_dot = M \\ (tau + tau_delta - CRB * nu - CA * nu_r - D * nu_r - g + MA * nu_c_dot);",
        "xdot = [nu_dot; J * nu];",
        "end",
        "",
        "",
        "function C = m2c_local(M, nu)",
        "% Coriolis-centripetal matrix of a 6x6 inertia matrix (Fossen 2011, eq. 3.46 / 6.43)",
        "a = M(1:3,1:3) * nu(1:3) + M(1:3,4:6) * nu(4:6);",
        "b = M(4:6,1:3) * nu(1:3) + M(4:6,4:6) * nu(4:6);",
        "C = [zeros(3,3), -smtrx_local(a); -smtrx_local(a), -smtrx_local(b)];",
        "end",
        "",
        "",
        "function S = smtrx_local(a)",
        "% Skew-symmetric matrix, S(a)*b = cross(a, b) (Fossen 2011, eq. 2.10)",
        "S = [0, -a(3), a(2); a(3), 0, -a(1); -a(2), a(1), 0];",
        "end",
        "",
        "",
        "function [J, R] = eulerang_local(phi, theta, psi)",
        "% J(eta) with the zyx rotation (Fossen 2011, eqs. 2.18 and 2.29)",
        "cphi = cos(phi); sphi = sin(phi); cth = cos(theta); sth = sin(theta);",
        "cpsi = cos(psi); spsi = sin(psi);",
        "R = [cpsi*cth, -spsi*cphi + cpsi*sth*sphi,  spsi*sphi + cpsi*cphi*sth;",
        "     spsi*cth,  cpsi*cphi + sphi*sth*spsi, -cpsi*sphi + sth*spsi*cphi;",
        "     -sth,      cth*sphi,                   cth*cphi];",
        "if abs(cth) < 1e-9, error('Tzyx is singular for theta = +-90 deg'); end",
        "T = [1, sphi*sth/cth, cphi*sth/cth; 0, cphi, -sphi; 0, sphi/cth, cphi/cth];",
        "J = [R, zeros(3,3); zeros(3,3), T];",
        "end",
        "",
        "",
        "function g = gvect_local(W, B, theta, phi, r_bg, r_bb)",
        "% Restoring forces of a submerged vehicle (Fossen 2011, eq. 4.6)",
        "sth = sin(theta); cth = cos(theta); sphi = sin(phi); cphi = cos(phi);",
        "g = [ (W-B) * sth;",
        "     -(W-B) * cth * sphi;",
        "     -(W-B) * cth * cphi;",
        "     -(r_bg(2)*W - r_bb(2)*B) * cth * cphi + (r_bg(3)*W - r_bb(3)*B) * cth * sphi;",
        "      (r_bg(3)*W - r_bb(3)*B) * sth + (r_bg(1)*W - r_bb(1)*B) * cth * cphi;",
        "     -(r_bg(1)*W - r_bb(1)*B) * cth * sphi - (r_bg(2)*W - r_bb(2)*B) * sth ];",
        "end",
    ]
    return "\n".join(lines) + "\n"


#: This format's entry of the registry :data:`stripcoef.export.FORMATS`.
FORMAT = ExportFormat(
    name=NAME,
    description="MATLAB/Octave function file in the style of Fossen's MSS vehicle models (FRD, CO)",
    suffix=".m",
    render=render,
    axes_allowed=("FRD",),
    options=("function_name",))

r"""Conventions: DOF order, SNAME names, and the one frame / reference-point transform.

Body axes are FRD (x forward, y starboard, z down).  DOF order is
``[surge, sway, heave, roll, pitch, yaw]`` with velocities ``[u, v, w, p, q, r]``
and generalized forces ``[X, Y, Z, K, M, N]``.  All units SI, angles in radians.

Matrices follow Fossen (2011): ``M_A``, ``D_L``, ``D_Q`` are positive and the
hydrodynamic force is ``-M_A nu_dot - C_A(nu) nu - D_L nu - D_Q(|nu|) nu``.
SNAME derivatives keep their sign (``X_udot = -M_A[0, 0]``).

Every conversion of a 6x6 matrix between reference points or between axis
systems goes through :func:`transform_matrix`, built on :func:`shift_operator`
and :func:`axes_operator`.
"""

from __future__ import annotations

import numpy as np

from stripcoef.errors import InputError

DOF = ("surge", "sway", "heave", "roll", "pitch", "yaw")
VELOCITIES = ("u", "v", "w", "p", "q", "r")
FORCES = ("X", "Y", "Z", "K", "M", "N")
POSE = ("x", "y", "z", "phi", "theta", "psi")

#: Sign change of each DOF from FRD body axes to FLU (x forward, y left, z up).
FRD_TO_FLU = np.array([1.0, -1.0, -1.0, 1.0, -1.0, -1.0])
AXES = ("FRD", "FLU")


def skew(a) -> np.ndarray:
    r"""Skew-symmetric cross-product matrix, :math:`S(a) b = a \times b`.

    Parameters
    ----------
    a : array of 3
        Vector [any unit]

    References
    ----------
    Fossen, Handbook of Marine Craft Hydrodynamics and Motion Control (2011), eq. 2.10.
    """
    a = np.asarray(a, dtype=float)
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


def shift_operator(r) -> np.ndarray:
    r"""Velocity transform from point O to point P, :math:`\nu_P = H(r)\,\nu_O`.

    .. math:: H(r) = \begin{bmatrix} I & S(r)^T \\ 0 & I \end{bmatrix},
              \quad v_P = v_O + \omega \times r

    Parameters
    ----------
    r : array of 3
        Position of P relative to O, in body axes [m]

    References
    ----------
    Fossen (2011), eq. 7.248 (system transformation matrix H(r)).
    """
    h = np.eye(6)
    h[:3, 3:] = skew(r).T
    return h


def axes_operator(axes: str) -> np.ndarray:
    """Diagonal sign matrix taking FRD body-axis components to ``axes`` ("FRD" or "FLU").

    T = I (FRD) or T = diag(1, -1, -1, 1, -1, -1) (FLU: a rotation by pi about x);
    returns T [-]. [assumption] convention of this package (see module docstring).
    """
    if axes == "FRD":
        return np.eye(6)
    if axes == "FLU":
        return np.diag(FRD_TO_FLU)
    raise InputError("unknown axes", key="axes", value=axes, expected="FRD or FLU")


#: Earth-fixed frames a log may use: NED (this package) and ENU (ROS, REP 103).
WORLD_FRAMES = ("NED", "ENU")


def world_axes_operator(world: str) -> np.ndarray:
    r"""Matrix taking earth-fixed components in ``world`` ("NED" or "ENU") to NED [-].

    .. math:: A_{ENU} = \begin{bmatrix} 0 & 1 & 0 \\ 1 & 0 & 0 \\ 0 & 0 & -1 \end{bmatrix},
              \quad v_{NED} = A\, v_{world}

    (north = y_ENU, east = x_ENU, down = -z_ENU; A is its own inverse).

    References
    ----------
    Fossen (2011), sec. 2.1 (NED); ROS REP 103, "Standard Units of Measure and Coordinate
    Conventions" (ENU world, FLU body).
    """
    if world == "NED":
        return np.eye(3)
    if world == "ENU":
        return np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]])
    raise InputError("unknown world frame", key="world", value=world,
                     expected=" or ".join(WORLD_FRAMES))


def transform_matrix(matrix, *, from_point=(0.0, 0.0, 0.0), to_point=(0.0, 0.0, 0.0),
                     axes: str = "FRD") -> np.ndarray:
    r"""Express a 6x6 inertia-like or linear-damping matrix about another point and axes.

    A matrix ``A`` about point O (generalized force ``tau_O = -A nu_O``) is, about
    point P with ``r = P - O`` (body axes),

    .. math:: A_P = H(-r)^T A_O H(-r)

    because ``nu_O = H(-r) nu_P`` and ``tau_P = H(-r)^T tau_O`` (power is invariant).
    The axis change is the congruence ``T A T`` with ``T`` from :func:`axes_operator`.

    Parameters
    ----------
    matrix : (6, 6) array
        Matrix about ``from_point`` in FRD body axes [kg, kg m, kg m^2 or per second]
    from_point, to_point : array of 3
        Reference points in FRD body axes [m]
    axes : str
        Output axes, "FRD" or "FLU"

    References
    ----------
    Fossen (2011), sec. 7.5.3 (transformation of M and D between points).
    """
    a = np.asarray(matrix, dtype=float)
    r = np.asarray(to_point, dtype=float) - np.asarray(from_point, dtype=float)
    h = shift_operator(-r)
    t = axes_operator(axes)
    return t @ (h.T @ a @ h) @ t


def transform_vector(vec, axes: str = "FRD") -> np.ndarray:
    """Components of a 3-vector (point, direction) of FRD body axes in ``axes``.

    v_axes = T_3 v_FRD with T_3 the first 3 diagonal entries of :func:`axes_operator`;
    ``vec`` and the result in the same unit ([m] for points, [-] for directions).
    [assumption] package convention (see module docstring).
    """
    return np.asarray(vec, dtype=float) * axes_operator(axes).diagonal()[:3]


def rotation_matrix(phi: float, theta: float, psi: float) -> np.ndarray:
    r"""Body-to-NED rotation :math:`R_{zyx}(\phi, \theta, \psi)` (J_1 of Wang & Clark 2006, eq. 2).

    .. math:: R_{zyx} = R_{z,\psi} R_{y,\theta} R_{x,\phi}

    Euler angles ``phi, theta, psi`` [rad]; returns R [-] (3x3, orthonormal).

    References
    ----------
    Fossen (2011), eq. 2.18; Wang & Clark (VideoRay), eq. 2.
    """
    cf, sf = np.cos(phi), np.sin(phi)
    ct, st = np.cos(theta), np.sin(theta)
    cp, sp = np.cos(psi), np.sin(psi)
    return np.array([
        [cp * ct, -sp * cf + cp * st * sf, sp * sf + cp * cf * st],
        [sp * ct, cp * cf + sf * st * sp, -cp * sf + st * sp * cf],
        [-st, ct * sf, ct * cf],
    ])


def euler_rate_matrix(phi: float, theta: float) -> np.ndarray:
    r"""Angular-velocity transform :math:`T(\Theta)` (J_2 of Wang & Clark 2006, eq. 2).

    .. math:: \dot\Theta = T(\Theta)\,\omega, \quad
        T = \begin{bmatrix} 1 & s\phi t\theta & c\phi t\theta \\
        0 & c\phi & -s\phi \\ 0 & s\phi/c\theta & c\phi/c\theta \end{bmatrix}

    ``phi, theta`` [rad]; returns T [-] (Euler rates [rad/s] from body rates [rad/s]).
    Singular at :math:`\theta = \pm 90^\circ`.

    References
    ----------
    Fossen (2011), eq. 2.29.
    """
    cf, sf = np.cos(phi), np.sin(phi)
    ct, tt = np.cos(theta), np.tan(theta)
    return np.array([[1.0, sf * tt, cf * tt], [0.0, cf, -sf], [0.0, sf / ct, cf / ct]])


def kinematics(eta) -> np.ndarray:
    r"""Full 6x6 kinematic transform :math:`J(\eta)`, :math:`\dot\eta = J(\eta)\nu`.

    .. math:: J(\eta) = \operatorname{diag}(R_{zyx}(\Theta),\ T(\Theta))

    ``eta`` = [x, y, z, phi, theta, psi] [m, rad]; returns J [-] mapping nu
    [m/s, rad/s] to eta_dot [m/s, rad/s].

    References
    ----------
    Wang & Clark (2006), eq. 2; Fossen (2011), eqs. 2.18 and 2.29 (blocks).
    """
    j = np.zeros((6, 6))
    j[:3, :3] = rotation_matrix(eta[3], eta[4], eta[5])
    j[3:, 3:] = euler_rate_matrix(eta[3], eta[4])
    return j


# ---------------------------------------------------------------------------
# SNAME names
# ---------------------------------------------------------------------------

def added_mass_name(i: int, j: int) -> str:
    """SNAME name of ``-M_A[i, j]``, e.g. ``X_udot``, ``Y_rdot``."""
    return f"{FORCES[i]}_{VELOCITIES[j]}dot"


def linear_damping_name(i: int, j: int) -> str:
    """SNAME name of ``-D_L[i, j]``, e.g. ``X_u``, ``N_v``."""
    return f"{FORCES[i]}_{VELOCITIES[j]}"


def quadratic_damping_name(i: int, j: int) -> str:
    """SNAME name of ``-D_Q[i, j]`` (the ``|nu_j| nu_j`` term), e.g. ``X_uu`` for X_u|u|."""
    return f"{FORCES[i]}_{VELOCITIES[j]}{VELOCITIES[j]}"


def sname_coefficients(added_mass, linear_damping, quadratic_damping, *, tol: float = 0.0) -> dict:
    """Every non-zero derivative by SNAME name, with its SNAME sign (negative of the matrix)."""
    out: dict[str, float] = {}
    for mat, namer in ((added_mass, added_mass_name), (linear_damping, linear_damping_name),
                       (quadratic_damping, quadratic_damping_name)):
        m = np.asarray(mat, dtype=float)
        scale = max(float(np.abs(m).max()), 1e-300)
        for i in range(6):
            for j in range(6):
                if abs(m[i, j]) > tol * scale and m[i, j] != 0.0:
                    out[namer(i, j)] = -float(m[i, j])
    return out


def parse_dof(name: str) -> int:
    """Index of a DOF given by name (surge..yaw), velocity letter (u..r) or force letter (X..N)."""
    key = str(name).strip()
    for table in (DOF, VELOCITIES, FORCES):
        if key in table:
            return table.index(key)
    low = key.lower()
    if low in DOF:
        return DOF.index(low)
    raise InputError("unknown degree of freedom", key="dof", value=name,
                     expected="one of " + ", ".join(DOF) + " (or u v w p q r)")


def clean_roundoff(m, rel=1e-12):
    """Set round-off below ``rel`` times the largest entry to exactly zero."""
    m = np.array(m, dtype=float)
    m[np.abs(m) < rel * max(float(np.abs(m).max()), 1e-300)] = 0.0
    return m + 0.0   # no negative zeros

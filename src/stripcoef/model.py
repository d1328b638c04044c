r"""HydroModel: the one result object every consumer reads.

Equations of motion (Fossen 2011, eq. 7.190; Wang & Clark 2006, eqs. 1-2):

.. math::
    M \dot\nu + C(\nu)\nu + D(\nu)\nu + g(\eta) = \tau, \qquad \dot\eta = J(\eta)\nu

with :math:`M = M_{RB} + M_A`, :math:`C = C_{RB} + C_A`,
:math:`D(\nu) = D_L + D_Q \operatorname{diag}(|\nu|)`.

All matrices are about :attr:`HydroModel.reference_point` in FRD body axes.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field, replace

import numpy as np

from stripcoef.conventions import DOF, sname_coefficients, skew, transform_matrix
from stripcoef.errors import InputError, ModelWarning
from stripcoef.fluid import G
from stripcoef.thrusters import Thruster, allocation_matrix


def coriolis_from_mass(mass_matrix, nu) -> np.ndarray:
    r"""Coriolis-centripetal matrix of a symmetric 6x6 inertia matrix (skew-symmetric).

    .. math::
        C(\nu) = \begin{bmatrix} 0 & -S(M_{11}\nu_1 + M_{12}\nu_2) \\
                 -S(M_{11}\nu_1 + M_{12}\nu_2) & -S(M_{21}\nu_1 + M_{22}\nu_2)\end{bmatrix}

    Valid for M_RB about any point and for M_A (``nu_1 = [u,v,w]``, ``nu_2 = [p,q,r]``).

    Parameters
    ----------
    mass_matrix : (6, 6) array
        Symmetric inertia matrix [kg, kg m, kg m^2]
    nu : (6,) array
        Body velocity [m/s, rad/s]

    Returns
    -------
    (6, 6) array
        C(nu) [kg/s, kg m/s, kg m^2/s]

    References
    ----------
    Fossen (2011), Theorem 3.2 (eq. 3.46) and eq. 6.43; Sagatun & Fossen (1991).
    """
    m = np.asarray(mass_matrix, dtype=float)
    nu = np.asarray(nu, dtype=float)
    m11, m12, m21, m22 = m[:3, :3], m[:3, 3:], m[3:, :3], m[3:, 3:]
    a = m11 @ nu[:3] + m12 @ nu[3:]
    b = m21 @ nu[:3] + m22 @ nu[3:]
    c = np.zeros((6, 6))
    c[:3, 3:] = -skew(a)
    c[3:, :3] = -skew(a)
    c[3:, 3:] = -skew(b)
    return c


def rigid_body_mass_matrix(mass: float, center_of_gravity, inertia_cg) -> np.ndarray:
    r"""Rigid-body inertia matrix about the origin of the coordinates of ``center_of_gravity``.

    .. math::
        M_{RB} = \begin{bmatrix} m I & -m S(r_g) \\ m S(r_g) & I_o \end{bmatrix},
        \quad I_o = I_g - m S(r_g)^2

    Parameters
    ----------
    mass : float
        m [kg]
    center_of_gravity : (3,)
        r_g relative to the reference point [m]
    inertia_cg : (3, 3)
        Inertia tensor about the CG [kg m^2]

    References
    ----------
    Fossen (2011), eqs. 3.44-3.45 (parallel-axis theorem, eq. 3.37).
    """
    rg = np.asarray(center_of_gravity, dtype=float)
    s = skew(rg)
    m = np.zeros((6, 6))
    m[:3, :3] = mass * np.eye(3)
    m[:3, 3:] = -mass * s
    m[3:, :3] = mass * s
    m[3:, 3:] = np.asarray(inertia_cg, dtype=float) - mass * s @ s
    return m


def restoring_forces(eta, *, weight: float, buoyancy: float, r_g, r_b) -> np.ndarray:
    r"""Restoring forces g(eta) of a submerged vehicle (force = -g).

    .. math::
        g(\eta) = \begin{bmatrix} (W-B)s\theta \\ -(W-B)c\theta s\phi \\ -(W-B)c\theta c\phi \\
        -(y_gW - y_bB)c\theta c\phi + (z_gW - z_bB)c\theta s\phi \\
        (z_gW - z_bB)s\theta + (x_gW - x_bB)c\theta c\phi \\
        -(x_gW - x_bB)c\theta s\phi - (y_gW - y_bB)s\theta \end{bmatrix}

    Parameters
    ----------
    eta : (6,) array
        Pose [m, rad]; only phi and theta matter
    weight, buoyancy : float
        W = m g and B = rho g V [N]
    r_g, r_b : (3,)
        CG and CB relative to the reference point [m]

    References
    ----------
    Fossen (2011), eq. 4.6.
    """
    phi, theta = eta[3], eta[4]
    cf, sf, ct, st = np.cos(phi), np.sin(phi), np.cos(theta), np.sin(theta)
    w, b = weight, buoyancy
    xg, yg, zg = r_g
    xb, yb, zb = r_b
    return np.array([
        (w - b) * st,
        -(w - b) * ct * sf,
        -(w - b) * ct * cf,
        -(yg * w - yb * b) * ct * cf + (zg * w - zb * b) * ct * sf,
        (zg * w - zb * b) * st + (xg * w - xb * b) * ct * cf,
        -(xg * w - xb * b) * ct * sf - (yg * w - yb * b) * st,
    ])


def plain(value):
    """Recursively convert numpy scalars/arrays to plain Python types (JSON/YAML safe)."""
    if isinstance(value, dict):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return plain(value.tolist())
    if isinstance(value, np.generic):
        return value.item()
    return value


@dataclass
class HydroModel:
    """A vehicle's hydrodynamic model about one reference point (FRD body axes).

    Attributes
    ----------
    name : str
    reference_point : (3,) [m]
    rigid_body_mass, added_mass, linear_damping, quadratic_damping : (6, 6)
        M_RB, M_A, D_L, D_Q (all positive, Fossen's convention)
    mass : float [kg]
    volume : float [m^3]
    center_of_gravity, center_of_buoyancy : (3,) [m], body axes (absolute, not relative)
    density : float [kg/m^3]
    kinematic_viscosity : float [m^2/s]
    thrusters : list of Thruster
    conditions : dict
        Reynolds numbers, regimes and drag coefficients used (for reports)
    effects : list of dict
        Extra force terms added by calibration (see :mod:`stripcoef.effects.laws`)
    provenance : dict
        Where each part came from (method, options, file)
    """

    name: str
    reference_point: np.ndarray
    rigid_body_mass: np.ndarray
    added_mass: np.ndarray
    linear_damping: np.ndarray
    quadratic_damping: np.ndarray
    mass: float
    volume: float
    center_of_gravity: np.ndarray
    center_of_buoyancy: np.ndarray
    density: float
    kinematic_viscosity: float = 1.19e-6
    gravity: float = G
    thrusters: list[Thruster] = field(default_factory=list)
    conditions: dict = field(default_factory=dict)
    effects: list[dict] = field(default_factory=list)
    provenance: dict = field(default_factory=dict)

    # -- derived quantities -------------------------------------------------
    @property
    def mass_matrix(self) -> np.ndarray:
        """M = M_RB + M_A [kg, kg m, kg m^2] (Fossen 2011, eq. 7.190; see module docstring)."""
        return self.rigid_body_mass + self.added_mass

    @property
    def weight(self) -> float:
        """W = m g [N], m [kg], g [m/s^2] (Fossen 2011, sec. 4.1)."""
        return self.mass * self.gravity

    @property
    def buoyancy(self) -> float:
        """B = rho g V [N], rho [kg/m^3], V [m^3] (Fossen 2011, sec. 4.1)."""
        return self.density * self.gravity * self.volume

    @property
    def r_g(self) -> np.ndarray:
        """CG relative to the reference point [m]."""
        return np.asarray(self.center_of_gravity) - np.asarray(self.reference_point)

    @property
    def r_b(self) -> np.ndarray:
        """CB relative to the reference point [m]."""
        return np.asarray(self.center_of_buoyancy) - np.asarray(self.reference_point)

    def coriolis(self, nu, *, rigid_body: bool = True, added_mass: bool = True,
                 munk: bool = True) -> np.ndarray:
        """C(nu) = C_RB(nu) + C_A(nu); ``munk=False`` drops the C_A terms that multiply
        linear velocities into moments (the Munk moment, Ferreira et al. 2009 sec. V.D).

        ``nu`` [m/s, rad/s]; returns C [kg/s, kg m/s, kg m^2/s] (C nu in [N, N m]).
        Each term from :func:`coriolis_from_mass` (Fossen 2011, Theorem 3.2, eq. 3.46).
        """
        c = np.zeros((6, 6))
        if rigid_body:
            c += coriolis_from_mass(self.rigid_body_mass, nu)
        if added_mass:
            ca = coriolis_from_mass(self.added_mass, nu)
            if not munk:
                ca = ca.copy()
                # Munk moment: moments from the linear momentum of the added mass.
                ca[3:, :3] = 0.0
            c += ca
        return c

    def damping(self, nu) -> np.ndarray:
        """D(nu) = D_L + D_Q diag(|nu|) [kg/s, ...]; hydrodynamic force = -D(nu) nu.

        ``nu`` [m/s, rad/s]; D_L [kg/s, kg m^2/s], D_Q [kg/m, kg m^2]. Quadratic
        diagonal drag of Wang & Clark 2006, eq. 7 (see module docstring, Fossen 2011, eq. 7.190).
        """
        return self.linear_damping + self.quadratic_damping * np.abs(np.asarray(nu, dtype=float))

    def restoring(self, eta) -> np.ndarray:
        """g(eta) [N, N m] (force = -g), eta [m, rad]; see :func:`restoring_forces`
        (Fossen 2011, eq. 4.6)."""
        return restoring_forces(eta, weight=self.weight, buoyancy=self.buoyancy,
                                r_g=self.r_g, r_b=self.r_b)

    def allocation(self) -> np.ndarray:
        """Thruster allocation matrix B (6 x n): tau = B @ thrust.

        tau [N, N m], thrust [N]; B is [-] in force rows, [m] in moment rows
        (column i = [d_i; r_i x d_i], see :func:`stripcoef.thrusters.allocation_matrix`).
        """
        return allocation_matrix(self.thrusters, self.reference_point)

    def thruster(self, name: str) -> Thruster:
        for t in self.thrusters:
            if t.name == name:
                return t
        from stripcoef.errors import unknown_name
        raise unknown_name("thruster", name, [t.name for t in self.thrusters])

    def coefficients(self) -> dict:
        """Every SNAME derivative by name, with its SNAME sign."""
        return sname_coefficients(self.added_mass, self.linear_damping, self.quadratic_damping,
                                  tol=1e-12)

    # -- transforms ---------------------------------------------------------
    def about(self, point) -> "HydroModel":
        """The same model expressed about another point (FRD body axes).

        M_RB, M_A and D_L transform exactly (:func:`stripcoef.conventions.transform_matrix`).
        D_Q is transformed with the same congruence, which is exact for the pure
        translation columns and an approximation for the rotation columns (the
        quadratic strip integral is not invariant); a :class:`ModelWarning` says so
        when rotational columns are affected.
        """
        point = np.asarray(point, dtype=float)
        old = np.asarray(self.reference_point, dtype=float)
        if np.allclose(point, old):
            return replace(self)

        def t(m):
            return transform_matrix(m, from_point=old, to_point=point)

        dq = t(self.quadratic_damping)
        if np.any(self.quadratic_damping[:, 3:] != 0.0):
            warnings.warn("quadratic damping moved to another reference point with the "
                          "linear congruence: exact for translation columns, approximate "
                          "for rotation columns", ModelWarning, stacklevel=2)
        return replace(self, reference_point=point, rigid_body_mass=t(self.rigid_body_mass),
                       added_mass=t(self.added_mass), linear_damping=t(self.linear_damping),
                       quadratic_damping=dq)

    # -- serialisation ------------------------------------------------------
    def to_dict(self) -> dict:
        """The JSON output contract (docs/conventions.md)."""
        def mat(m):
            return [[float(x) for x in row] for row in np.asarray(m)]

        return {
            "name": self.name,
            "dof": list(DOF),
            "reference_point": [float(x) for x in self.reference_point],
            "added_mass": mat(self.added_mass),
            "linear_damping": mat(self.linear_damping),
            "quadratic_damping": mat(self.quadratic_damping),
            "rigid_body_mass": mat(self.rigid_body_mass),
            "mass": float(self.mass),
            "volume": float(self.volume),
            "center_of_gravity": [float(x) for x in self.center_of_gravity],
            "center_of_buoyancy": [float(x) for x in self.center_of_buoyancy],
            "density": float(self.density),
            "kinematic_viscosity": float(self.kinematic_viscosity),
            "gravity": float(self.gravity),
            "coefficients": self.coefficients(),
            "thrusters": [t.to_dict() for t in self.thrusters],
            "conditions": plain(self.conditions),
            "effects": plain(self.effects),
            "provenance": plain(self.provenance),
        }

    @classmethod
    def from_dict(cls, data: dict) -> "HydroModel":
        """Inverse of :meth:`to_dict` (used by model files and round trips)."""
        thr = [Thruster(name=t["name"], position=np.asarray(t["position"], float),
                        direction=np.asarray(t["direction"], float),
                        ct_forward=t.get("ct_forward", 1.0), ct_backward=t.get("ct_backward", 1.0),
                        max_forward=t.get("max_forward", float("inf")),
                        max_backward=t.get("max_backward", float("inf")),
                        eta_forward=t.get("eta_forward", 1.0),
                        eta_backward=t.get("eta_backward", 1.0),
                        deadband=t.get("deadband", 0.0))
               for t in data.get("thrusters", [])]
        return cls(
            name=data.get("name", "model"),
            reference_point=np.asarray(data["reference_point"], float),
            rigid_body_mass=np.asarray(data["rigid_body_mass"], float),
            added_mass=np.asarray(data["added_mass"], float),
            linear_damping=np.asarray(data["linear_damping"], float),
            quadratic_damping=np.asarray(data["quadratic_damping"], float),
            mass=float(data["mass"]), volume=float(data["volume"]),
            center_of_gravity=np.asarray(data["center_of_gravity"], float),
            center_of_buoyancy=np.asarray(data["center_of_buoyancy"], float),
            density=float(data["density"]),
            kinematic_viscosity=float(data.get("kinematic_viscosity", 1.19e-6)),
            gravity=float(data.get("gravity", G)),
            thrusters=thr, conditions=data.get("conditions", {}),
            effects=list(data.get("effects", [])), provenance=data.get("provenance", {}),
        )


def check_physical(model, *, file: str | None = None) -> None:
    r"""Raise an :class:`InputError` if ``model`` is not a physically possible vehicle.

    Checked, each error naming the key, the value and what was expected:

    - every matrix, point and scalar finite; mass, volume and density > 0 [kg, m^3, kg/m^3];
    - :math:`M_{RB}` symmetric positive definite (Fossen 2011, eq. 3.44: a rigid body's
      kinetic energy :math:`\tfrac12\nu^T M_{RB}\nu > 0`), and so
      :math:`M = M_{RB} + M_A` (its symmetric part: the kinetic energy of body and fluid,
      Fossen 2011, sec. 6.3.1);
    - damping that dissipates: non-negative diagonals of :math:`D_L` and :math:`D_Q` and a
      positive semi-definite symmetric part of :math:`D_L`
      (:math:`\nu^T D_L \nu \ge 0`, Fossen 2011, sec. 6.4; a negative one is an energy source).

    Eigenvalue tolerances are relative to the matrix's largest entry (1e-9) [-].
    """
    def fail(key, what, value, expected):
        raise InputError(what, file=file, key=key, value=value, expected=expected)

    arrays = (("added_mass", model.added_mass), ("linear_damping", model.linear_damping),
              ("quadratic_damping", model.quadratic_damping),
              ("rigid_body_mass", model.rigid_body_mass),
              ("reference_point", model.reference_point),
              ("center_of_gravity", model.center_of_gravity),
              ("center_of_buoyancy", model.center_of_buoyancy))
    for key, arr in arrays:
        a = np.asarray(arr, dtype=float)
        if not np.all(np.isfinite(a)):
            k = np.unravel_index(int(np.flatnonzero(~np.isfinite(a))[0]), a.shape)
            fail(f"{key}[{']['.join(map(str, k))}]", "not finite", float(a[k]),
                 "finite numbers (the model is not usable)")
    for key in ("mass", "volume", "density"):
        v = float(getattr(model, key))
        if not (np.isfinite(v) and v > 0):
            fail(key, "not a positive number", v, "a finite number > 0")

    def lowest(m):
        m = np.asarray(m, dtype=float)
        return float(np.linalg.eigvalsh(0.5 * (m + m.T)).min()), max(1.0, float(np.abs(m).max()))

    m_rb = np.asarray(model.rigid_body_mass, dtype=float)
    low, scale = lowest(m_rb)
    if low <= 1e-12 * scale:
        fail("rigid_body_mass", "not positive definite",
             f"smallest eigenvalue {low:.4g}",
             "a positive-definite M_RB (mass > 0, inertia satisfying the triangle inequality)")
    low, scale = lowest(m_rb + np.asarray(model.added_mass, dtype=float))
    if low <= 1e-12 * scale:
        fail("added_mass", "M_RB + M_A not positive definite",
             f"smallest eigenvalue {low:.4g}", "a positive-definite total mass matrix")
    for key, mat in (("linear_damping", model.linear_damping),
                     ("quadratic_damping", model.quadratic_damping)):
        mat = np.asarray(mat, dtype=float)
        for i in range(6):
            if mat[i, i] < 0.0:
                fail(f"{key}[{i}][{i}]", "drag matrix is not positive", float(mat[i, i]),
                     ">= 0 (Fossen's convention: D positive, drag opposes motion)")
    low, scale = lowest(model.linear_damping)
    if low < -1e-9 * scale:
        fail("linear_damping", "drag matrix is not positive",
             f"smallest eigenvalue of the symmetric part {low:.4g}",
             "a positive semi-definite matrix (negative damping is an energy source)")

r"""HydroModel: the one result object every consumer reads.

Equations of motion (Fossen 2011, eq. 7.190; Wang & Clark 2006, eqs. 1-2):

.. math::
    M \dot\nu + C(\nu)\nu + D(\nu)\nu + g(\eta) = \tau, \qquad \dot\eta = J(\eta)\nu

with :math:`M = M_{RB} + M_A`, :math:`C = C_{RB} + C_A`,
:math:`D(\nu) = D_L + u\,L + D_Q \operatorname{diag}(|\nu|)` (``L``: the lift matrix, body
and fin lift, force :math:`-u L \nu`; Prestero 2001, sec. 3.6), and
:math:`\tau = B T + u^2 B_\delta \delta` (thrusters, and control surfaces deflected by
:math:`\delta` [rad]; Prestero 2001, sec. 3.7).

All matrices are about :attr:`HydroModel.reference_point` in FRD body axes.
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field, fields, replace
from functools import cached_property
from types import MappingProxyType

import numpy as np

from stripcoef.conventions import (DOF, FORCES, VELOCITIES, added_mass_name, linear_damping_name,
                                   quadratic_damping_name, shift_operator, skew, sname_coefficients,
                                   transform_matrix)
from stripcoef.errors import ModelWarning, unknown_name
from stripcoef.fluid import G, NU_SEAWATER
from stripcoef.thrusters import Thruster, allocation_matrix
from stripcoef.views import MATRICES, matrix_frame, model_html


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
    # -S(a) and -S(b) (eq. 2.10) written out: the right-hand side of every simulation calls
    # this twice, and three skew() calls were a third of its time (the same floats)
    c = np.zeros((6, 6))
    c[:3, 3:] = c[3:, :3] = ((-0.0, a[2], -a[1]), (-a[2], -0.0, a[0]), (a[1], -a[0], -0.0))
    c[3:, 3:] = ((-0.0, b[2], -b[1]), (-b[2], -0.0, b[0]), (b[1], -b[0], -0.0))
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
    return restoring_from_down((-st, ct * sf, ct * cf), weight=weight, buoyancy=buoyancy,
                               r_g=r_g, r_b=r_b)


def restoring_from_down(down, *, weight: float, buoyancy: float, r_g, r_b) -> np.ndarray:
    r"""Restoring forces g [N, N m] of :func:`restoring_forces` from the NED down axis in body
    axes, :math:`k = R^T e_z = (-s\theta,\ c\theta s\phi,\ c\theta c\phi)`, the third row of
    R (Fossen 2011, eq. 2.18), without the Euler angles (a simulation has R):

    .. math::
        g = -\begin{bmatrix} (W - B)\,k \\ (W r_g - B r_b)\times k \end{bmatrix}

    (Fossen 2011, eqs. 4.5-4.6). ``down`` three floats or three arrays (n,) [-]; ``weight``,
    ``buoyancy`` [N]; ``r_g``, ``r_b`` (3,) [m]. Returns (6,) or (6, n)."""
    k0, k1, k2 = down
    w, b = weight, buoyancy
    xg, yg, zg = r_g
    xb, yb, zb = r_b
    a0, a1, a2 = xg * w - xb * b, yg * w - yb * b, zg * w - zb * b
    return np.array([(w - b) * -k0, -(w - b) * k1, -(w - b) * k2,
                     a2 * k1 - a1 * k2, a0 * k2 - a2 * k0, a1 * k0 - a0 * k1])


@dataclass(frozen=True)
class ControlSurface:
    r"""A control surface (rudder or elevator) of a model: its force per deflection and limits.

    The generalized force of a deflection :math:`\delta` [rad] at surge speed u [m/s] is

    .. math:: \tau_\delta = u^2\, b\, \delta, \qquad |\delta| \le \delta_{max} < \alpha_{stall}

    with ``b`` = ``derivative`` about the model's reference point: for a rudder
    :math:`b = [0, Y_{uu\delta_r}, 0, K_{uu\delta_r}, 0, N_{uu\delta_r}]`
    (Prestero 2001, sec. 3.7, eq. 3.51: :math:`Y_{uu\delta_r} = \rho c_{L\alpha} S_{fin}`
    for the fin pair).

    Attributes
    ----------
    name : str
        Identifier; simulation inputs carry its deflection in the column ``delta_<name>`` [rad]
    kind : str
        ``rudder`` (lift along y) or ``elevator`` (lift along z)
    derivative : (6,) array
        b [N/((m/s)^2 rad), N m/((m/s)^2 rad)] about the model's reference point
    max_deflection : float
        Largest deflection either way [rad]
    stall_angle : float
        Effective angle of attack where the surface stalls [rad]
    """

    name: str
    kind: str
    derivative: np.ndarray
    max_deflection: float
    stall_angle: float

    def to_dict(self) -> dict:
        return {"name": self.name, "type": self.kind,
                "derivative": [float(x) for x in self.derivative],
                "max_deflection": float(self.max_deflection),
                "stall_angle": float(self.stall_angle)}

    @classmethod
    def from_dict(cls, d: dict) -> "ControlSurface":
        return cls(name=str(d["name"]), kind=str(d.get("type", "rudder")),
                   derivative=np.asarray(d["derivative"], float).reshape(6),
                   max_deflection=float(d["max_deflection"]),
                   stall_angle=float(d.get("stall_angle", d["max_deflection"])))


#: SNAME names of the control derivatives, by (surface kind, force row).
CONTROL_NAMES = {"rudder": "{F}_uudr", "elevator": "{F}_uuds"}


#: DOF indices of a method band's group (stripcoef.study.sources.GROUPS).
BAND_GROUPS = {"translation": (0, 1, 2), "rotation": (3, 4, 5), "all": (0, 1, 2, 3, 4, 5)}
#: The two-sided 95 % quantile of the normal distribution [-].
Z95 = 1.959963984540054
#: A term whose 95 % band reaches past this relative change is named in the CLI's warning.
UNCERTAIN = 0.5


@dataclass(frozen=True)
class MethodBand:
    """The method's measured (or assumed) spread of one matrix's DOF group.

    ``matrix``: added_mass | linear_damping | quadratic_damping | lift | control; ``dofs``:
    translation | rotation | coupling | all; ``distribution``: lognormal (``sd`` of ln of a
    term [-]) or normal (a coupling's error over sqrt(M_ii M_jj) [-]); ``basis``: measured |
    assumed | not_predicted; ``in_scope``: False where the vehicle lies outside the reference
    shapes the row was measured on (an extrapolation); ``source``: the row's justification.
    From ``data/method_uncertainty.csv`` through :func:`stripcoef.study.bands.method_bands`.
    """

    matrix: str
    dofs: str
    distribution: str
    sd: float
    basis: str = "measured"
    in_scope: bool = True
    source: str = ""

    def factor(self) -> float:
        """The 95 % band of a lognormal row as a factor: model/true within [1/f, f] [-]."""
        return float(np.exp(Z95 * self.sd))

    def describe(self) -> str:
        """The band's size and basis as the text output and the exports' comments print it:
        ``factor 2.35 (measured)`` for a lognormal row (:meth:`factor`), ``+- 0.102 sqrt(M_ii
        M_jj) (measured)`` for a coupling; ``, extrapolated`` out of the row's scope."""
        size = (f"factor {self.factor():.3g}" if self.distribution == "lognormal"
                else f"+- {Z95 * self.sd:.3g} sqrt(M_ii M_jj)")
        return f"{size} ({self.basis}{'' if self.in_scope else ', extrapolated'})"

    def to_dict(self) -> dict:
        return {"matrix": self.matrix, "dofs": self.dofs, "distribution": self.distribution,
                "sd": float(self.sd), "basis": self.basis, "in_scope": bool(self.in_scope),
                "source": self.source}

    @classmethod
    def from_dict(cls, d: dict) -> "MethodBand":
        return cls(matrix=str(d["matrix"]), dofs=str(d["dofs"]),
                   distribution=str(d["distribution"]), sd=float(d["sd"]),
                   basis=str(d.get("basis", "measured")), in_scope=bool(d.get("in_scope", True)),
                   source=str(d.get("source", "")))


def band_sd(bands, matrix: str, i: int, j: int) -> float | None:
    r"""sd of ln of entry (i, j) of ``matrix`` under the method bands (None: no band).

    The method scales a matrix DOF by DOF, :math:`M'_{ij} = M_{ij}\sqrt{f_i f_j}` with
    :math:`\ln f = \sigma_g z_g`, one :math:`z_g` per DOF group (stripcoef.study.sources):
    so :math:`\sigma(\ln M'_{ij}) = \sigma_g` within a group and
    :math:`	frac12\sqrt{\sigma_{g_i}^2 + \sigma_{g_j}^2}` across two independent groups.
    """
    rows = {b.dofs: b.sd for b in bands if b.matrix == matrix and b.distribution == "lognormal"}
    if "all" in rows:
        return rows["all"]
    gi = next((g for g, idx in BAND_GROUPS.items() if i in idx and g in rows), None)
    gj = next((g for g, idx in BAND_GROUPS.items() if j in idx and g in rows), None)
    if gi is None or gj is None:
        return None
    return rows[gi] if gi == gj else 0.5 * float(np.hypot(rows[gi], rows[gj]))


def control_derivative_names(surfaces) -> dict:
    """SNAME names of every non-zero control derivative, e.g. ``Y_uudr``, ``M_uuds``.

    Two surfaces of the same kind are told apart by their name (``Y_uudr_<name>``).
    Naming after Prestero 2001, sec. 3.7 (Y_uudr, Z_uuds, M_uuds, N_uudr).
    """
    out: dict[str, float] = {}
    kinds = [s.kind for s in surfaces]
    for s in surfaces:
        pattern = CONTROL_NAMES.get(s.kind, "{F}_uud_" + s.name)
        scale = max(float(np.abs(s.derivative).max()), 1e-300)
        for i, f in enumerate(FORCES):
            if s.derivative[i] != 0.0 and abs(s.derivative[i]) > 1e-12 * scale:
                key = pattern.format(F=f)
                if kinds.count(s.kind) > 1:
                    key += "_" + s.name
                out[key] = float(s.derivative[i])
    return out


def lift_names() -> dict:
    """SNAME name of ``-L[i, j]`` (force -u L nu): ``Y_uv``, ``N_ur``, ... (Prestero 2001, sec. 3.6)."""
    return {(i, j): f"{FORCES[i]}_u{VELOCITIES[j]}" for i in range(6) for j in range(6)}


def plain(value):
    """Recursively convert numpy scalars/arrays to plain Python types (JSON/YAML safe)."""
    if isinstance(value, Mapping):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return plain(value.tolist())
    if isinstance(value, np.generic):
        return value.item()
    return value


@dataclass(frozen=True, eq=False)
class Conditions(Mapping):
    """The conditions a strip-theory model was computed at, and the factors it used.

    A typed record (``model.conditions.regime``) that also reads as the read-only mapping of
    the JSON output (``model.conditions["regime"]``, ``"k1" in c``): its keys are the fields
    that are set (not ``None``), in field order, then :attr:`extra`. :meth:`to_dict` is the
    ``conditions`` object of ``coefficients --json`` (docs/conventions.md). Which fields are
    set depends on the model: hull terms only with a hull part, ``blunt_hull_cd`` for a
    blunt hull, ``members``/``junction_pieces`` for per-member corrections, the
    ``end_correction_*`` factors with corrections and ``k1`` without.

    Attributes
    ----------
    reference_speed : float
        U, the speed of the Reynolds numbers and of the damping split [m/s]
    reference_rate : float
        Omega = U / (L/2), the rotation rate of the split [rad/s]
    reynolds_length : float
        Re_L = U L / nu [-]
    regime : str
        Friction regime used (laminar or turbulent)
    cf_laminar, cf_turbulent, cf_used : float
        Blasius and ITTC-1957 friction coefficients at Re_L, and the one used [-]
    wetted_area : float
        Hull wetted area S_wet [m^2]
    form_factor : float
        Hoerner form factor FF [-]
    axial_drag_coefficient_wetted, axial_drag_coefficient_frontal : float
        The hull's axial drag (without a blunt hull's end drag) on the wetted area, and the
        same drag on the frontal area [-]
    axial_drag_method : str
        How the hull's axial drag was obtained: ``form_factor`` (friction with Hoerner's
        streamlined-body form factor, closed hull of L/D >= 3), ``measured_short_body`` (the
        measured drag of ellipsoids, L/D <= 2), ``bridge`` (between the two), ``blunt``
        (flat bow: the measured drag of flat-ended bodies end-on, plus plain friction) or
        ``blunt_base`` (closed bow, flat stern: the measured drag of ellipsoids of its L/D,
        plus plain friction)
    blunt_hull_cd : float
        Axial whole-body drag coefficient of a blunt hull on its largest section [-]
    blunt_hull_aspect_ratio : float
        Width over height of that section, which sets a thin plate's drag [-]
    blunt_hull_cd_astern, surge_quadratic_damping_astern : float
        The same going astern [-], and D_Q[0, 0] with it [kg/m] (not in D_Q: going ahead)
    short_body_crossflow : mapping
        Per short part and direction, :func:`stripcoef.assembly.damping.short_body_crossflow`
    rotational_drag : mapping
        A bluff body's K_pp, M_qq, N_rr from its surface's pressure drag
        (:func:`stripcoef.assembly.damping.with_rotational_pressure_drag`): the element
        coefficients, their rule, the strips' values it replaced [kg m^2], the faces
    hull_reynolds_diameter : float
        Re on the hull's largest cross-flow extent [-]
    hull_crossflow_cd_y, hull_crossflow_cd_z : float
        2D cross-flow drag coefficients of the hull's largest section [-]
    hull_length_factor : float
        Finite-length factor kappa of the hull's cross-flow drag [-]
    equivalent_spheroid_L_over_D : float
        L/D of the equal-length, equal-volume spheroid [-]
    section_panels : int
        Panels per 2D polygon section, when given
    members, junction_pieces : int
        Members and junction pieces of per-member corrections
    end_correction_sway, end_correction_heave, end_correction_pitch, end_correction_yaw : float
        3D correction factors of the strip matrix' diagonal [-]
    k1 : float
        Lamb's axial coefficient of the equivalent spheroid (no corrections) [-]
    axial_added_mass : float
        m_11 [kg]
    correction_method : str
        How the 3D terms were obtained
    correction_panels : int
        Meridian panels of the axisymmetric solves
    added_mass_method : str
        How M_A was obtained when not by the strips (the 3D panel method)
    added_mass_panels : int
        Panels of the finest resolution of the panel method
    added_mass_panel_levels : tuple of int
        Panels of each resolution of the panel method, coarse to fine (its grid convergence
        study: :mod:`stripcoef.hull.convergence`)
    added_mass_converged : bool
        Whether every term's estimate (the levels' step plus last change) is within the
        tolerance (:data:`stripcoef.hull.panels.ERROR_TOLERANCE` of the diagonal scale)
    added_mass_error_max : float
        Largest term of the band shown over the diagonal scale [-] (four levels or more: Eça
        & Hoekstra's uncertainty, wider than the estimate; :attr:`HydroModel.added_mass_error`)
    mirror_planes : str
        The body's mirror planes through the reference point (``x``, ``y``, ``z``: the axis
        each reverses, or ``none``) whose forbidden couplings of M_A were set to exactly zero
        (:mod:`stripcoef.assembly.symmetry`; the 3D panel method)
    lift : mapping
        How the lift terms were built (body and fin lift, :mod:`stripcoef.assembly.lift`)
    strips : int
        Number of strips
    corrections : bool
        3D corrections on
    density : float
        rho [kg/m^3]
    kinematic_viscosity : float
        nu [m^2/s]
    fluid : str
        Source of the fluid properties
    length : float
        Body length L [m]
    breadth, height : float
        The body's largest extent along y and along z [m] (its box B x H; the UUV
        Simulator export's ``<box>``)
    extra : mapping
        Keys of a model file that are none of the above, kept as they were
    """

    reference_speed: float | None = None
    reference_rate: float | None = None
    reynolds_length: float | None = None
    regime: str | None = None
    cf_laminar: float | None = None
    cf_turbulent: float | None = None
    cf_used: float | None = None
    wetted_area: float | None = None
    form_factor: float | None = None
    axial_drag_coefficient_wetted: float | None = None
    axial_drag_coefficient_frontal: float | None = None
    axial_drag_method: str | None = None
    blunt_hull_cd: float | None = None
    blunt_hull_aspect_ratio: float | None = None
    blunt_hull_cd_astern: float | None = None
    surge_quadratic_damping_astern: float | None = None
    short_body_crossflow: Mapping | None = None
    rotational_drag: Mapping | None = None
    hull_reynolds_diameter: float | None = None
    hull_crossflow_cd_y: float | None = None
    hull_crossflow_cd_z: float | None = None
    hull_length_factor: float | None = None
    equivalent_spheroid_L_over_D: float | None = None
    section_panels: int | None = None
    members: int | None = None
    junction_pieces: int | None = None
    end_correction_sway: float | None = None
    end_correction_heave: float | None = None
    end_correction_pitch: float | None = None
    end_correction_yaw: float | None = None
    k1: float | None = None
    axial_added_mass: float | None = None
    correction_method: str | None = None
    correction_panels: int | None = None
    added_mass_method: str | None = None
    added_mass_panels: int | None = None
    added_mass_panel_levels: tuple | None = None
    added_mass_converged: bool | None = None
    added_mass_error_max: float | None = None
    mirror_planes: str | None = None
    lift: Mapping | None = None
    strips: int | None = None
    corrections: bool | None = None
    density: float | None = None
    kinematic_viscosity: float | None = None
    fluid: str | None = None
    length: float | None = None
    breadth: float | None = None
    height: float | None = None
    extra: Mapping = field(default_factory=dict)

    def __post_init__(self):
        object.__setattr__(self, "extra", frozen_mapping(self.extra))
        for name in ("lift", "short_body_crossflow", "rotational_drag"):
            if getattr(self, name) is not None:
                object.__setattr__(self, name, frozen_mapping(getattr(self, name)))

    @classmethod
    def from_dict(cls, data) -> "Conditions":
        """The conditions of a mapping (a model file's ``conditions``, or
        :meth:`to_dict`); keys that are not fields go to :attr:`extra`, in their order."""
        if isinstance(data, cls):
            return data
        names = {f.name for f in fields(cls)} - {"extra"}
        data = dict(data or {})
        return cls(**{k: v for k, v in data.items() if k in names},
                   extra={k: v for k, v in data.items() if k not in names})

    def _keys(self):
        return [f.name for f in fields(self)
                if f.name != "extra" and getattr(self, f.name) is not None] + list(self.extra)

    def __getitem__(self, key):
        if key in self.extra:
            return self.extra[key]
        if key != "extra" and key in self.__dataclass_fields__:
            value = getattr(self, key)
            if value is not None:
                return value
        raise KeyError(key)

    def __iter__(self):
        return iter(self._keys())

    def __len__(self):
        return len(self._keys())

    def __repr__(self):
        return f"Conditions({dict(self)!r})"

    def to_dict(self) -> dict:
        """The set fields then :attr:`extra`, as a plain dict (JSON ``conditions``)."""
        return {k: dict(v) if isinstance(v, Mapping) else v
                for k, v in ((k, self[k]) for k in self._keys())}


def frozen_array(value) -> np.ndarray:
    """A float copy of ``value`` that cannot be written to (``setflags(write=False)``)."""
    a = np.array(value, dtype=float)
    a.setflags(write=False)
    return a


def frozen_mapping(value) -> Mapping:
    """A read-only view of a shallow copy of ``value`` (a mapping; ``None`` = empty)."""
    return MappingProxyType(dict(value or {}))


#: the array fields of a HydroModel, frozen by ``__post_init__``
_ARRAYS = ("reference_point", "rigid_body_mass", "added_mass", "linear_damping",
           "quadratic_damping", "center_of_gravity", "center_of_buoyancy", "lift", "fin_munk_lift")


def coriolis_table(mass_matrix, *, munk: bool = True) -> np.ndarray:
    r"""The Coriolis-centripetal matrix of :func:`coriolis_from_mass` as a table linear in the
    velocity: row j the flattened :math:`K_j = C(e_j)` (6, 36), so that
    :math:`C(\nu) = \sum_j \nu_j K_j` (C is linear in nu; Fossen 2011, Theorem 3.2,
    eq. 3.46). ``munk=False`` zeroes the lower-left block (the moments from linear momentum,
    as :meth:`HydroModel.coriolis`). [kg, kg m, kg m^2]"""
    table = np.array([coriolis_from_mass(mass_matrix, e) for e in np.eye(6)])
    if not munk:
        table[:, 3:, :3] = 0.0
    return table.reshape(6, 36)


def velocity_product(table, d_l, nu) -> np.ndarray:
    r""":math:`(D_L + \sum_j z_j T_j)\,\nu` of one velocity (6,) or row by row of (n, 6)
    [m/s, rad/s] -> [N, N m]: ``table`` (6, 36) on :math:`z = \nu` or (12, 36) on
    :math:`z = [\nu, |\nu|]`, the flattened 6 x 6 matrices :math:`T_j`; ``d_l`` (36,) or
    ``None`` (:meth:`HydroModel.velocity_forces`; Fossen 2011, eq. 7.190)."""
    z = nu if table.shape[0] == 6 else np.concatenate([nu, np.abs(nu)], axis=-1)
    mat = z @ table if d_l is None else z @ table + d_l
    if nu.ndim == 1:
        return mat.reshape(6, 6) @ nu
    return np.einsum("nik,nk->ni", mat.reshape(-1, 6, 6), nu)


@dataclass(frozen=True)
class HydroModel:
    """A vehicle's hydrodynamic model about one reference point (FRD body axes).

    Immutable: the fields cannot be assigned, the arrays are read-only copies, the
    thrusters and effects are tuples, ``conditions`` a :class:`Conditions` and
    ``provenance`` a read-only mapping. A changed model is a new one: :func:`dataclasses.replace`,
    :meth:`about`, :meth:`with_effects`, :meth:`with_provenance`.

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
    thrusters : tuple of Thruster
    conditions : Conditions
        Reynolds numbers, regimes, drag coefficients and correction factors used (for
        reports); a dict given here is read by :meth:`Conditions.from_dict`
    effects : tuple of dict
        Extra force terms added by calibration (see :mod:`stripcoef.effects.laws`)
    provenance : mapping
        Where each part came from (method, options, file)
    lift : (6, 6)
        L, the speed-dependent linear (lift) terms: force ``-u L nu`` [kg/m, kg, kg m];
        ``-L[1, 1] = Y_uv``, ``-L[5, 5] = N_ur`` (docs/conventions.md; Prestero 2001, sec. 3.6)
    fin_munk_lift : (6, 6)
        dL, the lifting fins' Munk moment taken off C_A (their lift carries it): force ``-u dL
        nu`` [kg/m, kg, kg m], counted and dropped with C_A's Munk moment (:attr:`total_lift`)
    control_surfaces : tuple of ControlSurface
        Rudders and elevators: force ``u^2 b delta`` and deflection limits
    added_mass_error : (6, 6) or None
        Estimated absolute error of each term of M_A [kg, kg m, kg m^2] where the method
        gives one (the 3D panel method: its two resolutions' Richardson correction,
        :func:`stripcoef.hull.panels.panel_added_mass`); ``None`` otherwise
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
    kinematic_viscosity: float = NU_SEAWATER
    gravity: float = G
    thrusters: tuple[Thruster, ...] = ()
    conditions: Conditions = field(default_factory=Conditions)
    effects: tuple[dict, ...] = ()
    provenance: Mapping = field(default_factory=dict)
    lift: np.ndarray = field(default_factory=lambda: np.zeros((6, 6)))
    control_surfaces: tuple = ()
    bands: tuple = ()
    added_mass_error: np.ndarray | None = None
    fin_munk_lift: np.ndarray = field(default_factory=lambda: np.zeros((6, 6)))

    def __post_init__(self):
        for name in _ARRAYS:
            object.__setattr__(self, name, frozen_array(getattr(self, name)))
        if self.added_mass_error is not None:
            object.__setattr__(self, "added_mass_error", frozen_array(self.added_mass_error))
        object.__setattr__(self, "thrusters", tuple(self.thrusters))
        object.__setattr__(self, "control_surfaces", tuple(self.control_surfaces))
        object.__setattr__(self, "bands", tuple(self.bands))
        object.__setattr__(self, "effects", tuple(dict(e) if isinstance(e, Mapping) else e
                                                  for e in self.effects))
        object.__setattr__(self, "conditions", Conditions.from_dict(self.conditions))
        object.__setattr__(self, "provenance", frozen_mapping(self.provenance))

    def __reduce__(self):
        # pickling and copy.deepcopy rebuild the model from plain fields (a read-only
        # mapping cannot be pickled)
        args = tuple(v.to_dict() if isinstance(v, Conditions) else
                     dict(v) if isinstance(v, MappingProxyType) else v
                     for v in (getattr(self, f.name) for f in fields(self)))
        return (type(self), args)

    def with_effects(self, *entries) -> "HydroModel":
        """A copy with ``entries`` (effect dicts, see :mod:`stripcoef.effects.laws`) appended
        to :attr:`effects`."""
        return replace(self, effects=self.effects + tuple(entries))

    def with_provenance(self, **entries) -> "HydroModel":
        """A copy whose :attr:`provenance` has ``entries`` added (or replaced)."""
        return replace(self, provenance={**self.provenance, **entries})

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
        The lifting fins' share of it, which their lift carries, is taken off again by
        :attr:`fin_munk_lift`, counted with it (:meth:`damping` ``munk``).

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

    @property
    def total_lift(self) -> np.ndarray:
        """L + dL [kg/m, kg, kg m], the u-terms beside C_A with its Munk moment (the
        coefficients, every export; :mod:`stripcoef.assembly.fin_munk`)."""
        return self.lift + self.fin_munk_lift

    def damping(self, nu, *, munk: bool = True) -> np.ndarray:
        """D(nu) = D_L + u L + D_Q diag(|nu|) [kg/s, ...]; hydrodynamic force = -D(nu) nu;
        with C_A's Munk moment (``munk``) L holds :attr:`fin_munk_lift` (:attr:`total_lift`).

        ``nu`` [m/s, rad/s]; D_L [kg/s, kg m^2/s], D_Q [kg/m, kg m^2], L [kg/m, kg, kg m]
        (lift, :attr:`lift`). Quadratic diagonal drag of Wang & Clark 2006, eq. 7 (see module
        docstring, Fossen 2011, eq. 7.190); the lift terms are Prestero 2001's Y_uv u v ...
        (sec. 3.6), which the UUV Simulator calls the forward-speed linear damping.
        """
        nu = np.asarray(nu, dtype=float)
        table, d_l = self._velocity_terms(False, False, munk, True)   # velocity_forces' rule
        return (np.concatenate([nu, np.abs(nu)]) @ table + d_l).reshape(6, 6)

    def velocity_forces(self, nu, nu_r=None, *, coriolis: bool = True, munk: bool = True,
                        rigid_body: bool = True) -> np.ndarray:
        r"""The velocity-dependent forces [N, N m] of one velocity ``nu`` (6,) or many (n, 6)
        [m/s, rad/s]; ``nu_r`` the velocity through the water (``None``: no current):

        .. math::
            C_{RB}(\nu)\nu + C_A(\nu_r)\nu_r + D(\nu_r)\nu_r,\qquad
            C(\nu) + D(\nu) = D_L + \sum_j \nu_j K_j + \sum_j |\nu_j| Q_j

        (Fossen 2011, eq. 7.190; C of Theorem 3.2, eq. 3.46, as :meth:`coriolis`; D as
        :meth:`damping`, the lift :math:`uL` of Prestero 2001, sec. 3.6, in :math:`K_0`): C
        and D are linear in :math:`[\nu, |\nu|]`, so each row's matrix is one product with a
        12 x 36 table (:func:`coriolis_table`, :math:`Q_j = D_Q e_j e_j^T`) built once per
        model. ``coriolis=False`` drops both C, ``munk=False`` the Munk moment of C_A (each with
        :attr:`fin_munk_lift`), ``rigid_body=False`` C_RB. The one rule of the simulation's
        right-hand side, the diagnose batch simulation and the log windows' force terms.
        """
        nu = np.asarray(nu, dtype=float)
        if nu_r is None:
            table, d_l = self._velocity_terms(rigid_body and coriolis, coriolis,
                                              munk and coriolis, True)
            return velocity_product(table, d_l, nu)
        out = velocity_product(*self._velocity_terms(False, coriolis, munk and coriolis, True),
                                np.asarray(nu_r, dtype=float))
        if rigid_body and coriolis:
            out = out + velocity_product(*self._velocity_terms(True, False, munk, False), nu)
        return out

    @cached_property
    def _velocity_tables(self) -> dict:
        """:meth:`velocity_forces`' tables built so far, by choice of terms (immutable model)."""
        return {}

    def _velocity_terms(self, rigid_body: bool, added_mass: bool, munk: bool,
                        damping: bool) -> tuple:
        """(table on [nu, |nu|] (12, 36), or on nu (6, 36) without the damping; D_L (36,) or
        ``None``) of :meth:`velocity_forces`: row j :math:`K_j` (:func:`coriolis_table`, the
        lift L in row 0 with the damping, :attr:`fin_munk_lift` with ``munk``), row 6 + j
        :math:`Q_j = D_Q e_j e_j^T`."""
        key = (rigid_body, added_mass, munk, damping)
        tables = self._velocity_tables
        if key not in tables:
            table = np.zeros((12, 36))
            if rigid_body:
                table[:6] += coriolis_table(self.rigid_body_mass)
            if added_mass:
                table[:6] += coriolis_table(self.added_mass, munk=munk)
            d_l = None
            if damping:
                quad = np.zeros((6, 6, 6))
                for j in range(6):
                    quad[j][:, j] = np.asarray(self.quadratic_damping, dtype=float)[:, j]
                table[6:] = quad.reshape(6, 36)
                table[0] += (self.total_lift if munk else self.lift).reshape(36)
                d_l = np.asarray(self.linear_damping, dtype=float).reshape(36)
            tables[key] = (table if damping else table[:6].copy(), d_l)
        return tables[key]

    @property
    def control_matrix(self) -> np.ndarray:
        """B_delta (6 x n_surfaces): force ``u^2 B_delta delta`` [N/((m/s)^2 rad), ...]
        (:class:`ControlSurface`; Prestero 2001, sec. 3.7)."""
        if not self.control_surfaces:
            return np.zeros((6, 0))
        return np.column_stack([np.asarray(s.derivative, float) for s in self.control_surfaces])

    def control_force(self, u: float, deflections) -> np.ndarray:
        r"""Generalized force of the control surfaces, :math:`u^2 B_\delta \delta` [N, N m].

        ``u`` surge speed through the water [m/s]; ``deflections`` [rad], one per surface
        (Prestero 2001, sec. 3.7; :class:`ControlSurface`).
        """
        return u * abs(u) * (self.control_matrix @ np.asarray(deflections, dtype=float))

    def surface(self, name: str) -> ControlSurface:
        for s in self.control_surfaces:
            if s.name == name:
                return s
        raise unknown_name("control surface", name, [s.name for s in self.control_surfaces])

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
        raise unknown_name("thruster", name, [t.name for t in self.thrusters])

    def coefficients(self) -> dict:
        """Every SNAME derivative by name, with its SNAME sign: added mass, damping, lift
        (``Y_uv = -L[1, 1]``...) and control derivatives (``Y_uudr``...; Prestero 2001,
        secs. 3.6-3.7)."""
        out = sname_coefficients(self.added_mass, self.linear_damping, self.quadratic_damping,
                                 tol=1e-12)
        lift = self.total_lift
        scale = max(float(np.abs(lift).max()), 1e-300)
        for (i, j), name in lift_names().items():
            if lift[i, j] != 0.0 and abs(lift[i, j]) > 1e-12 * scale:
                out[name] = -float(lift[i, j])
        out.update(control_derivative_names(self.control_surfaces))
        return out

    def coefficient_bands(self) -> dict:
        r"""The 95 % method band of every coefficient of :meth:`coefficients` that has one:
        name -> (low, high), in the coefficient's units and SNAME sign.

        A term scaled by the method's lognormal factors lies in
        :math:`[c\,e^{-1.96\sigma}, c\,e^{1.96\sigma}]` (:func:`band_sd`); an added-mass
        coupling moves additively, :math:`c \pm 1.96\,\sigma_c \sqrt{M_{ii}M_{jj}}`; lift
        terms and control derivatives take their one factor. Empty without :attr:`bands`.
        """
        if not self.bands:
            return {}
        coeffs = self.coefficients()
        named = {}
        for matrix, namer, m in (("added_mass", added_mass_name, self.added_mass),
                                 ("linear_damping", linear_damping_name, self.linear_damping),
                                 ("quadratic_damping", quadratic_damping_name,
                                  self.quadratic_damping)):
            for i in range(6):
                for j in range(6):
                    named[namer(i, j)] = (matrix, i, j, m)
        named.update({n: ("lift", i, j, self.total_lift) for (i, j), n in lift_names().items()})
        coupling = next((b.sd for b in self.bands if b.matrix == "added_mass"
                         and b.dofs == "coupling"), None)
        control = next((b.sd for b in self.bands if b.matrix == "control"), None)
        out = {}
        for name, value in coeffs.items():
            if "_uud" in name:
                sd = control
            elif name in named:
                matrix, i, j, m = named[name]
                if matrix == "added_mass" and i != j and coupling is not None:
                    half = Z95 * coupling * float(np.sqrt(abs(m[i, i] * m[j, j])))
                    out[name] = (value - half, value + half)
                    continue
                sd = band_sd(self.bands, matrix, i, j)
            else:
                sd = None
            if sd is not None:
                lo, hi = value * np.exp(-Z95 * sd), value * np.exp(Z95 * sd)
                out[name] = (float(min(lo, hi)), float(max(lo, hi)))
        return out

    # -- labelled views (stripcoef.views) -------------------------------------
    def frame(self, kind: str = "added_mass"):
        """One matrix (``rigid_body_mass``, ``added_mass``, ``linear_damping``,
        ``quadratic_damping``) as a pandas DataFrame labelled with the DOFs, units in
        ``frame.attrs["units"]`` (:func:`stripcoef.views.matrix_frame`; needs pandas)."""
        if kind not in MATRICES:
            raise unknown_name("matrix", kind, MATRICES, key="kind")
        return matrix_frame(getattr(self, kind), kind)

    def _repr_html_(self) -> str:
        """What a notebook shows: mass properties and the four labelled matrices."""
        return model_html(self)

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
        shift = shift_operator(-(point - old)).T     # tau_P = H(-r)^T tau_O
        surfaces = tuple(replace(s, derivative=shift @ np.asarray(s.derivative, float))
                         for s in self.control_surfaces)
        error = self.added_mass_error
        if error is not None:
            # a bound: |H^T dA H| <= |H|^T |dA| |H| term by term (triangle inequality)
            h = np.abs(shift_operator(-(point - old)))
            error = h.T @ np.asarray(error) @ h
        return replace(self, reference_point=point, rigid_body_mass=t(self.rigid_body_mass),
                       added_mass=t(self.added_mass), linear_damping=t(self.linear_damping),
                       quadratic_damping=dq, lift=t(self.lift), control_surfaces=surfaces,
                       added_mass_error=error, fin_munk_lift=t(self.fin_munk_lift))

    # -- serialisation ------------------------------------------------------
    def to_dict(self) -> dict:
        """The JSON output contract (docs/conventions.md): ``lift`` is :attr:`total_lift`,
        ``fin_munk_lift`` (where not zero) the part of it :attr:`fin_munk_lift`."""
        def mat(m):
            return [[float(x) for x in row] for row in np.asarray(m)]

        out = {
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
            "conditions": plain(self.conditions.to_dict()),
            "effects": plain(self.effects),
            "provenance": plain(self.provenance),
            "lift": mat(self.total_lift),
            "control_surfaces": [c.to_dict() for c in self.control_surfaces],
            "bands": [b.to_dict() for b in self.bands],
            "coefficient_bands": {k: list(v) for k, v in self.coefficient_bands().items()},
        }
        if self.added_mass_error is not None:
            out["added_mass_error"] = mat(self.added_mass_error)
        if np.any(self.fin_munk_lift):
            out["fin_munk_lift"] = mat(self.fin_munk_lift)
        return out

    @classmethod
    def from_dict(cls, data: dict) -> "HydroModel":
        """Inverse of :meth:`to_dict` (used by model files and round trips)."""
        thr = [Thruster(name=t["name"], position=np.asarray(t["position"], float),
                        direction=np.asarray(t["direction"], float),
                        ct_forward=t.get("ct_forward", 1.0), ct_backward=t.get("ct_backward", 1.0),
                        max_forward=Thruster.limit_from_data(t.get("max_forward")),
                        max_backward=Thruster.limit_from_data(t.get("max_backward")),
                        eta_forward=t.get("eta_forward", 1.0),
                        eta_backward=t.get("eta_backward", 1.0),
                        deadband=t.get("deadband", 0.0),
                        torque_ratio=t.get("torque_ratio", 0.0))
               for t in data.get("thrusters", [])]
        fin = np.asarray(data.get("fin_munk_lift", np.zeros((6, 6))), float)
        lift = np.asarray(data.get("lift", np.zeros((6, 6))), float) - fin   # lift: L + dL
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
            kinematic_viscosity=float(data.get("kinematic_viscosity", NU_SEAWATER)),
            gravity=float(data.get("gravity", G)),
            thrusters=thr, conditions=data.get("conditions", {}),
            effects=list(data.get("effects", [])), provenance=data.get("provenance", {}),
            lift=lift, fin_munk_lift=fin,
            control_surfaces=tuple(ControlSurface.from_dict(c)
                                   for c in data.get("control_surfaces", [])),
            bands=tuple(MethodBand.from_dict(b) for b in data.get("bands", [])),
            added_mass_error=(None if data.get("added_mass_error") is None
                              else np.asarray(data["added_mass_error"], float)),
        )

r"""Shared pieces of the exporters: the reference point, the axes and the warning class.

Every exporter works on an :class:`ExportView`: the model moved to the chosen
reference point with :meth:`stripcoef.model.HydroModel.about` and its matrices
and vectors expressed in the chosen axes with
:func:`stripcoef.conventions.transform_matrix` / :func:`~stripcoef.conventions.transform_vector`.
No exporter transforms a matrix any other way.
"""

from __future__ import annotations

import math
import sys
import warnings
from dataclasses import dataclass
from typing import Callable

import numpy as np

from stripcoef import __version__
from stripcoef.conventions import AXES, DOF, axes_operator, transform_matrix, transform_vector
from stripcoef.errors import InputError, ModelWarning
from stripcoef.model import HydroModel
from stripcoef.physical import check_physical

#: Names of the special reference points (see :func:`resolve_point`).
POINT_NAMES = ("CO", "CG", "CB", "origin")
#: Name -> (label, HydroModel attribute); the long names are those of the vehicle file's
#: ``reference_point`` key; "origin" is the origin of the vehicle file's coordinates.
_NAMED_POINTS = {
    "CO": ("CO", "reference_point"), "reference_point": ("CO", "reference_point"),
    "CG": ("CG", "center_of_gravity"), "center_of_gravity": ("CG", "center_of_gravity"),
    "CB": ("CB", "center_of_buoyancy"), "center_of_buoyancy": ("CB", "center_of_buoyancy"),
    "origin": ("origin", None),
}
POINT_EXPECTED = ("CO, CG, CB, origin or three finite numbers x,y,z [m] in the model's FRD "
                  "body coordinates")


@dataclass(frozen=True)
class ExportFormat:
    """One export format, the entry of the registry :data:`stripcoef.export.FORMATS`.

    Each format module defines ``FORMAT = ExportFormat(...)`` beside its ``render``.

    Attributes
    ----------
    name : str
        The format's name (``--to``)
    description : str
        One line for the CLI's help
    suffix : str
        File suffix of its files
    render : callable
        ``render(view, **options) -> str | bytes`` of an :class:`ExportView`
    binary : bool
        ``render`` returns bytes (the CLI then needs ``-o``)
    axes_allowed : tuple of str
        Axes the matrices may be written in (``FRD``, ``FLU``)
    default_axes : str
    default_point : str
        Reference point when none is asked for (``CO``: the model's own)
    points_allowed : tuple of str, optional
        The only points the format may be expressed about (None: any)
    holds_effects : bool
        The model's calibrated ``effects`` fit the format (else a SimulatorTrapWarning)
    options : tuple of str
        Keyword options of ``render`` (``link_name``, ``legacy_added_mass``,
        ``function_name``); any other is an error
    """

    name: str
    description: str
    suffix: str
    render: Callable
    binary: bool = False
    axes_allowed: tuple = AXES
    default_axes: str = "FRD"
    default_point: str = "CO"
    points_allowed: tuple | None = None
    holds_effects: bool = False
    options: tuple = ()


class SimulatorTrapWarning(ModelWarning):
    """An exported model would run into a known simulator trap, or a term the format cannot hold.

    Examples: added mass larger than the rigid-body mass in an engine that applies
    added mass explicitly (gz-sim issue #1923), quadratic cross terms that the UUV
    Simulator plugin ignores (it reads only the diagonal), an asymmetric added-mass
    matrix written to a format that stores only 21 elements.
    """


def trap(message: str) -> None:
    """Issue a :class:`SimulatorTrapWarning` pointing at the first caller outside this package."""
    frame, level = sys._getframe(1), 2
    while frame is not None and frame.f_globals.get("__name__", "").startswith(__package__):
        frame, level = frame.f_back, level + 1
    warnings.warn(message, SimulatorTrapWarning, stacklevel=level)


def resolve_point(model: HydroModel, point) -> tuple[np.ndarray, str]:
    """The reference point as coordinates in FRD body axes and a label.

    Parameters
    ----------
    model : HydroModel
    point : str or sequence of 3 numbers
        ``"CO"`` (the model's own reference point), ``"CG"``, ``"CB"`` (also spelt
        ``reference_point``, ``center_of_gravity``, ``center_of_buoyancy``), ``"origin"``
        (the origin of the model's coordinates), a point ``(x, y, z)`` [m] or the string
        ``"x,y,z"``, in the model's FRD body coordinates.

    Returns
    -------
    (3,) array [m], str
    """
    if isinstance(point, str):
        key = point.strip()
        named = _NAMED_POINTS.get(key.upper()) or _NAMED_POINTS.get(key.lower())
        if named is not None:
            label, attr = named
            xyz = np.zeros(3) if attr is None else getattr(model, attr)
            return np.asarray(xyz, dtype=float).copy(), label
        parts = [p for p in key.replace(";", ",").split(",")]
        if len(parts) != 3:
            raise InputError("not a reference point", key="point", value=point,
                             expected=POINT_EXPECTED)
        try:
            values = [float(p) for p in parts]
        except ValueError:
            raise InputError("not a reference point", key="point", value=point,
                             expected=POINT_EXPECTED) from None
    else:
        try:
            values = [float(v) for v in point]
        except (TypeError, ValueError):
            raise InputError("not a reference point", key="point", value=point,
                             expected=POINT_EXPECTED) from None
        if len(values) != 3:
            raise InputError("not a reference point", key="point", value=point,
                             expected=POINT_EXPECTED)
    if not all(math.isfinite(v) for v in values):
        raise InputError("not a reference point", key="point", value=point,
                         expected=POINT_EXPECTED)
    arr = np.asarray(values, dtype=float)
    return arr, "(" + ", ".join(fmt(v) for v in arr) + ")"


def check_axes(axes: str, allowed=AXES, *, fmt_name: str = "") -> str:
    """Validate an axes name against what a format can express."""
    if not isinstance(axes, str) or axes.upper() not in AXES:
        raise InputError("unknown axes", key="axes", value=axes, expected="FRD or FLU")
    axes = axes.upper()
    if axes not in allowed:
        raise InputError(f"format {fmt_name} is written in {' or '.join(allowed)} axes only",
                         key="axes", value=axes, expected=" or ".join(allowed))
    return axes


@dataclass
class ExportView:
    """A model seen from one reference point in one set of axes.

    Attributes
    ----------
    model : HydroModel
        The model about ``point`` (FRD body axes), from :meth:`HydroModel.about`
    source : HydroModel
        The model as given
    point : (3,) array
        The reference point in the source model's FRD body coordinates [m]
    point_label : str
        "CO", "CG", "CB" or the coordinates
    axes : str
        "FRD" or "FLU"
    """

    model: HydroModel
    source: HydroModel
    point: np.ndarray
    point_label: str
    axes: str

    @classmethod
    def of(cls, model: HydroModel, point, axes: str) -> "ExportView":
        check_physical(model)     # no impossible model (negative damping...) is exported
        xyz, label = resolve_point(model, point)
        moved = model.about(xyz)
        for name in ("rigid_body_mass", "added_mass", "linear_damping", "quadratic_damping"):
            if not np.all(np.isfinite(getattr(moved, name))):
                raise InputError("the matrices are not finite about this point", key="point",
                                 value=point, expected="a reference point near the vehicle")
        return cls(model=moved, source=model, point=xyz, point_label=label, axes=axes)

    def matrix(self, name: str) -> np.ndarray:
        """A 6x6 matrix of the model about the view's point, in the view's axes.

        ``name`` is one of rigid_body_mass, added_mass, linear_damping, quadratic_damping,
        lift (:attr:`HydroModel.total_lift`: L with the lifting fins' Munk compensation, the
        u-terms beside the simulator's C_A with its Munk moment). The axis change is
        :func:`transform_matrix` (``T A T`` with T = diag(1,-1,-1,1,-1,-1)
        for FLU), also exact for D_Q because ``|T nu| = |nu|``.
        """
        return transform_matrix(getattr(self.model, "total_lift" if name == "lift" else name),
                                axes=self.axes)

    def vector(self, vec) -> np.ndarray:
        """A 3-vector of FRD body axes in the view's axes."""
        return transform_vector(vec, axes=self.axes)

    def relative(self, xyz) -> np.ndarray:
        """A point of the model (FRD coordinates) relative to the view's point, in its axes."""
        return self.vector(np.asarray(xyz, dtype=float) - self.point)

    @property
    def r_g(self) -> np.ndarray:
        """CG relative to the view's point, in its axes [m]."""
        return self.relative(self.model.center_of_gravity)

    @property
    def r_b(self) -> np.ndarray:
        """CB relative to the view's point, in its axes [m]."""
        return self.relative(self.model.center_of_buoyancy)

    def inertia_about_cg(self) -> np.ndarray:
        r"""Inertia tensor about the CG in the view's axes [kg m^2].

        The lower-right block of M_RB moved to the CG with :func:`transform_matrix`
        (Fossen 2011, eq. 3.37 in reverse): :math:`I_g = I_o + m S(r_g)^2`.
        """
        m = transform_matrix(self.model.rigid_body_mass, from_point=self.model.reference_point,
                             to_point=self.model.center_of_gravity, axes=self.axes)
        return m[3:, 3:]

    def allocation(self) -> np.ndarray:
        """Thruster allocation matrix B (6 x n) about the view's point, in its axes."""
        b = self.model.allocation()
        if b.size == 0:
            return b
        return self.vector6(b)

    def vector6(self, v) -> np.ndarray:
        """Generalized forces/velocities (rows in DOF order) in the view's axes."""
        return axes_operator(self.axes) @ np.asarray(v, dtype=float)


def fmt(x) -> str:
    """Shortest text that reads back as the same double (``repr``), ``-0`` written as ``0``."""
    x = float(x)
    if x == 0.0:
        return "0"
    if math.isinf(x):
        return "Inf" if x > 0 else "-Inf"
    text = repr(x)
    if text.endswith(".0"):
        text = text[:-2]
    return text


def is_symmetric(m, *, rtol: float = 1e-9) -> tuple[bool, float]:
    """Whether a matrix is symmetric to ``rtol`` of its largest entry; and the largest asymmetry."""
    m = np.asarray(m, dtype=float)
    asym = float(np.abs(m - m.T).max())
    scale = max(float(np.abs(m).max()), 1e-300)
    return asym <= rtol * scale, asym


def header_lines(view: ExportView, fmt_name: str) -> list[str]:
    """Provenance lines every text export starts with (as comments)."""
    m = view.model
    lines = [
        f"{m.name}: hydrodynamic model exported by stripcoef {__version__} to format '{fmt_name}'",
        f"reference point: {view.point_label} = "
        f"[{', '.join(fmt(v) for v in view.point)}] m (FRD body coordinates of the source model)",
        f"axes: {view.axes} (x forward, " +
        ("y starboard, z down)" if view.axes == "FRD" else "y port, z up)"),
        f"mass {fmt(m.mass)} kg, volume {fmt(m.volume)} m^3, density {fmt(m.density)} kg/m^3",
    ]
    # the method's uncertainty beside the point values
    lines += [f"method band {b.matrix} {b.dofs}: 95 % within {b.describe()}" for b in m.bands]
    return lines


def xml_comment(lines) -> list[str]:
    """Lines of an XML comment (``--`` is not allowed inside one; nothing is escaped)."""
    return ["<!--", *("  " + str(line).replace("--", "- -") for line in lines), "-->"]


def clean(m, *, rtol: float = 1e-13) -> np.ndarray:
    """A copy of ``m`` with round-off entries (below ``rtol`` of its largest) set to zero.

    Used for the simulator files (gazebo, uuv, mss), so that transforms do not litter them
    with 1e-18 values; the data formats keep every bit.
    """
    m = np.array(m, dtype=float)
    scale = float(np.abs(m).max()) if m.size else 0.0
    m[np.abs(m) <= rtol * scale] = 0.0
    return m


def explicit_added_mass_trap(prefix: str, added_mass, rigid_body_mass, why: str) -> None:
    """Warn when an engine that applies added mass explicitly gets M_A[i,i] > M_RB[i,i].

    Explicit added mass, -M_A times the previous step's (finite-difference) acceleration,
    is an unstable feedback when M_A outweighs the rigid body: gz-sim issue #1923
    ("Unbounded velocity growth"); UUV Simulator HydrodynamicModel.cc, ComputeAcc comment
    ("This can lead to an oscillating system"), issues #181 and #96.
    """
    ma = np.asarray(added_mass, dtype=float)
    mrb = np.asarray(rigid_body_mass, dtype=float)
    big = [f"{DOF[i]} (M_A {ma[i, i]:.4g} > M_RB {mrb[i, i]:.4g})"
           for i in range(6) if ma[i, i] > mrb[i, i]]
    if big:
        trap(f"{prefix}: added mass exceeds the rigid-body term in " + ", ".join(big)
             + f"; {why}")

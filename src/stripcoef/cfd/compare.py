r"""The model's damping beside OpenFOAM's, DOF by DOF (``stripcoef cfd --compare``).

The model (:func:`stripcoef.assembly.estimate`, the default correlations) and the CFD runs
give the same law per DOF (Fossen 2011, sec. 6.4),

.. math:: F = -(d_L u + d_Q u |u|)

with :math:`d_L` [N s/m] and :math:`d_Q` [N s^2/m^2] (rotations [N m s/rad], [N m s^2/rad^2]).
A CFD run at one speed cannot split the two: its :math:`d_Q` is the whole force over
:math:`u^2`. The fair comparison is therefore the damping force at the speed the CFD ran,

.. math:: F_\mathrm{model}(u) = d_{L,\mathrm{model}} u + d_{Q,\mathrm{model}} u |u|

against the CFD's :math:`|F|` on its finest mesh, and their ratio; the quadratic and linear
terms are listed too. The model is estimated with the CFD's water and first speed, moments
about the same point (the origin of the surface the CFD ran: the mesh's volume centroid, or a
vehicle file's origin), so a rotation is compared about the same axis.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from stripcoef.cfd.case import DOFS


@dataclass(frozen=True)
class CompareRow:
    """One DOF: the model's damping beside the CFD's.

    Attributes
    ----------
    dof : str
    speed : float
        The speed [m/s] or rate [rad/s] of the CFD's first (finest-mesh) run.
    cfd_d_quadratic, model_d_quadratic : float
        d_Q [N s^2/m^2] ([N m s^2/rad^2]).
    cfd_d_linear, model_d_linear : float or None
        d_L [N s/m] ([N m s/rad]); the CFD's only from two speeds.
    cfd_force, model_force : float
        Damping force [N] (moment [N m]) at ``speed``, opposing the motion (positive):
        the CFD's mean force on its finest mesh; the model's ``d_L u + d_Q u |u|``.
    ratio : float
        model_force / cfd_force [-] (NaN when the CFD force is not positive).
    mesh_spread : float or None
        The CFD's mesh spread (:attr:`stripcoef.cfd.result.DofResult.mesh_spread`).
    converged : bool
        Every CFD run of the DOF converged.
    """

    dof: str
    speed: float
    cfd_d_quadratic: float
    model_d_quadratic: float
    cfd_d_linear: float | None
    model_d_linear: float
    cfd_force: float
    model_force: float
    ratio: float
    mesh_spread: float | None
    converged: bool

    def to_dict(self) -> dict:
        return {"dof": self.dof, "speed": self.speed,
                "cfd_d_quadratic": self.cfd_d_quadratic,
                "model_d_quadratic": self.model_d_quadratic,
                "cfd_d_linear": self.cfd_d_linear, "model_d_linear": self.model_d_linear,
                "cfd_force": self.cfd_force, "model_force": self.model_force,
                "ratio": self.ratio, "mesh_spread": self.mesh_spread,
                "converged": self.converged}

    @classmethod
    def from_dict(cls, d: dict) -> CompareRow:
        return cls(**{k: d[k] for k in cls.__dataclass_fields__})


def compare_rows(result, linear_damping, quadratic_damping) -> tuple[CompareRow, ...]:
    """The model's diagonal damping (D_L, D_Q: (6, 6) [Fossen's positive convention]) beside
    each DOF of a :class:`~stripcoef.cfd.result.CfdResult`."""
    rows = []
    for d in result.dofs:
        i = DOFS[d.dof][0] + (3 if DOFS[d.dof][1] else 0)
        fine = d.runs[0]
        u = float(fine.speed)
        dl, dq = float(linear_damping[i][i]), float(quadratic_damping[i][i])
        f_model = dl * u + dq * u * abs(u)
        f_cfd = -float(fine.force)
        ratio = f_model / f_cfd if math.isfinite(f_cfd) and f_cfd > 0 else float("nan")
        rows.append(CompareRow(dof=d.dof, speed=u, cfd_d_quadratic=d.d_quadratic,
                               model_d_quadratic=dq, cfd_d_linear=d.d_linear,
                               model_d_linear=dl, cfd_force=f_cfd, model_force=f_model,
                               ratio=ratio, mesh_spread=d.mesh_spread,
                               converged=d.converged))
    return tuple(rows)


#: Panels per 2D section of the comparison model's strip added mass (:func:`model_for`): the
#: damping compared does not read the added mass (``assembly.damping.damping_matrices`` takes
#: the strips, not M_A), so the coarse count only saves time: the stored CFD cases' damping
#: matrices and docs/validation.md's cfd section identical bit for bit to the default
#: adaptive count, validation.cfd.stored() 8.1-9.6 -> 3.8 s of CPU (docs/performance.md).
COMPARE_SECTION_PANELS = 16


def model_for(vehicle, *, speed: float, fluid):
    """The default model of ``vehicle`` for the comparison: the CFD's water and speed,
    moments about the vehicle's origin (where the CFD's surface has its origin), strip
    theory's added mass on :data:`COMPARE_SECTION_PANELS` panels per section (only the
    damping is compared, and it does not read the added mass; the panel method would cost
    time)."""
    from stripcoef.assembly import EstimateOptions, estimate

    return estimate(vehicle, EstimateOptions(speed=speed, reference_point="origin",
                                             fluid=fluid, added_mass_method="strips",
                                             section_panels=COMPARE_SECTION_PANELS))


def comparison_speed(result) -> float:
    """The speed [m/s] the model is estimated at: the first translation's, else the first
    rotation's tip speed ``rate L / 2`` (the model's own rate is ``U / (L/2)``)."""
    first = result.dofs[0].runs[0].speed
    translation = [d for d in result.dofs if not DOFS[d.dof][1]]
    return float(translation[0].runs[0].speed if translation else first * 0.5 * result.length)


def with_comparison(result, vehicle, *, fluid, model=None):
    """``result`` with its :attr:`~stripcoef.cfd.result.CfdResult.comparison` filled from
    the default model of ``vehicle`` (or ``model``, one :func:`model_for` gave for
    :func:`comparison_speed`)."""
    from dataclasses import replace

    if not result.dofs:
        return result
    speed = comparison_speed(result)
    if model is None:
        model = model_for(vehicle, speed=speed, fluid=fluid)
    return replace(result, comparison=compare_rows(result, model.linear_damping,
                                                   model.quadratic_damping),
                   compare_model={"name": model.name, "speed": float(speed),
                                  "reference_point": [float(v) for v in
                                                      model.reference_point]})


__all__ = ["COMPARE_SECTION_PANELS", "CompareRow", "compare_rows", "comparison_speed", "model_for", "with_comparison"]

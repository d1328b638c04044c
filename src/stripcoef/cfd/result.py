r"""The result of ``stripcoef cfd``: the runs, the damping terms per DOF and how sure they are.

Damping follows Fossen (Handbook of Marine Craft Hydrodynamics and Motion Control, 2011,
sec. 6.4): the hydrodynamic damping force of a DOF moving at speed :math:`u` is

.. math:: F = -(d_L u + d_Q u |u|)

with :math:`d_L` [N s/m] (the diagonal of D_L) and :math:`d_Q` [N s^2/m^2] (of D_Q), both
positive for a dissipative body; SNAME names them ``X_u = -d_L``, ``X_uu = -d_Q`` (surge),
``Y_v``, ``Z_w``, ``K_p``, ``M_q``, ``N_r`` and their quadratic twins. A rotation has the
same law in [N m s/rad] and [N m s^2/rad^2].
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from stripcoef.cfd.forces import DRIFT_TOLERANCE, SWING_TOLERANCE, Settled
from stripcoef.errors import InputError

#: SNAME names of the linear and quadratic damping derivatives per DOF.
NAMES = {"surge": ("X_u", "X_uu"), "sway": ("Y_v", "Y_vv"), "heave": ("Z_w", "Z_ww"),
         "roll": ("K_p", "K_pp"), "pitch": ("M_q", "M_qq"), "yaw": ("N_r", "N_rr")}
#: Status of a run.
CONVERGED, NOT_CONVERGED, DIVERGED = "converged", "not converged", "diverged"
#: Roache's grid convergence index for two meshes (:attr:`DofResult.gci`): safety factor,
#: refinement ratio of the surface cells, formal order of the schemes.
GCI_SAFETY, GCI_RATIO, GCI_ORDER = 3.0, 2.0, 2.0


def run_folder(path) -> str:
    """A run's case folder as a result stores it: its name under the result's ``case_dir``
    (older results stored the whole path; a stored result names no folder of the machine
    that wrote it)."""
    from pathlib import PurePath

    return PurePath(str(path)).name


def fit_damping(speeds, forces) -> tuple[float | None, float]:
    r"""Linear and quadratic damping from the force at one or more speeds.

    .. math:: F_i = -(d_L u_i + d_Q u_i |u_i|)

    solved by least squares (exactly for two speeds); one speed gives :math:`d_Q = -F /
    (u|u|)` and no :math:`d_L` (``None``).

    Parameters
    ----------
    speeds : array
        Speeds [m/s] or rates [rad/s], not zero, at least two different for d_L.
    forces : array
        Force [N] or moment [N m] along the motion at each speed.

    Returns
    -------
    (d_L or None, d_Q)
        [N s/m], [N s^2/m^2] (rotation: [N m s/rad], [N m s^2/rad^2]).

    References
    ----------
    Fossen (2011), eq. 6.57-6.63 (linear plus quadratic damping).
    """
    u = np.asarray(speeds, float)
    f = np.asarray(forces, float)
    if u.size == 0 or u.shape != f.shape or np.any(u == 0):
        raise InputError("speeds and forces do not match", key="speeds", value=u.tolist(),
                         expected="as many non-zero speeds as forces")
    if np.unique(np.abs(u)).size < 2:
        return None, float(-np.mean(f / (u * np.abs(u))))
    a = np.column_stack([u, u * np.abs(u)])
    (d_l, d_q), *_ = np.linalg.lstsq(a, -f, rcond=None)
    return float(d_l), float(d_q)


@dataclass(frozen=True)
class RunResult:
    """One OpenFOAM run: one DOF, one speed, one mesh level.

    Attributes
    ----------
    dof : str
    speed : float
        [m/s] or [rad/s].
    level : int
        Surface cells ``size / 2**level``.
    cells : int
    iterations : int
    status : str
        ``converged`` (the residuals met, or the mean force settled with a bounded swing:
        :attr:`stripcoef.cfd.forces.Settled.settled`), ``not converged`` (neither) or
        ``diverged`` (a NaN, or the solver stopped).
    force : float
        Mean force [N] (moment [N m]) along the motion over the last 100 iterations.
    swing : float
        Peak-to-peak of that force over the window, relative to it [-].
    drift : float
        Change of the mean from the window before, relative to it [-].
    force_vector, moment_vector : tuple
        Mean total force [N] and moment [N m] about the reference point, body axes.
    case : str
        The case folder's name under :attr:`CfdResult.case_dir`.
    note : str
        Why it is not converged, the failed mesh checks.
    cpu_seconds, wall_seconds : float
        CPU time of OpenFOAM's programs, all ranks [s]; wall-clock time of the run [s].
    y_plus : tuple or None
        The body's y+ at the end: min, max, mean over its faces
        (:func:`stripcoef.cfd.forces.read_y_plus`); None if not written.
    """

    dof: str
    speed: float
    level: int
    cells: int
    iterations: int
    status: str
    force: float
    swing: float
    drift: float
    force_vector: tuple
    moment_vector: tuple
    case: str
    note: str = ""
    cpu_seconds: float = 0.0
    wall_seconds: float = 0.0
    y_plus: tuple | None = None

    @property
    def converged(self) -> bool:
        return self.status == CONVERGED

    def to_dict(self) -> dict:
        return {"dof": self.dof, "speed": self.speed, "level": self.level, "cells": self.cells,
                "iterations": self.iterations, "status": self.status, "force": self.force,
                "swing": self.swing, "drift": self.drift, "force_vector": list(self.force_vector),
                "moment_vector": list(self.moment_vector), "case": self.case,
                "note": self.note, "cpu_seconds": self.cpu_seconds,
                "wall_seconds": self.wall_seconds,
                **({} if self.y_plus is None else {"y_plus": list(self.y_plus)})}

    @classmethod
    def from_dict(cls, d: dict) -> RunResult:
        """A run back from :meth:`to_dict` (a stored ``--json`` result)."""
        kw = {k: d[k] for k in cls.__dataclass_fields__ if k in d}
        kw["force_vector"] = tuple(kw["force_vector"])
        kw["moment_vector"] = tuple(kw["moment_vector"])
        kw["case"] = run_folder(kw["case"])
        if kw.get("y_plus") is not None:
            kw["y_plus"] = tuple(kw["y_plus"])
        return cls(**kw)


@dataclass(frozen=True)
class DofResult:
    """The damping of one DOF from its runs.

    Attributes
    ----------
    dof : str
    runs : tuple of RunResult
        The finest level at every speed, then the coarser level at the first speed.
    d_linear : float or None
        d_L [N s/m] ([N m s/rad]) when two speeds were run.
    d_quadratic : float
        d_Q [N s^2/m^2] ([N m s^2/rad^2]) on the finest mesh.
    mesh_spread : float or None
        |d_Q(fine) - d_Q(coarse)| / d_Q(fine) at the first speed [-]: the estimate of the
        discretisation error (None with one level).
    drag_coefficient : float or None
        C_D = d_Q / (rho A / 2) (translation; A the frontal area).
    reference_area : float
        Frontal area normal to the motion [m^2].
    converged : bool
        Every run converged.
    """

    dof: str
    runs: tuple
    d_linear: float | None
    d_quadratic: float
    mesh_spread: float | None
    drag_coefficient: float | None
    reference_area: float
    converged: bool

    @property
    def names(self) -> tuple[str, str]:
        return NAMES[self.dof]

    @property
    def gci(self) -> float | None:
        r"""Roache's grid convergence index of d_Q on the finer mesh [-] (None with one level).

        .. math:: \mathrm{GCI} = F_s \frac{|\varepsilon|}{r^p - 1}

        with :math:`\varepsilon` the mesh spread, the refinement ratio :math:`r = 2` (the
        surface cells halve from one level to the next), the scheme's formal order
        :math:`p = 2` (two levels cannot measure it) and the safety factor :math:`F_s = 3`
        Roache gives for a two-grid study: GCI = |eps| here, an error band, not a correction.

        References
        ----------
        Roache, P. J. (1994). Perspective: a method for uniform reporting of grid refinement
        studies. J. Fluids Eng. 116(3), 405-413 (eq. 7 and the factor 3 for two grids).
        """
        if self.mesh_spread is None:
            return None
        return GCI_SAFETY * self.mesh_spread / (GCI_RATIO ** GCI_ORDER - 1.0)

    def to_dict(self) -> dict:
        lin, quad = self.names
        return {"dof": self.dof, "converged": self.converged,
                "d_linear": self.d_linear, "d_quadratic": self.d_quadratic,
                lin: None if self.d_linear is None else -self.d_linear,
                quad: -self.d_quadratic, "mesh_spread": self.mesh_spread,
                "gci": self.gci,
                "drag_coefficient": self.drag_coefficient,
                "reference_area": self.reference_area,
                "runs": [r.to_dict() for r in self.runs]}

    @classmethod
    def from_dict(cls, d: dict) -> DofResult:
        """A DOF back from :meth:`to_dict`."""
        runs = tuple(RunResult.from_dict(r) for r in d["runs"])
        return cls(dof=d["dof"], runs=runs, d_linear=d["d_linear"],
                   d_quadratic=d["d_quadratic"], mesh_spread=d["mesh_spread"],
                   drag_coefficient=d["drag_coefficient"],
                   reference_area=d["reference_area"], converged=d["converged"])


@dataclass(frozen=True)
class CfdResult:
    """``stripcoef cfd``: the damping of the DOFs asked, by OpenFOAM.

    Attributes
    ----------
    source : str
        The mesh or vehicle file, as given.
    length, size : float
        Body length and cell reference size [m].
    density, viscosity : float
        [kg/m^3], [m^2/s].
    levels : tuple of int
        Every mesh level run (a DOF's own pair: its runs' ``level``).
    ranks : int
    case_dir : str
    dofs : tuple of DofResult
        Empty with ``write_only``.
    written : tuple of str
        The case folders written (names under ``case_dir``).
    comparison : tuple of CompareRow
        The default model's damping beside the CFD's per DOF (``--compare``;
        :mod:`stripcoef.cfd.compare`), empty otherwise.
    compare_model : dict
        The model compared: its name, speed [m/s] and reference point [m].
    """

    source: str
    length: float
    size: float
    density: float
    viscosity: float
    levels: tuple
    ranks: int
    case_dir: str
    dofs: tuple = ()
    written: tuple = field(default=())
    comparison: tuple = ()
    compare_model: dict = field(default_factory=dict)

    @property
    def converged(self) -> bool:
        return all(d.converged for d in self.dofs)

    def to_dict(self) -> dict:
        return {"source": self.source, "length": self.length, "size": self.size,
                "density": self.density, "viscosity": self.viscosity,
                "levels": list(self.levels), "ranks": self.ranks, "case_dir": self.case_dir,
                "converged": self.converged, "written": list(self.written),
                "dofs": [d.to_dict() for d in self.dofs],
                **({"compare": {"model": self.compare_model,
                                "rows": [c.to_dict() for c in self.comparison]}}
                   if self.comparison else {})}

    @classmethod
    def from_dict(cls, d: dict) -> CfdResult:
        """A result back from :meth:`to_dict` (``stripcoef cfd --json``; a stored
        reference). Raises KeyError or TypeError on a dict that is not one."""
        from stripcoef.cfd.compare import CompareRow

        comp = d.get("compare") or {}
        return cls(source=d["source"], length=d["length"], size=d["size"],
                   density=d["density"], viscosity=d["viscosity"],
                   levels=tuple(d["levels"]), ranks=d["ranks"], case_dir=d["case_dir"],
                   dofs=tuple(DofResult.from_dict(x) for x in d["dofs"]),
                   written=tuple(run_folder(w) for w in d.get("written", ())),
                   comparison=tuple(CompareRow.from_dict(r) for r in comp.get("rows", ())),
                   compare_model=dict(comp.get("model", {})))

    def text(self) -> str:
        """The result as the command prints it (every number read from this object)."""
        lines = [f"{self.source}: steady RANS (OpenFOAM simpleFoam, k-omega SST), body "
                 f"length {self.length:.4g} m, water {self.density:.6g} kg/m^3, "
                 f"nu {self.viscosity:.4g} m^2/s; case {self.case_dir}"]
        if not self.dofs:
            lines.append(f"  case written, not run ({len(self.written)} runs): "
                         "./Allrun in each folder")
            lines += [f"    {self.case_dir}/{w}" for w in self.written]
            return "\n".join(lines) + "\n"
        lines.append(f"  {'DOF':6s} {'term':6s} {'value':>11s} {'term':6s} {'value':>11s} "
                     f"{'C_D':>6s} {'mesh':>6s}  status")
        for d in self.dofs:
            lin, quad = d.names
            lv = "-" if d.d_linear is None else f"{-d.d_linear:.4g}"
            cd = "-" if d.drag_coefficient is None else f"{d.drag_coefficient:.3f}"
            ms = "-" if d.mesh_spread is None else f"{100 * d.mesh_spread:.1f}%"
            status = "converged" if d.converged else "NOT CONVERGED (see runs)"
            lines.append(f"  {d.dof:6s} {quad:6s} {-d.d_quadratic:11.4g} {lin:6s} {lv:>11s} "
                         f"{cd:>6s} {ms:>6s}  {status}")
        lines.append("  runs:")
        for d in self.dofs:
            for r in d.runs:
                unit = "rad/s" if d.dof in ("roll", "pitch", "yaw") else "m/s"
                fu = "N m" if unit == "rad/s" else "N"
                mark = "" if r.converged else f"  <- {r.status.upper()}"
                note = f" ({r.note})" if r.note else ""
                lines.append(f"    {d.dof:6s} {r.speed:.4g} {unit}, level {r.level}, "
                             f"{r.cells} cells, {r.iterations} it: {r.force:.5g} {fu} "
                             f"(swing {100 * r.swing:.1f}%, drift {100 * r.drift:.2f}%), "
                             f"{r.cpu_seconds / 60:.1f} CPU-min"
                             f"{mark}{note}")
        lines.append("  mesh: the relative change of d_Q from the coarser to the finer mesh "
                     "(the discretisation error estimate; Roache's two-grid GCI at order 2)")
        if self.comparison:
            lines += self._comparison_text()
        return "\n".join(lines) + "\n"

    def _comparison_text(self) -> list[str]:
        m = self.compare_model
        lines = [f"  the default model ({m.get('name', '')}, speed {m.get('speed', 0):.4g} m/s, "
                 f"moments about the same origin) against CFD, damping at the CFD's speed:",
                 f"  {'DOF':6s} {'term':6s} {'CFD':>10s} {'model':>10s} {'d_L model':>10s} "
                 f"{'at':>10s} {'F CFD':>10s} {'F model':>10s} {'model/CFD':>9s} "
                 f"{'mesh':>6s}"]
        for c in self.comparison:
            quad = NAMES[c.dof][1]
            rot = c.dof in ("roll", "pitch", "yaw")
            at = f"{c.speed:.3g} {'rad/s' if rot else 'm/s'}"
            ms = "-" if c.mesh_spread is None else f"{100 * c.mesh_spread:.1f}%"
            mark = "" if c.converged else "  NOT CONVERGED"
            lines.append(f"  {c.dof:6s} {quad:6s} {-c.cfd_d_quadratic:10.4g} "
                         f"{-c.model_d_quadratic:10.4g} {0.0 - c.model_d_linear:10.4g} {at:>10s} "
                         f"{c.cfd_force:10.4g} {c.model_force:10.4g} {c.ratio:9.3f} "
                         f"{ms:>6s}{mark}")
        lines.append("  (quadratic terms in SNAME sign; F = d_L u + d_Q u|u| opposing the "
                     "motion [N or N m]; the CFD's d_Q holds its whole force at one speed)")
        return lines


def judge(settled: Settled, residuals_met: bool, solver_error: str,
          iterations: int) -> tuple[str, str]:
    """Status and note of a run from its settled force and how it ended."""
    if solver_error or not settled.finite or not math.isfinite(settled.value):
        return DIVERGED, solver_error or "non-finite force"
    if iterations == 0:
        return DIVERGED, "no iteration ran"
    if residuals_met or settled.settled:
        return CONVERGED, ""
    return NOT_CONVERGED, (f"the mean force moved {100 * settled.drift:.2g}% over the last "
                           f"{settled.window} iterations (tolerance "
                           f"{100 * DRIFT_TOLERANCE:.1f}%), swing {100 * settled.spread:.2g}% "
                           f"(tolerance {100 * SWING_TOLERANCE:.0f}%); residuals not met")
